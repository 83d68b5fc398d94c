"""The Python bindings against the command line and against the definitions.

Run with ``pytest crates/stopscan-py/tests`` after ``pip install ./crates/stopscan-py``. The
CLI comparisons need the ``stopscan`` binary: ``STOPSCAN_BIN``, else ``target/release`` or
``target/debug`` of the repository (built by ``cargo build``).
"""

import json
import math
import os
import pathlib
import subprocess

import numpy as np
import pytest

import stopscan

ROOT = pathlib.Path(__file__).resolve().parents[3]
OFFICE = ROOT / "fixtures" / "office.geojson"
DEPOT = ROOT / "fixtures" / "ros-maps" / "depot.yaml"


def cli():
    if "STOPSCAN_BIN" in os.environ:
        return os.environ["STOPSCAN_BIN"]
    for profile in ("release", "debug"):
        p = ROOT / "target" / profile / "stopscan"
        if p.exists():
            return str(p)
    pytest.skip("no stopscan binary: cargo build first, or set STOPSCAN_BIN")


def run_cli(*args):
    out = subprocess.run([cli(), *args], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    return out.stdout


def test_loaders_read_every_format(tmp_path):
    office = stopscan.load(OFFICE)
    assert office.name == "office"
    assert office.holes and office.outer.shape[1] == 2
    assert office.outer.dtype == np.float64
    # The same polygon through WKT and the .pol-like benchmark format is the same area.
    outer = office.outer
    holes = office.holes
    ring = lambda r: "(" + ", ".join(f"{x!r} {y!r}" for x, y in [*r.tolist(), r[0].tolist()]) + ")"
    wkt = tmp_path / "office.wkt"
    wkt.write_text("POLYGON(" + ", ".join(ring(r) for r in [outer, *holes]) + ")")
    assert stopscan.load(wkt).area == pytest.approx(office.area, rel=1e-12)
    depot = stopscan.load(DEPOT)
    assert depot.cell_size == pytest.approx(0.05)
    with pytest.raises(ValueError, match="nope.geojson"):
        stopscan.load(tmp_path / "nope.geojson")


def test_shapely_and_geo_interface_go_in_and_come_out():
    shapely = pytest.importorskip("shapely")
    from shapely.geometry import Point, Polygon, shape

    square = Polygon([(0, 0), (4, 0), (4, 4), (0, 4)], [[(1, 1), (1, 2), (2, 2), (2, 1)]])
    regions = stopscan.visibility(square, [Point(0.5, 0.5), Point(3.5, 3.5)])
    assert len(regions) == 2
    for r in regions:
        poly = shape(r)
        assert poly.is_valid
        assert poly.area == pytest.approx(r.area, rel=1e-12)
        assert poly.within(square.buffer(1e-9))
    # From the corner (0.5, 0.5) the hole hides the square behind it.
    assert regions[0].area < square.area
    assert len(regions[0].windows) >= 1


def brute_force_visible(outer, holes, p, q):
    """Whether q is seen from p: the segment crosses no edge properly (from the definition)."""
    def cross(a, b, c):
        return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])

    for ring in [outer, *holes]:
        n = len(ring)
        for i in range(n):
            a, b = ring[i], ring[(i + 1) % n]
            d1, d2 = cross(p, q, a), cross(p, q, b)
            d3, d4 = cross(a, b, p), cross(a, b, q)
            if d1 * d2 < 0 and d3 * d4 < 0:
                return False
    return True


def inside(poly, q):
    x, y = q
    c = False
    n = len(poly)
    for i in range(n):
        (x1, y1), (x2, y2) = poly[i], poly[(i + 1) % n]
        if (y1 > y) != (y2 > y) and x < x1 + (y - y1) / (y2 - y1) * (x2 - x1):
            c = not c
    return c


