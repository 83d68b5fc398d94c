//! Regression tests, each named after the fuzz case or bug it keeps fixed.

use stopscan::algorithm::visibility::Visibility;
use stopscan::io::text_formats::parse_wkt;
use stopscan::kernel::orient_sign;

/// fuzz/artifacts/loaders/crash-3db3be0b…: a sliver with coordinates near 2e18 whose float
/// area has a different sign in each vertex order. Orientation is now decided exactly.
#[test]
fn fuzz_loaders_3db3be0b_sliver_orientation() {
    let e = parse_wkt("POLYGON ((5 0, 4 0,  2333333333333333331 1))", "fuzz").unwrap();
    let r = e.domain.outer();
    let k = (0..3).min_by(|&a, &b| r[a][0].total_cmp(&r[b][0])).unwrap();
    assert_eq!(
        orient_sign(r[(k + 2) % 3], r[k], r[(k + 1) % 3]),
        1,
        "the outer ring is counter-clockwise"
    );
    let v = Visibility::new(e.domain.clone()).unwrap();
    assert!(v.query([4.5, 0.0]).is_ok(), "a point on the boundary edge");
}

/// `stopscan bench explore` hung on its 586th generated floor, office(6, 14, 585): a window's
/// test point lay where no scan could see it (a hair inside a desk the window grazes), so the
/// same viewpoint was scanned forever. A sample is now handled once a scan was taken for it.
#[test]
fn exploration_office_585_grazing_window_terminates() {
    use stopscan::protocol::CostModel;
    use stopscan::sim::{NoObserver, polygon::run};
    use stopscan::strategy::polygon::by_name;
    let inst = stopscan::generate::office(6, 14, 585).unwrap();
    let world = stopscan::world::polygon::PolygonWorld::new(inst.domain.clone()).unwrap();
    for name in ["depth_first", "nearest_frontier", "greedy_nbv", "explore_lite"] {
        let mut s = by_name(name, &CostModel::default()).unwrap();
        let r =
            run(&world, inst.start, &CostModel::default(), s.as_mut(), &mut NoObserver).unwrap();
        assert!(
            r.tally.scans <= inst.domain.reflex_vertices().len() as u64 + 1
                || name != "depth_first"
        );
        assert!(r.tally.scans < 200, "{name}: {} scans", r.tally.scans);
    }
}
