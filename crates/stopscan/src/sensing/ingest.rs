//! One laser scan and its pose become the observation strategies consume: a star-shaped
//! region with labelled walls, windows and range frontiers.
//!
//! 1. **Cleaning** (ROS REP 117). A finite range in `[range_min, range_max)` is a return;
//!    `+inf`, and a finite range at or beyond `range_max`, is no return: open space up to
//!    `range_max`; `-inf` is an object nearer than `range_min`, taken as a return at
//!    `range_min`; `NaN` and a finite range below `range_min` are erroneous (dropouts). A
//!    dropout takes the nearer of its nearest valid neighbours on either side: it claims no
//!    free space that a neighbour did not see. An isolated return (one beam, both neighbours
//!    farther by more than the breakpoint threshold and agreeing with each other) is taken as
//!    spurious (dust, a mixed pixel) and replaced by its neighbours: a feature narrower than
//!    two beams is below the sensor's resolution.
//! 2. **Breakpoints** (Borges and Aldon's adaptive breakpoint detector). Neighbouring returns
//!    `r` and `r'` belong to one surface when `|r − r'| ≤ r · sin Δφ / sin(λ − Δφ) + 3σ`,
//!    with `Δφ` the beam spacing, `λ` the shallowest incidence a surface is seen at, and `σ`
//!    the range noise; or when each lies on the line fitted to the returns before and after
//!    the other, no more than `bridge` apart (a wall seen at a grazing angle, as down a
//!    corridor: an occlusion puts the far return off the near surface's line, and a longer
//!    gap may hide a door no beam went through). A break between returns is a **window**, from one end to the other,
//!    with the nearer end as its occluding corner; a break between a return and no return is
//!    a window too, out to `range_max`; neighbouring beams without return are joined by
//!    **range frontiers** (chords at `range_max`).
//! 3. **Walls** (split-and-merge). Each run of returns on one surface is split recursively at
//!    the point farthest from the chord of its ends while that distance exceeds the split
//!    tolerance; each piece gets a least-squares line (orthogonal regression), and
//!    neighbouring pieces whose joint fit stays within the tolerance are merged again. The
//!    region's vertices are the runs' ends projected along their beams onto the fitted lines
//!    and the corners where fitted lines meet. The runs are fitted a second time at a finer
//!    tolerance ([`IngestParams::fine_split`]), for refining scan matches only.
//!
//! Every vertex lies on its beam's ray (a corner, strictly between the rays of its
//! neighbours), in the order of the beams, so the region is star-shaped from the scanner and
//! simple; a scanner that does not sweep a full turn adds its own position as a vertex, with
//! the two sides of the unseen sector as range frontiers.

use crate::algorithm::visibility::{BoundaryPiece, VisibilityRegion};
use crate::kernel::Point;
use crate::protocol::laser::{InvalidScan, LaserScan, Pose};
use crate::protocol::polygon::PolygonObservation;

/// A fitted wall is evidence for scan matching ([`Ingested::walls`]) when at least this many
/// returns lie on it. The line through two neighbouring returns alone may join two surfaces
/// around a corner seen from far away (a shelf's front and its side, 0.25 m apart at 13 m):
/// another stop's returns on either surface would pair with a wall at the wrong slant. See
/// [`NORMAL_AGREEMENT`](super::icp::NORMAL_AGREEMENT) for what the two rules did.
pub const MIN_WALL_RETURNS: usize = 3;

/// How scans are read: the sensor's noise and the segmentation's thresholds.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct IngestParams {
    /// The range noise σ the breakpoint and split thresholds allow for, metres.
    pub sigma: f64,
    /// The breakpoint detector's λ: the shallowest angle between a beam and a surface at
    /// which neighbouring returns still count as one surface, radians (default 10°).
    pub lambda: f64,
    /// Split-and-merge's tolerance: the largest distance of a return from its wall line,
    /// metres (default `max(3σ, 0.03)`).
    pub split: f64,
    /// Whether isolated single-beam returns are removed as spurious.
    pub despeckle: bool,
    /// The longest gap between neighbouring returns on one line that is read as wall, metres:
    /// a longer one may hide an opening no beam went through (a door seen down a corridor),
    /// so it is left as a window (the shortest window worth a trip is a good value).
    pub bridge: f64,
}

impl IngestParams {
    /// The defaults for a sensor with range noise `sigma`.
    pub fn for_noise(sigma: f64) -> Self {
        Self {
            sigma,
            lambda: 10f64.to_radians(),
            split: (3.0 * sigma).max(0.03),
            despeckle: true,
            bridge: 0.4,
        }
    }

    /// The tolerance of the finer fit for refining alignments ([`Ingested::fine_walls`]):
    /// `max(1.5σ, 3 cm)`, at most [`IngestParams::split`].
    pub fn fine_split(&self) -> f64 {
        (1.5 * self.sigma).max(0.03).min(self.split)
    }

    /// These parameters with gaps on a wall line up to `min_window` (the shortest window worth
    /// a trip) read as wall too: no door the robot would drive to hides in a shorter one.
    #[must_use]
    pub fn bridging(self, min_window: f64) -> Self {
        Self { bridge: self.bridge.max(min_window), ..self }
    }
}

impl Default for IngestParams {
    fn default() -> Self {
        Self::for_noise(0.02)
    }
}

