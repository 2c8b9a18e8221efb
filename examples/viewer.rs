//! `viewer`: fly through a scene in a simulated display window, switch number formats
//! live and see the error against f64. Needs the `window` feature (SDL2: `libsdl2-dev`).
//!
//! ```text
//! cargo run --release --example viewer --features window [SCENE_FILE] [options]
//! ```
//!
//! Keys: arrows / WASD move the eye (left, right, up, down), Q / E move it nearer and
//! farther; 1–5 switch the format (I16F16, I20F12, I32F32, f32, f64); H toggles the
//! error heat map against f64; P saves a screenshot (`fixray-screenshot-N.png`); Esc quits.
//! The window title names the format; the status line at the bottom shows the format,
//! the frame time and the share of pixels that differ from f64 (the simulator's window
//! cannot change its title after it opens).
//!
//! Options (`--help` lists them):
//! - `--display WxH-rgb888 | WxH-rgb565 | WxH-binary`: a real panel's size and colour
//!   depth (`binary`: black and white with ordered dithering, as on a 128×64 OLED);
//!   default: the scene's pixeldim, Rgb888. The picture keeps the scene's aspect (its
//!   `worlddim`): on a panel of another shape it is letterboxed, as large as fits,
//!   centred between black bars (a 4:3 scene on a 240×240 panel: 240×180 between bars
//!   of 30 rows), so that a sphere stays round. Letterboxed rather than widened: the
//!   scene's screen window starts at the world's origin, so a wider window would show
//!   the scene off-centre, and it would show what the scene does not frame.
//! - `--scale N`: window pixels per display pixel (default 3).
//! - `--frames N`: quit after N frames (for scripts and CI).
//! - `--fly`: move the eye forward by itself every frame (a fly-through).
//! - `--bounce`: bounce the scene's first sphere, one step of `fixray::anim::Bounce::boing`
//!   per frame, as the firmware does (`scenes/boing.scene`: the boing ball).
//! - `--record DIR`: save every frame as `DIR/frame-NNNN.png` (a PNG sequence).
//! - `--screenshot FILE`: save the last frame to FILE on quitting.
//! - `--rules course|fixray`: draw by that rule set whatever the file says (a file
//!   without a `rules` statement is a course file); the status line names the rules.
//!
//! Errors: bad arguments exit with status 2. A scene error prints `FILE:LINE:COL:
//! message` (naming the number format when the error is that format's alone, as the
//! `render` example does) and exits with status 1 before a window opens: the scene is
//! read in f64 and in the first format shown (I16F16) first. A format key whose format
//! refuses the scene prints its error and keeps the format shown.

use std::io::Write;
use std::process::ExitCode;

const USAGE: &str = "usage: viewer [SCENE_FILE] [--display WxH-rgb888|WxH-rgb565|WxH-binary] \
                     [--scale N] [--frames N] [--fly] [--bounce] [--record DIR] \
                     [--screenshot FILE] [--rules course|fixray]
  --display  a panel's size and colour depth (default: the scene's pixeldim, rgb888);
             the picture keeps the scene's aspect, letterboxed (centred between black
             bars) on a panel of another shape
  --scale    window pixels per display pixel (default 3)
  --frames   quit after N frames
  --fly      move the eye forward every frame
  --bounce   bounce the scene's first sphere (the boing ball)
  --record   save every frame as DIR/frame-NNNN.png
  --screenshot  save the last frame to FILE on quitting
  --rules    draw by that rule set whatever the file says
keys: arrows/WASD move, Q/E nearer/farther, 1-5 format, H heat map, P screenshot, Esc quit";

fn main() -> ExitCode {
    match window::run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(window::Failure::Usage(e)) if e.is_empty() => {
            // A closed pipe (`viewer --help | head`) is not worth a panic.
            let _ = writeln!(std::io::stdout(), "{USAGE}");
            ExitCode::SUCCESS
        }
        Err(window::Failure::Usage(e)) => {
            eprintln!("viewer: {e}");
            eprintln!("{USAGE}");
            ExitCode::from(2)
        }
        Err(window::Failure::Scene(line)) => {
            eprintln!("{line}");
            ExitCode::from(1)
        }
        Err(window::Failure::Other(e)) => {
            eprintln!("viewer: {e}");
            ExitCode::from(1)
        }
    }
}

