//! The effects of the scene format: ASCII-pattern tests of each primitive on tiny scenes,
//! exact shading values, the counters that show absent stages cost nothing, shadow acne,
//! and precision against f64 per effect scene with stated budgets.

mod common;

use common::probes::sqrt_is_rounded;
use common::{assert_pattern_everywhere, top_left_pixel};
use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use fixray::compare::compare;
use fixray::num::formats::{FORMATS, REFERENCE};
use fixray::scene::Rules;
use fixray::stats::Counters;
use fixray::{Frame, I16F16, Scalar, Scene};

#[test]
fn a_sphere_is_a_disc() {
    // Eye 10 units from the centre: the ray of a pixel offset r (screen units, at 5 from
    // the eye) passes the centre at 10·sin(atan(r/5)); it hits when that is ≤ 3, r ≤ 1.57.
    // Offsets 0, 1 and √2 hit; 2 and √5 miss.
    let text = "camera c { pixeldim 5 5 worlddim 5 5 viewpoint 2.5 2.5 5 }
        material red { ambient 1 0 0 }
        sphere s { material red center 2.5 2.5 -5 radius 3 }";
    assert_pattern_everywhere(text, &["KKKKK", "KRRRK", "KRRRK", "KRRRK", "KKKKK"]);
}

/// A wall at z = −5 seen from (2, 2, 5): pixel centres land on wall coordinates
/// x, y ∈ {−1, 1, 3, 5} (tile centres, far from every edge).
const WALL_CAM: &str = "camera c { pixeldim 4 4 worlddim 4 4 viewpoint 2 2 5 }
    material green { ambient 0 1 0 } material red { ambient 1 0 0 }\n";

#[test]
fn a_tiled_plane_is_a_checkerboard() {
    // 2×2 tiles from the corner (0, 0): floor(a/2) + floor(b/2) odd shows the alternate.
    let text = format!(
        "{WALL_CAM}tiled_plane t {{ material green altmaterial red normal 0 0 1 \
         point 0 0 -5 xdir 1 0 0 dimension 2 2 }}"
    );
    assert_pattern_everywhere(&text, &["RGRG", "GRGR", "RGRG", "GRGR"]);
}

#[test]
fn a_finite_plane_is_a_rectangle() {
    // 0 ≤ a ≤ 4, 0 ≤ b ≤ 4: the middle 2×2 pixels (a, b ∈ {1, 3}).
    let text = format!(
        "{WALL_CAM}fplane f {{ material green normal 0 0 1 point 0 0 -5 xdir 1 0 0 dimensions 4 4 }}"
    );
    assert_pattern_everywhere(&text, &["KKKK", "KGGK", "KGGK", "KKKK"]);
}

#[test]
fn a_spotlight_lights_its_cone_only() {
    // From (2, 2, 0) aimed at the wall's centre (2, 2, −5), θ = 20°: radius 5·tan 20° = 1.82
    // on the wall. Offsets (±1, ±1) (1.41) are inside, (±3, ±1) (3.16) outside.
    let text = "camera c { pixeldim 4 4 worlddim 4 4 viewpoint 2 2 5 }
        material white { diffuse 1 1 1 }
        spotlight s { location 2 2 0 emissivity 100 100 100 point 2 2 -5 theta 20 }
        plane wall { material white normal 0 0 1 point 0 0 -5 }";
    assert_pattern_everywhere(text, &["KKKK", "KWWK", "KWWK", "KKKK"]);
}

#[test]
fn a_mirror_shows_what_lies_behind_the_eye() {
    // A perfect mirror facing the eye reflects every ray back towards +z, where a red
    // plane stands behind the eye (primary rays never see it: t < 0).
    let text = "camera c { pixeldim 4 4 worlddim 4 4 viewpoint 2 2 5 }
        material mirror { reflective 1 }
        material red { ambient 1 0 0 }
        plane wall { material mirror normal 0 0 1 point 0 0 -5 }
        plane behind { material red normal 0 0 1 point 0 0 10 }";
    assert_pattern_everywhere(text, &["RRRR", "RRRR", "RRRR", "RRRR"]);
}

