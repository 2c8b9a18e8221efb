//! The catalogue of hard cases for the plane test, one named test each, in every format
//! of the one list (`fixray::num::formats::FORMATS`), or in every format of it where the
//! case's right answer is exact (see [`exact`]).
//! Each says why it is hard and what the right answer is. (Spheres join this catalogue when
//! the renderer draws them.)
//!
//! The hard cases of frames drawn in blocks (`Frame::with_sampling`) and of the regions a
//! moved sphere changes (`Frame::changes_since`) are tested where those frames are drawn;
//! each is caught by its certificate or has its error stated:
//!
//! | case | what handles it | tested by |
//! |---|---|---|
//! | a sphere smaller than a block | every block its screen box meets is traced | `tests/sampling.rs`, `a_sphere_smaller_than_a_block_is_never_missed` |
//! | a tile's edge crossing a block | the edge located by the affine `(a − A)·β`, or the block traced; a pixel within rounding of the edge may take the other tile (stated: under 0.5 %) | `tests/sampling.rs`, `a_filled_pixel_stays_within_its_bound_of_the_exact_frame` |
//! | a shadow's edge crossing a block | one shadow state per light at the four corners and no sphere near the segments to the light, or the block traced | `tests/sampling.rs`, `shadow_edges_and_silhouettes_are_caught` |
//! | a mirror's edge crossing a block | a scene with a mirror is drawn exact | `tests/sampling.rs`, `frames_the_certificates_do_not_cover_are_exact` |
//! | a grazing silhouette | the sphere's screen box: its blocks are traced | `tests/sampling.rs`, `shadow_edges_and_silhouettes_are_caught` |
//! | a light on a surface | such a scene is drawn exact | `tests/sampling.rs`, `frames_the_certificates_do_not_cover_are_exact` |
//! | a shadow that leaves the moved sphere's box | the widened shadow cone's span on each row | `tests/changes.rs`, `a_ball_moved_anywhere_under_any_light_is_redrawn_exactly` |
//! | a reflection of the moved sphere | a scene another kernel draws changes whole rows | `tests/changes.rs`, `a_moved_sphere_another_kernel_draws_changes_whole_rows` |

mod common;

use common::probes::sqrt_error;
use common::v;
use fixray::Scalar;
use fixray::geometry::{Miss, Plane, PlaneError, Ray, RayKind, Vec3};

/// Runs `$check::<S>()` in every format of `FORMATS`.
macro_rules! all_formats {
    ($check:ident) => {
        fixray::for_each_format!(all: $check())
    };
}

/// Runs `$check::<S>()` in every format of `FORMATS` in which [`exact`] holds: the cases
/// whose right answer is exact.
macro_rules! every_exact_format {
    ($check:ident) => {{
        fn exact_only<S: Scalar>() {
            if exact::<S>() {
                $check::<S>();
            }
        }
        fixray::for_each_format!(all: exact_only());
    }};
}

/// Whether the exact cases hold in format `S`: their right answers are exact where every
/// value is a multiple of one DELTA (or start at the format's MAX, which a float cannot
/// step below by a few units) and every quotient the format can hold comes out exactly.
/// So: a fixed format (one with integer bits: `Scalar::INT_BITS` is 0 for the floats,
/// whose resolution is relative) whose division is exact there, as one truncation of the
/// exact quotient is. Not `i16f16r`: its division by reciprocal is off by up to
/// 1 + |q|·2⁻²⁸ DELTAs (measured: a t of 3 DELTAs comes out 2, and a hit on the plane
/// z = 0 lands in front of the screen).
fn exact<S: Scalar>() -> bool {
    let n = |k: i32| S::from_i32(k).unwrap();
    let three_deltas = S::DELTA.checked_mul_int(3).unwrap();
    let far = S::MAX.checked_sub(n(16)).unwrap();
    S::INT_BITS > 0
        && [
            (three_deltas, n(1), three_deltas),
            (three_deltas, n(-1), three_deltas.checked_neg().unwrap()),
            (n(15), n(1), n(15)),
            (n(6), n(3), n(2)),
            (far, n(1), far),
        ]
        .iter()
        .all(|&(a, b, q)| a.checked_div(b) == Some(q))
}

/// The notes' plane z = −7 (normal (0, 0, 1)).
fn floor<S: Scalar>() -> Plane<S> {
    Plane::new(v(0.0, 0.0, 1.0), v(0.0, 0.0, -7.0)).unwrap()
}

fn ray<S: Scalar>(base: Vec3<S>, dir: Vec3<S>, kind: RayKind) -> Ray<S> {
    Ray { base, dir, kind }
}