#[path = "common/scene_error.rs"]
mod scene_error;

mod window {
    use std::time::Instant;

    use embedded_graphics::mono_font::{MonoTextStyle, ascii::FONT_6X10};
    use embedded_graphics::pixelcolor::{BinaryColor, Rgb565, Rgb888, RgbColor};
    use embedded_graphics::prelude::*;
    use embedded_graphics::primitives::{PrimitiveStyle, Rectangle};
    use embedded_graphics::text::Text;
    use embedded_graphics_simulator::sdl2::Keycode;
    use embedded_graphics_simulator::{
        OutputSettings, OutputSettingsBuilder, SimulatorDisplay, SimulatorEvent, Window,
    };
    use fixray::anim::Bounce;
    use fixray::compare::heat_color;
    use fixray::geometry::Vec3;
    use fixray::num::formats::MAIN as FORMATS;
    use fixray::scene::{LargeScene as Scene, PixelGrid, Rules};
    use fixray::{Scalar, SceneError, render_line};

    use super::scene_error::explain;

    const DEFAULT_SCENE: &str = include_str!("../scenes/default.scene");
    const DEFAULT_SCENE_NAME: &str = "scenes/default.scene";
    /// Height of the status line under the picture.
    const STATUS: u32 = 12;

    /// Why the viewer stopped.
    pub enum Failure {
        /// Bad arguments (empty: `--help`).
        Usage(String),
        /// A scene error, as printed: `FILE:LINE:COL: message`.
        Scene(String),
        /// Anything else.
        Other(String),
    }

    impl From<String> for Failure {
        fn from(e: String) -> Self {
            Failure::Other(e)
        }
    }

    /// Why a frame was not drawn: the scene in its format, or the view.
    enum FrameError {
        Scene(SceneError),
        View(String),
    }

    #[derive(Clone, Copy, PartialEq)]
    enum Depth {
        Rgb888,
        Rgb565,
        Binary,
    }

    struct Options {
        scene: Option<String>,
        display: Option<(u16, u16, Depth)>,
        scale: u32,
        frames: Option<u32>,
        fly: bool,
        bounce: bool,
        record: Option<String>,
        screenshot: Option<String>,
        rules: Option<Rules>,
    }

    fn options() -> Result<Options, String> {
        let mut o = Options {
            scene: None,
            display: None,
            scale: 3,
            frames: None,
            fly: false,
            bounce: false,
            record: None,
            screenshot: None,
            rules: None,
        };
        let mut args = std::env::args().skip(1);
        while let Some(a) = args.next() {
            let mut value = |f: &str| args.next().ok_or(format!("{f} needs a value"));
            match a.as_str() {
                "--display" => {
                    let v = value("--display")?;
                    let (size, depth) = v.split_once('-').ok_or("--display WxH-DEPTH")?;
                    let (w, h) = size.split_once('x').ok_or("--display WxH-DEPTH")?;
                    let depth = match depth {
                        "rgb888" => Depth::Rgb888,
                        "rgb565" => Depth::Rgb565,
                        "binary" => Depth::Binary,
                        d => return Err(format!("unknown colour depth `{d}`")),
                    };
                    let dim = |s: &str| s.parse::<u16>().ok().filter(|v| (1..=4096).contains(v));
                    o.display = Some((
                        dim(w).ok_or("bad width")?,
                        dim(h).ok_or("bad height")?,
                        depth,
                    ));
                }
                "--scale" => o.scale = value("--scale")?.parse().map_err(|_| "bad --scale")?,
                "--frames" => {
                    o.frames = Some(value("--frames")?.parse().map_err(|_| "bad --frames")?)
                }
                "--fly" => o.fly = true,
                "--bounce" => o.bounce = true,
                "--record" => o.record = Some(value("--record")?),
                "--screenshot" => o.screenshot = Some(value("--screenshot")?),
                "--rules" => {
                    let r = value("--rules")?;
                    o.rules = Some(r.parse().map_err(|e| format!("--rules `{r}`: {e}"))?);
                }
                "-h" | "--help" => return Err(String::new()),
                s if s.starts_with("--") => return Err(format!("unknown option `{s}`")),
                s => o.scene = Some(s.to_string()),
            }
        }
        Ok(o)
    }