#[test]
fn facing_mirrors_stop_at_the_depth_bound() {
    // Two parallel mirrors: every bounce sees the other one. The bound ends the recursion
    // after MAX_REFLECTION_DEPTH reflected rays per pixel. Both mirrors are the same half
    // mirror of ambient 0.5 (127.5 levels), so every mix (1 − K)·127.5 + K·127.5 is 127.5
    // again: the picture is 128 at any depth, in every format.
    let text = "camera c { pixeldim 2 2 worlddim 2 2 viewpoint 1 1 5 }
        material m { ambient 0.5 0.5 0.5 reflective 0.5 }
        plane a { material m normal 0 0 1 point 0 0 -5 }
        plane b { material m normal 0 0 1 point 0 0 10 }";
    assert_pattern_everywhere_grey(text, 128);
    let c = counters::<I16F16>(text);
    let depth = u32::from(fixray::shade::MAX_REFLECTION_DEPTH);
    assert_eq!(c.reflection_rays, 4 * depth, "{c:?}");
}

fn assert_pattern_everywhere_grey(text: &str, level: u8) {
    for (format, c) in top_left_pixel(text) {
        assert_eq!(c, Rgb888::new(level, level, level), "{format}");
    }
}

#[test]
fn specular_follows_the_half_vector_formula() {
    // Light 4 units in front of the hit point on its normal, eye straight above: L = V =
    // N, so H = N and N·H = 1: 255 × 0.5 × 2 × 1^n / 4 = 63.75 → 64 for any shininess.
    let text = "camera c { pixeldim 1 1 worlddim 1 1 viewpoint 0.5 0.5 5 }
        material m { specular 0.5 shininess 7 }
        light l { location 0.5 0.5 -1 emissivity 2 2 2 }
        plane wall { material m normal 0 0 1 point 0 0 -5 }";
    for (format, c) in top_left_pixel(text) {
        assert_eq!(c, Rgb888::new(64, 64, 64), "{format}");
    }
    // Off-axis, computed here independently: hit (0.5, 0.5, −5), light (2.5, 0.5, −3).
    let text = text.replace("location 0.5 0.5 -1", "location 2.5 0.5 -3");
    let l = [2.0f64, 0.0, 2.0];
    let dist = (8.0f64).sqrt();
    let (lx, lz) = (l[0] / dist, l[2] / dist);
    let h = [lx, 0.0, lz + 1.0];
    let hn = (h[0] * h[0] + h[2] * h[2]).sqrt();
    let nh = h[2] / hn;
    let expected = 255.0 * 0.5 * 2.0 * nh.powf(7.0) / dist;
    for (format, c) in top_left_pixel(&text) {
        assert!(
            (f64::from(c.r()) - expected).abs() <= 1.0,
            "{format}: {c:?} vs {expected}"
        );
    }
}

/// The counters of a whole frame.
fn counters<S: Scalar>(text: &str) -> Counters {
    let scene = Scene::<S>::parse_as(text, Rules::Fixray).unwrap();
    let mut line = vec![Rgb888::BLACK; usize::from(scene.camera.width)];
    let mut c = Counters::default();
    let frame = Frame::new(&scene);
    for row in 0..scene.camera.height {
        frame.render_line_counted(row, &mut line, &mut c);
    }
    c
}

#[test]
fn absent_stages_do_no_work() {
    let planes = counters::<I16F16>(include_str!("../scenes/planes.scene"));
    assert_eq!(planes.primary_rays, 160 * 120);
    assert_eq!(
        (
            planes.shadow_rays,
            planes.reflection_rays,
            planes.diffuse,
            planes.specular,
            planes.cone_tests,
            planes.tile_lookups
        ),
        (0, 0, 0, 0, 0, 0),
        "an ambient-only scene: {planes:?}"
    );
    let lit = counters::<I16F16>(include_str!("../scenes/default.scene"));
    assert!(lit.shadow_rays > 0 && lit.diffuse > 0, "{lit:?}");
    assert_eq!(
        (
            lit.specular,
            lit.reflection_rays,
            lit.cone_tests,
            lit.tile_lookups
        ),
        (0, 0, 0, 0),
        "{lit:?}"
    );
    let spec = counters::<I16F16>(include_str!("../scenes/specular.scene"));
    assert!(spec.specular > 0, "{spec:?}");
    assert_eq!(
        (spec.reflection_rays, spec.cone_tests, spec.tile_lookups),
        (0, 0, 0),
        "{spec:?}"
    );
    let spot = counters::<I16F16>(include_str!("../scenes/spotlight.scene"));
    assert!(spot.cone_tests > 0, "{spot:?}");
    let mirror = counters::<I16F16>(include_str!("../scenes/mirror.scene"));
    assert!(
        mirror.reflection_rays > 0 && mirror.tile_lookups > 0,
        "{mirror:?}"
    );
    let tiles = counters::<I16F16>(include_str!("../scenes/tiles.scene"));
    assert!(tiles.tile_lookups > 0, "{tiles:?}");
    assert_eq!((tiles.shadow_rays, tiles.diffuse), (0, 0), "{tiles:?}");
}

