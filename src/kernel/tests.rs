//! The kernels' own tests: the flattened plane shading against the general one on
//! seeded random scenes (and the scene generator the fast kernel's tests share).

extern crate std;
use std::format;
use std::string::String;

use super::memo::{PlaneMemo, Weights};
use super::scanline::{fast_color, shaded};
use super::shading::{LightTerms, lit_plane_color, lit_sphere_color, own_sphere_clear, quiet_hit};
use super::*;
use crate::num::Rng;
use crate::shade::stages::DiffuseShadows;
use crate::{Scene, Vec3};

/// A seeded random scene of planes only (plain and tiled, any normal: walls with
/// `N.x ≠ 0` among them), sometimes lit.
pub(super) fn random_scene(rng: &mut Rng) -> String {
    let (w, h) = (16 + rng.below(48), 8 + rng.below(24));
    let mut uniform = |lo: f64, hi: f64| rng.uniform(lo, hi);
    let mut text = format!(
        "rules fixray\ncamera c {{ pixeldim {w} {h} worlddim 8 6 viewpoint {:.3} {:.3} {:.3} }}\n",
        uniform(0.0, 8.0),
        uniform(0.5, 5.5),
        uniform(2.0, 9.0)
    );
    // A coarse epsilon now and then: planes near parallel to the rays over wide bands,
    // where each pixel takes the exact test.
    if uniform(0.0, 1.0) < 0.3 {
        text.push_str(&format!("precision {:.3}\n", uniform(0.005, 0.2)));
    }
    text.push_str("material a { ambient 0.3 0.2 0.1 diffuse 0.5 0.4 0.3 }\n");
    text.push_str("material b { ambient 0.1 0.2 0.3 diffuse 0.2 0.6 0.3 }\n");
    if uniform(0.0, 1.0) < 0.7 {
        text.push_str(&format!(
            "light l {{ location {:.2} {:.2} {:.2} emissivity 5 5 5 }}\n",
            uniform(0.0, 8.0),
            uniform(1.0, 8.0),
            uniform(-8.0, 4.0)
        ));
    }
    let x = uniform(0.0, 4.0);
    let planes = 2 + u32::from(x >= 1.0) + u32::from(x >= 2.0) + u32::from(x >= 3.0);
    for i in 0..planes {
        let n = [uniform(-1.0, 1.0), uniform(-1.0, 1.0), uniform(-1.0, 1.0)];
        let p = [
            uniform(-4.0, 12.0),
            uniform(-3.0, 3.0),
            uniform(-16.0, -1.0),
        ];
        let r = uniform(0.0, 1.0);
        if i > 0 && r < 0.25 {
            // A twin of the first plane, turned by a hair: two planes whose `t'` cross
            // along whole rows, where only the roundings of `N·D` decide.
            let k = uniform(-0.002, 0.002);
            text.push_str(&format!(
                "plane q{i} {{ material b normal {:.4} 1 {:.4} point 1 -1 -4 }}\n",
                0.3 + k,
                0.2 - k
            ));
            text.push_str(&format!(
                "plane r{i} {{ material a normal 0.3 1 0.2 point 1 -1 -4 }}\n"
            ));
        } else if i == 0 && r < 0.5 {
            text.push_str("tiled_plane t { material a altmaterial b normal 0 1 0 point 0 -1 0 xdir 1 0 0 dimension 1 1 }\n");
        } else {
            text.push_str(&format!(
                "plane p{i} {{ material {} normal {:.3} {:.3} {:.3} point {:.2} {:.2} {:.2} }}\n",
                if i % 2 == 0 { "a" } else { "b" },
                n[0],
                n[1],
                n[2],
                p[0],
                p[1],
                p[2]
            ));
        }
    }
    text
}

/// The view of `scene` as a frame sets it up (`render.rs`: a light on a surface is the
/// plan's to find) and the fast kernel's per-frame part (`None` where it cannot be
/// formed).
fn fast_frame<S: Scalar>(scene: &Scene<S>) -> Option<(SceneView<'_, S>, Primary<S>)> {
    let mut view = scene.view();
    view.lights_on_surfaces = view.plan().lights_on_surfaces;
    let p = Primary::new(&view)?;
    Some((view, p))
}

