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
    // The parser's message may say more (the attributes there are).
    assert!(
        stderr.starts_with(&format!(
            "{}:3:3: `ambiant` is not an attribute of material",
            path.display()
        )),
        "{stderr}"
    );
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
}

#[test]
fn advise_names_the_choice_and_refuses_bad_cores_and_budgets() {
    let out = run(&["scenes/spheres.scene", "--advise", "cortex-m4f"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{stdout}");
    assert!(
        stdout.contains("advice for cortex-m4f, budget: at most 1 % of pixels beyond 2 levels"),
        "{stdout}"
    );
    assert!(stdout.contains("choice: "), "{stdout}");
    // One row per candidate: each format's exact frame and its priced modes (no sampled
    // I32F32 was counted on the M4F).
    let rows: Vec<&str> = stdout
        .lines()
        .filter(|l| l.ends_with(" yes") || l.ends_with(" no"))
        .collect();
    assert_eq!(rows.len(), 3 * 13 + 1, "{stdout}");
    assert!(
        rows.iter().any(|r| r.starts_with("i32f32  exact")),
        "{stdout}"
    );
    let out = run(&["--advise", "z80"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("not a core"));
    let out = run(&["--advise", "rp2040", "--budget", "lots"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("LEVELS:PERCENT"));
}

#[test]
fn bad_arguments_fail_with_usage() {
    let out = run(&["--format", "i8f8"]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("usage: render"), "{stderr}");
    // An unknown name is refused with the names that exist (and never becomes f64
    // silently).
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

/// Writes `text` as the scene file `name` in this run's folder.
fn scene(name: &str, text: &str) -> PathBuf {
    let path = temp(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// A scene whose floor lies at y = 40000: every format holds it but I16F16 (whose
/// largest number is 32768).
const BEYOND_I16F16: &str = "rules fixray
camera c { pixeldim 16 12 worlddim 8 6 viewpoint 4 3 5 }
material m { ambient 0.5 0.5 0.5 }
sphere ball { material m center 4 3 -5 radius 1 }
plane floor { material m normal 0 1 0 point 0 40000 0 }
";

/// The scene error lines of a run's stderr, each `FILE:LINE:COL: message`: the
/// messages, after checking that prefix.
fn scene_errors(out: &Output, path: &Path, line: u32, column: u32) -> Vec<String> {
    let prefix = format!("{}:{line}:{column}: ", path.display());
    let stderr = String::from_utf8_lossy(&out.stderr);
    let messages: Vec<String> = stderr
        .lines()
        .filter(|l| !l.starts_with("render: "))
        .map(|l| {
            l.strip_prefix(&prefix)
                .unwrap_or_else(|| panic!("`{l}` does not start with `{prefix}`:\n{stderr}"))
                .to_string()
        })
        .collect();
    assert!(!messages.is_empty(), "no scene error in:\n{stderr}");
    messages
}

/// The one error of a scene that only I16F16 refuses: the number, and the format named
/// (the parser's message may say more: the format's range, the formats that hold it).
fn assert_names_i16f16(messages: &[String]) {
    assert_eq!(messages.len(), 1, "{messages:?}");
    assert!(
        messages[0].starts_with("`40000` does not fit") && messages[0].contains("i16f16"),
        "{messages:?}"
    );
}

/// Without `--format`, a format that refuses the scene fails the run: its row of the
/// table says so, its error follows on stderr, and no picture is written (no f64 picture
/// in place of the I16F16 one).
#[test]
fn without_a_format_a_refusing_format_fails_the_run_and_writes_no_picture() {
    let path = scene("beyond-i16f16.scene", BEYOND_I16F16);
    let (png, cmp) = (temp("refused.png"), temp("refused-cmp.png"));
    let out = run(&[
        path.to_str().unwrap(),
        "--out",
        png.to_str().unwrap(),
        "--compare",
        cmp.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1), "{out:?}");
    assert_names_i16f16(&scene_errors(&out, &path, 5, 47));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("render: 1 of 5 formats refused the scene: no picture written"),
        "{stderr}"
    );
    // The table still reports every format: the refusing one in its row, the others'
    // figures.
    let stdout = String::from_utf8_lossy(&out.stdout);
    let row = |format: &str| {
        stdout
            .lines()
            .find(|l| l.split_whitespace().next() == Some(format))
            .unwrap_or_else(|| panic!("{format} missing from:\n{stdout}"))
            .to_string()
    };
    assert!(row("i16f16").contains("refused the scene"), "{stdout}");
    for format in ["i20f12", "i32f32", "f32", "f64"] {
        assert_eq!(row(format).split_whitespace().count(), 8, "{stdout}");
    }
    assert!(!png.exists() && !cmp.exists(), "a picture was written");
}

#[test]
fn with_a_format_a_refusing_format_fails_the_run() {
    let path = scene("beyond-i16f16-format.scene", BEYOND_I16F16);
    let png = temp("refused-format.png");
    let out = run(&[
        path.to_str().unwrap(),
        "--format",
        "i16f16",
        "--out",
        png.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1), "{out:?}");
    assert_names_i16f16(&scene_errors(&out, &path, 5, 47));
    assert!(!png.exists());
    // A format that holds the scene draws it.
    let out = run(&[
        path.to_str().unwrap(),
        "--format",
        "i20f12",
        "--out",
        png.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{out:?}");
    assert!(png.exists());
}

/// `--bounce-strip` prints a scene error as `FILE:LINE:COL: message` and exits with
/// status 1, as the other modes do.
#[test]
fn the_bounce_strip_prints_file_line_column_and_fails() {
    let path = scene("beyond-i16f16-strip.scene", BEYOND_I16F16);
    let strip = temp("refused-strip.png");
    let out = run(&[
        path.to_str().unwrap(),
        "--bounce-strip",
        strip.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1), "{out:?}");
    assert_names_i16f16(&scene_errors(&out, &path, 5, 47));
    assert!(!strip.exists());
}

/// `radius 1e400` fits no format: with `--format i16f16`, `--format f64` or none, the
/// message says so (rather than naming one format, such as the f64 reference's).
#[test]
fn a_number_beyond_every_format_is_said_to_fit_none() {
    let path = scene(
        "beyond-f64.scene",
        "rules fixray
camera c { pixeldim 16 12 worlddim 8 6 viewpoint 4 3 5 }
material m { ambient 0.5 0.5 0.5 }
sphere s { material m center 4 3 -5 radius 1e400 }
",
    );
    for args in [&[][..], &["--format", "i16f16"], &["--format", "f64"]] {
        let mut all = vec![path.to_str().unwrap()];
        all.extend(args);
        let out = run(&all);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {out:?}");
        assert_eq!(
            scene_errors(&out, &path, 4, 44),
            ["`1e400` does not fit in any number format (not even f64)"],
            "{args:?}"
        );
    }
}

/// An error of one format that is not a number out of its range says which format.
#[test]
fn a_formats_own_error_names_the_format() {
    // The normal rounds to zero in I16F16 (its step is 2^-16), not in f64.
    let path = scene(
        "zero-in-i16f16.scene",
        "rules fixray
camera c { pixeldim 16 12 worlddim 8 6 viewpoint 4 3 5 }
material m { ambient 0.5 0.5 0.5 }
plane p { material m normal 0.000001 0.000001 0 point 0 0 0 }
",
    );
    let out = run(&[path.to_str().unwrap(), "--format", "i16f16"]);
    assert_eq!(out.status.code(), Some(1), "{out:?}");
    let messages = scene_errors(&out, &path, 4, 22);
    assert_eq!(messages.len(), 1, "{messages:?}");
    assert!(
        messages[0].contains("normal") && messages[0].contains("i16f16"),
        "{messages:?}"
    );
    let out = run(&[path.to_str().unwrap(), "--format", "i32f32"]);
    assert!(out.status.success(), "{out:?}");
}

/// A scene over capacity names this program's limit, not a type parameter of the scene
/// type to raise: this program has raised them already (`LargeScene`).
#[test]
fn over_capacity_names_this_programs_limit() {
    let mut text = String::from(
        "rules fixray
camera c { pixeldim 16 12 worlddim 8 6 viewpoint 4 3 5 }
material m { ambient 0.5 0.5 0.5 }
",
    );
    for i in 0..1025 {
        text += &format!(
            "sphere s{i} {{ material m center {} 0 -10 radius 0.5 }}\n",
            i % 8
        );
    }
    let path = scene("too-many.scene", &text);
    for args in [&[][..], &["--format", "i32f32"]] {
        let mut all = vec![path.to_str().unwrap()];
        all.extend(args);
        let out = run(&all);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {out:?}");
        // The 1025th sphere, on line 1028.
        assert_eq!(
            scene_errors(&out, &path, 1028, 1),
            ["too many objects: this program holds at most 1024 objects"],
            "{args:?}"
        );
    }
}
