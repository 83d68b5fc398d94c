"""stopscan: where a robot should stop and scan when every scan costs time.

The Python face of the Rust library. Every function runs the library's own pipelines, so a
run record made here equals the command line's, byte for byte (see ``explore_json``).

Geometry goes in as shapely geometries, any object with ``__geo_interface__``, GeoJSON dicts,
or numpy float64 arrays of shape (n, 2); it comes out as numpy arrays, and regions expose
``__geo_interface__``.
"""

from __future__ import annotations

import json
import os
from typing import Any, Iterable, Optional, Sequence, Tuple, Union

import numpy as np

from ._stopscan import (
    Environment,
    Region,
    Strategy,
    __version__,
    corner_circle as _corner_circle,
    corner_policy as _corner_policy,
    corner_ratio as _corner_ratio,
    explore_json as _explore_json,
    from_geojson as _from_geojson,
    load as _load,
    load_region as _load_region,
    roi_json as _roi_json,
    visibility as _visibility,
)
from ._sweep import SweepTable, sweep

__all__ = [
    "Environment",
    "GridRegion",
    "MissionIncomplete",
    "Region",
    "Strategy",
    "SweepTable",
    "__version__",
    "corner_circle",
    "corner_policy",
    "corner_ratio",
    "environment",
    "explore",
    "explore_json",
    "load",
    "load_region",
    "roi",
    "roi_json",
    "sweep",
    "visibility",
]

Point = Tuple[float, float]


def load(path: Union[str, os.PathLike], start: Optional[Point] = None,
         simplify: Optional[float] = None) -> Environment:
    """Reads an environment file of any format the CLI reads: GeoJSON, WKT, ``.pol``, the
    benchmark format, or a ROS map's YAML (its free region holding ``start``, simplified
    within ``simplify`` metres)."""
    return _load(os.fspath(path), None if start is None else _point(start), simplify)


def environment(domain: Any, name: str = "polygon") -> Environment:
    """An environment from an ``Environment``, a path, a shapely Polygon (or any object with
    ``__geo_interface__``), a GeoJSON dict, or an outer ring as an (n, 2) array (with no
    holes)."""
    if isinstance(domain, Environment):
        return domain
    if isinstance(domain, (str, os.PathLike)):
        return load(domain)
    geo = getattr(domain, "__geo_interface__", None)
    if geo is None and isinstance(domain, dict):
        geo = domain
    if geo is None:
        ring = _points(domain)
        geo = {"type": "Polygon", "coordinates": [ring.tolist()]}
    return _from_geojson(json.dumps(geo), name)


def _points(points: Any) -> np.ndarray:
    """Points as a C-contiguous float64 array of shape (n, 2)."""
    geo = getattr(points, "__geo_interface__", None)
    if geo is not None:
        coords = geo["coordinates"]
        points = [coords] if geo["type"] == "Point" else coords
    elif isinstance(points, (list, tuple)) and any(hasattr(p, "__geo_interface__") for p in points):
        points = [_point(p) for p in points]
    a = np.ascontiguousarray(np.asarray(points, dtype=np.float64))
    if a.ndim == 1 and a.shape[0] == 2:
        a = a.reshape(1, 2)
    if a.ndim != 2 or a.shape[1] != 2:
        raise ValueError(f"expected points of shape (n, 2), got {a.shape}")
    return a


def _point(p: Any) -> Point:
    a = _points(p)
    if a.shape[0] != 1:
        raise ValueError(f"expected one point, got {a.shape[0]}")
    return (float(a[0, 0]), float(a[0, 1]))


def visibility(domain: Any, points: Any, range: Optional[float] = None,
               threads: Optional[int] = None) -> list:
    """The region seen from each point (an (n, 2) array, or shapely points), with a sensor
    of ``range`` metres if given. Returns one ``Region`` per point, in order. The queries run
    on ``threads`` threads (every core by default; 1 for this thread only), without the GIL."""
    return _visibility(environment(domain), _points(points), range, threads)


