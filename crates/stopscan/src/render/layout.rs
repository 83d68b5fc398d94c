//! Where things go on a chart, in pixels, with no drawing backend: axis ticks and their
//! labels, and the corner the legend takes so that it covers no data.

use crate::kernel::tolerance::COUNT_SLACK;

/// An axis's ticks and the decimals their labels print with.
#[derive(Debug, Clone, PartialEq)]
pub struct Ticks {
    /// The tick values, ascending.
    pub values: Vec<f64>,
    /// The decimals the step needs (0 for whole steps).
    pub decimals: usize,
}

/// Axis ticks on `[lo, hi]`: the multiples of the finest step `m·10^k` (m = 1, 2 or 5) that
/// gives at most `max` ticks, and the number of decimals that step needs (0 for whole steps,
/// so counts print as `5`, not `5.0`).
pub fn ticks(lo: f64, hi: f64, max: usize) -> Ticks {
    let span = (hi - lo).abs().max(f64::MIN_POSITIVE);
    let mut k = (span / max.max(1) as f64).log10().floor() as i32 - 1;
    loop {
        for m in [1.0, 2.0, 5.0] {
            let step = m * 10f64.powi(k);
            let (first, last) =
                ((lo / step - COUNT_SLACK).ceil(), (hi / step + COUNT_SLACK).floor());
            if last - first + 1.0 <= max as f64 {
                let decimals = (-k).max(0) as usize;
                let values = (first as i64..=last as i64).map(|i| i as f64 * step).collect();
                return Ticks { values, decimals };
            }
        }
        k += 1;
    }
}

/// A tick label with a fixed number of decimals (never `-0`).
pub fn tick_label(v: f64, decimals: usize) -> String {
    let s = format!("{v:.decimals$}");
    if s.trim_start_matches('-').chars().all(|c| c == '0' || c == '.') {
        s.trim_start_matches('-').to_string()
    } else {
        s
    }
}

/// A width and a height in pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PixelSize {
    /// Width.
    pub width: f64,
    /// Height.
    pub height: f64,
}

/// A rectangle in pixels, `left ≤ x ≤ right`, `top ≤ y ≤ bottom`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PixelBox {
    /// Left edge.
    pub left: f64,
    /// Top edge.
    pub top: f64,
    /// Right edge.
    pub right: f64,
    /// Bottom edge.
    pub bottom: f64,
}

impl PixelBox {
    /// Whether the segment from `a` to `b` meets the box (Liang–Barsky clipping).
    pub fn meets_segment(&self, a: (f64, f64), b: (f64, f64)) -> bool {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let (mut t0, mut t1) = (0.0f64, 1.0f64);
        for (p, q) in [
            (-dx, a.0 - self.left),
            (dx, self.right - a.0),
            (-dy, a.1 - self.top),
            (dy, self.bottom - a.1),
        ] {
            if p == 0.0 {
                if q < 0.0 {
                    return false;
                }
            } else {
                let t = q / p;
                if p < 0.0 {
                    t0 = t0.max(t);
                } else {
                    t1 = t1.min(t);
                }
                if t0 > t1 {
                    return false;
                }
            }
        }
        true
    }

    /// Whether any line (a polyline of pixel points; one point is a marker) comes within
    /// `clear` pixels of the box.
    pub fn meets_any(&self, lines: &[Vec<(f64, f64)>], clear: f64) -> bool {
        let grown = Self {
            left: self.left - clear,
            top: self.top - clear,
            right: self.right + clear,
            bottom: self.bottom + clear,
        };
        lines.iter().any(|l| match l.as_slice() {
            [] => false,
            [p] => grown.meets_segment(*p, *p),
            l => l.windows(2).any(|w| grown.meets_segment(w[0], w[1])),
        })
    }
}

/// Space kept between the legend box and any data line or marker, in pixels (lines are 2 px
/// wide, markers have a 3 px radius).
pub const LEGEND_CLEARANCE: f64 = 5.0;
/// The legend box's distance from the plotting area's edges, in pixels.
pub(super) const LEGEND_INSET: f64 = 8.0;

/// Where the legend box (`size` pixels) goes in a plotting area of `plot` pixels: the first
/// corner (upper right, upper left, lower right, lower left) where no data line or marker
/// (`lines`, in pixels relative to the plotting area) comes within [`LEGEND_CLEARANCE`] of
/// it. `None` when every corner is taken.
pub fn legend_corner(
    plot: PixelSize,
    size: PixelSize,
    lines: &[Vec<(f64, f64)>],
) -> Option<PixelBox> {
    let (w, h) = (size.width, size.height);
    let (left, right) = (LEGEND_INSET, plot.width - LEGEND_INSET - w);
    let (top, bottom) = (LEGEND_INSET, plot.height - LEGEND_INSET - h);
    [(right, top), (left, top), (right, bottom), (left, bottom)]
        .into_iter()
        .map(|(x, y)| PixelBox { left: x, top: y, right: x + w, bottom: y + h })
        .find(|b| b.left >= 0.0 && b.top >= 0.0 && !b.meets_any(lines, LEGEND_CLEARANCE))
}

