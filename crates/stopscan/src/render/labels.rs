//! Where the scan numbers of an exploration picture go: greedily, in scan order, each number
//! takes the first of eight spots around its marker where its box stays inside the map area
//! and clear of every marker, every reserved box (the legend, the start) and every number
//! already placed; a scan with no such spot is not numbered. A uniform grid of boxes keeps
//! each test local, so hundreds of scans place in well under a millisecond each.

use super::layout::PixelBox;

/// A digit's advance, in ems: DejaVu Sans (the widest common sans-serif digits) has 0.636,
/// Liberation Sans and Arial 0.556.
pub(super) const DIGIT_EM: f64 = 0.64;
/// Space added on each side of a label's digits, in ems.
pub(super) const SIDE_EM: f64 = 0.1;
/// How far a label's box reaches above its baseline, in ems (digits stand 0.73 em high).
pub(super) const ASCENT_EM: f64 = 0.8;
/// How far a label's box reaches below its baseline, in ems (digits have no descenders).
pub(super) const DESCENT_EM: f64 = 0.15;

/// The box a label of `digits` digits at font size `font` occupies when drawn centred on `x`
/// (`text-anchor="middle"`) with its baseline at `y`: `font·(DIGIT_EM·digits + 2·SIDE_EM)`
/// wide, from `ASCENT_EM·font` above the baseline to `DESCENT_EM·font` below it.
pub(super) fn label_box(x: f64, y: f64, digits: usize, font: f64) -> PixelBox {
    let half = 0.5 * font * (DIGIT_EM * digits as f64 + 2.0 * SIDE_EM);
    PixelBox {
        left: x - half,
        top: y - ASCENT_EM * font,
        right: x + half,
        bottom: y + DESCENT_EM * font,
    }
}

/// Whether two boxes share interior points (boxes that only touch do not overlap).
pub(super) fn overlap(a: &PixelBox, b: &PixelBox) -> bool {
    a.left < b.right && b.left < a.right && a.top < b.bottom && b.top < a.bottom
}

/// Whether `inner` lies within `outer` (edges included).
fn inside(inner: &PixelBox, outer: &PixelBox) -> bool {
    inner.left >= outer.left
        && inner.right <= outer.right
        && inner.top >= outer.top
        && inner.bottom <= outer.bottom
}

/// Boxes filed in a uniform grid of square cells over an area: a box is listed in every cell
/// it overlaps, so a query looks only at the boxes of the cells it overlaps.
struct Grid {
    origin: (f64, f64),
    cell: f64,
    cols: usize,
    rows: usize,
    cells: Vec<Vec<usize>>,
    boxes: Vec<PixelBox>,
}

impl Grid {
    fn new(area: &PixelBox, cell: f64) -> Self {
        let cols = (((area.right - area.left) / cell).ceil() as usize).max(1);
        let rows = (((area.bottom - area.top) / cell).ceil() as usize).max(1);
        let cells = vec![Vec::new(); cols * rows];
        Self { origin: (area.left, area.top), cell, cols, rows, cells, boxes: Vec::new() }
    }

    /// The cells `b` overlaps: columns and rows, clamped to the grid (a box beyond the area
    /// is filed in the border cells).
    fn span(
        &self,
        b: &PixelBox,
    ) -> (std::ops::RangeInclusive<usize>, std::ops::RangeInclusive<usize>) {
        let index =
            |v: f64, o: f64, n: usize| (((v - o) / self.cell).floor().max(0.0) as usize).min(n - 1);
        let c0 = index(b.left, self.origin.0, self.cols);
        let c1 = index(b.right, self.origin.0, self.cols);
        let r0 = index(b.top, self.origin.1, self.rows);
        let r1 = index(b.bottom, self.origin.1, self.rows);
        (c0..=c1, r0..=r1)
    }

    fn insert(&mut self, b: PixelBox) {
        let id = self.boxes.len();
        self.boxes.push(b);
        let (cols, rows) = self.span(&b);
        for r in rows {
            for c in cols.clone() {
                self.cells[r * self.cols + c].push(id);
            }
        }
    }

