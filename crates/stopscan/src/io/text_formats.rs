//! GeoJSON, WKT and the art-gallery `.pol` format, read into a validated [`Domain`].
//!
//! * GeoJSON: a `Feature` or `FeatureCollection` holding one `Polygon` (or a bare `Polygon`
//!   geometry). The first ring is the boundary, the others holes. The optional property
//!   `"start": [x, y]` is kept. Units are metres.
//! * WKT: `POLYGON ((x y, ...), (x y, ...))`.
//! * `.pol`: `n x1 y1 ... xn yn [h m1 <m1 pairs> ... mh <mh pairs>]`, coordinates integers,
//!   decimals or rationals `p/q`. A rational is rounded to the nearest double of `p` divided by
//!   the nearest double of `q` (within 2 ulp of `p/q`): the domain is `f64` throughout.

use serde_json::Value;

use super::{Environment, LoadError};
use crate::geometry::Domain;
use crate::kernel::Point;

fn syntax(file: &str, line: usize, reason: impl Into<String>) -> LoadError {
    LoadError::Syntax { file: file.into(), line, reason: reason.into() }
}

fn build(file: &str, mut rings: Vec<Vec<Point>>) -> Result<Domain, LoadError> {
    if rings.is_empty() {
        return Err(syntax(file, 0, "no polygon rings"));
    }
    let outer = rings.remove(0);
    Domain::new(outer, rings).map_err(|source| LoadError::Invalid { file: file.into(), source })
}

/// Parses GeoJSON text.
///
/// # Errors
/// [`LoadError`] naming the file and the JSON path of the problem.
pub fn parse_geojson(text: &str, file: &str) -> Result<Environment, LoadError> {
    let v: Value = serde_json::from_str(text)
        .map_err(|e| syntax(file, e.line(), format!("invalid JSON: {e}")))?;
    let (geometry, props, path, props_path) = match v.get("type").and_then(Value::as_str) {
        Some("FeatureCollection") => {
            let features = v
                .get("features")
                .and_then(Value::as_array)
                .ok_or_else(|| syntax(file, 0, "FeatureCollection without a 'features' array"))?;
            let polys: Vec<(usize, &Value)> = features
                .iter()
                .enumerate()
                .filter(|(_, f)| {
                    f.pointer("/geometry/type").and_then(Value::as_str) == Some("Polygon")
                })
                .collect();
            match polys.as_slice() {
                [(i, f)] => (
                    &f["geometry"],
                    f.get("properties"),
                    format!("features[{i}].geometry"),
                    format!("features[{i}].properties"),
                ),
                [] => return Err(syntax(file, 0, "the FeatureCollection holds no Polygon")),
                _ => {
                    return Err(syntax(
                        file,
                        0,
                        format!("the FeatureCollection holds {} Polygons; give one", polys.len()),
                    ));
                }
            }
        }
        Some("Feature") => {
            (&v["geometry"], v.get("properties"), "geometry".to_string(), "properties".to_string())
        }
        Some("Polygon") => (&v, None, String::new(), String::new()),
        Some(other) => {
            return Err(syntax(
                file,
                0,
                format!("expected a Feature, FeatureCollection or Polygon, got type {other:?}"),
            ));
        }
        None => return Err(syntax(file, 0, "the JSON object has no 'type'")),
    };
    if geometry.get("type").and_then(Value::as_str) != Some("Polygon") {
        return Err(syntax(file, 0, format!("{path}: the geometry is not a Polygon")));
    }
    let coords = geometry
        .get("coordinates")
        .and_then(Value::as_array)
        .ok_or_else(|| syntax(file, 0, format!("{path}.coordinates is missing or not an array")))?;
    let mut rings = Vec::new();
    for (r, ring) in coords.iter().enumerate() {
        let ring = ring
            .as_array()
            .ok_or_else(|| syntax(file, 0, format!("{path}.coordinates[{r}] is not an array")))?;
        let mut pts = Vec::with_capacity(ring.len());
        for (i, p) in ring.iter().enumerate() {
            let xy = p
                .as_array()
                .filter(|a| a.len() >= 2)
                .and_then(|a| Some([a[0].as_f64()?, a[1].as_f64()?]));
            pts.push(xy.ok_or_else(|| {
                syntax(
                    file,
                    0,
                    format!("{path}.coordinates[{r}][{i}] is not a [x, y] pair of numbers"),
                )
            })?);
        }
        rings.push(pts);
    }
    let domain = build(file, rings)?;
    let start = match props.and_then(|p| p.get("start")) {
        None => None,
        Some(s) => Some(start_point(s).ok_or_else(|| {
            let mut got = s.to_string();
            if got.chars().count() > 60 {
                got = got.chars().take(57).collect::<String>() + "...";
            }
            let hint =
                if s.is_null() { " (leave the property out for the default start)" } else { "" };
            syntax(
                file,
                0,
                format!("{props_path}.start must be [x, y] (two finite numbers), got {got}{hint}"),
            )
        })?),
    };
    Ok(Environment::new(domain).with_start(start))
}

