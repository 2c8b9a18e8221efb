//! The course's entities: one shipped scene each for translucency, a textured
//! plane, a projector and surfaces of revolution, read with their texture files (the
//! `textures` feature): error against f64 and host time per format, and instructions per
//! pixel on the three cores (I16F16 and f32, the firmware built with `textures`).

use super::*;

/// The scenes: name, what it is, text (their texture files are in `scenes/textures/`).
const ENTITY_SCENES: [(&str, &str, &str); 5] = [
    (
        "translucent",
        "transparency: a translucent sphere before a lit sphere",
        include_str!("../../../scenes/translucent.scene"),
    ),
    (
        "texplane",
        "a textured plane (a 32×32 PPM, tiled and fitted)",
        include_str!("../../../scenes/texplane.scene"),
    ),
    (
        "projector",
        "a projector: a light shining through a texture",
        include_str!("../../../scenes/projector.scene"),
    ),
    (
        "revsurf",
        "a surface of revolution (`surfer 1`, a cone)",
        include_str!("../../../scenes/revsurf.scene"),
    ),
    (
        "vases",
        "surfaces of revolution (`surfer 2` and `3`: an hourglass and a vase)",
        include_str!("../../../scenes/vases.scene"),
    ),
];

/// The firmware features with the course's entities.
const FEATURES: &str = "kernels,lighting,spheres,reflection,course,textures";

/// Host median time of one frame, in ms.
struct FrameTime<'a> {
    text: &'a str,
    runs: usize,
}
impl PerFormat for FrameTime<'_> {
    type Out = f64;
    fn run<S: Scalar>(&mut self) -> f64 {
        let scene = read::<S>(self.text);
        let (w, h) = (scene.camera.width, scene.camera.height);
        let mut line = vec![Rgb888::BLACK; usize::from(w)];
        median_ms(self.runs, || {
            let mut out = Vec::with_capacity(usize::from(w) * usize::from(h));
            for row in 0..h {
                render_line(std::hint::black_box(&scene), row, &mut line);
                out.extend_from_slice(&line);
            }
            out
        })
        .0
    }
}

/// The section: measured now, host and (unless `quick`) firmware.
pub(super) fn entities_section(quick: bool) -> String {
    let mut r = String::new();
    let _ = writeln!(
        r,
        "\n## The course's entities\n\n\
         One shipped scene per entity (course rules, 160×120), read with its texture file \
         (`Scene::read_with` and `fixray::scene::files::beside`, feature `textures`). \
         *differ*: pixels that differ at all from the f64 render; *max*: the largest \
         channel difference; *ms*: host median of {} frames (noisy: compare within a row).\n",
        if quick { 1 } else { 5 }
    );
    let _ = writeln!(r, "| scene | what | format | differ | max | ms/frame |");
    let _ = writeln!(r, "|---|---|---|---|---|---|");
    for (scene, what, text) in ENTITY_SCENES {
        for (format, _) in FORMATS {
            eprintln!("entities: {scene} {format}");
            let cmp = with_format(format, &mut MeasureAccuracy(text)).cmp;
            let runs = if quick { 1 } else { 5 };
            let ms = with_format(format, &mut FrameTime { text, runs });
            let _ = writeln!(
                r,
                "| {scene} | {what} | {format} | {:.3} % | {} | {ms:.2} |",
                100.0 * f64::from(cmp.differing_pixels) / f64::from(cmp.pixels.max(1)),
                cmp.max_channel_error,
            );
        }
    }
    let _ = writeln!(
        r,
        "\nFirmware instructions per pixel (QEMU, `-icount shift=0`, deterministic), built \
         with `--no-default-features --features {FEATURES}` and \
         `FIXRAY_FW_SCENES=translucent,texplane,projector,revsurf,vases`; flash is the whole \
         firmware's (the five scenes and their texture).\n"
    );
    if quick {
        let _ = writeln!(r, "--quick: firmware not measured.");
        return r;
    }
    if !qemu::qemu_available() {
        let _ = writeln!(
            r,
            "qemu-system-arm or qemu-system-riscv32 not found: no firmware figures (every core's is needed)."
        );
        return r;
    }
    let names = ENTITY_SCENES.map(|s| s.0).join(",");
    let _ = writeln!(
        r,
        "| core | format | {} | flash bytes |",
        ENTITY_SCENES.map(|s| s.0).join(" | ")
    );
    let _ = writeln!(r, "|---|---|{}---|", "---|".repeat(ENTITY_SCENES.len()));
    for (target, core) in qemu::CORES {
        for format in ["i16f16", "f32"] {
            eprintln!("entities firmware: {core} {format}");
            match qemu::run_with_features(target, format, &names, Some(FEATURES)) {
                Ok(run) => {
                    let px = per_pixel(&run);
                    let cells: Vec<String> = ENTITY_SCENES
                        .iter()
                        .map(|(s, _, _)| px.get(*s).map_or("–".into(), |p| format!("{p:.0}")))
                        .collect();
                    let _ = writeln!(
                        r,
                        "| {core} | {format} | {} | {} |",
                        cells.join(" | "),
                        run.flash
                    );
                }
                Err(e) => {
                    let rest = " |".repeat(ENTITY_SCENES.len());
                    let _ = writeln!(r, "| {core} | {format} | run failed: {e}{rest}");
                }
            }
        }
    }
    r
}
