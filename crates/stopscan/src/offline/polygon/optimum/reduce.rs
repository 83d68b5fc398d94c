//! The program made smaller before it is solved: coverage rows implied by another row, and
//! candidates another candidate dominates.

use crate::offline::polygon::Problem;

/// The coverage rows of the witnesses the start does not see, without the rows implied by
/// another (a superset of another row's candidates).
pub(super) fn cover_rows(p: &Problem) -> Vec<Vec<usize>> {
    let n = p.cands.len();
    let words = n.div_ceil(64);
    let mut rows: Vec<&Vec<usize>> = p.seen_by.iter().filter(|r| !r.contains(&0)).collect();
    rows.sort_by_key(|r| (r.len(), (*r).clone()));
    rows.dedup();
    let mut kept: Vec<(Vec<u64>, &Vec<usize>)> = Vec::new();
    for r in rows {
        let mut bits = vec![0u64; words];
        for &c in r {
            bits[c / 64] |= 1 << (c % 64);
        }
        let implied = kept.iter().any(|(k, _)| k.iter().zip(&bits).all(|(a, b)| a & !b == 0));
        if !implied {
            kept.push((bits, r));
        }
    }
    kept.into_iter().map(|(_, r)| r.clone()).collect()
}

/// Candidates another one dominates: it sees every witness they see (so it covers what they
/// cover) and every candidate they see (so it connects what they connect); the lower index
/// of two equal ones stays. Leaving them out keeps an optimum for the current witnesses.
/// Returns, per candidate, its dominator (`None` for those kept).
pub(super) fn dominated(p: &Problem) -> Vec<Option<usize>> {
    let n = p.cands.len();
    let words = n.div_ceil(64);
    let mut covers: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (w, by) in p.seen_by.iter().enumerate() {
        if !by.contains(&0) {
            for &c in by {
                covers[c].push(w);
            }
        }
    }
    let closed: Vec<Vec<u64>> = (0..n)
        .map(|c| {
            let mut b = vec![0u64; words];
            for &m in p.sees[c].iter().chain([&c]) {
                b[m / 64] |= 1 << (m % 64);
            }
            b
        })
        .collect();
    let subset = |a: &[usize], b: &[usize]| {
        let mut j = 0;
        a.iter().all(|x| {
            while j < b.len() && b[j] < *x {
                j += 1;
            }
            j < b.len() && b[j] == *x
        })
    };
    (0..n)
        .map(|c| {
            if c == 0 {
                return None;
            }
            (0..n).find(|&d| {
                d != c
                    && covers[c].len() <= covers[d].len()
                    && closed[c].iter().zip(&closed[d]).all(|(a, b)| a & !b == 0)
                    && subset(&covers[c], &covers[d])
                    && (d == 0
                        || covers[c].len() < covers[d].len()
                        || p.sees[c].len() < p.sees[d].len()
                        || d < c)
            })
        })
        .collect()
}

/// A solution with every dominated candidate replaced by the one that dominates it (in
/// turn, until one that stays): as large at most, still complete and connected.
pub(super) fn undominated(solution: &[usize], dom: &[Option<usize>]) -> Vec<usize> {
    let mut out: Vec<usize> = solution
        .iter()
        .map(|&c| {
            let mut c = c;
            while let Some(d) = dom[c] {
                c = d;
            }
            c
        })
        .collect();
    out.sort_unstable();
    out.dedup();
    out
}
