//! The reciprocal-division variant (`I16F16Recip`, "i16f16r") against I16F16 on every
//! shipped scene: a division off by a DELTA or two may move a boundary pixel or a shading
//! level, never the picture.

use embedded_graphics::pixelcolor::Rgb888;
use fixray::num::variants::I16F16Recip;
use fixray::{I16F16, Scalar, Scene, render_line};

fn picture<S: Scalar>(text: &str) -> Vec<Rgb888> {
    let scene = Scene::<S>::parse(text).unwrap();
    let mut line = vec![Rgb888::new(0, 0, 0); usize::from(scene.camera.width)];
    let mut out = Vec::new();
    for row in 0..scene.camera.height {
        render_line(&scene, row, &mut line);
        out.extend_from_slice(&line);
    }
    out
}

fn share(a: &[Rgb888], b: &[Rgb888]) -> f64 {
    a.iter().zip(b).filter(|(x, y)| x != y).count() as f64 / a.len() as f64
}

#[test]
fn reciprocal_division_draws_the_i16f16_pictures() {
    for name in [
        "default",
        "planes",
        "horizon",
        "spheres",
        "tiles",
        "specular",
        "spotlight",
        "mirror",
    ] {
        let text = std::fs::read_to_string(format!("scenes/{name}.scene")).unwrap();
        let exact = picture::<I16F16>(&text);
        let recip = picture::<I16F16Recip>(&text);
        let truth = picture::<f64>(&text);
        let (vs_exact, vs_truth, exact_vs_truth) = (
            share(&recip, &exact),
            share(&recip, &truth),
            share(&exact, &truth),
        );
        println!(
            "{name:<9} i16f16r vs i16f16 {:.3} %; against f64: i16f16r {:.3} %, i16f16 {:.3} %",
            100.0 * vs_exact,
            100.0 * vs_truth,
            100.0 * exact_vs_truth
        );
        assert!(vs_exact <= 0.03, "{name}: {vs_exact}");
        assert!(
            vs_truth <= 2.0 * exact_vs_truth + 0.01,
            "{name}: {vs_truth}"
        );
    }
}
