//! The RP2040 board (`boards/rp2040-st7789`): its row split between the two cores, and its
//! firmware run on an emulated RP2040.
//!
//! The emulated runs are ignored by default (they need Node, and build the board):
//!
//! ```text
//! cargo test --release --test board -- --ignored --nocapture
//! ```
//!
//! They build the board's `emulated` firmware, run it on rp2040js
//! (`boards/rp2040-st7789/emulator/run.mjs`, installed with `npm ci` when missing), and
//! check every frame the panel receives against the host's render of the same animation
//! frame, bit for bit in RGB565; the UART lines as the board's docs give them; the whole
//! panel drawn; and a bad scene turning the panel red with `error: …` on the UART. They
//! print the emulated cycles and write `target/board-report.md` (frame rates from cycles,
//! for `cargo xtask figures`).

use std::path::{Path, PathBuf};
use std::process::Command;

use embedded_graphics::pixelcolor::{IntoStorage, Rgb565};
use fixray::anim::Bounce;
use fixray::{Frame, I16F16, Scene};

#[allow(dead_code)]
#[path = "../boards/rp2040-st7789/src/rows.rs"]
mod rows;

const SCENE: &str = include_str!("../scenes/boing-240x240.scene");
const PANEL: (usize, usize) = (240, 240);
/// The emulated panel's controller memory: 240 columns, 320 rows.
const MEMORY_ROWS: usize = 320;

/// The boing ball's frame `k` drawn by the host, row by row, as the board draws it with
/// one core.
fn host_frame(k: u16) -> Vec<Vec<Rgb565>> {
    let mut scene = Scene::<I16F16>::parse(SCENE).unwrap();
    let bounce = Bounce::boing(&scene.objects).unwrap();
    bounce.apply(&mut scene, k).unwrap();
    let frame = Frame::new(&scene);
    (0..scene.camera.height)
        .map(|row| {
            let mut line = vec![Rgb565::default(); usize::from(scene.camera.width)];
            frame.render_line(row, &mut line);
            line
        })
        .collect()
}

#[test]
fn rows_drawn_by_two_cores_assemble_the_frame_one_core_draws() {
    // Each core parses its own copy of the scene, moves it to the frame and draws only
    // its rows, in order: the frame assembled from both is the one-core frame.
    for k in [0, 5, 11] {
        let whole = host_frame(k);
        let height = u16::try_from(whole.len()).unwrap();
        let mut assembled = vec![Vec::new(); whole.len()];
        for core in 0..2 {
            let mut scene = Scene::<I16F16>::parse(SCENE).unwrap();
            let bounce = Bounce::boing(&scene.objects).unwrap();
            bounce.apply(&mut scene, k).unwrap();
            let frame = Frame::new(&scene);
            for row in rows::rows_of(core, 2, height) {
                let mut line = vec![Rgb565::default(); usize::from(scene.camera.width)];
                frame.render_line(row, &mut line);
                assembled[usize::from(row)] = line;
            }
        }
        assert_eq!(assembled, whole, "frame {k}");
    }
}

#[test]
fn the_split_gives_every_row_to_exactly_one_core() {
    for cores in 1..=2 {
        for height in [1, 2, 63, 64, 240, 320] {
            let mut seen = vec![0; usize::from(height)];
            for core in 0..cores {
                for row in rows::rows_of(core, cores, height) {
                    assert_eq!(rows::core_of(row, cores), core);
                    seen[usize::from(row)] += 1;
                }
            }
            assert!(seen.iter().all(|&n| n == 1), "{cores} cores, {height} rows");
            // Dealt in turn: the cores' shares differ by at most one row.
            let shares: Vec<usize> = (0..cores)
                .map(|c| rows::rows_of(c, cores, height).count())
                .collect();
            assert!(shares.iter().max().unwrap() - shares.iter().min().unwrap() <= 1);
        }
    }
}

fn board() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("boards/rp2040-st7789")
}

/// Builds the board's firmware with `features` and returns a copy of the ELF of its own
/// (tests run in parallel: the next build must not overwrite an ELF being run).
fn build(features: &str) -> PathBuf {
    static BUILDS: std::sync::Mutex<()> = std::sync::Mutex::new(());
    let _one_at_a_time = BUILDS
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    let target = board().join("target");
    let status = Command::new(env!("CARGO"))
        .current_dir(board())
        .args(["build", "--release", "--features", features, "--target-dir"])
        .arg(&target)
        .status()
        .expect("cargo runs");
    assert!(status.success(), "the board builds with {features}");
    let copy = target.join(format!("board-{}.elf", features.replace(',', "-")));
    std::fs::copy(
        target.join("thumbv6m-none-eabi/release/fixray-rp2040-st7789"),
        &copy,
    )
    .unwrap();
    copy
}

