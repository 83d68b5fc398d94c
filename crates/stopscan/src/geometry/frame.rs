//! The local frame computations run in, and the input's frame results are reported in.
//!
//! Maps of outdoor robots carry georeferenced coordinates (UTM eastings of 4.5e6 m, say) while
//! the map itself spans metres. Computed in place, every constructed point (a ray meeting a
//! wall, a cut along a window) would round to the coordinates' magnitude, a million times
//! coarser than the map's own scale. Loaders therefore move such a domain next to the origin
//! by an exact translation, and results are moved back for output.

use serde::{Deserialize, Serialize};

use crate::kernel::Point;

/// A translation: `input = local + origin`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct Frame {
    /// Where the local frame's origin lies in the input's coordinates.
    pub origin: Point,
}

impl Frame {
    /// No translation.
    pub const IDENTITY: Self = Self { origin: [0.0, 0.0] };

    /// A frame with its origin at `origin` (input coordinates).
    pub fn at(origin: Point) -> Self {
        Self { origin }
    }

    /// The frame for a shape with these points: per axis, when the coordinates lie far from 0
    /// compared with their spread (`|min| ≥ 16·(max − min)`, all of one sign), the origin is
    /// the coordinate nearest to 0; otherwise 0. Then every `x − origin` of the shape is exact
    /// (Sterbenz: `x` and the origin lie within a factor 2 of each other), so the translated
    /// shape is the same shape, exact predicates give the same answers on it, and moving
    /// back restores every input coordinate bit for bit.
    pub fn for_points<'a>(points: impl IntoIterator<Item = &'a Point>) -> Self {
        let mut lo = [f64::INFINITY; 2];
        let mut hi = [f64::NEG_INFINITY; 2];
        for p in points {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let axis = |k: usize| {
            let spread = hi[k] - lo[k];
            if !spread.is_finite() {
                0.0
            } else if lo[k] > 0.0 && lo[k] >= 16.0 * spread {
                lo[k]
            } else if hi[k] < 0.0 && -hi[k] >= 16.0 * spread {
                hi[k]
            } else {
                0.0
            }
        };
        Self { origin: [axis(0), axis(1)] }
    }

    /// The frame for computations that start at `p` before the shape is known (a robot's
    /// odometry, say): per axis, the origin is `p` rounded to a multiple of [`Self::STEP`].
    /// That is the identity within `STEP / 2` of the origin, so runs near it compute as they
    /// always did; far from it, `x − origin` is exact for every `x` within `STEP / 2` of `p`
    /// (Sterbenz again), and two starts that differ by a multiple of `STEP` compute the same
    /// numbers.
    pub fn near(p: Point) -> Self {
        let axis = |v: f64| {
            let o = (v / Self::STEP).round() * Self::STEP;
            if o.is_finite() { o } else { 0.0 }
        };
        Self { origin: [axis(p[0]), axis(p[1])] }
    }

    /// The grid [`Self::near`] rounds to, metres: larger than a building, small enough that
    /// tolerances scaled to the coordinates' magnitude stay below a millimetre.
    pub const STEP: f64 = 1024.0;

    /// Whether this is the identity.
    pub fn is_identity(&self) -> bool {
        self.origin == [0.0, 0.0]
    }

    /// A point of the input's frame in the local frame.
    pub fn to_local(&self, p: Point) -> Point {
        [p[0] - self.origin[0], p[1] - self.origin[1]]
    }

    /// A point of the local frame in the input's frame.
    pub fn to_input(&self, p: Point) -> Point {
        [p[0] + self.origin[0], p[1] + self.origin[1]]
    }

    /// How coarsely the input's frame can represent points near its origin: the spacing of
    /// floating-point numbers there (0 for the identity). Results reported in the input's
    /// frame are rounded to this.
    pub fn resolution(&self) -> f64 {
        let m = self.origin[0].abs().max(self.origin[1].abs());
        if m == 0.0 { 0.0 } else { m * f64::EPSILON }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_start_far_away_moves_the_frame_by_whole_steps() {
        assert!(Frame::near([0.5, -511.9]).is_identity());
        assert_eq!(Frame::near([4_500_480.7, -5_300_224.2]).origin, [4_500_480.0, -5_300_224.0]);
        assert_eq!(Frame::near([600.0, -1600.0]).origin, [1024.0, -2048.0]);
        // Exact: a point 500 m off the start comes back bit for bit, and two starts a whole
        // number of steps apart see the same local coordinates.
        let f = Frame::near([4_500_480.7, 1e9]);
        for p in [[4_500_000.123_456_789, 1e9 - 499.987_654_321], [4_500_980.1, 1e9 + 0.3]] {
            assert_eq!(f.to_input(f.to_local(p)), p);
        }
        let (near, far) = (Frame::near([0.7, 0.0]), Frame::near([4_500_480.7, -5_300_224.2]));
        let q = [3.25, -1.125];
        assert_eq!(near.to_local(q), far.to_local([q[0] + 4_500_480.0, q[1] - 5_300_224.0]));
        assert_eq!(Frame::near([f64::MAX, 0.0]).to_local([f64::MAX, 1.0]), [0.0, 1.0]);
        assert!(Frame::near([f64::INFINITY, f64::NAN]).is_identity());
    }

    #[test]
    fn maps_near_the_origin_stay_put() {
        let f = Frame::for_points(&[[0.0, 0.0], [10.0, 5.0]]);
        assert!(f.is_identity());
        let f = Frame::for_points(&[[-12.0, 3.0], [40.0, 5.0]]);
        assert!(f.is_identity());
    }

    #[test]
    fn georeferenced_maps_move_exactly() {
        let pts = [
            [4_500_000.25, 5_300_000.5],
            [4_500_100.125, 5_300_050.0],
            [4_500_050.0, 5_300_020.75],
        ];
        let f = Frame::for_points(&pts);
        assert_eq!(f.origin, [4_500_000.25, 5_300_000.5]);
        for p in pts {
            assert_eq!(f.to_input(f.to_local(p)), p);
        }
        assert_eq!(f.to_local(pts[1]), [100.125 - 0.25, 49.5]);
        let neg = Frame::for_points(&[[-1e9, 2.0], [-1e9 + 3.0, 4.0]]);
        assert_eq!(neg.origin, [-1e9 + 3.0, 0.0]);
    }
}
