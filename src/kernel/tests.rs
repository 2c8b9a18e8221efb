//! The kernels' own tests: certified blocks and the flattened plane shading against
//! their oracles on seeded random scenes.

extern crate std;
use std::format;
use std::string::String;
use std::vec::Vec;

use super::fast::Row;
use super::memo::PlaneMemo;
use super::scanline::fast_color;
use super::shading::{lit_plane_color, quiet_hit};
use super::*;
use crate::Scene;
use crate::shade::stages::DiffuseShadows;

/// A seeded random scene of planes only (plain and tiled, any normal: walls with
/// `N.x ≠ 0` among them), sometimes lit.
fn random_scene(mut next: impl FnMut() -> u64) -> String {
    // A whole number in `0..n`, and a real in `[lo, hi)`.
    let mut below = |n: u64| u32::try_from(next() % n).unwrap();
    let (w, h) = (16 + below(48), 8 + below(24));
    let mut uniform =
        |lo: f64, hi: f64| lo + (hi - lo) * f64::from(below(1 << 24)) / f64::from(1u32 << 24);
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

/// Every scanline of `scenes` random plane scenes in format `S`: the hits a scanline
/// takes from certified blocks (stepping and restarting as `scanline` does) against
/// `nearest` at every pixel (object, point, bound and `t'`, bit for bit), and the
/// pixels of whole and partial scanlines with blocks and without. Returns the pixels
/// the blocks answered.
fn blocks_agree<S: Scalar>(scenes: usize) -> usize {
    let mut next = crate::num::xorshift(0x5EED_2026_1205);
    let mut blocked = 0;
    let mut guessed = 0;
    let mut parsed = 0;
    for case in 0..scenes {
        let text = random_scene(&mut next);
        let scene = match Scene::<S>::parse(&text) {
            Ok(scene) => scene,
            // Only a format's range may refuse a scene.
            Err(e) => {
                assert!(
                    std::format!("{e}").contains("range") || !fast::blocks_for::<S>(),
                    "{e}\n{text}"
                );
                continue;
            }
        };
        parsed += 1;
        let view = scene.view();
        let Some(p) = Primary::new(&view) else {
            continue;
        };
        let plain = p.clone().without_blocks();
        let w = view.camera.width;
        for row in 0..view.camera.height {
            // The hits, as the scanline steps.
            let mut state: Option<Row<S>> = None;
            let mut block = fast::Block::default();
            for column in 0..w {
                let stepped = match state.as_mut() {
                    Some(r) if column % fast::resync_pixels::<S>() != 0 => p.advance(r).is_some(),
                    _ => {
                        block = fast::Block::default();
                        state = p.row(&view, row, column);
                        state.is_some()
                    }
                };
                if !stepped {
                    state = None;
                    continue;
                }
                let Some(r) = state.as_ref() else { continue };
                let want = plain.nearest(&view, r).ok();
                let got = match p.block_hit(&view, r, &block, None) {
                    Some(hit) => {
                        blocked += 1;
                        hit.ok()
                    }
                    None => {
                        let hit = p.nearest(&view, r).ok();
                        if column % fast::resync_pixels::<S>() == 0
                            && let Some(h) = &hit
                        {
                            // Any guess of the winner (as `scanline` guesses the last
                            // pixel's) is certified only where it is the answer.
                            let n = view.objects.len();
                            let mut certified = 0;
                            for guess in (0..n).map(Some).chain([None]) {
                                let mut trial = fast::Block::default();
                                p.start_block(r, guess, w - 1, &mut trial);
                                if let Some(g) = p.block_hit(&view, r, &trial, None) {
                                    certified += 1;
                                    assert_eq!(g.ok(), want, "{} case {case}", S::NAME);
                                }
                            }
                            assert!(certified <= 1, "{} case {case}", S::NAME);
                            guessed += certified;
                            p.start_block(r, h.as_ref().map(|h| h.index), w - 1, &mut block);
                        }
                        hit
                    }
                };
                assert_eq!(
                    got,
                    want,
                    "{} case {case} row {row} column {column}:\n{text}",
                    S::NAME
                );
            }
            // The pixels, whole scanlines and one from the middle.
            for columns in [0..w, w / 3..w] {
                let mut counters = Counters::default();
                let with: Vec<Rgb888> = scanline::<S, DiffuseShadows, Rgb888>(
                    &view,
                    Some(&p),
                    row,
                    columns.clone(),
                    &mut counters,
                )
                .collect();
                let without: Vec<Rgb888> = scanline::<S, DiffuseShadows, Rgb888>(
                    &view,
                    Some(&plain),
                    row,
                    columns,
                    &mut counters,
                )
                .collect();
                assert_eq!(with, without, "{} case {case} row {row}:\n{text}", S::NAME);
            }
        }
    }
    assert!(
        parsed * 10 >= scenes * 9,
        "{parsed} of {scenes} scenes parsed"
    );
    // Guesses were certified (the right ones) wherever blocks were.
    assert_eq!(
        guessed > 0,
        blocked > 0,
        "{guessed} guesses, {blocked} pixels"
    );
    blocked
}

/// Every fast-kernel hit of `scenes` random plane scenes (and the default scene) in
/// format `S`, lit by the stage set `T`: the hits found with a scanline's memo of its
/// still planes (`fast::HitMemo`) are the hits, and [`lit_plane_color`]'s colour is
/// the general shading's ([`fast_color`]) bit for bit wherever it draws one.
/// Returns how many hits it drew.
fn lit_planes_agree<S: Scalar, T: Stages>(scenes: usize) -> (usize, usize) {
    let mut next = crate::num::xorshift(0x5EED_2026_1206);
    let (mut drawn, mut quiet) = (0, 0);
    let texts = (0..scenes)
        .map(|_| random_scene(&mut next))
        .chain([String::from(include_str!("../../scenes/default.scene"))]);
    for (case, text) in texts.enumerate() {
        let Ok(scene) = Scene::<S>::parse(&text) else {
            continue;
        };
        // As a frame sets its view up (`render.rs`): a light on a surface is the
        // plan's to find.
        let mut view = scene.view();
        view.lights_on_surfaces = view.plan().lights_on_surfaces;
        let Some(p) = Primary::new(&view) else {
            continue;
        };
        let mut at_hit = heapless::Vec::new();
        // One memo for the whole frame, as a scanline keeps one for its pixels.
        let mut memo = PlaneMemo::default();
        let mut hits = fast::HitMemo::default();
        for row in 0..view.camera.height {
            let mut state: Option<Row<S>> = None;
            for column in 0..view.camera.width {
                let stepped = match state.as_mut() {
                    Some(r) if column % fast::resync_pixels::<S>() != 0 => p.advance(r).is_some(),
                    _ => {
                        state = p.row(&view, row, column);
                        state.is_some()
                    }
                };
                let Some(r) = state.as_ref().filter(|_| stepped) else {
                    state = None;
                    continue;
                };
                // The still planes' hits from the memo are the hits themselves.
                let found = p.nearest(&view, r);
                let memoized = p.nearest_with(&view, r, Some(&mut hits));
                assert_eq!(found, memoized, "{} case {case} ({row}, {column})", S::NAME);
                let Ok(Some(h)) = found else {
                    continue;
                };
                let (mut c1, mut c2) = (Counters::default(), Counters::default());
                let at = (&mut at_hit, Some(&mut memo));
                let mut lit_row = r.clone();
                let lit = lit_plane_color::<S, T>(&view, &p, &mut lit_row, &h, at, &mut c1);
                let general = fast_color::<S, T>(&view, Some(&p), r, &h, &mut at_hit, &mut c2);
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
            }
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

/// The certified blocks (`Primary::certify_block`) answer what a search of every pixel
/// answers, in the formats that take them and in the others (which never do).
#[test]
fn certified_blocks_draw_what_every_pixel_searched_draws() {
    let blocked = blocks_agree::<fixed::types::I16F16>(150);
    // The blocks ran (tens of thousands of pixels over these scenes).
    assert!(blocked > 10_000, "{blocked} pixels in certified blocks");
    assert!(blocks_agree::<fixed::types::I20F12>(150) > 10_000);
    assert!(blocks_agree::<crate::num::variants::I16F16Recip>(60) > 1_000);
    assert_eq!(blocks_agree::<fixed::types::I32F32>(40), 0);
    assert_eq!(blocks_agree::<f32>(20), 0);
}