/// Installs the emulator's pinned packages (its lock file) when they are missing.
fn emulator() -> PathBuf {
    let dir = board().join("emulator");
    if !dir.join("node_modules/rp2040js/package.json").exists() {
        let status = Command::new("npm")
            .current_dir(&dir)
            .args(["ci", "--no-audit", "--no-fund"])
            .status()
            .expect("npm runs (Node 20 or later)");
        assert!(status.success(), "npm ci in {}", dir.display());
    }
    dir.join("run.mjs")
}

/// One frame as the emulator reports it.
#[derive(Debug)]
struct EmulatedFrame {
    index: u16,
    cycles: f64,
    pixels: usize,
    draw_even: f64,
    draw_odd: f64,
}

impl EmulatedFrame {
    /// The frame's cycles with two cores, each drawing half the rows: what is not drawing
    /// rows, plus the slower half.
    fn two_core_cycles(&self) -> f64 {
        self.cycles - self.draw_even - self.draw_odd + self.draw_even.max(self.draw_odd)
    }
}

/// What one emulated run printed.
#[derive(Debug)]
struct EmulatedRun {
    uart: Vec<String>,
    frames: Vec<EmulatedFrame>,
    stop: String,
    out: PathBuf,
}

/// Runs `elf` on the emulator for `frames` frames with `options`, its panels in `out`.
fn emulate(elf: &Path, frames: usize, out: &str, options: &[&str]) -> EmulatedRun {
    let out = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("target")
        .join(out);
    let output = Command::new("node")
        .arg(emulator())
        .arg(elf)
        .args(["--frames", &frames.to_string(), "--out"])
        .arg(&out)
        .args(options)
        .output()
        .expect("node runs");
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "the emulator fails: {}\n{stdout}",
        String::from_utf8_lossy(&output.stderr)
    );
    let field = |line: &str, key: &str| -> f64 {
        line.split_whitespace()
            .find_map(|w| w.strip_prefix(&format!("{key}=")))
            .and_then(|v| v.parse().ok())
            .unwrap_or_else(|| panic!("no {key} in {line:?}"))
    };
    let mut run = EmulatedRun {
        uart: Vec::new(),
        frames: Vec::new(),
        stop: String::new(),
        out,
    };
    for line in stdout.lines() {
        if let Some(text) = line.strip_prefix("uart: ") {
            run.uart.push(text.to_string());
        } else if line.starts_with("frame=") {
            run.frames.push(EmulatedFrame {
                index: field(line, "frame") as u16,
                cycles: field(line, "cycles"),
                pixels: field(line, "pixels") as usize,
                draw_even: field(line, "draw_even"),
                draw_odd: field(line, "draw_odd"),
            });
        } else if let Some(rest) = line.strip_prefix("stop=") {
            run.stop = rest.split_whitespace().next().unwrap_or("").to_string();
        }
    }
    run
}

/// The emulated panel's memory after frame `n` of a run: 240 × 320 RGB565 values.
fn panel(run: &EmulatedRun, file: &str) -> Vec<u16> {
    let bytes = std::fs::read(run.out.join(file)).unwrap();
    assert_eq!(bytes.len(), 2 * 240 * MEMORY_ROWS);
    bytes
        .chunks_exact(2)
        .map(|b| u16::from_be_bytes([b[0], b[1]]))
        .collect()
}

/// Checks the run's frames against the host's, bit for bit, and the UART lines; returns
/// the mean cycles per frame with one core and with two.
fn check_frames(run: &EmulatedRun, clock_mhz: u32, spi_khz: u32) -> (f64, f64) {
    assert_eq!(run.stop, "frames", "{:?}", run.uart);
    let start = format!(
        "fixray boing: 240x240 at (0,0) on a 240x240 panel, {clock_mhz} MHz, 1 core, SPI {spi_khz} kHz"
    );
    assert_eq!(run.uart[0], start);
    for (n, frame) in run.frames.iter().enumerate() {
        // The UART says `frame=K us=T`, K the animation's frame.
        let line = &run.uart[n + 1];
        let words: Vec<&str> = line.split_whitespace().collect();
        assert_eq!(words.len(), 2, "{line}");
        assert_eq!(words[0], format!("frame={}", n % 16));
        let us: u64 = words[1].strip_prefix("us=").unwrap().parse().unwrap();
        // The board's own timer agrees with the emulated cycles within 1 %.
        let from_cycles = frame.cycles / f64::from(clock_mhz);
        assert!(
            (us as f64 - from_cycles).abs() <= 0.01 * from_cycles,
            "{line}: {from_cycles} us from cycles"
        );
        assert_eq!(usize::from(frame.index), n % 16);
        // The whole panel, every pixel once a frame.
        assert_eq!(frame.pixels, PANEL.0 * PANEL.1, "frame {n}");
        let memory = panel(run, &format!("frame-{n}.rgb565"));
        let host = host_frame(frame.index);
        for (y, line) in host.iter().enumerate() {
            for (x, pixel) in line.iter().enumerate() {
                assert_eq!(
                    memory[y * 240 + x],
                    pixel.into_storage(),
                    "frame {n}: pixel ({x}, {y})"
                );
            }
        }
    }
    let count = run.frames.len() as f64;
    let one = run.frames.iter().map(|f| f.cycles).sum::<f64>() / count;
    let two = run
        .frames
        .iter()
        .map(EmulatedFrame::two_core_cycles)
        .sum::<f64>()
        / count;
    (one, two)
}