/// Every fast-kernel hit of `scenes` random plane scenes (and the default scene) in
/// format `S`, lit by the stage set `T`: the hits found with a scanline's memo of its
/// still planes (`fast::HitMemo`) are the hits, and [`lit_plane_color`]'s colour is
/// the general shading's ([`fast_color`]) bit for bit wherever it draws one.
/// Returns how many hits it drew.
fn lit_planes_agree<S: Scalar, T: Stages>(scenes: usize) -> (usize, usize) {
    let mut rng = Rng(0x5EED_2026_1206);
    let (mut drawn, mut quiet) = (0, 0);
    let texts = (0..scenes)
        .map(|_| random_scene(&mut rng))
        .chain([String::from(include_str!("../../scenes/default.scene"))]);
    for (case, text) in texts.enumerate() {
        let Ok(scene) = Scene::<S>::parse(&text) else {
            continue;
        };
        let Some((view, p)) = fast_frame(&scene) else {
            continue;
        };
        let mut at_hit = heapless::Vec::new();
        // One memo for the whole frame, as a scanline keeps one for its pixels.
        let mut memo = PlaneMemo::default();
        let mut hits = fast::HitMemo::default();
        for row in 0..view.camera.height {
            fast::each_pixel(&view, &p, row, |r| {
                let column = Primary::column(r);
                // The still planes' hits from the memo are the hits themselves.
                let found = p.nearest(&view, r);
                let memoized = p.nearest_with(&view, r, Some(&mut hits));
                assert_eq!(found, memoized, "{} case {case} ({row}, {column})", S::NAME);
                let Ok(Some(h)) = found else {
                    return;
                };
                let (mut c1, mut c2) = (Counters::default(), Counters::default());
                let at = (&mut at_hit, Some(&mut memo));
                let mut lit_row = r.clone();
                let lit = lit_plane_color::<S, T>(&view, &p, &mut lit_row, &h, at, &mut c1);
                let general =
                    fast_color::<S, T>(&view, Some(&p), r, &h, (&mut at_hit, None), &mut c2);
                if let Some(lit) = lit {
                    drawn += 1;
                    if T::SHADOWS && quiet_hit(&view, &p, r, &h, &mut memo) {
                        quiet += 1;
                    }
                    assert_eq!(
                        lit,
                        general,
                        "{} case {case} ({row}, {column}):\n{text}",
                        S::NAME
                    );
                }
            });
        }
    }
    (drawn, quiet)
}

/// The fast kernel's flattened plane shading (`lit_plane_color`) draws the general
/// shading's colours, with shadows and without, in the formats that take it.
#[test]
fn lit_planes_draw_the_general_shading() {
    use crate::shade::stages::Diffuse;
    // (Tens of thousands of hits each; with shadows, thousands of them where every
    // other plane is quiet.)
    let (drawn, quiet) = lit_planes_agree::<fixed::types::I16F16, DiffuseShadows>(60);
    assert!(drawn > 40_000 && quiet > 5_000, "{drawn} {quiet}");
    assert!(lit_planes_agree::<fixed::types::I16F16, Diffuse>(30).0 > 25_000);
    let (drawn, quiet) = lit_planes_agree::<fixed::types::I20F12, DiffuseShadows>(30);
    assert!(drawn > 25_000 && quiet > 2_000, "{drawn} {quiet}");
    let (drawn, quiet) = lit_planes_agree::<fixed::types::I32F32, DiffuseShadows>(20);
    assert!(drawn > 20_000 && quiet > 2_000, "{drawn} {quiet}");
    assert!(lit_planes_agree::<crate::num::variants::I16F16Recip, DiffuseShadows>(20).0 > 20_000);
    // Not in the float formats (the facing normal would not be the row's `N·D`).
    assert_eq!(lit_planes_agree::<f32, DiffuseShadows>(5).0, 0);
}

/// A seeded random scene of spheres over a tiled floor before a back wall (plain, or
/// turned about y), under one or two lights, some materials without a diffuse colour,
/// now and then a light low beside a sphere (hits on its far side, shadows cast on
/// other spheres).
fn sphere_scene(rng: &mut Rng) -> String {
    let (w, h) = (24 + rng.below(40), 16 + rng.below(24));
    let mut text = format!(
        "rules fixray\ncamera c {{ pixeldim {w} {h} worlddim 8 6 viewpoint {:.2} {:.2} {:.2} }}\n",
        rng.uniform(1.0, 7.0),
        rng.uniform(1.0, 5.0),
        rng.uniform(4.0, 10.0)
    );
    text += "material a { ambient 0.3 0.2 0.1 diffuse 0.5 0.4 0.3 }\n";
    text += "material b { ambient 0.1 0.1 0.3 diffuse 0.9 0.2 0.6 }\n";
    text += "material c { ambient 0.4 0.4 0.4 }\n";
    for j in 0..1 + rng.below(2) {
        let y = if rng.below(3) == 0 {
            0.8
        } else {
            rng.uniform(2.0, 10.0)
        };
        text += &format!(
            "light l{j} {{ location {:.2} {y:.2} {:.2} emissivity {:.1} {:.1} {:.1} }}\n",
            rng.uniform(-3.0, 10.0),
            rng.uniform(-8.0, 5.0),
            rng.uniform(2.0, 12.0),
            rng.uniform(2.0, 12.0),
            rng.uniform(2.0, 12.0)
        );
    }
    text += "tiled_plane floor { material a altmaterial b normal 0 1 0 point 0 0 0 xdir 1 0 0 dimension 1 1 }\n";
    let wall = if rng.below(2) == 0 {
        "0 0 1"
    } else {
        "0.2 0 1"
    };
    text += &format!("plane wall {{ material b normal {wall} point 0 0 -9 }}\n");
    for i in 0..1 + rng.below(3) {
        let r = rng.uniform(0.3, 1.8);
        let m = ["a", "b", "c"][usize::try_from(rng.below(3)).unwrap_or(0)];
        text += &format!(
            "sphere s{i} {{ material {m} center {:.2} {:.2} {:.2} radius {r:.2} }}\n",
            rng.uniform(-1.0, 9.0),
            r + rng.uniform(0.0, 3.0),
            rng.uniform(-7.0, 1.0)
        );
    }
    text
}

