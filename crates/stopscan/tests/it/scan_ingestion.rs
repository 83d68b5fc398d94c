//! Raw scans against the exact sensor: a noise-free lidar scan, read by the ingestion
//! pipeline, gives the exact visibility region within the beam resolution.

use proptest::prelude::*;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use stopscan::algorithm::region::Region;
use stopscan::algorithm::visibility::BoundaryPiece;
use stopscan::geometry::{Domain, Location};
use stopscan::kernel::Point;
use stopscan::protocol::laser::Pose;
use stopscan::sensing::ingest::{IngestParams, ingest};
use stopscan::world::lidar::{Lidar, Walls};
use stopscan::world::polygon::PolygonWorld;

/// Where the ray from `o` along `u` meets the segment `a b`, as a distance ahead.
fn ray_hit(o: Point, u: Point, a: Point, b: Point) -> Option<f64> {
    let s = [b[0] - a[0], b[1] - a[1]];
    let den = u[0] * s[1] - u[1] * s[0];
    if den == 0.0 {
        return None;
    }
    let w = [a[0] - o[0], a[1] - o[1]];
    let t = (w[0] * s[1] - w[1] * s[0]) / den;
    let v = (w[0] * u[1] - w[1] * u[0]) / den;
    (t > 1e-12 && (-1e-12..=1.0 + 1e-12).contains(&v)).then_some(t)
}

/// The domain for a case: an office floor or a pillar forest.
fn domain(kind: u8, seed: u64) -> Domain {
    match kind {
        0 => stopscan::generate::office(2, 6, seed).unwrap().domain,
        _ => stopscan::generate::pillar_forest(14.0, 9.0, 8, seed).unwrap().domain,
    }
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 48,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x5CA7_1A5E),
        ..ProptestConfig::default()
    })]

    /// The region read from a noise-free scan differs from the exact one by at most the
    /// wedges a beam spacing can hide: one wedge per vertex of the exact region (out to that
    /// vertex), and the slivers between the range circle and the chords of both.
    #[test]
    fn a_noise_free_scan_gives_the_exact_region_within_the_beam_resolution(
        kind in 0u8..2, seed in 0u64..1000, u in 0.0..1.0f64, v in 0.0..1.0f64,
        theta in -3.1..3.1f64, beams in prop::sample::select(vec![360usize, 720, 1440]),
        range in prop::sample::select(vec![6.0f64, 20.0]),
    ) {
        let d = domain(kind, seed);
        let [lo, hi] = stopscan::algorithm::cover::bounds_of(&d.rings()[0]);
        let at = [lo[0] + u * (hi[0] - lo[0]), lo[1] + v * (hi[1] - lo[1])];
        prop_assume!(d.locate(at) == Location::Interior && d.boundary_distance(at) > 0.1);
        let lidar = Lidar { beams, range_max: range, sigma: 0.0, dropout: 0.0, spurious: 0.0, ..Lidar::default() };
        let pose = Pose { x: at[0], y: at[1], theta };
        let scan = lidar.scan(&Walls::of(&d), &pose, &mut ChaCha8Rng::seed_from_u64(seed));
        // Without the speckle filter: a pillar's corner grazed by one beam is real here.
        let params = IngestParams { despeckle: false, ..IngestParams::for_noise(0.0) };
        let got = ingest(&scan, &pose, &params).unwrap();
        // Along every beam, the region's boundary stands where the beam ended (within
        // split-and-merge's tolerance): exact at the beam resolution.
        let poly = &got.observation.region.polygon;
        for (i, r) in scan.ranges.iter().enumerate() {
            let a = theta + scan.angle(i);
            let u = [a.cos(), a.sin()];
            let (along, slant) = (0..poly.len())
                .filter_map(|k| {
                    let (p, q) = (poly[k], poly[(k + 1) % poly.len()]);
                    let len = (q[0] - p[0]).hypot(q[1] - p[1]);
                    // |cos| of the angle between the beam and the edge's normal.
                    let cos = ((q[0] - p[0]) * u[1] - (q[1] - p[1]) * u[0]).abs() / len;
                    ray_hit(at, u, p, q).map(|t| (t, cos))
                })
                .fold((f64::INFINITY, 1.0), |b, x| if x.0 < b.0 { x } else { b });
            let want = r.min(range);
            // The fit is within the tolerance across the wall: along a slanted beam, more.
            let tol = params.split / slant.max(0.05) + 1e-9;
            prop_assert!((along - want).abs() <= tol, "beam {i}: boundary at {along}, beam ended at {want}");
        }
        let world = PolygonWorld::with_range(d.clone(), Some(range)).unwrap();
        let exact = world.scan(at).unwrap();
        let (a, b) = (
            Region::union_all(std::slice::from_ref(&got.observation.region.polygon)),
            Region::union_all(std::slice::from_ref(&exact.region.polygon)),
        );
        let diff = a.difference(&b).area() + b.difference(&a).area();
        let dphi = std::f64::consts::TAU / beams as f64;
        let r2 = |p: &Point| (p[0] - at[0]).powi(2) + (p[1] - at[1]).powi(2);
        let wedges: f64 = exact.region.polygon.iter().map(|p| r2(p).min(range * range) * dphi).sum();
        let arcs = 2.0 * std::f64::consts::PI * range * range * (dphi * dphi / 12.0 + 1e-4);
        prop_assert!(diff <= wedges + arcs, "difference {diff} m² above the bound {}", wedges + arcs);
        // Every wall the scan fitted lies on the domain's boundary, within split-and-merge's
        // tolerance (a corner seen at a grazing angle may be fitted into its neighbour).
        let tol = IngestParams::for_noise(0.0).split;
        for piece in &got.observation.region.boundary {
            if let BoundaryPiece::Wall { from, to } = piece {
                for p in [from, to] {
                    prop_assert!(d.boundary_distance(*p) <= tol, "{p:?} off the walls");
                }
            }
        }
        // And the region is simple and counter-clockwise: its area equals its overlay's.
        let signed = stopscan::geometry::signed_area_of(&got.observation.region.polygon);
        prop_assert!((signed - a.area()).abs() < 1e-6 * signed.max(1.0), "{signed} {}", a.area());
    }
}

#[test]
fn noise_leaves_the_region_close_to_the_exact_one() {
    let d = domain(0, 3);
    let at = [1.0, 6.2];
    let lidar = Lidar::default();
    let pose = Pose { x: at[0], y: at[1], theta: 0.3 };
    let scan = lidar.scan(&Walls::of(&d), &pose, &mut ChaCha8Rng::seed_from_u64(4));
    let got = ingest(&scan, &pose, &IngestParams::for_noise(lidar.sigma)).unwrap();
    assert!(got.cleaning.dropouts > 0);
    let world = PolygonWorld::with_range(d, Some(lidar.range_max)).unwrap();
    let exact = world.scan(at).unwrap();
    let (a, b) = (
        Region::union_all(std::slice::from_ref(&got.observation.region.polygon)),
        Region::union_all(std::slice::from_ref(&exact.region.polygon)),
    );
    let diff = a.difference(&b).area() + b.difference(&a).area();
    assert!(diff < 0.03 * b.area(), "{diff} of {}", b.area());
}
