//! Policy images like the corner paper's Fig. 4 and Fig. 6: one coloured cell per MDP state.

use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::prelude::*;

use super::RenderError;
use super::glyphs::PaddedText;
use crate::strategy::corner::mdp::StateAction;

/// Writes a policy image like the corner paper's Fig. 4 / Fig. 6 as `stem.svg` and `stem.png`.
/// For MDP2, row `i` (downwards) is the robot's stop and column `j` the last scan's stop; for
/// MDP1 (two rows) the columns are stops and the rows `s_i` and `s'_i`. Blue is inaccessible,
/// green reconstruct, red move.
///
/// # Errors
/// [`RenderError`] if the image is empty or cannot be drawn.
pub fn write_policy_image(
    rows: &[Vec<StateAction>],
    title: &str,
    stem: &Path,
) -> Result<Vec<PathBuf>, RenderError> {
    if rows.is_empty() || rows[0].is_empty() {
        return Err(RenderError::Empty(title.into()));
    }
    let svg = stem.with_extension("svg");
    let png = stem.with_extension("png");
    let side = 560u32;
    let h = if rows.len() <= 2 { 220 } else { side + 60 };
    draw_policy(&SVGBackend::new(&svg, (side + 80, h)).into_drawing_area(), rows, title)
        .map_err(|reason| RenderError::Draw { path: svg.clone(), reason })?;
    draw_policy(
        &PaddedText(BitMapBackend::new(&png, (side + 80, h))).into_drawing_area(),
        rows,
        title,
    )
    .map_err(|reason| RenderError::Draw { path: png.clone(), reason })?;
    Ok(vec![svg, png])
}

fn draw_policy<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    rows: &[Vec<StateAction>],
    title: &str,
) -> Result<(), String> {
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let (n_rows, n_cols) = (rows.len() as f64, rows[0].len() as f64);
    let mut ctx = ChartBuilder::on(root)
        .caption(title, ("sans-serif", 15))
        .margin(10)
        .x_label_area_size(48)
        .y_label_area_size(44)
        .build_cartesian_2d(0.0..n_cols, n_rows..0.0)
        .map_err(|e| e.to_string())?;
    ctx.configure_mesh()
        .disable_mesh()
        .x_desc(if rows.len() <= 2 {
            "stop i   (green: reconstruct, red: move, blue: no such state)"
        } else {
            "last scan stop j   (green: reconstruct, red: move, blue: no such state)"
        })
        .y_desc(if rows.len() <= 2 { "top: s_i, bottom: s'_i" } else { "current stop i" })
        .y_labels(if rows.len() <= 2 { 3 } else { 10 })
        .x_label_formatter(&|v| format!("{v:.0}"))
        .y_label_formatter(&|v| format!("{v:.0}"))
        .draw()
        .map_err(|e| e.to_string())?;
    let cells = rows.iter().enumerate().flat_map(|(i, row)| {
        row.iter().enumerate().map(move |(j, c)| {
            let color = match c {
                StateAction::Inaccessible => RGBColor(70, 110, 200),
                StateAction::Move => RGBColor(200, 50, 50),
                StateAction::Reconstruct => RGBColor(60, 170, 70),
            };
            Rectangle::new([(j as f64, i as f64), (j as f64 + 1.0, i as f64 + 1.0)], color.filled())
        })
    });
    ctx.draw_series(cells).map_err(|e| e.to_string())?;
    root.present().map_err(|e| e.to_string())
}