def test_visibility_matches_a_brute_force_and_the_cli():
    office = stopscan.load(OFFICE)
    rng = np.random.default_rng(3)
    lo, hi = office.outer.min(axis=0), office.outer.max(axis=0)
    holes = [h.tolist() for h in office.holes]
    outer = office.outer.tolist()
    points = []
    while len(points) < 6:
        p = rng.uniform(lo, hi)
        if inside(outer, p) and not any(inside(h, p) for h in holes):
            points.append(p)
    regions = stopscan.visibility(office, np.array(points))
    for p, r in zip(points, regions):
        poly = r.vertices.tolist()
        for _ in range(150):
            q = rng.uniform(lo, hi)
            if not inside(outer, q) or any(inside(h, q) for h in holes):
                continue
            # Points well inside or well outside the region (not on its boundary).
            if inside(poly, q) != brute_force_visible(outer, holes, p, q):
                d = min(math.dist(q, v) for v in poly)
                assert d < 1e-6, (p, q)
        # The CLI gives the same region.
        text = run_cli("visibility", "--env", str(OFFICE), "--at", f"{float(p[0])!r},{float(p[1])!r}", "--format", "json")
        want = json.loads(text)
        region = want["regions"][0] if "regions" in want else want
        np.testing.assert_array_equal(np.array(region["polygon"]), r.vertices)


def test_visibility_on_every_core_equals_one_thread_in_order():
    office = stopscan.load(OFFICE)
    rng = np.random.default_rng(5)
    lo, hi = office.outer.min(axis=0), office.outer.max(axis=0)
    outer, holes = office.outer.tolist(), [h.tolist() for h in office.holes]
    points = []
    while len(points) < 300:
        p = rng.uniform(lo, hi)
        if inside(outer, p) and not any(inside(h, p) for h in holes):
            points.append(p)
    points = np.array(points)
    one = stopscan.visibility(office, points, threads=1)
    for threads in (None, 2, 3):
        many = stopscan.visibility(office, points, threads=threads)
        assert [r.viewpoint for r in many] == [tuple(p) for p in points.tolist()]
        for a, b in zip(one, many):
            np.testing.assert_array_equal(a.vertices, b.vertices)
            np.testing.assert_array_equal(a.windows, b.windows)
            assert a.area == b.area
    # The error names the first bad point in the points' order, whichever thread met it.
    bad = points.copy()
    bad[200] = (-1e3, -1e3)
    bad[250] = (-2e3, -2e3)
    with pytest.raises(ValueError, match=r"point \(-1000"):
        stopscan.visibility(office, bad)
    with pytest.raises(ValueError, match="threads"):
        stopscan.visibility(office, points, threads=0)


def test_explore_records_equal_the_cli_byte_for_byte(tmp_path):
    for strategy, extra in [("depth_first", {}), ("cost_aware", {"robot_radius": 0.2})]:
        out = tmp_path / f"{strategy}.json"
        args = ["explore", "--env", str(OFFICE), "--strategy", strategy, "--out", str(out),
                "--optimum-seconds", "0", "--seed", "5"]
        if "robot_radius" in extra:
            args += ["--robot-radius", "0.2"]
        run_cli(*args)
        text = stopscan.explore_json(OFFICE, strategy=strategy, seed=5, optimum_seconds=0, **extra)
        assert text == out.read_text(), strategy
        record = stopscan.explore(OFFICE, strategy=strategy, seed=5, optimum_seconds=0, **extra)
        assert record == json.loads(out.read_text())


def drive(env, strategy):
    """Drives a strategy with the exact sensor from the environment's start: its scans."""
    at = env.start
    strategy.observe(start=at)
    scans = []
    while len(scans) < 1000:
        action = strategy.next_action()
        if action["type"] == "done":
            return scans
        if action["type"] == "move":
            at = action["to"]
            strategy.observe(arrived=True)
        else:
            region = stopscan.visibility(env, [at])[0]
            scans.append(region.viewpoint)
            strategy.observe(region=region)
    raise AssertionError("no end after 1000 scans")


