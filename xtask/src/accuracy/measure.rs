//! Measurements on the host: accuracy against f64, criterion timings, the epsilon sweep,
//! and every primary-ray kernel against the reference path.

use super::*;

/// Renders a frame into an RGB image.
pub(super) fn image<S: Scalar>(scene: &Scene<S>) -> image::RgbImage {
    let (w, h) = (scene.camera.width, scene.camera.height);
    let mut line = vec![Rgb888::BLACK; usize::from(w)];
    let mut img = image::RgbImage::new(u32::from(w), u32::from(h));
    for row in 0..h {
        render_line(scene, row, &mut line);
        for (x, c) in line.iter().enumerate() {
            img.put_pixel(x as u32, u32::from(row), image::Rgb([c.r(), c.g(), c.b()]));
        }
    }
    img
}

/// Accuracy of one format on one scene.
pub(super) struct Accuracy {
    pub(super) cmp: Comparison,
    pub(super) ssim: f64,
    pub(super) delta: f64,
}

/// Reads a shipped scene in format `S`, with the texture files it names (from `scenes/`).
pub(super) fn read<S: Scalar>(text: &str) -> Scene<S> {
    let beside = crate::root().join("scenes/x.scene");
    let mut scene = Scene::<S>::empty();
    scene
        .read_with(text, None, &mut fixray::scene::files::beside(&beside))
        .expect("shipped scenes read in every format");
    scene
}

pub(super) struct MeasureAccuracy<'a>(pub(super) &'a str);
impl PerFormat for MeasureAccuracy<'_> {
    type Out = Accuracy;
    fn run<S: Scalar>(&mut self) -> Accuracy {
        let scene = read::<S>(self.0);
        let reference = read::<f64>(self.0);
        let cmp = compare(&scene, &reference, |_, _, _, _| {});
        let ssim = image_compare::rgb_similarity_structure(
            &image_compare::Algorithm::MSSIMSimple,
            &image(&scene),
            &image(&reference),
        )
        .map_or(f64::NAN, |s| s.score);
        Accuracy {
            cmp,
            ssim,
            delta: S::DELTA.to_f64(),
        }
    }
}

/// Benchmarks one frame of one scene in one format with criterion.
pub(super) struct Bench<'a> {
    pub(super) c: &'a mut Criterion,
    pub(super) scene: &'a str,
    pub(super) text: &'a str,
}
impl PerFormat for Bench<'_> {
    type Out = ();
    fn run<S: Scalar>(&mut self) {
        let scene = Scene::<S>::parse(self.text).expect("shipped scenes parse");
        let mut line = vec![Rgb888::BLACK; usize::from(scene.camera.width)];
        self.c
            .benchmark_group(self.scene)
            .bench_function(S::NAME, |b| {
                b.iter(|| {
                    for row in 0..scene.camera.height {
                        render_line(std::hint::black_box(&scene), row, &mut line);
                    }
                })
            });
    }
}

/// Reads criterion's median (ns) for a benchmark from its estimates file.
pub(super) fn criterion_median(dir: &Path, group: &str, function: &str) -> Option<f64> {
    let text =
        std::fs::read_to_string(dir.join(group).join(function).join("new/estimates.json")).ok()?;
    let estimates: serde_json::Value = serde_json::from_str(&text).ok()?;
    estimates["median"]["point_estimate"].as_f64()
}

/// One row of the epsilon sweep.
pub(super) struct Sweep {
    pub(super) deltas: f64,
    pub(super) epsilon: f64,
    pub(super) false_misses: u32,
    pub(super) false_hits: u32,
    pub(super) wrong_object: u32,
}

/// Renders the scene with epsilon = DELTA × 2^k for k = 0, 1, … up to 2⁻⁴ and counts hit/miss
/// disagreements with the f64 render at its default epsilon (the ground truth).
pub(super) struct SweepEpsilon<'a>(pub(super) &'a str);
impl PerFormat for SweepEpsilon<'_> {
    type Out = Vec<Sweep>;
    fn run<S: Scalar>(&mut self) -> Vec<Sweep> {
        let mut scene = Scene::<S>::parse(self.0).expect("shipped scenes parse");
        let truth = Scene::<f64>::parse(self.0).expect("and in f64");
        let mut rows = Vec::new();
        let mut deltas = 1.0f64;
        while deltas * S::DELTA.to_f64() <= 1.0 / 16.0 {
            let Some(eps) = S::from_f64(deltas * S::DELTA.to_f64()) else {
                break;
            };
            scene.epsilon = eps;
            let mut row = Sweep {
                deltas,
                epsilon: eps.to_f64(),
                false_misses: 0,
                false_hits: 0,
                wrong_object: 0,
            };
            for y in 0..truth.camera.height {
                for x in 0..truth.camera.width {
                    let seen = trace_pixel(&scene, x, y).hit.map(|(i, _)| i);
                    let true_hit = trace_pixel(&truth, x, y).hit.map(|(i, _)| i);
                    match (seen, true_hit) {
                        (None, Some(_)) => row.false_misses += 1,
                        (Some(_), None) => row.false_hits += 1,
                        (Some(a), Some(b)) if a != b => row.wrong_object += 1,
                        _ => {}
                    }
                }
            }
            rows.push(row);
            deltas *= 2.0;
        }
        rows
    }
}

