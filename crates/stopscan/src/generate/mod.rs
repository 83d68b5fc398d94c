//! Seeded instance families for exploration: the paper's worst cases (spiral, star) and
//! ordinary buildings (combs, office floors, pillar forests). Every generator returns a
//! validated [`Domain`] and a start point in its free space.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::geometry::{Domain, InvalidEnvironment};
use crate::kernel::Point;

/// A generated environment.
#[derive(Debug, Clone)]
pub struct Instance {
    /// The domain.
    pub domain: Domain,
    /// Where the robot starts.
    pub start: Point,
}

/// A rectangular spiral corridor with `turns` reflex corners (the paper's Fig. 9 family):
/// from the start at the outer end, each turn hides the next leg, so any strategy needs
/// `turns + 1` views.
///
/// # Errors
/// Never for `turns ≥ 1` (the rings are valid by construction; validation still runs).
pub fn spiral(turns: usize) -> Result<Instance, InvalidEnvironment> {
    // Walk a square spiral inwards; the corridor has width 1 and walls between legs of width 1.
    let turns = turns.max(1);
    let dirs = [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]];
    // Leg lengths grow from the inside out: leg k (from the centre) has length 2 + 2·(k / 2)·... we
    // build the centre line outwards, then offset it by ±0.5.
    let legs = turns + 1;
    let mut centre = vec![[0.0, 0.0]];
    let mut p = [0.0, 0.0];
    for k in 0..legs {
        let len = 2.0 * (1 + k / 2) as f64 + 1.0;
        let d = dirs[k % 4];
        p = [p[0] + d[0] * len, p[1] + d[1] * len];
        centre.push(p);
    }
    let (left, right) = offset_polyline(&centre, 0.5);
    let mut ring = right;
    ring.extend(left.into_iter().rev());
    let domain = Domain::new(ring, vec![])?;
    let n = centre.len();
    let (a, b) = (centre[n - 1], centre[n - 2]);
    let start = [a[0] + 0.25 * (b[0] - a[0]).signum(), a[1] + 0.25 * (b[1] - a[1]).signum()];
    Ok(Instance { domain, start })
}

/// Offsets a rectilinear polyline by `w` to both sides (mitred corners).
fn offset_polyline(c: &[Point], w: f64) -> (Vec<Point>, Vec<Point>) {
    let n = c.len();
    let dir = |i: usize| {
        let (a, b) = (c[i], c[i + 1]);
        let l = (b[0] - a[0]).hypot(b[1] - a[1]);
        [(b[0] - a[0]) / l, (b[1] - a[1]) / l]
    };
    let mut left = Vec::with_capacity(n);
    let mut right = Vec::with_capacity(n);
    for (i, ci) in c.iter().enumerate() {
        let (d0, d1) = (dir(i.saturating_sub(1).min(n - 2)), dir(i.min(n - 2)));
        // Mitre: sum of the two normals, scaled so each side stays at distance w.
        let (n0, n1) = ([-d0[1], d0[0]], [-d1[1], d1[0]]);
        let m = [n0[0] + n1[0], n0[1] + n1[1]];
        let dot = m[0] * n1[0] + m[1] * n1[1];
        let s = if i == 0 || i == n - 1 { w } else { w / dot };
        let m = if i == 0 {
            n1
        } else if i == n - 1 {
            n0
        } else {
            m
        };
        left.push([ci[0] + m[0] * s, ci[1] + m[1] * s]);
        right.push([ci[0] - m[0] * s, ci[1] - m[1] * s]);
    }
    (left, right)
}

/// A star with `spikes` narrow spikes around a central hub (the paper's Fig. 11 family):
/// two views suffice (the start and the hub), but the depth-first algorithm started in a
/// spike can need `r + 1`.
///
/// # Errors
/// Never for `spikes ≥ 3`.
pub fn star(spikes: usize) -> Result<Instance, InvalidEnvironment> {
    let k = spikes.max(3);
    let mut ring = Vec::with_capacity(2 * k);
    let tau = std::f64::consts::TAU;
    for i in 0..k {
        let a = tau * i as f64 / k as f64;
        let b = a + tau / (2.0 * k as f64);
        ring.push([10.0 * a.cos(), 10.0 * a.sin()]);
        ring.push([2.0 * b.cos(), 2.0 * b.sin()]);
    }
    let domain = Domain::new(ring, vec![])?;
    Ok(Instance { domain, start: [8.0, 0.0] })
}