    /// Whether `b` overlaps any filed box.
    fn hits(&self, b: &PixelBox) -> bool {
        let (cols, rows) = self.span(b);
        rows.into_iter().any(|r| {
            cols.clone()
                .any(|c| self.cells[r * self.cols + c].iter().any(|&i| overlap(&self.boxes[i], b)))
        })
    }
}

/// What the placement needs to know of the picture, in pixels.
#[derive(Debug, Clone, Copy)]
pub(super) struct LabelSpace {
    /// Where labels may go (the map area).
    pub area: PixelBox,
    /// The labels' font size.
    pub font: f64,
    /// The least gap between a label and another label or a marker.
    pub clearance: f64,
}

/// A scan's marker: its centre and how far what is drawn there reaches from it, each way (a
/// circle's radius, or half the side of a square drawn around it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Marker {
    pub x: f64,
    pub y: f64,
    pub reach: f64,
}

impl Marker {
    fn bounds(&self) -> PixelBox {
        let (x, y, r) = (self.x, self.y, self.reach);
        PixelBox { left: x - r, top: y - r, right: x + r, bottom: y + r }
    }
}

/// A placed label: scan `scan` (0-based), drawn centred on `x` with its baseline at `y`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Placed {
    pub scan: usize,
    pub x: f64,
    pub y: f64,
}

/// The labels of the scans at `markers` (in scan order) that have room, in scan order: scan
/// k is numbered k + 1 at the first spot beside its marker's square (right, upper right, lower
/// right, left, upper left, lower left, above, below; `space.clearance` away from it) whose
/// box ([`label_box`]) lies inside `space.area` and, grown by `space.clearance`, overlaps no
/// marker's square, no box of `reserved` and no label placed before it.
pub(super) fn place_labels(
    markers: &[Marker],
    reserved: &[PixelBox],
    space: LabelSpace,
) -> Vec<Placed> {
    let LabelSpace { area, font, clearance } = space;
    let height = (ASCENT_EM + DESCENT_EM) * font;
    let widest = label_box(0.0, 0.0, digits(markers.len()), font);
    let reach = markers.iter().map(|m| m.reach).fold(0.0, f64::max);
    let cell = (widest.right - widest.left).max(height).max(2.0 * reach) + clearance;
    let mut grid = Grid::new(&area, cell);
    for m in markers {
        grid.insert(m.bounds());
    }
    for b in reserved {
        grid.insert(*b);
    }
    let mut placed = Vec::new();
    for (scan, m) in markers.iter().enumerate() {
        let n = digits(scan + 1);
        let b0 = label_box(0.0, 0.0, n, font);
        let (hw, hh) = (0.5 * (b0.right - b0.left), 0.5 * height);
        let (cx, cy, d) = (m.x, m.y, m.reach + clearance);
        // Box centres beside the marker's square; the baseline sits below the centre.
        let spots = [
            (cx + d + hw, cy),
            (cx + d + hw, cy - d - hh),
            (cx + d + hw, cy + d + hh),
            (cx - d - hw, cy),
            (cx - d - hw, cy - d - hh),
            (cx - d - hw, cy + d + hh),
            (cx, cy - d - hh),
            (cx, cy + d + hh),
        ];
        let below_centre = hh - DESCENT_EM * font;
        for (bx, by) in spots {
            let (x, y) = (bx, by + below_centre);
            let b = label_box(x, y, n, font);
            let grown = PixelBox {
                left: b.left - clearance,
                top: b.top - clearance,
                right: b.right + clearance,
                bottom: b.bottom + clearance,
            };
            if inside(&b, &area) && !grid.hits(&grown) {
                grid.insert(b);
                placed.push(Placed { scan, x, y });
                break;
            }
        }
    }
    placed
}

