//! What a polygon strategy knows: the views it took, their windows, and the tree of moves
//! between them (each viewpoint was chosen inside the region of its parent view, so the
//! straight segment between them is known free space).

use serde::{Deserialize, Serialize};

use crate::algorithm::cover::{self, Intervals};
use crate::algorithm::region::Region;
use crate::algorithm::visibility::BoundaryPiece;
use crate::geometry::{fit_line, segments_closer_than, segments_distance};
use crate::kernel::{
    Point, RingSide, magnitude, on_segment, orient_sign, ring_side, rounding, segments_intersect,
};
use crate::protocol::Action;
use crate::protocol::polygon::{
    Footprint, PolygonObservation, RobotSetup, Sensor, WALL_GAP_LINE, WALL_GAP_SIDE,
    WALL_GAP_SLANT, WALL_GAP_TILT,
};

use super::PolygonFeedback;
use super::approach::{Approach, holds};
use super::raster::{CELL, DEPTH, Raster, Stops, rays_through};
use super::roads::SeenRaster;
use super::trip::{Next, Trip};

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub(super) struct View {
    pub(super) at: Point,
    polygon: Vec<Point>,
    bounds: [Point; 2],
    /// The region's boundary pieces, counter-clockwise.
    pub(super) pieces: Vec<BoundaryPiece>,
    windows: Vec<Window>,
    pub(super) parent: Option<usize>,
    /// Waypoints of the move from the parent's viewpoint to this one, when it was not
    /// straight ([`approach`](super::approach)); empty otherwise.
    #[serde(default)]
    via: Vec<Point>,
    /// Every window explored: covered parts only grow, so it stays so and is skipped.
    #[serde(default)]
    pub(super) explored: bool,
    /// The [`rounding`] of the region's coordinates: steps off a window are at least this.
    #[serde(default)]
    rounding: f64,
    /// How unsure the scan's placement is ([`PolygonObservation::placement`]), metres.
    #[serde(default)]
    placement: f64,
}

/// The sensor rule's lift on a window's parts.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
enum Lift {
    /// The rule applies; the window was never reopened.
    #[default]
    Never,
    /// Part of the window was opened again as part of a longer opening: the rule does not
    /// apply to its parts.
    Lifted,
    /// A scan was taken for one of its parts since the lift: the opening was visited, and
    /// what is left of it (parts that other scans' regions split off, which noisy scans do
    /// often) is judged by the rule again. A window is reopened at most once.
    Spent,
}

/// A window and how far its exploration test has got: the parts of it (as parameter
/// intervals from `from` to `to`) whose far side is covered, by the views before `checked`
/// or by a scan taken for it. Covered parts only grow, so the test resumes where it stopped.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct Window {
    /// Its index among the view's pieces.
    piece: usize,
    from: Point,
    to: Point,
    /// Uncovered parts shorter than this (in parameter) are ignored ([`cover::tolerance`]).
    tol: f64,
    covered: Intervals,
    /// The parts of `covered` that the sensor rule closed as what was left open of the
    /// window by other views (not a whole window below the rule).
    #[serde(default)]
    ruled: Intervals,
    /// Whether the rule was lifted for the window ([`Known::reopen_wide_openings`]).
    #[serde(default)]
    lift: Lift,
    checked: usize,
    /// The piece is a range frontier (a chord of the sensor's range arc), not a window: the
    /// sensor rule does not apply to it.
    #[serde(default)]
    range_frontier: bool,
    /// A scan was taken at a junction of this window: from now on only its gap middles are
    /// targeted (and marked handled), so each window costs at most one junction scan and
    /// the exploration ends.
    #[serde(default)]
    no_junction: bool,
}

/// A next viewpoint and the part of a window it is for.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub(super) struct Target {
    pub(super) at: Point,
    /// Waypoints from the view's viewpoint to `at` when a straight move there would not keep
    /// the footprint's clearance (empty for a straight move).
    #[serde(default)]
    pub(super) via: Vec<Point>,
    view: usize,
    window: usize,
    gap: [f64; 2],
    /// The view from whose viewpoint the robot drives to `at` (through `via`), when it is not
    /// `view`: a part no viewpoint in `view`'s own region reaches with the footprint's
    /// clearance (seen from a corridor through a door at a slant) may be reached inside a
    /// later view's region that holds its near side.
    #[serde(default)]
    anchor: Option<usize>,
    /// Placed at a point of the window other than the gap's middle (a wall junction), from
    /// where the scan may see only part of the gap: it is not marked handled, but the window
    /// gets only gap-middle targets from then on.
    #[serde(default)]
    off_gap: bool,
    /// The scan is taken where a move toward the target failed, to place the robot again
    /// ([`Known::move_failed`]): the target's part stays open.
    #[serde(default)]
    relocate: bool,
}

impl Target {
    /// The same target with its viewpoint at `z` (a point of the same view's region that the
    /// robot can drive to straight from its viewpoint).
    pub(super) fn moved_to(&self, z: Point) -> Self {
        Self { at: z, via: Vec::new(), ..self.clone() }
    }

    /// The view whose viewpoint the trip to the target starts from: the target's own view,
    /// or its anchor.
    pub(super) fn base(&self) -> usize {
        self.anchor.unwrap_or(self.view)
    }

    /// The view whose window part the target is for.
    pub(super) fn view(&self) -> usize {
        self.view
    }
}

/// Where on the uncovered part of a window the next viewpoint goes (the paper leaves it open:
/// "choose a point z on any constructed edge", and notes that the choice decides the count).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Placement {
    /// The middle of the part (the default).
    #[default]
    Middle,
    /// Near the part's end farthest from the view's viewpoint (a thousandth of the part in):
    /// deep behind the reflex vertex, as in the paper's Fig. 11.
    Far,
}

/// An occupancy raster of the views, and how many of them it holds.
#[derive(Debug, Clone, Default, PartialEq)]
struct WallsSeen {
    raster: Option<Raster>,
    views: usize,
}

/// The views taken so far.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub(super) struct Known {
    /// Where on an unexplored window part the next viewpoint goes.
    #[serde(default)]
    pub(super) placement: Placement,
    /// The robot's footprint: with one, every planned move keeps its planning clearance from
    /// the boundary (walls and windows) of the view it is planned in, so the robot only
    /// drives where it has seen free space around it.
    #[serde(default)]
    footprint: Footprint,
    /// The sensor's rule for windows worth a trip.
    #[serde(default)]
    sensor: Sensor,
    /// What the rule and the footprint left unvisited.
    #[serde(default)]
    pub(super) skipped: Skipped,
    pub(super) views: Vec<View>,
    /// Window parts closed as out of reach, to be tried again when a later view holds their
    /// near side.
    #[serde(default)]
    deferred: Vec<Deferred>,
    /// Window parts dropped because a move toward their viewpoint failed
    /// ([`Known::move_failed`]), with no near side kept.
    #[serde(default)]
    dropped: Vec<Deferred>,
    /// How many views there were when the parts left out of reach or dropped were last tried
    /// again at what would have been the end ([`Known::retry_left_parts`]).
    #[serde(default)]
    retried_at: usize,
    /// The viewpoints asked for by the scans taken so far for window parts (a robot that
    /// could not stand exactly there scanned as near as it could).
    #[serde(default)]
    asked: Vec<Point>,
    /// The window part the next scan is for.
    pending: Option<Target>,
    /// On raw scans, the occupancy raster of the views ([`Known::close_if_walled`]): rebuilt
    /// from the views after deserialising.
    #[serde(skip)]
    walls_seen: WallsSeen,
    /// The trip being driven.
    #[serde(default)]
    trip: Trip,
    /// The view the robot stands at when it plans (the last scan's).
    #[serde(default)]
    here: usize,
    /// The waypoint of the last move that failed since the last scan, and how many moves in
    /// a row have failed near it.
    #[serde(default)]
    failed_at: Option<(Point, u32)>,
    /// Whether the last scan was taken to place the robot again ([`Known::move_failed`]).
    #[serde(default)]
    placed_again: bool,
    /// Whether a scan was taken at what would have been the end to place the robot again
    /// ([`Known::place_again_for_dropped`]) with no scan for a target since.
    #[serde(default)]
    placed_again_at_end: bool,
    /// Where the robot scanned because it could not even drive back ([`Known::stuck`]):
    /// stuck there again, the strategy gives up.
    #[serde(default)]
    stuck_at: Vec<Point>,
    /// A point just beyond each window part the rule's pocket term closed: the pockets that
    /// hold one are those the rule left, whose areas share one budget.
    #[serde(default)]
    left_in_pockets: Vec<Point>,
    /// The union of the views' regions and its holes, for the sensor rule's pocket term:
    /// built on demand, and rebuilt from the views after deserialising.
    #[serde(skip)]
    seen: Seen,
    /// On raw scans, the raster of the views whose safe cells the trips are driven through
    /// ([`Known::go_route`]): rebuilt from the views after deserialising.
    #[serde(skip)]
    roads: SeenRaster,
}

/// The union of the regions of the first `views` views, its area, and its holes (pockets of
/// unseen space enclosed by what was seen), each with its bounding box and area.
#[derive(Debug, Clone, Default)]
struct Seen {
    views: usize,
    union: Region,
    area: f64,
    pockets: Vec<Pocket>,
}

/// A hole of the union of the views' regions.
#[derive(Debug, Clone)]
struct Pocket {
    ring: Vec<Point>,
    bounds: [Point; 2],
    area: f64,
    /// Whether the rule's pocket term left it: it holds a point of
    /// [`Known::left_in_pockets`].
    left: bool,
}

impl PartialEq for Seen {
    /// A cache of the views, which are compared themselves: it takes no part in comparing
    /// states.
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

/// A window part closed without a visit: out of reach, with points on its near side (beside
/// its middle); or dropped by a failed move, with none.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct Deferred {
    view: usize,
    window: usize,
    gap: [f64; 2],
    near: Vec<Point>,
}

/// Windows closed without a visit, and why.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct Skipped {
    /// Windows, and parts of windows left open, shorter than the sensor rule's minimum
    /// ([`Sensor::min_window_at`]).
    pub below_rule: usize,
    /// Their total length, metres.
    pub below_rule_length: f64,
    /// Window parts no viewpoint with the footprint's clearance could be planned for from the
    /// view that saw them: none beside the part, and none from where the part is seen, that
    /// the robot can reach inside that view's region, straight or bending around its corners;
    /// nor after the scans that came later, at what would have been the end.
    pub out_of_reach: usize,
    /// Window parts that open into a pocket enclosed by what was seen smaller than the
    /// sensor rule's `min_pocket` share of the area seen ([`Sensor::min_pocket`]).
    #[serde(default)]
    pub small_pocket: usize,
    /// Window parts dropped because the robot reported that it could not reach the viewpoint
    /// planned for them (a move failure), and again when tried at what would have been the
    /// end, after the scans that came later.
    #[serde(default)]
    pub move_failed: usize,
    /// Window parts whose viewpoint a scan already stood at or was asked for (a view's parts
    /// along one wall may share the point clear of it): handled as after a scan there.
    #[serde(default)]
    pub looked_from: usize,
    /// Window parts that open onto a pocket of unseen space enclosed by walls seen and space
    /// seen, smaller than a quarter of the sensor rule's pocket limit, or onto a wall seen
    /// right behind them (raw scans, on a raster of the views).
    #[serde(default)]
    pub walled_pocket: usize,
    /// Windows of raw scans that are gaps in one wall seen at a slant (the walls on either
    /// side lie on one line, seen at 30° or less), read as that wall.
    #[serde(default)]
    pub wall_gap: usize,
    /// Scans taken where the robot was stuck: its moves failed, and so did the way back
    /// (odometry's drift can put the robot against a wall it believes it is clear of). The
    /// scan places it again, and the strategy plans on from there.
    #[serde(default)]
    pub stuck_scans: usize,
    /// Scans taken at what would have been the end, where the robot stood, because window
    /// parts were still dropped by failed moves and no view had been added since they were
    /// last tried: the scan places the robot again, and the parts are tried once more from a
    /// better pose.
    #[serde(default)]
    pub placed_again_scans: usize,
    /// Whether the strategy gave up before every window was explored: stuck again where it
    /// had scanned because it was stuck. What was left open is counted nowhere else.
    #[serde(default)]
    pub gave_up: bool,
}

impl View {
    /// Whether the robot, driving straight from the viewpoint to `z`, stays at least `c` from
    /// the region's boundary (walls and windows alike: beyond a window nothing is known);
    /// `relaxed` on raw scans ([`keeps_clear_leaving`]).
    fn clear(&self, z: Point, c: f64, relaxed: bool) -> bool {
        if relaxed {
            keeps_clear_leaving(&self.polygon, self.at, z, c)
        } else {
            keeps_clear(&self.polygon, self.at, z, c)
        }
    }

    /// Whether the straight move from the viewpoint to `z` stays strictly inside the region
    /// after leaving the viewpoint ([`reaches`]).
    fn reaches(&self, z: Point) -> bool {
        reaches(&self.polygon, self.at, z)
    }

    /// Whether `p` lies in the region's bounding box (closed).
    fn in_bounds(&self, p: Point) -> bool {
        self.near_bounds(p, 0.0)
    }

    /// Adds to `covered` the parts of the window `from`–`to` along which this view saw a wall
    /// within `tol` ([`cover::band_cover`]; nothing for `tol` 0, the exact sensor).
    fn band_cover(&self, from: Point, to: Point, tol: f64, covered: &mut Intervals) {
        if tol > 0.0 && (self.near_bounds(from, tol) || self.near_bounds(to, tol)) {
            for b in &self.pieces {
                if let BoundaryPiece::Wall { from: p, to: q } = *b {
                    cover::band_cover(from, to, p, q, tol, covered);
                }
            }
        }
    }

    /// Whether `p` lies in the region's bounding box grown by `eps`.
    fn near_bounds(&self, p: Point, eps: f64) -> bool {
        p[0] >= self.bounds[0][0] - eps
            && p[0] <= self.bounds[1][0] + eps
            && p[1] >= self.bounds[0][1] - eps
            && p[1] <= self.bounds[1][1] + eps
    }

    /// How many windows the view's region has.
    pub(super) fn windows_len(&self) -> usize {
        self.windows.len()
    }
}

/// Whether a robot driving straight from `at` to `z` stays at least `c` from the boundary of
/// `polygon`, a region seen from `at` (walls and windows alike: beyond a window nothing is
/// known). Floating point, like the clearance it checks.
pub(super) fn keeps_clear(polygon: &[Point], at: Point, z: Point, c: f64) -> bool {
    let n = polygon.len();
    let (x0, y0) = (at[0].min(z[0]) - c, at[1].min(z[1]) - c);
    let (x1, y1) = (at[0].max(z[0]) + c, at[1].max(z[1]) + c);
    (0..n).all(|i| {
        let (p, q) = (polygon[i], polygon[(i + 1) % n]);
        // An edge whose box lies more than `c` beyond the move's box along an axis is farther
        // than `c` from it: the exact distance is needed only for the others.
        p[0].max(q[0]) < x0
            || p[0].min(q[0]) > x1
            || p[1].max(q[1]) < y0
            || p[1].min(q[1]) > y1
            || !segments_closer_than(at, z, p, q, c)
    })
}

/// [`keeps_clear`] for a robot that may stand nearer than `c` to the boundary (on raw scans,
/// where the drift or a scan's alignment put it): the move needs only keep 99% of the
/// clearance the robot has where it stands, when that is less than `c`.
pub(super) fn keeps_clear_leaving(polygon: &[Point], at: Point, z: Point, c: f64) -> bool {
    let n = polygon.len();
    // The robot's own clearance, where it is below `c` (edges whose box lies farther than
    // `c` from `at` along an axis cannot be nearer).
    let own = (0..n)
        .map(|i| (polygon[i], polygon[(i + 1) % n]))
        .filter(|(p, q)| {
            p[0].max(q[0]) >= at[0] - c
                && p[0].min(q[0]) <= at[0] + c
                && p[1].max(q[1]) >= at[1] - c
                && p[1].min(q[1]) <= at[1] + c
        })
        .map(|(p, q)| segments_distance(at, at, p, q))
        .fold(f64::INFINITY, f64::min);
    keeps_clear(polygon, at, z, if own < c { 0.99 * own } else { c })
}

