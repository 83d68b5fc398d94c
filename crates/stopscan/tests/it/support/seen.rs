//! The share of a domain's free space a set of stops sees, written from the definition: grid
//! points of the free space, each seen when it is within range of some stop and the ray to it
//! meets no wall. No visibility region is involved. Shared by the raw-scan tests of the
//! library, the CLI (`serve`) and the ROS node, each including this file with `#[path]`.

use stopscan::geometry::{Domain, Location};
use stopscan::kernel::Point;
use stopscan::world::lidar::Walls;

/// The share of the grid points (every `step` metres) of `d`'s free space within `range` of
/// some stop and in its sight.
pub(crate) fn seen_share(d: &Domain, stops: &[Point], range: f64, step: f64) -> f64 {
    let walls = Walls::of(d);
    let [lo, hi] = stopscan::algorithm::cover::bounds_of(&d.rings()[0]);
    let (mut inside, mut seen) = (0usize, 0usize);
    let mut y = lo[1] + 0.5 * step;
    while y < hi[1] {
        let mut x = lo[0] + 0.5 * step;
        while x < hi[0] {
            let p = [x, y];
            if d.locate(p) == Location::Interior {
                inside += 1;
                let visible = stops.iter().any(|s| {
                    let dist = (p[0] - s[0]).hypot(p[1] - s[1]);
                    dist <= range
                        && (dist == 0.0
                            || walls
                                .cast(*s, [(p[0] - s[0]) / dist, (p[1] - s[1]) / dist], dist)
                                .is_none())
                });
                seen += usize::from(visible);
            }
            x += step;
        }
        y += step;
    }
    seen as f64 / inside as f64
}
