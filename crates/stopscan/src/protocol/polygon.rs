//! The polygon family: a robot in an unknown polygon with holes scans visibility regions.

use serde::{Deserialize, Serialize};

use crate::algorithm::visibility::VisibilityRegion;
use crate::kernel::Point;

/// What one scan returns: the region visible from where the robot stands, with labelled
/// boundary pieces (its windows are the paper's constructed edges).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PolygonObservation {
    /// Where the scan was taken.
    pub at: Point,
    /// The visibility region seen.
    pub region: VisibilityRegion,
    /// How unsure the scan's placement in the map frame is: one standard deviation of its
    /// position, metres, along its least sure direction (0: placed exactly, as the exact
    /// sensor's scans are). A scan read from raw returns carries its pose graph's spread
    /// ([`Reading::placement`](crate::sensing::mapper::Reading::placement)); strategies
    /// widen the band in which a wall seen by another scan closes a window by it
    /// ([`Sensor::cover_band_between`]).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub placement: f64,
}

/// Whether `x` is 0 (a field left out of JSON at its default).
#[allow(clippy::trivially_copy_pass_by_ref)] // serde's skip_serializing_if passes a reference
fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

impl PolygonObservation {
    /// The region `region` seen from `at`, placed exactly.
    pub fn new(at: Point, region: VisibilityRegion) -> Self {
        Self { at, region, placement: 0.0 }
    }

    /// The same observation with every point moved by `f` (a change of frame).
    #[must_use]
    pub fn mapped(&self, f: impl Fn(Point) -> Point) -> Self {
        Self { at: f(self.at), region: self.region.mapped(f), placement: self.placement }
    }
}

/// The robot's footprint around its reference point (the point that moves along the path and
/// where scans are taken), in the robot's frame. The polygon paper models a point robot and
/// leaves a convex robot open; stopscan plans in the configuration space of a footprint
/// without rotation (a disc, or a convex polygon kept at a fixed heading).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Footprint {
    /// A point robot: the paper's model.
    #[default]
    Point,
    /// A disc of this radius, metres, centred on the reference point.
    Disc {
        /// Radius, metres.
        radius: f64,
    },
    /// A convex polygon (counter-clockwise) containing the reference point, metres.
    Convex {
        /// The vertices.
        vertices: Vec<Point>,
    },
}

/// Sides of the regular polygon that stands for a disc footprint. It circumscribes the disc,
/// so the configuration space it gives lies inside the disc's (conservative by at most
/// `radius · (1/cos(π/32) − 1)`, 0.5% of the radius).
pub const DISC_SIDES: usize = 32;

/// The slack of [`Footprint::planning_clearance`], relative to the coordinates' magnitude.
pub const CLEARANCE_SLACK_REL: f64 = 1e-6;

/// Why a footprint was refused.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum InvalidFootprint {
    /// A radius that is negative or not finite.
    #[error("the robot radius must be a finite number >= 0, got {0}")]
    Radius(f64),
    /// A polygon with too few vertices, a coordinate that is not finite, a reflex or
    /// collinear corner, or the reference point outside.
    #[error("the footprint polygon {0}")]
    Polygon(String),
}

impl Footprint {
    /// A disc of `radius` metres (`Point` for 0).
    ///
    /// # Errors
    /// [`InvalidFootprint::Radius`] for a negative or non-finite radius.
    pub fn disc(radius: f64) -> Result<Self, InvalidFootprint> {
        if !radius.is_finite() || radius < 0.0 {
            return Err(InvalidFootprint::Radius(radius));
        }
        Ok(if radius == 0.0 { Self::Point } else { Self::Disc { radius } })
    }