/// Whether the straight move from `at` (the viewpoint `polygon` was seen from) to `z` stays
/// strictly inside the region after leaving `at`, `(at, z]` (exact tests against its
/// boundary, whose reflex vertices are exact input points). The viewpoint itself may lie on
/// the boundary (a start against a wall or in a corner): an edge through it meets the move
/// only there unless `z` lies on the edge's line.
pub(super) fn reaches(polygon: &[Point], at: Point, z: Point) -> bool {
    let n = polygon.len();
    ring_side(polygon, z) == RingSide::Inside
        && (0..n).all(|i| {
            let (p, q) = (polygon[i], polygon[(i + 1) % n]);
            if on_segment(p, q, at) {
                orient_sign(p, q, z) != 0
            } else {
                !segments_intersect(at, z, p, q)
            }
        })
}

impl Known {
    /// What a strategy knows before its first scan: the robot's footprint and sensor.
    pub(super) fn for_robot(setup: &RobotSetup) -> Self {
        Self { footprint: setup.footprint.clone(), sensor: setup.sensor, ..Self::default() }
    }

    /// The robot's footprint.
    pub(super) fn footprint(&self) -> &Footprint {
        &self.footprint
    }

    /// Whether the robot may stand nearer a wall than its clearance (raw scans: the sensor
    /// rule tolerates walls placed apart by noise), so that moves out of there are relaxed.
    pub(super) fn relaxed(&self) -> bool {
        self.sensor.wall_tolerance > 0.0
    }

    /// The clearance planned moves keep near view `v` (0 for a point robot).
    pub(super) fn clearance(&self, v: usize) -> f64 {
        self.footprint.planning_clearance(magnitude(&self.views[v].polygon))
    }

    /// The pocket just beyond the window part `p q` (on the side away from its view's region,
    /// which lies left of its windows), with the point probed there: `Some` when the space
    /// there is a hole of the union of all views' regions ([`Known::update_seen`]), enclosed
    /// by what was seen and so no larger than the hole; `None` when it opens onto the
    /// unbounded unseen space.
    fn pocket_beyond(&mut self, p: Point, q: Point) -> Option<(usize, Point)> {
        self.update_seen();
        // A thousandth of the part's length beyond its middle.
        let m = [
            f64::midpoint(p[0], q[0]) + 1e-3 * (q[1] - p[1]),
            f64::midpoint(p[1], q[1]) - 1e-3 * (q[0] - p[0]),
        ];
        self.pocket_at(m).map(|k| (k, m))
    }

    /// The pocket (hole of the union of the views' regions) that holds `m`, if any.
    fn pocket_at(&self, m: Point) -> Option<usize> {
        self.seen.pockets.iter().position(|k| {
            (k.bounds[0][0]..=k.bounds[1][0]).contains(&m[0])
                && (k.bounds[0][1]..=k.bounds[1][1]).contains(&m[1])
                && ring_side(&k.ring, m) == RingSide::Inside
        })
    }

    /// Brings the union of the views' regions and its holes up to date with the views.
    pub(super) fn update_seen(&mut self) {
        let n = self.views.len();
        if self.seen.views < n {
            let new: Vec<Vec<Point>> =
                self.views[self.seen.views..].iter().map(|v| v.polygon.clone()).collect();
            let seen = &mut self.seen;
            seen.union = seen.union.union(&Region::union_all(&new));
            seen.views = n;
            seen.area = seen.union.area();
            seen.pockets = seen
                .union
                .shapes
                .iter()
                .flat_map(|s| s.iter().skip(1))
                .filter(|h| h.len() >= 3)
                .map(|h| Pocket {
                    ring: h.clone(),
                    bounds: cover::bounds_of(h),
                    area: crate::geometry::signed_area_of(h).abs(),
                    left: false,
                })
                .collect();
            for i in 0..self.left_in_pockets.len() {
                if let Some(k) = self.pocket_at(self.left_in_pockets[i]) {
                    self.seen.pockets[k].left = true;
                }
            }
        }
    }

    /// A viewpoint for the part `gap` (at `pq`) of the window `from`–`to` of `view` when none
    /// is found in the view's own region: from the regions of other views that hold one of
    /// the points `near` on its near side, nearest viewpoint first (ties to the earlier view;
    /// the view returned as the anchor), else through the union of all views
    /// ([`Known::union_point`], no anchor).
    fn plan_elsewhere(
        &mut self,
        view: usize,
        (from, to, gap): (Point, Point, [f64; 2]),
        pq: [Point; 2],
        near: &[Point],
        c: f64,
    ) -> Option<(Point, Vec<Point>, Option<usize>)> {
        let m = [f64::midpoint(pq[0][0], pq[1][0]), f64::midpoint(pq[0][1], pq[1][1])];
        let mut others: Vec<(f64, usize)> = (0..self.views.len())
            .filter(|&w| w != view && near.iter().any(|&z| self.inside(w, z)))
            .map(|w| {
                let a = self.views[w].at;
                ((a[0] - m[0]).hypot(a[1] - m[1]), w)
            })
            .collect();
        others.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
        let cw = |w: usize| self.clearance(w);
        if let Some((w, (at, via))) = others
            .into_iter()
            .find_map(|(_, w)| self.clear_point(w, from, to, gap, cw(w)).map(|x| (w, x)))
        {
            return Some((at, via, Some(w)));
        }
        self.union_point(view, (from, to, gap), c).map(|(at, via)| (at, via, None))
    }

    /// A viewpoint for the part `gap` of the window `from`–`to` of `view` that a robot with
    /// clearance `c` reaches from the view's viewpoint along a path in the union of all
    /// views' regions (seen free space, from several scans), bending around its corners
    /// ([`Approach::with_holes`]); `None` if none does. The last resort before a part is
    /// deferred: a door seen at a slant by every view, through which no single view's region
    /// leaves room for the robot, while together they do. The union is clipped to a box
    /// around the viewpoint and the part, grown by a margin, so the search stays local.
    fn union_point(
        &mut self,
        view: usize,
        (from, to, gap): (Point, Point, [f64; 2]),
        c: f64,
    ) -> Option<(Point, Vec<Point>)> {
        self.update_seen();
        let at = self.views[view].at;
        // Only goals in the view's region, from where the robot looks through its window.
        let beside: Vec<(Point, Point)> = self
            .beside_points(from, to, gap, c)
            .into_iter()
            .filter(|&(z, _)| self.inside(view, z))
            .collect();
        let g = part_points(from, to, gap);
        let mid = [f64::midpoint(g[0][0], g[1][0]), f64::midpoint(g[0][1], g[1][1])];
        let margin = UNION_MARGIN * c;
        let pts: Vec<Point> = beside.iter().map(|b| b.0).chain([at, mid]).collect();
        let [lo, hi] = cover::bounds_of(&pts);
        let boxed = Region::polygon(&[
            [lo[0] - margin, lo[1] - margin],
            [hi[0] + margin, lo[1] - margin],
            [hi[0] + margin, hi[1] + margin],
            [lo[0] - margin, hi[1] + margin],
        ]);
        let local = self.seen.union.intersection(&boxed);
        let shape = local.shapes.iter().find(|s| holds(s, at))?;
        // Or a corner of the union from where the part is seen across it: in front of a door
        // too steep and narrow to pass, the robot looks through it.
        let beside: Vec<Point> = beside
            .into_iter()
            .filter(|&(z, foot)| sees_across(shape, z, foot))
            .map(|(z, _)| z)
            .collect();
        let a = Approach::with_holes(shape, c).leaving(self.relaxed());
        self.pass_or_look(&a, at, g, &beside, |z, m| sees_across(shape, z, m))
    }

    /// The sensor rule's pocket term for the open part `gap` (at `pq`) of window `k` of
    /// `view`: when what lies behind it is enclosed by what was seen and smaller than the
    /// rule's share of it and its cap, and the pockets left so far with this one hold less
    /// than the rule's budget ([`Sensor::pocket_allowance`]), the part is closed and counted,
    /// and `true` returned. Each pocket left is known by the point probed beyond its part,
    /// and counted once at its hole's area now: a hole only shrinks as views are added, so
    /// the pockets left hold no more than the budget granted when the last was left (a hole
    /// that a later view splits is counted by the piece that holds the probed point).
    fn closed_as_pocket(&mut self, view: usize, k: usize, gap: [f64; 2], pq: [Point; 2]) -> bool {
        if !self.sensor.has_pocket_term() {
            return false;
        }
        let Some((pocket, probe)) = self.pocket_beyond(pq[0], pq[1]) else {
            return false;
        };
        let seen = self.seen.area;
        if self.seen.pockets[pocket].area >= self.sensor.pocket_limit(seen) {
            return false;
        }
        // The pockets the rule left so far, each counted once, with this one.
        let total: f64 = (self.seen.pockets.iter().enumerate())
            .filter(|&(j, k)| k.left || j == pocket)
            .map(|(_, k)| k.area)
            .sum();
        if total >= self.sensor.pocket_allowance(seen) {
            return false;
        }
        self.left_in_pockets.push(probe);
        self.seen.pockets[pocket].left = true;
        self.skipped.small_pocket += 1;
        self.close(view, k, gap);
        true
    }

    /// Records a scan, taken at the pending target (inside its view's region, which becomes
    /// the new view's parent in the tree of moves); the target counts as handled.
    pub(super) fn add(&mut self, obs: &PolygonObservation) -> usize {
        let pending = self.pending.take();
        // The view the trip to the target started from: the target lies in its region.
        let parent = pending.as_ref().map(Target::base);
        self.failed_at = None;
        self.placed_again = pending.as_ref().is_some_and(|t| t.relocate);
        self.placed_again_at_end &= self.placed_again;
        // A scan to place the robot again leaves its target's part open; any other is a
        // visit of the target's window.
        if let Some(t) = pending.as_ref().filter(|t| !t.relocate) {
            if !t.off_gap {
                self.handled(t);
            }
            self.asked.push(t.at);
            let w = &mut self.views[t.view].windows[t.window];
            if w.lift == Lift::Lifted {
                w.lift = Lift::Spent;
            }
        }
        let (sensor, at) = (self.sensor, obs.at);
        let skipped = &mut self.skipped;
        let windows = obs
            .region
            .boundary
            .iter()
            .enumerate()
            .filter_map(|(piece, b)| match *b {
                BoundaryPiece::Window { from, to, .. } | BoundaryPiece::Frontier { from, to } => {
                    let tol = cover::tolerance(obs.at, b);
                    let mut covered = Vec::new();
                    // The sensor rule closes short windows (not range frontiers: a range's
                    // arc comes as many short chords).
                    if matches!(b, BoundaryPiece::Window { .. })
                        && let Some(len) = below_rule(&sensor, at, from, to)
                    {
                        skipped.below_rule += 1;
                        skipped.below_rule_length += len;
                        covered.push([0.0, 1.0]);
                    }
                    // On raw scans, a gap in one wall line seen at a slant is that wall.
                    if covered.is_empty()
                        && sensor.wall_tolerance > 0.0
                        && gap_in_a_wall(&obs.region.boundary, piece, at, sensor.wall_tolerance)
                    {
                        skipped.wall_gap += 1;
                        covered.push([0.0, 1.0]);
                    }
                    let range_frontier = matches!(b, BoundaryPiece::Frontier { .. });
                    Some(Window {
                        piece,
                        from,
                        to,
                        tol,
                        covered,
                        ruled: Vec::new(),
                        lift: Lift::Never,
                        checked: 0,
                        range_frontier,
                        no_junction: false,
                    })
                }
                _ => None,
            })
            .collect();
        let poly = &obs.region.polygon;
        let bounds = cover::bounds_of(poly);
        self.views.push(View {
            at: obs.at,
            polygon: poly.clone(),
            bounds,
            pieces: obs.region.boundary.clone(),
            windows,
            parent,
            via: pending.as_ref().map(|t| t.via.clone()).unwrap_or_default(),
            explored: false,
            rounding: rounding(magnitude(poly)),
            placement: obs.placement,
        });
        if let Some(t) = pending.filter(|t| t.off_gap) {
            self.views[t.view].windows[t.window].no_junction = true;
        }
        let nv = self.views.len() - 1;
        self.revive(nv);
        nv
    }

    /// The next viewpoint for the first unexplored window of `view` (the paper's Step 5): a
    /// window is unexplored while part of its far side is covered by no other view
    /// ([`cover::side_cover`], exact up to the rounding of cut points). The viewpoint is the
    /// middle of the first uncovered part, moved a millionth of the window's length into the
    /// view's region (less where the region is thinner), so the straight move there from the
    /// viewpoint is safe, and from it the whole far side of the window is seen.
    pub(super) fn next_target(&mut self, view: usize) -> Option<Target> {
        if self.views[view].explored {
            return None;
        }
        let t = (0..self.views[view].windows.len())
            .find_map(|k| self.window_target(view, k).map(|t| t.0));
        self.views[view].explored = t.is_none();
        t
    }

    /// Counts in window `k` of `view`'s cover what the views taken since it was last tested
    /// see of it (and, on raw scans, the walls they saw along it).
    fn update_cover(&mut self, view: usize, k: usize) {
        let n = self.views.len();
        let (from, to, checked) = {
            let w = &self.views[view].windows[k];
            (w.from, w.to, w.checked)
        };
        if checked < n {
            let mut covered = std::mem::take(&mut self.views[view].windows[k].covered);
            let own = self.views[view].placement;
            for (j, v) in self.views.iter().enumerate().skip(checked) {
                if j != view {
                    cover::side_cover(from, to, &v.polygon, v.bounds, &mut covered);
                    // A wall another scan saw along the window (raw scans only).
                    let tol = self.sensor.cover_band_between(own, v.placement);
                    v.band_cover(from, to, tol, &mut covered);
                }
            }
            cover::merge(&mut covered);
            let w = &mut self.views[view].windows[k];
            w.covered = covered;
            w.checked = n;
        }
    }

    /// Brings window `k` of `view` up to date with the views taken since it was last tested,
    /// and returns the viewpoint for its first uncovered part with the window's total
    /// uncovered length (metres), or `None` once it is explored.
    pub(super) fn window_target(&mut self, view: usize, k: usize) -> Option<(Target, f64)> {
        self.update_cover(view, k);
        let (from, to) = (self.views[view].windows[k].from, self.views[view].windows[k].to);
        loop {
            let w = &self.views[view].windows[k];
            let covered = &w.covered;
            let gap = cover::first_gap(covered, w.tol)?;
            let (dx, dy) = (to[0] - from[0], to[1] - from[1]);
            let open = (1.0 - covered.iter().map(|c| c[1] - c[0]).sum::<f64>()) * dx.hypot(dy);
            // The sensor rule applies to what is left open of a window as to a whole window
            // (not to range frontiers, whose arc comes as many short chords): an open part
            // shorter than the sensor resolves from the view is not worth a trip.
            let p = [from[0] + gap[0] * dx, from[1] + gap[0] * dy];
            let q = [from[0] + gap[1] * dx, from[1] + gap[1] * dy];
            // A lifted window ([`reopen_wide_openings`](Self::reopen_wide_openings)) is part
            // of an opening wider than the rule, so the rule's width is lifted for it; what
            // the sensor resolves is not: a part shorter than the beams' spacing at its
            // distance (a sliver between two noisy scans' regions) is not worth a trip.
            let rule = match w.lift {
                Lift::Lifted => Sensor { min_window: 0.0, ..self.sensor },
                _ => self.sensor,
            };
            if !w.range_frontier
                && let Some(len) = below_rule(&rule, self.views[view].at, p, q)
            {
                self.skipped.below_rule += 1;
                self.skipped.below_rule_length += len;
                self.close(view, k, gap).ruled.push(gap);
                continue;
            }
            if self.closed_as_pocket(view, k, gap, [p, q]) {
                continue;
            }
            let tm = match self.placement {
                Placement::Middle => 0.5 * (gap[0] + gap[1]),
                Placement::Far => {
                    let at = self.views[view].at;
                    let d = |p: Point| (p[0] - at[0]).hypot(p[1] - at[1]);
                    let inset = 1e-3 * (gap[1] - gap[0]);
                    if d(to) >= d(from) { gap[1] - inset } else { gap[0] + inset }
                }
            };
            let target = Target {
                at: self.views[view].at,
                via: Vec::new(),
                view,
                window: k,
                gap,
                anchor: None,
                off_gap: false,
                relocate: false,
            };
            let c = self.clearance(view);
            if c > 0.0 {
                let near = near_side(p, q, c);
                let planned = match self.clear_point(view, from, to, gap, c) {
                    Some((at, via)) => Some(Target { at, via, ..target.clone() }),
                    // From the regions of other views that hold the part's near side, or
                    // through the union of all views.
                    None => self
                        .plan_elsewhere(view, (from, to, gap), [p, q], &near, c)
                        .map(|(at, via, anchor)| Target { at, via, anchor, ..target.clone() }),
                };
                if let Some(t) = planned {
                    if self.looked_from(&t) || self.close_if_walled(&t, [p, q]) {
                        continue;
                    }
                    return Some((t, open));
                }
                self.skipped.out_of_reach += 1;
                self.deferred.push(Deferred { view, window: k, gap, near });
                self.handled(&target);
                continue;
            }
            let x = [from[0] + tm * dx, from[1] + tm * dy];
            // Windows are radial, so the step goes sideways into the region (left of the
            // window, which runs counter-clockwise around it), not toward the viewpoint: a move
            // along the window's own ray would graze its reflex vertex.
            let v = &self.views[view];
            let floor = 4.0 * v.rounding / dx.hypot(dy);
            let found = [1e-6, 1e-8, 1e-10]
                .into_iter()
                .map(|e: f64| e.max(floor))
                .map(|e| [x[0] - e * dy, x[1] + e * dx])
                .find(|&z| v.reaches(z));
            if let Some(at) = found {
                let t = Target { at, ..target };
                if self.looked_from(&t) || self.close_if_walled(&t, [p, q]) {
                    continue;
                }
                return Some((t, open));
            }
            // No point beside this part can be reached in a straight line, and a scan where the
            // robot stands would only repeat this view: the part counts as handled, as it would
            // after a scan for it, so that every scan makes progress.
            self.handled(&target);
        }
    }

