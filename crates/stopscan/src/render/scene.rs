//! SVG scenes of a domain with visibility regions, written by hand (exact coordinates, no
//! rasterisation, deterministic text).

use std::fmt::Write;

use crate::algorithm::visibility::{BoundaryPiece, VisibilityRegion};
use crate::geometry::Domain;

/// The smallest width or height a scene is scaled from (metres), so that a degenerate domain
/// does not divide by zero.
const MIN_EXTENT: f64 = 1e-9;

/// An SVG picture of the domain (free space white, holes grey) with each region translucent,
/// its windows dashed and its viewpoint marked.
pub fn scene_svg(domain: &Domain, regions: &[VisibilityRegion]) -> String {
    const COLOURS: [&str; 6] = ["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b"];
    let [lo, hi] = domain.bounds();
    let (w, h) = ((hi[0] - lo[0]).max(MIN_EXTENT), (hi[1] - lo[1]).max(MIN_EXTENT));
    let scale = 800.0 / w.max(h);
    let (pw, ph) = (w * scale + 20.0, h * scale + 20.0);
    let x = |v: f64| 10.0 + (v - lo[0]) * scale;
    let y = |v: f64| 10.0 + (hi[1] - v) * scale;
    let path = |ring: &[[f64; 2]]| {
        let mut s = String::new();
        for (i, p) in ring.iter().enumerate() {
            let _ = write!(s, "{}{:.3},{:.3} ", if i == 0 { "M" } else { "L" }, x(p[0]), y(p[1]));
        }
        s.push('Z');
        s
    };
    let mut out = String::new();
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{pw:.0}" height="{ph:.0}" viewBox="0 0 {pw:.3} {ph:.3}">"#
    );
    let _ = writeln!(out, r##"<rect width="100%" height="100%" fill="#b8b8b8"/>"##);
    let mut d = path(domain.outer());
    for hole in domain.holes() {
        d.push(' ');
        d.push_str(&path(hole));
    }
    let _ = writeln!(
        out,
        r##"<path d="{d}" fill="#ffffff" fill-rule="evenodd" stroke="#222" stroke-width="1"/>"##
    );
    for (k, r) in regions.iter().enumerate() {
        let c = COLOURS[k % COLOURS.len()];
        let _ = writeln!(
            out,
            r#"<path d="{}" fill="{c}" fill-opacity="0.25" stroke="{c}" stroke-width="1"/>"#,
            path(&r.polygon)
        );
        for b in r.windows() {
            if let BoundaryPiece::Window { reflex, far, .. } = b {
                let _ = writeln!(
                    out,
                    r#"<line x1="{:.3}" y1="{:.3}" x2="{:.3}" y2="{:.3}" stroke="{c}" stroke-width="1.5" stroke-dasharray="4 3"/>"#,
                    x(reflex[0]),
                    y(reflex[1]),
                    x(far[0]),
                    y(far[1])
                );
            }
        }
        let _ = writeln!(
            out,
            r##"<circle cx="{:.3}" cy="{:.3}" r="4" fill="{c}" stroke="#000"/>"##,
            x(r.viewpoint[0]),
            y(r.viewpoint[1])
        );
    }
    out.push_str("</svg>\n");
    out
}

/// An SVG of an exploration run: the domain, each scan's region in a translucent colour, the
/// path driven, and the scan points numbered in order.
pub fn exploration_svg(domain: &Domain, regions: &[VisibilityRegion], path: &[[f64; 2]]) -> String {
    let base = scene_svg(domain, &[]);
    let [lo, hi] = domain.bounds();
    let (w, h) = ((hi[0] - lo[0]).max(MIN_EXTENT), (hi[1] - lo[1]).max(MIN_EXTENT));
    let scale = 800.0 / w.max(h);
    let x = |v: f64| 10.0 + (v - lo[0]) * scale;
    let y = |v: f64| 10.0 + (hi[1] - v) * scale;
    let mut out = base.trim_end().trim_end_matches("</svg>").to_string();
    out.push('\n');
    for (k, r) in regions.iter().enumerate() {
        let hue = (k * 137) % 360;
        let mut d = String::new();
        for (i, p) in r.polygon.iter().enumerate() {
            let _ = write!(d, "{}{:.3},{:.3} ", if i == 0 { "M" } else { "L" }, x(p[0]), y(p[1]));
        }
        let _ = writeln!(
            out,
            r#"<path d="{d}Z" fill="hsl({hue},70%,55%)" fill-opacity="0.18" stroke="none"/>"#
        );
    }
    let pts: Vec<String> = path.iter().map(|p| format!("{:.3},{:.3}", x(p[0]), y(p[1]))).collect();
    let _ = writeln!(
        out,
        r##"<polyline points="{}" fill="none" stroke="#111" stroke-width="1.5"/>"##,
        pts.join(" ")
    );
    for (k, r) in regions.iter().enumerate() {
        let (cx, cy) = (x(r.viewpoint[0]), y(r.viewpoint[1]));
        let _ = writeln!(
            out,
            r##"<circle cx="{cx:.3}" cy="{cy:.3}" r="5" fill="#d62728" stroke="#000"/><text x="{:.3}" y="{:.3}" font-family="sans-serif" font-size="11">{}</text>"##,
            cx + 6.0,
            cy - 6.0,
            k + 1
        );
    }
    out.push_str("</svg>\n");
    out
}
