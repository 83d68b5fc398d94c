//! Loaders: real files, and malformed files that must give clear errors, never panics.

use std::path::{Path, PathBuf};

use stopscan::algorithm::visibility::Visibility;
use stopscan::geometry::Location;
use stopscan::io::ros_map::{RosMapOptions, read};
use stopscan::io::{read_environment, text_formats::to_geojson_in};

fn fixture(p: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fixtures").join(p)
}

fn temp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("stopscan-io-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn turtlebot_world_becomes_a_valid_domain_and_round_trips() {
    let env = read(
        &fixture("ros-maps/turtlebot3_world.yaml"),
        &RosMapOptions { start: Some([-2.0, -0.5]), ..RosMapOptions::default() },
    )
    .unwrap();
    let d = &env.domain;
    // The map is in the frame of its grid; its origin is the YAML's.
    assert_eq!(env.frame.origin, [-10.0, -10.0]);
    let start = env.frame.to_local([-2.0, -0.5]);
    assert_eq!(env.start, Some(start));
    assert!(d.holes().len() >= 5, "the pillars are holes: {}", d.holes().len());
    assert!(d.area() > 10.0 && d.area() < 40.0, "area {}", d.area());
    assert_eq!(d.locate(start), Location::Interior);
    // The simplification only drops traced vertices: every vertex lies on the 5 cm grid of
    // the map.
    for p in d.rings().iter().flatten() {
        for v in p {
            let k = v / 0.05;
            assert!((k - k.round()).abs() < 1e-6, "{v}");
        }
    }
    let vis = Visibility::new(d.clone()).unwrap();
    assert!(vis.query(start).unwrap().area() > 1.0);
    // GeoJSON round trip, in the map's own coordinates.
    let dir = temp("tb3");
    let path = dir.join("tb3.geojson");
    std::fs::write(&path, to_geojson_in(d, Some(start), &env.frame).to_string()).unwrap();
    let back = read_environment(&path).unwrap();
    assert!(back.frame.is_identity());
    let moved: Vec<Vec<[f64; 2]>> =
        d.rings().iter().map(|r| r.iter().map(|&p| env.frame.to_input(p)).collect()).collect();
    assert_eq!(back.domain.rings(), &moved[..]);
    assert_eq!(back.start, Some([-2.0, -0.5]));
}

fn write(dir: &Path, name: &str, body: &[u8]) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, body).unwrap();
    p
}

#[test]
fn malformed_maps_are_clear_errors() {
    let dir = temp("bad");
    let pgm = |w: usize, h: usize, px: &[u8]| {
        let mut v = format!("P5\n{w} {h}\n255\n").into_bytes();
        v.extend_from_slice(px);
        v
    };
    write(&dir, "ok.pgm", &pgm(3, 3, &[254; 9]));
    write(&dir, "short.pgm", &pgm(3, 3, &[254; 4]));
    write(&dir, "black.pgm", &pgm(3, 3, &[0; 9]));
    write(&dir, "junk.pgm", b"GIF89a....");
    let y = |img: &str, extra: &str| {
        format!(
            "image: {img}\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n{extra}"
        )
    };
    let cases: Vec<(String, Option<[f64; 2]>, &str)> = vec![
        (y("missing.pgm", ""), None, "missing.pgm"),
        (y("short.pgm", ""), None, "truncated PGM"),
        (y("black.pgm", ""), None, "no free cell"),
        (y("junk.pgm", ""), None, "not a PGM"),
        ("resolution: 0.05\norigin: [0,0,0]\nfree_thresh: 0.2\n".into(), None, "no 'image'"),
        ("image: ok.pgm\norigin: [0,0,0]\nfree_thresh: 0.2\n".into(), None, "no 'resolution'"),
        (
            "image: ok.pgm\nresolution: -1\norigin: [0,0,0]\nfree_thresh: 0.2\n".into(),
            None,
            "positive",
        ),
        ("image: ok.pgm\nresolution: 0.05\norigin: [0]\nfree_thresh: 0.2\n".into(), None, "origin"),
        ("image: ok.pgm\nresolution: abc\n".into(), None, "expected a number"),
        ("just some words\n".into(), None, "key: value"),
        (y("ok.pgm", ""), Some([5.0, 5.0]), "outside the map"),
    ];
    for (i, (text, start, needle)) in cases.into_iter().enumerate() {
        let p = write(&dir, &format!("m{i}.yaml"), text.as_bytes());
        let e =
            read(&p, &RosMapOptions { start, ..RosMapOptions::default() }).unwrap_err().to_string();
        assert!(e.contains(needle), "case {i}: {e:?} should mention {needle:?}");
        assert!(
            e.contains(&format!("m{i}.yaml")) || e.contains(".pgm"),
            "case {i} names no file: {e}"
        );
    }
    // A start inside an obstacle.
    let mut px = vec![254u8; 25];
    px[12] = 0;
    write(&dir, "dot.pgm", &pgm(5, 5, &px));
    let p = write(&dir, "dot.yaml", y("dot.pgm", "").as_bytes());
    let e = read(
        &p,
        &RosMapOptions {
            start: Some([0.125, 0.125]),
            min_speck_area: 0.0,
            ..RosMapOptions::default()
        },
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("not in a free cell"), "{e}");
    // The same dot is a speck below the default area: it is dropped.
    let env = read(&p, &RosMapOptions::default()).unwrap();
    assert!(env.domain.holes().is_empty());
    let env =
        read(&p, &RosMapOptions { start: None, min_speck_area: 0.0, ..RosMapOptions::default() })
            .unwrap();
    assert_eq!(env.domain.holes().len(), 1);
}