/// What cleaning did to a scan's beams.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Cleaning {
    /// Beams in the scan.
    pub beams: usize,
    /// Returns used as they came.
    pub returns: usize,
    /// Beams without return (`+inf`, or at or beyond `range_max`).
    pub no_return: usize,
    /// `-inf` beams, taken as returns at `range_min`.
    pub too_close: usize,
    /// `NaN` beams and finite ranges below `range_min`, filled from their neighbours.
    pub dropouts: usize,
    /// Isolated returns removed as spurious.
    pub spurious: usize,
}

/// A scan read into an observation.
#[derive(Debug, Clone, PartialEq)]
pub struct Ingested {
    /// The region, in the frame the pose is given in.
    pub observation: PolygonObservation,
    /// The returns after cleaning, in the same frame (for scan matching).
    pub points: Vec<Point>,
    /// Each return's surface normal in the same frame (a unit vector, either way round), from
    /// the wall fitted through it: `None` at a corner between two walls, or for a return
    /// alone. Scan matching pairs a return only with a wall that runs as its own surface
    /// does.
    pub normals: Vec<Option<Point>>,
    /// The fitted wall segments, in the same frame: those fitted to at least
    /// [`MIN_WALL_RETURNS`] returns (the region's boundary has the others too).
    pub walls: Vec<[Point; 2]>,
    /// The walls fitted again at [`IngestParams::fine_split`] (those on at least
    /// [`MIN_WALL_RETURNS`] returns), for refining an alignment: walls traced from an
    /// occupancy grid have steps of a cell, which a line fitted at three σ cuts through,
    /// tilted toward the side its scan saw more of.
    pub fine_walls: Vec<[Point; 2]>,
    /// Each return's surface normal from the fine walls, as [`Ingested::normals`].
    pub fine_normals: Vec<Option<Point>>,
    /// Gaps longer than [`IngestParams::bridge`] between returns on one wall line (left as
    /// windows in the region, since an opening may hide there), as segments between the two
    /// returns: evidence of the line for scan matching, not of a wall.
    pub bridges: Vec<[Point; 2]>,
    /// What cleaning did.
    pub cleaning: Cleaning,
}

/// Why a scan could not be read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum IngestError {
    /// The scan's fields are invalid.
    #[error(transparent)]
    Scan(#[from] InvalidScan),
    /// The pose is not finite.
    #[error("field `pose`: every coordinate must be finite, got {0:?}")]
    Pose(Pose),
    /// No beam holds a valid measurement.
    #[error("field `ranges`: no beam holds a valid measurement (all NaN or below range_min)")]
    NoValidBeam,
}

/// A beam after cleaning.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Beam {
    Hit(f64),
    Open,
    Unknown,
}

/// How many returns on each side of a break are fitted to test whether the wall continues.
const LINE_POINTS: usize = 4;

/// The nearest a vertex may be to the scanner, metres (a return at range 0 would put a
/// vertex on the viewpoint).
const MIN_RADIUS: f64 = 1e-3;

/// Reads one scan taken at `pose` (the scanner's pose in the map frame).
///
/// # Errors
/// [`IngestError`]: invalid scan fields (named), a non-finite pose, or no valid beam.
pub fn ingest(
    scan: &LaserScan,
    pose: &Pose,
    params: &IngestParams,
) -> Result<Ingested, IngestError> {
    scan.validate()?;
    if !pose.is_finite() {
        return Err(IngestError::Pose(*pose));
    }
    let n = scan.ranges.len();
    // Beams in counter-clockwise order.
    let order: Vec<usize> =
        if scan.angle_increment > 0.0 { (0..n).collect() } else { (0..n).rev().collect() };
    let (beams, mut cleaning) = classify(scan, &order);
    let mut b = Beams {
        kinds: beams,
        dirs: order.iter().map(|&i| [scan.angle(i).cos(), scan.angle(i).sin()]).collect(),
        full: scan.is_full_turn(),
        range_max: scan.range_max,
        dphi: scan.angle_increment.abs(),
        params,
    };
    let range_of = |x: Beam| b.range_of(x);
    let mut filled = b.kinds.clone();
    fill_dropouts(&mut filled, b.full, range_of)?;
    if params.despeckle {
        cleaning.spurious = despeckle(&mut filled, b.full, |r| b.gap(r), range_of);
    }
    b.kinds = filled;
    cleaning.returns -= cleaning.spurious.min(cleaning.returns);
    let t = b.trace();
    let placing = pose.placing();
    let to_map = |p: Point| placing.apply(p);
    let at = pose.at();
    let polygon: Vec<Point> = t.verts.iter().map(|v| to_map(v.0)).collect();
    let m = polygon.len();
    let boundary = (0..m)
        .map(|i| {
            let (from, to) = (polygon[i], polygon[(i + 1) % m]);
            match t.verts[i].1 {
                Piece::Wall => BoundaryPiece::Wall { from, to },
                Piece::Frontier => BoundaryPiece::Frontier { from, to },
                Piece::Break => {
                    let d = |p: Point| (p[0] - at[0]).hypot(p[1] - at[1]);
                    let (reflex, far) = if d(from) <= d(to) { (from, to) } else { (to, from) };
                    BoundaryPiece::Window { from, to, reflex, far }
                }
            }
        })
        .collect();
    let segments =
        |v: Vec<[Point; 2]>| v.into_iter().map(|w| [to_map(w[0]), to_map(w[1])]).collect();
    Ok(Ingested {
        observation: PolygonObservation::new(
            at,
            VisibilityRegion { viewpoint: at, polygon, boundary },
        ),
        points: t.points.into_iter().map(to_map).collect(),
        normals: t.normals.into_iter().map(|n| n.map(|n| pose.turn(n))).collect(),
        walls: segments(t.walls),
        fine_walls: segments(t.fine_walls),
        fine_normals: t.fine_normals.into_iter().map(|n| n.map(|n| pose.turn(n))).collect(),
        bridges: segments(t.bridges),
        cleaning,
    })
}