    /// When nothing else is left open: the sensor rule judged each view's window parts
    /// alone, but where views overlap, an opening (a door seen at a slant from both sides of
    /// a corridor) may be left as a short open part of each of several windows, each below the
    /// rule. This looks at the frontier of everything seen (the boundary of the union of the
    /// views' regions that lies on their windows) and opens again the parts the rule closed
    /// along every chain of it at least `min_window` long; the rule's width is then lifted for
    /// their windows until a scan is taken for one of their parts (what the beams resolve
    /// still applies), so each window is reopened at most once, visited at most once under the
    /// lift, and the exploration ends. Returns whether any part was opened.
    pub(super) fn reopen_wide_openings(&mut self) -> bool {
        let need = self.sensor.min_window_at(0.0);
        if self.sensor.excludes_nothing() || self.views.is_empty() {
            return false;
        }
        if !self
            .views
            .iter()
            .any(|v| v.windows.iter().any(|w| !w.ruled.is_empty() && w.lift == Lift::Never))
        {
            return false;
        }
        self.update_seen();
        let union = &self.seen.union;
        // The windows (view, index) an edge of the union's boundary lies on, and where.
        let on_windows = |m: Point| -> Vec<WindowAt> {
            let eps = 1e-6 * m[0].abs().max(m[1].abs()).max(1.0);
            let mut out = Vec::new();
            for (vi, v) in self.views.iter().enumerate() {
                if !v.near_bounds(m, eps) {
                    continue;
                }
                for (k, w) in v.windows.iter().enumerate() {
                    if segments_distance(w.from, w.to, m, m) <= eps {
                        let (dx, dy) = (w.to[0] - w.from[0], w.to[1] - w.from[1]);
                        let t = ((m[0] - w.from[0]) * dx + (m[1] - w.from[1]) * dy)
                            / (dx * dx + dy * dy);
                        out.push((vi, k, t));
                    }
                }
            }
            out
        };
        let mut reopen: Vec<WindowAt> = Vec::new();
        for ring in union.shapes.iter().flatten() {
            let n = ring.len();
            let edges: Vec<(f64, Vec<WindowAt>)> = (0..n)
                .map(|i| {
                    let (a, b) = (ring[i], ring[(i + 1) % n]);
                    let m = [f64::midpoint(a[0], b[0]), f64::midpoint(a[1], b[1])];
                    ((b[0] - a[0]).hypot(b[1] - a[1]), on_windows(m))
                })
                .collect();
            // Chains of consecutive frontier edges, starting after a wall edge (a ring that is
            // all frontier is one chain).
            let start = edges.iter().position(|e| e.1.is_empty()).map_or(0, |i| i + 1);
            let mut chain: Vec<usize> = Vec::new();
            for j in 0..=n {
                let i = (start + j) % n;
                if j < n && !edges[i].1.is_empty() {
                    chain.push(i);
                    continue;
                }
                // The opening's width: from where the chain leaves a wall to where it meets
                // one again (the whole ring's length when it touches no wall).
                let width = match (chain.first(), chain.last()) {
                    (Some(&f), Some(&l)) if chain.len() < n => {
                        let (a, b) = (ring[f], ring[(l + 1) % n]);
                        (b[0] - a[0]).hypot(b[1] - a[1])
                    }
                    _ => chain.iter().map(|&c| edges[c].0).sum(),
                };
                if width >= need {
                    reopen.extend(chain.iter().flat_map(|&c| edges[c].1.iter().copied()));
                }
                chain.clear();
            }
        }
        let mut any = false;
        for (vi, k, t) in reopen {
            let w = &mut self.views[vi].windows[k];
            if w.lift != Lift::Never {
                continue;
            }
            let Some(&gap) = w.ruled.iter().find(|g| g[0] <= t && t <= g[1]) else { continue };
            w.covered = uncover(&w.covered, gap);
            w.ruled.retain(|g| *g != gap);
            w.lift = Lift::Lifted;
            w.checked = 0;
            let len = (gap[1] - gap[0]) * (w.to[0] - w.from[0]).hypot(w.to[1] - w.from[1]);
            self.views[vi].explored = false;
            self.skipped.below_rule -= 1;
            self.skipped.below_rule_length -= len;
            any = true;
        }
        any
    }

    /// At what would be the end of the exploration, opens again every window part left out of
    /// reach ([`Skipped::out_of_reach`]) or dropped by a failed move ([`Skipped::move_failed`]),
    /// when views were added since they were last tried: the scans taken since may have opened
    /// a way to them (a path through the union of the views' regions), and a move that failed
    /// on a pose error may succeed from a better pose. Each try either ends in a scan, which
    /// adds a view, or leaves the parts as they were, so the exploration still ends. Returns
    /// whether any part was opened.
    fn retry_left_parts(&mut self) -> bool {
        if self.views.len() <= self.retried_at {
            return false;
        }
        self.retried_at = self.views.len();
        let left: Vec<Deferred> = std::mem::take(&mut self.deferred)
            .into_iter()
            .chain(std::mem::take(&mut self.dropped))
            .collect();
        let any = !left.is_empty();
        self.skipped.out_of_reach = 0;
        self.skipped.move_failed = 0;
        for d in left {
            self.open_again(&d);
        }
        any
    }

    /// Opens part `d` of its window again; the window's cover is recomputed from every view,
    /// so what was seen of it since stays covered.
    fn open_again(&mut self, d: &Deferred) {
        let v = &mut self.views[d.view];
        v.explored = false;
        let w = &mut v.windows[d.window];
        w.covered = uncover(&w.covered, d.gap);
        w.checked = 0;
    }

    /// Opens again the deferred window parts whose near side the new view `nv` holds: a
    /// viewpoint in its region may reach them. Their windows' cover is recomputed from every
    /// view, so the parts seen since stay covered.
    fn revive(&mut self, nv: usize) {
        let (revived, kept): (Vec<Deferred>, Vec<Deferred>) = std::mem::take(&mut self.deferred)
            .into_iter()
            .partition(|d| d.near.iter().any(|&z| self.inside(nv, z)));
        self.deferred = kept;
        for d in revived {
            self.skipped.out_of_reach -= 1;
            self.open_again(&d);
        }
    }

    /// A viewpoint for the part `gap` of the window `from`–`to` of `view` that a robot with
    /// clearance `c` can reach from the view's viewpoint, with the waypoints on the way
    /// (empty for a straight move). In order of preference:
    /// - points of the part (its middle first, then quarters and eighths) stepped `c` and
    ///   more off the window into the region, that see the point of the part they stand
    ///   beside, the first whose straight move keeps `c` from the region's boundary; from
    ///   there the robot looks through the window from a step
    ///   back, and what it cannot see is left behind the new view's own windows;
    /// - the same points, the first reached by a path that bends around the region's
    ///   corners ([`Approach`]): a door seen at a slant;
    /// - a point stepped off a corner of the region that sees the part across it, nearest
    ///   the part under the widest angle first (at least [`MIN_LOOK_ANGLE`]): where the
    ///   door is too steep to pass through in the region, the robot looks through it from
    ///   in front.
    fn clear_point(
        &self,
        view: usize,
        from: Point,
        to: Point,
        gap: [f64; 2],
        c: f64,
    ) -> Option<(Point, Vec<Point>)> {
        let v = &self.views[view];
        let (dx, dy) = (to[0] - from[0], to[1] - from[1]);
        let len = dx.hypot(dy);
        if len == 0.0 {
            return None;
        }
        let beside = self.beside_points(from, to, gap, c);
        let sees_foot = |&(z, foot): &(Point, Point)| {
            self.inside(view, z) && self.sees_point_within(view, z, foot)
        };
        if let Some(&(z, _)) = beside
            .iter()
            .find(|b| v.reaches(b.0) && v.clear(b.0, c, self.relaxed()) && sees_foot(b))
        {
            return Some((z, Vec::new()));
        }
        let beside: Vec<Point> = beside.iter().filter(|b| sees_foot(b)).map(|b| b.0).collect();
        let a = Approach::new(&v.polygon, c).leaving(self.relaxed());
        let g = part_points(from, to, gap);
        self.pass_or_look(&a, v.at, g, &beside, |z, m| self.sees_point_within(view, z, m))
    }

    /// Along paths in `a` from `at`: the first of `beside` reached, else a point stepped off
    /// a corner of `a` near the straight line to the part `g` from where the robot looks
    /// through the part, the steepest look first. A look is a sight line from the corner to
    /// one of the part's sample points ([`LOOK_SAMPLES`]) that `sees` (across the region),
    /// crossing the part at an angle of at least [`MIN_LOOK_ANGLE`]; the corner is ranked by
    /// its steepest such crossing, since the steeper a sight line crosses the window, the
    /// farther it reaches into what lies behind. A door seen at a slant is so looked through
    /// from in front of it, although its window's middle is hidden from there behind a jamb;
    /// a corner on the window's own line (behind the viewpoint, say) sees nothing new.
    fn pass_or_look(
        &self,
        a: &Approach<'_>,
        at: Point,
        g: [Point; 2],
        beside: &[Point],
        sees: impl Fn(Point, Point) -> bool,
    ) -> Option<(Point, Vec<Point>)> {
        let mid = [f64::midpoint(g[0][0], g[1][0]), f64::midpoint(g[0][1], g[1][1])];
        let corners = a.corners([at, mid]);
        if let Some(p) = a.path(at, &corners, beside) {
            return Some((beside[p.goal], p.via));
        }
        let (dx, dy) = (g[1][0] - g[0][0], g[1][1] - g[0][1]);
        let len = dx.hypot(dy);
        if len == 0.0 {
            return None;
        }
        let min_sin = MIN_LOOK_ANGLE.sin();
        let mut looks: Vec<(f64, Point)> = corners
            .iter()
            .filter(|&&z| !self.stood_at(z))
            .filter_map(|&z| {
                // The samples by the steepness of their sight lines; the first seen ranks z.
                let mut aims: Vec<(f64, Point)> = LOOK_SAMPLES
                    .iter()
                    .map(|&f| [g[0][0] + f * dx, g[0][1] + f * dy])
                    .filter_map(|m| {
                        let (sx, sy) = (m[0] - z[0], m[1] - z[1]);
                        let sl = sx.hypot(sy);
                        let sin =
                            if sl > 0.0 { (dx * sy - dy * sx).abs() / (len * sl) } else { 0.0 };
                        (sin >= min_sin).then_some((sin, m))
                    })
                    .collect();
                aims.sort_by(|x, y| y.0.total_cmp(&x.0));
                aims.into_iter().find(|&(_, m)| sees(z, m)).map(|(sin, _)| (sin, z))
            })
            .collect();
        looks.sort_by(|x, y| y.0.total_cmp(&x.0));
        let looks: Vec<Point> = looks.into_iter().map(|x| x.1).collect();
        let p = a.path(at, &corners, &looks)?;
        Some((looks[p.goal], p.via))
    }

    /// Points beside the part `gap` of the window `from`–`to`, in order of preference: its
    /// middle, then quarters and eighths, each stepped 1, 1.5, 2.5 and 4 times `c` off the
    /// window into its view's region (left of the window); none where a scan was taken. Each
    /// comes with its foot on the part, which a viewpoint there must see: a step off a part
    /// just behind a door's jamb can land across the wall, in the corridor the door opens
    /// from, where a scan would not see the part at all.
    fn beside_points(&self, from: Point, to: Point, gap: [f64; 2], c: f64) -> Vec<(Point, Point)> {
        let (dx, dy) = (to[0] - from[0], to[1] - from[1]);
        let len = dx.hypot(dy);
        if len == 0.0 {
            return Vec::new();
        }
        // The unit normal into the region (left of the window).
        let n = [-dy / len, dx / len];
        [0.5, 0.25, 0.75, 0.125, 0.375, 0.625, 0.875]
            .into_iter()
            .flat_map(|f| {
                let t = gap[0] + f * (gap[1] - gap[0]);
                let x = [from[0] + t * dx, from[1] + t * dy];
                [1.0, 1.5, 2.5, 4.0]
                    .into_iter()
                    .map(move |k| ([x[0] + k * c * n[0], x[1] + k * c * n[1]], x))
            })
            .filter(|&(z, _)| !self.stood_at(z))
            .collect()
    }

    /// The window segment a target is for, and the part of it (as points) still open.
    pub(super) fn gap_of(&self, t: &Target) -> [Point; 2] {
        let w = &self.views[t.view].windows[t.window];
        part_points(w.from, w.to, t.gap)
    }

    /// Viewpoints for target `t` stepped back from its window into its view's region by each
    /// of `depths` (metres, beyond the target's own step), that the robot can drive to straight
    /// from the view's viewpoint keeping its clearance: places from where one scan may look
    /// through several windows of the view at once.
    pub(super) fn stepped_back(&self, t: &Target, depths: &[f64]) -> Vec<Point> {
        let v = &self.views[t.base()];
        let [p, q] = self.gap_of(t);
        let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
        let len = dx.hypot(dy);
        if len == 0.0 {
            return Vec::new();
        }
        let n = [-dy / len, dx / len];
        let c = self.clearance(t.base());
        depths
            .iter()
            .map(|&s| [t.at[0] + s * n[0], t.at[1] + s * n[1]])
            .filter(|&z| {
                v.reaches(z) && (c == 0.0 || v.clear(z, c, self.relaxed())) && !self.stood_at(z)
            })
            .collect()
    }

    /// Viewpoints in the corners of view `view`'s region: each convex corner stepped along its
    /// bisector into the region until it stands `inset` beyond the clearance from both of its
    /// sides, kept when the robot reaches it straight from the view's viewpoint keeping its
    /// clearance and no scan was taken there; the `max` nearest to `near` within `within`.
    /// The corners of a room hold the places from where one scan sees all around a desk.
    pub(super) fn corner_points(
        &self,
        view: usize,
        near: Point,
        within: f64,
        inset: f64,
        max: usize,
    ) -> Vec<Point> {
        let v = &self.views[view];
        let c = self.clearance(view);
        let poly = &v.polygon;
        let n = poly.len();
        let d = |p: Point| (p[0] - near[0]).hypot(p[1] - near[1]);
        let mut out: Vec<(f64, Point)> = (0..n)
            .filter_map(|i| {
                let (a, p, b) = (poly[(i + n - 1) % n], poly[i], poly[(i + 1) % n]);
                if d(p) > within {
                    return None;
                }
                let (u, w) = ([a[0] - p[0], a[1] - p[1]], [b[0] - p[0], b[1] - p[1]]);
                let (lu, lw) = (u[0].hypot(u[1]), w[0].hypot(w[1]));
                if lu == 0.0 || lw == 0.0 || (p[0] - a[0]) * w[1] - (p[1] - a[1]) * w[0] <= 0.0 {
                    return None;
                }
                let (u, w) = ([u[0] / lu, u[1] / lu], [w[0] / lw, w[1] / lw]);
                let bis = [u[0] + w[0], u[1] + w[1]];
                let lb = bis[0].hypot(bis[1]);
                // sin of half the corner's angle: the step along the bisector that puts the
                // point `c + inset` from both sides.
                let half_sin = (u[0] * w[1] - u[1] * w[0]).abs() / lb;
                if lb == 0.0 || !(0.2..=FLAT_CORNER).contains(&half_sin) {
                    return None;
                }
                let s = (c + inset) / half_sin;
                let z = [p[0] + s * bis[0] / lb, p[1] + s * bis[1] / lb];
                (v.reaches(z) && (c == 0.0 || v.clear(z, c, self.relaxed())) && !self.stood_at(z))
                    .then_some((d(z), z))
            })
            .collect();
        out.sort_by(|x, y| x.0.total_cmp(&y.0));
        out.into_iter().take(max).map(|x| x.1).collect()
    }