    /// The eye's offset from the scene's own viewpoint, in world units.
    #[derive(Default, Clone, Copy)]
    struct Eye {
        dx: f64,
        dy: f64,
        dz: f64,
    }

    /// One rendered frame: pixels (Rgb888), time, and the share differing from f64.
    struct Frame {
        pixels: Vec<Rgb888>,
        reference: Vec<Rgb888>,
        ms: f64,
        differ: f64,
    }

    /// The scene file's path, for its texture files (none for the built-in scene).
    static SCENE_PATH: std::sync::OnceLock<std::path::PathBuf> = std::sync::OnceLock::new();

    /// The scene drawn by `rules` if given, else by its file's rules, its textures read
    /// from beside the scene file.
    fn read<S: Scalar>(text: &str, rules: Option<Rules>) -> Result<Scene<S>, fixray::SceneError> {
        let mut scene = Scene::<S>::empty();
        match SCENE_PATH.get() {
            Some(path) => scene.read_with(text, rules, &mut fixray::scene::files::beside(path))?,
            None => scene.read_with(text, rules, &mut |_| None)?,
        }
        Ok(scene)
    }

    /// What a frame shows: the eye's offset, the picture's size (on a panel: as large as
    /// fits with the scene's aspect, [`fit`]), the bounce's frame.
    #[derive(Clone, Copy)]
    struct View {
        eye: Eye,
        size: Option<(u16, u16)>,
        bounce: Option<u16>,
    }

    fn scene_for<S: Scalar>(
        text: &str,
        rules: Option<Rules>,
        view: View,
    ) -> Result<Scene<S>, FrameError> {
        let View { eye, size, bounce } = view;
        let mut scene = read::<S>(text, rules).map_err(FrameError::Scene)?;
        if let Some(k) = bounce {
            // The sphere moved in the parsed scene, as the firmware moves it.
            let bounce_error = |e| FrameError::View(format!("--bounce: {e}"));
            let b = Bounce::boing(&scene.objects).map_err(bounce_error)?;
            b.apply(&mut scene, k).map_err(bounce_error)?;
        }
        let v = scene.camera.viewpoint.to_f64();
        scene.camera.viewpoint =
            Vec3::from_f64([v[0] + eye.dx, v[1] + eye.dy, (v[2] + eye.dz).max(0.1)])
                .ok_or_else(|| FrameError::View("the eye left the format's range".into()))?;
        if let Some((w, h)) = size {
            scene.camera.width = w;
            scene.camera.height = h;
        }
        Ok(scene)
    }

    fn render_all<S: Scalar>(scene: &Scene<S>) -> Vec<Rgb888> {
        let w = usize::from(scene.camera.width);
        let mut pixels = vec![Rgb888::BLACK; w * usize::from(scene.camera.height)];
        for (row, line) in pixels.chunks_mut(w).enumerate() {
            render_line(scene, row as u16, line);
        }
        pixels
    }

    fn frame_in<S: Scalar>(
        text: &str,
        rules: Option<Rules>,
        view: View,
    ) -> Result<Frame, FrameError> {
        let scene = scene_for::<S>(text, rules, view)?;
        let start = Instant::now();
        let pixels = render_all(&scene);
        let ms = start.elapsed().as_secs_f64() * 1e3;
        let reference = render_all(&scene_for::<f64>(text, rules, view)?);
        let differ = pixels
            .iter()
            .zip(&reference)
            .filter(|(a, b)| a != b)
            .count() as f64
            / pixels.len().max(1) as f64;
        Ok(Frame {
            pixels,
            reference,
            ms,
            differ,
        })
    }

