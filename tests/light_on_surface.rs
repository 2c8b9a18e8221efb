//! The hard case "lights on surfaces" (`docs/numerics.md`): a light lying on a plane (or
//! within the tolerance of one) makes the shadow test `t < dist` a tie that rounding
//! decides pixel by pixel, salt-and-pepper shadows even in f64 (the course tracer
//! speckles there too). Here a plane through the light never shadows it, a sphere
//! through it only when the shadow ray leaves the sphere at the light, under both rule
//! sets and in every format: each format draws the picture of the same scene without
//! the tied surface as an occluder, and the same picture as f64.

mod common;

use fixray::{Scalar, Scene};

/// A back wall lit by a lamp that lies exactly on the floor (and one on the left wall),
/// seen from above the floor; `floor` is the floor's block (or nothing). No two planes
/// meet on a pixel's ray (a tie of two planes, another hard case, would blur this one).
fn scene(rules: &str, floor: &str, lamp_y: &str) -> String {
    format!(
        "rules {rules}\n\
         camera c {{ pixeldim 64 48 worlddim 8 6 viewpoint 4 3 6 }}\n\
         material wall_m {{ ambient 0.05 0.05 0.05 diffuse 0.8 0.7 0.6 }}\n\
         material floor_m {{ ambient 0.1 0.1 0.1 diffuse 0.5 0.5 0.5 }}\n\
         light lamp {{ location 4 {lamp_y} -5 emissivity 6 6 6 }}\n\
         light side {{ location -0.6 2 -6 emissivity 3 3 3 }}\n\
         plane back {{ material wall_m normal 0 0 1 point 0 0 -10 }}\n\
         plane left {{ material wall_m normal 1 0 0 point -0.6 0 0 }}\n\
         {floor}"
    )
}

const FLOOR: &str = "plane floor { material floor_m normal 0 1 0 point 0 0 0 }";

fn pixels<S: Scalar>(text: &str) -> Vec<embedded_graphics::pixelcolor::Rgb888> {
    let scene = Scene::<S>::parse(text).unwrap();
    let (w, h) = (scene.camera.width, scene.camera.height);
    (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| fixray::shade::pixel(&scene, x, y))
        .collect()
}

/// Pixels that see the back wall above the floor: lit there exactly as without the
/// floor (the floor's own pixels differ, of course).
fn the_wall_is_lit_as_without_the_floor<S: Scalar>() {
    lit_as_without_the_floor::<S>("0");
}

fn lit_as_without_the_floor<S: Scalar>(lamp_y: &str) {
    for rules in ["course", "fixray"] {
        let with = pixels::<S>(&scene(rules, FLOOR, lamp_y));
        let without = pixels::<S>(&scene(rules, "", lamp_y));
        let truth = pixels::<f64>(&scene(rules, FLOOR, lamp_y));
        let (w, h) = (64usize, 48usize);
        let mut wall = 0;
        for y in 0..h {
            for x in 0..w {
                let i = y * w + x;
                // The upper part of the image sees the walls (the floor is below y = 3).
                if y < h / 3 {
                    wall += 1;
                    assert!(with[i] == without[i], "{rules} {} ({x}, {y})", S::NAME);
                }
            }
        }
        assert!(wall > 0);
        let differ = with.iter().zip(&truth).filter(|(a, b)| a != b).count();
        let share = differ as f64 / (w * h) as f64;
        // One level where the exact value lies near a rounding point, nothing more.
        let worst = with
            .iter()
            .zip(&truth)
            .map(|(a, b)| {
                use embedded_graphics::pixelcolor::RgbColor;
                a.r()
                    .abs_diff(b.r())
                    .max(a.g().abs_diff(b.g()))
                    .max(a.b().abs_diff(b.b()))
            })
            .max()
            .unwrap_or(0);
        println!(
            "{rules} {}: {:.2} % of pixels differ from f64, by at most {worst}",
            S::NAME,
            100.0 * share
        );
        assert!(worst <= 2, "{rules} {}: {worst} levels", S::NAME);
    }
}

#[test]
fn a_plane_through_the_light_never_shadows_it_in_any_format() {
    common::every_format!(the_wall_is_lit_as_without_the_floor);
}

/// Within the tolerance (the scene's epsilon × the coordinates' magnitude: about 0.0024
/// world units in I16F16 here), a light just below the floor is taken as on it: the
/// floor does not shadow it (f64's tolerance is far smaller, so f64 is not the judge).
#[test]
fn a_light_within_the_tolerance_counts_as_on_the_plane() {
    for rules in ["course", "fixray"] {
        for y in ["0.001", "-0.001"] {
            let with = pixels::<fixray::I16F16>(&scene(rules, FLOOR, y));
            let without = pixels::<fixray::I16F16>(&scene(rules, "", y));
            let top = 64 * 16;
            assert!(with[..top] == without[..top], "{rules} lamp at y = {y}");
        }
    }
}

/// A light on a sphere's surface: points whose shadow ray enters the sphere at the light
/// are lit, points whose ray passes through the sphere first are in its shadow.
#[test]
fn a_sphere_through_the_light_shadows_only_through_itself() {
    {
        let text = "camera c { pixeldim 8 6 worlddim 8 6 viewpoint 4 3 6 }\n\
                    material m { diffuse 1 1 1 }\n\
                    light lamp { location 0 0 -4 emissivity 1 1 1 }\n\
                    sphere s { material m center 0 0 -5 radius 1 }\n";
        fn check<S: Scalar, R: fixray::shade::RuleSet>(text: &str) {
            let scene = Scene::<S>::parse_as(text, R::RULES).unwrap();
            let v = |x, y, z| common::v::<S>(x, y, z);
            let shape = &scene.objects[0].shape;
            let light = v(0.0, 0.0, -4.0);
            assert!(shape.holds(light, S::DEFAULT_EPSILON));
            let tol = S::from_f64(1e-3).unwrap_or(S::DEFAULT_EPSILON);
            // From in front (z = −2): the ray reaches the light before the sphere.
            let ray = |from: fixray::geometry::Vec3<S>| {
                let to = light.diff(from).unwrap();
                let n = to.normalize().unwrap();
                (
                    fixray::geometry::Ray {
                        base: from,
                        dir: n.unit,
                        kind: fixray::geometry::RayKind::Secondary,
                    },
                    n.length().unwrap(),
                )
            };
            let (r, d) = ray(v(0.0, 0.0, -2.0));
            assert!(!R::shadows(shape, &r, scene.epsilon, d, light, tol));
            // From behind the sphere (z = −8): through the sphere first.
            let (r, d) = ray(v(0.0, 0.0, -8.0));
            assert!(R::shadows(shape, &r, scene.epsilon, d, light, tol));
        }
        fn both<S: Scalar>(text: &str) {
            check::<S, fixray::shade::Course>(text);
            check::<S, fixray::shade::Fixray>(text);
        }
        both::<fixray::I16F16>(text);
        both::<fixray::I32F32>(text);
        both::<f32>(text);
        both::<f64>(text);
    }
}
