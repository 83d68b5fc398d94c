//! Successive scans into observations in one map frame: each scan is read ([`ingest`]),
//! aligned by ICP to the walls of the scans before it, and its walls join the map.
//!
//! The first scan defines the map frame's walls; it is placed where odometry says. A scan ICP
//! could not align (a [`Fallback`](super::icp::Fallback)) is placed by odometry and informs
//! the strategy, but its walls stay out of the map: put in the wrong place, they would pull
//! every later alignment.
//!
//! **Loop closure.** Every stop is a node of a [pose graph](super::posegraph). Odometry ties
//! each stop to the one before (as sure as its drift over the metres driven); an aligned scan
//! is tied by its alignment to the map to the stops whose walls it paired with (each by the
//! information of its own pairs: the map's walls remember the stop they were seen from), and
//! matched on its own to
//! the nearest [`MAX_LINKS`] earlier stops whose reach overlaps its own. A match that converged
//! on [`LINK_MIN_PAIRS`] pairs becomes an edge when the graph can meet it without straining
//! what it already holds (a scan slid along one stop's walls would, and so would a match that
//! disagrees with a well-constrained alignment to the map). The graph is solved after every scan, and when it moved an earlier stop, the map's
//! walls are put again where their stops now are. So a stop placed wrongly along a corridor
//! (odometry kept along it) is moved when a later stop sees both its walls and walls placed
//! well, and the next scans align to walls in their right places. The pose reported for a
//! stop is the graph's at the time it was read; [`Mapper::poses`] has them as they are now.

use serde::{Deserialize, Serialize};

use super::icp::{self, Alignment, IcpParams, Prior, WallMap};
use super::ingest::{Cleaning, IngestError, IngestParams, ingest};
use super::posegraph::{Edge, Information, PoseGraph};
use crate::algorithm::visibility::BoundaryPiece;
use crate::kernel::Point;
use crate::protocol::laser::{LaserScan, Pose, wrap};
use crate::protocol::polygon::PolygonObservation;

/// The wall map keeps walls in pieces of at most this length, metres.
pub const MAP_PIECE: f64 = 0.5;

/// A wall piece within this distance of a mapped wall of the same orientation is that wall,
/// seen again, metres: it is not added twice.
pub const MAP_SAME_WALL: f64 = 0.3;

/// The smallest prior standard deviations ICP is given: 1 cm and 0.002 rad, so that a short
/// move does not pin the alignment to odometry.
const MIN_PRIOR: Prior = Prior { position: 0.01, heading: 0.002 };

/// The smallest correction ICP may not make, metres: a wall seen again within
/// [`MAP_SAME_WALL`] is the same wall.
pub const MIN_PLAUSIBLE_SHIFT: f64 = MAP_SAME_WALL;

/// The smallest turn ICP may not make, radians (3°).
pub const MIN_PLAUSIBLE_TURN: f64 = 0.052;

/// The relay rule's default threshold, metres: a third of the 0.1 m a stop may be off
/// ([`Mapper::relay`]).
pub const RELAY: f64 = 0.033;

/// A relay stands where a scan is predicted to be placed with this margin
/// ([`icp::Prediction::places_by`]), twice [`icp::PREDICTION_MARGIN`]: the place nearest the
/// trip's end that passes the end's own test is at the edge of what ICP can place. On the
/// 720 raw-scan runs of the README's grid, a margin of 4 left the relay itself the first
/// stop beyond 0.1 m in 47 runs; with 8, runs with a stop beyond 0.1 m fell from 155 to
/// 130 and runs beyond 1.25 × their exact run's scans from 169 to 158.
pub const RELAY_MARGIN: f64 = 2.0 * icp::PREDICTION_MARGIN;