def test_a_python_driver_reproduces_the_run():
    """Driving a strategy step by step, with the exact sensor, is the simulator's run."""
    office = stopscan.load(OFFICE)
    record = stopscan.explore(office, optimum_seconds=0)
    scans = drive(office, stopscan.Strategy("depth_first"))
    want = [tuple(x["at"]) for x in record["robots"][0]["scans"]]
    assert scans == want


def test_a_georeferenced_driver_gets_the_same_run_moved(tmp_path):
    """The office moved by UTM-sized offsets: every strategy, with a footprint, scans at the
    same places moved by the same offsets, as long as the two runs take the same decisions.
    (Strategies' tolerances are a map's; handed coordinates of millions of metres, these runs
    once stopped after their first scan.)"""
    # Coordinates on a 2^-20 m grid, so that both offices are exact. The regions handed to
    # the driver are rounded to the far coordinates' spacing (1e-9 m), so that a near tie
    # between two goals may still be decided the other way later in the run.
    grid = 2.0 ** 20

    def moved(c, shift):
        if isinstance(c[0], (int, float)):
            return [round(c[k] * grid) / grid + shift[k] for k in range(2)]
        return [moved(x, shift) for x in c]

    def office(shift):
        feature = json.loads(OFFICE.read_text())
        feature["geometry"]["coordinates"] = moved(feature["geometry"]["coordinates"], shift)
        feature["properties"]["start"] = moved(feature["properties"]["start"], shift)
        path = tmp_path / f"office-{shift[0]}.geojson"
        path.write_text(json.dumps(feature))
        return stopscan.load(path)

    shift = (4_500_480.0, -5_300_224.0)
    near, far = office((0.0, 0.0)), office(shift)
    for name in ("depth_first", "cost_aware", "explore_lite"):
        want = drive(near, stopscan.Strategy(name, robot_radius=0.2))
        got = drive(far, stopscan.Strategy(name, robot_radius=0.2))
        assert abs(len(got) - len(want)) <= 0.1 * len(want), (name, len(got), len(want))
        for g, w in zip(got[:10], want[:10]):
            assert abs(g[0] - shift[0] - w[0]) < 1e-6 and abs(g[1] - shift[1] - w[1]) < 1e-6, name

def test_bad_input_is_a_clear_error():
    with pytest.raises(ValueError, match="shape"):
        stopscan.visibility(OFFICE, np.zeros((3, 3)))
    with pytest.raises(ValueError, match="range"):
        stopscan.visibility(OFFICE, [[1.0, 6.0]], range=-1.0)
    with pytest.raises(ValueError):
        stopscan.Strategy("no_such_strategy")
    s = stopscan.Strategy()
    with pytest.raises(ValueError, match="observe first"):
        s.next_action()
    with pytest.raises(ValueError, match="exactly one"):
        s.observe(arrived=True, start=(0.0, 0.0))


def test_corner_circle_equals_the_cli():
    text = run_cli("corner", "circle", "--distance", "2", "--format", "json")
    assert stopscan.corner_circle(2.0) == json.loads(text)


def test_corner_ratio_and_policy_equal_the_cli():
    for strategy, extra in [("unirec", []), ("exprec", ["--exprec", "appendix"]),
                            ("circle", []), ("stops", ["--stops-deg", "10,40,90"])]:
        want = json.loads(run_cli("--format", "json", "corner", "ratio", "--strategy", strategy,
                                  "--delta", "0.05", *extra))
        kw = {"exprec": "appendix"} if extra[:1] == ["--exprec"] else {}
        stops = [10, 40, 90] if strategy == "stops" else None
        assert stopscan.corner_ratio(strategy, 0.05, stops, **kw) == want
    want = json.loads(run_cli("--format", "json", "corner", "policy", "--belief", "normal:60,10",
                              "--memory", "none", "--step-deg", "10", "--distance", "8"))
    got = stopscan.corner_policy("normal:60,10", memory="none", step_deg=10, distance=8)
    assert got == want
    assert got["expected_time"] > 0 and got["stops"] >= len(got["scan_angles_deg"])