    /// A convex polygon footprint (either orientation; stored counter-clockwise).
    ///
    /// # Errors
    /// [`InvalidFootprint::Polygon`] unless the vertices are at least three finite points
    /// forming a strictly convex polygon that contains the reference point `[0, 0]`
    /// (inside or on its boundary).
    pub fn convex(mut vertices: Vec<Point>) -> Result<Self, InvalidFootprint> {
        let bad = |m: String| Err(InvalidFootprint::Polygon(m));
        if vertices.len() < 3 {
            return bad(format!("needs at least 3 vertices, got {}", vertices.len()));
        }
        if let Some(i) = vertices.iter().position(|p| !p[0].is_finite() || !p[1].is_finite()) {
            return bad(format!("vertex {i} is not a finite point: {:?}", vertices[i]));
        }
        if crate::geometry::signed_area_of(&vertices) < 0.0 {
            vertices.reverse();
        }
        let n = vertices.len();
        for i in 0..n {
            let (a, b, c) = (vertices[i], vertices[(i + 1) % n], vertices[(i + 2) % n]);
            if crate::kernel::orient_sign(a, b, c) <= 0 {
                return bad(format!(
                    "is not strictly convex at vertex {b:?} (reflex, collinear or repeated)"
                ));
            }
        }
        if crate::kernel::ring_side(&vertices, [0.0, 0.0]) == crate::kernel::RingSide::Outside {
            return bad("does not contain the robot's reference point [0, 0]".into());
        }
        Ok(Self::Convex { vertices })
    }

    /// Whether the robot is a point.
    pub fn is_point(&self) -> bool {
        matches!(self, Self::Point)
    }

    /// The convex polygon the configuration space is built from: `None` for a point, the
    /// regular [`DISC_SIDES`]-gon circumscribing a disc, the polygon itself otherwise.
    pub fn polygon(&self) -> Option<Vec<Point>> {
        match self {
            Self::Point => None,
            Self::Disc { radius } => {
                let k = DISC_SIDES as f64;
                let r = radius / (std::f64::consts::PI / k).cos();
                Some(
                    (0..DISC_SIDES)
                        .map(|i| {
                            let a = std::f64::consts::TAU * (i as f64 + 0.5) / k;
                            [r * a.cos(), r * a.sin()]
                        })
                        .collect(),
                )
            }
            Self::Convex { vertices } => Some(vertices.clone()),
        }
    }

    /// The clearance strategies keep from everything they have not seen to be free: the
    /// largest distance from the reference point to the [`polygon`](Self::polygon) (0 for a
    /// point). A disc of this radius contains the footprint at every heading.
    pub fn clearance(&self) -> f64 {
        self.polygon().map_or(0.0, |p| p.iter().map(|v| v[0].hypot(v[1])).fold(0.0, f64::max))
    }

    /// The clearance a planner keeps, with a slack of [`CLEARANCE_SLACK_REL`] of `scale` (the
    /// magnitude of the coordinates, at least 1) over [`clearance`](Self::clearance): the
    /// configuration space is built by an overlay that snaps to about 5e-10 of its extent,
    /// and a plan that keeps this much lies inside it. 0 for a point.
    pub fn planning_clearance(&self, scale: f64) -> f64 {
        if self.is_point() { 0.0 } else { self.clearance() + CLEARANCE_SLACK_REL * scale.max(1.0) }
    }

    /// The robot's width: the narrowest gap it can pass (the disc's diameter; a polygon's
    /// minimum width over directions).
    pub fn width(&self) -> f64 {
        match self {
            Self::Point => 0.0,
            Self::Disc { radius } => 2.0 * radius,
            Self::Convex { vertices } => {
                let n = vertices.len();
                (0..n)
                    .map(|i| {
                        let (a, b) = (vertices[i], vertices[(i + 1) % n]);
                        let len = (b[0] - a[0]).hypot(b[1] - a[1]);
                        vertices
                            .iter()
                            .map(|p| {
                                ((b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]))
                                    .abs()
                                    / len
                            })
                            .fold(0.0, f64::max)
                    })
                    .fold(f64::INFINITY, f64::min)
            }
        }
    }
}

