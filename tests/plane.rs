//! The plane test of the course notes (`plane_hits`), in every number format (every one of
//! the one list, `fixray::num::formats::FORMATS`): the notes' numeric example exactly,
//! then a table of cases around each rule of the test.

mod common;

use common::probes::divides_exactly;
use common::v;
use fixray::geometry::{Hit, Miss, Plane, PlaneError, Ray, RayKind, Vec3};
use fixray::{I16F16, Scalar};

/// Runs `$check::<S>()` in every format of `FORMATS`.
macro_rules! all_formats {
    ($check:ident) => {
        fixray::for_each_format!(all: $check())
    };
}

fn ray<S: Scalar>(base: [f64; 3], dir: [f64; 3], kind: RayKind) -> Ray<S> {
    Ray {
        base: v(base[0], base[1], base[2]),
        dir: v(dir[0], dir[1], dir[2]).unit().unwrap(),
        kind,
    }
}

/// The notes: plane n = (0,0,1), p = (0,0,−7); ray base (4,3,5), dir (0,0,−1):
/// N·d = −1, N·b = 5, N·p = −7, t = (−7 − 5)/(−1) = 12, hit = (4, 3, −7). Every value is
/// exact in every format that divides exactly ([`divides_exactly`]), so the result must be
/// exact too; in the others t is within the first-order bound of `geometry`'s module
/// documentation, `(ΔD' + (2‖b‖₁ + ½)δ + 7.5tδ)/|N·d| + δ` with `ΔD' ≤ (2‖p‖₁ + ½)δ`
/// (the unit normal's 2δ per component): (14.5 + 24.5 + 90 + 1)δ = 130δ here.
fn notes_example<S: Scalar>() {
    let plane = Plane::new(v::<S>(0.0, 0.0, 1.0), v(0.0, 0.0, -7.0)).unwrap();
    let r = ray::<S>([4.0, 3.0, 5.0], [0.0, 0.0, -1.0], RayKind::Primary);
    let hit = plane.intersect(&r, S::DEFAULT_EPSILON).unwrap();
    if divides_exactly::<S>() {
        assert_eq!(plane.offset().to_f64(), -7.0, "{}", S::NAME);
        assert_eq!(hit.t.to_f64(), 12.0, "{}", S::NAME);
        assert_eq!(hit.point.to_f64(), [4.0, 3.0, -7.0], "{}", S::NAME);
    } else {
        let bound = 130.0 * S::DELTA.to_f64();
        assert!(
            (hit.t.to_f64() - 12.0).abs() <= bound,
            "{}: {hit:?}",
            S::NAME
        );
    }
}

#[test]
fn notes_numeric_example_is_exact_in_every_format() {
    all_formats!(notes_example);
}