/// Each beam's reading under REP 117, in the order given, and the counts.
fn classify(scan: &LaserScan, order: &[usize]) -> (Vec<Beam>, Cleaning) {
    let mut cleaning = Cleaning { beams: order.len(), ..Cleaning::default() };
    let beams = order
        .iter()
        .map(|&i| {
            let r = scan.ranges[i];
            if r.is_nan() || (r.is_finite() && r < scan.range_min) {
                cleaning.dropouts += 1;
                Beam::Unknown
            } else if r == f64::NEG_INFINITY {
                cleaning.too_close += 1;
                Beam::Hit(scan.range_min.max(MIN_RADIUS))
            } else if r >= scan.range_max {
                cleaning.no_return += 1;
                Beam::Open
            } else {
                cleaning.returns += 1;
                Beam::Hit(r.max(MIN_RADIUS))
            }
        })
        .collect();
    (beams, cleaning)
}

/// A scan's beams after cleaning, counter-clockwise, in the scanner's frame.
struct Beams<'a> {
    kinds: Vec<Beam>,
    /// Each beam's unit direction.
    dirs: Vec<Point>,
    full: bool,
    range_max: f64,
    dphi: f64,
    params: &'a IngestParams,
}

/// What tracing the beams gives, in the scanner's frame.
struct Traced {
    /// Vertices with the kind of piece that leaves each one.
    verts: Vec<(Point, Piece)>,
    walls: Vec<[Point; 2]>,
    fine_walls: Vec<[Point; 2]>,
    bridges: Vec<[Point; 2]>,
    points: Vec<Point>,
    normals: Vec<Option<Point>>,
    fine_normals: Vec<Option<Point>>,
}

impl Beams<'_> {
    fn n(&self) -> usize {
        self.kinds.len()
    }

    fn range_of(&self, b: Beam) -> f64 {
        match b {
            Beam::Hit(r) => r,
            _ => self.range_max,
        }
    }

    /// The breakpoint threshold at range `r`.
    fn gap(&self, r: f64) -> f64 {
        let p = self.params;
        r * self.dphi.sin() / (p.lambda - self.dphi).sin().max(1e-9) + 3.0 * p.sigma
    }

    fn point(&self, k: usize) -> Point {
        let (u, r) = (self.dirs[k], self.range_of(self.kinds[k]));
        [r * u[0], r * u[1]]
    }

    fn is_hit(&self, k: usize) -> bool {
        matches!(self.kinds[k], Beam::Hit(_))
    }

    /// Beam `k`'s return (cyclically on a full turn), if it has one.
    fn hit_at(&self, k: isize) -> Option<Point> {
        let n = self.n();
        let k =
            if self.full { k.rem_euclid(n as isize) as usize } else { usize::try_from(k).ok()? };
        (k < n && self.is_hit(k)).then(|| self.point(k))
    }

    /// Whether each of the returns `a` and `b` lies on the line fitted to the returns before
    /// and after the other (a wall seen at a grazing angle: an occlusion puts the far return
    /// off the near surface's line).
    fn continues(&self, a: usize, b: usize) -> bool {
        let tol = 3.0 * self.params.sigma + 0.01;
        let side = |from: isize, step: isize, other: Point| {
            let pts: Vec<Point> =
                (0..LINE_POINTS as isize).map_while(|i| self.hit_at(from + step * i)).collect();
            pts.len() >= 2 && {
                let l = fit_line(&pts);
                pts.iter().all(|p| l.distance(*p) <= tol) && l.distance(other) <= tol
            }
        };
        side(a as isize, -1, self.point(b)) && side(b as isize, 1, self.point(a))
    }

    /// Whether neighbouring beams `a` and `b` are returns from one surface: the breakpoint
    /// test, or a wall that continues across a gap of at most `bridge`.
    fn joined(&self, a: usize, b: usize) -> bool {
        match (self.kinds[a], self.kinds[b]) {
            (Beam::Hit(x), Beam::Hit(y)) => {
                (x - y).abs() <= self.gap(x.min(y)) || {
                    let (pa, pb) = (self.point(a), self.point(b));
                    (pb[0] - pa[0]).hypot(pb[1] - pa[1]) <= self.params.bridge
                        && self.continues(a, b)
                }
            }
            _ => false,
        }
    }

    /// Where tracing starts (after a break on a full turn, so that no run wraps) and the runs
    /// of returns on one surface, `[start, end]` in beam order (ends may pass `n`).
    fn runs(&self) -> (usize, Vec<(usize, usize)>) {
        let n = self.n();
        let start = if self.full {
            (0..n).find(|&k| !self.joined((k + n - 1) % n, k)).unwrap_or(0)
        } else {
            0
        };
        let mut runs = Vec::new();
        let mut k = 0;
        while k < n {
            if !self.is_hit((start + k) % n) {
                k += 1;
                continue;
            }
            let mut len = 1;
            while k + len < n && self.joined((start + k + len - 1) % n, (start + k + len) % n) {
                len += 1;
            }
            runs.push((start + k, start + k + len - 1));
            k += len;
        }
        (start, runs)
    }

    /// The region's vertices and pieces, the walls fitted, the long gaps on wall lines and
    /// the returns.
    fn trace(&self) -> Traced {
        let n = self.n();
        let (start, runs) = self.runs();
        let mut t = Traced {
            verts: Vec::new(),
            walls: Vec::new(),
            fine_walls: Vec::new(),
            bridges: Vec::new(),
            points: Vec::new(),
            normals: Vec::new(),
            fine_normals: Vec::new(),
        };
        // A full turn all on one surface closes on itself: its last piece is a wall too.
        let closed = self.full
            && runs.len() == 1
            && self.joined(n - 1, 0)
            && runs[0] == (start, start + n - 1);
        let mut run_at = runs.iter().peekable();
        let mut k = start;
        while k < start + n {
            let b = k % n;
            if let Some(&&(s, e)) = run_at.peek()
                && s == k
            {
                run_at.next();
                self.trace_run(s, e, closed, &mut t);
                k = e + 1;
                continue;
            }
            // A beam without return: a range frontier to the next beam if it has none either.
            let next_open = k + 1 < start + n || self.full;
            let open = |j: usize| self.kinds[j] == Beam::Open;
            let kind = if next_open && open(b) && open((b + 1) % n) {
                Piece::Frontier
            } else {
                Piece::Break
            };
            t.verts.push((self.point(b), kind));
            k += 1;
        }
        if !self.full {
            // The unseen sector: back to the scanner and out again, as range frontiers.
            if let Some(l) = t.verts.last_mut() {
                l.1 = Piece::Frontier;
            }
            t.verts.push(([0.0, 0.0], Piece::Frontier));
        }
        t
    }

    /// One run of returns `s..=e` (beam order, ends may pass `n`): its fitted walls, and a
    /// bridge to the next run when a long gap on one line separates them.
    fn trace_run(&self, s: usize, e: usize, closed: bool, t: &mut Traced) {
        let n = self.n();
        let idx: Vec<usize> = (s..=e).map(|j| j % n).collect();
        let pts: Vec<Point> = idx.iter().map(|&j| self.point(j)).collect();
        t.points.extend(&pts);
        let dirs: Vec<Point> = idx.iter().map(|&j| self.dirs[j]).collect();
        let Fit { vertices: vs, support, normals } =
            fit_run(&pts, &dirs, self.params.split, self.params.sigma);
        let fine = self.params.fine_split();
        if fine < self.params.split {
            let f = fit_run(&pts, &dirs, fine, self.params.sigma);
            t.fine_normals.extend(f.normals);
            t.fine_walls.extend(wall_pieces(&f.vertices, &f.support, closed));
        } else {
            t.fine_normals.extend(&normals);
            t.fine_walls.extend(wall_pieces(&vs, &support, closed));
        }
        t.normals.extend(normals);
        let last = vs.len() - 1;
        for (i, &v) in vs.iter().enumerate() {
            let wall = i < last || closed;
            t.verts.push((v, if wall { Piece::Wall } else { Piece::Break }));
        }
        t.walls.extend(wall_pieces(&vs, &support, closed));
        // A long gap to the next run on the same line: evidence for scan matching.
        let (a, b) = (e % n, (e + 1) % n);
        if (e + 1 < n || self.full)
            && self.is_hit(a)
            && self.is_hit(b)
            && !self.joined(a, b)
            && self.continues(a, b)
        {
            t.bridges.push([self.point(a), self.point(b)]);
        }
    }
}