/// At every sphere hit of the fast kernel in `scenes` random sphere scenes and the boing
/// ball's frames, in format `S` with the stage set `T`: [`lit_sphere_color`] draws the
/// general shading's colour ([`general_color`]) with the same counts, wherever it draws
/// one. Returns how many it drew.
fn lit_spheres_agree<S: Scalar, T: Stages>(scenes: usize) -> usize {
    let mut rng = Rng(0x5EED_2026_1207);
    let mut drawn = 0;
    let boing = String::from(include_str!("../../scenes/boing.scene"));
    let texts = (0..scenes)
        .map(|_| (sphere_scene(&mut rng), None))
        .chain((0..16).map(|k| (boing.clone(), Some(k))));
    for (case, (text, frame)) in texts.enumerate() {
        let Ok(mut scene) = Scene::<S>::parse(&text) else {
            continue;
        };
        if let Some(k) = frame
            && crate::anim::Bounce::boing(&scene.objects)
                .ok()
                .and_then(|b| b.apply(&mut scene, k).ok())
                .is_none()
        {
            continue;
        }
        let Some((view, p)) = fast_frame(&scene) else {
            continue;
        };
        let mut at_hit = heapless::Vec::new();
        // The weights a scanline keeps, for every other pixel (the others form theirs).
        let mut weights = Weights::default();
        for row in 0..view.camera.height {
            fast::each_pixel(&view, &p, row, |r| {
                let column = Primary::column(r);
                let Ok(Some(h)) = p.nearest(&view, r) else {
                    return;
                };
                let (mut c1, mut c2) = (Counters::default(), Counters::default());
                let kept = column.is_multiple_of(2).then_some(&mut weights);
                let general =
                    shaded::<S, T>(&view, Some(&p), r, &h, (&mut at_hit, None), &mut c2, false);
                let sides = p.sides_at(r, h.param, &mut at_hit);
                let sides = sides.filter(|_| T::SHADOWS && !p.at_lights().is_empty());
                let sides = sides.map(|bits| crate::shade::PlaneSides {
                    at_hit: &at_hit,
                    at_lights: p.at_lights(),
                    cones: p.cones(),
                    bits,
                });
                if let Some(lit) = lit_sphere_color::<S, T>(&view, &h, sides, kept, &mut c1) {
                    drawn += 1;
                    let at = || format!("{} case {case} ({column}, {row}):\n{text}", S::NAME);
                    assert_eq!(lit, general, "{}", at());
                    assert_eq!(c1, c2, "{}", at());
                }
            });
        }
    }
    drawn
}

/// The fast kernel's flattened sphere shading (`lit_sphere_color`) draws the general
/// shading's colours and counts, with shadows and without, in the fixed formats.
#[test]
fn lit_spheres_draw_the_general_shading() {
    use crate::shade::stages::{Diffuse, Full};
    let counts = [
        lit_spheres_agree::<fixed::types::I16F16, DiffuseShadows>(60),
        lit_spheres_agree::<fixed::types::I16F16, Diffuse>(20),
        lit_spheres_agree::<fixed::types::I20F12, DiffuseShadows>(30),
        lit_spheres_agree::<fixed::types::I32F32, DiffuseShadows>(20),
        lit_spheres_agree::<crate::num::variants::I16F16Recip, DiffuseShadows>(20),
    ];
    assert!(counts.iter().all(|n| *n > 5_000), "{counts:?}");
    // Not in the float formats (flash: they keep the general shading).
    assert_eq!(lit_spheres_agree::<f32, DiffuseShadows>(5), 0);
    // Not for a stage set with more than diffuse lights.
    assert_eq!(lit_spheres_agree::<fixed::types::I16F16, Full>(5), 0);
}

