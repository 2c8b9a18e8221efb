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
//! Options:
//! - `--display WxH-rgb888 | WxH-rgb565 | WxH-binary`: a real panel's size and colour
//!   depth (`binary`: black and white with ordered dithering, as on a 128×64 OLED);
//!   default: the scene's pixeldim, Rgb888.
//! - `--scale N`: window pixels per display pixel (default 3).
//! - `--frames N`: quit after N frames (for scripts and CI).
//! - `--fly`: move the eye forward by itself every frame (a fly-through).
//! - `--bounce`: bounce the scene's first sphere, one step of `fixray::anim::Bounce::boing`
//!   per frame, as the firmware does (`scenes/boing.scene`: the boing ball).
//! - `--record DIR`: save every frame as `DIR/frame-NNNN.png` (a PNG sequence).
//! - `--screenshot FILE`: save the last frame to FILE on quitting.
//! - `--rules course|fixray`: draw by that rule set whatever the file says (a file
//!   without a `rules` statement is a course file); the status line names the rules.

fn main() {
    if let Err(e) = window::run() {
        eprintln!("viewer: {e}");
        std::process::exit(1);
    }
}

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
    use fixray::num::formats::MAIN as FORMATS;
    use fixray::{LargeScene as Scene, Rules, Scalar, Vec3, render_line};

    const DEFAULT_SCENE: &str = include_str!("../scenes/default.scene");
    /// Height of the status line under the picture.
    const STATUS: u32 = 12;

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

    /// What a frame shows: the eye's offset, the panel's size, the bounce's frame.
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
    ) -> Result<Scene<S>, String> {
        let View { eye, size, bounce } = view;
        let mut scene = read::<S>(text, rules).map_err(|e| e.to_string())?;
        if let Some(k) = bounce {
            // The sphere moved in the parsed scene, as the firmware moves it.
            let b = Bounce::boing(&scene.objects).map_err(|e| format!("--bounce: {e}"))?;
            b.apply(&mut scene, k)
                .map_err(|e| format!("--bounce: {e}"))?;
        }
        let v = scene.camera.viewpoint.to_f64();
        scene.camera.viewpoint =
            Vec3::from_f64([v[0] + eye.dx, v[1] + eye.dy, (v[2] + eye.dz).max(0.1)])
                .ok_or("the eye left the format's range")?;
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

    fn frame_in<S: Scalar>(text: &str, rules: Option<Rules>, view: View) -> Result<Frame, String> {
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

    fn frame(format: &str, text: &str, rules: Option<Rules>, view: View) -> Result<Frame, String> {
        fixray::with_format!(format, frame_in(text, rules, view)).map_err(|e| e.to_string())?
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

    pub fn run() -> Result<(), String> {
        let o = options()?;
        let text = match &o.scene {
            Some(path) => {
                let _ = SCENE_PATH.set(path.into());
                std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?
            }
            None => DEFAULT_SCENE.to_string(),
        };
        let probe = read::<f64>(&text, o.rules).map_err(|e| {
            format!(
                "{}:{e}",
                o.scene.as_deref().unwrap_or("scenes/default.scene")
            )
        })?;
        let (w, h, depth) =
            o.display
                .unwrap_or((probe.camera.width, probe.camera.height, Depth::Rgb888));
        let size = o.display.map(|(w, h, _)| (w, h));
        let mut display =
            SimulatorDisplay::<Rgb888>::new(Size::new(u32::from(w), u32::from(h) + STATUS));
        let settings = OutputSettingsBuilder::new().scale(o.scale).build();
        let mut format = 0usize;
        let mut window = Window::new(&format!("fixray: {}", FORMATS[format]), &settings);
        let (mut eye, mut show_heat, mut n, mut shots) = (Eye::default(), false, 0u32, 0u32);
        if let Some(dir) = &o.record {
            std::fs::create_dir_all(dir).map_err(|e| format!("{dir}: {e}"))?;
        }
        loop {
            let bounce = o.bounce.then_some((n % u32::from(u16::MAX)) as u16);
            let f = frame(FORMATS[format], &text, o.rules, View { eye, size, bounce })?;
            let wu = usize::from(w);
            for (i, (p, r)) in f.pixels.iter().zip(&f.reference).enumerate() {
                let (x, y) = (i % wu, i / wu);
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
                format = k;
                // The title is fixed when a window opens: a new one carries the new format.
                window = Window::new(&format!("fixray: {}", FORMATS[format]), &settings);
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