/// A relay stands where a scan is predicted to be placed not only where the robot believes
/// it stands but also this many standard deviations of odometry's reach
/// ([`Mapper::unsure_after`]) away along each axis, where it may really stand
/// ([`Mapper::relay`]). A relay's alignment may rest on one wall the robot stands beside:
/// on the warehouse (`range_limited`, seed 11) a relay 17 m from the start, believed
/// 0.35 m from the end of a wall that alone held it across the aisle, truly stood level with
/// the wall's end, saw it edge-on, and was placed 0.4 m off across the aisle; the stops after
/// aligned to its walls. On the 720 raw-scan runs of the README's grid, runs with a stop
/// beyond 0.1 m fell from 78 to 51 and beyond 0.5 m from 6 to 1 (1 σ: 20 and 2 on the
/// warehouse's `range_limited` runs against 13 and 0 at 2 σ; 3 σ: more relays, 56 and 2
/// over the warehouse's 240 runs against 46 and 1).
pub const RELAY_SPREAD: f64 = 2.0;

/// At most this many relays before the strategy's next scan.
pub const MAX_RELAYS: usize = 2;

/// Relays are looked for along the trip every this many metres, back from its end...
pub const RELAY_STEP: f64 = 0.5;

/// ...and no nearer than this to where the robot stands, metres.
pub const RELAY_GAP: f64 = 1.0;

/// How scans are read and aligned, and how far odometry drifts.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MapperParams {
    /// How scans are read.
    pub ingest: IngestParams,
    /// How scans are aligned.
    pub icp: IcpParams,
    /// Odometry's drift: the standard deviation of the position error per metre driven (per
    /// axis), and `heading_drift` radians per metre for the heading.
    pub drift: f64,
    /// The heading's drift per metre driven, radians.
    pub heading_drift: f64,
}

impl MapperParams {
    /// The defaults for a sensor with range noise `sigma` on odometry that drifts `drift`
    /// metres per metre (per axis) and `heading_drift` radians per metre.
    pub fn for_sensor(sigma: f64, drift: f64, heading_drift: f64) -> Self {
        Self {
            ingest: IngestParams::for_noise(sigma),
            icp: IcpParams { huber: (3.0 * sigma).max(0.02), sigma, ..IcpParams::default() },
            drift,
            heading_drift,
        }
    }
}

/// One scan, read and placed.
#[derive(Debug, Clone, PartialEq)]
pub struct Reading {
    /// The region seen, in the map frame.
    pub observation: PolygonObservation,
    /// The pose the scan was placed at: ICP's, or odometry's when it could not align.
    pub estimate: Pose,
    /// What ICP did (none for the first scan: nothing was known).
    pub alignment: Option<Alignment>,
    /// How many earlier stops the scan was matched to on its own: the pose graph's edges
    /// from it, besides odometry.
    pub links: usize,
    /// How unsure the placement is: one standard deviation of the position, metres, along
    /// its least sure direction, as the pose graph holds it when the scan is read
    /// ([`PoseGraph::covariance`]; 0 for the first stop, which defines the map frame).
    pub placement: f64,
    /// What cleaning did.
    pub cleaning: Cleaning,
}

/// The most earlier stops a scan is matched to on its own, nearest first.
pub const MAX_LINKS: usize = 6;

/// The fewest pairs for a match to one earlier stop to become an edge of the pose graph.
pub const LINK_MIN_PAIRS: usize = 100;

/// How far a match to one earlier stop is expected to move the map's alignment, one standard
/// deviation: a match that moves it by more than four of these is kept only when every
/// restart agrees (a single stop's walls can let a scan slide along them).
const LINK_PRIOR: Prior = Prior { position: 0.1, heading: 0.01 };

/// A scan match's information is divided by this: its pairs' residuals are not independent
/// (the same wall fit, the same beam pattern), so `n` pairs know less than `n` independent
/// ones would.
const LINK_INFLATION: f64 = 10.0;

/// A match is kept when adding it to the graph raises the graph's weighted squared error by
/// at most this much (about the 1-in-100,000 tail of a chi-squared with three degrees of
/// freedom): a wrong match strains the measurements the graph already holds.
const LINK_STRAIN: f64 = 25.0;

/// At most this many Gauss-Newton steps per scan.
const GRAPH_STEPS: usize = 10;

/// The map is rebuilt from every stop when the graph moved one by more than this, metres...
const REBUILD: f64 = 0.005;

