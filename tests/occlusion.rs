//! The division-free shadow test (`Plane::occludes`) against the full plane test
//! (`Plane::intersect` then `t < dist`), on seeded random rays, planes and distances in
//! every format. They must agree except where the rounded `t` and the exact quotient
//! fall on different sides of `dist` (within the division's rounding) or where
//! `intersect` finds `t` or the hit point out of range.

mod common;
use common::sampling;

use fixray::geometry::{Miss, Plane, Ray, RayKind, Shape, Vec3};
use fixray::num::formats::FORMATS;
use fixray::{I16F16, Scalar};
use sampling::SplitMix;

const CASES: u32 = 200_000;

/// Agreements, hits among them, and disagreements outside the rounding band.
fn check<S: Scalar>(seed: u64) -> (u32, u32) {
    let mut rng = SplitMix(seed);
    let vec = |a: [f64; 3]| Vec3::<S>::from_f64(a);
    let (mut occluded, mut exercised) = (0, 0);
    for case in 0..CASES {
        let scale = [1.0, 10.0, 100.0][rng.below(3)];
        let p = [0; 3].map(|_| rng.uniform(-scale, scale));
        let b = [0; 3].map(|_| rng.uniform(-scale, scale));
        let (Some(n), Some(p), Some(b)) = (vec(rng.unit()), vec(p), vec(b)) else {
            continue;
        };
        let Some(d) = vec(rng.unit()).and_then(Vec3::unit) else {
            continue;
        };
        let Ok(plane) = Plane::new(n, p) else {
            continue;
        };
        let Some(dist) = S::from_f64(rng.uniform(0.0, 3.0 * scale)) else {
            continue;
        };
        let ray = Ray {
            base: b,
            dir: d,
            kind: RayKind::Secondary,
        };
        exercised += 1;
        let fast = plane.occludes(&ray, S::DEFAULT_EPSILON, dist);
        assert_eq!(
            fast,
            Shape::Plane(plane).occludes(&ray, S::DEFAULT_EPSILON, dist),
            "{} case {case}: the shape dispatches to the plane",
            S::NAME
        );
        occluded += u32::from(fast);
        let full = plane.intersect(&ray, S::DEFAULT_EPSILON);
        let reference = full.is_ok_and(|h| h.t < dist);
        if fast == reference {
            continue;
        }
        match full {
            // A t beyond the format's range exceeds every dist; the exact comparison
            // may still see t < dist only if the rounded point overflowed on the way.
            Err(Miss::OutOfRange) => continue,
            Ok(hit) => {
                // The rounded t and the exact quotient straddle dist: within one
                // rounding of the division (fixed: 1 DELTA; floats: 1 ulp of t).
                let gap = (hit.t.to_f64() - dist.to_f64()).abs();
                assert!(
                    gap <= 2.0 * hit.t.ulp().to_f64(),
                    "{} case {case}: occludes {fast}, intersect t = {:?}, dist = {:?}",
                    S::NAME,
                    hit.t,
                    dist
                );
            }
            Err(miss) => panic!(
                "{} case {case}: occludes {fast} but intersect missed ({miss:?})",
                S::NAME
            ),
        }
    }
    (exercised, occluded)
}

fn check_format<S: Scalar>() {
    let (exercised, occluded) = check::<S>(0x5AAD_2026);
    println!("{}: {exercised} cases, {occluded} occluded", S::NAME);
    // Not vacuous: most cases formed, and both answers common.
    assert!(exercised > CASES / 2, "{}", S::NAME);
    assert!(occluded > exercised / 10, "{}", S::NAME);
    assert!(occluded < exercised - exercised / 10, "{}", S::NAME);
}

/// Every format of the one list (`fixray::num::formats::FORMATS`), each on its own
/// thread (as many cases as one test per format, run side by side).
#[test]
fn every_format_agrees_with_the_full_test() {
    std::thread::scope(|threads| {
        for name in FORMATS {
            threads.spawn(move || fixray::with_format!(name, check_format()).unwrap());
        }
    });
}

#[test]
fn a_parallel_ray_is_never_occluded_and_the_light_side_decides() {
    // Plane z = 0, ray from (0, 0, 1) going down: the plane is at t = 1.
    let v = |x: f64, y: f64, z: f64| Vec3::<I16F16>::from_f64([x, y, z]).unwrap();
    let plane = Plane::new(v(0.0, 0.0, 1.0), v(0.0, 0.0, 0.0)).unwrap();
    let eps = I16F16::DEFAULT_EPSILON;
    let down = Ray {
        base: v(0.0, 0.0, 1.0),
        dir: v(0.0, 0.0, -1.0),
        kind: RayKind::Secondary,
    };
    let d = |x: f64| I16F16::from_f64(x).unwrap();
    assert!(plane.occludes(&down, eps, d(2.0)), "light beyond the plane");
    assert!(
        !plane.occludes(&down, eps, d(0.5)),
        "light before the plane"
    );
    assert!(!plane.occludes(&down, eps, d(1.0)), "t < dist is strict");
    let up = Ray {
        dir: v(0.0, 0.0, 1.0),
        ..down
    };
    assert!(!plane.occludes(&up, eps, d(100.0)), "plane behind the base");
    let along = Ray {
        dir: v(1.0, 0.0, 0.0),
        ..down
    };
    assert!(!plane.occludes(&along, eps, d(100.0)), "parallel");
}