/// No acne: every pixel that sees a lit floor is lit. A sphere far off to the side makes
/// the scene need shadow rays (so every floor pixel casts one) without shadowing the view.
fn no_acne<S: Scalar>() {
    let text = "camera c { pixeldim 40 30 worlddim 8 6 viewpoint 4 3 5 }
        material floor_m { ambient 0.1 0.1 0.1 diffuse 0.8 0.8 0.8 }
        material s_m { ambient 0.1 0 0 }
        light l { location 4 20 -10 emissivity 30 30 30 }
        plane floor { material floor_m normal 0 1 0 point 0 0 0 }
        sphere far { material s_m center 500 1 -100 radius 1 }";
    let scene = Scene::<S>::parse_as(text, Rules::Fixray).unwrap();
    assert!(scene.plan().shadows);
    let unlit = fixray::shade::to_rgb888(scene.materials[0].ambient);
    let mut acne = 0;
    for row in 0..scene.camera.height {
        for column in 0..scene.camera.width {
            let t = fixray::shade::trace_pixel(&scene, column, row);
            if t.hit.is_some_and(|(i, _)| i == 0) && fixray::shade::to_rgb888(t.color) == unlit {
                acne += 1;
            }
        }
    }
    assert_eq!(
        acne,
        0,
        "{}: {acne} floor pixels shadow themselves",
        S::NAME
    );
}

#[test]
fn a_lit_plane_never_shadows_itself() {
    fixray::for_each_format!(all: no_acne());
}

/// The share of pixels of `text` in format `S` with any channel different from
/// `reference`'s.
fn share_against<S: Scalar>(text: &str, reference: &Scene<f64>) -> f64 {
    let scene = Scene::<S>::parse_as(text, Rules::Fixray).unwrap();
    compare(&scene, reference, |_, _, _, _| {}).differing_share()
}

/// The budget of format `S` for a scene with budgets `coarse` and `fine`: smooth lighting
/// differs by one level where the exact value lies within the shading error (a few
/// `DELTA`s) of x.5, so a format whose `DELTA` is I16F16's 2⁻¹⁶ or coarser (0.004 levels
/// or more per `DELTA`) has the `coarse` budget; a finer one (f32's 2⁻²³, I32F32's 2⁻³²)
/// differs at edges and horizons only and has the `fine` budget. `None` for a format
/// with an approximate square root: measured (printed), not bounded.
fn budget<S: Scalar>(coarse: f64, fine: f64) -> Option<f64> {
    if !sqrt_is_rounded::<S>() {
        None
    } else if S::DELTA.to_f64() >= (-16f64).exp2() {
        Some(coarse)
    } else {
        Some(fine)
    }
}