/// ...or turned one by more than this, radians.
const REBUILD_TURN: f64 = 0.0005;

/// One stop, kept so that later scans can be matched to it and its walls moved with it.
#[derive(Debug, Clone)]
struct Kept {
    /// Its walls, in its scanner's frame.
    walls: Vec<[Point; 2]>,
    /// Its bridges (gaps between returns on one wall line), in its scanner's frame.
    bridges: Vec<[Point; 2]>,
    /// Its occluders ([`occluders`]), in its scanner's frame.
    occluders: Vec<[Point; 2]>,
    /// The same, indexed for matching.
    local: WallMap,
    /// Its walls fitted finer ([`Ingested::fine_walls`](super::ingest::Ingested)), in its
    /// scanner's frame.
    fine_walls: Vec<[Point; 2]>,
    /// The same, indexed for refining matches ([`icp::refine`]).
    fine_local: WallMap,
    /// Whether it was aligned: a scan ICP could not align stays out of the map.
    aligned: bool,
    /// Its farthest return, metres.
    reach: f64,
    /// The pose reported for it: odometry to the next stop counts from there.
    reported: Pose,
    /// The pose its walls were put in the map at.
    placed: Pose,
}

/// The walls seen so far, and how new scans are read against them.
///
/// Give it poses in a frame near the map, as the strategies its observations feed: their
/// tolerances grow with the coordinates' magnitude, so that odometry millions of metres from
/// its origin (a georeferenced frame) makes them coarser than a map's features. `serve` moves
/// the robot's poses to a frame near its start ([`crate::geometry::Frame::near`]) first.
#[derive(Debug, Clone)]
pub struct Mapper {
    params: MapperParams,
    map: WallMap,
    /// The aligned stops' walls fitted finer, for refining alignments ([`icp::refine`]).
    fine_map: WallMap,
    /// What may hide the map's walls from a scan not taken yet ([`occluders`]).
    occluders: WallMap,
    kept: Vec<Kept>,
    graph: PoseGraph,
    /// Metres driven since the last stop whose alignment was kept (or the first stop): the
    /// stops between kept odometry's pose, so its drift since then is still in the estimate.
    unaligned: f64,
    /// How unsure the graph was of the last stop's position when it was read
    /// ([`Reading::placement`]).
    placement: f64,
}

impl Mapper {
    /// An empty map.
    pub fn new(params: MapperParams) -> Self {
        Self {
            params,
            map: WallMap::new(),
            fine_map: WallMap::new(),
            occluders: WallMap::new(),
            kept: Vec::new(),
            graph: PoseGraph::new(),
            unaligned: 0.0,
            placement: 0.0,
        }
    }

    /// How far off the pose of a scan taken after driving `metres` more on odometry alone
    /// may be before it is aligned, one standard deviation, metres: the last stop's
    /// placement and odometry's reach since the last stop it aligned.
    pub fn unsure_after(&self, metres: f64) -> f64 {
        let (_, reach) = odometry_spread(&self.params, self.unaligned + metres);
        self.placement.hypot(reach)
    }