    /// A frame in `format` (one of [`FORMATS`]); a scene error as printed, naming the
    /// scene file `file`.
    fn frame(
        format: &str,
        file: &str,
        text: &str,
        rules: Option<Rules>,
        view: View,
    ) -> Result<Frame, Failure> {
        match fixray::with_format!(format, frame_in(text, rules, view)) {
            Ok(Ok(frame)) => Ok(frame),
            // The f64 reading succeeded before any frame: the error is the format's.
            Ok(Err(FrameError::Scene(e))) => Err(Failure::Scene(explain(file, format, &e, None))),
            Ok(Err(FrameError::View(e))) => Err(Failure::Other(e)),
            Err(unknown) => Err(Failure::Other(unknown.to_string())),
        }
    }

    /// The picture's size on a `panel` (width, height): as large as fits with the aspect
    /// of the scene's screen window `world` (width, height), the other way letterboxed.
    /// On the corner grid the pixels span one less than their count (`Camera::screen_x`).
    fn fit(panel: (u16, u16), world: (f64, f64), grid: PixelGrid) -> (u16, u16) {
        let c = match grid {
            PixelGrid::Centres => 0.0,
            PixelGrid::Corners => 1.0,
        };
        let (w, h) = (f64::from(panel.0), f64::from(panel.1));
        let aspect = world.0 / world.1;
        if (w - c) / (h - c) > aspect {
            let width = ((h - c) * aspect + c).round().clamp(1.0, w);
            (width as u16, panel.1)
        } else {
            let height = ((w - c) / aspect + c).round().clamp(1.0, h);
            (panel.0, height as u16)
        }
    }

    /// 4×4 Bayer thresholds for ordered dithering to black and white.
    const BAYER: [[u16; 4]; 4] = [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];

    /// Draws the frame as the chosen panel would show it, then back to Rgb888 for the
    /// window (so one window type serves every depth).
    fn to_panel(p: Rgb888, x: usize, y: usize, depth: Depth) -> Rgb888 {
        match depth {
            Depth::Rgb888 => p,
            Depth::Rgb565 => Rgb888::from(Rgb565::from(p)),
            Depth::Binary => {
                let luma =
                    (u16::from(p.r()) * 77 + u16::from(p.g()) * 150 + u16::from(p.b()) * 29) >> 8;
                let threshold = BAYER[y % 4][x % 4] * 16 + 8;
                if luma > threshold {
                    BinaryColor::On.into()
                } else {
                    BinaryColor::Off.into()
                }
            }
        }
    }

    fn save(display: &SimulatorDisplay<Rgb888>, path: &str) -> Result<(), String> {
        display
            .to_rgb_output_image(&OutputSettings::default())
            .save_png(path)
            .map_err(|e| format!("cannot write {path}: {e}"))
    }

    /// The error of reading the scene in `format` (one of [`FORMATS`]), if any.
    fn read_error(format: &str, text: &str, rules: Option<Rules>) -> Option<SceneError> {
        fixray::with_format!(format, read_err(text, rules)).unwrap_or(None)
    }

    fn read_err<S: Scalar>(text: &str, rules: Option<Rules>) -> Option<SceneError> {
        read::<S>(text, rules).err()
    }