/// |N·d| swept across the epsilon from 8 DELTAs below to 8 above. Hard: the decision turns
/// on the last bit of N·d. Right answer: `|N·d| < EPS` misses (Parallel), `|N·d| >= EPS`
/// hits at t = 12/|N·d|. The direction (1, 0, −a) is not unit on purpose: N·d is then
/// exactly −a in every format, so the sweep tests the rule, not rounding.
fn sweep_across_epsilon<S: Scalar>() {
    let plane = floor::<S>();
    let eps = S::DEFAULT_EPSILON;
    for k in -8i32..=8 {
        let a = eps
            .checked_add(S::DELTA.checked_mul(S::from_i32(k).unwrap()).unwrap())
            .unwrap();
        let r = ray(
            v(0.0, 0.0, 5.0),
            Vec3::new(S::ONE, S::ZERO, S::ZERO.checked_sub(a).unwrap()),
            RayKind::Secondary,
        );
        let got = plane.intersect(&r, eps);
        if k < 0 {
            assert_eq!(got, Err(Miss::Parallel), "{} k = {k}", S::NAME);
        } else {
            // t = 12 / a exceeds the range of the fixed formats here: a hit or a
            // documented out-of-range miss, never parallel.
            assert!(
                matches!(got, Ok(_) | Err(Miss::OutOfRange)),
                "{} k = {k}: {got:?}",
                S::NAME
            );
        }
    }
}

#[test]
fn grazing_rays_swept_across_the_epsilon() {
    all_formats!(sweep_across_epsilon);
}

/// The base exactly on the plane. Hard: N·b − D' is exactly 0, t = 0. Right answer: a hit
/// at t = 0, the base itself (it lies on the plane), for any non-parallel direction.
fn base_on_plane<S: Scalar>() {
    let r = ray(
        v::<S>(3.0, -2.0, -7.0),
        v(0.0, 0.0, -1.0),
        RayKind::Secondary,
    );
    let hit = floor::<S>().intersect(&r, S::DEFAULT_EPSILON).unwrap();
    assert_eq!(hit.t, S::ZERO);
    assert_eq!(hit.point, r.base);
}

#[test]
fn ray_base_exactly_on_the_plane() {
    all_formats!(base_on_plane);
}

/// The base k DELTAs above and below the plane, the ray heading down. Hard: |t| is a few
/// DELTAs, its sign is the whole answer. Right answer (fixed formats, where k DELTAs is
/// exact): above, a hit at t = k DELTA; below, behind (t = −k DELTA < 0).
fn base_off_plane<S: Scalar>() {
    let plane = floor::<S>();
    let down = v::<S>(0.0, 0.0, -1.0);
    let seven = S::from_i32(-7).unwrap();
    for k in 1..=4 {
        let off = S::DELTA.checked_mul(S::from_i32(k).unwrap()).unwrap();
        let above = Vec3::new(S::ZERO, S::ZERO, seven.checked_add(off).unwrap());
        let below = Vec3::new(S::ZERO, S::ZERO, seven.checked_sub(off).unwrap());
        let hit = plane
            .intersect(&ray(above, down, RayKind::Secondary), S::DEFAULT_EPSILON)
            .unwrap();
        assert_eq!(hit.t, off, "{} k = {k}", S::NAME);
        assert_eq!(
            plane.intersect(&ray(below, down, RayKind::Secondary), S::DEFAULT_EPSILON),
            Err(Miss::Behind),
            "{} k = {k}",
            S::NAME
        );
    }
}

#[test]
fn ray_base_k_deltas_off_the_plane_and_t_just_below_zero() {
    every_exact_format!(base_off_plane);
}

/// A plane as far away as the format reaches, and one beyond (grazing). Hard: t and the
/// hit point sit at the edge of the range. Right answer: the reachable plane is hit with
/// exact t; the one beyond is a documented `OutOfRange` miss, never a wrapped t.
fn far_planes<S: Scalar>() {
    let far = S::MAX.checked_sub(S::from_i32(16).unwrap()).unwrap();
    let plane = Plane::new(
        v::<S>(0.0, 0.0, 1.0),
        Vec3::new(S::ZERO, S::ZERO, far.checked_neg().unwrap()),
    )
    .unwrap();
    let straight = ray(v::<S>(0.0, 0.0, 5.0), v(0.0, 0.0, -1.0), RayKind::Primary);
    let hit = plane.intersect(&straight, S::DEFAULT_EPSILON).unwrap();
    assert_eq!(
        hit.t,
        far.checked_add(S::from_i32(5).unwrap()).unwrap(),
        "{}",
        S::NAME
    );
    let slanted = ray(
        v::<S>(0.0, 0.0, 5.0),
        v::<S>(1.0, 0.0, -1.0).unit().unwrap(),
        RayKind::Primary,
    );
    assert_eq!(
        plane.intersect(&slanted, S::DEFAULT_EPSILON),
        Err(Miss::OutOfRange),
        "{}",
        S::NAME
    );
}

