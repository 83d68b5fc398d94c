//! Visibility on small arbitrary domains and viewpoints (coordinates on a coarse grid, so
//! collinear and degenerate configurations are common): no panic, and every region is a
//! star-shaped polygon no larger than the domain.
#![no_main]

use libfuzzer_sys::fuzz_target;
use stopscan::algorithm::visibility::Visibility;
use stopscan::geometry::{Domain, Location};

fuzz_target!(|data: &[u8]| {
    if data.len() < 8 {
        return;
    }
    let coord = |b: u8| f64::from(b % 16);
    let n = 3 + (data[0] % 8) as usize;
    if data.len() < 1 + 2 * n + 2 {
        return;
    }
    let outer: Vec<[f64; 2]> =
        (0..n).map(|i| [coord(data[1 + 2 * i]), coord(data[2 + 2 * i])]).collect();
    let rest = &data[1 + 2 * n..];
    let mut holes = Vec::new();
    let mut k = 2;
    if rest.len() >= 8 && rest[0] % 2 == 1 {
        let m = 3 + (rest[1] % 4) as usize;
        if rest.len() >= 2 + 2 * m + 2 {
            holes.push(
                (0..m)
                    .map(|i| [coord(rest[2 + 2 * i]) + 0.5, coord(rest[3 + 2 * i]) + 0.5])
                    .collect::<Vec<_>>(),
            );
            k = 2 + 2 * m;
        }
    }
    let Ok(d) = Domain::new(outer, holes) else { return };
    let v = Visibility::new(d.clone()).expect("a valid domain triangulates");
    let q = [
        f64::from(rest[k % rest.len()] % 32) / 2.0,
        f64::from(rest[(k + 1) % rest.len()] % 32) / 2.0,
    ];
    match v.query(q) {
        Ok(r) => {
            assert_ne!(d.locate(q), Location::Outside, "a region for an outside point");
            let a = r.area();
            assert!(a >= -1e-9 && a <= d.area() * (1.0 + 1e-9) + 1e-9, "area {a} of {}", d.area());
            let _ = v.query_range(q, 3.0).map(|x| x.area());
        }
        Err(_) => assert_eq!(d.locate(q), Location::Outside, "no region for a free point"),
    }
});