/// `[x, y]`: exactly two finite numbers (unlike coordinates, a start has no altitude).
fn start_point(v: &Value) -> Option<Point> {
    match v.as_array()?.as_slice() {
        [x, y] => Some([x.as_f64()?, y.as_f64()?]).filter(|p| p.iter().all(|c| c.is_finite())),
        _ => None,
    }
}

/// Parses WKT `POLYGON` text.
///
/// # Errors
/// [`LoadError`] naming the file and the line of the problem.
pub fn parse_wkt(text: &str, file: &str) -> Result<Environment, LoadError> {
    let bytes = text.as_bytes();
    let mut pos = 0;
    let line_at = |p: usize| text[..p.min(text.len())].matches('\n').count() + 1;
    let skip_ws = |pos: &mut usize| {
        while *pos < bytes.len() && bytes[*pos].is_ascii_whitespace() {
            *pos += 1;
        }
    };
    skip_ws(&mut pos);
    let kw_end =
        bytes[pos..].iter().position(|b| !b.is_ascii_alphabetic()).map_or(bytes.len(), |k| pos + k);
    if !text[pos..kw_end].eq_ignore_ascii_case("POLYGON") {
        return Err(syntax(
            file,
            line_at(pos),
            format!("expected POLYGON, got {:?}", &text[pos..kw_end.min(pos + 20)]),
        ));
    }
    pos = kw_end;
    let expect = |pos: &mut usize, c: u8| -> Result<(), LoadError> {
        skip_ws(pos);
        if *pos < bytes.len() && bytes[*pos] == c {
            *pos += 1;
            Ok(())
        } else {
            Err(syntax(file, line_at(*pos), format!("expected '{}'", c as char)))
        }
    };
    expect(&mut pos, b'(')?;
    let mut rings = Vec::new();
    loop {
        expect(&mut pos, b'(')?;
        let mut ring = Vec::new();
        loop {
            let mut xy = [0.0; 2];
            for v in &mut xy {
                skip_ws(&mut pos);
                let end = bytes[pos..]
                    .iter()
                    .position(|b| b.is_ascii_whitespace() || *b == b',' || *b == b')')
                    .map_or(bytes.len(), |k| pos + k);
                *v = text[pos..end].parse::<f64>().ok().filter(|x| x.is_finite()).ok_or_else(
                    || {
                        syntax(
                            file,
                            line_at(pos),
                            format!("expected a finite number, got {:?}", &text[pos..end]),
                        )
                    },
                )?;
                pos = end;
            }
            ring.push(xy);
            skip_ws(&mut pos);
            match bytes.get(pos) {
                Some(b',') => pos += 1,
                Some(b')') => {
                    pos += 1;
                    break;
                }
                _ => {
                    return Err(syntax(
                        file,
                        line_at(pos),
                        "expected ',' or ')' after a coordinate pair",
                    ));
                }
            }
        }
        rings.push(ring);
        skip_ws(&mut pos);
        match bytes.get(pos) {
            Some(b',') => pos += 1,
            Some(b')') => {
                pos += 1;
                break;
            }
            _ => return Err(syntax(file, line_at(pos), "expected ',' or ')' after a ring")),
        }
    }
    skip_ws(&mut pos);
    if pos < bytes.len() {
        let rest: String = text[pos..].chars().take(40).collect();
        let more = if text[pos..].chars().count() > 40 { "…" } else { "" };
        return Err(syntax(
            file,
            line_at(pos),
            format!(
                "unexpected text after the POLYGON: {rest:?}{more} (one POLYGON per file; MULTIPOLYGON is not supported)"
            ),
        ));
    }
    Ok(Environment::new(build(file, rings)?))
}

