//! Precision of every format against the f64 reference on the scenes in `scenes/`:
//! per-pixel |Δt| inside the documented first-order bound, pixel-mismatch budgets, and the
//! measurement behind the wide dot product (narrow against wide on the same inputs).
//!
//! Run with `cargo test --release --test precision -- --nocapture` to see the figures.

mod common;
use common::sampling;
use sampling::SplitMix;

use embedded_graphics::pixelcolor::RgbColor;
use fixray::compare::{Comparison, compare};
use fixray::internals::nearest_hit;
use fixray::{I16F16, I20F12, I32F32, Plane, Ray, RayKind, Scalar, Scene, Shape, Vec3};
use fixray::{Traced, trace_pixel};

const SCENES: [(&str, &str); 3] = [
    ("default", include_str!("../scenes/default.scene")),
    ("planes", include_str!("../scenes/planes.scene")),
    ("horizon", include_str!("../scenes/horizon.scene")),
];

fn plane_of<S: Scalar>(scene: &Scene<S>, i: usize) -> Plane<S> {
    match scene.objects[i].shape {
        Shape::Plane(p) => p,
        _ => panic!("the planes scenes hold planes only"),
    }
}

/// The first-order bound on |Δt| of `geometry`'s module documentation, in world units.
///
/// With δ the format's DELTA: the unit vectors N and d carry ≤ 2δ per component, so
/// N·d is off by ≤ 2(‖N‖₁ + ‖d‖₁)δ + ½δ ≤ 7.5δ; N·b by ≤ 2‖b‖₁δ + ½δ; the offset D' by
/// what the test measures (`d_offset`). t = (D' − N·b)/(N·d) then errs by
/// (ΔD' + Δ(N·b) + t·Δ(N·d)) / |N·d| plus one rounding of the division.
fn dt_bound(t: f64, n_dot_d: f64, base_l1: f64, d_offset: f64, delta: f64) -> f64 {
    (d_offset + (2.0 * base_l1 + 0.5) * delta + 7.5 * t * delta) / n_dot_d.abs() + delta
}

/// Checks every pixel where both formats see the same plane; returns the largest
/// |Δt| / bound and the largest |Δt| in DELTAs.
fn check_dt_bound<S: Scalar>(name: &str, text: &str) -> (f64, f64) {
    let scene = Scene::<S>::parse(text).unwrap();
    let reference = Scene::<f64>::parse(text).unwrap();
    let delta = S::DELTA.to_f64();
    let eye = reference.camera.viewpoint.to_f64();
    let base_l1 = eye.iter().map(|c| c.abs()).sum::<f64>();
    let (mut worst_ratio, mut worst_deltas) = (0.0f64, 0.0f64);
    for row in 0..scene.camera.height {
        for column in 0..scene.camera.width {
            let (Some(r), Some(rr)) = (
                scene.camera.primary_ray(column, row),
                reference.camera.primary_ray(column, row),
            ) else {
                continue;
            };
            let (Some((i, h)), Some((j, g))) =
                (nearest_hit(&scene, &r), nearest_hit(&reference, &rr))
            else {
                continue;
            };
            if i != j {
                continue;
            }
            let plane = plane_of(&reference, i);
            let n_dot_d = plane.normal().dot(rr.dir).unwrap();
            let d_offset = (plane_of(&scene, i).offset().to_f64() - plane.offset()).abs();
            let bound = dt_bound(g.t, n_dot_d, base_l1, d_offset, delta);
            let dt = (h.t.to_f64() - g.t).abs();
            assert!(
                dt <= bound,
                "{name} {}: pixel ({column}, {row}): |Δt| = {dt} > bound {bound} (t = {}, N·d = {n_dot_d})",
                S::NAME,
                g.t
            );
            worst_ratio = worst_ratio.max(dt / bound);
            worst_deltas = worst_deltas.max(dt / delta);
        }
    }
    println!(
        "{name:<8} {:<7} max |Δt| = {worst_deltas:>12.1} DELTAs, at most {:>5.1} % of the bound",
        S::NAME,
        100.0 * worst_ratio
    );
    (worst_ratio, worst_deltas)
}

#[test]
fn dt_stays_inside_the_first_order_bound() {
    for (name, text) in SCENES {
        check_dt_bound::<I16F16>(name, text);
        check_dt_bound::<I20F12>(name, text);
        check_dt_bound::<I32F32>(name, text);
        check_dt_bound::<f32>(name, text);
    }
}