/// The sensor a strategy plans with, and its rule for windows worth a trip.
///
/// A real scanner resolves an opening only if it spans several beams: at distance `d` two
/// neighbouring beams of a scanner with `beams` per revolution are `d · 2π / beams` apart.
/// A window is **worth a trip** when its length is at least
/// `max(min_window, min_feature, d · 2π / beams)`, where `d` is the distance from the
/// viewpoint to the window's near end. Shorter windows (pixel steps of an occupancy map's
/// walls, gaps narrower than the robot) are closed without a visit and counted in the run
/// record as excluded by the rule. With the defaults (no beam count, zero sizes) every window
/// counts: the paper's model.
///
/// The rule has a second term, for **pockets**: unseen space enclosed by what was seen (the
/// back of a pillar, the hidden face of a desk, wedges between the shadows of two scans),
/// that is, a hole in the union of the scans' regions. A pocket is no larger than its hole,
/// obstacle included, so a window part that opens into a hole smaller than `min_pocket`
/// times the area seen so far, and smaller than `pocket_cap`, cannot hide more than that,
/// and is not worth a trip. The cap keeps a small room in a large building a room. The
/// pockets the rule leaves share one budget, `pocket_budget` times the area seen: a part
/// is closed only while the holes of every pocket left so far, this one included, hold less
/// in all, so that many small pockets (the backs of every desk on a floor, slivers between
/// noisy scans) cannot add up to more than the budget of what was seen.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct Sensor {
    /// The range, metres (`None`: unlimited).
    pub range: Option<f64>,
    /// Beams per revolution (`None`: continuous).
    pub beams: Option<u32>,
    /// The smallest feature the scanner resolves at any distance, metres.
    pub min_feature: f64,
    /// The shortest window worth a trip, metres (`--min-window`).
    pub min_window: f64,
    /// The smallest pocket worth a trip, as a share of the area seen so far (`--min-pocket`;
    /// 0: every pocket counts).
    #[serde(default)]
    pub min_pocket: f64,
    /// The largest pocket the rule may leave, square metres (`--pocket-cap`).
    #[serde(default)]
    pub pocket_cap: f64,
    /// The most the pockets the rule leaves may hold in all, as a share of the area seen so
    /// far (`--pocket-budget`; `None`: no total, each pocket judged alone, as before the
    /// budget existed).
    #[serde(default)]
    pub pocket_budget: Option<f64>,
    /// How far apart two scans may place one wall, metres: range noise and pose error
    /// (0 for the exact sensor). A window part along which another scan saw a wall within
    /// this distance is closed: the wall was seen from elsewhere (a wall seen down a corridor
    /// at a grazing angle reads as a chain of short windows).
    #[serde(default)]
    pub wall_tolerance: f64,
}

/// How much farther apart than [`Sensor::wall_tolerance`] two scans may place one wall, metres:
/// twice the pose error a stop is allowed after alignment (0.1 m each), as the two scans are
/// placed independently. A wall seen from elsewhere hides no opening, wherever odometry and
/// alignment put it. On the warehouse from raw scans, a stop placed by odometry along an
/// aisle put the outer wall 0.19 m from where well-aligned stops later saw it, and each gap
/// of its grazing view of that wall cost a scan of its own.
pub const POSE_ALLOWANCE: f64 = 0.2;

/// How many standard deviations of a scan's placement ([`PolygonObservation::placement`]) its
/// share of the pose allowance spans, when that is more than half of [`POSE_ALLOWANCE`].
///
/// On the 600 raw-scan runs (five strategies, the office, depot and the warehouse, seeds 1 to
/// 40) the spread took the runs beyond 1.25 × their exact run's scans from 160 to 129 (two
/// standard deviations, capped at 0.25 m: 134), with none below 99%.
pub const PLACEMENT_SIGMAS: f64 = 3.0;

/// The most a scan's share of the pose allowance grows to, metres, however unsure its
/// placement. Uncapped (two standard deviations), stops 0.7 to 1.6 m off with spreads of 0.4
/// to 0.6 m closed the windows into a warehouse aisle with a band over a metre wide, and the
/// run saw 96.3%.
pub const PLACEMENT_CAP: f64 = 0.3;

/// How far from each other's lines the walls on either side of a window may lie for the
/// window to be a gap in one wall (the window strategies' `gap_in_a_wall`), in multiples of the sensor's
/// `wall_tolerance` (0.07 m at σ = 0.02 m: 0.14 m). Lines fitted at three σ to a wall seen at
/// a slant from 10 to 20 m, where the returns lie a metre or more apart, tilt by a few
/// centimetres over a gap: at one tolerance (0.07 m), a gap of 0.8 m in a shelf's face seen
/// from 12 m had its far wall 7.4 cm off the near wall's line, and stayed a window.
pub const WALL_GAP_LINE: f64 = 2.0;