def test_corner_bad_input_is_a_clear_error():
    with pytest.raises(ValueError, match="allow_large"):
        stopscan.corner_ratio("unirec", 1e-9)
    with pytest.raises(ValueError, match="stops_deg"):
        stopscan.corner_ratio("stops", 0.1)
    with pytest.raises(ValueError, match="route: expected arc or chord"):
        stopscan.corner_ratio("exprec", 0.1, route="straight")
    with pytest.raises(ValueError, match="delta"):
        stopscan.corner_ratio("exprec", float("nan"))
    with pytest.raises(ValueError, match="belief|uniform"):
        stopscan.corner_policy("gaussian:1")


def test_roi_records_and_pictures_equal_the_cli_byte_for_byte(tmp_path):
    out = tmp_path / "cli.json"
    run_cli("--seed", "3", "--out", str(out), "roi", "--random", "300", "--robots", "3",
            "--report", str(tmp_path / "cli.html"), "--mcap", str(tmp_path / "cli.mcap"))
    text = stopscan.roi_json(random=300, robots=3, seed=3, svg=tmp_path / "py.svg",
                             report=tmp_path / "py.html", mcap=tmp_path / "py.mcap")
    assert text == out.read_text()
    for ext in ("svg", "html", "mcap"):
        cli_file = out.with_suffix(".svg") if ext == "svg" else tmp_path / f"cli.{ext}"
        assert (tmp_path / f"py.{ext}").read_bytes() == cli_file.read_bytes(), ext
    # A text grid from a file, and the same region as a numpy mask (from the file read by
    # its definition: '#' region, '.' outside, 'S' start), give the same record.
    lake = ROOT / "fixtures" / "roi" / "lake.txt"
    run_cli("--out", str(out), "roi", "--grid", str(lake), "--robots", "2",
            "--roi-speed", "0.1", "--roi-heading-deg", "30")
    rows = [l.rstrip() for l in lake.read_text().splitlines() if not l.lstrip().startswith(";")]
    width = max(len(r) for r in rows)
    mask = np.array([[c in "#S" for c in r.ljust(width)] for r in rows])
    (start,) = [(i, r.index("S")) for i, r in enumerate(rows) if "S" in r] or [None]
    record = stopscan.roi(mask, start=start, name="lake", robots=2, roi_speed=0.1,
                          roi_heading_deg=30)
    assert record == json.loads(out.read_text())
    assert stopscan.roi_json(lake, robots=2, roi_speed=0.1, roi_heading_deg=30) == out.read_text()
    region = stopscan.load_region(lake)
    assert (region.mask == mask[: region.mask.shape[0]]).all() and region.start == start
    assert record["metrics"]["visited_cells"] == int(mask.sum())


def test_roi_bad_input_is_a_clear_error(tmp_path):
    with pytest.raises(ValueError, match="exactly one of region"):
        stopscan.roi()
    with pytest.raises(ValueError, match="allow_large"):
        stopscan.roi(random=10**8)
    with pytest.raises(ValueError, match="not a cell of the region"):
        stopscan.roi(np.array([[True, False]]), start=(0, 1))
    with pytest.raises(ValueError, match="4-connected|connected"):
        stopscan.roi(np.array([[True, False, True]]))
    with pytest.raises(ValueError, match="search_box and launch"):
        stopscan.roi(random=50, search_box=(0, 0, 5, 5))
    with pytest.raises(ValueError, match="nope.txt"):
        stopscan.roi(tmp_path / "nope.txt")