    pub fn run() -> Result<(), Failure> {
        let o = options().map_err(Failure::Usage)?;
        let text = match &o.scene {
            Some(path) => {
                let _ = SCENE_PATH.set(path.into());
                std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?
            }
            None => DEFAULT_SCENE.to_string(),
        };
        let file = o.scene.as_deref().unwrap_or(DEFAULT_SCENE_NAME);
        let mut format = 0usize;
        let probe = read::<f64>(&text, o.rules).map_err(|r| {
            // The first format's own reading says which format the error concerns.
            let line = match read_error(FORMATS[format], &text, o.rules) {
                Some(e) => explain(file, FORMATS[format], &e, Some(&r)),
                None => explain(file, "f64", &r, Some(&r)),
            };
            Failure::Scene(line)
        })?;
        let (w, h, depth) =
            o.display
                .unwrap_or((probe.camera.width, probe.camera.height, Depth::Rgb888));
        // On a panel the picture keeps the scene's aspect, letterboxed and centred.
        let world = (
            probe.camera.world_width.to_f64(),
            probe.camera.world_height.to_f64(),
        );
        let size = o
            .display
            .map(|(w, h, _)| fit((w, h), world, probe.camera.grid));
        let (pw, ph) = size.unwrap_or((w, h));
        let (ox, oy) = (usize::from((w - pw) / 2), usize::from((h - ph) / 2));
        let mut display =
            SimulatorDisplay::<Rgb888>::new(Size::new(u32::from(w), u32::from(h) + STATUS));
        let settings = OutputSettingsBuilder::new().scale(o.scale).build();
        let mut window = Window::new(&format!("fixray: {}", FORMATS[format]), &settings);
        let (mut eye, mut show_heat, mut n, mut shots) = (Eye::default(), false, 0u32, 0u32);
        if let Some(dir) = &o.record {
            std::fs::create_dir_all(dir).map_err(|e| format!("{dir}: {e}"))?;
        }
        loop {
            let bounce = o.bounce.then_some((n % u32::from(u16::MAX)) as u16);
            let view = View { eye, size, bounce };
            let f = frame(FORMATS[format], file, &text, o.rules, view)?;
            let wu = usize::from(pw);
            for (i, (p, r)) in f.pixels.iter().zip(&f.reference).enumerate() {
                // The picture's pixel on the panel (the bars stay black).
                let (x, y) = (ox + i % wu, oy + i / wu);
                let c = if show_heat {
                    heat_color(*p, *r)
                } else {
                    to_panel(*p, x, y, depth)
                };
                display
                    .draw_iter([Pixel(Point::new(x as i32, y as i32), c)])
                    .ok();
            }
            let status = format!(
                "{} {} {:.1} ms {:.2}% differ{}",
                FORMATS[format],
                probe.rules(),
                f.ms,
                100.0 * f.differ,
                if show_heat { " [heat]" } else { "" }
            );
            Rectangle::new(Point::new(0, i32::from(h)), Size::new(u32::from(w), STATUS))
                .into_styled(PrimitiveStyle::with_fill(Rgb888::new(30, 30, 30)))
                .draw(&mut display)
                .ok();
            Text::new(
                &status,
                Point::new(1, i32::from(h) + 9),
                MonoTextStyle::new(&FONT_6X10, Rgb888::WHITE),
            )
            .draw(&mut display)
            .ok();
            println!("{status}");
            window.update(&display);
            if let Some(dir) = &o.record {
                save(&display, &format!("{dir}/frame-{n:04}.png"))?;
            }
            n += 1;
            if o.fly {
                eye.dz -= 0.25;
            }
            let mut quit = o.frames.is_some_and(|max| n >= max);
            let mut new_format = None;
            for event in window.events() {
                match event {
                    SimulatorEvent::Quit => quit = true,
                    SimulatorEvent::KeyDown { keycode, .. } => match keycode {
                        Keycode::Escape => quit = true,
                        Keycode::Left | Keycode::A => eye.dx -= 0.25,
                        Keycode::Right | Keycode::D => eye.dx += 0.25,
                        Keycode::Up | Keycode::W => eye.dy += 0.25,
                        Keycode::Down | Keycode::S => eye.dy -= 0.25,
                        Keycode::Q => eye.dz -= 0.25,
                        Keycode::E => eye.dz += 0.25,
                        Keycode::H => show_heat = !show_heat,
                        Keycode::P => {
                            shots += 1;
                            save(&display, &format!("fixray-screenshot-{shots}.png"))?;
                        }
                        Keycode::Num1 => new_format = Some(0),
                        Keycode::Num2 => new_format = Some(1),
                        Keycode::Num3 => new_format = Some(2),
                        Keycode::Num4 => new_format = Some(3),
                        Keycode::Num5 => new_format = Some(4),
                        _ => {}
                    },
                    _ => {}
                }
            }
            if let Some(k) = new_format.filter(|k| *k != format) {
                match read_error(FORMATS[k], &text, o.rules) {
                    // A format that refuses the scene is not shown: the error says why.
                    Some(e) => eprintln!("{}", explain(file, FORMATS[k], &e, None)),
                    None => {
                        format = k;
                        // The title is fixed when a window opens: a new one carries the
                        // new format.
                        window = Window::new(&format!("fixray: {}", FORMATS[format]), &settings);
                    }
                }
            }
            if quit {
                if let Some(path) = &o.screenshot {
                    save(&display, path)?;
                }
                return Ok(());
            }
        }
    }
}
