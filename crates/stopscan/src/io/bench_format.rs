//! The visibility benchmark format of `shared/bench/visibility`:
//!
//! ```text
//! # comments before OUTER
//! OUTER m     then m lines "x y" (counter-clockwise, not closed)
//! HOLES h     then h blocks: a line "k", then k lines "x y"
//! QUERIES q   then q lines "x y" (optional)
//! ```

use std::path::Path;

use super::LoadError;
use crate::geometry::Domain;
use crate::kernel::Point;

/// A benchmark environment with its query points.
#[derive(Debug, Clone)]
pub struct BenchEnvironment {
    /// The validated domain.
    pub domain: Domain,
    /// The query points (empty if the file has no QUERIES section).
    pub queries: Vec<Point>,
}

/// Reads a benchmark file.
///
/// # Errors
/// [`LoadError`] naming the file and line.
pub fn read(path: &Path) -> Result<BenchEnvironment, LoadError> {
    let text = std::fs::read_to_string(path)
        .map_err(|source| LoadError::Io { file: path.display().to_string(), source })?;
    parse(&text, &path.display().to_string())
}

/// Parses benchmark text; `file` names it in errors.
///
/// # Errors
/// [`LoadError`] naming the file and line.
pub fn parse(text: &str, file: &str) -> Result<BenchEnvironment, LoadError> {
    const MAX: usize = 50_000_000;
    let mut lines =
        text.lines().enumerate().map(|(i, l)| (i + 1, l.trim())).filter(|(_, l)| !l.is_empty());
    let err = |line: usize, reason: String| LoadError::Syntax { file: file.into(), line, reason };
    let last_line = text.lines().count();
    let mut next = |what: &str| -> Result<(usize, &str), LoadError> {
        loop {
            match lines.next() {
                Some((_, l)) if l.starts_with('#') => {}
                Some(x) => return Ok(x),
                None => {
                    return Err(err(last_line, format!("the file ends where {what} was expected")));
                }
            }
        }
    };
    let header = |(no, l): (usize, &str), key: &str| -> Result<usize, LoadError> {
        let mut it = l.split_whitespace();
        match (it.next(), it.next().map(str::parse::<usize>), it.next()) {
            (Some(k), Some(Ok(n)), None) if k == key => Ok(n),
            _ => Err(err(no, format!("expected '{key} <count>', got {l:?}"))),
        }
    };
    let point = |(no, l): (usize, &str)| -> Result<Point, LoadError> {
        let v: Vec<&str> = l.split_whitespace().collect();
        match v.as_slice() {
            [x, y] => match (x.parse::<f64>(), y.parse::<f64>()) {
                (Ok(x), Ok(y)) if x.is_finite() && y.is_finite() => Ok([x, y]),
                _ => Err(err(no, format!("expected two finite numbers, got {l:?}"))),
            },
            _ => Err(err(no, format!("expected 'x y', got {l:?}"))),
        }
    };
    let m = header(next("OUTER")?, "OUTER")?;
    if m > MAX {
        return Err(err(0, format!("OUTER count {m} is implausibly large")));
    }
    let mut outer = Vec::with_capacity(m);
    for _ in 0..m {
        outer.push(point(next("an outer vertex")?)?);
    }
    let h = header(next("HOLES")?, "HOLES")?;
    let mut holes = Vec::with_capacity(h.min(MAX));
    for _ in 0..h {
        let (no, l) = next("a hole size")?;
        let k: usize =
            l.parse().map_err(|_| err(no, format!("expected a hole's vertex count, got {l:?}")))?;
        if k > MAX {
            return Err(err(no, format!("hole size {k} is implausibly large")));
        }
        let mut ring = Vec::with_capacity(k);
        for _ in 0..k {
            ring.push(point(next("a hole vertex")?)?);
        }
        holes.push(ring);
    }
    let mut queries = Vec::new();
    if let Ok(x) = next("QUERIES") {
        let q = header(x, "QUERIES")?;
        for _ in 0..q.min(MAX) {
            queries.push(point(next("a query point")?)?);
        }
    }
    let domain = Domain::new(outer, holes)
        .map_err(|source| LoadError::Invalid { file: file.into(), source })?;
    Ok(BenchEnvironment { domain, queries })
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = "# c\nOUTER 4\n0 0\n4 0\n4 4\n0 4\nHOLES 1\n4\n1 1\n1 2\n2 2\n2 1\nQUERIES 2\n3 3\n0.5 0.5\n";

    #[test]
    fn reads_the_format() {
        let e = parse(GOOD, "t").unwrap();
        assert_eq!(e.domain.vertex_count(), 8);
        assert_eq!(e.queries.len(), 2);
    }

    #[test]
    fn errors_name_the_line() {
        let cases = [
            ("", "ends"),
            ("OUTER x\n", "t:1"),
            ("OUTER 3\n0 0\n1 nan\n", "t:3"),
            ("OUTER 3\n0 0\n1 0\n", "ends"),
            ("OUTER 3\n0 0\n1 0\n0 1\nHOLES 1\nfour\n", "t:6"),
            ("OUTER 3\n0 0\n1 0 2\n0 1\n", "t:3"),
            ("OUTER 4\n0 0\n2 2\n2 0\n0 2\nHOLES 0\n", "not simple"),
        ];
        for (text, needle) in cases {
            let e = parse(text, "t").unwrap_err().to_string();
            assert!(e.contains(needle), "{text:?}: {e}");
        }
    }
}