/// The walls for scan matching among a run's fitted pieces (its vertices `vs`, each piece's
/// `support`; the last vertex joins the first when the run is `closed`): a piece fitted to
/// two returns is the region's boundary, but no evidence of a wall.
fn wall_pieces(vs: &[Point], support: &[usize], closed: bool) -> Vec<[Point; 2]> {
    let last = vs.len() - 1;
    (0..vs.len())
        .filter(|&i| {
            (i < last || closed) && support.get(i).copied().unwrap_or(2) >= MIN_WALL_RETURNS
        })
        .map(|i| [vs[i], vs[(i + 1) % vs.len()]])
        .collect()
}

/// The piece that leaves a vertex.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Piece {
    Wall,
    Frontier,
    Break,
}

/// Fills each dropout with the nearer of its nearest valid neighbours on either side (one
/// side only at the ends of a scan that is not a full turn).
fn fill_dropouts(
    beams: &mut [Beam],
    full: bool,
    range_of: impl Fn(Beam) -> f64,
) -> Result<(), IngestError> {
    let n = beams.len();
    if beams.iter().all(|b| *b == Beam::Unknown) {
        return Err(IngestError::NoValidBeam);
    }
    let src = beams.to_vec();
    let find = |k: usize, step: isize| -> Option<Beam> {
        let mut j = k as isize;
        for _ in 0..n {
            j += step;
            if !full && (j < 0 || j >= n as isize) {
                return None;
            }
            let b = src[j.rem_euclid(n as isize) as usize];
            if b != Beam::Unknown {
                return Some(b);
            }
        }
        None
    };
    for k in 0..n {
        if src[k] == Beam::Unknown {
            let (l, r) = (find(k, -1), find(k, 1));
            beams[k] = match (l, r) {
                (Some(a), Some(b)) => {
                    if range_of(a) <= range_of(b) {
                        a
                    } else {
                        b
                    }
                }
                (Some(a), None) | (None, Some(a)) => a,
                (None, None) => unreachable!("some beam is valid"),
            };
        }
    }
    Ok(())
}

