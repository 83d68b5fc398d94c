//! The simplification on small synthetic maps: tiny PGMs written to a temporary folder.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use super::{MapImport, RosMapOptions, read_with_report};
use crate::geometry::Location;
use crate::io::LoadError;
use crate::kernel::Point;

/// A fresh folder per map.
fn folder() -> PathBuf {
    static NEXT: AtomicUsize = AtomicUsize::new(0);
    let k = NEXT.fetch_add(1, Ordering::Relaxed);
    let d = std::env::temp_dir().join(format!("stopscan-ros-map-{}-{k}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A map from rows of text (top row first): `.` free, anything else blocked.
fn map(rows: &[String], resolution: f64) -> PathBuf {
    let (w, h) = (rows[0].len(), rows.len());
    let mut pgm = format!("P5\n{w} {h}\n255\n").into_bytes();
    for r in rows {
        assert_eq!(r.len(), w);
        pgm.extend(r.bytes().map(|b| if b == b'.' { 254 } else { 0 }));
    }
    let dir = folder();
    std::fs::write(dir.join("m.pgm"), pgm).unwrap();
    let yaml = format!(
        "image: m.pgm\nresolution: {resolution}\norigin: [0, 0, 0]\nnegate: 0\nfree_thresh: 0.2\n"
    );
    std::fs::write(dir.join("m.yaml"), yaml).unwrap();
    dir.join("m.yaml")
}

fn read(path: &Path, start: Option<Point>, simplify: Option<f64>) -> MapImport {
    let opts = RosMapOptions { start, min_speck_area: 0.0, simplify };
    read_with_report(path, &opts).unwrap_or_else(|e| panic!("{e}"))
}

/// Free below the line through `(0, y0)` with slope `dy/dx` (cell units, y up), in a
/// `w × h` map: a wall slanting across as a staircase.
fn slanted(w: usize, h: usize, y0: f64, dy: f64, dx: f64) -> Vec<String> {
    (0..h)
        .map(|r| {
            let y = (h - 1 - r) as f64 + 0.5;
            (0..w).map(|c| if y < y0 + dy / dx * (c as f64 + 0.5) { '.' } else { '#' }).collect()
        })
        .collect()
}

/// The distance from `p` to the closed segment `a b`, from the definition: the nearest point
/// of the segment is the projection of `p`, clamped to its ends.
fn distance_to_segment(p: Point, a: Point, b: Point) -> f64 {
    let (ux, uy) = (b[0] - a[0], b[1] - a[1]);
    let t = ((p[0] - a[0]) * ux + (p[1] - a[1]) * uy) / (ux * ux + uy * uy);
    let t = t.clamp(0.0, 1.0);
    (p[0] - a[0] - t * ux).hypot(p[1] - a[1] - t * uy)
}

/// Points along every edge of a ring, its vertices included.
fn samples(ring: &[Point]) -> Vec<Point> {
    let n = ring.len();
    let mut out = Vec::new();
    for i in 0..n {
        let (a, b) = (ring[i], ring[(i + 1) % n]);
        for k in 0..16 {
            let t = f64::from(k) / 16.0;
            out.push([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]);
        }
    }
    out
}

/// The Hausdorff distance between two closed rings, sampled: the largest distance from a
/// point of either to the other.
fn hausdorff(a: &[Point], b: &[Point]) -> f64 {
    let one_way = |from: &[Point], to: &[Point]| {
        let m = to.len();
        samples(from)
            .into_iter()
            .map(|p| {
                (0..m)
                    .map(|i| distance_to_segment(p, to[i], to[(i + 1) % m]))
                    .fold(f64::INFINITY, f64::min)
            })
            .fold(0.0, f64::max)
    };
    one_way(a, b).max(one_way(b, a))
}

/// Shoelace, from the definition: ½ Σ (x_i y_{i+1} − x_{i+1} y_i), positive counter-clockwise.
fn shoelace(ring: &[Point]) -> f64 {
    let n = ring.len();
    0.5 * (0..n)
        .map(|i| ring[i][0] * ring[(i + 1) % n][1] - ring[(i + 1) % n][0] * ring[i][1])
        .sum::<f64>()
}

/// Valid with room to spare: every vertex lies at least a millionth of a cell from every edge
/// of any ring that does not end at it (so rounding cannot make the rings touch, and no
/// needle-thin spike is left for later constructions to trip on).
fn assert_clear(m: &MapImport) {
    let rings = m.environment.domain.rings();
    let gap = 1e-6 * m.report.resolution;
    for (ra, a) in rings.iter().enumerate() {
        for (i, &p) in a.iter().enumerate() {
            for (rb, b) in rings.iter().enumerate() {
                let n = b.len();
                for j in 0..n {
                    if ra == rb && (j == i || (j + 1) % n == i) {
                        continue;
                    }
                    let d = distance_to_segment(p, b[j], b[(j + 1) % n]);
                    assert!(d > gap, "ring {ra} vertex {i} {p:?} is {d} from ring {rb} edge {j}");
                }
            }
        }
    }
}

/// Ring by ring, the simplified boundary lies within `tol` of the traced one and back.
fn assert_within(traced: &MapImport, simplified: &MapImport, tol: f64) {
    let (t, s) = (traced.environment.domain.rings(), simplified.environment.domain.rings());
    assert_eq!(t.len(), s.len(), "ring count");
    for (k, (a, b)) in t.iter().zip(s).enumerate() {
        let d = hausdorff(a, b);
        assert!(d <= tol * (1.0 + 1e-12), "ring {k}: Hausdorff distance {d} above {tol}");
    }
    assert_clear(simplified);
}

#[test]
fn slanted_staircase_walls_become_a_few_edges() {
    for (dy, dx) in [(1.0, 1.0), (1.0, 2.0), (1.0, 3.0), (2.0, 5.0), (3.0, 7.0), (1.0, 10.0)] {
        for (dy, dx) in [(dy, dx), (dx, dy)] {
            let path = map(&slanted(60, 60, 3.3, dy, dx), 0.05);
            let traced = read(&path, None, Some(0.0));
            let m = read(&path, None, None);
            let r = m.report;
            assert!(r.traced_vertices >= 14, "{dy}/{dx}: {} traced", r.traced_vertices);
            // The map's corners below the wall and the wall's two ends: no step is left.
            assert!(r.vertices <= 5, "{dy}/{dx}: {r:?}\n{:?}", m.environment.domain.outer());
            assert_eq!(r.reflex_vertices, 0, "{dy}/{dx}: {r:?}");
            assert_eq!(r.tolerance, 1.5 * 0.05);
            assert_eq!(r.tolerance_used, r.tolerance);
            assert_within(&traced, &m, r.tolerance);
        }
    }
}

#[test]
fn zero_keeps_the_traced_boundary_and_bad_tolerances_are_errors() {
    let path = map(&slanted(12, 12, 2.0, 1.0, 2.0), 0.1);
    let m = read(&path, None, Some(0.0));
    assert_eq!(m.report.vertices, m.report.traced_vertices);
    assert_eq!(m.report.area_change, 0.0);
    assert_eq!(m.report.tolerance_used, 0.0);
    // Every vertex is a cell corner: nothing but collinear vertices was dropped.
    for p in m.environment.domain.rings().iter().flatten() {
        for v in p {
            assert!((v / 0.1 - (v / 0.1).round()).abs() < 1e-9, "{v}");
        }
    }
    for bad in [-0.1, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let opts = RosMapOptions { simplify: Some(bad), ..RosMapOptions::default() };
        let e = read_with_report(&path, &opts).unwrap_err();
        assert!(matches!(e, LoadError::InvalidOption { name: "simplify", .. }), "{e}");
        assert!(e.to_string().starts_with("simplify must be a finite non-negative"), "{e}");
    }
}

/// Two rooms joined by a straight corridor one cell wide and by a staircase corridor one
/// cell wide (the wall between them is a hole), a one-cell pillar and a 2 × 2 pillar.
fn rooms() -> Vec<String> {
    let mut g = vec![vec!['#'; 40]; 30];
    let mut free = |r0: usize, r1: usize, c0: usize, c1: usize| {
        for row in &mut g[r0..r1] {
            for cell in &mut row[c0..c1] {
                *cell = '.';
            }
        }
    };
    free(1, 12, 1, 12); // room A
    free(1, 12, 28, 39); // room B
    free(5, 6, 12, 28); // the straight corridor
    // The staircase corridor: from room A's bottom right, down and right to room B.
    for k in 0..16 {
        free(11 + k, 12 + k, 6 + k, 8 + k);
    }
    free(26, 29, 20, 39);
    free(11, 29, 33, 36);
    g[3][4] = '#'; // the one-cell pillar in room A
    g[7][31] = '#'; // the 2 × 2 pillar in room B
    g[7][32] = '#';
    g[8][31] = '#';
    g[8][32] = '#';
    g.into_iter().map(|r| r.into_iter().collect()).collect()
}

#[test]
fn corridors_one_cell_wide_and_small_pillars_survive() {
    for tol in [None, Some(0.1), Some(0.2), Some(1.0)] {
        let path = map(&rooms(), 0.1);
        let traced = read(&path, None, Some(0.0));
        let m = read(&path, None, tol);
        let d = &m.environment.domain;
        assert_eq!(traced.environment.domain.holes().len(), 3);
        assert_eq!(d.holes().len(), 3, "{tol:?}: every hole kept");
        for h in d.holes() {
            assert!(h.len() >= 3 && -shoelace(h) > 0.0, "{tol:?}: {h:?}");
        }
        // The straight corridor stays open: the middle of its centre line is free.
        assert_eq!(d.locate([2.0, 2.45]), Location::Interior, "{tol:?}");
        assert_within(&traced, &m, m.report.tolerance);
        assert!(m.report.vertices < traced.report.vertices, "{tol:?}");
    }
}

/// Found by `random_grids_keep_their_topology` when the triangle test ran on coordinates in
/// metres: 6 × 0.1 rounds to 0.6000000000000001, so a vertex that lies on a new edge in the
/// grid lay a hair beside it in metres, and the edge was drawn through it, leaving two rings'
/// worth of boundary 1e-16 m apart (valid in exact arithmetic, a needle to everything after).
#[test]
fn an_edge_never_runs_through_a_corner_rounded_off_its_line() {
    let rows: Vec<String> = [
        ".........",
        ".........",
        "##.##.###",
        "..##.#...",
        "###..##.#",
        "#..#...#.",
        "#..#..##.",
        ".#.##.##.",
        "..##.....",
        "###.##.#.",
        "#.#.#.##.",
        "###.#.#..",
    ]
    .iter()
    .map(|r| (*r).into())
    .collect();
    assert!(keeps_its_topology(&rows, 0.1, 2.718_437_196_955_086_2 * 0.1));
}

#[test]
fn the_area_change_is_the_difference_of_the_two_areas() {
    let rows = slanted(40, 30, 7.0, 2.0, 5.0);
    let free_cells = rows.iter().flat_map(|r| r.bytes()).filter(|&b| b == b'.').count();
    let path = map(&rows, 0.05);
    let m = read(&path, None, None);
    let r = m.report;
    let traced = free_cells as f64 * 0.05 * 0.05;
    let simplified: f64 = m.environment.domain.rings().iter().map(|ring| shoelace(ring)).sum();
    assert!((r.traced_area - traced).abs() < 1e-12, "{} vs {traced}", r.traced_area);
    assert!((r.area - simplified).abs() < 1e-12, "{} vs {simplified}", r.area);
    let change = (traced - simplified).abs();
    assert!(change > 0.0);
    assert!((r.area_change - change).abs() < 1e-12, "{} vs {change}", r.area_change);
    assert!((r.relative_area_change - change / traced).abs() < 1e-12);
}

#[test]
fn the_start_stays_inside() {
    // A 45° staircase: the centres of the cells along it lie on the straight edge that would
    // replace it, unless the start holds the edge back.
    let path = map(&slanted(20, 20, 0.0, 1.0, 1.0), 0.1);
    for k in 2..18 {
        let start = [(f64::from(k) + 0.5) * 0.1, (f64::from(k) - 0.5) * 0.1];
        let m = read(&path, Some(start), None);
        assert_eq!(m.environment.domain.locate(start), Location::Interior, "{start:?}");
        assert_eq!(m.environment.start, Some(start));
    }
}

/// The properties of `random_grids_keep_their_topology` on one grid (`false`: no free cell).
fn keeps_its_topology(rows: &[String], resolution: f64, tol: f64) -> bool {
    let path = map(rows, resolution);
    let opts = RosMapOptions { start: None, min_speck_area: 0.0, simplify: Some(0.0) };
    let Ok(traced) = read_with_report(&path, &opts) else {
        return false;
    };
    let m = read(&path, None, Some(tol));
    let td = &traced.environment.domain;
    assert_eq!(m.environment.domain.holes().len(), td.holes().len());
    assert_within(&traced, &m, tol);
    // A start at the first cell centre inside the traced free space.
    let (w, h) = (rows[0].len(), rows.len());
    let start = (0..w * h)
        .map(|i| [((i % w) as f64 + 0.5) * resolution, ((h - 1 - i / w) as f64 + 0.5) * resolution])
        .find(|&p| td.locate(p) == Location::Interior)
        .unwrap();
    let from_start = read(&path, Some(start), Some(0.0));
    let m = read(&path, Some(start), Some(tol));
    let d = &m.environment.domain;
    assert_eq!(d.holes().len(), from_start.environment.domain.holes().len());
    assert_eq!(d.locate(start), Location::Interior);
    assert_within(&from_start, &m, tol);
    let area: f64 = d.rings().iter().map(|r| shoelace(r)).sum();
    assert!((m.report.area - area).abs() <= 1e-9 * area.abs().max(1.0));
    true
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(96))]

    /// Random small occupancy grids, random tolerances: the result validates (it is a
    /// `Domain`), keeps every hole, keeps the start inside, stays within the tolerance and
    /// clear of needles; its area is its shoelace area.
    #[test]
    fn random_grids_keep_their_topology(
        w in 3usize..14,
        h in 3usize..14,
        bits in proptest::collection::vec(proptest::prelude::any::<u8>(), 196),
        density in 0.4..0.95f64,
        cells in 0.0..4.0f64,
        resolution in proptest::sample::select(vec![0.05, 0.1, 1.0]),
    ) {
        let rows: Vec<String> = (0..h)
            .map(|r| {
                (0..w)
                    .map(|c| if f64::from(bits[r * 14 + c]) < density * 256.0 { '.' } else { '#' })
                    .collect()
            })
            .collect();
        // Grids without a free cell say nothing.
        proptest::prop_assume!(keeps_its_topology(&rows, resolution, cells * resolution));
    }
}

#[test]
fn a_start_in_a_diagonal_pinch_keeps_its_cell() {
    // Cells (1, 1) and (2, 2) touch diagonally between two blocked cells: one of them is
    // blocked to part the rings, never the start's.
    let rows: Vec<String> = ["....", "..#.", ".#..", "...."].iter().map(|r| (*r).into()).collect();
    let path = map(&rows, 1.0);
    for start in [[1.5, 2.5], [2.5, 1.5]] {
        let m = read(&path, Some(start), None);
        assert_eq!(m.environment.domain.locate(start), Location::Interior, "{start:?}");
        assert_eq!(m.environment.domain.holes().len(), 1);
    }
}

#[test]
fn a_start_on_a_grid_line_is_in_the_free_cell_beside_it() {
    // Column 0 is blocked; x = 0.05 is the line between it and the free column 1.
    let rows: Vec<String> = ["#...", "#...", "#..."].iter().map(|r| (*r).into()).collect();
    let path = map(&rows, 0.05);
    for start in [[0.05, 0.07], [0.05, 0.05], [0.2, 0.1], [0.1, 0.15]] {
        let m = read(&path, Some(start), None);
        assert_ne!(m.environment.domain.locate(start), Location::Outside, "{start:?}");
    }
    let opts = RosMapOptions { start: Some([0.04, 0.07]), ..RosMapOptions::default() };
    let e = read_with_report(&path, &opts).unwrap_err().to_string();
    assert!(e.contains("not in a free cell"), "{e}");
    let opts = RosMapOptions { start: Some([0.21, 0.07]), ..RosMapOptions::default() };
    let e = read_with_report(&path, &opts).unwrap_err().to_string();
    assert!(e.contains("outside the map"), "{e}");
}

#[test]
fn a_missing_image_is_named_with_the_yaml_that_names_it() {
    let dir = folder();
    let yaml = dir.join("lost.yaml");
    let text =
        "image: nowhere.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\nfree_thresh: 0.2\n";
    std::fs::write(&yaml, text).unwrap();
    let e = read_with_report(&yaml, &RosMapOptions::default()).expect_err("no image");
    let text = e.to_string();
    assert!(matches!(e, LoadError::Io { .. }), "{text}");
    assert!(text.contains("nowhere.pgm") && text.contains("lost.yaml's `image`"), "{text}");
}