/// Budgets (share of pixels with any channel different from f64) per effect scene, for
/// every format of the one list (`fixray::num::formats::FORMATS`) by [`budget`],
/// measured by `cargo run --release --example render -- scenes/X.scene`: smooth lighting
/// differs by one level where the exact value lies near x.5; the horizon of a floor and
/// object edges where the formats resolve a grazing ray or a silhouette differently.
#[test]
fn effects_stay_within_their_budgets_against_f64() {
    type Budget = (&'static str, &'static str, f64, f64);
    let scenes: [Budget; 5] = [
        (
            "spheres",
            include_str!("../scenes/spheres.scene"),
            0.03,
            0.005,
        ),
        ("tiles", include_str!("../scenes/tiles.scene"), 0.02, 0.005),
        (
            "specular",
            include_str!("../scenes/specular.scene"),
            0.03,
            0.005,
        ),
        (
            "spotlight",
            include_str!("../scenes/spotlight.scene"),
            0.03,
            0.005,
        ),
        ("mirror", include_str!("../scenes/mirror.scene"), 0.05, 0.03),
    ];
    let mut bounded = 0;
    for (name, text, coarse, fine) in scenes {
        let reference = Scene::<f64>::parse_as(text, Rules::Fixray).unwrap();
        let mut row = format!("{name:<10}");
        for format in FORMATS {
            if format == REFERENCE {
                continue;
            }
            let share = fixray::with_format!(format, share_against(text, &reference)).unwrap();
            row += &format!(" {format} {:.3} %", 100.0 * share);
            if let Some(budget) = fixray::with_format!(format, budget(coarse, fine)).unwrap() {
                assert!(share <= budget, "{name} {format}: {share}");
                bounded += 1;
            }
        }
        println!("{row}");
    }
    // Not vacuous: the main formats other than the reference are all bounded.
    assert!(
        bounded >= scenes.len() * (fixray::num::formats::MAIN.len() - 1),
        "{bounded}"
    );
}

/// The course's shadow ray of a sphere's hit goes on past a translucent occluder and
/// leaves the sphere's record of its hit at the line's crossing behind it
/// (`COURSE-RULES.md` §11, fitted on texplane3): the transmitted ray then starts there.
/// A translucent sphere `A` lit from straight above, through an opaque occluder `O` and
/// a translucent one `B` stacked out of view; behind `A` an unlit checkerboard wall. With
/// `O` nearest, the shadow ray stops at it and `A`'s transmitted rays start at their
/// hits: the picture is the one without `B`. With `B` nearest, they start behind `A`'s
/// lit side, and what `A` shows of the wall moves.
fn moved_transmission<S: Scalar>() {
    let scene = |stack: &str| {
        format!(
            "camera c {{ pixeldim 64 48 worlddim 8 6 viewpoint 4 3 10 }}
             material glass {{ ambient 0.5 0.5 0.5 diffuse 4 4 4 transparency 0.6 }}
             material dark {{ ambient 1 1 1 }}
             material pale {{ ambient 6 6 6 }}
             material black {{ diffuse 1 1 1 }}
             light top {{ location 4 20 -3 emissivity 9 9 9 }}
             sphere a {{ material glass center 4 3 -3 radius 1.5 }}
             tiled_plane wall {{ material dark normal 0 0 1 point 0 0 -8 dimensions 0.25 0.25
                 altmaterial pale xdir 1 0 0 }}
             {stack}"
        )
    };
    let opaque = |y: f64| format!("sphere o {{ material black center 4 {y} -3 radius 1 }}\n");
    let translucent = |y: f64| format!("sphere b {{ material glass center 4 {y} -3 radius 1 }}\n");
    let picture = |text: String| {
        let scene = Scene::<S>::parse(&text).unwrap();
        let mut pixels = vec![Rgb888::BLACK; 64 * 48];
        for (row, line) in (0..48).zip(pixels.chunks_mut(64)) {
            fixray::render_line(&scene, row, line);
        }
        pixels
    };
    let without_b = picture(scene(&opaque(10.0)));
    let o_nearest = picture(scene(&(opaque(10.0) + &translucent(14.0))));
    let b_nearest = picture(scene(&(translucent(10.0) + &opaque(14.0))));
    let differ = |a: &[Rgb888], b: &[Rgb888]| a.iter().zip(b).filter(|(p, q)| p != q).count();
    assert_eq!(
        differ(&o_nearest, &without_b),
        0,
        "{}: pixels that moved behind an opaque occluder",
        S::NAME
    );
    let moved = differ(&b_nearest, &without_b);
    assert!(
        moved >= 20,
        "{}: {moved} pixels show the moved transmission",
        S::NAME
    );
}

#[test]
fn a_course_shadow_ray_past_a_translucent_occluder_moves_the_transmission() {
    fixray::for_each_format!(moved_transmission());
}