/// A comb: a corridor along the bottom with `teeth` rooms opening upwards.
///
/// # Errors
/// Never for `teeth ≥ 1`.
pub fn comb(teeth: usize) -> Result<Instance, InvalidEnvironment> {
    // Corridor 0 ≤ y ≤ 2 under teeth 3i ≤ x ≤ 3i + 2, 2 ≤ y ≤ 6; 2(t − 1) reflex corners.
    let t = teeth.max(1);
    let w = 3.0 * t as f64 - 1.0;
    let mut ring = vec![[0.0, 0.0], [w, 0.0]];
    for i in (0..t).rev() {
        let x = 3.0 * i as f64;
        ring.push([x + 2.0, 6.0]);
        ring.push([x, 6.0]);
        if i > 0 {
            ring.push([x, 2.0]);
            ring.push([x - 1.0, 2.0]);
        }
    }
    let domain = Domain::new(ring, vec![])?;
    Ok(Instance { domain, start: [0.5, 0.5] })
}

/// A seeded office floor: a corridor along the middle with `rooms_per_side` rooms above and
/// below it, each opening onto the corridor through a door, and up to `desks` rectangular
/// desks (holes) placed in the rooms. Walls are 0.2 m thick, rooms 4 m × 5 m, doors 1 m.
///
/// # Errors
/// Never (desks that would touch a wall or each other are skipped).
pub fn office(
    rooms_per_side: usize,
    desks: usize,
    seed: u64,
) -> Result<Instance, InvalidEnvironment> {
    let n = rooms_per_side.max(1);
    let (room_w, room_h, wall, door, corridor) = (4.0, 5.0, 0.2, 1.0, 2.0);
    let (c0, c1) = (room_h + wall, room_h + wall + corridor); // corridor between y = c0 and c1
    let top = c1 + wall + room_h;
    let x0 = |i: usize| i as f64 * (room_w + wall);
    // Counter-clockwise: bottom rooms left to right, then top rooms right to left.
    let mut ring: Vec<Point> = Vec::new();
    for i in 0..n {
        let (a, b) = (x0(i), x0(i) + room_w);
        let (d0, d1) = (a + 0.5 * (room_w - door), a + 0.5 * (room_w + door));
        if i == 0 {
            ring.push([a, c0]);
        }
        ring.extend([
            [d0, c0],
            [d0, c0 - wall],
            [a, c0 - wall],
            [a, 0.0],
            [b, 0.0],
            [b, c0 - wall],
            [d1, c0 - wall],
            [d1, c0],
        ]);
        if i + 1 == n {
            ring.push([b, c0]);
        }
    }
    for i in (0..n).rev() {
        let (a, b) = (x0(i), x0(i) + room_w);
        let (d0, d1) = (a + 0.5 * (room_w - door), a + 0.5 * (room_w + door));
        if i + 1 == n {
            ring.push([b, c1]);
        }
        ring.extend([
            [d1, c1],
            [d1, c1 + wall],
            [b, c1 + wall],
            [b, top],
            [a, top],
            [a, c1 + wall],
            [d0, c1 + wall],
            [d0, c1],
        ]);
        if i == 0 {
            ring.push([a, c1]);
        }
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut holes: Vec<Vec<Point>> = Vec::new();
    let mut boxes: Vec<[f64; 4]> = Vec::new();
    for _ in 0..desks * 20 {
        if holes.len() == desks {
            break;
        }
        let i = rng.random_range(0..n);
        let upper = rng.random_bool(0.5);
        let (ry0, ry1) = if upper { (c1 + wall, top) } else { (0.0, c0 - wall) };
        let (w, h) = (rng.random_range(0.6..1.6), rng.random_range(0.5..1.0));
        let x = rng.random_range(x0(i) + 0.4..x0(i) + room_w - 0.4 - w);
        let y = rng.random_range(ry0 + 0.4..ry1 - 0.4 - h);
        let b = [x, y, x + w, y + h];
        // Keep the door's approach free and desks apart.
        let (d0, d1) = (x0(i) + 0.5 * (room_w - door) - 0.3, x0(i) + 0.5 * (room_w + door) + 0.3);
        let near_door = if upper { y < ry0 + 1.2 } else { y + h > ry1 - 1.2 };
        if near_door && x < d1 && x + w > d0 {
            continue;
        }
        if boxes.iter().any(|o| {
            b[0] < o[2] + 0.3 && o[0] < b[2] + 0.3 && b[1] < o[3] + 0.3 && o[1] < b[3] + 0.3
        }) {
            continue;
        }
        boxes.push(b);
        holes.push(vec![[x, y], [x, y + h], [x + w, y + h], [x + w, y]]);
    }
    let domain = Domain::new(ring, holes)?;
    Ok(Instance { domain, start: [0.5, 0.5 * (c0 + c1)] })
}

/// A seeded pillar forest: a rectangle `w × h` with `pillars` disjoint convex pillars.
///
/// # Errors
/// Never (overlapping candidates are skipped).
pub fn pillar_forest(
    w: f64,
    h: f64,
    pillars: usize,
    seed: u64,
) -> Result<Instance, InvalidEnvironment> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut holes: Vec<Vec<Point>> = Vec::new();
    let mut boxes: Vec<[f64; 4]> = vec![[0.0, 0.0, 1.0, 1.0]]; // keep the start corner free
    for _ in 0..pillars * 30 {
        if holes.len() == pillars {
            break;
        }
        let (cx, cy) =
            (rng.random_range(1.5..(w - 1.5).max(1.6)), rng.random_range(1.5..(h - 1.5).max(1.6)));
        let r = rng.random_range(0.3..1.2);
        let b = [cx - r, cy - r, cx + r, cy + r];
        if b[0] < 0.2 || b[1] < 0.2 || b[2] > w - 0.2 || b[3] > h - 0.2 {
            continue;
        }
        if boxes.iter().any(|o| {
            b[0] < o[2] + 0.2 && o[0] < b[2] + 0.2 && b[1] < o[3] + 0.2 && o[1] < b[3] + 0.2
        }) {
            continue;
        }
        let k = rng.random_range(3..7);
        let start: f64 = rng.random_range(0.0..1.0);
        holes.push(
            (0..k)
                .map(|i| {
                    let a = std::f64::consts::TAU * (start + f64::from(i)) / f64::from(k);
                    [cx + r * a.cos(), cy + r * a.sin()]
                })
                .collect(),
        );
        boxes.push(b);
    }
    let domain = Domain::new(vec![[0.0, 0.0], [w, 0.0], [w, h], [0.0, h]], holes)?;
    Ok(Instance { domain, start: [0.5, 0.5] })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Location;

    #[test]
    fn families_are_valid_with_known_reflex_counts() {
        for turns in 1..8 {
            let s = spiral(turns).unwrap();
            assert_eq!(s.domain.reflex_vertices().len(), turns, "spiral {turns}");
            assert_eq!(s.domain.locate(s.start), Location::Interior);
        }
        for k in [3, 5, 8] {
            let s = star(k).unwrap();
            assert_eq!(s.domain.reflex_vertices().len(), k);
            assert_eq!(s.domain.locate(s.start), Location::Interior);
        }
        for t in [1, 3, 6] {
            let c = comb(t).unwrap();
            assert_eq!(c.domain.reflex_vertices().len(), 2 * (t - 1));
            assert_eq!(c.domain.locate(c.start), Location::Interior);
        }
        for (rooms, desks) in [(1, 0), (3, 4), (8, 30)] {
            let o = office(rooms, desks, 7).unwrap();
            assert_eq!(o.domain.locate(o.start), Location::Interior);
            assert!(o.domain.holes().len() <= desks);
        }
        let big = office(40, 220, 1).unwrap();
        assert!(big.domain.vertex_count() >= 1000, "{}", big.domain.vertex_count());
        let f = pillar_forest(30.0, 20.0, 12, 3).unwrap();
        assert!(f.domain.holes().len() >= 8);
        assert_eq!(f.domain.locate(f.start), Location::Interior);
    }
}
