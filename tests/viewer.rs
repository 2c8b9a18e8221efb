//! The viewer runs headless under Xvfb for a few frames of a fly-through and its
//! screenshot is a picture, not a blank window. Needs the `window` feature (SDL2) and
//! `xvfb-run`; `.ci/run` installs both and runs `cargo test --features window --test viewer`.
#![cfg(feature = "window")]

use std::path::Path;
use std::process::Command;

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use embedded_graphics::prelude::*;
use embedded_graphics_simulator::SimulatorDisplay;

/// The viewer example, built in this test's profile (`cargo test --test viewer` does
/// not build examples).
fn viewer() -> std::path::PathBuf {
    let exe = std::env::current_exe().unwrap();
    let dir = exe.parent().and_then(Path::parent).unwrap();
    let mut build = Command::new(env!("CARGO"));
    build.args([
        "build",
        "--quiet",
        "--features",
        "window",
        "--example",
        "viewer",
    ]);
    if dir.file_name().is_some_and(|n| n == "release") {
        build.arg("--release");
    }
    assert!(
        build.status().unwrap().success(),
        "building the viewer example"
    );
    dir.join("examples").join("viewer")
}

/// A fresh directory for one test's output.
fn out_dir(name: &str) -> std::path::PathBuf {
    let out = std::env::temp_dir().join(format!("fixray-viewer-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&out).unwrap();
    out
}

/// How many colours a screenshot holds.
fn colours(shot: &Path) -> usize {
    let image = SimulatorDisplay::<Rgb888>::load_png(shot).unwrap();
    let size = image.size();
    let mut colours = std::collections::BTreeSet::new();
    for y in 0..size.height as i32 {
        for x in 0..size.width as i32 {
            let c = image.get_pixel(Point::new(x, y));
            colours.insert((c.r(), c.g(), c.b()));
        }
    }
    colours.len()
}

#[test]
fn the_viewer_draws_the_scene_headless() {
    let out = out_dir("fly");
    let shot = out.join("shot.png");
    let record = out.join("frames");
    let run = Command::new("xvfb-run")
        .arg("-a")
        .arg(viewer())
        .args(["--frames", "3", "--fly", "--screenshot"])
        .arg(&shot)
        .arg("--record")
        .arg(&record)
        .output()
        .expect("xvfb-run and the viewer example (cargo test --features window builds it)");
    assert!(run.status.success(), "{run:?}");
    // One status line per frame: format, frame time, differing share.
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert_eq!(
        stdout.lines().filter(|l| l.starts_with("i16f16 ")).count(),
        3,
        "{stdout}"
    );
    // Three recorded frames, and a screenshot that is a picture.
    assert_eq!(std::fs::read_dir(&record).unwrap().count(), 3);
    let n = colours(&shot);
    assert!(n > 100, "a blank or flat screenshot: {n} colours");
}

/// A scene with a texture: the viewer reads its PPM from beside the scene file (as the
/// `render` example does) and shows the textured wall.
#[test]
fn the_viewer_reads_a_scenes_texture_files() {
    let out = out_dir("texture");
    let shot = out.join("shot.png");
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/texplane.scene");
    let run = Command::new("xvfb-run")
        .arg("-a")
        .arg(viewer())
        .arg(&scene)
        .args(["--frames", "1", "--screenshot"])
        .arg(&shot)
        .output()
        .expect("xvfb-run and the viewer example (cargo test --features window builds it)");
    assert!(run.status.success(), "{run:?}");
    let n = colours(&shot);
    assert!(n > 100, "a blank or flat screenshot: {n} colours");
}

/// The boing ball plays: `--bounce` moves the sphere one step of its loop per
/// frame, so consecutive recorded frames differ and frame 16 is frame 0 again.
#[test]
fn the_viewer_plays_the_boing_ball() {
    let out = out_dir("boing");
    let record = out.join("frames");
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/boing.scene");
    let run = Command::new("xvfb-run")
        .arg("-a")
        .arg(viewer())
        .arg(&scene)
        .args(["--frames", "17", "--bounce", "--record"])
        .arg(&record)
        .output()
        .expect("xvfb-run and the viewer example (cargo test --features window builds it)");
    assert!(run.status.success(), "{run:?}");
    let frame = |k: u32| {
        let image =
            SimulatorDisplay::<Rgb888>::load_png(record.join(format!("frame-{k:04}.png"))).unwrap();
        let size = image.size();
        // The picture without the status line (its frame time changes).
        let rows = size.height as i32 - 12;
        (0..rows)
            .flat_map(|y| (0..size.width as i32).map(move |x| Point::new(x, y)))
            .map(|p| image.get_pixel(p))
            .collect::<Vec<_>>()
    };
    let first = frame(0);
    assert_ne!(first, frame(1), "the ball did not move");
    assert_ne!(frame(4), frame(8));
    assert_eq!(first, frame(16), "the loop does not close");
}

/// Writes `text` as the scene file `name` in a fresh folder.
fn scene(name: &str, text: &str) -> std::path::PathBuf {
    let path = out_dir(name).join(format!("{name}.scene"));
    std::fs::write(&path, text).unwrap();
    path
}

/// A scene error of the format shown first (I16F16), or of every format, prints
/// `FILE:LINE:COL: message` and exits with status 1. Errors come before any window
/// opens, so this runs without a display.
#[test]
fn a_scene_error_prints_file_line_column_and_fails() {
    let beyond_i16f16 = scene(
        "beyond-i16f16",
        "rules fixray
camera c { pixeldim 16 12 worlddim 8 6 viewpoint 4 3 5 }
material m { ambient 0.5 0.5 0.5 }
plane floor { material m normal 0 1 0 point 0 40000 0 }
",
    );
    let misspelt = scene(
        "misspelt",
        "camera c { pixeldim 8 6 worlddim 8 6 viewpoint 4 3 5 }\nmaterial m {\n  ambiant 1 1 1 }\n",
    );
    // The parser's messages may say more (the range, the attributes there are).
    let cases = [
        (&beyond_i16f16, "4:47: `40000` does not fit", "i16f16"),
        (
            &misspelt,
            "3:3: `ambiant` is not an attribute of material",
            "",
        ),
    ];
    let viewer = viewer();
    for (path, start, format) in cases {
        let run = Command::new(&viewer)
            .arg(path)
            .args(["--frames", "1"])
            .env_remove("DISPLAY")
            .env_remove("WAYLAND_DISPLAY")
            .output()
            .unwrap();
        assert_eq!(run.status.code(), Some(1), "{run:?}");
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert!(
            stderr.starts_with(&format!("{}:{start}", path.display())),
            "{stderr}"
        );
        assert!(stderr.contains(format), "{stderr}");
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
    }
}

/// `--display 240x240-rgb565` does not stretch a 4:3 scene over the square panel (spheres
/// would become eggs): the picture keeps the scene's aspect, letterboxed: 240×180 between
/// black bars of 30 rows, and a sphere at the centre is as wide as it is tall.
#[test]
fn a_square_panel_letterboxes_the_scene_and_keeps_spheres_round() {
    let out = out_dir("round");
    let shot = out.join("shot.png");
    let path = scene(
        "round",
        "rules fixray
camera c { pixeldim 160 120 worlddim 8 6 viewpoint 4 3 5 }
background 0 0 1
material red { ambient 1 0 0 }
sphere ball { material red center 4 3 -5 radius 2 }
",
    );
    let run = Command::new("xvfb-run")
        .arg("-a")
        .arg(viewer())
        .arg(&path)
        .args([
            "--display",
            "240x240-rgb565",
            "--frames",
            "1",
            "--screenshot",
        ])
        .arg(&shot)
        .output()
        .expect("xvfb-run and the viewer example (cargo test --features window builds it)");
    assert!(run.status.success(), "{run:?}");
    let image = SimulatorDisplay::<Rgb888>::load_png(&shot).unwrap();
    // The panel and the status line under it.
    assert_eq!(image.size(), Size::new(240, 240 + 12));
    let at = |x: i32, y: i32| image.get_pixel(Point::new(x, y));
    // Black bars above and below the picture, the background's blue in it, edge to edge.
    for x in [0, 120, 239] {
        for y in [0, 29, 210, 239] {
            assert_eq!(at(x, y), Rgb888::BLACK, "bar at ({x}, {y})");
        }
        for y in [30, 209] {
            assert_eq!(at(x, y), Rgb888::BLUE, "picture at ({x}, {y})");
        }
    }
    // The sphere's extent across and down, in pixels.
    let red: Vec<(i32, i32)> = (0..240)
        .flat_map(|y| (0..240).map(move |x| (x, y)))
        .filter(|&(x, y)| at(x, y) == Rgb888::RED)
        .collect();
    let extent = |of: fn(&(i32, i32)) -> i32| {
        let (lo, hi) = (red.iter().map(of).min(), red.iter().map(of).max());
        hi.unwrap() - lo.unwrap() + 1
    };
    let (across, down) = (extent(|p| p.0), extent(|p| p.1));
    assert!(across > 40, "the sphere is {across} pixels across");
    assert!(
        across.abs_diff(down) <= 1,
        "the sphere is {across} pixels across and {down} down"
    );
}