    /// The viewpoint of view `view`.
    pub(super) fn viewpoint(&self, view: usize) -> Point {
        self.views[view].at
    }

    /// The view's region (counter-clockwise) and its boundary pieces.
    pub(super) fn region_of(&self, view: usize) -> (&[Point], &[BoundaryPiece]) {
        (&self.views[view].polygon, &self.views[view].pieces)
    }

    /// Whether `z`, a point inside view `view`'s region, sees the middle of the segment
    /// `g` on the region's boundary across the region (a straight line that crosses none of
    /// its edges).
    pub(super) fn sees_within(&self, view: usize, z: Point, g: [Point; 2]) -> bool {
        let m = [f64::midpoint(g[0][0], g[1][0]), f64::midpoint(g[0][1], g[1][1])];
        self.sees_point_within(view, z, m)
    }

    /// Whether `z`, a point inside view `view`'s region, sees the point `m` on the region's
    /// boundary across the region.
    fn sees_point_within(&self, view: usize, z: Point, m: Point) -> bool {
        let v = &self.views[view];
        // A hair off the boundary, toward z.
        let m = [m[0] + 1e-6 * (z[0] - m[0]), m[1] + 1e-6 * (z[1] - m[1])];
        let n = v.polygon.len();
        ring_side(&v.polygon, m) == RingSide::Inside
            && (0..n).all(|i| !segments_intersect(z, m, v.polygon[i], v.polygon[(i + 1) % n]))
    }

    /// Whether `z` lies strictly inside view `view`'s region.
    pub(super) fn inside(&self, view: usize, z: Point) -> bool {
        let v = &self.views[view];
        v.in_bounds(z) && ring_side(&v.polygon, z) == RingSide::Inside
    }

    /// How far view `view`'s region reaches from its viewpoint (its farthest vertex).
    pub(super) fn reach_of(&self, view: usize) -> f64 {
        let v = &self.views[view];
        v.polygon.iter().map(|p| (p[0] - v.at[0]).hypot(p[1] - v.at[1])).fold(0.0, f64::max)
    }

    /// Whether a scan was already taken at `z`, or asked for there (windows of two views on
    /// one ray give the same stepped-back point, and a view's window parts along one wall the
    /// same point clear of it; a second scan there would see nothing new).
    pub(super) fn stood_at(&self, z: Point) -> bool {
        self.view_at(z).is_some() || self.asked.contains(&z)
    }

    /// The index among `view`'s windows of the window that is its piece `piece`, if it is one
    /// and junction targets are still tried on it.
    pub(super) fn window_of_piece(&self, view: usize, piece: usize) -> Option<usize> {
        self.views[view].windows.iter().position(|w| w.piece == piece && !w.no_junction)
    }

    /// A target for window `k` of `view` placed at `point` of the view's closed region (a
    /// junction of a wall and the window, say), moved a hair toward the view's viewpoint and
    /// along the unit vector `inward` (off the wall) so that it lies inside; `None` if the
    /// window is explored.
    pub(super) fn target_near(
        &mut self,
        view: usize,
        k: usize,
        point: Point,
        inward: [f64; 2],
    ) -> Option<Target> {
        let (t, _) = self.window_target(view, k)?;
        let v = &self.views[view];
        // A junction at a window's far end lies on the window's ray, and a move along that
        // ray would graze its reflex vertex; a junction on a wall reached along the wall
        // would round onto either side of it. So the step goes off the wall as well.
        let (dx, dy) = (v.at[0] - point[0], v.at[1] - point[1]);
        let d = dx.hypot(dy);
        let floor = 4.0 * v.rounding / d;
        let c = self.clearance(view);
        let at = [1e-6, 1e-4, 1e-2]
            .into_iter()
            .map(|l: f64| l.max(floor))
            .map(|l| [point[0] + l * (dx + d * inward[0]), point[1] + l * (dy + d * inward[1])])
            .find(|&z| v.reaches(z) && (c == 0.0 || v.clear(z, c, self.relaxed())));
        Some(match at {
            Some(at) => Target { at, via: Vec::new(), anchor: None, off_gap: true, ..t },
            None => Target { off_gap: true, ..t },
        })
    }

    /// Whether a scan was already taken, or asked for, at `t`'s viewpoint; if so its part
    /// counts as handled, as after a scan for it: a scan there would see nothing new (on
    /// raw scans, a robot that stopped short of a point clear of a wall seen at a grazing
    /// angle scanned again for each piece of the wall's chain of windows).
    fn looked_from(&mut self, t: &Target) -> bool {
        let stood = self.stood_at(t.at);
        if stood {
            self.skipped.looked_from += 1;
            self.handled(t);
        }
        stood
    }

    /// Marks a target's window part as handled once a scan was taken for it, seen or not: a
    /// part no point near the window can see (a window grazing an obstacle) must not be
    /// tried again, so every scan makes progress and the exploration ends.
    fn handled(&mut self, t: &Target) {
        self.close(t.view, t.window, t.gap);
    }

    /// On raw scans, closes the part `t` stands for (its ends `p`, `q`) without a scan when
    /// it opens onto a pocket of the raster of the views (unknown cells, four-connected,
    /// enclosed by cells seen free and walls seen) smaller than [`WALLED_POCKET_SHARE`] of
    /// the sensor rule's pocket limit, or onto a wall seen right behind it: the rays from its
    /// viewpoint through it meet walls seen before [`NOTHING_BEHIND`] of unknown space.
    /// Returns whether it did ([`Skipped::walled_pocket`]). Noise leaves window parts a few
    /// centimetres in front of walls other scans saw, each of which cost a scan: the sensor
    /// rule's own pockets are holes in the union of the views' regions, which walls do not
    /// bound, and behind a shelf's face lies its unknown inside, too large for a pocket.
    fn close_if_walled(&mut self, t: &Target, [p, q]: [Point; 2]) -> bool {
        let limit = WALLED_POCKET_SHARE * self.pocket_limit_on_raw_scans();
        if limit <= 0.0 {
            return false;
        }
        let scale = self.raster_scale();
        let n = self.views.len();
        let raster = self.walls_seen.raster.get_or_insert_with(|| Raster::new(scale * CELL));
        for v in &self.views[self.walls_seen.views..n] {
            raster.scale = raster.scale.max(crate::kernel::magnitude(&v.polygon)).max(1.0);
            raster.add_view(&v.polygon, &v.pieces, v.at);
        }
        self.walls_seen.views = n;
        let rays = rays_through(t.at, &[[p, q]], scale);
        let behind = DEPTH * scale;
        let walled = raster.pocket_behind(p, q, limit).is_some()
            || raster.unknown_area_seen(t.at, &rays, scale, behind, None, Stops::Walls)
                < NOTHING_BEHIND;
        if walled {
            self.close_as_walled_pocket(t);
        }
        walled
    }

    /// The length scale of the rasters of the views: the sensor's range, or without one how
    /// far the first view reached.
    pub(super) fn raster_scale(&self) -> f64 {
        self.sensor
            .range
            .filter(|r| r.is_finite())
            .unwrap_or_else(|| self.reach_of(0))
            .max(f64::MIN_POSITIVE)
    }

    /// Closes the part `t` stands for without a scan: it opens onto a small pocket with walls
    /// seen as its bounds, or onto a wall ([`Skipped::walled_pocket`]).
    fn close_as_walled_pocket(&mut self, t: &Target) {
        self.skipped.walled_pocket += 1;
        self.handled(t);
    }

    /// On raw scans (a wall tolerance above 0), the sensor rule's pocket limit for what was
    /// seen so far, square metres; 0 with an exact sensor or without the rule's pocket term.
    pub(super) fn pocket_limit_on_raw_scans(&mut self) -> f64 {
        if !self.sensor.has_pocket_term() || self.sensor.wall_tolerance <= 0.0 {
            return 0.0;
        }
        self.update_seen();
        self.sensor.pocket_limit(self.seen.area)
    }

    /// Counts the part `gap` of window `k` of `view` as covered; returns the window.
    fn close(&mut self, view: usize, k: usize, gap: [f64; 2]) -> &mut Window {
        let w = &mut self.views[view].windows[k];
        w.covered.push(gap);
        cover::merge(&mut w.covered);
        w
    }

    /// Plans a trip from view `from`'s viewpoint along the tree of moves to the view the
    /// target belongs to, then to the target, then a scan.
    pub(super) fn go_from(&mut self, from: usize, target: Target) -> Action<Point> {
        let (waypoints, _) = self.route(from, target.base());
        self.go_route(from, waypoints, target)
    }

    /// Plans a trip from view `from`'s viewpoint to the target: through `waypoints` along
    /// the tree of moves ([`go`](Self::go)), or, on raw scans with a footprint, along the
    /// shortest way through the safe cells of a raster of the views ([`SeenRaster`]), where
    /// it leads there. The target is the same either way; only the way to it differs.
    /// Odometry drifts with every metre driven, and a stop whose alignment leaves a
    /// direction free keeps odometry's error along it: along the tree, trips on raw scans
    /// ran 1.8 times the straight distance between scans (1.6 to 2.3 by strategy and map).
    pub(super) fn go_route(
        &mut self,
        from: usize,
        waypoints: Vec<Point>,
        target: Target,
    ) -> Action<Point> {
        if self.relaxed() && !self.footprint.is_point() {
            let mut roads = std::mem::take(&mut self.roads);
            roads.sync(self, None);
            self.update_seen();
            let road = roads.route_to(self, from, &target);
            self.roads = roads;
            if let Some(pts) = road {
                return self.go_along(pts, target);
            }
        }
        self.go(waypoints, target)
    }

    /// Plans a trip: drive through `waypoints` (in order, ending at the viewpoint of the
    /// target's [`base`](Target::base)) to the target, then scan.
    pub(super) fn go(&mut self, mut waypoints: Vec<Point>, target: Target) -> Action<Point> {
        waypoints.extend_from_slice(&target.via);
        waypoints.push(target.at);
        waypoints.reverse();
        self.trip.set_route(waypoints);
        self.pending = Some(target);
        self.next_move()
    }

    /// Plans a trip from view `from`'s viewpoint to the target as [`go_from`](Self::go_from)
    /// does, with the route's corners cut: from each waypoint the robot drives straight to
    /// the farthest later one ([`SHORTCUT_LOOKAHEAD`] at most) that the straight move reaches
    /// inside the region of a view the route passes through (its viewpoint is a waypoint
    /// between them), keeping the footprint's clearance from its boundary. So every move still
    /// lies in space seen free around the robot.
    pub(super) fn go_shortcut(&mut self, from: usize, target: Target) -> Action<Point> {
        let pts = self.tree_route(from, &target);
        // The robot's position, then the waypoints, each with the view whose viewpoint it is.
        let mut all = vec![self.views[from].at];
        all.extend_from_slice(&pts);
        let owner: Vec<Option<usize>> = all.iter().map(|&p| self.view_at(p)).collect();
        let mut out = Vec::with_capacity(pts.len());
        let mut i = 0;
        while i + 1 < all.len() {
            let last = (i + 1 + SHORTCUT_LOOKAHEAD).min(all.len() - 1);
            let j = (i + 2..=last)
                .rev()
                .find(|&j| {
                    let mut ws: Vec<usize> = owner[i..=j].iter().flatten().copied().collect();
                    ws.sort_unstable();
                    ws.dedup();
                    ws.into_iter().any(|w| self.straight_in(w, all[i], all[j]))
                })
                .unwrap_or(i + 1);
            out.push(all[j]);
            i = j;
        }
        out.reverse();
        self.trip.set_route(out);
        self.pending = Some(target);
        self.next_move()
    }

    /// Drives through `waypoints` (ending at the target's viewpoint), then scans: a route
    /// planned elsewhere (through safe cells of a raster of the views). The target keeps its
    /// own `via`, so the tree of moves stays as if the robot had come from its base.
    pub(super) fn go_along(&mut self, mut waypoints: Vec<Point>, target: Target) -> Action<Point> {
        waypoints.reverse();
        self.trip.set_route(waypoints);
        self.pending = Some(target);
        self.next_move()
    }

    /// The waypoints of the tree of moves from view `from`'s viewpoint to `target`: back and
    /// down the tree to the view its trip starts from, then through its `via` to it.
    pub(super) fn tree_route(&self, from: usize, target: &Target) -> Vec<Point> {
        let (mut pts, _) = self.route(from, target.base());
        pts.extend_from_slice(&target.via);
        pts.push(target.at);
        pts
    }

    /// Whether the straight move from `a` to `b` keeps the clearance `c` from the boundary of
    /// the union of the views' regions (seen free space, walls and frontiers alike), inside
    /// the part of it that holds `a`. The union must be up to date
    /// ([`update_seen`](Self::update_seen)).
    pub(super) fn clear_in_seen(&self, a: Point, b: Point, c: f64) -> bool {
        self.seen
            .union
            .shapes
            .iter()
            .any(|shape| holds(shape, a) && Approach::with_holes(shape, c).clear(a, b))
    }

    /// Whether the straight move from `a` to `b` lies inside the region of some view, keeping
    /// the footprint's clearance from its boundary ([`Known::straight_in`]), as the moves of
    /// the tree of moves do.
    pub(super) fn straight_in_a_view(&self, a: Point, b: Point) -> bool {
        (0..self.views.len()).any(|w| self.straight_in(w, a, b))
    }

    /// Whether the straight move from `a` to `b` lies inside view `w`'s region, `a` inside it
    /// or its viewpoint, keeping the footprint's clearance from its boundary.
    fn straight_in(&self, w: usize, a: Point, b: Point) -> bool {
        let v = &self.views[w];
        let c = self.clearance(w);
        v.in_bounds(a)
            && v.in_bounds(b)
            && (c == 0.0 || keeps_clear(&v.polygon, a, b, c))
            && (v.at == a || self.inside(w, a))
            && reaches(&v.polygon, a, b)
    }

    /// The next action of the planned trip: the next waypoint, or the scan at its end.
    pub(super) fn next_move(&mut self) -> Action<Point> {
        self.trip.next_move()
    }

    /// [`PolygonStrategy::ahead`](super::PolygonStrategy::ahead): the trip's waypoints
    /// after the one issued last.
    pub(super) fn ahead(&self) -> Vec<Point> {
        self.trip.ahead()
    }

    /// A move failed: the target the trip was for is dropped (its window part counted in
    /// [`Skipped::move_failed`]) and the robot drives back to the latest viewpoint the trip
    /// passed ([`Trip::failed_back_to`]), to plan again from there.
    ///
    /// When moves fail [`SAME_WAYPOINT_FAILURES`] times in a row near one waypoint
    /// ([`SAME_WAYPOINT`] clearances) with no scan between, the robot's belief is what is wrong
    /// there (odometry's drift over a long trip put the waypoint inside a shelf in truth):
    /// the target of the last is kept, and the robot scans where it stands, which places it
    /// again. That view joins the tree of views, reached from the latest viewpoint the trip
    /// passed through the waypoints driven after it. Every such scan follows failures that
    /// dropped targets, so the exploration still ends. It is not taken again before a scan
    /// for a target: when the scan that placed the robot did not cure the failures (ICP
    /// settled on the same belief), more scans there would not either, and the targets
    /// failing on are dropped (on the warehouse, `range_limited` seed 3, five scans in a row
    /// at one spot, each after three moves to a waypoint 13 m off that a 0.43 m pose error
    /// put inside a shelf). Without it, on the warehouse
    /// (`nearest_frontier` on raw scans, seed 6) one waypoint failed for 45 targets in a row,
    /// each dropped, and the run ended at 73.7% of the area (99.7% with it). After two
    /// failures rather than three, it scanned in 20 of 150 raw-scan runs against 13, and cost
    /// 4.6% more mission time over them against 2.9%.
    fn move_failed(&mut self) -> Action<Point> {
        let issued = self.trip.issued_ahead();
        let near = if self.here < self.views.len() {
            self.clearance(self.here) * SAME_WAYPOINT
        } else {
            0.0
        };
        let times = match (issued, self.failed_at) {
            (Some(w), Some((f, n))) if (w[0] - f[0]).hypot(w[1] - f[1]) <= near => n + 1,
            _ => 1,
        };
        self.failed_at = issued.map(|w| (w, times));
        if times >= SAME_WAYPOINT_FAILURES
            && !self.placed_again
            && let Some(t) = self.pending.take()
        {
            return self.scan_to_place_again(t);
        }
        if let Some(t) = self.pending.take() {
            self.handled(&t);
            self.skipped.move_failed += 1;
            let (view, window, gap) = (t.view, t.window, t.gap);
            self.dropped.push(Deferred { view, window, gap, near: Vec::new() });
        }
        let views = &self.views;
        match self.trip.failed_back_to(|p| views.iter().any(|v| v.at == p)) {
            Action::Done => self.stuck(),
            a => a,
        }
    }