/// The number of decimal digits of `n` (1 for 0).
pub(super) fn digits(n: usize) -> usize {
    n.checked_ilog10().map_or(1, |d| d as usize + 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn space(w: f64, h: f64) -> LabelSpace {
        LabelSpace {
            area: PixelBox { left: 0.0, top: 0.0, right: w, bottom: h },
            font: 12.0,
            clearance: 1.0,
        }
    }

    fn marker(x: f64, y: f64) -> Marker {
        Marker { x, y, reach: 5.0 }
    }

    fn boxes(placed: &[Placed], font: f64) -> Vec<PixelBox> {
        placed.iter().map(|p| label_box(p.x, p.y, digits(p.scan + 1), font)).collect()
    }

    #[test]
    fn digits_counts_decimal_digits() {
        assert_eq!([0, 9, 10, 99, 100, 400, 1000].map(digits), [1, 1, 2, 2, 3, 3, 4]);
    }

    #[test]
    fn sparse_markers_are_all_numbered_at_their_first_spot() {
        let markers: Vec<Marker> =
            (0..5).map(|i| marker(50.0 + 100.0 * f64::from(i), 100.0)).collect();
        let placed = place_labels(&markers, &[], space(600.0, 200.0));
        assert_eq!(placed.iter().map(|p| p.scan).collect::<Vec<_>>(), [0, 1, 2, 3, 4]);
        for (p, m) in placed.iter().zip(&markers) {
            let b = label_box(p.x, p.y, 1, 12.0);
            assert_eq!(b.left, m.x + 6.0, "right of its marker, a clearance away");
            assert!(b.top < m.y && b.bottom > m.y, "at its height");
        }
    }

    /// 400 markers, a quarter of them piled onto one spot: no two labels overlap, none
    /// covers a marker or a reserved box, every label stays in the area, and the first of the
    /// pile is numbered.
    #[test]
    fn dense_markers_never_get_overlapping_labels() {
        let mut markers = Vec::new();
        for i in 0..300 {
            markers.push(marker(20.0 + f64::from(i % 20) * 25.0, 20.0 + f64::from(i / 20) * 13.0));
        }
        for i in 0..100 {
            markers.push(marker(300.0 + f64::from(i % 10) * 0.5, 260.0 + f64::from(i / 10) * 0.5));
        }
        let s = space(520.0, 320.0);
        let reserved = [PixelBox { left: 400.0, top: 280.0, right: 520.0, bottom: 320.0 }];
        let placed = place_labels(&markers, &reserved, s);
        assert!(!placed.is_empty() && placed.len() < markers.len());
        assert!(placed.iter().any(|p| p.scan == 300));
        let b = boxes(&placed, s.font);
        for (i, a) in b.iter().enumerate() {
            assert!(inside(a, &s.area));
            assert!(!overlap(a, &reserved[0]));
            for c in &b[i + 1..] {
                assert!(!overlap(a, c), "{a:?} {c:?}");
            }
            for m in &markers {
                let square = PixelBox {
                    left: m.x - 5.0,
                    top: m.y - 5.0,
                    right: m.x + 5.0,
                    bottom: m.y + 5.0,
                };
                assert!(!overlap(a, &square));
            }
        }
        assert!(placed.windows(2).all(|w| w[0].scan < w[1].scan), "one label per scan, in order");
    }

    #[test]
    fn the_grid_finds_what_a_scan_of_all_boxes_finds() {
        let area = PixelBox { left: -10.0, top: -10.0, right: 90.0, bottom: 90.0 };
        let mut grid = Grid::new(&area, 7.0);
        let mut all = Vec::new();
        for i in 0..40 {
            let (x, y) = (f64::from(i * 37 % 97) - 5.0, f64::from(i * 53 % 89) - 5.0);
            let b =
                PixelBox { left: x, top: y, right: x + f64::from(i % 9) + 1.0, bottom: y + 3.0 };
            grid.insert(b);
            all.push(b);
        }
        for i in 0..500 {
            let (x, y) = (f64::from(i * 31 % 113) - 15.0, f64::from(i * 17 % 107) - 15.0);
            let q = PixelBox { left: x, top: y, right: x + 4.5, bottom: y + 2.5 };
            assert_eq!(grid.hits(&q), all.iter().any(|b| overlap(b, &q)), "{q:?}");
        }
    }
}
