//! Certified blocks against their oracle, every pixel searched, on seeded random
//! scenes.

extern crate std;

use std::vec::Vec;

use embedded_graphics_core::pixelcolor::Rgb888;

use super::super::scanline;
use super::super::tests::random_scene;
use super::*;
use crate::Scene;
use crate::num::Rng;
use crate::shade::stages::DiffuseShadows;
use crate::stats::Counters;

/// Every scanline of `scenes` random plane scenes in format `S`: the hits a scanline
/// takes from certified blocks (stepping and restarting as `scanline` does) against
/// `nearest` at every pixel (object, point, bound and `t'`, bit for bit), and the
/// pixels of whole and partial scanlines with blocks and without. Returns the pixels
/// the blocks answered.
fn blocks_agree<S: Scalar>(scenes: usize) -> usize {
    let mut rng = Rng(0x5EED_2026_1205);
    let mut blocked = 0;
    let mut guessed = 0;
    let mut parsed = 0;
    for case in 0..scenes {
        let text = random_scene(&mut rng);
        let scene = match Scene::<S>::parse(&text) {
            Ok(scene) => scene,
            // Only a format's range may refuse a scene.
            Err(e) => {
                assert!(
                    std::format!("{e}").contains("range") || !blocks_for::<S>(),
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
            let mut block = blocks::Block::default();
            for column in 0..w {
                let stepped = match state.as_mut() {
                    Some(r) if column % resync_pixels::<S>() != 0 => p.advance(r).is_some(),
                    _ => {
                        block = blocks::Block::default();
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
                        if column % resync_pixels::<S>() == 0
                            && let Some(h) = &hit
                        {
                            // Any guess of the winner (as `scanline` guesses the last
                            // pixel's) is certified only where it is the answer.
                            let n = view.objects.len();
                            let mut certified = 0;
                            for guess in (0..n).map(Some).chain([None]) {
                                let mut trial = blocks::Block::default();
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