    /// At what would be the end of the exploration, with window parts still dropped by failed
    /// moves ([`Known::move_failed`]) that no view added since could retry
    /// ([`Known::retry_left_parts`]): a scan where the robot stands, to place it again, unless
    /// one was taken so with no scan for a target since, or the robot stands where it last
    /// scanned. A trip that fails on odometry's drift (a long drive through
    /// earlier viewpoints with no scan between puts a waypoint inside a shelf in truth) fails
    /// again from the same belief, and the parts would be left for good: on the warehouse,
    /// `range_limited` seed 24 on raw scans ended at 88.5% of the area after 100 m of driving
    /// back and forth with the robot 0.5 m from where it believed. The scan adds a view, so
    /// the parts are tried again; another such scan needs a scan for a part before it, so the
    /// exploration still ends. Returns the scan, if one is asked for.
    pub(super) fn place_again_for_dropped(&mut self) -> Option<Action<Point>> {
        if self.dropped.is_empty() || self.placed_again_at_end || self.here >= self.views.len() {
            return None;
        }
        let at = self.trip.driven().last().copied().or(self.trip.start())?;
        // Not where the latest scan was taken: that scan placed the robot already.
        if self.views.last().is_some_and(|v| v.at == at) {
            return None;
        }
        self.skipped.placed_again_scans += 1;
        self.placed_again_at_end = true;
        Some(self.scan_to_place_here(at))
    }

    /// [`Known::scan_to_place_again`] at `at`, where the robot stands, for no target: the
    /// scan's target part was dropped already, or there is none, so its window and gap are
    /// not used ([`Known::add`] reads only the anchor and the waypoints of a scan to place
    /// again).
    fn scan_to_place_here(&mut self, at: Point) -> Action<Point> {
        let here = self.here;
        self.scan_to_place_again(Target {
            at,
            via: Vec::new(),
            view: here,
            window: 0,
            gap: [0.0, 0.0],
            anchor: None,
            off_gap: false,
            relocate: true,
        })
    }

    /// A scan where the robot stands, to place it again: the view it gives hangs from the
    /// latest viewpoint the trip passed, through the waypoints reached after it. `t` is the
    /// target the scan is for (its part stays open).
    fn scan_to_place_again(&mut self, mut t: Target) -> Action<Point> {
        let driven = self.trip.driven();
        let (from, view) = (driven.iter().enumerate().rev())
            .find_map(|(i, &p)| self.view_at(p).map(|v| (i + 1, v)))
            .unwrap_or((0, self.here));
        t.via = driven[from..].to_vec();
        t.anchor = Some(view);
        t.relocate = true;
        self.pending = Some(t);
        self.trip.clear();
        Action::Scan
    }

    /// The robot can drive neither on nor back ([`Trip::failed`](super::trip::Trip::failed)
    /// gave up): it scans where it stands ([`Known::scan_to_place_again`]), and plans on from
    /// the view that gives. Stuck again within the clearance of a place it scanned at for
    /// being stuck, or where its last scan was taken to place it again, the strategy gives
    /// up, and says so ([`Skipped::gave_up`]).
    fn stuck(&mut self) -> Action<Point> {
        let at = self.trip.driven().last().copied().or(self.trip.start());
        let Some(at) = at.filter(|_| self.here < self.views.len()) else {
            self.skipped.gave_up = true;
            return Action::Done;
        };
        let near = self.clearance(self.here).max(1e-3);
        let d = |p: &Point| (p[0] - at[0]).hypot(p[1] - at[1]);
        // A scan there to place the robot again did not help either.
        let placed_here = self.placed_again && self.views.last().is_some_and(|v| d(&v.at) <= near);
        if placed_here || self.stuck_at.iter().any(|p| d(p) <= near) {
            self.skipped.gave_up = true;
            return Action::Done;
        }
        self.stuck_at.push(at);
        self.skipped.stuck_scans += 1;
        self.scan_to_place_here(at)
    }

    /// The view whose viewpoint is `p`, the earliest if several are.
    fn view_at(&self, p: Point) -> Option<usize> {
        self.views.iter().position(|v| v.at == p)
    }

    /// The chain of views from `v` up to the root.
    fn ancestors(&self, mut v: usize) -> Vec<usize> {
        let mut out = vec![v];
        while let Some(p) = self.views[v].parent {
            out.push(p);
            v = p;
        }
        out
    }

    /// Waypoints from view `a`'s point to view `b`'s point along the tree of moves (every
    /// segment known free), with the length of that route.
    pub(super) fn route(&self, a: usize, b: usize) -> (Vec<Point>, f64) {
        let (up, down) = (self.ancestors(a), self.ancestors(b));
        let common = *up.iter().find(|x| down.contains(x)).unwrap_or(&a);
        let mut pts: Vec<Point> = Vec::new();
        for &x in up.iter().take_while(|&&x| x != common) {
            self.retreat(x, &mut pts);
        }
        let tail: Vec<usize> = down.iter().take_while(|&&x| x != common).copied().collect();
        for &x in tail.iter().rev() {
            pts.extend_from_slice(&self.views[x].via);
            pts.push(self.views[x].at);
        }
        let len = path_length(self.views[a].at, &pts);
        (pts, len)
    }

    /// The moves and length of the route from view `cur`'s viewpoint to that of target `t`'s
    /// [`base`](Target::base), given the `route` from `cur` to the target's own view.
    pub(super) fn trip_to(
        &self,
        cur: usize,
        t: &Target,
        route: &(Vec<Point>, f64),
    ) -> (usize, f64) {
        if t.base() == t.view {
            (route.0.len(), route.1)
        } else {
            let (pts, len) = self.route(cur, t.base());
            (pts.len(), len)
        }
    }

    /// Appends the waypoints of the move back from view `child`'s viewpoint to its parent's
    /// (the way the robot came, reversed).
    fn retreat(&self, child: usize, route: &mut Vec<Point>) {
        let v = &self.views[child];
        route.extend(v.via.iter().rev());
        if let Some(p) = v.parent {
            route.push(self.views[p].at);
        }
    }

    /// The length of the approach from the viewpoint of a target's [`base`](Target::base)
    /// to the target.
    pub(super) fn approach_length(&self, t: &Target) -> f64 {
        let mut pts = t.via.clone();
        pts.push(t.at);
        path_length(self.views[t.base()].at, &pts)
    }
}

/// The covered intervals `covered` without the interval `gap`.
fn uncover(covered: &Intervals, gap: [f64; 2]) -> Intervals {
    let mut out = Vec::with_capacity(covered.len() + 1);
    for &[a, b] in covered {
        if b <= gap[0] || a >= gap[1] {
            out.push([a, b]);
            continue;
        }
        if a < gap[0] {
            out.push([a, gap[0]]);
        }
        if b > gap[1] {
            out.push([gap[1], b]);
        }
    }
    out
}

/// The length of the window segment `p q` seen from `at` if the sensor's rule finds it too
/// short to be worth a trip ([`Sensor::min_window_at`] its near end's distance), `None` if it
/// is worth one.
fn below_rule(sensor: &Sensor, at: Point, p: Point, q: Point) -> Option<f64> {
    if sensor.excludes_nothing() {
        return None;
    }
    let d = |x: Point| (x[0] - at[0]).hypot(x[1] - at[1]);
    let len = (q[0] - p[0]).hypot(q[1] - p[1]);
    (len < sensor.min_window_at(d(p).min(d(q)))).then_some(len)
}

/// Whether window piece `i` of a raw scan's region seen from `at` is a gap in one wall seen at
/// a slant ([`Skipped::wall_gap`]): on either side of it a return that lies on the line
/// through the gap (the far end of a wall of at least [`WALL_GAP_SIDE`], or of a window
/// between two returns: a wall seen from far at a slant comes back as single returns a
/// metre or more apart), the four points within half of [`WALL_GAP_LINE`] × `tol` of the
/// line fitted to them (a step of [`WALL_GAP_LINE`] × `tol` between the two sides leaves
/// them about that far off), each wall running along that line (its ends within `tol` of
/// each other across it, or [`WALL_GAP_TILT`] of its length), and the sight line to the
/// gap's middle meets that line at no more than 30°. On one side (not both) the beam next
/// to the gap may instead have met nothing within the range: the line is then fitted to the
/// other three returns, and that beam must end short of it (or within `tol` beyond it): the
/// wall, if it runs on, lies beyond the range there, where a beam that crossed the line went
/// through an opening.
///
/// A wall seen at a slant from far away comes back as returns a metre or more apart, and
/// reading the scan leaves the gaps longer than the shortest window worth a trip as windows
/// (a door no beam went through may hide there); the ends of the runs, projected along their
/// beams onto lines fitted at three σ that run nearly parallel to the beams, move along the
/// wall by as much again. A door the beams entered does not look like this: they return
/// from the room behind, off the wall's line, so the windows beside the door end off that
/// line. Only a door no beam entered can hide in such a gap, as in a gap the reading bridges;
/// another scan that sees the wall there closes the gap the same way
/// ([`Sensor::cover_band`]). On the warehouse, the scans at the end of raw runs that went to
/// such gaps, with no other scan near, saw nothing new. A chain of such gaps with single
/// returns between them is read link by link, each link's neighbours being the windows
/// beside it; a later scan that sees through a gap read so still opens what lies behind.
/// Such a chain often ends at the range: seen from beside a wall, the returns along it fall
/// metres apart, and the last gap before the beams that met nothing was left open. On the
/// warehouse (`nearest_frontier`, seeds 1 to 16), 91 of the 127 scans that saw under 0.5 m²
/// that no earlier scan saw went to window parts lying within 0.15 m of a wall; 16 of them
/// were such last gaps (measured on the ground truth).
pub(super) fn gap_in_a_wall(pieces: &[BoundaryPiece], i: usize, at: Point, tol: f64) -> bool {
    let n = pieces.len();
    if n < 5 {
        return false;
    }
    let BoundaryPiece::Window { from: p, to: q, .. } = pieces[i] else { return false };
    let len = |u: Point, v: Point| (v[0] - u[0]).hypot(v[1] - u[1]);
    // What lies beyond the gap's end `end` along piece `j`, the next piece beyond it being
    // `beyond`: a return (a wall's far end, or a window's far end when that end is a
    // return), or the point at the range where a window to no return ends.
    let support = |j: usize, beyond: usize, end: Point, before: bool| -> Option<Beyond> {
        let (a, b) = pieces[j].ends();
        let (near, far) = if before { (b, a) } else { (a, b) };
        if near != end {
            return None;
        }
        match pieces[j] {
            BoundaryPiece::Wall { .. } => {
                (len(a, b) >= WALL_GAP_SIDE).then_some(Beyond::Return(far))
            }
            BoundaryPiece::Window { .. } => match pieces[beyond] {
                BoundaryPiece::Wall { .. } | BoundaryPiece::Window { .. } => {
                    Some(Beyond::Return(far))
                }
                BoundaryPiece::Frontier { .. } => Some(Beyond::Range(far)),
                _ => None,
            },
            _ => None,
        }
    };
    let (before, after) = (
        support((i + n - 1) % n, (i + n - 2) % n, p, true),
        support((i + 1) % n, (i + 2) % n, q, false),
    );
    // The returns the line is fitted to, and a beam beyond one end that met nothing.
    let (line, open): (Vec<Point>, Option<Point>) = match (before, after) {
        (Some(Beyond::Return(a)), Some(Beyond::Return(b))) => (vec![a, p, q, b], None),
        (Some(Beyond::Range(f)), Some(Beyond::Return(b))) => (vec![p, q, b], Some(f)),
        (Some(Beyond::Return(a)), Some(Beyond::Range(f))) => (vec![a, p, q], Some(f)),
        _ => return false,
    };
    let (c, d) = fit_line(&line);
    let off = |x: Point| (x[0] - c[0]) * d[1] - (x[1] - c[1]) * d[0];
    // A wall beside the gap must run along the line too, not only end near it: four points
    // in two tight pairs (short walls far apart, such as a box's face and the wall behind
    // it across an occlusion) always lie near the line through the pairs.
    let along = |j: usize, near: Point, far: Point| {
        !matches!(pieces[j], BoundaryPiece::Wall { .. })
            || (off(far) - off(near)).abs() <= tol.max(WALL_GAP_TILT * len(near, far))
    };
    // A beam beyond one end that met nothing within the range must not have crossed the
    // line: the wall, if it runs on, lies beyond the range along that beam.
    let short_of_line = |f: Point| off(f) * off(at) >= 0.0 || off(f).abs() <= tol;
    let middle = [f64::midpoint(p[0], q[0]), f64::midpoint(p[1], q[1])];
    line.iter().all(|&x| off(x).abs() <= 0.5 * WALL_GAP_LINE * tol)
        && along((i + n - 1) % n, p, line[0])
        && along((i + 1) % n, q, line[line.len() - 1])
        && open.is_none_or(short_of_line)
        && off(at).abs() <= WALL_GAP_SLANT * len(at, middle)
}

/// What a raw scan saw beyond an end of a gap ([`gap_in_a_wall`]).
#[derive(Debug, Clone, Copy)]
enum Beyond {
    /// A return.
    Return(Point),
    /// Nothing: the beam ran to the range and ended at this point.
    Range(Point),
}

/// Whether window piece `i` of a raw scan's region seen from `at` is a gap between two walls
/// on one line seen at a slant, as `explore_lite`'s raster reads it: the pieces on either
/// side of it are walls (lines fitted to returns) of at least [`WALL_GAP_SIDE`], each wall's
/// ends lie within [`WALL_GAP_LINE`] × `tol` of the other's line, and the sight line to the
/// gap's middle meets that wall at no more than 30°. It reads some gaps [`gap_in_a_wall`]
/// does not (a wall's far end off the fitted line by up to twice the tolerance), and
/// `explore_lite` assumes either reading to be wall until a later scan holds or sees through
/// the gap's cells. (When that raster kept such a wall for good, reading gaps as the window
/// strategies do shut the doors along the built-in office's corridor, seen from its end, and
/// every run on it, seeds 1 to 40, saw less than 99%, the least 48.8%.)
pub(super) fn gap_between_two_walls(
    pieces: &[BoundaryPiece],
    i: usize,
    at: Point,
    tol: f64,
) -> bool {
    let n = pieces.len();
    let (
        BoundaryPiece::Wall { from: a, to: p },
        BoundaryPiece::Window { from, to, .. },
        BoundaryPiece::Wall { from: q, to: b },
    ) = (pieces[(i + n - 1) % n], pieces[i], pieces[(i + 1) % n])
    else {
        return false;
    };
    let len = |u: Point, v: Point| (v[0] - u[0]).hypot(v[1] - u[1]);
    if from != p || to != q || len(a, p) < WALL_GAP_SIDE || len(q, b) < WALL_GAP_SIDE {
        return false;
    }
    // The distance of `x` from the line through `u` and `v` (not the same point: the walls
    // are longer than WALL_GAP_SIDE).
    let off = |u: Point, v: Point, x: Point| {
        ((v[0] - u[0]) * (x[1] - u[1]) - (v[1] - u[1]) * (x[0] - u[0])).abs() / len(u, v)
    };
    let tol = WALL_GAP_LINE * tol;
    let on_line = [off(a, p, q), off(a, p, b), off(q, b, a), off(q, b, p)];
    let middle = [f64::midpoint(p[0], q[0]), f64::midpoint(p[1], q[1])];
    on_line.iter().all(|&d| d <= tol)
        && len(a, b) > 0.0
        && off(a, b, at) <= WALL_GAP_SLANT * len(at, middle)
}

/// A point on a window: the view, the window's index among its windows, and the parameter
/// along it (0 at `from`, 1 at `to`).
type WindowAt = (usize, usize, f64);

/// On raw scans, the share of the sensor rule's pocket limit below which a window part that
/// opens onto a pocket of the raster of the views is closed without a visit
/// ([`Known::close_if_walled`]). Walls seen bound such a pocket, as they do not bound the
/// rule's own pockets (holes in the union of the views' regions): the sliver between a window
/// and the wall another scan saw a few centimetres behind it, which cost a scan each. At the
/// whole limit the space behind a desk (1–2 m²) was closed too: on the built-in office, seed
/// 21, coverage fell from 99.62% to 98.62%. Not with an exact sensor, which leaves no such
/// slivers: there the pockets it closed were real spaces (on willow-full at 10 cm, 20 parts,
/// 302 scans against 324 and 98.81% seen against 98.90%).
const WALLED_POCKET_SHARE: f64 = 0.25;