/// |N·d| just below the epsilon misses, just above hits; equal to it hits (the rule is
/// `|N·d| < EPS` → miss). Both signs of N·d.
fn parallel_within_epsilon<S: Scalar>() {
    let eps = S::from_f64(1.0 / 64.0).unwrap(); // exact in every format
    let plane = Plane::new(v::<S>(0.0, 0.0, 1.0), v(0.0, 0.0, -7.0)).unwrap();
    for sign in [-1.0, 1.0] {
        // dir = (√(1 − a²), 0, a): N·d = a.
        let dir_for = |a: f64| [(1.0 - a * a).sqrt(), 0.0, sign * a];
        let below = ray::<S>([0.0, 0.0, 5.0], dir_for(0.9 / 64.0), RayKind::Secondary);
        assert_eq!(
            plane.intersect(&below, eps),
            Err(Miss::Parallel),
            "{}",
            S::NAME
        );
        let above = ray::<S>([0.0, 0.0, 5.0], dir_for(1.1 / 64.0), RayKind::Secondary);
        let got = plane.intersect(&above, eps);
        if sign < 0.0 {
            // Heading down towards z = −7 from z = 5: t = 12 / (1.1/64) ≈ 698.
            // Within the documented first-order bound (4|b| + 1 + 4t)·DELTA/|N·d|.
            let t = got.unwrap().t.to_f64();
            let exact = 12.0 * 64.0 / 1.1;
            let bound = (4.0 * 5.0 + 1.0 + 4.0 * exact) * S::DELTA.to_f64() * 64.0 / 1.1;
            assert!((t - exact).abs() <= bound, "{} t = {t}", S::NAME);
        } else {
            // Heading up, away from the plane: not parallel, but behind.
            assert_eq!(got, Err(Miss::Behind), "{}", S::NAME);
        }
    }
    // |N·d| exactly equal to the epsilon is not below it: a hit. A non-unit direction makes
    // N·d exactly −1/64 in every format.
    let exact = Ray {
        base: v(0.0, 0.0, 5.0),
        dir: v(1.0, 0.0, -1.0 / 64.0),
        kind: RayKind::Secondary,
    };
    assert_eq!(
        plane.normal().dot(exact.dir),
        Some(S::ZERO.checked_sub(eps).unwrap())
    );
    // t = 768 within 64 DELTAs (its division's rounding, amplified by 1/|N·d| = 64), or,
    // where the format does not divide exactly ([`divides_exactly`]: its unit normal is
    // off too), within the first-order bound above.
    let t = plane.intersect(&exact, eps).unwrap().t.to_f64();
    let bound = if divides_exactly::<S>() {
        64.0
    } else {
        (4.0 * 5.0 + 1.0 + 4.0 * 768.0) * 64.0
    };
    assert!(
        (t - 12.0 * 64.0).abs() <= bound * S::DELTA.to_f64(),
        "{} t = {t}",
        S::NAME
    );
    // Exactly parallel: N·d = 0 is always a miss, even with a zero epsilon (no division
    // by zero, no panic).
    let flat = ray::<S>([0.0, 0.0, 5.0], [1.0, 0.0, 0.0], RayKind::Secondary);
    assert_eq!(plane.intersect(&flat, eps), Err(Miss::Parallel));
    assert_eq!(plane.intersect(&flat, S::ZERO), Err(Miss::OutOfRange));
}

#[test]
fn rays_parallel_within_epsilon_miss_on_both_sides() {
    all_formats!(parallel_within_epsilon);
}

/// A plane behind the base: t < 0 is a miss.
fn behind_base<S: Scalar>() {
    let plane = Plane::new(v::<S>(0.0, 0.0, 1.0), v(0.0, 0.0, 8.0)).unwrap();
    let r = ray::<S>([0.0, 0.0, 5.0], [0.0, 0.0, -1.0], RayKind::Secondary);
    assert_eq!(plane.intersect(&r, S::DEFAULT_EPSILON), Err(Miss::Behind));
}

#[test]
fn a_plane_behind_the_base_is_a_miss() {
    all_formats!(behind_base);
}

/// A plane between the eye (z = 5) and the screen (z = 0): a primary ray's hit has z > 0
/// and is rejected; a secondary ray hits it. A hit exactly on the screen (z = 0) counts.
fn in_front_of_screen<S: Scalar>() {
    let plane = Plane::new(v::<S>(0.0, 0.0, 1.0), v(0.0, 0.0, 2.0)).unwrap();
    let primary = ray::<S>([0.0, 0.0, 5.0], [0.0, 0.0, -1.0], RayKind::Primary);
    assert_eq!(
        plane.intersect(&primary, S::DEFAULT_EPSILON),
        Err(Miss::InFrontOfScreen)
    );
    let secondary = Ray {
        kind: RayKind::Secondary,
        ..primary
    };
    let hit = plane.intersect(&secondary, S::DEFAULT_EPSILON).unwrap();
    if !divides_exactly::<S>() {
        // Neither t nor the screen's z = 0 is exact ([`divides_exactly`]).
        return;
    }
    assert_eq!(hit.t.to_f64(), 3.0);
    let screen = Plane::new(v::<S>(0.0, 0.0, 1.0), v(0.0, 0.0, 0.0)).unwrap();
    assert_eq!(
        screen
            .intersect(&primary, S::DEFAULT_EPSILON)
            .map(|h| h.point.z.to_f64()),
        Ok(0.0)
    );
}