/// How far a wall beside a gap may turn from the line fitted through the gap and the returns
/// beside it (the window strategies' `gap_in_a_wall`) over its length, beyond the wall
/// tolerance: the sine of 2°. Two parallel walls 0.13 m apart, a metre or more long, tilt
/// that line by half a degree; a box's face 1 m long and the wall behind it across an
/// occlusion seen from 10 m, by 6°.
pub const WALL_GAP_TILT: f64 = 0.035;

/// The shortest wall on either side of a gap that sets the line the gap must lie on, metres.
pub const WALL_GAP_SIDE: f64 = 0.2;

/// The steepest slant at which a gap in a wall line is read as that wall: the sine of the
/// angle between the wall and the sight line to the gap's middle (30°).
pub const WALL_GAP_SLANT: f64 = 0.5;

impl Sensor {
    /// The shortest window worth a trip whose near end is `distance` metres away.
    pub fn min_window_at(&self, distance: f64) -> f64 {
        let beam = self.beams.map_or(0.0, |b| distance * std::f64::consts::TAU / f64::from(b));
        self.min_window.max(self.min_feature).max(beam)
    }

    /// The area below which a pocket enclosed by what was seen is not worth a trip, when
    /// `seen` square metres have been seen (0 without the pocket term).
    pub fn pocket_limit(&self, seen: f64) -> f64 {
        if self.has_pocket_term() { (self.min_pocket * seen).min(self.pocket_cap) } else { 0.0 }
    }

    /// The area the pockets the rule leaves may hold in all, when `seen` square metres have
    /// been seen: `pocket_budget` of it, unbounded without a budget, 0 without the pocket
    /// term.
    pub fn pocket_allowance(&self, seen: f64) -> f64 {
        if self.has_pocket_term() {
            self.pocket_budget.map_or(f64::INFINITY, |b| b * seen)
        } else {
            0.0
        }
    }

    /// How near a wall another scan saw must run along a window part to close it, metres (raw
    /// scans; 0 for the exact sensor): the same wall, placed apart by range noise
    /// (`wall_tolerance`) and by both scans' pose errors ([`POSE_ALLOWANCE`]).
    ///
    /// Until this release only a window that was a gap between returns on one wall line had
    /// the pose allowance; an occlusion's window kept the noise alone. On the 600 raw-scan runs
    /// (five strategies, the office, depot and the warehouse, seeds 1 to 40) the allowance for
    /// every window took the runs beyond 1.25 × their exact run's scans from 295 to 183 and the
    /// scans from 22,900 to 20,590, with none below 99% (the lowest 99.09%, against 99.13%).
    /// A band of the rule's width (0.4 m) took them to 119, but two runs fell below 99%: on
    /// depot, windows through gaps in the outline of a hollow shelf were closed by the
    /// outline seen from elsewhere.
    pub fn cover_band(&self) -> f64 {
        self.cover_band_between(0.0, 0.0)
    }

    /// The [`cover_band`](Self::cover_band) between a window of a scan placed with spread
    /// `a` and the walls of a scan placed with spread `b` ([`PolygonObservation::placement`],
    /// metres): each scan's share of the pose allowance is half of [`POSE_ALLOWANCE`], or
    /// [`PLACEMENT_SIGMAS`] of its spread when that is more. A scan placed by odometry after
    /// a long drive down an aisle is placed as well as its pose graph knows, and its walls
    /// and windows are where they are up to that spread.
    pub fn cover_band_between(&self, a: f64, b: f64) -> f64 {
        let share =
            |sd: f64| (POSE_ALLOWANCE / 2.0).max((PLACEMENT_SIGMAS * sd).min(PLACEMENT_CAP));
        if self.wall_tolerance > 0.0 { self.wall_tolerance + share(a) + share(b) } else { 0.0 }
    }

    /// Whether the rule has its pocket term (a share and a cap above 0).
    pub fn has_pocket_term(&self) -> bool {
        self.min_pocket > 0.0 && self.pocket_cap > 0.0
    }

    /// Whether the rule excludes nothing (every window is worth a trip).
    pub fn excludes_nothing(&self) -> bool {
        self.beams.is_none()
            && self.min_window <= 0.0
            && self.min_feature <= 0.0
            && !self.has_pocket_term()
    }