/// Parses a `.pol` file (one line of whitespace-separated tokens).
///
/// # Errors
/// [`LoadError`] naming the file and the token of the problem.
pub fn parse_pol(text: &str, file: &str) -> Result<Environment, LoadError> {
    let mut c = Tokens { list: text.split_whitespace().collect(), k: 0, file };
    let mut rings = vec![c.ring()?];
    if c.k < c.list.len() {
        let h = c.count("the number of holes")?;
        for _ in 0..h {
            rings.push(c.ring()?);
        }
    }
    if c.k < c.list.len() {
        return Err(syntax(
            file,
            1,
            format!("{} unexpected tokens after the polygon", c.list.len() - c.k),
        ));
    }
    Ok(Environment::new(build(file, rings)?))
}

struct Tokens<'a> {
    list: Vec<&'a str>,
    k: usize,
    file: &'a str,
}

impl<'a> Tokens<'a> {
    fn take(&mut self, what: &str) -> Result<&'a str, LoadError> {
        let t = self.list.get(self.k).copied().ok_or_else(|| {
            syntax(
                self.file,
                1,
                format!("the file ends where {what} (token {}) was expected", self.k + 1),
            )
        })?;
        self.k += 1;
        Ok(t)
    }

    fn count(&mut self, what: &str) -> Result<usize, LoadError> {
        let t = self.take(what)?;
        t.parse::<usize>().ok().filter(|&n| n <= 50_000_000).ok_or_else(|| {
            syntax(self.file, 1, format!("token {}: expected a count, got {t:?}", self.k))
        })
    }

    fn number(&mut self, what: &str) -> Result<f64, LoadError> {
        let t = self.take(what)?;
        let v = match t.split_once('/') {
            Some((p, q)) => match (p.parse::<f64>(), q.parse::<f64>()) {
                (Ok(p), Ok(q)) if q != 0.0 => p / q,
                _ => f64::NAN,
            },
            None => t.parse::<f64>().unwrap_or(f64::NAN),
        };
        if v.is_finite() {
            Ok(v)
        } else {
            Err(syntax(
                self.file,
                1,
                format!("token {}: expected a number or p/q, got {t:?}", self.k),
            ))
        }
    }

    fn ring(&mut self) -> Result<Vec<Point>, LoadError> {
        let n = self.count("a vertex count")?;
        (0..n)
            .map(|_| Ok([self.number("an x coordinate")?, self.number("a y coordinate")?]))
            .collect()
    }
}

/// The domain as a GeoJSON Feature (rings closed, outer counter-clockwise, holes clockwise),
/// with the optional start point as the `start` property.
pub fn to_geojson(domain: &Domain, start: Option<Point>) -> Value {
    to_geojson_in(domain, start, &crate::geometry::Frame::IDENTITY)
}