#[test]
fn primary_hits_in_front_of_the_screen_are_rejected() {
    all_formats!(in_front_of_screen);
}

/// The normal need not be unit length: (0, 0, 7) and (0, 0, 1) give the same plane and
/// the same hit; (1, 2, 2) (length 3) gives a tilted plane with an exact answer.
fn non_unit_normal<S: Scalar>() {
    let r = ray::<S>([4.0, 3.0, 5.0], [0.0, 0.0, -1.0], RayKind::Primary);
    let a = Plane::new(v::<S>(0.0, 0.0, 7.0), v(0.0, 0.0, -7.0)).unwrap();
    let b = Plane::new(v::<S>(0.0, 0.0, 1.0), v(0.0, 0.0, -7.0)).unwrap();
    assert_eq!(
        a.intersect(&r, S::DEFAULT_EPSILON),
        b.intersect(&r, S::DEFAULT_EPSILON)
    );
    // x + 2y + 2z = 0 through the origin; the ray x = 4, y = 3 meets it at z = −5: t = 10.
    let tilted = Plane::new(v::<S>(1.0, 2.0, 2.0), v(0.0, 0.0, 0.0)).unwrap();
    let hit = tilted.intersect(&r, S::DEFAULT_EPSILON).unwrap();
    let tol = 64.0 * S::DELTA.to_f64();
    assert!(
        (hit.t.to_f64() - 10.0).abs() <= tol,
        "{} t = {:?}",
        S::NAME,
        hit.t
    );
    assert!((hit.point.z.to_f64() + 5.0).abs() <= tol, "{}", S::NAME);
}

#[test]
fn non_unit_normals_are_normalised() {
    all_formats!(non_unit_normal);
}

/// A plane through the eye: a ray leaving it at an angle hits at t = 0, the eye itself,
/// which lies in front of the screen (z > 0): rejected for primary rays, a hit at t = 0
/// for secondary ones. Running along it is parallel.
fn plane_through_eye<S: Scalar>() {
    let plane = Plane::new(v::<S>(1.0, 0.0, 0.0), v(4.0, 3.0, 5.0)).unwrap();
    let primary = ray::<S>([4.0, 3.0, 5.0], [1.0, 0.0, -1.0], RayKind::Primary);
    assert_eq!(
        plane.intersect(&primary, S::DEFAULT_EPSILON),
        Err(Miss::InFrontOfScreen)
    );
    let secondary = Ray {
        kind: RayKind::Secondary,
        ..primary
    };
    let Hit { t, point } = plane.intersect(&secondary, S::DEFAULT_EPSILON).unwrap();
    assert_eq!(t, S::ZERO);
    assert_eq!(point.to_f64(), [4.0, 3.0, 5.0]);
    let along = ray::<S>([4.0, 3.0, 5.0], [0.0, 0.0, -1.0], RayKind::Primary);
    assert_eq!(
        plane.intersect(&along, S::DEFAULT_EPSILON),
        Err(Miss::Parallel)
    );
}

#[test]
fn a_plane_through_the_eye() {
    all_formats!(plane_through_eye);
}

fn zero_normal<S: Scalar>() {
    assert_eq!(
        Plane::new(Vec3::<S>::ZERO, v(1.0, 2.0, 3.0)),
        Err(PlaneError::ZeroNormal)
    );
}

#[test]
fn a_zero_normal_is_refused() {
    all_formats!(zero_normal);
}