    /// A relay: where on the first leg of `trip` (map frame: where the robot stands, the
    /// move it is about to make, then the waypoints after it; the last is where the next scan
    /// is to be taken) the robot should stop and scan to place itself, if anywhere. It
    /// should when the scan where the trip ends is predicted not to be placed
    /// ([`Mapper::would_place`], with the lidar's `beams` and `range`), odometry may be off
    /// there by more than `threshold` (one standard deviation, [`Mapper::unsure_after`]
    /// `since_scan` metres already driven and the trip), and a scan is predicted to be placed
    /// somewhere on the way (with [`RELAY_MARGIN`], and from the four places
    /// [`RELAY_SPREAD`] standard deviations of odometry's reach there away from it along the
    /// axes): the place nearest the trip's end, every [`RELAY_STEP`] back along it and at
    /// least [`RELAY_GAP`] from where the robot stands. That place is returned when it lies
    /// on the first leg or at its end; one on a later leg is found when the robot stands at
    /// the start of that leg.
    pub fn relay(
        &self,
        trip: &[Point],
        since_scan: f64,
        beams: usize,
        range: f64,
        threshold: f64,
    ) -> Option<Point> {
        let (&end, legs) = (trip.last()?, trip.windows(2));
        let lengths: Vec<f64> =
            legs.map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1])).collect();
        let length: f64 = lengths.iter().sum();
        if threshold.is_nan()
            || threshold <= 0.0
            || self.unsure_after(since_scan + length) <= threshold
            || self.would_place(end, beams, range)
        {
            return None;
        }
        // Back from the end, leg by leg.
        let mut left = length;
        for (k, w) in trip.windows(2).enumerate().rev() {
            let l = lengths[k];
            let mut t = l;
            while t > 0.0 {
                t = (t - RELAY_STEP).max(0.0);
                // How far along the trip the place lies.
                let along = left - l + t;
                if along < RELAY_GAP {
                    return None;
                }
                let p =
                    [w[0][0] + (w[1][0] - w[0][0]) * t / l, w[0][1] + (w[1][1] - w[0][1]) * t / l];
                // How far off odometry may put the robot there, one standard deviation.
                let spread = self.unsure_after(since_scan + along);
                if self.would_place_by(p, beams, range, RELAY_MARGIN)
                    && self.would_place_around(p, RELAY_SPREAD * spread, beams, range)
                {
                    return (k == 0 || (k == 1 && t == 0.0)).then_some(p);
                }
            }
            left -= l;
        }
        None
    }

    /// Whether a scan from `at` (map frame) is predicted to be placed by ICP
    /// ([`icp::predict`] with the lidar's `beams` and `range`).
    pub fn would_place(&self, at: Point, beams: usize, range: f64) -> bool {
        self.would_place_by(at, beams, range, icp::PREDICTION_MARGIN)
    }

    /// Whether a scan is predicted to be placed ([`Mapper::would_place`]) from each of the
    /// four places `off` metres from `at` along the axes: where odometry may really have put
    /// a robot that believes it stands at `at`.
    fn would_place_around(&self, at: Point, off: f64, beams: usize, range: f64) -> bool {
        [[off, 0.0], [-off, 0.0], [0.0, off], [0.0, -off]]
            .iter()
            .all(|d| self.would_place([at[0] + d[0], at[1] + d[1]], beams, range))
    }

    /// [`Mapper::would_place`] with another margin ([`icp::Prediction::places_by`]).
    fn would_place_by(&self, at: Point, beams: usize, range: f64, margin: f64) -> bool {
        let icp = &self.params.icp;
        !self.map.is_empty()
            && icp::predict(&self.map, &self.occluders, at, beams, range, icp)
                .places_by(icp, margin)
    }

    /// The parameters.
    pub fn params(&self) -> &MapperParams {
        &self.params
    }

    /// Every stop's pose as the pose graph now has it, in the order read: a stop read before
    /// a loop closure may since have moved from the estimate reported for it.
    pub fn poses(&self) -> &[Pose] {
        self.graph.poses()
    }

    /// Reads `scan`, taken where odometry says `odometry` (map frame: the pose reported for
    /// the last scan, moved by what odometry measured since) after driving `driven` metres
    /// since the last scan; aligns it to the map, matches it to the earlier stops near it one
    /// by one, solves the pose graph, and puts its walls in the map (moving the earlier
    /// stops' walls when the graph moved them).
    ///
    /// # Errors
    /// [`IngestError`] for an invalid scan or pose, or a scan with no valid return.
    pub fn read(
        &mut self,
        scan: &LaserScan,
        odometry: &Pose,
        driven: f64,
    ) -> Result<Reading, IngestError> {
        if !odometry.is_finite() {
            return Err(IngestError::Pose(*odometry));
        }
        let p = &self.params;
        // Read in the scanner's frame, aligned, then placed at the estimate.
        let local = ingest(scan, &Pose::default(), &p.ingest)?;
        // Odometry may be off by its drift over every metre since the last stop whose
        // alignment was kept: a stop that kept odometry's pose corrected nothing.
        let driven_since = self.unaligned + driven;
        let (prior, reach) = odometry_spread(p, driven_since);
        // A correction is plausible within three standard deviations of how far odometry may
        // be off. Never less than a mapped wall's own tolerance.
        let icp = IcpParams {
            max_shift: (3.0 * std::f64::consts::SQRT_2 * reach).max(MIN_PLAUSIBLE_SHIFT),
            max_turn: (3.0 * prior.heading).max(MIN_PLAUSIBLE_TURN),
            ..p.icp
        };
        let mut refined = false;
        let alignment = (!self.map.is_empty()).then(|| {
            let a =
                icp::align(&local.points, &local.normals, odometry, Some(prior), &self.map, &icp);
            let fine = icp::refine(
                &local.points,
                &local.fine_normals,
                &a,
                [&self.fine_map, &self.map],
                &icp,
            );
            refined = fine.is_some();
            fine.unwrap_or(a)
        });
        let aligned = alignment.as_ref().is_none_or(|a| a.fallback.is_none());
        self.unaligned = if aligned { 0.0 } else { driven_since };
        let initial = alignment.as_ref().map_or(*odometry, |a| a.pose);
        let mut own = WallMap::new();
        own.extend(&local.walls);
        own.extend_bridges(&local.bridges);
        let mut fine_own = WallMap::new();
        fine_own.extend(&local.fine_walls);
        fine_own.extend_bridges(&local.bridges);
        // The farthest return: how far the scan reaches.
        let far = local.points.iter().map(|q| q[0].hypot(q[1])).fold(0.0, f64::max);
        let k = self.graph.add_node(initial);
        let mut links = 0;
        if let Some(last) = self.kept.last() {
            // Odometry since the last stop, as sure as its drift over this leg alone.
            let (leg, reach) = odometry_spread(p, driven);
            let sd = [reach.max(leg.position), reach.max(leg.position), leg.heading];
            self.graph.add_edge(Edge {
                from: k - 1,
                to: k,
                measured: last.reported.inverse().compose(odometry),
                information: diagonal(sd),
            });
        }
        if aligned && k > 0 {
            // The map's alignment, tied to the stops whose walls it paired with, each by the
            // information of its own pairs: a match to a single stop that disagrees with it
            // must outweigh it. (Tied to the nearest stop instead, an alignment to walls
            // placed well would carry the error of a nearby stop placed badly, and hold it
            // there against the loop closure that should move it.)
            let (normals, map) = if refined {
                (&local.fine_normals, &self.fine_map)
            } else {
                (&local.normals, &self.map)
            };
            for (owner, information, _) in
                icp::information_by_owner(&local.points, normals, &initial, map, &icp)
            {
                let j = owner as usize;
                if j >= k {
                    continue;
                }
                let from = self.graph.poses()[j];
                self.graph.add_edge(Edge {
                    from: j,
                    to: k,
                    measured: from.inverse().compose(&initial),
                    information: scaled(in_frame(information, from.theta), 1.0 / LINK_INFLATION),
                });
            }
            links = self.link(k, &local, far, &initial, &icp);
        }
        self.graph.optimize(GRAPH_STEPS);
        let estimate = self.graph.poses()[k];
        let placement = self.graph.covariance(k).map_or(0.0, |c| largest_spread(&c));
        self.placement = placement;
        self.kept.push(Kept {
            occluders: occluders(&local.observation, scan.range_max),
            walls: local.walls,
            bridges: local.bridges,
            local: own,
            fine_walls: local.fine_walls,
            fine_local: fine_own,
            aligned,
            reach: far,
            reported: estimate,
            placed: estimate,
        });
        self.place_walls();
        let placing = estimate.placing();
        let place = |q: Point| placing.apply(q);
        let mut observation = local.observation.mapped(place);
        observation.placement = placement;
        Ok(Reading { observation, estimate, alignment, links, placement, cleaning: local.cleaning })
    }

    /// Matches the scan of stop `k` (its returns `points` and their surfaces' `normals`, reaching `far` metres, placed at
    /// `initial` by the map's alignment) to each of the nearest [`MAX_LINKS`] aligned stops
    /// whose reach overlaps its own, alone; every match that converged on [`LINK_MIN_PAIRS`]
    /// pairs becomes an edge. Returns how many did.
    fn link(
        &mut self,
        k: usize,
        scan: &super::ingest::Ingested,
        far: f64,
        initial: &Pose,
        icp: &IcpParams,
    ) -> usize {
        let poses = self.graph.poses();
        let mut near: Vec<(f64, usize)> = self
            .kept
            .iter()
            .enumerate()
            .filter(|(_, s)| s.aligned)
            .map(|(j, s)| {
                let d = (poses[j].x - initial.x).hypot(poses[j].y - initial.y);
                (d, j, s.reach)
            })
            .filter(|&(d, _, r)| d <= r + far)
            .map(|(d, j, _)| (d, j))
            .collect();
        near.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        near.truncate(MAX_LINKS);
        // The graph as odometry alone leaves it: each match is tried on it alone, then the
        // matches are added from the one that strains the graph least, each kept only when the
        // graph can meet it together with those kept before it. A wrong match (a scan slid
        // along one stop's walls) strains the measurements the graph already holds.
        let mut graph = self.graph.clone();
        graph.optimize(GRAPH_STEPS);
        let base = graph.error();
        let mut tried: Vec<(f64, Edge)> = Vec::new();
        // One stop's walls: another place along them is found as readily, so no search.
        let single = IcpParams { search_span: 0.0, ..*icp };
        for (_, j) in near {
            let from = self.graph.poses()[j];
            let stop = &self.kept[j];
            let start = from.inverse().compose(initial);
            let (points, normals) = (&scan.points, &scan.normals);
            let a = icp::align(points, normals, &start, Some(LINK_PRIOR), &stop.local, &single);
            if a.fallback.is_some() || !a.converged || a.pairs < LINK_MIN_PAIRS {
                continue;
            }
            let fine = icp::refine(
                points,
                &scan.fine_normals,
                &a,
                [&stop.fine_local, &stop.local],
                &single,
            );
            let information = match &fine {
                Some(f) => {
                    icp::information(points, &scan.fine_normals, &f.pose, &stop.fine_local, icp)
                }
                None => icp::information(points, normals, &a.pose, &stop.local, icp),
            };
            let a = fine.unwrap_or(a);
            let edge = Edge {
                from: j,
                to: k,
                measured: a.pose,
                information: scaled(information, 1.0 / LINK_INFLATION),
            };
            let mut trial = graph.clone();
            trial.add_edge(edge);
            trial.optimize(GRAPH_STEPS);
            let strain = trial.error() - base;
            if strain <= LINK_STRAIN {
                tried.push((strain, edge));
            }
        }
        tried.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.from.cmp(&b.1.from)));
        let mut links = 0;
        let mut error = base;
        for (_, edge) in tried {
            let mut trial = graph.clone();
            trial.add_edge(edge);
            trial.optimize(GRAPH_STEPS);
            let e = trial.error();
            if e - error <= LINK_STRAIN {
                (graph, error) = (trial, e);
                links += 1;
            }
        }
        self.graph = graph;
        links
    }

    /// Puts the newest stop's walls in the map; when the graph moved an earlier stop by more
    /// than [`REBUILD`], rebuilds the map from every aligned stop at its pose, oldest first.
    fn place_walls(&mut self) {
        let poses = self.graph.poses();
        let moved = self.kept.iter().zip(poses).any(|(s, p)| {
            s.aligned
                && ((s.placed.x - p.x).hypot(s.placed.y - p.y) > REBUILD
                    || wrap(s.placed.theta - p.theta).abs() > REBUILD_TURN)
        });
        let place = |map: &mut (WallMap, WallMap, WallMap), k: usize, s: &Kept, at: &Pose| {
            let placed = |w: &[[Point; 2]]| -> Vec<[Point; 2]> {
                let at = at.placing();
                w.iter().map(|w| [at.apply(w[0]), at.apply(w[1])]).collect()
            };
            let (walls, bridges) = (placed(&s.walls), placed(&s.bridges));
            map.0.extend_unseen(&walls, &bridges, MAP_PIECE, MAP_SAME_WALL, k as u32);
            map.1.extend(&placed(&s.occluders));
            map.2.extend_unseen(
                &placed(&s.fine_walls),
                &bridges,
                MAP_PIECE,
                MAP_SAME_WALL,
                k as u32,
            );
        };
        let mut maps = (
            std::mem::take(&mut self.map),
            std::mem::take(&mut self.occluders),
            std::mem::take(&mut self.fine_map),
        );
        if moved {
            maps = (WallMap::new(), WallMap::new(), WallMap::new());
            for (k, (s, p)) in self.kept.iter_mut().zip(poses).enumerate() {
                if s.aligned {
                    s.placed = *p;
                    place(&mut maps, k, s, p);
                }
            }
        } else if let Some(s) = self.kept.last().filter(|s| s.aligned) {
            place(&mut maps, self.kept.len() - 1, s, &s.placed);
        }
        (self.map, self.occluders, self.fine_map) = maps;
    }
}

