//! Precision of every format against the f64 reference on the scenes in `scenes/`:
//! per-pixel |Δt| inside the documented first-order bound, pixel-mismatch budgets, and the
//! measurement behind the wide dot product (narrow against wide on the same inputs).
//!
//! Run with `cargo test --release --test precision -- --nocapture` to see the figures.

mod common;

use common::probes::{dot_rounds_once, sqrt_error, sqrt_is_rounded};
use common::sampling;
use sampling::SplitMix;

use embedded_graphics::pixelcolor::RgbColor;
use fixray::compare::{Comparison, compare};
use fixray::geometry::{Plane, Ray, RayKind, Shape, Vec3};
use fixray::num::formats::{FORMATS, MAIN, REFERENCE};
use fixray::shade::{Traced, trace_pixel};
use fixray::{Scalar, Scene};

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
///
/// The 2δ per component assume a square root rounded to within δ (relative). With
/// `unit_error` = max(δ, ρ), ρ the format's square root's relative error ([`sqrt_error`]),
/// the unit vectors carry 2·`unit_error` per component instead: the same bound for every
/// rounded root (ρ < δ measured in every such format), and the first-order bound of an
/// approximate one (`f32m`: ρ ≈ 6 %).
fn dt_bound(t: f64, n_dot_d: f64, base_l1: f64, d_offset: f64, delta: f64, unit_error: f64) -> f64 {
    (d_offset + 2.0 * base_l1 * unit_error + 0.5 * delta + (7.0 * unit_error + 0.5 * delta) * t)
        / n_dot_d.abs()
        + delta
}

/// Checks every pixel where both formats see the same plane; returns the largest
/// |Δt| / bound and the largest |Δt| in DELTAs.
fn check_dt_bound<S: Scalar>(name: &str, text: &str) -> (f64, f64) {
    let scene = Scene::<S>::parse(text).unwrap();
    let reference = Scene::<f64>::parse(text).unwrap();
    let delta = S::DELTA.to_f64();
    let unit_error = delta.max(sqrt_error::<S>());
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
            let (Some((i, h)), Some((j, g))) = (
                fixray::shade::trace(&scene, &r).hit,
                fixray::shade::trace(&reference, &rr).hit,
            ) else {
                continue;
            };
            if i != j {
                continue;
            }
            let plane = plane_of(&reference, i);
            let n_dot_d = plane.normal().dot(rr.dir).unwrap();
            let d_offset = (plane_of(&scene, i).offset().to_f64() - plane.offset()).abs();
            let bound = dt_bound(g.t, n_dot_d, base_l1, d_offset, delta, unit_error);
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
        fixray::for_each_format!(all: check_dt_bound(name, text));
    }
}

/// Compares a format with f64: the comparison, and the largest channel difference away
/// from object boundaries (the f64 render sees one object in the pixel's 3×3
/// neighbourhood) where both see that object.
fn comparison<S: Scalar>(text: &str) -> (Comparison, u8) {
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
    let (mut interior, mut worst) = (0, 0);
    for y in 1..h - 1 {
        for x in 1..w - 1 {
            let o = ref_objects[y * w + x];
            let uniform =
                (y - 1..=y + 1).all(|yy| (x - 1..=x + 1).all(|xx| ref_objects[yy * w + xx] == o));
            let (own, e) = errors[y * w + x];
            if uniform && own == o {
                interior += 1;
                worst = worst.max(e);
            }
        }
    }
    // Not vacuous: most of the image is interior.
    assert!(
        interior > w * h / 2,
        "{}: only {interior} interior pixels",
        S::NAME
    );
    (c, worst)
}

