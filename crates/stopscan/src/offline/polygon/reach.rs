//! What a robot with a footprint can see at all: the free space seen from its reachable
//! configuration space ([`crate::world::polygon::Reach`]).
//!
//! The exact region visible from a polygon (its weak visibility region) is not computed;
//! instead the visibility regions from sample points of the reachable configuration space
//! (its vertices and the centroids of its triangles), and from wherever a run scanned, are
//! united. The result lies inside the exact region, so the area "not visible from anywhere
//! reachable" it leaves ([`unreachable_area`]) is an upper estimate, and a coverage measured
//! against it is an upper estimate of the true one (stated in the run record).

use crate::algorithm::region::Region;
use crate::kernel::Point;
use crate::world::polygon::PolygonWorld;

/// Sample points of the reachable configuration space: its vertices and the centroid of
/// every triangle of its triangulation; empty for a point robot.
pub fn reachable_samples(world: &PolygonWorld) -> Vec<Point> {
    let Some(reach) = world.reach() else { return Vec::new() };
    let mut out: Vec<Point> = reach.domain().rings().iter().flatten().copied().collect();
    let m = reach.mesh();
    out.extend(m.tri.iter().map(|t| {
        let p = t.map(|i| m.points()[i as usize]);
        [(p[0][0] + p[1][0] + p[2][0]) / 3.0, (p[0][1] + p[1][1] + p[2][1]) / 3.0]
    }));
    out
}

/// The union of what the world's sensor sees from `points` and the `seen` polygons (a run's
/// scans). Points the sensor cannot scan from are skipped.
pub fn visible_from(world: &PolygonWorld, points: &[Point], seen: &[Vec<Point>]) -> Region {
    use rayon::prelude::*;
    let mut polys: Vec<Vec<Point>> =
        points.par_iter().filter_map(|&p| world.scan(p).ok().map(|o| o.region.polygon)).collect();
    polys.extend(seen.iter().cloned());
    Region::union_all(&polys)
}

/// The free area no sampled reachable viewpoint and no scan sees: `free − visible`, never
/// below 0.
pub fn unreachable_area(world: &PolygonWorld, visible: &Region) -> f64 {
    (world.domain().area() - visible.area()).max(0.0)
}

/// Where the robot's body can be: the reachable configuration space grown by the footprint
/// ([`dilation`](crate::algorithm::region::dilation); a disc as its circumscribed polygon,
/// so a hair more); `None` for a point robot. What lies outside it but inside the free
/// space is a crevice narrower than the robot: a slot between furniture, or a laser's
/// see-through spike on a traced map.
pub fn body_space(world: &PolygonWorld) -> Option<Region> {
    let reach = world.reach()?;
    let shape = reach.footprint().polygon()?;
    Some(
        crate::algorithm::region::dilation(reach.domain(), &shape)
            .intersection(&Region::of_domain(world.domain())),
    )
}