/// The longest gap between two returns taken as an occluder, metres ([`occluders`]).
const OCCLUDER_GAP: f64 = 2.0;

/// Three returns lie on one line when the middle one is within this of the line through
/// the others, metres ([`occluders`]).
const OCCLUDER_LINE: f64 = 0.1;

/// What in a scan's region (in its scanner's frame, reaching `range_max`) may hide a wall
/// from another place, for [`icp::predict`]: every piece of its boundary along returns, and
/// the windows of a surface seen too sparsely for a wall of the map (a shelf's face seen at
/// a grazing angle from far away, whose returns fall a beam apart, each alone): a window
/// between two returns at most [`OCCLUDER_GAP`] apart whose next or previous window runs
/// on along its line to a third return ([`OCCLUDER_LINE`]). A window out to no return, an
/// occluding corner's window alone, and a range frontier hide nothing seen.
fn occluders(observation: &PolygonObservation, range_max: f64) -> Vec<[Point; 2]> {
    let at = observation.region.viewpoint;
    let boundary = &observation.region.boundary;
    let returned = |p: Point| (p[0] - at[0]).hypot(p[1] - at[1]) < range_max * (1.0 - 1e-6);
    let gap = |k: usize| match boundary[k] {
        BoundaryPiece::Window { from, to, .. }
            if returned(from)
                && returned(to)
                && (to[0] - from[0]).hypot(to[1] - from[1]) <= OCCLUDER_GAP =>
        {
            Some([from, to])
        }
        _ => None,
    };
    let n = boundary.len();
    let on_line = |a: [Point; 2], b: [Point; 2]| {
        let (p, q, r) = (a[0], a[1], b[1]);
        let (dx, dy) = (r[0] - p[0], r[1] - p[1]);
        let l = dx.hypot(dy);
        l > 0.0
            && ((q[0] - p[0]) * dy - (q[1] - p[1]) * dx).abs() / l <= OCCLUDER_LINE
            && (q[0] - p[0]) * dx + (q[1] - p[1]) * dy > 0.0
            && (r[0] - q[0]) * dx + (r[1] - q[1]) * dy > 0.0
    };
    (0..n)
        .filter_map(|k| match boundary[k] {
            BoundaryPiece::Wall { from, to } => Some([from, to]),
            BoundaryPiece::Window { .. } => {
                let w = gap(k)?;
                let before = gap((k + n - 1) % n).is_some_and(|v| v[1] == w[0] && on_line(v, w));
                let after = gap((k + 1) % n).is_some_and(|v| w[1] == v[0] && on_line(w, v));
                (before || after).then_some(w)
            }
            _ => None,
        })
        .collect()
}

