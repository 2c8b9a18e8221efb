//! Triangles (`triangle`, `tri`): the hard cases of the intersection in every format
//! (degenerate vertices, a ray in the triangle's plane, hits on an edge and on a vertex,
//! no crack along a shared edge), the parser's forms and errors, and the pictures
//! against f64 under both rule sets. Every format is every one of the one list
//! (`fixray::num::formats::FORMATS`).

mod common;

use common::probes::{divides_exactly, sqrt_error};
use common::v;

use fixray::geometry::{Miss, Ray, RayKind, Triangle, TriangleError, Vec3};
use fixray::num::formats::{FORMATS, REFERENCE};
use fixray::scene::Rules;
use fixray::{I16F16, Scalar, Scene};

fn down<S: Scalar>(x: f64, y: f64) -> Ray<S> {
    Ray {
        base: v(x, y, 5.0),
        dir: v(0.0, 0.0, -1.0),
        kind: RayKind::Primary,
    }
}

fn hard_cases<S: Scalar>() {
    let eps = S::DEFAULT_EPSILON;
    let tri =
        Triangle::new([v::<S>(0.0, 0.0, -5.0), v(4.0, 0.0, -5.0), v(0.0, 4.0, -5.0)]).unwrap();
    // Inside: t = 10 (the plane test of the notes), from one division: exactly where the
    // format divides exactly, else within its division's error, 1 DELTA at t = 10.
    let hit = tri.intersect(&down(1.0, 1.0), eps).unwrap();
    let tolerance = if divides_exactly::<S>() {
        0.0
    } else {
        S::DELTA.to_f64()
    };
    assert!(
        (hit.t.to_f64() - 10.0).abs() <= tolerance,
        "{}: {:?}",
        S::NAME,
        hit.t
    );
    // On each edge (midpoints) and on each vertex: hits, edges included.
    for (x, y) in [
        (2.0, 0.0),
        (0.0, 2.0),
        (2.0, 2.0),
        (0.0, 0.0),
        (4.0, 0.0),
        (0.0, 4.0),
    ] {
        assert!(
            tri.intersect(&down(x, y), eps).is_ok(),
            "{} ({x}, {y})",
            S::NAME
        );
    }
    // Clearly outside each edge: misses, as outside the bounds.
    for (x, y) in [(2.0, -0.01), (-0.01, 2.0), (2.01, 2.01), (5.0, 5.0)] {
        assert_eq!(
            tri.intersect(&down(x, y), eps),
            Err(Miss::OutsideBounds),
            "{} ({x}, {y})",
            S::NAME
        );
    }
    // A ray in the triangle's own plane (edge-on): parallel within the epsilon, a miss.
    let edge_on = Ray {
        base: v::<S>(-1.0, 1.0, -5.0),
        dir: v(1.0, 0.0, 0.0),
        kind: RayKind::Secondary,
    };
    assert_eq!(
        tri.intersect(&edge_on, eps),
        Err(Miss::Parallel),
        "{}",
        S::NAME
    );
    // Degenerate: coincident and collinear vertices have no plane.
    let same = v::<S>(1.0, 1.0, -5.0);
    assert_eq!(
        Triangle::new([same, same, v(2.0, 0.0, -5.0)]),
        Err(TriangleError::Degenerate)
    );
    assert_eq!(
        Triangle::new([v::<S>(0.0, 0.0, -5.0), v(1.0, 1.0, -5.0), v(3.0, 3.0, -5.0)]),
        Err(TriangleError::Degenerate)
    );
}

#[test]
fn hard_cases_in_every_format() {
    fixray::for_each_format!(all: hard_cases());
}

/// A square split along its diagonal into two triangles: every ray through the square,
/// the diagonal included, hits at least one of them (no crack; the edge slack,
/// `fixray::geometry::EDGE_SLACK_ULPS`, is what closes it), and some rays on the
/// diagonal hit both halves (the test reaches the edge).
fn shared_edge<S: Scalar>() {
    let eps = S::DEFAULT_EPSILON;
    let (a, b, c, d) = (
        v::<S>(0.5, 0.5, -8.0),
        v(3.5, 0.5, -8.0),
        v(3.5, 3.5, -8.0),
        v(0.5, 3.5, -8.0),
    );
    let halves = [
        Triangle::new([a, b, c]).unwrap(),
        Triangle::new([a, c, d]).unwrap(),
    ];
    let eye = v::<S>(2.0, 2.0, 6.0);
    let (mut rays, mut both) = (0, 0);
    // Rays aimed along the diagonal and off it, at irregular steps.
    for i in 0..=600 {
        let s = 0.55 + 2.9 * f64::from(i) / 600.0;
        for off in [0.0, 1e-4, -1e-4, 0.003, -0.003] {
            let target = v::<S>(s + off, s, -8.0);
            let dir = target.diff(eye).and_then(Vec3::unit).unwrap();
            let ray = Ray {
                base: eye,
                dir,
                kind: RayKind::Primary,
            };
            let hits = halves
                .iter()
                .filter(|t| t.intersect(&ray, eps).is_ok())
                .count();
            assert!(hits >= 1, "{}: crack at ({}, {s})", S::NAME, s + off);
            rays += 1;
            both += usize::from(hits == 2);
        }
    }
    println!(
        "{}: {rays} rays, {both} on the shared edge hit both halves",
        S::NAME
    );
    assert!(
        both > 0,
        "{}: rays on the diagonal hit both halves",
        S::NAME
    );
}