def sweep_folder(path, count):
    """A folder of `count` small generated environments, and a file that does not load."""
    path.mkdir()
    families = ["forest", "comb", "spiral", "office"]
    for k in range(count):
        family = families[k % len(families)]
        size = {"forest": 3 + k % 3, "comb": 2 + k % 4, "spiral": 2 + k % 3, "office": 1 + k % 2}
        run_cli("--seed", str(k), "generate", family, "--size", str(size[family]),
                "--output", str(path / f"{family}{k:02}.geojson"))
    (path / "broken.wkt").write_text("POLYGON ((0 0, 4 0\n")
    return path


def test_a_sweep_equals_the_cli_csv_byte_for_byte(tmp_path):
    folder = sweep_folder(tmp_path / "envs", 6)
    out = tmp_path / "cli.csv"
    run_cli("--out", str(out), "explore", "--env", str(folder), "--strategy", "all",
            "--scan-time", "2", "--speed", "0.5")
    with pytest.warns(UserWarning) as warned:
        table = stopscan.sweep(folder, "all", scan_time=2, speed=0.5, backend="serial")
    messages = [str(w.message) for w in warned]
    assert any(m.startswith("broken.wkt: not swept: ") for m in messages), messages
    assert table.csv() == out.read_text()
    assert len(table) == 7 * 6 and table.columns[:2] == ["environment", "strategy"]
    # Every row's time is its terms' sum, and the broken file's rows carry its error.
    for row in table:
        if row["error"]:
            assert row["environment"] == "broken.wkt"
        else:
            terms = row["scan_time_total"] + row["move_time_total"] + row["travel_time_total"]
            assert row["time"] == pytest.approx(terms, rel=1e-12)
            assert row["scan_time_total"] == pytest.approx(2 * row["scans"])
    table.write_csv(tmp_path / "py.csv")
    assert (tmp_path / "py.csv").read_text() == out.read_text()
    # With a budget of steps for the lower bounds, as --bounds-steps.
    run_cli("--out", str(out), "explore", "--env", str(folder), "--strategy", "greedy_nbv",
            "--bounds-steps", "3")
    with pytest.warns(UserWarning):
        cut = stopscan.sweep(folder, "greedy_nbv", bounds_steps=3, backend="serial")
    assert cut.csv() == out.read_text()
    with pytest.raises(ValueError, match="warp"):
        stopscan.sweep(folder, "warp", backend="serial")
    with pytest.raises(ValueError, match="backend"):
        stopscan.sweep(folder, "depth_first", backend="dask")
    with pytest.raises(ValueError, match="nope.geojson: no such file or folder"):
        stopscan.sweep([folder / "spiral02.geojson", folder / "nope.geojson"], "depth_first",
                       backend="serial")


def test_a_ray_sweep_of_200_runs_equals_the_serial_one(tmp_path):
    if os.environ.get("STOPSCAN_CI"):
        import ray
    else:
        ray = pytest.importorskip("ray", reason="Ray is not installed (pip install ray)")
    folder = sweep_folder(tmp_path / "envs", 40)
    strategies = ["depth_first", "nearest_frontier", "greedy_nbv", "explore_lite", "cost_aware"]
    # A budget of steps for the lower bounds: a deadline would cut them where the load puts
    # it, and two runs per core compete on Ray.
    with pytest.warns(UserWarning, match="broken.wkt"):
        serial = stopscan.sweep(folder, strategies, backend="serial", bounds_steps=5000)
    ray.init(num_cpus=2, include_dashboard=False)
    try:
        seen = []
        with pytest.warns(UserWarning, match="broken.wkt"):
            on_ray = stopscan.sweep(folder, strategies, backend="ray", bounds_steps=5000,
                                    progress=lambda done, total: seen.append((done, total)))
    finally:
        ray.shutdown()
    assert on_ray.backend == "ray" and serial.backend == "serial"
    assert sum(1 for r in serial if not r["error"]) == 200
    assert on_ray.csv() == serial.csv()
    assert on_ray.rows == serial.rows
    assert seen[-1] == (200, 200)