def explore_json(domain: Any, start: Optional[Any] = None, **options: Any) -> str:
    """The run record of an exploration as JSON text, exactly as ``stopscan explore --out``
    writes it. Options: ``strategy`` (default "depth_first"), ``scan_time`` (1), ``move_time``
    (0), ``speed`` (1), ``range``, ``robot_radius``, ``seed`` (0), ``optimum_seconds`` (5),
    ``optimum_nodes``."""
    env = environment(domain)
    return _explore_json(env, None if start is None else _point(start), **options)


def explore(domain: Any, start: Optional[Any] = None, **options: Any) -> dict:
    """Explores ``domain`` from ``start`` (by default the file's start) and returns the run
    record as a dict (see ``explore_json`` for the options)."""
    return json.loads(explore_json(domain, start, **options))


def corner_circle(d: float) -> dict:
    """The circle strategy around a corner at distance ``d`` (the circle paper): its stops,
    ratio and bound, as ``stopscan corner circle --format json`` reports them."""
    return json.loads(_corner_circle(d))


def corner_ratio(strategy: str, delta: float, stops_deg: Optional[Sequence[float]] = None,
                 **options: Any) -> dict:
    """The worst-case and asymptotic competitive ratios of a stop list around a corner
    (``"unirec"``, ``"exprec"``, ``"circle"``, or ``"stops"`` with ``stops_deg``) at
    δ = τ·v/D, as ``stopscan corner ratio --format json`` reports them. Options:
    ``last_step`` ("capped" or "nominal"), ``exprec`` ("table_i" or "appendix"), ``route``
    ("arc" or "chord"), ``allow_large`` (lift the soft limit on UNIREC's stops)."""
    stops = None if stops_deg is None else [float(x) for x in stops_deg]
    return json.loads(_corner_ratio(strategy, float(delta), stops, **options))


def corner_policy(belief: str, **options: Any) -> dict:
    """The corner paper's MDP policy for a belief over the corner's angle, in degrees
    (``"uniform:0,180"``, ``"normal:60,5"``, ``"mix:0.5*normal:30,3+0.5*normal:90,3"``,
    ``"histogram:FILE"``, ``"observed:FILE[,BUCKET_DEG]"``), as ``stopscan corner policy
    --format json`` reports it. Options: ``truth``, ``distance`` (10 m), ``scan_time``
    (2 s), ``move_time`` (0 s), ``speed`` (0.5 m/s), ``memory`` ("last": MDP2, or "none":
    MDP1), ``reading`` ("conditional" or "literal"), ``step_deg`` (5), ``solver``
    ("backward" or "general")."""
    return json.loads(_corner_policy(belief, **options))


class GridRegion:
    """A region of interest on a grid: ``mask[row - origin[0], col - origin[1]]`` is True for
    the region's cells; ``start`` is the (row, column) the team starts from."""

    def __init__(self, mask: Any, start: Optional[Tuple[int, int]] = None,
                 origin: Tuple[int, int] = (0, 0), cell_size: float = 1.0,
                 name: str = "roi") -> None:
        self.mask = np.asarray(mask, dtype=bool)
        if self.mask.ndim != 2:
            raise ValueError(f"a region's mask has two dimensions, got shape {self.mask.shape}")
        self.origin = (int(origin[0]), int(origin[1]))
        self.start = None if start is None else (int(start[0]), int(start[1]))
        self.cell_size = float(cell_size)
        self.name = name

    @property
    def cells(self) -> np.ndarray:
        """The region's cells, (row, column), an (n, 2) int64 array in reading order."""
        return np.argwhere(self.mask).astype(np.int64) + np.array(self.origin, dtype=np.int64)

    def text_grid(self) -> str:
        """The region as a text grid (``#`` region, ``.`` outside, ``S`` start), rows from
        ``origin``."""
        rows = [["#" if v else "." for v in row] for row in self.mask]
        if self.start is not None:
            r, c = self.start[0] - self.origin[0], self.start[1] - self.origin[1]
            if not (0 <= r < self.mask.shape[0] and 0 <= c < self.mask.shape[1] and self.mask[r, c]):
                raise ValueError(f"start {self.start} is not a cell of the region")
            rows[r][c] = "S"
        return "".join("".join(row) + "\n" for row in rows)

    def __repr__(self) -> str:
        return (f"GridRegion({self.name!r}: {int(self.mask.sum())} cells, start {self.start}, "
                f"cell {self.cell_size} m)")