/// How a chart is laid out: axis ranges and ticks, its data in pixels and the legend box.
#[derive(Debug, Clone, PartialEq)]
pub struct ChartLayout {
    /// X range.
    pub x: std::ops::Range<f64>,
    /// Y range (raised above the data when no corner was free for the legend).
    pub y: std::ops::Range<f64>,
    /// X ticks.
    pub x_ticks: Ticks,
    /// Y ticks.
    pub y_ticks: Ticks,
    /// Every series (one polyline, and one single-point line per marker), as `(x, y)` pixels
    /// relative to the plotting area (the drawing backend's coordinate pairs).
    pub lines: Vec<Vec<(f64, f64)>>,
    /// The plotting area's size in pixels.
    pub plot: PixelSize,
    /// The legend box, relative to the plotting area.
    pub legend: PixelBox,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn count_axes_print_whole_numbers() {
        // Fig. 7 (c): 1 to 32 robots, padded by 4%.
        let Ticks { values: t, decimals: d } = ticks(1.0 - 1.24, 32.0 + 1.24, 10);
        assert_eq!(d, 0);
        let labels: Vec<String> = t.iter().map(|&v| tick_label(v, d)).collect();
        assert_eq!(labels, ["0", "5", "10", "15", "20", "25", "30"]);
        // Cells 40–400.
        let Ticks { values: t, decimals: d } = ticks(25.6, 414.4, 10);
        assert_eq!((t[0], d), (50.0, 0));
        assert!(t.iter().all(|v| !tick_label(*v, d).contains('.')));
        // A fractional axis keeps one decimal throughout: 1.5, 2.0, … 6.0.
        let Ticks { values: t, decimals: d } = ticks(1.32, 6.18, 10);
        assert_eq!(d, 1);
        assert_eq!(tick_label(t[0], d), "1.5");
        assert_eq!(tick_label(t[1], d), "2.0");
        assert!(t.len() <= 10);
        // Sign of zero and tiny steps.
        assert_eq!(tick_label(-0.0, 0), "0");
        assert_eq!(tick_label(-1e-17, 2), "0.00");
        let Ticks { values: t, decimals: d } = ticks(0.0, 0.003, 8);
        assert_eq!(d, 4);
        assert_eq!(tick_label(t[1], d), "0.0005");
    }

    #[test]
    fn legend_takes_the_first_free_corner() {
        let plot = PixelSize { width: 800.0, height: 400.0 };
        let size = PixelSize { width: 150.0, height: 80.0 };
        // A flat line along the top covers both upper corners.
        let top = vec![(0.0, 20.0), (800.0, 20.0)];
        let b = legend_corner(plot, size, std::slice::from_ref(&top)).unwrap();
        assert_eq!((b.left, b.top), (800.0 - 8.0 - 150.0, 400.0 - 8.0 - 80.0), "lower right");
        assert!(!b.meets_any(std::slice::from_ref(&top), LEGEND_CLEARANCE));
        // A marker alone in the lower right corner moves it to the lower left.
        let marker = vec![(700.0, 350.0)];
        let b = legend_corner(plot, size, &[top.clone(), marker]).unwrap();
        assert_eq!((b.left, b.top), (8.0, 312.0));
        // A diagonal through the whole plot leaves the other two corners.
        let diag = vec![(0.0, 0.0), (800.0, 400.0)];
        let b = legend_corner(plot, size, std::slice::from_ref(&diag)).unwrap();
        assert_eq!((b.left, b.top), (642.0, 8.0));
        // Every corner taken.
        let bottom = vec![(0.0, 380.0), (800.0, 380.0)];
        assert!(legend_corner(plot, size, &[top, bottom]).is_none());
    }

    #[test]
    fn segments_meet_boxes_exactly() {
        let b = PixelBox { left: 10.0, top: 10.0, right: 20.0, bottom: 20.0 };
        assert!(b.meets_segment((0.0, 15.0), (30.0, 15.0)));
        assert!(b.meets_segment((15.0, 15.0), (15.0, 15.0)));
        assert!(!b.meets_segment((0.0, 0.0), (9.0, 30.0)));
        assert!(b.meets_segment((0.0, 0.0), (30.0, 30.0)));
        assert!(!b.meets_segment((21.0, 0.0), (40.0, 30.0)));
        assert!(!b.meets_any(&[vec![(25.0, 15.0)]], 4.0));
        assert!(b.meets_any(&[vec![(23.0, 15.0)]], 4.0));
    }
}
