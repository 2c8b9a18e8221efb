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
//! frame, bit for bit in RGB565, whether it sends every pixel or only those that changed;
//! the UART lines as the board's docs give them; the whole panel drawn; and a bad scene
//! turning the panel red with `error: …` on the UART. They print the emulated cycles and
//! write `target/board-report.md` (frame rates from cycles, for `cargo xtask figures`).
//! The still camera's builds have the `bounce` feature; the orbit's (the default program,
//! and `exact`) draw the ball before a circling camera
//! in 8×8 blocks and exact; every frame is checked against the host's the same way, and
//! `target/board-orbit-report.md` gives their cycles beside their error.

use std::path::{Path, PathBuf};
use std::process::Command;

mod common;

use common::pictures::{difference, psnr, squared_error};
use embedded_graphics::pixelcolor::{IntoStorage, Rgb565, Rgb888, RgbColor};
use fixray::anim::{Bounce, Orbit};
use fixray::{BlockSize, Frame, I16F16, Sampling, Scene};

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
    windows: f64,
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
                windows: field(line, "windows"),
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

/// What a run's frames after the first cost, on average (the first is whole in every run).
struct Means {
    /// Cycles per frame with one core.
    one: f64,
    /// With two, each drawing every other row.
    two: f64,
    /// Pixels sent a frame.
    pixels: f64,
    /// Windows opened a frame.
    windows: f64,
}