/// Replaces isolated returns (both neighbours farther by more than `gap` and agreeing with
/// each other) by the nearer neighbour; returns how many.
fn despeckle(
    beams: &mut [Beam],
    full: bool,
    gap: impl Fn(f64) -> f64,
    range_of: impl Fn(Beam) -> f64,
) -> usize {
    let n = beams.len();
    let src = beams.to_vec();
    let mut count = 0;
    for k in 0..n {
        if !full && (k == 0 || k == n - 1) {
            continue;
        }
        let Beam::Hit(r) = src[k] else { continue };
        let (a, b) = (src[(k + n - 1) % n], src[(k + 1) % n]);
        let (ra, rb) = (range_of(a), range_of(b));
        let g = gap(r);
        if ra > r + g && rb > r + g && (ra - rb).abs() <= gap(ra.min(rb)) {
            beams[k] = if ra <= rb { a } else { b };
            count += 1;
        }
    }
    count
}

/// Split-and-merge at tolerance `split` over one run of returns `pts` (on the rays `dirs`,
/// with range noise `sigma`): the run's vertices, its ends projected along their rays onto
/// the fitted lines and corners where lines meet.
fn fit_run(pts: &[Point], dirs: &[Point], split: f64, sigma: f64) -> Fit {
    let n = pts.len();
    if n == 1 {
        return Fit { vertices: vec![pts[0]], support: Vec::new(), normals: vec![None] };
    }
    // Split.
    let mut cuts = vec![0, n - 1];
    let mut stack = vec![(0, n - 1)];
    while let Some((a, b)) = stack.pop() {
        if b <= a + 1 {
            continue;
        }
        let (p, q) = (pts[a], pts[b]);
        let far = (a + 1..b)
            .map(|i| (i, crate::geometry::segment_distance(pts[i], p, q)))
            .fold((a, -1.0), |m, x| if x.1 > m.1 { x } else { m });
        if far.1 > split {
            cuts.push(far.0);
            stack.push((a, far.0));
            stack.push((far.0, b));
        }
    }
    cuts.sort_unstable();
    // Merge neighbours whose joint fit stays within the tolerance.
    let mut i = 1;
    while i + 1 < cuts.len() {
        let (a, b) = (cuts[i - 1], cuts[i + 1]);
        let line = fit_line(&pts[a..=b]);
        if pts[a..=b].iter().all(|p| line.distance(*p) <= split) {
            cuts.remove(i);
        } else {
            i += 1;
        }
    }
    let lines: Vec<Line> = cuts.windows(2).map(|w| fit_line(&pts[w[0]..=w[1]])).collect();
    let tol = (4.0 * sigma).max(split);
    let onto = |k: usize, l: &Line| l.along_ray(dirs[k], pts[k], tol).unwrap_or(pts[k]);
    let mut out = vec![onto(0, &lines[0])];
    for (j, &c) in cuts.iter().enumerate().skip(1).take(cuts.len() - 2) {
        let (l0, l1) = (&lines[j - 1], &lines[j]);
        let corner = l0.meet(l1).filter(|x| {
            let d = (x[0] - pts[c][0]).hypot(x[1] - pts[c][1]);
            d <= tol && strictly_between(dirs[c - 1], *x, dirs[c + 1])
        });
        out.push(corner.unwrap_or_else(|| {
            let (a, b) = (onto(c, l0), onto(c, l1));
            [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])]
        }));
    }
    out.push(onto(n - 1, &lines[lines.len() - 1]));
    let support = cuts.windows(2).map(|w| w[1] - w[0] + 1).collect();
    // Each return's surface normal: its line's, except at a cut, where two lines meet.
    let mut normals = vec![None; n];
    for (j, w) in cuts.windows(2).enumerate() {
        for (i, slot) in normals.iter_mut().enumerate().take(w[1] + 1).skip(w[0]) {
            let corner = (i == w[0] && j > 0) || (i == w[1] && j + 2 < cuts.len());
            *slot = (!corner).then_some(lines[j].normal);
        }
    }
    Fit { vertices: out, support, normals }
}

/// What split-and-merge makes of one run of returns.
struct Fit {
    /// The run's vertices ([`fit_run`]).
    vertices: Vec<Point>,
    /// How many returns each piece between consecutive vertices was fitted to.
    support: Vec<usize>,
    /// Each return's surface normal (a unit vector, either way round): its fitted line's,
    /// or `None` at a corner between two lines.
    normals: Vec<Option<Point>>,
}

/// Whether the direction of `x` lies strictly between the directions `a` and `b`
/// (counter-clockwise from `a`, less than a half turn).
fn strictly_between(a: Point, x: Point, b: Point) -> bool {
    let cross = |u: Point, v: Point| u[0] * v[1] - u[1] * v[0];
    cross(a, x) > 0.0 && cross(x, b) > 0.0
}

/// A line `normal · p = offset` with a unit normal.
#[derive(Debug, Clone, Copy)]
struct Line {
    normal: Point,
    offset: f64,
}

impl Line {
    fn distance(&self, p: Point) -> f64 {
        (self.normal[0] * p[0] + self.normal[1] * p[1] - self.offset).abs()
    }

    /// Where the ray from the origin along `dir` meets the line, if it does ahead and within
    /// `tol` of the measured point `p`.
    fn along_ray(&self, dir: Point, p: Point, tol: f64) -> Option<Point> {
        let c = self.normal[0] * dir[0] + self.normal[1] * dir[1];
        if c.abs() < 1e-9 {
            return None;
        }
        let t = self.offset / c;
        let x = [t * dir[0], t * dir[1]];
        (t > MIN_RADIUS && (x[0] - p[0]).hypot(x[1] - p[1]) <= tol).then_some(x)
    }