#[test]
fn t_at_and_beyond_the_formats_range() {
    every_exact_format!(far_planes);
}

/// Coordinates near the format's MAX. Hard: N·b alone is near overflow. Right answer: a
/// plane x = MAX − ½ hit from x = MAX − 1 along +x at t = ½.
fn near_max<S: Scalar>() {
    let one = S::ONE;
    let half = S::from_f64(0.5).unwrap();
    let x0 = S::MAX.checked_sub(one).unwrap();
    let plane = Plane::new(
        v::<S>(1.0, 0.0, 0.0),
        Vec3::new(x0.checked_add(half).unwrap(), S::ZERO, S::ZERO),
    )
    .unwrap();
    let r = ray(
        Vec3::new(x0, S::ZERO, S::ZERO),
        v(1.0, 0.0, 0.0),
        RayKind::Secondary,
    );
    assert_eq!(
        plane.intersect(&r, S::DEFAULT_EPSILON).unwrap().t,
        half,
        "{}",
        S::NAME
    );
    // Heading away from it: behind, no overflow on the way.
    let away = ray(
        Vec3::new(x0, S::ZERO, S::ZERO),
        v(-1.0, 0.0, 0.0),
        RayKind::Secondary,
    );
    assert_eq!(
        plane.intersect(&away, S::DEFAULT_EPSILON),
        Err(Miss::Behind),
        "{}",
        S::NAME
    );
}

#[test]
fn coordinates_near_the_formats_max() {
    every_exact_format!(near_max);
}

/// Coordinates of a few DELTAs, and a normal of one DELTA. Hard: the normal's direction
/// comes from its last bits; the hit is a few DELTAs from the base. Right answer: the
/// normal (DELTA, 0, 0) is the unit x axis; the plane x = 3 DELTA is hit from the origin
/// along +x at t = 3 DELTA exactly.
fn near_delta<S: Scalar>() {
    let d = S::DELTA;
    let three = d.checked_mul(S::from_i32(3).unwrap()).unwrap();
    let plane = Plane::new(Vec3::new(d, S::ZERO, S::ZERO), Vec3::new(three, d, d)).unwrap();
    assert_eq!(plane.normal(), v(1.0, 0.0, 0.0), "{}", S::NAME);
    let r = ray(Vec3::ZERO, v(1.0, 0.0, 0.0), RayKind::Secondary);
    assert_eq!(
        plane.intersect(&r, S::DEFAULT_EPSILON).unwrap().t,
        three,
        "{}",
        S::NAME
    );
}

#[test]
fn coordinates_and_normals_near_delta() {
    every_exact_format!(near_delta);
}

/// Non-unit normals (long and short) and the zero normal. Right answer: the same plane as
/// the unit normal; zero is refused with `PlaneError::ZeroNormal`.
fn normals<S: Scalar>() {
    let r = ray(v::<S>(4.0, 3.0, 5.0), v(0.0, 0.0, -1.0), RayKind::Primary);
    let unit = floor::<S>().intersect(&r, S::DEFAULT_EPSILON);
    for n in [1000.0, 0.001] {
        let p = Plane::new(v::<S>(0.0, 0.0, n), v(0.0, 0.0, -7.0)).unwrap();
        assert_eq!(
            p.intersect(&r, S::DEFAULT_EPSILON),
            unit,
            "{} n = {n}",
            S::NAME
        );
    }
    assert_eq!(
        Plane::new(Vec3::<S>::ZERO, v(0.0, 0.0, -7.0)),
        Err(PlaneError::ZeroNormal)
    );
}

#[test]
fn non_unit_and_zero_normals() {
    all_formats!(normals);
}

/// A zero direction. Hard: N·d = 0 exactly; with a zero epsilon the division would be by
/// zero. Right answer: Parallel with any positive epsilon; a documented OutOfRange (not a
/// panic) with epsilon 0.
fn zero_direction<S: Scalar>() {
    let r = ray(v::<S>(0.0, 0.0, 5.0), Vec3::ZERO, RayKind::Secondary);
    assert_eq!(
        floor::<S>().intersect(&r, S::DEFAULT_EPSILON),
        Err(Miss::Parallel)
    );
    assert_eq!(floor::<S>().intersect(&r, S::ZERO), Err(Miss::OutOfRange));
}

