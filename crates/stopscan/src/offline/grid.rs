//! Bounds for multi-robot exploration of a region of interest (Sung and Tokekar, section 4.2)
//! and the lawn-mower baseline of section 6. Times are in seconds for cells of side `s`
//! metres; the paper's formulas count edges of unit length, so every time is scaled by `s`.
//! Logarithms are base 2 (the tree is binary).

use serde::{Deserialize, Serialize};

use crate::protocol::CostModel;
use crate::protocol::grid::{Cell, CellMap, Record, TimeModel};
use crate::world::grid::GridWorld;

/// ⌊log₂ R⌋ for R ≥ 1 (0 for R = 0).
pub fn floor_log2(r: usize) -> u32 {
    if r == 0 { 0 } else { usize::BITS - 1 - r.leading_zeros() }
}

/// The speeds and scale the bounds need.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Speeds {
    /// S_r.
    pub robot: f64,
    /// S_p.
    pub region: f64,
    /// The side of a cell, metres.
    pub cell_size: f64,
}

impl From<TimeModel> for Speeds {
    fn from(t: TimeModel) -> Self {
        Self { robot: t.robot_speed, region: t.drift_speed, cell_size: t.cell_size }
    }
}

/// Lemma 1 (upper bound on Algorithm 1): `2(C + d_max⌊log R⌋) / ((S_r − S_p)(1 + ⌊log R⌋))`.
pub fn lemma1_upper(cells: usize, d_max: usize, robots: usize, v: Speeds) -> f64 {
    let l = f64::from(floor_log2(robots));
    v.cell_size * 2.0 * (cells as f64 + d_max as f64 * l) / ((v.robot - v.region) * (1.0 + l))
}

/// Lemma 2 (lower bound on the optimum): `(C − 1) / ((S_r + S_p) R)`.
pub fn lemma2_lower(cells: usize, robots: usize, v: Speeds) -> f64 {
    v.cell_size * cells.saturating_sub(1) as f64 / ((v.robot + v.region) * robots.max(1) as f64)
}

/// Theorem 1: `ALG ≤ ratio · OPT + additive`; returns `(ratio, additive)` with
/// `ratio = 2(S_r + S_p)(R + ⌊log R⌋) / ((S_r − S_p)(1 + ⌊log R⌋))` and
/// `additive = 2 / ((S_r − S_p)(1 + ⌊log R⌋))` (times the cell size).
pub fn theorem1(robots: usize, v: Speeds) -> (f64, f64) {
    let l = f64::from(floor_log2(robots));
    let den = (v.robot - v.region) * (1.0 + l);
    (2.0 * (v.robot + v.region) * (robots as f64 + l) / den, v.cell_size * 2.0 / den)
}

/// Theorem 2 (arbitrary fat shapes, through the outer grid approximation): `ALG ≤ ratio ·
/// OPT + additive` with `ratio = 2(S_r + S_p)(18R + ⌊log R⌋) / M` and `additive = 48 / M`,
/// `M = (S_r − S_p)(1 + ⌊log R⌋)` (times the cell size).
pub fn theorem2(robots: usize, v: Speeds) -> (f64, f64) {
    let l = f64::from(floor_log2(robots));
    let m = (v.robot - v.region) * (1.0 + l);
    (2.0 * (v.robot + v.region) * (18.0 * robots as f64 + l) / m, v.cell_size * 48.0 / m)
}

/// Equation (8), the tighter single-robot bound: `2 S_r C / ((S_r + S_p)(S_r − S_p))`.
pub fn bound8_single(cells: usize, v: Speeds) -> f64 {
    v.cell_size * 2.0 * v.robot * cells as f64 / ((v.robot + v.region) * (v.robot - v.region))
}