/// Compares a format with f64 and checks that, away from object boundaries (the f64
/// render sees one object in the pixel's 3×3 neighbourhood) and where both see that object,
/// no channel differs by more than `max_interior_error` levels.
fn comparison<S: Scalar>(text: &str, max_interior_error: u8) -> Comparison {
    let scene = Scene::<S>::parse(text).unwrap();
    let reference = Scene::<f64>::parse(text).unwrap();
    let (w, h) = (
        usize::from(reference.camera.width),
        usize::from(reference.camera.height),
    );
    fn object<T>(t: &Traced<T>) -> Option<usize> {
        t.hit.as_ref().map(|(i, _)| *i)
    }
    let mut ref_objects = Vec::with_capacity(w * h);
    let mut errors = Vec::with_capacity(w * h);
    let c = compare(&scene, &reference, |column, row, px, ref_px| {
        let own = object(&trace_pixel(&scene, column, row));
        ref_objects.push(object(&trace_pixel(&reference, column, row)));
        let e = px
            .r()
            .abs_diff(ref_px.r())
            .max(px.g().abs_diff(ref_px.g()))
            .max(px.b().abs_diff(ref_px.b()));
        errors.push((own, e));
    });
    let mut interior = 0;
    for y in 1..h - 1 {
        for x in 1..w - 1 {
            let o = ref_objects[y * w + x];
            let uniform =
                (y - 1..=y + 1).all(|yy| (x - 1..=x + 1).all(|xx| ref_objects[yy * w + xx] == o));
            let (own, e) = errors[y * w + x];
            if uniform && own == o {
                interior += 1;
                assert!(
                    e <= max_interior_error,
                    "{}: pixel ({x}, {y}) differs by {e} levels inside an object",
                    S::NAME
                );
            }
        }
    }
    // Not vacuous: most of the image is interior.
    assert!(
        interior > w * h / 2,
        "{}: only {interior} interior pixels",
        S::NAME
    );
    c
}

/// Pixel-mismatch budgets (share of pixels with any channel different from the f64
/// render) and the largest channel error allowed.
///
/// - Ambient-only scenes (`planes`, `horizon`): colours are constant per object, so only
///   pixels on object boundaries and at the horizon can differ. Budget: 1 % for I16F16
///   and I20F12, 0.1 % for I32F32 and f32.
/// - The lit `default` scene: diffuse shading varies smoothly, and a pixel differs by one
///   level wherever the exact value lies within the shading error of a rounding boundary
///   (x.5). I16F16 shades to about 0.02 levels (1.3 % of pixels measured), I20F12 to
///   about 0.3 levels (18 %): budgets 3 % and 25 %.
///
/// In every case, away from object boundaries (and where both renders see the same
/// object) no channel may differ by more than 1 level; for ambient-only scenes by none.
#[test]
fn pixel_mismatch_stays_within_budget() {
    type Budget = (&'static str, &'static str, f64);
    let budgets: [Budget; 12] = [
        ("planes", "i16f16", 0.01),
        ("planes", "i20f12", 0.01),
        ("planes", "i32f32", 0.001),
        ("planes", "f32", 0.001),
        ("horizon", "i16f16", 0.01),
        ("horizon", "i20f12", 0.01),
        ("horizon", "i32f32", 0.001),
        ("horizon", "f32", 0.001),
        ("default", "i16f16", 0.03),
        ("default", "i20f12", 0.25),
        ("default", "i32f32", 0.001),
        ("default", "f32", 0.001),
    ];
    for (scene, format, budget) in budgets {
        let text = SCENES.iter().find(|(n, _)| *n == scene).unwrap().1;
        // Ambient-only scenes have constant colours per object: no interior error at all.
        let interior = if scene == "default" { 1 } else { 0 };
        let c = match format {
            "i16f16" => comparison::<I16F16>(text, interior),
            "i20f12" => comparison::<I20F12>(text, interior),
            "i32f32" => comparison::<I32F32>(text, interior),
            _ => comparison::<f32>(text, interior),
        };
        println!(
            "{scene:<8} {format:<7} differing {:>7.3} % (budget {:>5.1} %), PSNR {:>6.1} dB, \
             objects disagree on {} pixels",
            100.0 * c.differing_share(),
            100.0 * budget,
            c.psnr(),
            c.object_disagreements
        );
        assert!(
            c.differing_share() <= budget,
            "{scene} {format}: {} % of pixels differ",
            100.0 * c.differing_share()
        );
        // Not vacuous: the scenes do show objects.
        assert!(c.same_object_pixels > c.pixels / 2);
    }
}