/// [`to_geojson`] for a domain and start in the local `frame` of their input: the output is in
/// the input's coordinates (bit for bit, for a frame chosen by [`Frame::for_points`]).
///
/// [`Frame::for_points`]: crate::geometry::Frame::for_points
pub fn to_geojson_in(
    domain: &Domain,
    start: Option<Point>,
    frame: &crate::geometry::Frame,
) -> Value {
    let rings: Vec<Vec<Point>> = domain
        .rings()
        .iter()
        .map(|r| {
            let mut v: Vec<Point> = r.iter().map(|&p| frame.to_input(p)).collect();
            v.push(v[0]);
            v
        })
        .collect();
    let start = start.map(|s| frame.to_input(s));
    let mut props = serde_json::Map::new();
    if let Some(s) = start {
        props.insert("start".into(), serde_json::json!(s));
    }
    serde_json::json!({
        "type": "Feature",
        "properties": props,
        "geometry": {"type": "Polygon", "coordinates": rings},
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn geojson_round_trip() {
        let text = r#"{"type":"Feature","properties":{"start":[3,3]},"geometry":{"type":"Polygon","coordinates":[[[0,0],[4,0],[4,4],[0,4],[0,0]],[[1,1],[1,2],[2,2],[2,1],[1,1]]]}}"#;
        let e = parse_geojson(text, "t").unwrap();
        assert_eq!(e.domain.vertex_count(), 8);
        assert_eq!(e.start, Some([3.0, 3.0]));
        assert!(e.queries.is_empty());
        let back = to_geojson(&e.domain, Some([3.0, 3.0])).to_string();
        let again = parse_geojson(&back, "t").unwrap();
        assert_eq!(again.domain, e.domain);
    }

    #[test]
    fn wkt_and_pol() {
        let w = parse_wkt("POLYGON ((0 0, 4 0, 4 4, 0 4, 0 0), (1 1, 1 2, 2 2, 2 1, 1 1))", "t")
            .unwrap();
        assert_eq!(w.domain.vertex_count(), 8);
        let p = parse_pol("4 0/1 0 8/2 0 4 4 0 4 1 4 1 1 1 2 2 2 2 1", "t").unwrap();
        assert_eq!(p.domain, w.domain);
    }

    #[test]
    fn malformed_inputs_are_clear_errors() {
        type Parser = fn(&str, &str) -> Result<Environment, LoadError>;
        let cases: &[(&str, Parser, &str)] = &[
            ("{", parse_geojson, "invalid JSON"),
            (r#"{"type":"Point","coordinates":[0,0]}"#, parse_geojson, "Point"),
            (
                r#"{"type":"Feature","geometry":{"type":"Polygon","coordinates":[[[0,0],[1,"a"],[0,1]]]}}"#,
                parse_geojson,
                "coordinates[0][1]",
            ),
            (r#"{"type":"FeatureCollection","features":[]}"#, parse_geojson, "no Polygon"),
            (r#"{"type":"Polygon","coordinates":[]}"#, parse_geojson, "no polygon rings"),
            ("LINESTRING (0 0, 1 1)", parse_wkt, "expected POLYGON"),
            ("POLYGON ((0 0, 1 0, 0 1)", parse_wkt, "expected ',' or ')'"),
            ("POLYGON ((0 0, 1 x, 0 1))", parse_wkt, "finite number"),
            ("POLYGON ((0 0, 2 2, 2 0, 0 2))", parse_wkt, "not simple"),
            (
                "POLYGON ((0 0, 1 0, 0 1))\nPOLYGON ((2 0, 3 0, 2 1))",
                parse_wkt,
                ":2: unexpected text",
            ),
            ("POLYGON ((0 0, 1 0, 0 1)))", parse_wkt, "unexpected text after the POLYGON"),
            (
                r#"{"type":"Feature","properties":{"start":[1,2,3]},"geometry":{"type":"Polygon","coordinates":[[[0,0],[4,0],[0,4]]]}}"#,
                parse_geojson,
                "properties.start must be [x, y]",
            ),
            (
                r#"{"type":"Feature","properties":{"start":null},"geometry":{"type":"Polygon","coordinates":[[[0,0],[4,0],[0,4]]]}}"#,
                parse_geojson,
                "leave the property out",
            ),
            ("3 0 0 1 0", parse_pol, "ends"),
            ("3 0 0 1/0 0 0 1", parse_pol, "p/q"),
            ("3 0 0 1 0 0 1 1 3 5 5 6 5 5 6", parse_pol, "outside"),
            ("3 0 0 1 0 0 1 junk", parse_pol, "count"),
            ("x", parse_pol, "count"),
        ];
        for (text, f, needle) in cases {
            let e = f(text, "file.x").unwrap_err().to_string();
            assert!(e.contains(needle) && e.contains("file.x"), "{text:?}: {e}");
        }
    }
}
