//! Host benchmarks: one frame of the default scene per number format, and the plane test
//! with wide (the library's) against narrow dot products.
//!
//! ```text
//! cargo bench --bench render
//! ```
//! Host timings on a shared machine are noisy: compare ratios within one run.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use fixray::geometry::{Plane, Ray, RayKind, Vec3};
use fixray::internals::render_line_ambient;
use fixray::stats::Counters;
use fixray::{I16F16, I20F12, I32F32, Scalar, Scene, render_line};

const DEFAULT: &str = include_str!("../scenes/default.scene");

fn frame<S: Scalar>(scene: &Scene<S>, line: &mut [Rgb888]) {
    for row in 0..scene.camera.height {
        render_line(scene, row, line);
    }
}

fn bench_format<S: Scalar>(c: &mut Criterion) {
    let scene = Scene::<S>::parse(DEFAULT).unwrap();
    let mut line = vec![Rgb888::BLACK; usize::from(scene.camera.width)];
    c.bench_function(&format!("frame/default/{}", S::NAME), |b| {
        b.iter(|| frame(black_box(&scene), &mut line));
    });
}

/// t of the plane test with the library's (wide) dot products.
fn wide_t<S: Scalar>(plane: &Plane<S>, ray: &Ray<S>) -> Option<S> {
    let nd = plane.normal().dot(ray.dir)?;
    let nb = plane.normal().dot(ray.base)?;
    plane.offset().checked_sub(nb)?.checked_div(nd)
}

/// The same with narrow products (three roundings per dot product), for comparison.
fn narrow_t<S: Scalar>(plane: &Plane<S>, ray: &Ray<S>) -> Option<S> {
    let dot = |a: Vec3<S>, b: Vec3<S>| -> Option<S> {
        a.x.checked_mul(b.x)?
            .checked_add(a.y.checked_mul(b.y)?)?
            .checked_add(a.z.checked_mul(b.z)?)
    };
    let nd = dot(plane.normal(), ray.dir)?;
    let nb = dot(plane.normal(), ray.base)?;
    plane.offset().checked_sub(nb)?.checked_div(nd)
}

fn bench_dot<S: Scalar>(c: &mut Criterion) {
    let v = |x, y, z| Vec3::<S>::from_f64([x, y, z]).unwrap();
    let plane = Plane::new(v(0.4, 1.0, 0.3), v(1.0, 0.5, -6.0)).unwrap();
    let ray = Ray {
        base: v(4.0, 3.0, 6.0),
        dir: v(-0.2, -0.5, -1.0).unit().unwrap(),
        kind: RayKind::Primary,
    };
    c.bench_function(&format!("plane_t/wide/{}", S::NAME), |b| {
        b.iter(|| wide_t(black_box(&plane), black_box(&ray)));
    });
    c.bench_function(&format!("plane_t/narrow/{}", S::NAME), |b| {
        b.iter(|| narrow_t(black_box(&plane), black_box(&ray)));
    });
}

/// The full renderer (plan picks the stages) against the ambient-only stage set called
/// directly (every other stage compiled out) on the ambient-only planes scene: the plan
/// must cost nothing (within 5 %).
fn bench_plan(c: &mut Criterion) {
    let scene = Scene::<I16F16>::parse(include_str!("../scenes/planes.scene")).unwrap();
    let mut line = vec![Rgb888::BLACK; usize::from(scene.camera.width)];
    let mut group = c.benchmark_group("ambient-only planes scene");
    group.bench_function("full renderer (planned)", |b| {
        b.iter(|| frame(black_box(&scene), &mut line));
    });
    group.bench_function("stages compiled out", |b| {
        b.iter(|| {
            let mut counters = Counters::default();
            for row in 0..scene.camera.height {
                render_line_ambient(black_box(&scene), row, &mut line, &mut counters);
            }
        });
    });
    group.finish();
}

fn benches(c: &mut Criterion) {
    bench_plan(c);
    bench_format::<I16F16>(c);
    bench_format::<I20F12>(c);
    bench_format::<I32F32>(c);
    bench_format::<f32>(c);
    bench_format::<f64>(c);
    bench_dot::<I16F16>(c);
    bench_dot::<I32F32>(c);
}

criterion_group!(render, benches);
criterion_main!(render);