/// The pixel-mismatch budget of format `S` (share of pixels with any channel different
/// from the f64 render) on a lit scene or an ambient-only one, from its DELTA δ:
/// `0.1 % + k·δ`. The 0.1 % are the edge pixels any format may resolve differently from
/// f64; the rest is the share of pixels whose exact value lies within the format's
/// error of a decision, proportional to δ:
///
/// - lit (`default`): diffuse shading varies smoothly, and a channel differs by one level
///   wherever its exact value lies within the shading error of a rounding boundary
///   (x.5): within ±2 δ (in units of 255 levels) of it, `k = 4·255` (I16F16: 1.6 %,
///   measured 0.6 %; I20F12: 25 %, measured 7 %);
/// - ambient-only (`planes`, `horizon`): colours are constant per object, so only the
///   boundaries and the horizon differ, where a grazing ray's decision turns: within
///   16 δ of the epsilon on either side (the band of `tests/properties.rs` (b)),
///   `k = 32` (I16F16: 0.15 %, measured 0.02 %; I20F12: 0.9 %, measured 0.24 %).
///
/// Finer formats (I32F32, f32) are left with the 0.1 %. `None` for a lit scene in a
/// format with an approximate square root: it shades every normalised vector as far off
/// as its root (`f32m`: 9 % of `default`'s pixels measured), so that share is measured,
/// not bounded; its interior error is bounded all the same.
fn budget<S: Scalar>(lit: bool) -> Option<f64> {
    let delta = S::DELTA.to_f64();
    if lit && !sqrt_is_rounded::<S>() {
        return None;
    }
    let per_delta = if lit { 4.0 * 255.0 } else { 32.0 };
    Some(0.001 + per_delta * delta)
}

/// Pixel-mismatch budgets ([`budget`]) in every format of the one list
/// (`fixray::num::formats::FORMATS`). In every case, away from object boundaries (and
/// where both renders see the same object) no channel may differ by more than 1 level;
/// for ambient-only scenes by none.
#[test]
fn pixel_mismatch_stays_within_budget() {
    for (scene, text) in SCENES {
        // Ambient-only scenes have constant colours per object: no interior error at all.
        let lit = scene == "default";
        let interior = u8::from(lit);
        for format in FORMATS {
            if format == REFERENCE {
                continue;
            }
            let (c, worst) = fixray::with_format!(format, comparison(text)).unwrap();
            let budget = fixray::with_format!(format, budget(lit)).unwrap();
            println!(
                "{scene:<8} {format:<7} differing {:>7.3} % (budget {:>6}), PSNR {:>6.1} dB, \
                 objects disagree on {} pixels",
                100.0 * c.differing_share(),
                budget.map_or("none".to_string(), |b| format!("{:.2} %", 100.0 * b)),
                c.psnr(),
                c.object_disagreements
            );
            assert!(
                worst <= interior,
                "{scene} {format}: a pixel differs by {worst} levels inside an object"
            );
            if let Some(budget) = budget {
                assert!(
                    c.differing_share() <= budget,
                    "{scene} {format}: {} % of pixels differ",
                    100.0 * c.differing_share()
                );
            }
            // Not vacuous: the scenes do show objects.
            assert!(c.same_object_pixels > c.pixels / 2);
        }
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
fn narrow_vs_wide<S: Scalar>(samples: usize) -> NarrowWide {
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

/// (mean, max) |Δt| in DELTAs, narrow and wide.
type NarrowWide = ((f64, f64), (f64, f64));

/// Narrow against wide in format `S` if it is fixed (it has integer bits:
/// `Scalar::INT_BITS` is 0 for the floats, which have no wider accumulator): whether its
/// `dot3` rounds once, and the measurement.
fn fixed_narrow_vs_wide<S: Scalar>() -> Option<(bool, NarrowWide)> {
    (S::INT_BITS > 0).then(|| (dot_rounds_once::<S>(), narrow_vs_wide::<S>(20_000)))
}

/// The measurement behind `Scalar::dot3`: wide accumulation must be at least as accurate
/// as narrow products, on average and in the worst case, in every fixed format of the
/// one list (`fixray::num::formats::FORMATS`). A fixed format whose `dot3` is itself
/// narrow (`i16f16n`, by [`dot_rounds_once`]) must compute the same t both ways.
#[test]
fn wide_dot_products_are_more_accurate_than_narrow() {
    let mut fixed = Vec::new();
    for name in FORMATS {
        let Some((wide, ((mean_n, max_n), (mean_w, max_w)))) =
            fixray::with_format!(name, fixed_narrow_vs_wide()).unwrap()
        else {
            continue;
        };
        println!(
            "{name}: |Δt| narrow mean {mean_n:.2} max {max_n:.1} DELTAs; wide mean {mean_w:.2} max {max_w:.1} DELTAs"
        );
        fixed.push((name, wide));
        if wide {
            assert!(mean_w < mean_n, "{name}");
            assert!(max_w <= max_n, "{name}");
        } else {
            assert_eq!((mean_w, max_w), (mean_n, max_n), "{name}");
        }
    }
    // Not vacuous: every fixed main format accumulates wide.
    assert!(!fixed.is_empty());
    for (name, wide) in fixed {
        assert!(wide || !MAIN.contains(&name), "{name}");
    }
}