/// Dot product with three narrow products (each rounded towards −∞), as the alternative
/// to `Scalar::dot3`'s wide accumulation.
fn narrow_dot<S: Scalar>(a: Vec3<S>, b: Vec3<S>) -> Option<S> {
    a.x.checked_mul(b.x)?
        .checked_add(a.y.checked_mul(b.y)?)?
        .checked_add(a.z.checked_mul(b.z)?)
}

/// t of the plane test computed with the narrow dot product.
fn narrow_t<S: Scalar>(plane: &Plane<S>, ray: &Ray<S>) -> Option<S> {
    let nd = narrow_dot(plane.normal(), ray.dir)?;
    let nb = narrow_dot(plane.normal(), ray.base)?;
    plane.offset().checked_sub(nb)?.checked_div(nd)
}

/// Narrow against wide dot products in the plane test, on the same quantised inputs,
/// against f64 evaluated on those inputs: (mean, max) |Δt| in DELTAs for each.
fn narrow_vs_wide<S: Scalar>(samples: usize) -> ((f64, f64), (f64, f64)) {
    let mut rng = SplitMix(0xD07);
    let (mut sum_n, mut max_n, mut sum_w, mut max_w, mut n) = (0.0, 0.0f64, 0.0, 0.0f64, 0);
    while n < samples {
        let mut v = |lo, hi| {
            [
                rng.uniform(lo, hi),
                rng.uniform(lo, hi),
                rng.uniform(lo, hi),
            ]
        };
        let (normal, point, base, dir) =
            (v(-1.0, 1.0), v(-20.0, 20.0), v(-10.0, 10.0), v(-1.0, 1.0));
        let (Some(normal), Some(point), Some(base), Some(dir)) = (
            Vec3::<S>::from_f64(normal),
            Vec3::<S>::from_f64(point),
            Vec3::<S>::from_f64(base),
            Vec3::<S>::from_f64(dir).and_then(Vec3::unit),
        ) else {
            continue;
        };
        let Ok(plane) = Plane::new(normal, point) else {
            continue;
        };
        let ray = Ray {
            base,
            dir,
            kind: RayKind::Secondary,
        };
        // The f64 reference on exactly the same (quantised) unit normal, offset and ray.
        let f = |v: Vec3<S>| Vec3::<f64>::from_f64(v.to_f64()).unwrap();
        let (nf, df, bf) = (f(plane.normal()), f(ray.dir), f(ray.base));
        let nd = nf.dot(df).unwrap();
        if nd.abs() < 0.05 {
            continue; // keep to well-conditioned rays: this compares arithmetic, not grazing
        }
        let t_ref = (plane.offset().to_f64() - nf.dot(bf).unwrap()) / nd;
        let (Some(tn), Ok(hit)) = (narrow_t(&plane, &ray), plane.intersect(&ray, S::ZERO)) else {
            continue;
        };
        let delta = S::DELTA.to_f64();
        let en = (tn.to_f64() - t_ref).abs() / delta;
        let ew = (hit.t.to_f64() - t_ref).abs() / delta;
        sum_n += en;
        sum_w += ew;
        max_n = max_n.max(en);
        max_w = max_w.max(ew);
        n += 1;
    }
    let count = f64::from(u32::try_from(n).unwrap());
    ((sum_n / count, max_n), (sum_w / count, max_w))
}

/// The measurement behind `Scalar::dot3`: wide accumulation must be at least as accurate
/// as narrow products, on average and in the worst case, in every fixed format.
#[test]
fn wide_dot_products_are_more_accurate_than_narrow() {
    for (name, ((mean_n, max_n), (mean_w, max_w))) in [
        ("i16f16", narrow_vs_wide::<I16F16>(20_000)),
        ("i20f12", narrow_vs_wide::<I20F12>(20_000)),
        ("i32f32", narrow_vs_wide::<I32F32>(20_000)),
    ] {
        println!(
            "{name}: |Δt| narrow mean {mean_n:.2} max {max_n:.1} DELTAs; wide mean {mean_w:.2} max {max_w:.1} DELTAs"
        );
        assert!(mean_w < mean_n, "{name}");
        assert!(max_w <= max_n, "{name}");
    }
}
