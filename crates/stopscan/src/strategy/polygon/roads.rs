//! Routes through what was seen: an occupancy raster of the views ([`Raster`]), its safe
//! cells for a robot with a footprint (every cell within `k` free, `k · res` at least the
//! clearance), and the shortest way through them from where the robot stands (Dijkstra's
//! algorithm once per decision, which also prices every place it reaches).
//!
//! `cost_aware` plans and prices all its trips on these roads (and predicts its gain on the
//! same raster). On raw scans the other window strategies drive their trips along them too
//! ([`Known::go_route`]): odometry drifts with every metre driven, and along the tree of
//! moves between viewpoints, as the paper's robot drives, their trips ran 1.8 times the
//! straight distance between their scans (1.6 to 2.3 by strategy and map).

use super::known::{Known, Target};
use super::raster::{CELL, Entry, Raster, STEP};
use crate::algorithm::visibility::BoundaryPiece;
use crate::kernel::Point;

/// How many safe cells near a viewpoint are tried as the end of the road to it.
const ROAD_ENDS: usize = 32;

/// The occupancy raster of the views, how many of them it holds, and their bounding box.
#[derive(Debug, Clone, Default)]
pub(super) struct SeenRaster {
    pub(super) raster: Option<Raster>,
    views: usize,
    pub(super) bounds: Option<[Point; 2]>,
    /// The length scale of the raster's cell ([`Known::raster_scale`]).
    pub(super) scale: f64,
    /// The inflation of the raster's safe cells, cells (0 for a point robot, whose routes
    /// follow the tree of moves).
    pub(super) k: i64,
}

impl PartialEq for SeenRaster {
    /// Derived from the views: equal whenever the views are.
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

/// The robot's ways through safe cells of the raster from where it stands: its first steps
/// and the cost of the cheapest path to every cell ([`Raster::distances`]).
pub(super) struct Roads {
    at: Point,
    entries: Vec<Entry>,
    dist: Vec<u64>,
}

impl SeenRaster {
    /// Brings the raster up to date with `known`'s views. The length scale is the range, or
    /// without one how far the first view reached. With `assumed` (a fraction of the length
    /// scale), the wall a window's far end lies on is assumed to run on that far out of sight
    /// ([`assumed_walls`]).
    pub(super) fn sync(&mut self, known: &Known, assumed: Option<f64>) {
        let n = known.views.len();
        if self.views >= n || n == 0 {
            return;
        }
        let footprint = known.footprint();
        if self.raster.is_none() {
            let scale = known.raster_scale();
            self.scale = scale;
            let mut res = scale * CELL;
            if !footprint.is_point() {
                // A whole number of cells spans the clearance (at a scale the map's later
                // scans do not exceed), as in explore_lite, so that passages lose no more
                // than the rounding of the safe cells' box.
                let mag = crate::kernel::magnitude(known.region_of(0).0);
                let c = footprint.planning_clearance((4.0 * mag).max(1000.0));
                res = c / (c / res).round().max(1.0);
            }
            self.raster = Some(Raster::new(res));
        }
        let scale = self.scale;
        let Some(raster) = self.raster.as_mut() else { return };
        for v in self.views..n {
            let (poly, pieces) = known.region_of(v);
            raster.scale = raster.scale.max(crate::kernel::magnitude(poly)).max(1.0);
            let changed = raster.add_view(poly, pieces, known.viewpoint(v));
            if let Some(share) = assumed {
                for (a, b) in assumed_walls(pieces, share * scale) {
                    raster.assume_wall(a, b);
                }
            }
            if !footprint.is_point() {
                // The safe cells: every cell within k free, k·res at least the clearance.
                let k = (footprint.planning_clearance(raster.scale) / raster.res).ceil() as i64;
                if k != self.k {
                    self.k = k;
                    raster.update_safe_everywhere(k);
                } else if let Some((lo, hi)) = changed {
                    raster.update_safe(lo, hi, k);
                }
            }
            let [lo, hi] = crate::algorithm::cover::bounds_of(poly);
            self.bounds = Some(match self.bounds {
                None => [lo, hi],
                Some([l, h]) => {
                    [[l[0].min(lo[0]), l[1].min(lo[1])], [h[0].max(hi[0]), h[1].max(hi[1])]]
                }
            });
        }
        self.views = n;
    }

    /// The robot's roads from view `cur`'s viewpoint: `None` for a point robot, or when no
    /// safe cell is within its reach.
    pub(super) fn roads(&self, known: &Known, cur: usize) -> Option<Roads> {
        let raster = self.raster.as_ref().filter(|_| self.k > 0)?;
        let at = known.viewpoint(cur);
        let poly = known.region_of(cur).0;
        let c = known.clearance(cur);
        let entries = raster.entries(at, Some(poly), c, self.k, known.relaxed());
        if entries.is_empty() {
            return None;
        }
        let dist = raster.distances(&entries);
        Some(Roads { at, entries, dist })
    }

    /// The safe cells near `z` the roads reach, with the length of the way to `z` through
    /// each (the road to the cell's centre, then straight on), shortest first.
    fn road_ends(&self, roads: &Roads, z: Point) -> Vec<(f64, usize)> {
        let mut out: Vec<(f64, usize)> = self.ends_near(roads, z).collect();
        out.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        out
    }

