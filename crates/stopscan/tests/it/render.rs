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

// ---------------------------------------------------------------------------------------------
// The exploration picture, read back from its SVG: numbers that never collide, the legend.

mod exploration_picture {
    use stopscan::algorithm::visibility::VisibilityRegion;
    use stopscan::geometry::Domain;
    use stopscan::render::{SceneExtras, exploration_svg};

    type Point = [f64; 2];

    /// A box, `[left, top, right, bottom]`.
    type Box4 = [f64; 4];

    fn overlap(a: &Box4, b: &Box4) -> bool {
        a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]
    }

    fn attr(tag: &str, name: &str) -> Option<String> {
        let key = format!(" {name}=\"");
        let at = tag.find(&key)? + key.len();
        Some(tag[at..].split('"').next()?.to_string())
    }

    fn num(tag: &str, name: &str) -> f64 {
        attr(tag, name).unwrap_or_else(|| panic!("no {name} in {tag}")).parse().unwrap()
    }

    /// The contents of the first `<g class="CLASS" …>` up to its `</g>` (the picture's groups
    /// do not nest), with the opening tag.
    fn group<'a>(svg: &'a str, class: &str) -> Option<(&'a str, &'a str)> {
        let at = svg.find(&format!("<g class=\"{class}\""))?;
        let rest = &svg[at..];
        let open = &rest[..=rest.find('>')?];
        Some((open, &rest[open.len()..rest.find("</g>")?]))
    }

    /// Every `<text …>WORDS</text>` of `part`: its opening tag and words.
    fn texts(part: &str) -> Vec<(&str, &str)> {
        part.match_indices("<text ")
            .map(|(i, _)| {
                let rest = &part[i..];
                let close = rest.find('>').unwrap();
                (&rest[..=close], &rest[close + 1..rest.find("</text>").unwrap()])
            })
            .collect()
    }

    struct Picture {
        width: f64,
        height: f64,
        /// Each number drawn and its box, as the API documents it: centred on x, font·(0.64·
        /// digits + 0.2) wide, from 0.8·font above the baseline to 0.15·font below.
        labels: Vec<(usize, Box4)>,
        /// Each marker's bounding square.
        markers: Vec<Box4>,
        marker_fills: Vec<String>,
        legend: Box4,
        legend_words: Vec<String>,
    }

    fn read(svg: &str) -> Picture {
        let root = &svg[..svg.find('>').unwrap()];
        let (open, body) = group(svg, "scan-labels").expect("a scan-labels group");
        let font = num(open, "font-size");
        assert_eq!(attr(open, "text-anchor").as_deref(), Some("middle"));
        let labels = texts(body)
            .into_iter()
            .map(|(tag, words)| {
                let (x, y) = (num(tag, "x"), num(tag, "y"));
                let half = 0.5 * font * (0.64 * words.len() as f64 + 0.2);
                (words.parse().unwrap(), [x - half, y - 0.8 * font, x + half, y + 0.15 * font])
            })
            .collect();
        let (_, body) = group(svg, "scans").expect("a scans group");
        let circles: Vec<&str> = body.split("<circle").skip(1).collect();
        let markers = circles
            .iter()
            .map(|c| {
                let (x, y, r) = (num(c, "cx"), num(c, "cy"), num(c, "r"));
                [x - r, y - r, x + r, y + r]
            })
            .collect();
        let marker_fills = circles.iter().map(|c| attr(c, "fill").unwrap()).collect();
        let (_, body) = group(svg, "legend").expect("a legend group");
        let rect = &body[body.find("<rect").unwrap()..];
        let (x, y) = (num(rect, "x"), num(rect, "y"));
        let legend = [x, y, x + num(rect, "width"), y + num(rect, "height")];
        let legend_words = texts(body).into_iter().map(|(_, w)| w.to_string()).collect();
        Picture {
            width: num(root, "width"),
            height: num(root, "height"),
            labels,
            markers,
            marker_fills,
            legend,
            legend_words,
        }
    }

    fn square(c: Point, half: f64) -> Vec<Point> {
        vec![
            [c[0] - half, c[1] - half],
            [c[0] + half, c[1] - half],
            [c[0] + half, c[1] + half],
            [c[0] - half, c[1] + half],
        ]
    }

    /// A scan at each of `points`, seeing a small square around it, driven in order.
    fn scene(points: &[Point]) -> (Vec<VisibilityRegion>, Vec<Point>) {
        let regions = points
            .iter()
            .map(|&p| VisibilityRegion { viewpoint: p, polygon: square(p, 0.4), boundary: vec![] })
            .collect();
        (regions, points.to_vec())
    }

    fn rectangle(w: f64, h: f64, holes: Vec<Vec<Point>>) -> Domain {
        Domain::new(vec![[0.0, 0.0], [w, 0.0], [w, h], [0.0, h]], holes).unwrap()
    }

    /// 400 scans: a 30 × 10 grid a few label widths apart, 100 piled within half a metre in the
    /// middle of it. No two numbers overlap, none covers a marker or the legend, each is a
    /// distinct scan's (in order), and the legend says how many were numbered.
    #[test]
    fn four_hundred_scans_get_numbers_that_never_collide() {
        let mut points = Vec::new();
        for i in 0..300 {
            points.push([1.5 + f64::from(i % 30) * 3.3, 1.5 + f64::from(i / 30) * 3.2]);
        }
        for i in 0..100 {
            points.push([50.0 + f64::from(i % 10) * 0.05, 16.0 + f64::from(i / 10) * 0.05]);
        }
        let domain = rectangle(100.0, 33.0, vec![square([20.0, 20.0], 1.0)]);
        let (regions, path) = scene(&points);
        let svg = exploration_svg(&domain, &regions, &path, SceneExtras::default());
        assert_eq!(svg, exploration_svg(&domain, &regions, &path, SceneExtras::default()));
        let p = read(&svg);

        assert_eq!(p.markers.len(), 400);
        assert_eq!(p.marker_fills.first().map(String::as_str), Some("#440154"), "first: dark");
        assert_eq!(p.marker_fills.last().map(String::as_str), Some("#fde725"), "last: yellow");
        let drawn = p.labels.len();
        assert!(drawn > 100 && drawn < 400, "{drawn} numbered");
        assert!(p.labels.windows(2).all(|w| w[0].0 < w[1].0), "distinct, in scan order");
        assert!(p.labels.iter().all(|&(k, _)| (1..=400).contains(&k)));
        for (i, (k, a)) in p.labels.iter().enumerate() {
            assert!(a[0] >= 0.0 && a[2] <= p.width && a[1] >= 0.0 && a[3] <= p.legend[1], "{k}");
            assert!(!overlap(a, &p.legend), "{k} covers the legend");
            for (j, b) in p.labels.iter().enumerate().skip(i + 1) {
                assert!(!overlap(a, &b.1), "{k} and {} overlap", p.labels[j].0);
            }
            for (m, b) in p.markers.iter().enumerate() {
                assert!(!overlap(a, b), "{k} covers the marker of scan {}", m + 1);
            }
        }

        assert!(p.legend[2] <= p.width && p.legend[3] <= p.height, "the legend is on the canvas");
        for words in [
            "free space",
            "obstacles and outside",
            "scan regions: tinted by the first scan to see them",
            "path",
            "start",
            "scan order",
            "1",
            "400",
        ] {
            assert!(p.legend_words.iter().any(|w| w == words), "legend lacks {words:?}");
        }
        let count = format!("scan points, numbered where there is room ({drawn} of 400)");
        assert!(p.legend_words.contains(&count), "{:?}", p.legend_words);
        assert!(!p.legend_words.iter().any(|w| w.contains("configuration space")));
        assert!(!svg.contains("class=\"cspace\""));
    }

    /// The configuration space is drawn (every component's rings, beneath the path) and named
    /// in the legend only when given.
    #[test]
    fn the_configuration_space_is_drawn_when_given() {
        let domain = rectangle(20.0, 10.0, vec![square([10.0, 5.0], 1.0)]);
        let (regions, path) = scene(&[[2.0, 2.0], [18.0, 8.0]]);
        let cspace = vec![
            vec![square([5.0, 5.0], 4.0), square([5.0, 5.0], 1.0)],
            vec![square([15.0, 5.0], 4.0)],
        ];
        let with = SceneExtras { cspace: Some(&cspace), ..SceneExtras::default() };
        let svg = exploration_svg(&domain, &regions, &path, with);
        assert_eq!(svg.matches("class=\"cspace\"").count(), 1);
        let layer = &svg[svg.find("class=\"cspace\"").unwrap()..];
        let d = attr(&layer[..layer.find("/>").unwrap()], "d").unwrap();
        assert_eq!(d.matches('M').count(), 3, "three rings: {d}");
        assert!(svg.find("class=\"cspace\"") < svg.find("class=\"path\""), "beneath the path");
        assert!(read(&svg).legend_words.iter().any(|w| w == "configuration space"));
        let none = exploration_svg(&domain, &regions, &path, SceneExtras::default());
        assert!(!none.contains("cspace") && !none.contains("configuration space"));
    }

    /// Relays are drawn as diamonds, one per relay and at its scan's place, and named in the
    /// legend with their count; without relays there is neither.
    #[test]
    fn relays_are_drawn_as_diamonds() {
        let domain = rectangle(20.0, 10.0, vec![]);
        let (regions, path) = scene(&[[2.0, 2.0], [10.0, 5.0], [18.0, 8.0]]);
        let relays = [false, true, false];
        let with = SceneExtras { relays: Some(&relays), ..SceneExtras::default() };
        let svg = exploration_svg(&domain, &regions, &path, with);
        assert_eq!(svg.matches("class=\"relay\"").count(), 1);
        let none = exploration_svg(&domain, &regions, &path, SceneExtras::default());
        let circles = |s: &str| s.matches("<circle").count();
        assert_eq!(circles(&svg) + 1, circles(&none));
        assert!(read(&svg).legend_words.iter().any(|w| w.contains("relays") && w.contains("(1)")));
        assert!(!none.contains("relay"));
        let all_false = [false; 3];
        let quiet = SceneExtras { relays: Some(&all_false), ..SceneExtras::default() };
        assert_eq!(exploration_svg(&domain, &regions, &path, quiet), none);
    }

    /// A small scene with room everywhere numbers every scan, the one at the start included;
    /// a map narrower than its legend widens the canvas rather than cutting the legend.
    #[test]
    fn a_small_scene_numbers_every_scan() {
        let points: Vec<Point> =
            (0..12).map(|i| [2.0 + f64::from(i % 4) * 5.0, 2.0 + f64::from(i / 4) * 3.5]).collect();
        let domain = rectangle(20.0, 10.0, vec![]);
        let (regions, path) = scene(&points);
        let p = read(&exploration_svg(&domain, &regions, &path, SceneExtras::default()));
        assert_eq!(p.labels.iter().map(|l| l.0).collect::<Vec<_>>(), (1..=12).collect::<Vec<_>>());
        assert!(p.legend_words.iter().any(|w| w.ends_with("(12 of 12)")));

        let corridor = rectangle(1.0, 50.0, vec![]);
        let (regions, path) = scene(&[[0.5, 1.0], [0.5, 25.0], [0.5, 49.0]]);
        let svg = exploration_svg(&corridor, &regions, &path, SceneExtras::default());
        let p = read(&svg);
        assert!(p.legend[2] <= p.width && p.legend[3] <= p.height);
        assert!(p.width > 200.0, "widened for the legend: {}", p.width);
        assert_eq!(p.labels.len(), 3);
    }
}