#[test]
fn a_shared_edge_has_no_crack() {
    fixray::for_each_format!(all: shared_edge());
}

#[test]
fn both_course_forms_are_read_and_checked() {
    let head = "camera c { pixeldim 8 6 worlddim 8 6 viewpoint 4 3 5 }\n\
                material m { ambient 1 1 1 }\n";
    for rules in Rules::ALL {
        // `triangle` reads normal and point (the course draws the vertices' own plane).
        let text = format!(
            "{head}triangle t {{ material m normal 0 0 1 point 9 9 9 \
             vertex1 0 0 -2 vertex2 4 0 -2 vertex3 0 4 -2 }}\n\
             tri u {{ material m v0 0 0 -3 v1 2 0 -3 v2 0 2 -3 }}"
        );
        let scene = Scene::<I16F16>::parse_as(&text, rules).unwrap();
        assert_eq!(scene.objects.len(), 2);
        let (p, q) = (
            scene.objects[0].shape.plane().unwrap(),
            scene.objects[1].shape.plane().unwrap(),
        );
        // Both normals by the vertices' order: +z here.
        assert_eq!(p.normal(), v(0.0, 0.0, 1.0));
        assert_eq!(q.normal(), v(0.0, 0.0, 1.0));
        assert_eq!(p.offset().to_f64(), -2.0);
        // Collinear vertices: an error at the block.
        let bad = format!("{head}tri u {{ material m v0 0 0 -3 v1 1 1 -3 v2 2 2 -3 }}");
        let e = Scene::<I16F16>::parse_as(&bad, rules).unwrap_err();
        assert_eq!((e.line, e.column), (3, 1), "{e}");
        assert!(e.to_string().contains("span a triangle"), "{e}");
        // A missing vertex.
        let short = format!("{head}tri u {{ material m v0 0 0 -3 v1 1 1 -3 }}");
        let e = Scene::<I16F16>::parse_as(&short, rules).unwrap_err();
        assert_eq!(e.to_string(), "3:1: tri is missing its `v2`");
    }
}

/// The budget of format `S` for a scene whose budget at I16F16's resolution is `base`:
/// the pixels that differ lie in bands (edges, the horizon, shading levels near x.5) as
/// wide as the format's error, so the budget grows with `DELTA` above I16F16's:
/// `base · max(1, DELTA / 2⁻¹⁶)` (I20F12: 16 ×). `None` for a format whose square root
/// is approximate ([`sqrt_error`] above one DELTA: `f32m`): its unit directions are as
/// far off as its root (11 % of the lit `course` scene measured), so that share is
/// measured, not bounded.
fn budget<S: Scalar>(base: f64) -> Option<f64> {
    (sqrt_error::<S>() <= S::DELTA.to_f64())
        .then(|| base * (S::DELTA.to_f64() / (-16f64).exp2()).max(1.0))
}

/// The share of pixels of `text` that differ from its f64 picture in format `S`.
fn differ_from_f64<S: Scalar>(text: &str) -> f64 {
    let scene = Scene::<S>::parse(text).unwrap();
    let truth = Scene::<f64>::parse(text).unwrap();
    let (w, h) = (scene.camera.width, scene.camera.height);
    let mut differ = 0u32;
    for y in 0..h {
        for x in 0..w {
            differ +=
                u32::from(fixray::shade::pixel(&scene, x, y) != fixray::shade::pixel(&truth, x, y));
        }
    }
    f64::from(differ) / f64::from(u32::from(w) * u32::from(h))
}

#[test]
fn triangle_scenes_draw_the_f64_picture() {
    let ours = include_str!("../scenes/triangles.scene");
    // A course scene with triangles, small enough for a debug build.
    let course = "camera c { pixeldim 96 72 worlddim 8 6 viewpoint 4 3 4 }\n\
                  material floor { diffuse 0.6 0.6 0.6 }\n\
                  material red { diffuse 4.0 1.5 1.5 }\n\
                  light l { location 4 6 -1 emissivity 5 5 5 }\n\
                  plane p { material floor normal 0 1 0 point 0 0 0 }\n\
                  tri t { material red v0 1 1 -0.1 v1 3 1 -0.1 v2 2 3 -0.1 }\n\
                  triangle u { material red normal 0 0 1 point 0 0 0 \
                  vertex1 5 0.5 -3 vertex2 7 0.5 -3 vertex3 6 2.5 -3 }";
    // Budgets at I16F16's resolution, scaled per format by [`budget`].
    for (name, text, base) in [("triangles", ours, 0.01), ("course", course, 0.01)] {
        for format in FORMATS {
            if format == REFERENCE {
                continue;
            }
            let share = fixray::with_format!(format, differ_from_f64(text)).unwrap();
            println!(
                "{name} {format}: {:.3} % of pixels differ from f64",
                100.0 * share
            );
            if let Some(budget) = fixray::with_format!(format, budget(base)).unwrap() {
                assert!(share <= budget, "{name} {format}: {share}");
            }
        }
    }
}