/// The standard deviation of a position along its least sure direction, metres: the square
/// root of the larger eigenvalue of the covariance's position block.
fn largest_spread(c: &[[f64; 3]; 3]) -> f64 {
    let (a, b, d) = (c[0][0], c[0][1], c[1][1]);
    let mean = f64::midpoint(a, d);
    let half = (f64::midpoint(a, -d)).hypot(b);
    (mean + half).max(0.0).sqrt()
}

/// An information matrix from standard deviations per axis.
fn diagonal(sd: [f64; 3]) -> Information {
    let mut m = [[0.0; 3]; 3];
    for (k, s) in sd.iter().enumerate() {
        m[k][k] = 1.0 / s.max(1e-9).powi(2);
    }
    m
}

/// `m` (information about an error in the map frame) about the same error in the frame of a
/// pose turned by `theta`: `Rᵀ m R`, with `R` turning the position block by `theta`.
fn in_frame(m: Information, theta: f64) -> Information {
    let (c, s) = (theta.cos(), theta.sin());
    let r = [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]];
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            (0..3).map(|a| (0..3).map(|b| r[a][i] * m[a][b] * r[b][j]).sum::<f64>()).sum()
        })
    })
}

/// How far odometry may be off after driving `metres`: one standard deviation of its position
/// (per axis) and heading error, at least [`MIN_PRIOR`]; and the reach of its position error
/// with the heading error made on the way turning every metre after it (about
/// `heading_drift · d² / 2` across the direction of travel, for a trip of several legs).
fn odometry_spread(p: &MapperParams, metres: f64) -> (Prior, f64) {
    let heading = p.heading_drift * metres;
    let reach = (p.drift * metres).hypot(heading * metres / 2.0);
    let prior = Prior {
        position: (p.drift * metres).max(MIN_PRIOR.position),
        heading: heading.max(MIN_PRIOR.heading),
    };
    (prior, reach)
}