/// t beyond the format's range is a documented miss (`OutOfRange`), in debug builds (with
/// overflow checks) and release builds alike: no panic, no wrapped t.
#[test]
fn t_beyond_the_range_is_a_miss_not_a_wrap() {
    // I16F16 holds ±32768. A plane at z = −30000 seen at 45°: t ≈ 42433.
    let plane = Plane::new(v::<I16F16>(0.0, 0.0, 1.0), v(0.0, 0.0, -30000.0)).unwrap();
    let r = ray::<I16F16>([0.0, 0.0, 5.0], [1.0, 0.0, -1.0], RayKind::Primary);
    assert_eq!(
        plane.intersect(&r, I16F16::DEFAULT_EPSILON),
        Err(Miss::OutOfRange)
    );
    // Straight on, t = 30005 fits and hits.
    let r = ray::<I16F16>([0.0, 0.0, 5.0], [0.0, 0.0, -1.0], RayKind::Primary);
    assert_eq!(
        plane
            .intersect(&r, I16F16::DEFAULT_EPSILON)
            .unwrap()
            .t
            .to_f64(),
        30005.0
    );
    // t fits but the hit point does not: base near MAX, t carries it past.
    // z = −5000 from (30000, 0, 5) at 45°: t ≈ 7078 fits, the hit's x = 35005 does not.
    let plane = Plane::new(v::<I16F16>(0.0, 0.0, 1.0), v(0.0, 0.0, -5000.0)).unwrap();
    let r = ray::<I16F16>([30000.0, 0.0, 5.0], [1.0, 0.0, -1.0], RayKind::Secondary);
    assert_eq!(
        plane.intersect(&r, I16F16::DEFAULT_EPSILON),
        Err(Miss::OutOfRange)
    );
    // Grazing: |N·d| just above the default epsilon of I16F16 (16 DELTA ≈ 2.4e-4) puts t
    // at ≈ 12 / 3e-4 = 40000 > 32768.
    let plane = Plane::new(v::<I16F16>(0.0, 0.0, 1.0), v(0.0, 0.0, -7.0)).unwrap();
    let a = 3.0e-4;
    let r = ray::<I16F16>(
        [0.0, 0.0, 5.0],
        [(1.0f64 - a * a).sqrt(), 0.0, -a],
        RayKind::Secondary,
    );
    assert_eq!(
        plane.intersect(&r, I16F16::DEFAULT_EPSILON),
        Err(Miss::OutOfRange)
    );
    // The same ray in f64 hits far away.
    let plane = Plane::new(v::<f64>(0.0, 0.0, 1.0), v(0.0, 0.0, -7.0)).unwrap();
    let r = ray::<f64>(
        [0.0, 0.0, 5.0],
        [(1.0f64 - a * a).sqrt(), 0.0, -a],
        RayKind::Secondary,
    );
    assert!((plane.intersect(&r, f64::DEFAULT_EPSILON).unwrap().t - 40000.0).abs() < 1e-6);
}

/// Planes whose offset N·point does not fit are refused when built, not wrapped.
#[test]
fn an_offset_beyond_the_range_is_refused() {
    let n = v::<I16F16>(1.0, 1.0, 0.0);
    let p = v::<I16F16>(30000.0, 30000.0, 0.0);
    // N·p = 60000/√2 ≈ 42426 > 32768.
    assert_eq!(Plane::new(n, p), Err(PlaneError::OffsetOutOfRange));
    assert!(Plane::new(v::<f64>(1.0, 1.0, 0.0), v(30000.0, 30000.0, 0.0)).is_ok());
}

/// The epsilon is a parameter: the same ray hits with a small epsilon and misses with a
/// large one, in every format.
fn epsilon_is_a_parameter<S: Scalar>() {
    let plane = Plane::new(v::<S>(0.0, 0.0, 1.0), v(0.0, 0.0, -7.0)).unwrap();
    let r = ray::<S>([0.0, 0.0, 5.0], [1.0, 0.0, -0.25], RayKind::Primary);
    assert!(plane.intersect(&r, S::from_f64(0.125).unwrap()).is_ok());
    assert_eq!(
        plane.intersect(&r, S::from_f64(0.5).unwrap()),
        Err(Miss::Parallel)
    );
}