def load_region(path: Union[str, os.PathLike], **options: Any) -> GridRegion:
    """Reads a region of interest as ``stopscan roi --grid`` does: a text grid, a PNG/PGM
    mask (``cell_px`` pixels per cell, ``invert_mask``), or a polygon file through its outer
    grid approximation (``cell_size`` metres). ``start`` (row, column) where the file has
    none."""
    name, cells, start, cell_size = _load_region(os.fspath(path), **options)
    lo = cells.min(axis=0)
    hi = cells.max(axis=0)
    mask = np.zeros((int(hi[0] - lo[0] + 1), int(hi[1] - lo[1] + 1)), dtype=bool)
    mask[cells[:, 0] - lo[0], cells[:, 1] - lo[1]] = True
    return GridRegion(mask, start, (int(lo[0]), int(lo[1])), cell_size, name)


class MissionIncomplete(RuntimeError):
    """A mission whose robots gave up; ``record`` is its run record (as the CLI writes it
    before it fails)."""

    def __init__(self, message: str, record: dict) -> None:
        super().__init__(message)
        self.record = record


def roi_json(region: Any = None, **options: Any) -> str:
    """The run record of a region-of-interest mission as JSON text, exactly as ``stopscan roi
    --out`` writes it. ``region`` is a file (text grid, PNG/PGM mask, polygon), a
    ``GridRegion``, or a 2-D boolean array (rows × columns, True inside; the start is
    ``start=(row, col)``, by default the first cell in reading order); or give
    ``random=CELLS`` and ``seed``. Options as ``stopscan roi``'s flags: ``robots``,
    ``robot_speed``, ``roi_speed``, ``roi_heading_deg``, ``battery_s``, ``scan_time``,
    ``move_time``, ``cell_size``, ``cell_px``, ``invert_mask``, ``start``, ``camera``,
    ``frames``, ``search_box`` (row0, col0, row1, col1), ``launch``, ``paths``, ``seed``, and
    ``svg``, ``report``, ``mcap`` (files to write)."""
    for k in ("svg", "report", "mcap"):
        if options.get(k) is not None:
            options[k] = os.fspath(options[k])
    if region is None:
        return _roi_json(None, **options)
    if isinstance(region, (str, os.PathLike)):
        return _roi_json(os.fspath(region), **options)
    if not isinstance(region, GridRegion):
        region = GridRegion(region, options.pop("start", None),
                            cell_size=options.get("cell_size", 1.0),
                            name=options.pop("name", "roi"))
    else:
        if "start" in options:
            region = GridRegion(region.mask, options.pop("start"), region.origin,
                                region.cell_size, region.name)
        options.setdefault("cell_size", region.cell_size)
    if region.origin != (0, 0):
        raise ValueError("a region given in place has its origin at (0, 0): its cells are "
                         f"rows and columns of its mask (origin {region.origin}); give the file")
    options["name"] = options.get("name", region.name)
    return _roi_json(None, grid=region.text_grid(), **options)


def roi(region: Any = None, **options: Any) -> dict:
    """Flies a team over a region of interest (Algorithm 1 of the ROI paper) and returns the
    run record as a dict (see ``roi_json`` for the arguments). Raises ``MissionIncomplete``,
    with the record attached, when robots gave up."""
    record = json.loads(roi_json(region, **options))
    if record.get("failures"):
        raise MissionIncomplete("the mission did not complete: " + "; ".join(record["failures"]),
                                record)
    return record