    /// The rule in words, for run records.
    pub fn rule(&self) -> String {
        if self.excludes_nothing() {
            return "every window is worth a trip".into();
        }
        let mut terms = vec![format!("{} m (min_window)", self.min_window)];
        if self.min_feature > 0.0 {
            terms.push(format!("{} m (min_feature)", self.min_feature));
        }
        if let Some(b) = self.beams {
            terms.push(format!("d·2π/{b} (beam spacing at the window's distance d)"));
        }
        let windows = format!(
            "a window is worth a trip when its length is at least max({})",
            terms.join(", ")
        );
        let windows = if self.has_pocket_term() {
            format!(
                "{windows}, and when what lies behind it is not a pocket enclosed by what was \
                 seen smaller than both {} of the area seen so far (min_pocket) and {} m² \
                 (pocket_cap){}",
                self.min_pocket,
                self.pocket_cap,
                self.pocket_budget.map_or(String::new(), |b| format!(
                    ", while the pockets left so far, this one included, hold less than {b} of \
                     the area seen in all (pocket_budget)"
                ))
            )
        } else {
            windows
        };
        if self.wall_tolerance > 0.0 {
            format!(
                "{windows}; a window part along which another scan saw a wall within {} m is \
                 closed (wall_tolerance, {} m: the same wall, placed apart by range noise, and \
                 {POSE_ALLOWANCE} m: the two scans' pose errors; each scan's half of that grows \
                 to {PLACEMENT_SIGMAS} standard deviations of its placement as the pose graph \
                 holds it, up to {PLACEMENT_CAP} m)",
                self.cover_band(),
                self.wall_tolerance
            ) + &format!(
                "; a window of a scan is that wall (a gap between returns on a wall seen at a \
                 slant) when its ends and the next return beyond each (a single return, or the \
                 far end of a wall of at least {WALL_GAP_SIDE} m that runs along the line: its \
                 ends within {} m of each other across it, or {}° over its length) lie within \
                 {} m of the line fitted to the four, seen at {}° or less; where the beam \
                 beyond one end (not both) met nothing within the range, when the other three \
                 lie so and that beam ends short of the line, or within the wall tolerance \
                 beyond it (explore_lite's raster: such a window, or one between two such walls each within {} m of \
                 the other's line, is assumed to be that wall until a later scan holds its \
                 cells or sees through it; and a frontier cluster whose cells farther than {} m \
                 from every wall seen or assumed span less than half of min_frontier_size is \
                 no frontier: scans place one wall a few centimetres apart)",
                self.wall_tolerance,
                WALL_GAP_TILT.asin().to_degrees().round(),
                0.5 * WALL_GAP_LINE * self.wall_tolerance,
                WALL_GAP_SLANT.asin().to_degrees().round(),
                WALL_GAP_LINE * self.wall_tolerance,
                self.wall_tolerance
            )
        } else {
            windows
        }
    }
}

/// What a polygon strategy knows before it starts: the cost model that prices its choices,
/// the robot's footprint and its sensor.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct RobotSetup {
    /// The cost model.
    pub cost: crate::protocol::CostModel,
    /// The footprint.
    pub footprint: Footprint,
    /// The sensor and its window rule.
    pub sensor: Sensor,
}