#[test]
fn a_zero_direction() {
    all_formats!(zero_direction);
}

/// A plane through the eye. Hard: t = 0 for every ray from the eye. Right answer: primary
/// rays reject the hit (the eye is in front of the screen), secondary rays hit at t = 0,
/// rays along the plane are parallel.
fn through_eye<S: Scalar>() {
    let eye = v::<S>(4.0, 3.0, 5.0);
    let plane = Plane::new(v::<S>(0.0, 1.0, 0.0), eye).unwrap();
    let down = v::<S>(0.0, -1.0, -1.0).unit().unwrap();
    assert_eq!(
        plane.intersect(&ray(eye, down, RayKind::Primary), S::DEFAULT_EPSILON),
        Err(Miss::InFrontOfScreen)
    );
    assert_eq!(
        plane
            .intersect(&ray(eye, down, RayKind::Secondary), S::DEFAULT_EPSILON)
            .unwrap()
            .t,
        S::ZERO
    );
    let along = v::<S>(1.0, 0.0, -1.0).unit().unwrap();
    assert_eq!(
        plane.intersect(&ray(eye, along, RayKind::Primary), S::DEFAULT_EPSILON),
        Err(Miss::Parallel)
    );
}

#[test]
fn a_plane_through_the_eye() {
    all_formats!(through_eye);
}

/// Hits with z ≈ 0: the screen-plane rule `hit.z > 0` is rejected for primary rays. Hard:
/// the rule compares against exactly 0. Right answer (fixed formats, exact): a plane at
/// z = 0 is accepted (z = 0 is not > 0), at z = +DELTA rejected, at z = −DELTA accepted.
fn screen_rule<S: Scalar>() {
    let r = ray(v::<S>(1.0, 1.0, 5.0), v(0.0, 0.0, -1.0), RayKind::Primary);
    for (k, accepted) in [(0, true), (1, false), (-1, true)] {
        let z = S::DELTA.checked_mul(S::from_i32(k).unwrap()).unwrap();
        let plane = Plane::new(v::<S>(0.0, 0.0, 1.0), Vec3::new(S::ZERO, S::ZERO, z)).unwrap();
        let got = plane.intersect(&r, S::DEFAULT_EPSILON);
        assert_eq!(got.is_ok(), accepted, "{} z = {k} DELTA: {got:?}", S::NAME);
        if !accepted {
            assert_eq!(got, Err(Miss::InFrontOfScreen));
        }
    }
}

#[test]
fn hits_with_z_near_zero_and_the_screen_rule() {
    every_exact_format!(screen_rule);
}

fn sphere<S: Scalar>(c: [f64; 3], r: f64) -> fixray::geometry::Sphere<S> {
    fixray::geometry::Sphere::new(v(c[0], c[1], c[2]), S::from_f64(r).unwrap()).unwrap()
}

/// Rays tangent to a sphere, and k DELTAs inside or outside tangency. Hard: the
/// discriminant is 0 (or a few DELTAs²). Right answer: exactly tangent hits at the touching
/// point (t = 15); passing outside by a DELTA misses (`NoRoot`); inside hits. In the
/// fixed formats every quantity here is exact.
fn tangent<S: Scalar>() {
    let s = sphere::<S>([0.0, 0.0, -10.0], 2.0);
    let down = v::<S>(0.0, 0.0, -1.0);
    let two = S::from_i32(2).unwrap();
    let hit = s
        .intersect(&ray(v(2.0, 0.0, 5.0), down, RayKind::Primary))
        .unwrap();
    assert_eq!(
        (hit.t.to_f64(), hit.point.to_f64()),
        (15.0, [2.0, 0.0, -10.0]),
        "{}",
        S::NAME
    );
    let outside = Vec3::new(
        two.checked_add(S::DELTA).unwrap(),
        S::ZERO,
        S::from_i32(5).unwrap(),
    );
    assert_eq!(
        s.intersect(&ray(outside, down, RayKind::Primary)),
        Err(Miss::NoRoot),
        "{}",
        S::NAME
    );
    let inside = Vec3::new(
        two.checked_sub(S::DELTA).unwrap(),
        S::ZERO,
        S::from_i32(5).unwrap(),
    );
    assert!(
        s.intersect(&ray(inside, down, RayKind::Primary)).is_ok(),
        "{}",
        S::NAME
    );
}

#[test]
fn rays_tangent_to_a_sphere() {
    every_exact_format!(tangent);
}