/// The scenes and formats of the fast-path table.
pub(super) const FAST_SCENES: [&str; 3] = ["default", "planes", "horizon"];
pub(super) const FAST_FORMATS: [&str; 5] = ["i16f16", "i16f16r", "i20f12", "i32f32", "f32"];

/// One primary-ray path on one scene in one format.
pub(super) struct PathRow {
    pub(super) scene: &'static str,
    pub(super) format: &'static str,
    pub(super) path: &'static str,
    /// Share of pixels differing from the f64 reference picture.
    pub(super) vs_f64: f64,
    /// Share of pixels differing from this format's reference path.
    pub(super) vs_reference: f64,
    /// Host median ms per frame, and the ratio to the reference path in the same run.
    pub(super) ms: f64,
    pub(super) ratio: f64,
}

pub(super) type Picture = Vec<Rgb888>;

pub(super) fn share(a: &Picture, b: &Picture) -> f64 {
    a.iter().zip(b).filter(|(x, y)| x != y).count() as f64 / a.len() as f64
}

/// Median wall time of `runs` frames, in ms.
pub(super) fn median_ms(runs: usize, mut frame: impl FnMut() -> Picture) -> (f64, Picture) {
    let mut times = Vec::new();
    let mut picture = Vec::new();
    for _ in 0..runs {
        let start = std::time::Instant::now();
        picture = std::hint::black_box(frame());
        times.push(start.elapsed().as_secs_f64() * 1e3);
    }
    times.sort_by(f64::total_cmp);
    (times[times.len() / 2], picture)
}

pub(super) struct MeasurePaths<'a> {
    pub(super) scene: &'static str,
    pub(super) text: &'a str,
    pub(super) runs: usize,
}
impl PerFormat for MeasurePaths<'_> {
    type Out = Vec<PathRow>;
    fn run<S: Scalar>(&mut self) -> Vec<PathRow> {
        use fixray::PlaneMode;
        let scene = Scene::<S>::parse(self.text).expect("shipped scenes parse");
        let truth = Scene::<f64>::parse(self.text).expect("and in f64");
        let (w, h) = (scene.camera.width, scene.camera.height);
        let every = |f: &dyn Fn(u16, u16) -> Rgb888| -> Picture {
            (0..h)
                .flat_map(|y| (0..w).map(move |x| (x, y)))
                .map(|(x, y)| f(x, y))
                .collect()
        };
        let truth_picture = every(&|x, y| fixray::shade::pixel(&truth, x, y));
        let lines = |scene: &Scene<S>, mode: PlaneMode| -> Picture {
            let mut out = Vec::new();
            let mut line = vec![Rgb888::BLACK; usize::from(w)];
            let frame = fixray::Frame::with_mode(std::hint::black_box(scene), mode);
            for row in 0..h {
                frame.render_line(row, &mut line);
                out.extend_from_slice(&line);
            }
            out
        };
        let (ref_ms, reference) = median_ms(self.runs, || {
            every(&|x, y| fixray::shade::pixel(&scene, x, y))
        });
        let mut rows = Vec::new();
        let mut push = |path, ms: f64, picture: &Picture| {
            rows.push(PathRow {
                scene: self.scene,
                format: S::NAME,
                path,
                vs_f64: share(picture, &truth_picture),
                vs_reference: share(picture, &reference),
                ms,
                ratio: ref_ms / ms,
            })
        };
        push("reference (per pixel, normalised rays)", ref_ms, &reference);
        if fixray::Frame::<_>::new(&scene).kernel() == fixray::KernelKind::Flat {
            // The general fast path, which the pure-geometry kernel replaces for these
            // scenes: the plane `fast::Primary` picks, its ambient colour.
            let primary = fixray::internals::Primary::new(&scene.view()).expect("a plane scene");
            let (ms, picture) = median_ms(self.runs, || {
                every(&|x, y| match primary
                    .row(&scene.view(), y, x)
                    .map(|r| primary.nearest(&scene.view(), &r))
                {
                    Some(Ok(Some(hit))) => {
                        let m = scene.objects[hit.index].material;
                        fixray::shade::to_rgb888(scene.materials[usize::from(m)].ambient)
                    }
                    Some(Ok(None)) => fixray::shade::to_rgb888(scene.background),
                    _ => fixray::shade::pixel(&scene, x, y),
                })
            });
            push("fast: cross-products, one pixel at a time", ms, &picture);
            let (ms, picture) = median_ms(self.runs, || lines(&scene, PlaneMode::PerPixel));
            push("pure geometry, per-pixel mode", ms, &picture);
            let (ms, picture) = median_ms(self.runs, || lines(&scene, PlaneMode::Spans));
            push("pure geometry, span mode", ms, &picture);
        } else {
            let (ms, picture) = median_ms(self.runs, || lines(&scene, PlaneMode::PerPixel));
            push("fast: cross-products, division-free shadows", ms, &picture);
        }
        rows
    }
}