/// Points on and near random spheres (within ±1.5 % of the radius: inside beyond the
/// segments' tolerance, on the surface, outside) and lights in every direction from
/// them, most of them within a few degrees of the tangent plane, a quarter within a
/// few ten-thousandths of a radian: wherever
/// `own_sphere_clear` says the sphere cannot stop the segment, its own segment test
/// (`Sphere::meets_segment`) says no. Returns the clear segments and the segments with a
/// positive `N·L` that the sphere does stop (where a weaker certificate would fail).
fn own_sphere_holds<S: Scalar>(cases: usize, seed: u64) -> (usize, usize) {
    let mut rng = Rng(seed);
    let (mut clear, mut stopped) = (0, 0);
    let v =
        |x: f64, y: f64, z: f64| Some(Vec3::new(S::from_f64(x)?, S::from_f64(y)?, S::from_f64(z)?));
    for _ in 0..cases {
        let r = rng.uniform(0.2, 4.0);
        let c = [
            rng.uniform(-5.0, 5.0),
            rng.uniform(-5.0, 5.0),
            rng.uniform(-5.0, 5.0),
        ];
        let Some(sphere) =
            v(c[0], c[1], c[2]).and_then(|centre| crate::Sphere::new(centre, S::from_f64(r)?).ok())
        else {
            continue;
        };
        // A unit direction `u` from the centre and one `w` across it.
        let (theta, phi) = (
            rng.uniform(0.0, core::f64::consts::TAU),
            rng.uniform(-1.0, 1.0),
        );
        let s = (1.0 - phi * phi).sqrt();
        let u = [s * theta.cos(), s * theta.sin(), phi];
        let a = if u[0].abs() < 0.9 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        let w = [
            u[1] * a[2] - u[2] * a[1],
            u[2] * a[0] - u[0] * a[2],
            u[0] * a[1] - u[1] * a[0],
        ];
        let wn = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
        let k = r * (1.0 + rng.uniform(-0.015, 0.015));
        let p = [c[0] + k * u[0], c[1] + k * u[1], c[2] + k * u[2]];
        let Some(point) = v(p[0], p[1], p[2]) else {
            continue;
        };
        let Some((normal, Some(excess))) = sphere.normal_and_excess(point) else {
            continue;
        };
        // The light's angle from the tangent plane: mostly within a few degrees.
        let angle = match rng.below(4) {
            0 => rng.uniform(-1.5, 1.5),
            1 => rng.uniform(-0.0005, 0.0005),
            _ => rng.uniform(-0.06, 0.06),
        };
        let dist = rng.uniform(0.3, 25.0);
        let (cs, sn) = (angle.cos(), angle.sin());
        let l = [0, 1, 2].map(|i| dist * (sn * u[i] + cs * w[i] / wn));
        let tol = S::from_f64(rng.uniform(0.0001, 0.002)).unwrap_or(S::ZERO);
        let Some(to_light) = v(l[0], l[1], l[2]) else {
            continue;
        };
        let Some(ll) = to_light.dot(to_light).filter(|ll| *ll > S::ZERO) else {
            continue;
        };
        let Some(nl) = to_light.dot_axis(normal).filter(|nl| *nl > S::ZERO) else {
            continue;
        };
        let meets = sphere.meets_segment(point, to_light, ll, tol);
        stopped += usize::from(meets == Some(true));
        let t = LightTerms {
            to_light,
            ll,
            nl,
            knl: None,
        };
        if own_sphere_clear(&sphere, excess, tol, &t) {
            clear += 1;
            assert_eq!(
                meets,
                Some(false),
                "{} r {r} point {p:?} light {l:?}",
                S::NAME
            );
        }
    }
    (clear, stopped)
}

/// The own-sphere certificate of the flattened sphere shading (`own_sphere_clear`)
/// holds in the fixed formats, and the cases it leaves to the exact test include
/// segments the sphere does stop though `N·L` is positive.
#[test]
fn a_sphere_clear_of_its_own_segment_is_not_met_by_it() {
    for (clear, stopped) in [
        own_sphere_holds::<fixed::types::I16F16>(200_000, 0x5EED_2026_1208),
        own_sphere_holds::<fixed::types::I20F12>(200_000, 0x5EED_2026_1209),
        own_sphere_holds::<fixed::types::I32F32>(100_000, 0x5EED_2026_120A),
    ] {
        assert!(clear > 5_000 && stopped > 500, "{clear} {stopped}");
    }
}