/// Less unknown space than this, square metres, seen through a window part from its own
/// viewpoint before walls seen stop the rays, is nothing: the part opens onto a wall
/// ([`Known::close_if_walled`]). About two cells of the raster at 5 m.
const NOTHING_BEHIND: f64 = 0.01;

/// How far around the viewpoint and the part [`Known::union_point`] searches the union of
/// the views' regions, in multiples of the clearance.
const UNION_MARGIN: f64 = 10.0;

/// How many waypoints ahead [`Known::go_shortcut`] looks for a straight move.
const SHORTCUT_LOOKAHEAD: usize = 24;

/// Two failed moves whose waypoints lie within this many clearances of each other failed at
/// the same place ([`Known::move_failed`]).
const SAME_WAYPOINT: f64 = 4.0;

/// How many moves in a row must fail at the same place, with no scan between, before the
/// robot scans there to place itself again ([`Known::move_failed`]).
const SAME_WAYPOINT_FAILURES: u32 = 3;

/// A convex vertex of a region whose angle is wider than 150° (the sine of half of it above
/// this) is a kink of a wall, not a corner of a room: a viewpoint stepped in from it stands
/// beside the wall, from where the wall is seen at a grazing angle.
const FLAT_CORNER: f64 = 0.966;

/// The least angle (radians) at which a sight line from a corner must cross a window part
/// for the corner to be worth a scan that looks through it ([`Known::clear_point`]'s last
/// resort): 15°. A corner on the window's own line sees nothing new. 5° and 10° were tried on willow-full (0.05 m and
/// 0.1 m cells): coverage moved both ways by up to 2% from map to map, with more scans.
const MIN_LOOK_ANGLE: f64 = std::f64::consts::PI / 12.0;

/// Where along a window part a look from a corner may aim (fractions of the part): the
/// middle, quarters, eighths and the sixteenths at its ends. Near the part's ends, a door
/// seen at a slant is seen through from in front of it.
const LOOK_SAMPLES: [f64; 9] = [0.5, 0.25, 0.75, 0.125, 0.375, 0.625, 0.875, 0.0625, 0.9375];

/// Points on the near side of the window part `p q` (its view's region lies left of it),
/// beside its middle at 1.5, 2.5 and 4 times the clearance `c`: where a later view that holds
/// one may plan a viewpoint for it.
fn near_side(p: Point, q: Point, c: f64) -> Vec<Point> {
    let m = [f64::midpoint(p[0], q[0]), f64::midpoint(p[1], q[1])];
    let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
    let len = dx.hypot(dy);
    if len == 0.0 {
        return vec![m];
    }
    [1.5, 2.5, 4.0]
        .into_iter()
        .map(|f| [m[0] - f * c * dy / len, m[1] + f * c * dx / len])
        .collect()
}

/// The points of the part `gap` (parameters along it) of the window `from`–`to`.
fn part_points(from: Point, to: Point, gap: [f64; 2]) -> [Point; 2] {
    let (dx, dy) = (to[0] - from[0], to[1] - from[1]);
    [[from[0] + gap[0] * dx, from[1] + gap[0] * dy], [from[0] + gap[1] * dx, from[1] + gap[1] * dy]]
}

/// Whether `z` sees the point `m` on the boundary of the region `shape` (outer ring and
/// holes) across it: the segment from `z` to a hair short of `m` crosses no edge of any ring.
fn sees_across(shape: &[Vec<Point>], z: Point, m: Point) -> bool {
    let m = [m[0] + 1e-6 * (z[0] - m[0]), m[1] + 1e-6 * (z[1] - m[1])];
    shape.iter().all(|r| {
        let n = r.len();
        (0..n).all(|i| !segments_intersect(z, m, r[i], r[(i + 1) % n]))
    })
}

/// The length of the polyline from `from` through `pts`.
pub(super) fn path_length(from: Point, pts: &[Point]) -> f64 {
    let mut len = 0.0;
    let mut prev = from;
    for p in pts {
        len += (p[0] - prev[0]).hypot(p[1] - prev[1]);
        prev = *p;
    }
    len
}