#[test]
fn the_epsilon_is_an_explicit_parameter() {
    all_formats!(epsilon_is_a_parameter);
}

/// `crossing_along` from an unnormalised direction: the notes' example with the
/// direction (0, 0, −4) lands exactly on (4, 3, −7); towards a course floor at grazing
/// angles (the eye of texplane3, screen points of its 800×600 corner grid) its point
/// stays within its rounding bound of the exact crossing, and in a coarse format it is
/// far nearer the exact crossing than the unit ray's point (whose direction rounding
/// is amplified by t/|N·d|).
fn crossing_along<S: Scalar>() {
    let plane = Plane::new(v::<S>(0.0, 0.0, 1.0), v(0.0, 0.0, -7.0)).unwrap();
    let p = plane
        .crossing_along(v(4.0, 3.0, 5.0), v(0.0, 0.0, -4.0))
        .unwrap();
    if divides_exactly::<S>() {
        assert_eq!(p.to_f64(), [4.0, 3.0, -7.0], "{}", S::NAME);
    }
    assert!(
        plane
            .crossing_along(v(4.0, 3.0, 5.0), v(1.0, 0.0, 0.0))
            .is_none(),
        "{}: parallel",
        S::NAME
    );

    let floor = Plane::new(v::<S>(0.0, 1.0, 0.0), v(0.0, 0.0, 0.0)).unwrap();
    let eye = [6.0, 3.0, 10.0];
    let delta = S::DELTA.to_f64();
    let (mut along, mut unit, mut n) = (0.0, 0.0, 0.0);
    for row in (400..600).step_by(7) {
        for column in (0..800).step_by(13) {
            let screen = [
                12.0 * f64::from(column) / 799.0,
                9.0 * f64::from(599 - row) / 599.0,
            ];
            let d: Vec3<S> = v(screen[0], screen[1], 0.0)
                .diff(v(eye[0], eye[1], eye[2]))
                .unwrap();
            let df = d.to_f64();
            // The exact crossing of the rounded direction (the screen point's rounding is
            // the input, not the test's error).
            let s = -eye[1] / df[1];
            let exact = [eye[0] + s * df[0], 0.0, eye[2] + s * df[2]];
            let err = |q: [f64; 3]| (q[0] - exact[0]).abs().max((q[2] - exact[2]).abs());
            let q = floor
                .crossing_along(v(eye[0], eye[1], eye[2]), d)
                .unwrap()
                .to_f64();
            let norm = df.iter().fold(0.0_f64, |m, c| m.max(c.abs()));
            let bound = (s * norm / (2.0 * df[1].abs()) + norm + 2.0) * delta;
            assert!(
                err(q) <= bound,
                "{} row {row} column {column}: off by {:e}, bound {:e}",
                S::NAME,
                err(q),
                bound
            );
            let r = Ray {
                base: v(eye[0], eye[1], eye[2]),
                dir: d.unit().unwrap(),
                kind: RayKind::Secondary,
            };
            // (A ray within the epsilon of parallel misses the unit test.)
            if let Ok(h) = floor.intersect(&r, S::DEFAULT_EPSILON) {
                along += err(q);
                unit += err(h.point.to_f64());
                n += 1.0;
            }
        }
    }
    if delta >= 1e-6 {
        assert!(
            along * 4.0 < unit,
            "{}: mean error {:e} along the screen direction, {:e} along the unit one",
            S::NAME,
            along / n,
            unit / n
        );
    }
}

#[test]
fn crossing_along_an_unnormalised_direction_keeps_its_precision() {
    all_formats!(crossing_along);
}