/// d_max: the depth of the deepest vertex of the tree the robots built (edges between cells
/// count 1, dummy edges 0), from the parent each record names. Records without a parent that
/// are not the root (cells flown over before the region was found) are not in the tree.
pub fn tree_depth(boards: &CellMap<Record>) -> usize {
    let mut depth: CellMap<usize> = CellMap::default();
    let mut best = 0;
    let mut chain = Vec::new();
    for &c in boards.keys() {
        chain.clear();
        let mut cur = c;
        let d = loop {
            if let Some(&d) = depth.get(&cur) {
                break Some(d);
            }
            let Some(r) = boards.get(&cur) else { break None };
            if r.root {
                depth.insert(cur, 0);
                break Some(0);
            }
            match r.parent {
                Some(p) if chain.len() <= boards.len() => {
                    chain.push(cur);
                    cur = p;
                }
                _ => break None,
            }
        };
        if let Some(mut d) = d {
            while let Some(x) = chain.pop() {
                d += 1;
                depth.insert(x, d);
            }
            best = best.max(d);
        }
    }
    best
}

/// The lawn-mower baseline of section 6: the bounding rectangle of the region (aligned with
/// the grid) is split among the R robots into strips, along its length or its breadth, and
/// each strip is swept boustrophedon cell by cell; the better split and sweep direction is
/// taken, and the flight to the strips is ignored. Returns the time of the slowest strip.
pub fn lawn_mower(bounds: [Cell; 2], robots: usize, times: TimeModel) -> f64 {
    let w = (bounds[1][1] - bounds[0][1] + 1).max(1) as usize;
    let h = (bounds[1][0] - bounds[0][0] + 1).max(1) as usize;
    let r = robots.max(1);
    let strip_cols = (w.div_ceil(r), h);
    let strip_rows = (w, h.div_ceil(r));
    sweep_time(strip_cols.0, strip_cols.1, times).min(sweep_time(strip_rows.0, strip_rows.1, times))
}

/// The fastest boustrophedon over a `w` × `h` block of cells (rows or columns as lanes, either
/// starting direction, stepping either way between lanes).
fn sweep_time(w: usize, h: usize, times: TimeModel) -> f64 {
    let t = |d: Cell| times.seconds([0, 0], d).unwrap_or(f64::INFINITY);
    let (east, west, north, south) = (t([0, 1]), t([0, -1]), t([-1, 0]), t([1, 0]));
    // Lanes of length `len` along (a, b) alternately, `lanes` of them, stepping by c or d.
    let lanes = |len: usize, lanes: usize, a: f64, b: f64, c: f64, d: f64| {
        let moves = len.saturating_sub(1) as f64;
        let (first, second) = (lanes.div_ceil(2) as f64, (lanes / 2) as f64);
        let along = (moves * (first * a + second * b)).min(moves * (first * b + second * a));
        along + lanes.saturating_sub(1) as f64 * c.min(d)
    };
    lanes(w, h, east, west, north, south).min(lanes(h, w, north, south, east, west))
}

/// Every bound of a grid run, reported beside its time.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct GridBounds {
    /// d_max of the tree built.
    pub d_max: usize,
    /// Lemma 1's upper bound on the time.
    pub lemma1_upper: f64,
    /// Lemma 2's lower bound on the optimum.
    pub lemma2_lower: f64,
    /// Theorem 1's competitive ratio.
    pub theorem1_ratio: f64,
    /// Theorem 1's additive term.
    pub theorem1_additive: f64,
    /// Theorem 2's competitive ratio (arbitrary fat shapes).
    pub theorem2_ratio: f64,
    /// Theorem 2's additive term.
    pub theorem2_additive: f64,
    /// Equation (8) for one robot (`None` for a team).
    pub bound8_single: Option<f64>,
    /// The lawn-mower baseline.
    pub lawn_mower: f64,
}