/// What every polygon strategy does with feedback: scan at the start, drive the planned trip,
/// and after each scan record it in `known(s)` and ask `plan(s, view)` for the next trip. A
/// failed move drops the trip's target and drives back to where the trip started, to plan
/// again from there ([`trip`](super::trip)).
pub(super) fn act<S>(
    s: &mut S,
    feedback: &PolygonFeedback,
    known: fn(&mut S) -> &mut Known,
    plan: fn(&mut S, usize) -> Action<Point>,
) -> Action<Point> {
    let replan = |s: &mut S, v: usize| {
        let mut a = plan(s, v);
        while matches!(a, Action::Done)
            && (known(s).reopen_wide_openings() || known(s).retry_left_parts())
        {
            a = plan(s, v);
        }
        if matches!(a, Action::Done)
            && let Some(scan) = known(s).place_again_for_dropped()
        {
            return scan;
        }
        a
    };
    match feedback {
        PolygonFeedback::Start { .. } => Action::Scan,
        PolygonFeedback::Arrived => match known(s).trip.arrived() {
            Next::Act(a) => a,
            Next::Replan => {
                // Back where the trip started, or at the viewpoint a way back ended at.
                let k = known(s);
                if let Some(p) = k.trip.start()
                    && let Some(v) = k.view_at(p)
                {
                    k.here = v;
                }
                let v = k.here;
                replan(s, v)
            }
        },
        PolygonFeedback::Scanned(obs) => {
            let k = known(s);
            let v = k.add(obs);
            k.here = v;
            k.trip.begin(obs.at);
            replan(s, v)
        }
        PolygonFeedback::MoveFailed { .. } => known(s).move_failed(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::polygon::{PLACEMENT_CAP, PLACEMENT_SIGMAS};

    /// A corridor 1.2 m wide and 20 m long; in its right wall (0.1 m thick) a door of width
    /// `door` at 10 ≤ y ≤ 10 + door into a 4 × 5 m room. A 0.4 m robot, windows under 0.4 m
    /// not worth a trip; scans in the corridor at (0.6, 4) and (0.6, 16).
    fn corridor_views(door: f64) -> Known {
        corridor_views_and_walls(door).0
    }

    /// [`corridor_views`], with the corridor's and room's boundary ring.
    fn corridor_views_and_walls(door: f64) -> (Known, Vec<Point>) {
        use crate::algorithm::visibility::Visibility;
        use crate::geometry::Domain;
        let ring = vec![
            [0.0, 0.0],
            [1.2, 0.0],
            [1.2, 10.0],
            [1.3, 10.0],
            [1.3, 8.0],
            [5.3, 8.0],
            [5.3, 13.0],
            [1.3, 13.0],
            [1.3, 10.0 + door],
            [1.2, 10.0 + door],
            [1.2, 20.0],
            [0.0, 20.0],
        ];
        let vis = Visibility::new(Domain::new(ring.clone(), vec![]).unwrap()).unwrap();
        let scan = |at: Point| PolygonObservation::new(at, vis.query(at).unwrap());
        let setup = RobotSetup {
            footprint: Footprint::disc(0.2).unwrap(),
            sensor: Sensor { min_window: 0.4, ..Sensor::default() },
            ..RobotSetup::default()
        };
        let mut k = Known::for_robot(&setup);
        k.add(&scan([0.6, 4.0]));
        k.add(&scan([0.6, 16.0]));
        (k, ring)
    }

    /// A 10 m square room with a 1 m pillar at its middle, scanned from (1, 1) and (9, 1):
    /// neither sees the pillar's top face, and their shadows behind it meet in a triangle.
    /// The sensor rule has the pocket term with a share of 1 (no limit from the share) and
    /// the given cap.
    fn pillar_views(cap: f64) -> Known {
        let sensor = Sensor { min_pocket: 1.0, pocket_cap: cap, ..Sensor::default() };
        let room = vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]];
        let pillar = vec![[4.5, 4.5], [4.5, 5.5], [5.5, 5.5], [5.5, 4.5]];
        views_of(room, vec![pillar], &[[1.0, 1.0], [9.0, 1.0]], sensor)
    }

    /// What a point robot with `sensor` knows after scanning the room `ring` with `holes`
    /// from each of `ats` in turn.
    fn views_of(ring: Vec<Point>, holes: Vec<Vec<Point>>, ats: &[Point], sensor: Sensor) -> Known {
        use crate::algorithm::visibility::Visibility;
        use crate::geometry::Domain;
        let vis = Visibility::new(Domain::new(ring, holes).unwrap()).unwrap();
        let mut k = Known::for_robot(&RobotSetup { sensor, ..RobotSetup::default() });
        for &at in ats {
            k.add(&PolygonObservation::new(at, vis.query(at).unwrap()));
        }
        k
    }

    /// A robot of radius 0.2 m that has scanned the room `ring` from `at`.
    fn room_seen_from(ring: Vec<Point>, at: Point) -> Known {
        use crate::algorithm::visibility::Visibility;
        use crate::geometry::Domain;
        let vis = Visibility::new(Domain::new(ring, vec![]).unwrap()).unwrap();
        let setup =
            RobotSetup { footprint: Footprint::disc(0.2).unwrap(), ..RobotSetup::default() };
        let mut k = Known::for_robot(&setup);
        k.add(&PolygonObservation::new(at, vis.query(at).unwrap()));
        k
    }

    /// A region seen from `at` whose boundary runs through `verts` counter-clockwise, each
    /// vertex starting a wall (`true`) or a window (`false`) to the next.
    fn raw_region(at: Point, verts: &[(Point, bool)]) -> PolygonObservation {
        use crate::algorithm::visibility::VisibilityRegion;
        let n = verts.len();
        let boundary = (0..n)
            .map(|i| {
                let ((from, wall), (to, _)) = (verts[i], verts[(i + 1) % n]);
                let d = |p: Point| (p[0] - at[0]).hypot(p[1] - at[1]);
                let (reflex, far) = if d(from) <= d(to) { (from, to) } else { (to, from) };
                if wall {
                    BoundaryPiece::Wall { from, to }
                } else {
                    BoundaryPiece::Window { from, to, reflex, far }
                }
            })
            .collect();
        let polygon = verts.iter().map(|v| v.0).collect();
        PolygonObservation::new(at, VisibilityRegion { viewpoint: at, polygon, boundary })
    }

    /// A hall 18 × 4 m with a box at 5 ≤ x ≤ 6, 2.6 ≤ y ≤ 3.6, seen as from raw scans (wall
    /// tolerance 0.07 m, windows under 0.4 m not worth a trip):
    /// - from (1, 2): the bottom wall whole to x = 9, then as gaps between returns on its line
    ///   (a grazing view) with walls of 0.1 m between them, too short to set a line, to
    ///   x = 15, and whole to the corner; the box casts two occlusions;
    /// - from (13, 0.5), placed `offset` metres off in y (a pose error): the bottom wall whole
    ///   from x = 8.5 to 17.5;
    /// - from below the box's far occlusion: a wall beside it, 0.15 m off its line.
    fn grazing_views(offset: f64) -> Known {
        grazing_views_placed(offset, 0.0)
    }

    /// Nothing known yet, for a 0.2 m robot on raw scans (wall tolerance 0.07 m, windows
    /// under 0.4 m not worth a trip).
    fn raw_known() -> Known {
        let sensor = Sensor { min_window: 0.4, wall_tolerance: 0.07, ..Sensor::default() };
        Known::for_robot(&RobotSetup {
            footprint: Footprint::disc(0.2).unwrap(),
            sensor,
            ..RobotSetup::default()
        })
    }

    /// [`grazing_views`] with the second and third scans placed with spread `placement`.
    fn grazing_views_placed(offset: f64, placement: f64) -> Known {
        let mut k = raw_known();
        let (wall, gap) = (true, false);
        k.add(&raw_region(
            [1.0, 2.0],
            &[
                ([0.0, 0.0], wall),
                ([9.0, 0.0], gap),
                ([10.0, 0.0], wall),
                ([10.1, 0.0], gap),
                ([11.4, 0.0], wall),
                ([11.5, 0.0], gap),
                ([13.0, 0.0], wall),
                ([13.1, 0.0], gap),
                ([15.0, 0.0], wall),
                ([18.0, 0.0], wall),
                ([18.0, 4.0], wall),
                ([17.67, 4.0], gap),
                ([6.0, 2.6], wall),
                ([5.0, 2.6], wall),
                ([5.0, 3.6], gap),
                ([6.0, 4.0], wall),
                ([0.0, 4.0], wall),
            ],
        ));
        let y = offset;
        let placed = |mut o: PolygonObservation| {
            o.placement = placement;
            o
        };
        k.add(&placed(raw_region(
            [13.0, 0.5 + y],
            &[([8.5, y], wall), ([17.5, y], gap), ([17.5, 2.0], gap), ([8.5, 2.0], gap)],
        )));
        // Along the occlusion from (17.67, 4) to (6, 2.6), `offset` to its near side.
        let (a, b) = ([17.67, 4.0], [6.0, 2.6]);
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len = f64::hypot(dx, dy);
        let nrm = [-dy / len, dx / len];
        let at = |t: f64, off: f64| [a[0] + t * dx + off * nrm[0], a[1] + t * dy + off * nrm[1]];
        k.add(&placed(raw_region(
            at(0.5, 1.0),
            &[
                (at(0.8, offset), wall),
                (at(0.02, offset), gap),
                (at(0.02, 1.5), gap),
                (at(0.8, 1.5), gap),
            ],
        )));
        k
    }

    #[test]
    fn window_parts_are_closed_by_walls_seen_within_two_pose_errors() {
        // The band, from the definition: range noise (0.07 m) and two poses' errors (0.1 m
        // each).
        let k = grazing_views(0.15);
        assert!((k.sensor.cover_band() - 0.27).abs() < 1e-12);
        // The second scan sees the hall's bottom wall whole from x = 8.5 to 17.5, and the
        // third a wall beside the box's occlusion from 2% to 80% of the way from (17.67, 4) to
        // (6, 2.6), each placed 0.15 m off: beyond the noise, within the band. The first
        // scan's gaps between returns on the bottom wall (both ends on y = 0) there are
        // closed; placed 0.3 m off, they stay open, as they do with an exact sensor.
        assert_eq!(bottom_gaps(&k).len(), 4);
        assert_eq!(bottom_gaps_open(&mut k.clone()), vec![false; 4]);
        assert_eq!(bottom_gaps_open(&mut grazing_views(0.3)), vec![true; 4]);
        // The occlusion is closed where the wall runs beside it; what is left before that (2%
        // of its 11.75 m) is below the rule's 0.4 m, and what is left beyond stays open.
        let occlusion_of = |k: &Known| {
            (0..k.views[0].windows.len()).find(|&i| k.views[0].windows[i].from == [17.67, 4.0])
        };
        let mut k = k;
        let occlusion = occlusion_of(&k).unwrap();
        let (t, _) = k.window_target(0, occlusion).unwrap();
        let near = |a: f64, b: f64| (a - b).abs() < 1e-9;
        assert!(near(t.gap[0], 0.8) && near(t.gap[1], 1.0), "{:?}", t.gap);
        let covered = &k.views[0].windows[occlusion].covered;
        assert!(covered.len() == 1 && near(covered[0][0], 0.0) && near(covered[0][1], 0.8));
        // 0.3 m off, nothing of it is closed.
        let mut far = grazing_views(0.3);
        let occlusion = occlusion_of(&far).unwrap();
        let (t, _) = far.window_target(0, occlusion).unwrap();
        assert_eq!(t.gap, [0.0, 1.0]);
    }

    /// The first scan's gaps between returns on the hall's bottom wall (both ends on y = 0)
    /// where the second scan saw it, from x = 8.5 to 17.5: their window indices.
    fn bottom_gaps(k: &Known) -> Vec<usize> {
        (0..k.views[0].windows.len())
            .filter(|&i| {
                let w = &k.views[0].windows[i];
                w.from[1] == 0.0
                    && w.to[1] == 0.0
                    && w.from[0].min(w.to[0]) >= 8.5
                    && w.from[0].max(w.to[0]) <= 17.5
            })
            .collect()
    }

    /// Whether each of [`bottom_gaps`] is still open.
    fn bottom_gaps_open(k: &mut Known) -> Vec<bool> {
        bottom_gaps(k).into_iter().map(|i| k.window_target(0, i).is_some()).collect()
    }

    /// A hall 18 × 4 m seen as from raw scans (wall tolerance 0.07 m, windows under 0.4 m not
    /// worth a trip) from `at`: its bottom wall read as a wall to x = 9, a gap to x = 10,
    /// and a wall from `(10, far)` to `(10 + side, far)` and on to `(18, far)`. Whether the
    /// gap is open after the scan, and how many windows were read as gaps in a wall.
    fn wall_gap_open(at: Point, far: f64, side: f64) -> (bool, usize) {
        let mut k = raw_known();
        let (wall, gap) = (true, false);
        k.add(&raw_region(
            at,
            &[
                ([0.0, 0.0], wall),
                ([9.0, 0.0], gap),
                ([10.0, far], wall),
                ([10.0 + side, far], wall),
                ([18.0, far], wall),
                ([18.0, 4.0], wall),
                ([0.0, 4.0], wall),
            ],
        ));
        let w = (0..k.views[0].windows.len()).find(|&i| k.views[0].windows[i].from == [9.0, 0.0]);
        (k.window_target(0, w.unwrap()).is_some(), k.skipped.wall_gap)
    }

    #[test]
    fn a_gap_in_one_wall_line_seen_at_a_slant_is_that_wall() {
        // From (1, 2) the gap's middle (9.5, 0) is seen at asin(2 / 8.73) = 13°: the walls on
        // either side on one line, within twice the wall tolerance (0.14 m), close it.
        let slant = [1.0, 2.0];
        assert_eq!(wall_gap_open(slant, 0.0, 7.0), (false, 1));
        assert_eq!(wall_gap_open(slant, -0.13, 7.0), (false, 1));
        // The far wall 0.15 m off the near one's line: a step, or a door's jamb with the room
        // behind; the window stays.
        assert_eq!(wall_gap_open(slant, -0.15, 7.0), (true, 0));
        assert_eq!(wall_gap_open(slant, 0.5, 7.0), (true, 0));
        // Seen at more than 30° (from (5, 3): 34°; from (4, 3), 29°), or with a side too short
        // to set a line (0.1 m: a return or two), it stays a window.
        assert_eq!(wall_gap_open([5.0, 3.0], 0.0, 7.0), (true, 0));
        assert_eq!(wall_gap_open([4.0, 3.0], 0.0, 7.0), (false, 1));
        assert_eq!(wall_gap_open(slant, 0.0, 0.1), (true, 0));
    }

    /// From (1, 2), the wall y = 0 whole to x = 9, a gap between returns on it to x = 10,
    /// and beyond that a beam that met nothing within the range, ending at `f`: whether
    /// [`gap_in_a_wall`] reads the gap as wall. With `range_before`, the beam before the wall
    /// met nothing either.
    fn gap_before_range(f: Point, range_before: bool) -> bool {
        let at = [1.0, 2.0];
        let window =
            |from: Point, to: Point| BoundaryPiece::Window { from, to, reflex: from, far: to };
        let top = [1.0, 11.3];
        let mut pieces = vec![
            BoundaryPiece::Wall { from: [0.0, 0.0], to: [9.0, 0.0] },
            window([9.0, 0.0], [10.0, 0.0]),
            window([10.0, 0.0], f),
            BoundaryPiece::Frontier { from: f, to: top },
            BoundaryPiece::Wall { from: top, to: [0.0, 11.3] },
            BoundaryPiece::Wall { from: [0.0, 11.3], to: [0.0, 0.0] },
        ];
        if range_before {
            pieces[0] = window([0.5, 0.5], [9.0, 0.0]);
            pieces[5] = BoundaryPiece::Frontier { from: [0.0, 11.3], to: [0.5, 0.5] };
        }
        gap_in_a_wall(&pieces, 1, at, 0.07)
    }

    #[test]
    fn a_gap_whose_next_beam_met_nothing_short_of_the_wall_line_is_that_wall() {
        // The beam after the gap's far return, 0.5° on, meets y = 0 at 9.62 m; with a range
        // of 9.3 m it ends at (10.10, 0.07), short of the line: the wall may run on beyond
        // the range, and the gap, on the line of the wall before it, is that wall.
        assert!(gap_before_range([10.10, 0.067], false));
        // Ending within the wall tolerance beyond the line, the same.
        assert!(gap_before_range([10.10, -0.05], false));
        // A beam that crossed the line and met nothing went through an opening there.
        assert!(!gap_before_range([10.3, -0.6], false));
        // Nothing seen on either side: no line to read the gap on.
        assert!(!gap_before_range([10.10, 0.067], true));
    }

    /// The hall of [`wall_gap_open`] seen from (1, 2): its bottom wall whole to x = 6, then
    /// single returns at `returns` with gaps between them (a wall seen from far at a slant),
    /// and whole again from x = 16. The gaps' ends, in order, and whether each is open.
    fn chain_open(returns: &[Point], through_returns: bool) -> Vec<(Point, bool)> {
        let mut k = raw_known();
        let (wall, gap) = (true, false);
        let mut verts = vec![([0.0, 0.0], wall), ([6.0, 0.0], gap)];
        verts.extend(returns.iter().map(|&r| (r, gap)));
        verts.extend([([16.0, 0.0], wall), ([18.0, 0.0], wall), ([18.0, 4.0], wall)]);
        verts.push(([0.0, 4.0], wall));
        let region = raw_region([1.0, 2.0], &verts);
        let pieces = &region.region.boundary;
        // Read as the window strategies read it (`through_returns`), or as explore_lite's
        // raster does.
        let read: Vec<bool> = (0..pieces.len())
            .map(|i| {
                if through_returns {
                    gap_in_a_wall(pieces, i, [1.0, 2.0], 0.07)
                } else {
                    gap_between_two_walls(pieces, i, [1.0, 2.0], 0.07)
                }
            })
            .collect();
        k.add(&region);
        (0..k.views[0].windows.len())
            .map(|i| {
                let (from, piece) = (k.views[0].windows[i].from, k.views[0].windows[i].piece);
                let open = k.window_target(0, i).is_some();
                // The window strategies' bookkeeping agrees with the reading.
                if through_returns {
                    assert_eq!(open, !read[piece], "{from:?}");
                }
                (from, if through_returns { open } else { !read[piece] })
            })
            .filter(|(from, _)| from[0] >= 6.0 && from[0] < 16.0 && from[1] <= 0.0)
            .collect()
    }

    #[test]
    fn a_chain_of_gaps_between_single_returns_on_one_wall_line_is_that_wall() {
        // Returns every 2 m on y = 0 from x = 8: each gap lies between two returns on the
        // line (or a wall's far end), all four within 0.07 m of the line fitted to them, seen
        // at 14° or less: the whole chain is wall.
        let line = [[8.0, 0.0], [10.0, 0.0], [12.0, 0.0], [14.0, 0.0]];
        let chain = chain_open(&line, true);
        assert_eq!(chain.len(), 5);
        assert!(chain.iter().all(|&(_, open)| !open), "{chain:?}");
        // Noise of a few centimetres about the line changes nothing.
        let noisy = [[8.0, 0.03], [10.0, -0.03], [12.0, 0.03], [14.0, -0.03]];
        assert!(chain_open(&noisy, true).iter().all(|&(_, open)| !open));
        // A beam that went through a door at x = 11 and came back from the room behind
        // (0.5 m beyond the line): the gaps beside that return end off the line and stay
        // windows, and so do the next ones, whose fitted lines it pulls off; the gaps at the
        // chain's ends are still wall.
        let door = [[8.0, 0.0], [10.0, 0.0], [11.0, -0.5], [12.0, 0.0], [14.0, 0.0]];
        let open: Vec<bool> = chain_open(&door, true).iter().map(|&(_, o)| o).collect();
        assert_eq!(open, vec![false, true, true, true, true, false]);
        // Between two walls (explore_lite's other reading, for gaps flanked by fitted walls):
        // none of these.
        assert!(chain_open(&line, false).iter().all(|&(_, open)| open));
    }

    #[test]
    fn a_scan_placed_unsurely_closes_windows_within_its_spread() {
        // The bottom wall seen 0.3 m off: beyond the band of two well-placed scans (0.27 m),
        // within that of a scan placed with a spread of 0.05 m (0.07 + 0.1 + 3 · 0.05 m).
        assert_eq!(PLACEMENT_SIGMAS, 3.0);
        assert_eq!(bottom_gaps_open(&mut grazing_views_placed(0.3, 0.0)), vec![true; 4]);
        assert_eq!(bottom_gaps_open(&mut grazing_views_placed(0.3, 0.04)), vec![true; 4]);
        assert_eq!(bottom_gaps_open(&mut grazing_views_placed(0.3, 0.05)), vec![false; 4]);
        // However unsure, a scan's share stops at the cap: 0.07 + 0.1 + 0.3 m.
        let cap = 0.07 + 0.1 + PLACEMENT_CAP;
        assert_eq!(bottom_gaps_open(&mut grazing_views_placed(cap - 0.01, 5.0)), vec![false; 4]);
        assert_eq!(bottom_gaps_open(&mut grazing_views_placed(cap + 0.01, 5.0)), vec![true; 4]);
    }

    #[test]
    fn corner_points_stand_inset_beyond_the_clearance_from_both_walls() {
        let at = [1.0, 1.0];
        let k = room_seen_from(vec![[0.0, 0.0], [4.0, 0.0], [4.0, 3.0], [0.0, 3.0]], at);
        let c = k.clearance(0);
        let s = c + 0.1;
        let pts = k.corner_points(0, at, 10.0, 0.1, 16);
        // Nearest to the viewpoint first.
        let want = [[s, s], [s, 3.0 - s], [4.0 - s, s], [4.0 - s, 3.0 - s]];
        assert_eq!(pts.len(), 4, "{pts:?}");
        for (p, w) in pts.iter().zip(want) {
            assert!(
                (p[0] - w[0]).abs() < 1e-9 && (p[1] - w[1]).abs() < 1e-9,
                "{p:?} against {w:?}"
            );
        }
        // The nearest ones only, and none beyond `within`.
        assert_eq!(k.corner_points(0, at, 10.0, 0.1, 2).len(), 2);
        assert_eq!(k.corner_points(0, [0.0, 0.0], 1.0, 0.1, 16).len(), 1);
    }

    #[test]
    fn a_pocket_behind_a_pillar_is_measured_and_left_only_below_the_cap() {
        // The pocket: the pillar and the triangle above it between the rays from (1, 1)
        // through (4.5, 5.5) and from (9, 1) through (5.5, 5.5), which meet at x = 5.
        let apex = 5.5 + 0.5 * 4.5 / 3.5;
        let exact = 1.0 + 0.5 * (apex - 5.5);
        // Brute force from the definition: grid points of the room seen from neither
        // viewpoint (every other point of the room is seen by one of them).
        let k = pillar_views(2.0);
        let step = 0.005;
        let mut unseen = 0usize;
        for i in 0..2000 {
            for j in 0..2000 {
                let p = [(f64::from(i) + 0.5) * step, (f64::from(j) + 0.5) * step];
                if k.views.iter().all(|v| ring_side(&v.polygon, p) == RingSide::Outside) {
                    unseen += 1;
                }
            }
        }
        let brute = unseen as f64 * step * step;
        assert!((brute - exact).abs() < 0.01, "brute force {brute}, by hand {exact}");
        // Every window part still open leads into that pocket, whose area is measured.
        let mut k = pillar_views(2.0);
        let parts: Vec<(usize, usize)> =
            (0..2).flat_map(|v| (0..k.views[v].windows.len()).map(move |w| (v, w))).collect();
        let mut open = Vec::new();
        for &(v, w) in &parts {
            let mut probe = k.clone();
            probe.sensor = Sensor::default();
            if let Some((t, _)) = probe.window_target(v, w) {
                let [p, q] = probe.gap_of(&t);
                let (j, _) = k.pocket_beyond(p, q).expect("a pocket behind the part");
                let (pocket, seen) = (k.seen.pockets[j].area, k.seen.area);
                assert!((pocket - exact).abs() < 1e-6, "pocket {pocket}, by hand {exact}");
                assert!((seen - (100.0 - exact)).abs() < 1e-6, "seen {seen}");
                open.push((v, w));
            }
        }
        assert!(!open.is_empty(), "the shadows' edges leave open parts");
        // Under a cap of 2 m², the parts are closed by the rule, and counted.
        let closed: Vec<_> = open.iter().filter_map(|&(v, w)| k.window_target(v, w)).collect();
        assert!(closed.is_empty());
        assert_eq!(k.skipped.small_pocket, open.len());
        // Under a cap of 1 m², below the pocket's area, they stay open.
        let mut k = pillar_views(1.0);
        assert!(open.iter().all(|&(v, w)| k.window_target(v, w).is_some()));
        assert_eq!(k.skipped.small_pocket, 0);
    }

    #[test]
    fn the_pockets_left_share_one_budget_of_the_area_seen() {
        // Two pillars in a long room, each seen from two viewpoints below it: behind each, a
        // pocket (the pillar and the wedge where its shadows meet). Each is below the
        // per-pocket limit; the budget lets the rule leave one of them, not both.
        let room = vec![[0.0, 0.0], [20.0, 0.0], [20.0, 10.0], [0.0, 10.0]];
        let pillar = |x: f64| vec![[x - 0.5, 4.5], [x - 0.5, 5.5], [x + 0.5, 5.5], [x + 0.5, 4.5]];
        let ats = [[1.0, 1.0], [9.0, 1.0], [11.0, 1.0], [19.0, 1.0]];
        let known = |budget: Option<f64>| {
            let sensor = Sensor {
                min_pocket: 1.0,
                pocket_cap: 5.0,
                pocket_budget: budget,
                ..Sensor::default()
            };
            views_of(room.clone(), vec![pillar(5.0), pillar(15.0)], &ats, sensor)
        };
        // Brute force from the definition: the grid points of each half of the room that no
        // view's region holds (the pillar's own area included, as a hole's area is).
        let k = known(None);
        let step = 0.01;
        let mut unseen = [0usize; 2];
        for i in 0..2000 {
            for j in 0..1000 {
                let p = [(f64::from(i) + 0.5) * step, (f64::from(j) + 0.5) * step];
                if k.views.iter().all(|v| ring_side(&v.polygon, p) == RingSide::Outside) {
                    unseen[usize::from(p[0] > 10.0)] += 1;
                }
            }
        }
        let area = unseen.map(|n| n as f64 * step * step);
        let seen = 200.0 - area[0] - area[1];
        assert!(area.iter().all(|&a| a > 1.0 && a < 5.0), "{area:?}");
        // The open parts, and the pocket (left or right half) each leads into.
        let parts: Vec<(usize, usize, usize)> = {
            let mut probe = k.clone();
            probe.sensor = Sensor::default();
            (0..4)
                .flat_map(|v| (0..k.views[v].windows.len()).map(move |w| (v, w)))
                .filter_map(|(v, w)| {
                    let (t, _) = probe.window_target(v, w)?;
                    let [p, q] = probe.gap_of(&t);
                    Some((v, w, usize::from(p[0] + q[0] > 20.0)))
                })
                .collect()
        };
        assert!((0..2).all(|h| parts.iter().any(|x| x.2 == h)), "{parts:?}");
        // Which pockets the rule leaves, under a budget (a share of the area seen).
        let left = |budget: Option<f64>| {
            let mut k = known(budget);
            let open: Vec<usize> = parts
                .iter()
                .filter(|&&(v, w, _)| k.window_target(v, w).is_some())
                .map(|x| x.2)
                .collect();
            let left: Vec<usize> = (0..2).filter(|h| !open.contains(h)).collect();
            (left, k.skipped.small_pocket)
        };
        let per_half = |h: usize| parts.iter().filter(|x| x.2 == h).count();
        // No budget, or one that holds both: both are left, every part counted.
        assert_eq!(left(None), (vec![0, 1], parts.len()));
        let both = (area[0] + area[1]) / seen;
        assert_eq!(left(Some(1.01 * both)), (vec![0, 1], parts.len()));
        // A budget between the larger pocket and both: the first asked for is left, alone.
        let one = 0.5 * (area[0].max(area[1]) + area[0] + area[1]) / seen;
        let (got, counted) = left(Some(one));
        assert_eq!(got.len(), 1, "{got:?}");
        assert_eq!(counted, per_half(got[0]));
        assert!(area[got[0]] < one * seen);
        // A budget below either pocket: none is left.
        assert_eq!(left(Some(0.99 * area[0].min(area[1]) / seen)), (vec![], 0));
    }

    #[test]
    fn paths_through_the_union_of_views_keep_clear_of_the_walls() {
        // The corridor's two views see the room's door at a slant from both sides. Every
        // viewpoint planned through the union of their regions is reached along legs that
        // keep the clearance from the walls themselves, checked from the definition on the
        // domain, and lies in the region of the view whose window it is for.
        let (mut k, walls) = corridor_views_and_walls(0.8);
        let c = k.clearance(0);
        let mut planned = 0;
        for v in 0..k.views.len() {
            for w in 0..k.views[v].windows.len() {
                let (from, to) = (k.views[v].windows[w].from, k.views[v].windows[w].to);
                let Some((at, via)) = k.union_point(v, (from, to, [0.0, 1.0]), c) else { continue };
                planned += 1;
                assert_eq!(ring_side(&k.views[v].polygon, at), RingSide::Inside);
                let pts: Vec<Point> =
                    std::iter::once(k.views[v].at).chain(via).chain([at]).collect();
                for leg in pts.windows(2) {
                    for s in 0..=200 {
                        let t = f64::from(s) / 200.0;
                        let x = [
                            leg[0][0] + t * (leg[1][0] - leg[0][0]),
                            leg[0][1] + t * (leg[1][1] - leg[0][1]),
                        ];
                        let n = walls.len();
                        let d = (0..n)
                            .map(|i| {
                                crate::geometry::segment_distance(x, walls[i], walls[(i + 1) % n])
                            })
                            .fold(f64::INFINITY, f64::min);
                        assert!(d >= c - 1e-9, "{x:?} is {d} from a wall: {pts:?}");
                    }
                }
            }
        }
        assert!(planned > 0, "no window was planned through the union");
    }

    /// The targets of every window of every view.
    fn all_targets(k: &mut Known) -> Vec<Target> {
        (0..k.views.len())
            .flat_map(|v| (0..k.views[v].windows.len()).map(move |i| (v, i)))
            .collect::<Vec<_>>()
            .into_iter()
            .filter_map(|(v, i)| k.window_target(v, i).map(|t| t.0))
            .collect()
    }

    #[test]
    fn a_viewpoint_a_scan_was_asked_for_is_not_asked_for_again() {
        use crate::algorithm::visibility::Visibility;
        use crate::geometry::Domain;
        // An L-shaped room seen from its lower leg: one window into the upper leg. The robot
        // is sent to the part's viewpoint but scans short of it (as a robot does that a noisy
        // wall stops), from where nothing of the window is seen; the part is handled. Left
        // open again (by noise, or a sibling part beside the same wall), its viewpoint is
        // where a scan was asked for: a point robot, whose viewpoint is beside the part,
        // handles it without a trip; a robot with a footprint looks from another corner.
        let ring = vec![[0.0, 0.0], [6.0, 0.0], [6.0, 2.0], [2.0, 2.0], [2.0, 6.0], [0.0, 6.0]];
        let vis = Visibility::new(Domain::new(ring.clone(), vec![]).unwrap()).unwrap();
        let seen = |at: Point| PolygonObservation::new(at, vis.query(at).unwrap());
        let mut point = Known::for_robot(&RobotSetup::default());
        point.add(&seen([5.0, 1.0]));
        for mut k in [point, room_seen_from(ring, [5.0, 1.0])] {
            let t = all_targets(&mut k).remove(0);
            let (v, w) = (t.view, t.window);
            k.pending = Some(t.clone());
            k.add(&seen([5.0, 1.0]));
            assert!(k.stood_at(t.at));
            let n = k.views.len();
            let win = &mut k.views[v].windows[w];
            win.covered.clear();
            win.checked = n;
            let again = k.window_target(v, w);
            if k.clearance(v) == 0.0 {
                assert!(again.is_none(), "a second trip to {:?}: {again:?}", t.at);
                assert_eq!(k.skipped.looked_from, 1);
            } else {
                let z = again.expect("another corner sees the part").0.at;
                assert!(z != t.at && !k.stood_at(z), "{z:?}");
            }
        }
    }

    #[test]
    fn a_door_left_open_in_short_parts_by_two_views_is_opened_again() {
        // Each corridor view sees the 0.6 m door at a slant, and the other covers most of its
        // window: what is left open of each is under 0.4 m, so the rule closed both.
        let mut k = corridor_views(0.6);
        assert!(all_targets(&mut k).is_empty());
        assert!(k.skipped.below_rule >= 2);
        // The frontier of both views there spans the door, wider than the rule: reopened.
        assert!(k.reopen_wide_openings());
        let ts = all_targets(&mut k);
        assert!(!ts.is_empty());
        for t in &ts {
            let [p, q] = k.gap_of(t);
            assert!(p[0] > 1.2 && q[0] > 1.2 && p[1] > 8.0 && q[1] < 13.0, "{p:?} {q:?}");
        }
        // Once only: with the rule lifted for those windows, nothing more to reopen.
        for t in &ts {
            k.handled(t);
        }
        assert!(!k.reopen_wide_openings());
        // A door narrower than the rule stays closed.
        let mut k = corridor_views(0.3);
        assert!(all_targets(&mut k).is_empty());
        assert!(!k.reopen_wide_openings());
    }

    #[test]
    fn a_reopened_part_shorter_than_the_beams_resolve_is_not_a_trip() {
        // The door's reopened parts, each with its length and its near end's distance from
        // its view's viewpoint (from the definition of the beams' spacing, d · 2π / beams).
        let mut k = corridor_views(0.6);
        assert!(all_targets(&mut k).is_empty() && k.reopen_wide_openings());
        let parts: Vec<(f64, f64)> = all_targets(&mut k)
            .iter()
            .map(|t| {
                let [p, q] = k.gap_of(t);
                let at = k.views[t.view].at;
                let d = |x: Point| (x[0] - at[0]).hypot(x[1] - at[1]);
                ((q[0] - p[0]).hypot(q[1] - p[1]), d(p).min(d(q)))
            })
            .collect();
        assert!(!parts.is_empty());
        // Beams whose spacing at every part's distance is longer than the part: under the
        // lift the rule's width is lifted, not what the sensor resolves, so none is a trip.
        let coarse = parts
            .iter()
            .map(|&(len, d)| ((d * std::f64::consts::TAU / len).ceil() as u32).saturating_sub(1))
            .min()
            .unwrap();
        let fine = parts
            .iter()
            .map(|&(len, d)| (d * std::f64::consts::TAU / len).ceil() as u32 + 1)
            .max()
            .unwrap();
        assert!(coarse >= 1);
        for (beams, trips) in [(coarse, false), (fine, true)] {
            let mut k = corridor_views(0.6);
            assert!(all_targets(&mut k).is_empty() && k.reopen_wide_openings());
            k.sensor.beams = Some(beams);
            assert_eq!(!all_targets(&mut k).is_empty(), trips, "{beams} beams: {parts:?}");
        }
    }

    #[test]
    fn a_reopened_window_is_judged_by_the_rule_again_after_its_scan() {
        use crate::algorithm::visibility::Visibility;
        use crate::geometry::Domain;
        // The door's reopened part, split by a cover in its middle into two parts under the
        // rule (as noisy scans' regions split one): the trip goes to the first; once it is
        // scanned, the opening was visited and the second is closed by the rule, not a trip.
        let (mut k, ring) = corridor_views_and_walls(0.6);
        assert!(all_targets(&mut k).is_empty());
        assert!(k.reopen_wide_openings());
        let t = all_targets(&mut k).remove(0);
        let (v, w, [a, b]) = (t.view, t.window, t.gap);
        let win = &mut k.views[v].windows[w];
        win.covered.push([a + 0.4 * (b - a), a + 0.6 * (b - a)]);
        cover::merge(&mut win.covered);
        let first = k.window_target(v, w).expect("the part before the cover").0;
        assert!(first.gap[1] <= a + 0.4 * (b - a) + 1e-12, "{:?}", first.gap);
        let before = k.skipped.below_rule;
        // The scan for it, from where nothing beyond the door is seen (so its region covers
        // no part of the window).
        let vis = Visibility::new(Domain::new(ring, vec![]).unwrap()).unwrap();
        k.pending = Some(first);
        k.add(&PolygonObservation::new([0.6, 1.0], vis.query([0.6, 1.0]).unwrap()));
        assert!(k.window_target(v, w).is_none(), "the part after the cover is a trip");
        assert_eq!(k.skipped.below_rule, before + 1);
        // Never reopened a second time.
        k.reopen_wide_openings();
        assert!(k.window_target(v, w).is_none(), "reopened twice");
    }

    /// Whether the segment `a b` crosses the ring's edges only where it touches them: the
    /// real walls, for a brute-force look from the definition.
    fn crosses_a_wall(ring: &[Point], a: Point, b: Point) -> bool {
        let n = ring.len();
        (0..n).any(|i| segments_intersect(a, b, ring[i], ring[(i + 1) % n]))
    }

    #[test]
    fn every_viewpoint_planned_for_a_door_seen_at_a_slant_sees_its_part() {
        // A corridor 2 m wide above a 4 × 5 m room, joined by a door 1 m wide in a wall
        // 0.2 m thick (the built-in office's rooms). Scanned at a slant from beside the door,
        // the room shows as thin wedges whose windows run just behind a jamb. A point stepped
        // off such a window part can land across the jamb, in the corridor: a scan there does
        // not see the part at all (it cost the office a whole room on raw scans). Every
        // viewpoint planned must see a quarter of its part, checked against the walls.
        use crate::algorithm::visibility::Visibility;
        use crate::geometry::Domain;
        let ring = vec![
            [0.0, 5.2],
            [4.5, 5.2],
            [4.5, 5.0],
            [3.0, 5.0],
            [3.0, 0.0],
            [7.0, 0.0],
            [7.0, 5.0],
            [5.5, 5.0],
            [5.5, 5.2],
            [10.0, 5.2],
            [10.0, 7.2],
            [0.0, 7.2],
        ];
        let vis = Visibility::new(Domain::new(ring.clone(), vec![]).unwrap()).unwrap();
        let mut planned = 0;
        // Robots of radius 0.2 m and 0.27 m (the clearance a 0.2 m robot keeps on raw scans),
        // at viewpoints all over the corridor, 0.25 m apart along it.
        let corridor = (1..40)
            .flat_map(|i| (0..6).map(move |j| [0.25 * f64::from(i), 5.45 + 0.3 * f64::from(j)]));
        let cases = [0.2, 0.27].into_iter().flat_map(|r| corridor.clone().map(move |at| (r, at)));
        for (radius, at) in cases {
            let footprint = Footprint::disc(radius).unwrap();
            let setup = RobotSetup { footprint, ..RobotSetup::default() };
            let mut k = Known::for_robot(&setup);
            k.add(&PolygonObservation::new(at, vis.query(at).unwrap()));
            for t in all_targets(&mut k) {
                let [p, q] = k.gap_of(&t);
                let seen = (0..=64).filter(|&i| {
                    let f = f64::from(i) / 64.0;
                    let m = [p[0] + f * (q[0] - p[0]), p[1] + f * (q[1] - p[1])];
                    // A hair short of the part, toward the viewpoint.
                    let m = [m[0] + 1e-6 * (t.at[0] - m[0]), m[1] + 1e-6 * (t.at[1] - m[1])];
                    !crosses_a_wall(&ring, t.at, m)
                });
                // At least a quarter of the part, to the sample: the broken placement, across
                // the jamb, saw 12 of these 65 points.
                let seen = seen.count();
                assert!(
                    seen >= 16,
                    "from {at:?}, r = {radius}: the viewpoint {:?} sees {seen} of 65 points of {p:?} {q:?}",
                    t.at
                );
                planned += 1;
            }
        }
        assert!(planned > 0);
    }

    #[test]
    fn uncovering_a_gap_splits_and_trims_the_intervals_it_meets() {
        let covered = vec![[0.0, 0.2], [0.3, 0.6], [0.7, 1.0]];
        // A gap inside one interval splits it; one across two trims both.
        assert_eq!(uncover(&covered, [0.4, 0.5]), [[0.0, 0.2], [0.3, 0.4], [0.5, 0.6], [0.7, 1.0]]);
        assert_eq!(uncover(&covered, [0.5, 0.8]), [[0.0, 0.2], [0.3, 0.5], [0.8, 1.0]]);
        // A gap holding an interval whole removes it; one between intervals changes nothing.
        assert_eq!(uncover(&covered, [0.25, 0.65]), [[0.0, 0.2], [0.7, 1.0]]);
        assert_eq!(uncover(&covered, [0.2, 0.3]), covered);
    }

    #[test]
    fn a_move_inside_one_views_region_keeping_the_clearance_is_straight_in_a_view() {
        // The corridor (0 ≤ x ≤ 1.2) seen from (0.6, 4) and (0.6, 16), a 0.2 m robot.
        let (k, _) = corridor_views_and_walls(1.0);
        let c = k.clearance(0);
        assert!(c >= 0.2, "{c}");
        // Along the corridor's middle, from a viewpoint or from any point inside a region.
        assert!(k.straight_in_a_view([0.6, 4.0], [0.6, 6.0]));
        assert!(k.straight_in_a_view([0.5, 7.0], [0.7, 12.0]));
        // Not nearer a wall than the clearance, not through a wall, not from outside.
        assert!(!k.straight_in_a_view([0.6, 4.0], [1.1, 6.0]));
        assert!(!k.straight_in_a_view([0.6, 4.0], [3.0, 9.0]));
        assert!(!k.straight_in_a_view([3.0, 9.0], [0.6, 4.0]));
        // Whatever it accepts keeps the clearance in the union of the regions too.
        let mut k = k;
        k.update_seen();
        for (a, b) in [([0.6, 4.0], [0.6, 6.0]), ([0.5, 7.0], [0.7, 12.0])] {
            assert!(k.clear_in_seen(a, b, c), "{a:?} {b:?}");
        }
    }

    #[test]
    fn a_flat_kink_of_a_wall_is_not_a_corner() {
        // The room of `corner_points_stand_inset_beyond_the_clearance_from_both_walls`, its
        // bottom wall kinked out at (2, -0.1) by 174°.
        let ring = vec![[0.0, 0.0], [2.0, -0.1], [4.0, 0.0], [4.0, 3.0], [0.0, 3.0]];
        let at = [1.0, 1.0];
        let k = room_seen_from(ring, at);
        let pts = k.corner_points(0, at, 10.0, 0.1, 16);
        assert_eq!(pts.len(), 4, "the room's four corners only: {pts:?}");
        assert!(pts.iter().all(|p| (p[0] - 2.0).abs() > 1.0), "{pts:?}");
    }

    /// Three views of an open 12 × 12 m room (a window along half its top wall, a door seen
    /// at a grazing angle), the second and third each reached from the first (its corner):
    /// the tree of moves between the other two runs through that corner.
    fn room_views(mut k: Known) -> Known {
        let room = |at: Point| {
            raw_region(
                at,
                &[
                    ([0.0, 0.0], true),
                    ([12.0, 0.0], true),
                    ([12.0, 12.0], true),
                    ([6.0, 12.0], false),
                    ([0.0, 12.0], true),
                ],
            )
        };
        let target = |at: Point| Target {
            at,
            via: Vec::new(),
            view: 0,
            window: 0,
            gap: [0.0, 1.0],
            anchor: None,
            off_gap: false,
            relocate: false,
        };
        k.add(&room([1.0, 1.0]));
        for at in [[11.0, 1.0], [11.0, 11.0]] {
            k.pending = Some(target(at));
            k.add(&room(at));
        }
        k.pending = None;
        k.here = 1;
        k
    }

    /// The length of the trip a plan starts, from `from`.
    fn trip_length(k: &Known, from: Point, first: &Action<Point>) -> f64 {
        let Action::MoveTo { to } = first else { panic!("{first:?}") };
        let pts: Vec<Point> = std::iter::once(*to).chain(k.ahead()).collect();
        path_length(from, &pts)
    }

    #[test]
    fn on_raw_scans_a_trip_takes_the_shortest_way_through_what_was_seen_not_the_tree() {
        let goal = Target {
            at: [10.5, 10.5],
            via: Vec::new(),
            view: 2,
            window: 0,
            gap: [0.0, 1.0],
            anchor: None,
            off_gap: false,
            relocate: false,
        };
        // Raw scans: straight up the room's side, 9.5 m.
        let mut raw = room_views(raw_known());
        let first = raw.go_from(1, goal.clone());
        let len = trip_length(&raw, [11.0, 1.0], &first);
        assert!(len < 10.0, "{len}");
        assert!(raw.ahead().iter().all(|p| p[0] > 5.0), "{:?}", raw.ahead());
        // The exact sensor: the tree of moves, through the first view's corner (10 + 14 m).
        let mut exact = room_views(Known::for_robot(&RobotSetup {
            footprint: Footprint::disc(0.2).unwrap(),
            ..RobotSetup::default()
        }));
        let first = exact.go_from(1, goal);
        let len = trip_length(&exact, [11.0, 1.0], &first);
        assert!(len > 23.0, "{len}");
    }
}
