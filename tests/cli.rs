//! The `render` example's command-line interface, as outside checks use it:
//! `render [SCENE_FILE] [--format F] [--out FILE.png] [--compare FILE.png]`.
//!
//! The example is built once (with the test's own profile) before the first run, so that
//! `cargo test --test cli` never runs a stale binary.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use embedded_graphics::prelude::*;
use embedded_graphics_simulator::SimulatorDisplay;
use fixray::{I16F16, Scene, render_line};

fn render_exe() -> &'static Path {
    static EXE: OnceLock<PathBuf> = OnceLock::new();
    EXE.get_or_init(|| {
        // target/<profile>/deps/cli-<hash> → target/<profile>/examples/render
        let exe = std::env::current_exe().unwrap();
        let dir = exe.parent().and_then(Path::parent).unwrap();
        let mut build = Command::new(env!("CARGO"));
        build.args(["build", "--quiet", "--example", "render"]);
        if dir.file_name().is_some_and(|n| n == "release") {
            build.arg("--release");
        }
        assert!(
            build.status().unwrap().success(),
            "building the render example"
        );
        dir.join("examples")
            .join(format!("render{}", std::env::consts::EXE_SUFFIX))
    })
}

fn run(args: &[&str]) -> Output {
    Command::new(render_exe())
        .args(args)
        .output()
        .expect("the render example is built by `cargo test`")
}

fn temp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("fixray-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

#[test]
fn a_scene_error_prints_file_line_column_and_fails() {
    let path = temp("bad.scene");
    std::fs::write(
        &path,
        "camera c { pixeldim 8 6 worlddim 8 6 viewpoint 4 3 5 }\nmaterial m {\n  ambiant 1 1 1 }\n",
    )
    .unwrap();
    let out = run(&[path.to_str().unwrap(), "--format", "i16f16"]);
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(
        stderr.trim_end(),
        format!(
            "{}:3:3: `ambiant` is not an attribute of material",
            path.display()
        )
    );
}

#[test]
fn bad_arguments_fail_with_usage() {
    let out = run(&["--format", "i8f8"]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("usage: render"), "{stderr}");
    // Regression: an unknown name was refused without saying which ones exist (and in
    // the other tools it silently became f64).
    assert!(
        stderr.contains("unknown number format `i8f8` (known: i16f16, i16f16n,"),
        "{stderr}"
    );
}

#[test]
fn one_format_renders_the_scene_at_its_pixeldim() {
    let png = temp("i16f16.png");
    let cmp = temp("cmp.png");
    let out = run(&[
        "--format",
        "i16f16",
        "--out",
        png.to_str().unwrap(),
        "--compare",
        cmp.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{out:?}");
    // The PNG holds exactly what the library renders, pixel for pixel.
    let image = SimulatorDisplay::<Rgb888>::load_png(&png).unwrap();
    assert_eq!(image.size(), Size::new(160, 120));
    let scene = Scene::<I16F16>::parse(include_str!("../scenes/default.scene")).unwrap();
    let mut line = vec![Rgb888::BLACK; 160];
    for row in [0u16, 60, 119] {
        render_line(&scene, row, &mut line);
        for (x, c) in line.iter().enumerate() {
            let p = Point::new(i32::try_from(x).unwrap(), i32::from(row));
            assert_eq!(image.get_pixel(p), *c, "{p:?}");
        }
    }
    // The comparison: format | f64 | heat map, side by side.
    let compare = SimulatorDisplay::<Rgb888>::load_png(&cmp).unwrap();
    assert_eq!(compare.size(), Size::new(480, 120));
}

#[test]
fn without_a_format_every_format_is_reported() {
    let png = temp("all.png");
    let out = run(&["--out", png.to_str().unwrap()]);
    assert!(out.status.success(), "{out:?}");
    let stdout = String::from_utf8(out.stdout).unwrap();
    for format in fixray::num::formats::MAIN {
        // A row of figures: the name, then eight numeric columns (an error row would
        // carry a message instead).
        let row = stdout
            .lines()
            .find(|l| l.split_whitespace().next() == Some(format))
            .unwrap_or_else(|| panic!("{format} missing from:\n{stdout}"));
        let figures: Vec<&str> = row.split_whitespace().skip(1).collect();
        assert_eq!(figures.len(), 7, "{row}");
        for f in figures {
            let f = f.trim_end_matches('%');
            assert!(f == "inf" || f.parse::<f64>().is_ok(), "`{f}` in {row}");
        }
    }
    assert!(png.exists());
}