impl GridBounds {
    /// All bounds for a region of `cells` cells and `bounds`, explored by `robots` robots under
    /// `times`, whose tree had depth `d_max`.
    pub fn new(
        cells: usize,
        bounds: [Cell; 2],
        d_max: usize,
        robots: usize,
        times: TimeModel,
    ) -> Self {
        let v = Speeds::from(times);
        let (ratio, additive) = theorem1(robots, v);
        let (ratio2, additive2) = theorem2(robots, v);
        Self {
            d_max,
            lemma1_upper: lemma1_upper(cells, d_max, robots, v),
            lemma2_lower: lemma2_lower(cells, robots, v),
            theorem1_ratio: ratio,
            theorem1_additive: additive,
            theorem2_ratio: ratio2,
            theorem2_additive: additive2,
            bound8_single: (robots == 1).then(|| bound8_single(cells, v)),
            lawn_mower: lawn_mower(bounds, robots, times),
        }
    }

    /// All bounds for the region of `world` explored by `robots` robots under `cost`, with the
    /// d_max of the tree recorded on its cells.
    pub fn of_world(world: &GridWorld, robots: usize, cost: &CostModel) -> Self {
        let roi = world.roi();
        let d_max = tree_depth(&world.records());
        Self::new(roi.len(), roi.bounds(), d_max, robots, world.time_model(cost))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const STATIC: Speeds = Speeds { robot: 1.0, region: 0.0, cell_size: 1.0 };

    #[test]
    fn logs() {
        assert_eq!([1, 2, 3, 4, 20, 64].map(floor_log2), [0, 1, 1, 2, 4, 6]);
    }

    #[test]
    fn corollary_1_special_cases() {
        // SRSR: 2C / S_r; MRSR with R = 4: 2(C + 2 d) / (3 S_r).
        assert_eq!(lemma1_upper(10, 5, 1, STATIC), 20.0);
        assert!((lemma1_upper(10, 5, 4, STATIC) - 2.0 * 20.0 / 3.0).abs() < 1e-12);
        // SRTR: 2C / (S_r − S_p), and (8) is tighter by S_r / (S_r + S_p).
        let v = Speeds { robot: 2.5, region: 1.0, cell_size: 1.0 };
        assert!((lemma1_upper(10, 5, 1, v) - 20.0 / 1.5).abs() < 1e-12);
        assert!((bound8_single(10, v) / lemma1_upper(10, 5, 1, v) - 2.5 / 3.5).abs() < 1e-12);
        assert!((lemma2_lower(11, 2, v) - 10.0 / 7.0).abs() < 1e-12);
    }

    #[test]
    fn theorem_1_ratio_is_the_abstract_constant() {
        let v = Speeds { robot: 2.0, region: 1.0, cell_size: 1.0 };
        let (ratio, add) = theorem1(4, v);
        assert!((ratio - 2.0 * 3.0 * 6.0 / 3.0).abs() < 1e-12);
        assert!((add - 2.0 / 3.0).abs() < 1e-12);
    }

    #[test]
    fn theorem_2_is_the_abstract_constant() {
        let v = Speeds { robot: 2.0, region: 1.0, cell_size: 1.0 };
        let (ratio, add) = theorem2(4, v);
        assert!((ratio - 2.0 * 3.0 * (72.0 + 2.0) / 3.0).abs() < 1e-12);
        assert!((add - 16.0).abs() < 1e-12);
    }

    #[test]
    fn lawn_mower_of_a_static_block() {
        let tm = TimeModel { robot_speed: 1.0, drift_speed: 0.0, heading_deg: 0.0, cell_size: 1.0 };
        // 4 × 3 block, one robot: 12 cells, 11 moves.
        assert_eq!(lawn_mower([[0, 0], [2, 3]], 1, tm), 11.0);
        // Two robots: strips of 2 × 3 (5 moves) or 4 × 2 (7 moves).
        assert_eq!(lawn_mower([[0, 0], [2, 3]], 2, tm), 5.0);
    }

    #[test]
    fn depth_follows_parents() {
        let mut b = CellMap::default();
        b.insert([0, 0], Record { root: true, ..Record::default() });
        b.insert([0, 1], Record { parent: Some([0, 0]), ..Record::default() });
        b.insert([0, 2], Record { parent: Some([0, 1]), ..Record::default() });
        b.insert([5, 5], Record::default());
        assert_eq!(tree_depth(&b), 2);
    }
}