#[test]
fn diagonal_pinches_do_not_make_touching_rings() {
    let dir = temp("pinch");
    // Free everywhere except two diagonal blocked cells, which would touch at a corner.
    let mut px = vec![254u8; 36];
    px[2 * 6 + 2] = 0;
    px[3 * 6 + 3] = 0;
    let mut img = b"P5\n6 6\n255\n".to_vec();
    img.extend_from_slice(&px);
    write(&dir, "p.pgm", &img);
    let p = write(
        &dir,
        "p.yaml",
        b"image: p.pgm\nresolution: 1\norigin: [0, 0, 0]\nnegate: 0\nfree_thresh: 0.2\n",
    );
    let env =
        read(&p, &RosMapOptions { start: None, min_speck_area: 0.0, ..RosMapOptions::default() })
            .unwrap();
    assert_eq!(
        env.domain.holes().len(),
        1,
        "the two cells and the blocked pinch cell form one hole"
    );
}

/// The ROS maps vendored in fixtures/ (navigation2's turtlebot3_world, depot and warehouse,
/// Apache-2.0).
#[test]
fn every_vendored_ros_map_loads() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/ros-maps");
    let mut n = 0;
    for f in std::fs::read_dir(&root).unwrap() {
        let f = f.unwrap().path();
        if f.extension().and_then(|e| e.to_str()) == Some("yaml") {
            let env = read_environment(&f).unwrap_or_else(|e| panic!("{e}"));
            assert!(env.domain.area() > 0.0, "{}", f.display());
            n += 1;
        }
    }
    assert!(n >= 2, "{n} maps in {}", root.display());
}

/// Every file of the shared data: the AGP `.pol` polygons may not be copied into the
/// repository, so the test is ignored by default and fails when run without them.
#[test]
#[ignore = "needs ../shared/data (the AGP .pol polygons are not redistributable)"]
fn every_shared_environment_loads() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data");
    assert!(root.exists(), "{} is absent: run beside ../shared", root.display());
    let mut n = 0;
    for dir in ["agp-polygons", "ros-maps"] {
        for sub in std::fs::read_dir(root.join(dir)).unwrap() {
            let sub = sub.unwrap().path();
            if !sub.is_dir() {
                continue;
            }
            for f in std::fs::read_dir(&sub).unwrap() {
                let f = f.unwrap().path();
                let ext = f.extension().and_then(|e| e.to_str()).unwrap_or("");
                if ext == "pol" || ext == "yaml" {
                    let env = read_environment(&f).unwrap_or_else(|e| panic!("{e}"));
                    assert!(env.domain.area() > 0.0);
                    n += 1;
                }
            }
        }
    }
    assert!(n >= 20, "{n} files");
}

#[test]
fn png_maps_load_like_pgm() {
    let dir = temp("png");
    // 8×6 free room with a 2×2 blocked pillar, as grey PNG and as PGM.
    let (w, h) = (8u32, 6u32);
    let px: Vec<u8> = (0..w * h)
        .map(|i| if (3..5).contains(&(i % w)) && (2..4).contains(&(i / w)) { 0 } else { 254 })
        .collect();
    let mut bytes = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut bytes, w, h);
        enc.set_color(png::ColorType::Grayscale);
        enc.set_depth(png::BitDepth::Eight);
        enc.write_header().unwrap().write_image_data(&px).unwrap();
    }
    write(&dir, "m.png", &bytes);
    let mut pgm = format!("P5\n{w} {h}\n255\n").into_bytes();
    pgm.extend_from_slice(&px);
    write(&dir, "m.pgm", &pgm);
    let yaml = |img: &str| {
        format!("image: {img}\nresolution: 0.5\norigin: [0, 0, 0]\nnegate: 0\nfree_thresh: 0.196\n")
    };
    let a = read(
        &write(&dir, "a.yaml", yaml("m.png").as_bytes()),
        &RosMapOptions { start: None, min_speck_area: 0.0, simplify: Some(0.0) },
    )
    .unwrap();
    let b = read(
        &write(&dir, "b.yaml", yaml("m.pgm").as_bytes()),
        &RosMapOptions { start: None, min_speck_area: 0.0, simplify: Some(0.0) },
    )
    .unwrap();
    assert_eq!(a.domain, b.domain);
    assert_eq!(a.domain.holes().len(), 1);
    // Traced, not simplified: the room less its pillar, cell for cell.
    assert!((a.domain.area() - (4.0 * 3.0 - 1.0)).abs() < 1e-12);
}