/// The base inside the sphere. Hard: one root is negative; the near root must not be
/// taken. Right answer: the far root, t = r from the centre, in every direction: within
/// 8 DELTAs, or within 2ρr where the format's square root errs by ρ relative (the unit
/// direction and the root of the discriminant each carry it once; for a rounded root
/// 2ρr < 8 DELTAs, for `f32m`'s approximate one it is 0.37).
fn inside<S: Scalar>() {
    let s = sphere::<S>([1.0, 2.0, -10.0], 3.0);
    let tolerance = (8.0 * S::DELTA.to_f64()).max(2.0 * sqrt_error::<S>() * 3.0);
    for dir in [
        [1.0, 0.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [1.0, 1.0, 1.0],
    ] {
        let d = v::<S>(dir[0], dir[1], dir[2]).unit().unwrap();
        let hit = s
            .intersect(&ray(v(1.0, 2.0, -10.0), d, RayKind::Secondary))
            .unwrap();
        assert!(
            (hit.t.to_f64() - 3.0).abs() <= tolerance,
            "{} {dir:?}: {:?}",
            S::NAME,
            hit.t
        );
    }
}

#[test]
fn a_ray_base_inside_the_sphere() {
    all_formats!(inside);
}

/// The cancellation-prone discriminant: a small sphere 20 000 units away. Hard: the
/// textbook b² − c subtracts two numbers of about 4·10⁸ to find 0.25, far beyond I16F16's
/// range and its precision; c itself does not fit I16F16. Right answer: t = 20004.5 (the
/// near surface), within a few DELTAs × t, from r² − |oc − (oc·d)d|² and −b − √Δ: within
/// 10⁻³, or within 2ρr where the format's square root errs by ρ relative (√Δ ≤ r carries
/// it; 2ρr is below 10⁻³ for a rounded root, 0.06 for `f32m`'s approximate one).
fn far_small_sphere<S: Scalar>() {
    let s = sphere::<S>([0.0, 0.0, -20000.0], 0.5);
    let tolerance = 1e-3f64.max(2.0 * sqrt_error::<S>() * 0.5);
    let hit = s
        .intersect(&ray(v(0.0, 0.0, 5.0), v(0.0, 0.0, -1.0), RayKind::Primary))
        .unwrap();
    assert!(
        (hit.t.to_f64() - 20004.5).abs() <= tolerance,
        "{}: {:?}",
        S::NAME,
        hit.t
    );
    // Slightly off-axis: disc = 0.25 − 0.3² = 0.16, t = 20005 − 0.4 = 20004.6.
    let hit = s
        .intersect(&ray(v(0.3, 0.0, 5.0), v(0.0, 0.0, -1.0), RayKind::Primary))
        .unwrap();
    assert!(
        (hit.t.to_f64() - 20004.6).abs() <= tolerance,
        "{}: {:?}",
        S::NAME,
        hit.t
    );
}

#[test]
fn the_cancellation_prone_discriminant() {
    all_formats!(far_small_sphere);
}

/// A ray starting a DELTA outside the surface, heading in. Hard: the near root is a
/// DELTA, the difference of two numbers near 4; c/q keeps it to one rounding. Right
/// answer: a hit at t = 1 DELTA (the exact root is DELTA·(1 − DELTA/4)); the division
/// rounds towards zero, so 0 is within the bound too, a negative t (behind) is not.
fn base_on_the_surface<S: Scalar>() {
    let s = sphere::<S>([0.0, 0.0, -10.0], 2.0);
    let z = S::from_i32(-8).unwrap().checked_add(S::DELTA).unwrap();
    let hit = s
        .intersect(&ray(
            Vec3::new(S::ZERO, S::ZERO, z),
            v(0.0, 0.0, -1.0),
            RayKind::Secondary,
        ))
        .unwrap();
    assert!(
        hit.t >= S::ZERO && hit.t <= S::DELTA,
        "{}: {:?}",
        S::NAME,
        hit.t
    );
}

#[test]
fn a_ray_starting_a_delta_off_the_sphere() {
    every_exact_format!(base_on_the_surface);
}

/// Not vacuous: the exact cases run in every fixed main format (`fixray::num::formats::MAIN`).
#[test]
fn the_exact_cases_run_in_every_fixed_main_format() {
    fn fixed_and_exact<S: Scalar>() -> (bool, bool) {
        (S::INT_BITS > 0, exact::<S>())
    }
    for name in fixray::num::formats::MAIN {
        let (fixed, exact) = fixray::with_format!(name, fixed_and_exact()).unwrap();
        assert!(!fixed || exact, "{name}");
    }
}