#[test]
#[ignore = "needs Node and builds the board: cargo test --release --test board -- --ignored"]
fn the_emulated_board_draws_the_hosts_frames_on_the_whole_panel() {
    let pixels = (PANEL.0 * PANEL.1) as f64;
    let frames = 16;
    let elf = build("emulated");
    let timed = emulate(&elf, frames, "board-200", &[]);
    let (one_200, two_200) = check_frames(&timed, 200, 50_000);
    // With every SPI byte sent at once: the difference is the time spent waiting on the
    // display.
    let instant = emulate(&elf, frames, "board-200-instant", &["--instant-spi"]);
    let (instant_200, _) = check_frames(&instant, 200, 50_000);
    let waiting = (one_200 - instant_200) / one_200;
    let elf = build("emulated,clock-125mhz");
    let slow = emulate(&elf, frames, "board-125", &[]);
    let (one_125, two_125) = check_frames(&slow, 125, 62_500);

    let mut report = String::from(
        "| clock | cores | cycles per pixel | ms per frame | frames per second |\n|---|---|---|---|---|\n",
    );
    for (mhz, cores, cycles) in [
        (125.0, 1, one_125),
        (125.0, 2, two_125),
        (200.0, 1, one_200),
        (200.0, 2, two_200),
    ] {
        let ms = cycles / (mhz * 1e3);
        report += &format!(
            "| {mhz} MHz | {cores} | {:.1} | {ms:.1} | {:.2} |\n",
            cycles / pixels,
            1e3 / ms
        );
    }
    println!(
        "the boing ball at 240x240, the mean of {frames} frames on the emulated RP2040:\n{report}"
    );
    println!(
        "waiting on the display: {:.3} % of a frame at 200 MHz ({:.0} cycles a frame)",
        100.0 * waiting,
        one_200 - instant_200
    );
    let target = Path::new(env!("CARGO_MANIFEST_DIR")).join("target");
    std::fs::write(target.join("board-report.md"), report).unwrap();
    // The transfer overlaps the drawing: no more waiting than the last row's transfer
    // (480 bytes at 50 MHz, 15,360 cycles at 200 MHz) and a row's worth of FIFO slack.
    assert!(
        one_200 - instant_200 < 2.0 * 15_360.0,
        "{} cycles waiting",
        one_200 - instant_200
    );
}

#[test]
#[ignore = "needs Node and builds the board: cargo test --release --test board -- --ignored"]
fn a_bad_scene_turns_the_panel_red_and_says_why_on_the_uart() {
    let elf = build("emulated");
    // The scene text is in flash: each case changes it in the image before the run.
    for (patch, says) in [
        (
            "pixeldim 240 240=pixeldim 240 2x0",
            "error: scenes/boing-240x240.scene:5:",
        ),
        (
            "pixeldim 240 240=pixeldim 480 240",
            "error: the scene is 480x240, the panel 240x240",
        ),
        (
            "sphere ball=sphere_ball",
            "error: scenes/boing-240x240.scene:13:",
        ),
    ] {
        let run = emulate(&elf, 1, "board-error", &["--patch", patch]);
        assert_eq!(run.stop, "error", "{patch}: {:?}", run.uart);
        let last = run.uart.last().unwrap();
        assert!(last.starts_with(says), "{patch}: {last}");
        assert!(run.frames.is_empty());
        let memory = panel(&run, "panel.rgb565");
        let red = Rgb565::new(31, 0, 0).into_storage();
        assert!(
            memory[..240 * PANEL.1].iter().all(|&p| p == red),
            "{patch}: the panel is not all red"
        );
    }
}