impl RobotSetup {
    /// A point robot with an ideal sensor (the paper's model), priced by `cost`.
    pub fn point(cost: crate::protocol::CostModel) -> Self {
        Self { cost, ..Self::default() }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn footprints_validate_and_measure() {
        assert_eq!(Footprint::disc(0.0).unwrap(), Footprint::Point);
        assert!(Footprint::disc(-1.0).is_err() && Footprint::disc(f64::NAN).is_err());
        let d = Footprint::disc(0.2).unwrap();
        assert_eq!(d.width(), 0.4);
        // The circumscribed 32-gon: its vertices at r / cos(π/32), its edges' middles at r.
        let p = d.polygon().unwrap();
        assert_eq!(p.len(), DISC_SIDES);
        let c = d.clearance();
        assert!((c - 0.2 / (std::f64::consts::PI / 32.0).cos()).abs() < 1e-15);
        for i in 0..p.len() {
            let (a, b) = (p[i], p[(i + 1) % p.len()]);
            let m = [f64::midpoint(a[0], b[0]), f64::midpoint(a[1], b[1])];
            assert!((m[0].hypot(m[1]) - 0.2).abs() < 1e-12);
        }
        // A 0.6 × 0.4 rectangle, given clockwise: stored counter-clockwise, width 0.4.
        let r =
            Footprint::convex(vec![[0.3, 0.2], [0.3, -0.2], [-0.3, -0.2], [-0.3, 0.2]]).unwrap();
        assert!((r.width() - 0.4).abs() < 1e-12);
        assert!((r.clearance() - 0.3f64.hypot(0.2)).abs() < 1e-15);
        let Footprint::Convex { vertices } = &r else { panic!() };
        assert!(crate::geometry::signed_area_of(vertices) > 0.0);
        for bad in [
            vec![[0.0, 0.0], [1.0, 0.0]],
            vec![[1.0, 1.0], [2.0, 1.0], [1.0, 2.0]],
            vec![[-1.0, -1.0], [1.0, -1.0], [0.0, 0.0], [1.0, 1.0], [-1.0, 1.0]],
            vec![[-1.0, -1.0], [f64::NAN, -1.0], [0.0, 1.0]],
        ] {
            assert!(Footprint::convex(bad.clone()).is_err(), "{bad:?}");
        }
    }

    #[test]
    fn the_window_rule_follows_its_terms() {
        let s = Sensor::default();
        assert!(s.excludes_nothing());
        assert_eq!(s.min_window_at(100.0), 0.0);
        let s = Sensor { beams: Some(360), min_window: 0.1, ..Sensor::default() };
        assert_eq!(s.min_window_at(1.0), 0.1);
        let at_20 = 20.0 * std::f64::consts::TAU / 360.0;
        assert!((s.min_window_at(20.0) - at_20).abs() < 1e-15);
        assert!(s.rule().contains("d·2π/360"));
    }

    #[test]
    fn the_cover_band_is_the_noise_and_two_pose_errors_on_raw_scans_only() {
        // The exact sensor places every wall where it is: no band, whatever the rule.
        let exact = Sensor { min_window: 0.4, min_feature: 0.5, ..Sensor::default() };
        assert_eq!(exact.cover_band(), 0.0);
        assert!(!exact.rule().contains("another scan"));
        let raw = Sensor { min_window: 0.4, wall_tolerance: 0.07, ..Sensor::default() };
        assert_eq!(raw.cover_band(), 0.07 + POSE_ALLOWANCE);
        assert!(raw.rule().contains("within 0.27 m is closed"), "{}", raw.rule());
        // And the gaps in a wall seen at a slant: the tolerance from the fitted line, 2° of
        // a wall's turn, 30°; explore_lite's raster, such gaps and those between two walls
        // (twice the tolerance), assumed until a later scan holds them or sees through.
        for part in [
            "within 0.07 m of each other across it, or 2° over its length",
            "lie within 0.07 m of the line fitted to the four, seen at 30° or less",
            "beyond one end (not both) met nothing within the range, when the other three lie \
             so and that beam ends short of the line",
            "each within 0.14 m of the other's line, is assumed to be that wall until a later \
             scan",
            "a frontier cluster whose cells farther than 0.07 m from every wall seen or assumed \
             span less than half of min_frontier_size is no frontier",
        ] {
            assert!(raw.rule().contains(part), "{part}: {}", raw.rule());
        }
        // Each scan's share: 0.1 m, or three times its placement spread, up to 0.3 m.
        assert_eq!((PLACEMENT_SIGMAS, PLACEMENT_CAP), (3.0, 0.3));
        let near = |a: f64, b: f64| (a - b).abs() < 1e-12;
        assert!(near(raw.cover_band_between(0.0, 0.0), 0.27));
        assert!(near(raw.cover_band_between(0.03, 0.02), 0.27));
        assert!(near(raw.cover_band_between(0.05, 0.0), 0.07 + 0.15 + 0.1));
        assert!(near(raw.cover_band_between(0.05, 0.06), 0.07 + 0.15 + 0.18));
        assert!(near(raw.cover_band_between(0.2, 0.0), 0.07 + 0.3 + 0.1));
        assert!(near(raw.cover_band_between(3.0, 3.0), 0.07 + 0.3 + 0.3));
        assert_eq!(exact.cover_band_between(1.0, 1.0), 0.0);
    }
}