/// Checks the run's frames against the host's, bit for bit, and the UART lines; returns
/// what the frames after the first cost.
fn check_frames(run: &EmulatedRun, clock_mhz: u32, spi_khz: u32, whole: bool) -> Means {
    assert_eq!(run.stop, "frames", "{:?}", run.uart);
    let sent = if whole {
        "whole frames"
    } else {
        "changes only"
    };
    let start = format!(
        "fixray boing: 240x240 at (0,0) on a 240x240 panel, {clock_mhz} MHz, 1 core, SPI {spi_khz} kHz, {sent}"
    );
    assert_eq!(run.uart[0], start);
    for (n, frame) in run.frames.iter().enumerate() {
        // The UART says `frame=K us=T pixels=P`, K the animation's frame.
        let line = &run.uart[n + 1];
        let words: Vec<&str> = line.split_whitespace().collect();
        assert_eq!(words.len(), 3, "{line}");
        assert_eq!(words[0], format!("frame={}", n % 16));
        let us: u64 = words[1].strip_prefix("us=").unwrap().parse().unwrap();
        // The board's own timer agrees with the emulated cycles within 1 %.
        let from_cycles = frame.cycles / f64::from(clock_mhz);
        assert!(
            (us as f64 - from_cycles).abs() <= 0.01 * from_cycles,
            "{line}: {from_cycles} us from cycles"
        );
        assert_eq!(usize::from(frame.index), n % 16);
        // The pixels the board says it sent are those the panel received: every one in
        // the first frame (and with whole frames), fewer after it.
        let said: usize = words[2].strip_prefix("pixels=").unwrap().parse().unwrap();
        assert_eq!(frame.pixels, said, "{line}");
        if whole || n == 0 {
            assert_eq!(frame.pixels, PANEL.0 * PANEL.1, "frame {n}");
        } else {
            assert!(
                frame.pixels < PANEL.0 * PANEL.1 / 2,
                "frame {n}: {}",
                frame.pixels
            );
        }
        // The panel shows the frame, bit for bit.
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
    let after_first = &run.frames[1..];
    let mean = |f: &dyn Fn(&EmulatedFrame) -> f64| {
        after_first.iter().map(f).sum::<f64>() / after_first.len() as f64
    };
    Means {
        one: mean(&|f| f.cycles),
        two: mean(&EmulatedFrame::two_core_cycles),
        pixels: mean(&|f| f.pixels as f64),
        windows: mean(&|f| f.windows),
    }
}

#[test]
#[ignore = "needs Node and builds the board: cargo test --release --test board -- --ignored"]
fn the_emulated_board_draws_the_hosts_frames_on_the_whole_panel() {
    let displayed = (PANEL.0 * PANEL.1) as f64;
    // 17 frames: the first, whole, then the loop's 16.
    let frames = 17;
    let mut costs = Vec::new();
    for (features, mhz, spi_khz, whole) in [
        (
            "emulated,bounce,whole-frames,clock-125mhz",
            125,
            62_500,
            true,
        ),
        ("emulated,bounce,whole-frames", 200, 50_000, true),
        ("emulated,bounce,clock-125mhz", 125, 62_500, false),
        ("emulated,bounce", 200, 50_000, false),
    ] {
        let elf = build(features);
        let out = format!("board-{}", features.replace(',', "-"));
        let run = emulate(&elf, frames, &out, &[]);
        let means = check_frames(&run, mhz, spi_khz, whole);
        let (one, two, pixels) = (means.one, means.two, means.pixels);
        // With every SPI byte sent at once: the difference is the time spent waiting on
        // the display.
        let instant = emulate(&elf, frames, &format!("{out}-instant"), &["--instant-spi"]);
        let waiting = one - check_frames(&instant, mhz, spi_khz, whole).one;
        println!(
            "{features}: waiting on the display {waiting:.0} cycles a frame ({:.3} %), {:.1} windows",
            100.0 * waiting / one,
            means.windows
        );
        // The transfer overlaps the drawing: the CPU waits for the last row's transfer
        // (at most 480 bytes) and the windows' commands (11 bytes each, written by the
        // CPU), and no more: a byte is 8 SPI clocks, `8 × clk / spi` cycles.
        let byte = 8.0 * f64::from(mhz) * 1e3 / f64::from(spi_khz);
        let bound = (480.0 + 11.0 * means.windows) * byte * 1.5;
        assert!(
            waiting < bound,
            "{features}: {waiting} cycles waiting, bound {bound}"
        );
        for (cores, cycles) in [(1, one), (2, two)] {
            costs.push((whole, mhz, cores, pixels, cycles / displayed));
        }
    }
    // One row per kind of frame and core count, both clocks side by side.
    let mut report = String::from(
        "| frames sent | cores | pixels sent a frame | 125 MHz: cycles per displayed pixel | fps | \
         200 MHz: cycles per displayed pixel | fps |\n|---|---|---|---|---|---|---|\n",
    );
    for whole in [true, false] {
        for cores in [1, 2] {
            let at = |mhz| {
                costs
                    .iter()
                    .find(|c| c.0 == whole && c.1 == mhz && c.2 == cores)
                    .copied()
                    .unwrap()
            };
            let (slow, fast) = (at(125), at(200));
            let fps = |c: (bool, u32, u16, f64, f64)| f64::from(c.1) * 1e6 / (c.4 * displayed);
            report += &format!(
                "| {} | {cores} | {:.0} | {:.1} | {:.2} | {:.1} | {:.2} |\n",
                if whole { "whole" } else { "changes only" },
                fast.3,
                slow.4,
                fps(slow),
                fast.4,
                fps(fast)
            );
        }
    }
    println!(
        "the boing ball at 240x240, the mean of the loop's 16 frames on the emulated RP2040:\n{report}"
    );
    let target = Path::new(env!("CARGO_MANIFEST_DIR")).join("target");
    std::fs::write(target.join("board-report.md"), report).unwrap();
    // Sending only what changed costs less than every pixel, at each clock and core count.
    for &(whole, mhz, cores, _, cost) in &costs {
        if !whole {
            let full = costs
                .iter()
                .find(|c| c.0 && c.1 == mhz && c.2 == cores)
                .map(|c| c.4)
                .unwrap();
            assert!(
                cost < full,
                "{mhz} MHz, {cores} cores: {cost} against {full}"
            );
        }
    }
}

/// The orbit's frame `k` drawn by the host with `sampling`, whole (the board draws it band
/// by band with `Frame::render_rows`, the same pixels), in colour `C`.
fn host_orbit_frame<C: From<Rgb888> + Copy>(k: u16, sampling: Sampling) -> Vec<C> {
    let mut scene = Scene::<I16F16>::parse(SCENE).unwrap();
    let bounce = Bounce::boing(&scene.objects).unwrap();
    let orbit = Orbit::boing(&scene.objects).unwrap();
    bounce.apply(&mut scene, k).unwrap();
    orbit.apply(&mut scene, k).unwrap();
    let (w, h) = (scene.camera.width, scene.camera.height);
    let mut out = vec![C::from(Rgb888::BLACK); usize::from(w) * usize::from(h)];
    Frame::new(&scene)
        .with_sampling(sampling)
        .render_rows(0..h, &mut out);
    out
}

#[test]
#[ignore = "needs Node and builds the board: cargo test --release --test board -- --ignored"]
fn the_emulated_board_draws_the_orbit_in_blocks_and_exact() {
    let displayed = (PANEL.0 * PANEL.1) as f64;
    let blocks = Sampling::blocks(BlockSize::Eight, 8);
    let mut report = String::from(
        "| the ball before the circling camera | cycles per displayed pixel (200 MHz, one core) | \
         fps | pixels > 2 levels of exact | PSNR against exact |\n|---|---|---|---|---|\n",
    );
    for (features, sampling, said) in [
        ("emulated", blocks, "orbit, 8x8 blocks, bound 8"),
        ("emulated,exact", Sampling::Exact, "orbit, exact"),
    ] {
        let elf = build(features);
        // An exact frame is about 284 M cycles: more than the emulator's default limit
        // over the 17 frames.
        let out = format!("board-{}", features.replace(',', "-"));
        let run = emulate(&elf, 17, &out, &["--max-mcycles", "10000"]);
        assert_eq!(run.stop, "frames", "{:?}", run.uart);
        assert_eq!(
            run.uart[0],
            format!(
                "fixray boing: 240x240 at (0,0) on a 240x240 panel, 200 MHz, 1 core, SPI 50000 kHz, {said}"
            )
        );
        let (mut beyond, mut squared) = (0usize, 0.0f64);
        for (n, frame) in run.frames.iter().enumerate() {
            let line = &run.uart[n + 1];
            assert!(line.starts_with(&format!("frame={} ", n % 16)), "{line}");
            assert!(line.ends_with(" pixels=57600"), "{line}");
            let us: f64 = line.split_whitespace().nth(1).unwrap()[3..]
                .parse()
                .unwrap();
            assert!((us - frame.cycles / 200.0).abs() <= 0.01 * us, "{line}");
            assert_eq!(frame.pixels, PANEL.0 * PANEL.1, "frame {n}");
            // The panel shows the host's frame, bit for bit.
            let memory = panel(&run, &format!("frame-{n}.rgb565"));
            let host: Vec<Rgb565> = host_orbit_frame(frame.index, sampling);
            for (i, pixel) in host.iter().enumerate() {
                assert_eq!(
                    memory[i],
                    pixel.into_storage(),
                    "{features}, frame {n}: pixel {i}"
                );
            }
            // Its error against the exact frame, on the host, in the shading's 8-bit
            // levels (before the panel's RGB565 rounds both).
            if n > 0 {
                let drawn: Vec<Rgb888> = host_orbit_frame(frame.index, sampling);
                let exact: Vec<Rgb888> = host_orbit_frame(frame.index, Sampling::Exact);
                beyond += drawn
                    .iter()
                    .zip(&exact)
                    .filter(|(a, b)| difference(**a, **b) > 2)
                    .count();
                squared += squared_error(&drawn, &exact);
            }
        }
        let loop_frames = &run.frames[1..];
        let cycles = loop_frames.iter().map(|f| f.cycles).sum::<f64>() / loop_frames.len() as f64;
        let per_pixel = cycles / displayed;
        let pixels = displayed * loop_frames.len() as f64;
        let psnr = if squared == 0.0 {
            "∞".to_string()
        } else {
            format!("{:.1} dB", psnr(squared, pixels as usize))
        };
        report += &format!(
            "| {said} | {per_pixel:.1} | {:.2} | {:.3} % | {psnr} |\n",
            200e6 / cycles,
            100.0 * beyond as f64 / pixels,
        );
    }
    println!(
        "the orbit at 240x240, the mean of the loop's 16 frames on the emulated RP2040:\n{report}"
    );
    let target = Path::new(env!("CARGO_MANIFEST_DIR")).join("target");
    std::fs::write(target.join("board-orbit-report.md"), report).unwrap();
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