/// `m` times `f`.
fn scaled(m: Information, f: f64) -> Information {
    m.map(|row| row.map(|v| v * f))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algorithm::visibility::VisibilityRegion;

    fn window(from: Point, to: Point) -> BoundaryPiece {
        let d = |p: Point| p[0].hypot(p[1]);
        let (reflex, far) = if d(from) <= d(to) { (from, to) } else { (to, from) };
        BoundaryPiece::Window { from, to, reflex, far }
    }

    #[test]
    fn a_face_seen_one_return_at_a_time_occludes_and_an_occluding_corner_does_not() {
        // Returns a beam apart along a face at y = 3 seen at a grazing angle (x = 6, 7,
        // 8, 9.5), then a corner's window out to a wall behind it, a window out to no
        // return at the range (20 m), a range frontier and a wall.
        let face = [[6.0, 3.0], [7.0, 3.02], [8.0, 3.0], [9.5, 3.01]];
        let boundary = vec![
            BoundaryPiece::Wall { from: [5.0, -1.0], to: face[0] },
            window(face[0], face[1]),
            window(face[1], face[2]),
            window(face[2], face[3]),
            // The face ends: its last return to a wall 1.5 m behind (an occluding corner).
            window(face[3], [9.5, 4.5]),
            BoundaryPiece::Wall { from: [9.5, 4.5], to: [-2.0, 4.5] },
            window([-2.0, 4.5], [-19.0, 5.0]),
            BoundaryPiece::Frontier { from: [-19.0, 5.0], to: [-18.0, -7.0] },
            window([-18.0, -7.0], [5.0, -1.0]),
        ];
        let polygon = boundary.iter().map(|b| b.ends().0).collect();
        let region = VisibilityRegion { viewpoint: [0.0, 0.0], polygon, boundary };
        let o = occluders(&PolygonObservation::new([0.0, 0.0], region), 20.0);
        let has = |a: Point, b: Point| o.contains(&[a, b]);
        // The face's three gaps, each on one line with the next or the one before.
        assert!(has(face[0], face[1]) && has(face[1], face[2]) && has(face[2], face[3]), "{o:?}");
        // The walls.
        assert!(has([5.0, -1.0], face[0]) && has([9.5, 4.5], [-2.0, 4.5]), "{o:?}");
        // Not the corner's window (it turns off the face's line), nor the long window, the
        // frontier, or the window from the range back to a return.
        assert_eq!(o.len(), 5, "{o:?}");
    }
}