    /// The safe cells within `k + 3` cells of `z` the roads reach, with the length of the way
    /// to `z` through each, in no particular order.
    fn ends_near<'a>(
        &'a self,
        roads: &'a Roads,
        z: Point,
    ) -> impl Iterator<Item = (f64, usize)> + 'a {
        let raster = self.raster.as_ref();
        let r = self.k + 3;
        let zc = raster.map_or([0, 0], |ra| ra.cell_of(z));
        raster.into_iter().flat_map(move |ra| {
            (zc[1] - r..=zc[1] + r).flat_map(move |y| {
                (zc[0] - r..=zc[0] + r).filter_map(move |x| {
                    let i = ra.local([x, y])?;
                    let d = roads.dist[i];
                    (d != u64::MAX).then(|| {
                        let q = ra.centre([x, y]);
                        (d as f64 * ra.res / STEP as f64 + (q[0] - z[0]).hypot(q[1] - z[1]), i)
                    })
                })
            })
        })
    }

    /// Fewer waypoints: from the robot and then from each waypoint kept, straight on to the
    /// farthest later one the move reaches keeping the clearance `c` from the boundary of the
    /// union of the views' regions (the safe cells' inflation is rounded up to whole cells,
    /// so their paths turn more often than the space seen requires). Every move of a real
    /// robot is a goal of its own to its navigation stack.
    fn straighten(known: &Known, from: Point, pts: &[Point], c: f64) -> Vec<Point> {
        let mut out = Vec::with_capacity(pts.len());
        let (mut at, mut i) = (from, 0);
        while i < pts.len() {
            let j =
                (i + 1..pts.len()).rev().find(|&j| known.clear_in_seen(at, pts[j], c)).unwrap_or(i);
            out.push(pts[j]);
            at = pts[j];
            i = j + 1;
        }
        out
    }

    /// The length of the way to `z` along the roads, if they come near it.
    pub(super) fn road_length(&self, roads: &Roads, z: Point) -> Option<f64> {
        self.ends_near(roads, z).map(|e| e.0).min_by(f64::total_cmp)
    }

    /// The waypoints of a route to `z` along the roads, ending at `z`: through safe cells to
    /// the nearest cell near `z` from whose centre the last leg keeps the clearance (in safe
    /// cells, in the union of the views' regions, or inside one view's region), corners cut
    /// while the moves stay in safe cells. The union must be up to date
    /// ([`Known::update_seen`]).
    pub(super) fn road_to(&self, known: &Known, roads: &Roads, z: Point) -> Option<Vec<Point>> {
        let raster = self.raster.as_ref()?;
        let c = known.footprint().planning_clearance(raster.scale);
        for (_, cell) in self.road_ends(roads, z).into_iter().take(ROAD_ENDS) {
            let q = raster.centre(raster.global(cell));
            if !(q == z
                || raster.segment_is_safe(q, z)
                || known.clear_in_seen(q, z, c)
                || known.straight_in_a_view(q, z))
            {
                continue;
            }
            let path = raster.astar(&roads.entries, cell)?;
            let mut pts = raster.compress(roads.at, &roads.entries, &path)?;
            if pts.last() != Some(&z) {
                pts.push(z);
            }
            return Some(Self::straighten(known, roads.at, &pts, c));
        }
        None
    }

    /// Where no safe cell near the viewpoint of `t` leads on to it (a viewpoint in a narrow
    /// place, planned at the clearance inside its view's region, that the safe cells' rounded
    /// inflation closes): the roads to the last waypoint of the tree of moves toward it that
    /// they reach, then the tree's moves on from there. Along the tree alone, from where the
    /// robot stands, the trip went back through every viewpoint between (on depot, raw scans,
    /// seed 2: 37.7 m for a hop of 2 m).
    pub(super) fn road_then_tree(
        &self,
        known: &Known,
        roads: &Roads,
        cur: usize,
        t: &Target,
    ) -> Option<Vec<Point>> {
        let tree = known.tree_route(cur, t);
        (0..tree.len() - 1).rev().find_map(|j| {
            let mut pts = self.road_to(known, roads, tree[j])?;
            pts.extend_from_slice(&tree[j + 1..]);
            Some(pts)
        })
    }

    /// The route from view `cur`'s viewpoint to `t` along the roads ([`SeenRaster::road_to`],
    /// else [`SeenRaster::road_then_tree`]), if they lead there.
    pub(super) fn route_to(&self, known: &Known, cur: usize, t: &Target) -> Option<Vec<Point>> {
        let roads = self.roads(known, cur)?;
        self.road_to(known, &roads, t.at).or_else(|| self.road_then_tree(known, &roads, cur, t))
    }
}

/// Where the walls beside a region's windows are assumed to run on behind them, for the
/// predicted gain: the wall piece that a window's far end lies on, extended beyond that end
/// by `len` (the wall the window's ray met runs on out of sight).
pub(super) fn assumed_walls(pieces: &[BoundaryPiece], len: f64) -> Vec<(Point, Point)> {
    let n = pieces.len();
    let mut out = Vec::new();
    for (i, piece) in pieces.iter().enumerate() {
        let BoundaryPiece::Window { far, .. } = *piece else { continue };
        for j in [(i + 1) % n, (i + n - 1) % n] {
            let (BoundaryPiece::Edge { from: a, to: b, .. }
            | BoundaryPiece::Partial { from: a, to: b, .. }
            | BoundaryPiece::Wall { from: a, to: b }) = pieces[j]
            else {
                continue;
            };
            let (end, other) = if a == far {
                (a, b)
            } else if b == far {
                (b, a)
            } else {
                continue;
            };
            let (dx, dy) = (end[0] - other[0], end[1] - other[1]);
            let l = dx.hypot(dy);
            if l > 0.0 {
                out.push((end, [end[0] + len * dx / l, end[1] + len * dy / l]));
            }
        }
    }
    out
}
