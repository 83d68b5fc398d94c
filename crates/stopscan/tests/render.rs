//! Charts as the reproductions draw them: the layout of every produced chart. (Unit tests of
//! the ticks and the legend's corner live beside them in `render::layout`; this one needs the
//! experiments, which stand above `render`.)

use stopscan::experiment;
use stopscan::render::{LEGEND_CLEARANCE, chart_layout};

/// Every chart the reproductions and the demo draw: the legend box stays clear of every
/// line and marker, and charts with fixed parameters say so under the title.
#[test]
fn legends_never_cover_data_in_the_produced_charts() {
    let mut charts = Vec::new();
    for id in ["corner-fig-7", "corner-fig-8", "roi-fig-7"] {
        charts.extend(experiment::reproduce(id, 2, 1).unwrap().charts);
    }
    charts.push(experiment::NamedChart::new("demo", experiment::corner::demo().unwrap().chart));
    assert!(charts.len() >= 7);
    for experiment::NamedChart { stem: name, chart } in &charts {
        let l = chart_layout(chart).unwrap();
        assert!(!l.legend.meets_any(&l.lines, LEGEND_CLEARANCE), "{name}");
        assert!(l.legend.left >= 0.0 && l.legend.right <= l.plot.width, "{name}");
        assert!(l.legend.top >= 0.0 && l.legend.bottom <= l.plot.height, "{name}");
        if name.starts_with("roi-fig-7") || name.starts_with("corner-fig") {
            assert!(!chart.subtitle.is_empty(), "{name} states no fixed parameters");
        }
    }
}