    /// Where two lines meet, unless they are nearly parallel.
    fn meet(&self, o: &Line) -> Option<Point> {
        let det = self.normal[0] * o.normal[1] - self.normal[1] * o.normal[0];
        if det.abs() < 1e-6 {
            return None;
        }
        Some([
            (self.offset * o.normal[1] - self.normal[1] * o.offset) / det,
            (self.normal[0] * o.offset - self.offset * o.normal[0]) / det,
        ])
    }
}

/// The least-squares line through `pts` (orthogonal regression: the normal is the direction
/// of least spread about the centroid).
fn fit_line(pts: &[Point]) -> Line {
    let (c, d) = crate::geometry::fit_line(pts);
    let normal = [-d[1], d[0]];
    Line { normal, offset: normal[0] * c[0] + normal[1] * c[1] }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{PI, TAU};

    /// A full-turn scan of `n` beams from `angle_min = -π`, with `f(angle)` as the range.
    fn turn(n: usize, f: impl Fn(f64) -> f64) -> LaserScan {
        let inc = TAU / n as f64;
        LaserScan {
            angle_min: -PI,
            angle_increment: inc,
            range_min: 0.05,
            range_max: 20.0,
            ranges: (0..n).map(|i| f(-PI + i as f64 * inc)).collect(),
        }
    }

    /// The range from the origin to the axis-aligned square of half side `h` around it.
    fn square(h: f64) -> impl Fn(f64) -> f64 {
        move |a: f64| h / a.cos().abs().max(a.sin().abs())
    }

    fn area(p: &[Point]) -> f64 {
        crate::geometry::signed_area_of(p)
    }

    #[test]
    fn a_square_room_becomes_four_walls_with_its_corners() {
        let s = turn(720, square(2.0));
        let g = ingest(&s, &Pose::default(), &IngestParams::for_noise(0.0)).unwrap();
        let r = &g.observation.region;
        assert!(r.boundary.iter().all(|b| matches!(b, BoundaryPiece::Wall { .. })));
        assert!((area(&r.polygon) - 16.0).abs() < 1e-6, "{}", area(&r.polygon));
        // Four corners at (±2, ±2), and vertices only where the walls meet or a run starts.
        for c in [[2.0, 2.0], [-2.0, 2.0], [-2.0, -2.0], [2.0, -2.0]] {
            assert!(
                r.polygon.iter().any(|p| (p[0] - c[0]).hypot(p[1] - c[1]) < 1e-6),
                "corner {c:?} missing from {:?}",
                r.polygon
            );
        }
        assert!(r.polygon.len() <= 6, "{:?}", r.polygon);
        assert_eq!(g.cleaning.returns, 720);
    }

    #[test]
    fn rep117_cleaning_fills_dropouts_from_the_nearer_neighbour() {
        let mut s = turn(360, square(2.0));
        s.ranges[10] = f64::NAN;
        s.ranges[11] = 0.01; // below range_min: erroneous
        for r in &mut s.ranges[100..103] {
            *r = f64::NEG_INFINITY;
        }
        s.ranges[200] = 25.0; // beyond range_max: no return
        let g = ingest(&s, &Pose::default(), &IngestParams::for_noise(0.0)).unwrap();
        let c = g.cleaning;
        assert_eq!((c.dropouts, c.too_close, c.no_return), (2, 3, 1));
        // The dropouts lie on a wall: no window there.
        let r = &g.observation.region;
        let windows =
            r.boundary.iter().filter(|b| matches!(b, BoundaryPiece::Window { .. })).count();
        // The too-close returns and the beam without return each break the wall twice.
        assert_eq!(windows, 4, "{:?}", r.boundary);
        // The too-close beam stands at range_min.
        assert!(r.polygon.iter().any(|p| (p[0].hypot(p[1]) - 0.05).abs() < 1e-4));
        // The beam without return reaches range_max, between two windows (frontier-less).
        assert!(r.polygon.iter().any(|p| (p[0].hypot(p[1]) - 20.0).abs() < 1e-9));
    }

    #[test]
    fn a_spurious_return_is_removed_and_a_real_step_is_a_window() {
        let mut s = turn(720, square(3.0));
        s.ranges[50] = 1.0;
        let g = ingest(&s, &Pose::default(), &IngestParams::for_noise(0.02)).unwrap();
        assert_eq!(g.cleaning.spurious, 1);
        assert!((area(&g.observation.region.polygon) - 36.0).abs() < 0.05);
        // A doorway: beams 300..320 see 3 m farther.
        let mut s = turn(720, square(3.0));
        for r in &mut s.ranges[300..320] {
            *r += 3.0;
        }
        let g = ingest(&s, &Pose::default(), &IngestParams::for_noise(0.02)).unwrap();
        let ws: Vec<_> = g
            .observation
            .region
            .boundary
            .iter()
            .filter_map(|b| match b {
                BoundaryPiece::Window { reflex, far, .. } => Some((*reflex, *far)),
                _ => None,
            })
            .collect();
        assert_eq!(ws.len(), 2);
        for (reflex, far) in ws {
            assert!(reflex[0].hypot(reflex[1]) < far[0].hypot(far[1]));
            assert!((far[0].hypot(far[1]) - reflex[0].hypot(reflex[1]) - 3.0).abs() < 0.1);
        }
    }

    #[test]
    fn open_space_gives_range_frontiers_and_a_partial_turn_closes_at_the_scanner() {
        // A 270° scanner facing a wall 2 m ahead (+x), open elsewhere.
        let n = 541usize;
        let inc = 1.5 * PI / (n - 1) as f64;
        let s = LaserScan {
            angle_min: -0.75 * PI,
            angle_increment: inc,
            range_min: 0.05,
            range_max: 10.0,
            ranges: (0..n)
                .map(|i| {
                    let a = -0.75 * PI + i as f64 * inc;
                    if a.cos() > 0.5 { 2.0 / a.cos() } else { f64::INFINITY }
                })
                .collect(),
        };
        let pose = Pose { x: 5.0, y: -1.0, theta: 0.3 };
        let g = ingest(&s, &pose, &IngestParams::for_noise(0.0)).unwrap();
        let r = &g.observation.region;
        assert!(r.polygon.contains(&[5.0, -1.0]), "the scanner is a vertex");
        assert_eq!(g.observation.at, [5.0, -1.0]);
        let kinds = |f: fn(&BoundaryPiece) -> bool| r.boundary.iter().filter(|b| f(b)).count();
        assert_eq!(kinds(|b| matches!(b, BoundaryPiece::Wall { .. })), 1);
        assert_eq!(kinds(|b| matches!(b, BoundaryPiece::Window { .. })), 2);
        assert!(kinds(|b| matches!(b, BoundaryPiece::Frontier { .. })) > 100);
        assert!(area(&r.polygon) > 0.0, "counter-clockwise");
        // The wall lies 2 m ahead along the heading.
        let w = g.walls[0];
        let ahead = |p: Point| (p[0] - 5.0) * 0.3f64.cos() + (p[1] + 1.0) * 0.3f64.sin();
        assert!((ahead(w[0]) - 2.0).abs() < 1e-6 && (ahead(w[1]) - 2.0).abs() < 1e-6);
    }

    #[test]
    fn a_clockwise_scanner_gives_the_same_region() {
        let ccw = turn(360, square(2.5));
        let mut cw = ccw.clone();
        cw.angle_min = ccw.angle(359);
        cw.angle_increment = -ccw.angle_increment;
        cw.ranges.reverse();
        let p = IngestParams::for_noise(0.0);
        let (a, b) = (
            ingest(&ccw, &Pose::default(), &p).unwrap(),
            ingest(&cw, &Pose::default(), &p).unwrap(),
        );
        assert!(
            (area(&a.observation.region.polygon) - area(&b.observation.region.polygon)).abs()
                < 1e-9
        );
    }

    /// A hall with a shelf whose front steps back by 0.25 m, seen from 14 m away: the step's
    /// side faces away, so the returns jump from the front to the recess between neighbouring
    /// beams, closer than the breakpoint test can tell from a wall seen at a slant.
    fn far_step() -> (crate::geometry::Domain, LaserScan, Pose) {
        let hall = crate::geometry::Domain::new(
            vec![[0.0, 0.0], [30.0, 0.0], [30.0, 16.0], [0.0, 16.0]],
            vec![vec![
                [12.0, 10.0],
                [12.0, 11.0],
                [16.0, 11.0],
                [16.0, 10.25],
                [15.0, 10.25],
                [15.0, 10.0],
            ]],
        )
        .unwrap();
        let at = Pose::new([2.0, 3.0], 0.3);
        let scan = exact_scan(&hall, &at);
        (hall, scan, at)
    }

    /// 720 exact beams from `at` (in its frame), each to the nearest edge of `d` it meets
    /// within 20 m.
    fn exact_scan(d: &crate::geometry::Domain, at: &Pose) -> LaserScan {
        turn(720, |a: f64| {
            let u = [(a + at.theta).cos(), (a + at.theta).sin()];
            d.rings()
                .iter()
                .flat_map(|r| (0..r.len()).map(move |i| [r[i], r[(i + 1) % r.len()]]))
                .filter_map(|e| crate::geometry::ray_segment(at.at(), u, e[0], e[1]))
                .reduce(f64::min)
                .filter(|&t| t < 20.0)
                .unwrap_or(f64::INFINITY)
        })
    }

    /// The unit normal of the domain's edge nearest `p`, and how far `p` is from it.
    fn nearest_edge(d: &crate::geometry::Domain, p: Point) -> (Point, f64) {
        d.rings()
            .iter()
            .flat_map(|r| (0..r.len()).map(move |i| [r[i], r[(i + 1) % r.len()]]))
            .map(|[a, b]| {
                let l = (b[0] - a[0]).hypot(b[1] - a[1]);
                ([(a[1] - b[1]) / l, (b[0] - a[0]) / l], crate::geometry::segment_distance(p, a, b))
            })
            .min_by(|x, y| x.1.total_cmp(&y.1))
            .unwrap()
    }

    #[test]
    fn walls_for_matching_lie_on_three_returns_and_normals_are_their_surfaces() {
        let (hall, scan, at) = far_step();
        let p = IngestParams::for_noise(0.0);
        let g = ingest(&scan, &at, &p).unwrap();
        assert_eq!(g.points.len(), g.normals.len());
        // Every wall handed to scan matching has at least three returns on it (within the
        // split tolerance of the segment, counted from the definition).
        for w in &g.walls {
            let on = g
                .points
                .iter()
                .filter(|q| crate::geometry::segment_distance(**q, w[0], w[1]) <= p.split + 1e-9)
                .count();
            assert!(on >= MIN_WALL_RETURNS, "{w:?} lies on {on} returns");
        }
        // The region's boundary still joins the shelf's front to its recess: a piece of wall
        // between two returns on different surfaces, which matching does not get.
        let joins = g.observation.region.boundary.iter().any(|b| match *b {
            BoundaryPiece::Wall { from, to } => {
                let (n0, d0) = nearest_edge(&hall, from);
                let (n1, d1) = nearest_edge(&hall, to);
                // Both ends on south faces, at different heights: across the step.
                d0 < 1e-6
                    && d1 < 1e-6
                    && (n0[0] * n1[0] + n0[1] * n1[1]) > 0.99
                    && (0.2..0.3).contains(&(from[1] - to[1]).abs())
            }
            _ => false,
        });
        assert!(joins, "no boundary piece across the step: the test would prove nothing");
        // From the front (y = 10) to the recess (y = 10.25), slanting across the step.
        let across = |w: &[Point; 2]| {
            let (dx, dy) = ((w[0][0] - w[1][0]).abs(), (w[0][1] - w[1][1]).abs());
            (0.2..0.3).contains(&dy) && dx > 0.1
        };
        assert!(!g.walls.iter().any(across), "a wall across the step: {:?}", g.walls);
        // A return with a normal lies on a surface with that normal; corners have none.
        let mut corners = 0;
        for (q, n) in g.points.iter().zip(&g.normals) {
            let (_, d) = nearest_edge(&hall, *q);
            assert!(d < 1e-6, "return {q:?} off the walls by {d}");
            let Some(n) = n else {
                corners += 1;
                continue;
            };
            // Some edge through the return (two at a corner of the hall) runs as its normal says,
            // within 5°: a line may take in a return of the next wall within the split
            // tolerance, which tilts it a little (1.2° at the hall's far corner).
            let agrees = hall
                .rings()
                .iter()
                .flat_map(|r| (0..r.len()).map(move |i| [r[i], r[(i + 1) % r.len()]]))
                .filter(|[a, b]| crate::geometry::segment_distance(*q, *a, *b) < 1e-6)
                .any(|[a, b]| {
                    let l = (b[0] - a[0]).hypot(b[1] - a[1]);
                    (n[0] * (b[0] - a[0]) + n[1] * (b[1] - a[1])).abs() / l
                        < 5f64.to_radians().sin()
                });
            assert!(agrees, "return {q:?}: normal {n:?} is no wall's through it");
        }
        assert!(corners > 0 && corners < g.points.len() / 10, "{corners} corners");
    }

    /// A room whose north wall is traced from a 5 cm grid: it rises a cell every 0.6 m, a
    /// staircase 0.3 m at most from a straight line, as `map import` makes of a wall drawn at
    /// a slant. Scanned without noise from (2, 2), read as if σ were 2 cm.
    fn stepped_room() -> (crate::geometry::Domain, LaserScan, Pose) {
        let mut ring = vec![[0.0, 0.0], [8.0, 0.0]];
        // East to west along the top: y = 5 + 0.05 · step, a step every 0.6 m.
        let steps = 12;
        for k in (0..steps).rev() {
            let (x1, x0) = (0.6 * f64::from(k + 1) + 0.4, 0.6 * f64::from(k) + 0.4);
            let y = 5.0 + 0.05 * f64::from(k);
            if k + 1 == steps {
                ring.push([8.0, y]);
            }
            ring.push([x1.min(8.0), y]);
            ring.push([x0, y]);
            if k > 0 {
                ring.push([x0, y - 0.05]);
            }
        }
        ring.push([0.0, 5.0]);
        ring.dedup();
        let room = crate::geometry::Domain::new(ring, vec![]).unwrap();
        let at = Pose::new([2.0, 2.0], 0.0);
        let scan = exact_scan(&room, &at);
        (room, scan, at)
    }

    #[test]
    fn fine_walls_follow_a_grid_traced_wall_the_coarse_ones_cut_through() {
        let (room, scan, at) = stepped_room();
        let p = IngestParams::for_noise(0.02);
        assert!(p.fine_split() < p.split);
        let g = ingest(&scan, &at, &p).unwrap();
        assert_eq!(g.fine_normals.len(), g.points.len());
        // How far a wall strays from the room's boundary, at most (21 points along it).
        let stray = |w: &[Point; 2]| {
            (0..=20)
                .map(|i| {
                    let t = f64::from(i) / 20.0;
                    let e = [w[0][0] + t * (w[1][0] - w[0][0]), w[0][1] + t * (w[1][1] - w[0][1])];
                    nearest_edge(&room, e).1
                })
                .fold(0.0, f64::max)
        };
        let top = |w: &&[Point; 2]| w[0][1] > 4.9 && w[1][1] > 4.9;
        // The coarse walls along the top cut through its steps (the test would prove nothing
        // otherwise); the fine ones, and every other fine wall, stay within their tolerance.
        let coarse = g.walls.iter().filter(top).map(stray).fold(0.0, f64::max);
        assert!(coarse > p.fine_split(), "coarse walls within {coarse}");
        assert!(g.fine_walls.iter().filter(top).count() > g.walls.iter().filter(top).count());
        for w in &g.fine_walls {
            let d = stray(w);
            assert!(d <= p.fine_split() + 1e-9, "{w:?} strays {d} from the wall");
        }
    }

    #[test]
    fn bad_scans_are_refused_with_the_field() {
        let mut s = turn(360, square(2.0));
        s.ranges = vec![f64::NAN; 360];
        assert_eq!(
            ingest(&s, &Pose::default(), &IngestParams::default()),
            Err(IngestError::NoValidBeam)
        );
        let s = turn(360, square(2.0));
        let e = ingest(&s, &Pose { x: f64::NAN, y: 0.0, theta: 0.0 }, &IngestParams::default());
        assert!(e.unwrap_err().to_string().contains("pose"));
    }
}