/// The offline greedy reference for a robot with a footprint and a range: from the start,
/// repeatedly add the sampled reachable viewpoint ([`reachable_samples`]) whose scan sees
/// the most area not yet covered, until everything any of them sees is covered. Coverage is
/// required at the centroid of every triangle of the free space, weighted by its area.
/// Unlike the point robot's reference, viewpoints need not see each other: the robot drives
/// between them through its configuration space. A reference, not a bound.
///
/// `certified` is true when the chosen scans cover every witness any sample covers.
pub fn greedy(world: &PolygonWorld, start: Point) -> super::ViewSet {
    use rayon::prelude::*;
    let mut cands = vec![start];
    cands.extend(reachable_samples(world));
    let regions: Vec<Option<(Vec<Point>, [Point; 2])>> = cands
        .par_iter()
        .map(|&c| {
            world.scan(c).ok().map(|o| {
                let b = crate::algorithm::cover::bounds_of(&o.region.polygon);
                (o.region.polygon, b)
            })
        })
        .collect();
    let m = world.visibility().mesh();
    let witnesses: Vec<(Point, f64)> = m
        .tri
        .iter()
        .map(|t| {
            let p = t.map(|i| m.points()[i as usize]);
            let c = [(p[0][0] + p[1][0] + p[2][0]) / 3.0, (p[0][1] + p[1][1] + p[2][1]) / 3.0];
            (c, crate::geometry::signed_area_of(&p).abs())
        })
        .collect();
    // sees[c]: the witnesses candidate c covers.
    let sees: Vec<Vec<u32>> = regions
        .par_iter()
        .map(|r| {
            let Some((poly, b)) = r else { return Vec::new() };
            witnesses
                .iter()
                .enumerate()
                .filter(|(_, (w, _))| {
                    w[0] >= b[0][0]
                        && w[0] <= b[1][0]
                        && w[1] >= b[0][1]
                        && w[1] <= b[1][1]
                        && crate::kernel::ring_side(poly, *w) != crate::kernel::RingSide::Outside
                })
                .map(|(i, _)| i as u32)
                .collect()
        })
        .collect();
    let mut covered = vec![false; witnesses.len()];
    let mut chosen = vec![0usize];
    for &w in &sees[0] {
        covered[w as usize] = true;
    }
    let coverable: Vec<bool> = {
        let mut c = vec![false; witnesses.len()];
        for s in &sees {
            for &w in s {
                c[w as usize] = true;
            }
        }
        c
    };
    // Lazy greedy: a candidate's gain only shrinks, so a stale gain is an upper bound. Gains
    // are not negative, so their bits order as the numbers do; ties go to the earlier one.
    let gain = |c: usize, covered: &[bool]| -> f64 {
        sees[c].iter().filter(|&&w| !covered[w as usize]).map(|&w| witnesses[w as usize].1).sum()
    };
    let key = |g: f64| g.max(0.0).to_bits();
    let mut heap: std::collections::BinaryHeap<(u64, std::cmp::Reverse<usize>)> =
        (1..cands.len()).map(|c| (key(gain(c, &covered)), std::cmp::Reverse(c))).collect();
    while let Some((_, std::cmp::Reverse(c))) = heap.pop() {
        let now = gain(c, &covered);
        if now <= 0.0 {
            continue;
        }
        if heap.peek().is_some_and(|(top, _)| key(now) < *top) {
            heap.push((key(now), std::cmp::Reverse(c)));
            continue;
        }
        chosen.push(c);
        for &w in &sees[c] {
            covered[w as usize] = true;
        }
    }
    let certified = coverable.iter().zip(&covered).all(|(&can, &did)| !can || did);
    super::ViewSet { viewpoints: chosen.into_iter().map(|c| cands[c]).collect(), certified }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Domain;
    use crate::protocol::polygon::Footprint;

    #[test]
    fn a_pocket_behind_a_narrow_gap_is_unreachable_but_partly_visible() {
        // A 6 × 4 room; a wall at x = 6 with a 0.3-wide gap at y ∈ [1.85, 2.15] into a
        // 2 × 4 pocket. A robot of radius 0.2 cannot pass the gap.
        let outer = vec![
            [0.0, 0.0],
            [6.0, 0.0],
            [6.0, 1.85],
            [6.2, 1.85],
            [6.2, 0.0],
            [8.2, 0.0],
            [8.2, 4.0],
            [6.2, 4.0],
            [6.2, 2.15],
            [6.0, 2.15],
            [6.0, 4.0],
            [0.0, 4.0],
        ];
        let d = Domain::new(outer, vec![]).unwrap();
        let free = d.area();
        let w = PolygonWorld::with_robot(d, None, &Footprint::disc(0.2).unwrap(), Some([1.0, 2.0]))
            .unwrap();
        let reach = w.reach().unwrap();
        // The configuration space is the room shrunk by 0.2, with a small bulge into the
        // mouth of the gap (the centre gets within 0.2 of the gap's corners): the pocket is
        // out of reach.
        assert!(reach.domain().area() < 5.6 * 3.6 + 0.05, "{}", reach.domain().area());
        assert!(reach.domain().area() > 5.6 * 3.6 - 0.01);
        assert!(reach.domain().rings().iter().flatten().all(|p| p[0] < 6.0 - 0.1));
        let samples = reachable_samples(&w);
        assert!(!samples.is_empty());
        let v = visible_from(&w, &samples, &[]);
        let lost = unreachable_area(&w, &v);
        // The room is seen whole; of the pocket only what the gap lets through.
        assert!(lost > 0.0 && lost < 8.0, "{lost}");
        assert!(v.area() > 24.0 && v.area() < free, "{}", v.area());
        // The greedy reference covers everything the samples see: the room, from one place
        // or two.
        let g = greedy(&w, [1.0, 2.0]);
        assert!(g.certified);
        assert!((1..=3).contains(&g.viewpoints.len()), "{:?}", g.viewpoints);
        assert_eq!(g.viewpoints[0], [1.0, 2.0]);
    }
}
