//! The fast kernel's invariants, each tested on its own.
//!
//! Each shortcut of the kernel stands for an exact test it skips: a quiet plane for the
//! shadow segments it cannot stop (`Primary::quiet_planes`), a frame whose terms fit for
//! the overflow tests of its steps (`Primary::frame_fits`), a sphere's screen box for its
//! ray test outside the box (`sphere_rows`, `sphere_columns`), a certified block for the
//! search at each of its pixels (`Primary::certify_block`). Each test draws seeded random
//! scenes and, at every pixel where the shortcut applies, asks the exact test it stands
//! for, with the scanline's own stepped terms.

extern crate std;
use std::format;
use std::string::String;
use std::vec::Vec;

use fixed::types::{I16F16, I20F12, I32F32};

use super::Primary;
use super::blocks::{Block, block_starts};
use super::search::sphere_root;
use super::step::{Row, resync_pixels};
use crate::kernel::shading::segment_tolerance;
use crate::num::Rng;
use crate::shade::occludes_segment;
use crate::{Scalar, Scene, SceneView};

/// A random scene of plain and tiled planes (any normal) under `lights` lights: now and
/// then a coarse epsilon, and twin planes turned by a hair, whose `t'` cross along whole
/// rows (where only the roundings of `N·D` decide the nearest).
fn plane_scene(rng: &mut Rng, lights: u32) -> String {
    let (w, h) = (16 + rng.below(40), 8 + rng.below(20));
    let mut text = format!(
        "rules fixray\ncamera c {{ pixeldim {w} {h} worlddim 8 6 viewpoint {:.3} {:.3} {:.3} }}\n",
        rng.uniform(0.0, 8.0),
        rng.uniform(0.5, 5.5),
        rng.uniform(2.0, 9.0)
    );
    if rng.uniform(0.0, 1.0) < 0.3 {
        text += &format!("precision {:.3}\n", rng.uniform(0.005, 0.2));
    }
    text += "material a { ambient 0.3 0.2 0.1 diffuse 0.5 0.4 0.3 }\n";
    text += "material b { ambient 0.1 0.2 0.3 diffuse 0.2 0.6 0.3 }\n";
    for j in 0..lights {
        text += &format!(
            "light l{j} {{ location {:.2} {:.2} {:.2} emissivity 5 5 5 }}\n",
            rng.uniform(0.0, 8.0),
            rng.uniform(1.0, 8.0),
            rng.uniform(-8.0, 4.0)
        );
    }
    let planes = 2 + rng.below(4);
    for i in 0..planes {
        let r = rng.uniform(0.0, 1.0);
        if i > 0 && r < 0.25 {
            let k = rng.uniform(-0.002, 0.002);
            text += &format!(
                "plane q{i} {{ material b normal {:.4} 1 {:.4} point 1 -1 -4 }}\n",
                0.3 + k,
                0.2 - k
            );
            text += &format!("plane r{i} {{ material a normal 0.3 1 0.2 point 1 -1 -4 }}\n");
        } else if i == 0 && r < 0.5 {
            text += "tiled_plane t { material a altmaterial b normal 0 1 0 point 0 -1 0 xdir 1 0 0 dimension 1 1 }\n";
        } else {
            text += &format!(
                "plane p{i} {{ material {} normal {:.3} {:.3} {:.3} point {:.2} {:.2} {:.2} }}\n",
                if i % 2 == 0 { "a" } else { "b" },
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
                rng.uniform(-4.0, 12.0),
                rng.uniform(-3.0, 3.0),
                rng.uniform(-16.0, -1.0)
            );
        }
    }
    text
}

/// A random scene of one to three spheres (some between the eye and the screen, some
/// off the screen) over a floor, now and then a back wall, lit by one light; the eye at
/// `z ≥ 3`, where the fast kernel takes spheres in the fixed formats.
fn sphere_scene(rng: &mut Rng) -> String {
    let (w, h) = (24 + rng.below(48), 16 + rng.below(32));
    let mut text = format!(
        "rules fixray\ncamera c {{ pixeldim {w} {h} worlddim {:.2} {:.2} viewpoint {:.2} {:.2} {:.2} }}\n",
        rng.uniform(4.0, 12.0),
        rng.uniform(3.0, 8.0),
        rng.uniform(1.0, 7.0),
        rng.uniform(0.5, 5.0),
        rng.uniform(3.0, 10.0)
    );
    text += "material a { ambient 0.3 0.2 0.1 diffuse 0.5 0.4 0.3 }\n";
    text += "light l { location 2 9 4 emissivity 5 5 5 }\n";
    text += "tiled_plane floor { material a altmaterial a normal 0 1 0 point 0 -1 0 xdir 1 0 0 dimension 1 1 }\n";
    if rng.below(2) == 0 {
        text += "plane back { material a normal 0.1 0 1 point 0 0 -12 }\n";
    }
    for i in 0..1 + rng.below(3) {
        text += &format!(
            "sphere s{i} {{ material a center {:.2} {:.2} {:.2} radius {:.2} }}\n",
            rng.uniform(-3.0, 11.0),
            rng.uniform(-1.0, 6.0),
            rng.uniform(-9.0, 2.0),
            rng.uniform(0.2, 2.5)
        );
    }
    text
}

/// A random scene seen from far through a wide window (scale `k`, world units), with
/// planes and one or two spheres at `|eye − centre|` up to `m` (`m²` within the range):
/// where `|D|` exceeds `m` the spheres' terms `oc·D` reach the format's range at some
/// corners of the frame, and not at others.
fn wide_scene(rng: &mut Rng, k: f64, m: f64) -> String {
    let (w, h) = (8 + rng.below(40), 4 + rng.below(20));
    let eye = [
        k * rng.uniform(-1.0, 1.0),
        k * rng.uniform(-1.0, 1.0),
        k * rng.uniform(0.2, 1.5),
    ];
    let mut text = format!(
        "rules fixray\ncamera c {{ pixeldim {w} {h} worlddim {:.3} {:.3} viewpoint {:.3} {:.3} {:.3} }}\n",
        k * rng.uniform(0.5, 3.0),
        k * rng.uniform(0.3, 2.0),
        eye[0],
        eye[1],
        eye[2]
    );
    text += "material a { ambient 0.3 0.2 0.1 diffuse 0.5 0.4 0.3 }\n";
    for i in 0..rng.below(3) {
        text += &format!(
            "plane p{i} {{ material a normal {:.3} {:.3} {:.3} point {:.3} {:.3} {:.3} }}\n",
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
            k * rng.uniform(-1.0, 1.0),
            k * rng.uniform(-1.0, 1.0),
            k * rng.uniform(-1.0, 0.0)
        );
    }
    for i in 0..1 + rng.below(2) {
        // `oc = eye − centre`: a random direction, `|oc|` up to `m`.
        let u = [(); 3].map(|()| rng.uniform(-1.0, 1.0));
        let norm = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt().max(1e-3);
        let oc = m * rng.uniform(0.2, 0.95);
        text += &format!(
            "sphere s{i} {{ material a center {:.3} {:.3} {:.3} radius {:.3} }}\n",
            eye[0] - u[0] * oc / norm,
            eye[1] - u[1] * oc / norm,
            eye[2] - u[2] * oc / norm,
            oc * rng.uniform(0.05, 0.5)
        );
    }
    text
}

/// The square root of format `S`'s range, `2^((INT_BITS − 1)/2)`: the scale at which a
/// product of two coordinates reaches it.
fn root_of_range<S: Scalar>() -> f64 {
    2f64.powf((f64::from(S::INT_BITS) - 1.0) / 2.0)
}

/// The row of scanline `row` at each of its pixels, stepped as a scanline steps it
/// (`Primary::advance`, restarted from the exact screen x every `resync_pixels` and
/// after a step that fails), handed to `f`; a pixel whose row cannot be formed is
/// skipped.
pub(in crate::kernel) fn each_pixel<S: Scalar>(
    view: &SceneView<'_, S>,
    p: &Primary<S>,
    row: u16,
    mut f: impl FnMut(&Row<S>),
) {
    let mut state: Option<Row<S>> = None;
    for column in 0..view.camera.width {
        let stepped = match state.as_mut() {
            Some(r) if column % resync_pixels::<S>() != 0 => p.advance(r).is_some(),
            _ => {
                state = p.row(view, row, column);
                state.is_some()
            }
        };
        if !stepped {
            state = None;
        } else if let Some(r) = state.as_ref() {
            f(r);
        }
    }
}

/// At every quiet plane hit of `scenes` random lit plane scenes in format `S` (a hit
/// whose `t'` is within `Quiet::t_max`, every other plane quiet and out of the epsilon's
/// margin at the pixel), the definition's shadow test (`occludes_segment`, every
/// object's exact segment test with the segments' tolerance at the hit) finds no object
/// on the segment from the hit to any light. Returns the quiet hits and the segments
/// tested.
fn quiet_hits_unshadowed<S: Scalar>(scenes: usize, seed: u64) -> (usize, usize) {
    let mut rng = Rng(seed);
    let (mut hits, mut segments) = (0, 0);
    for case in 0..scenes {
        let lights = 1 + rng.below(2);
        let text = plane_scene(&mut rng, lights);
        let Ok(scene) = Scene::<S>::parse(&text) else {
            continue;
        };
        // As a frame sets its view up: a light on a surface is the plan's to find.
        let mut view = scene.view();
        view.lights_on_surfaces = view.plan().lights_on_surfaces;
        let Some(p) = Primary::new(&view) else {
            continue;
        };
        let eye = view.camera.viewpoint;
        for row in 0..view.camera.height {
            let mut quiet = None;
            each_pixel(&view, &p, row, |r| {
                let Ok(Some(h)) = p.nearest(&view, r) else {
                    return;
                };
                let q = *quiet.get_or_insert_with(|| p.quiet_planes(&view, r));
                let own = 1u8 << h.index;
                if q.loud & !own != 0 || h.param > q.t_max || !Primary::clear_of_margin(r, h.index)
                {
                    return;
                }
                hits += 1;
                for (j, light) in view.lights.iter().enumerate() {
                    let Some(l) = light.location.diff(h.point) else {
                        continue;
                    };
                    let ll = l.dot(l).filter(|ll| *ll > S::ZERO);
                    let tol = segment_tolerance(eye, h.point, h.t_bound, None);
                    let (Some(ll), Some(tol)) = (ll, tol) else {
                        continue;
                    };
                    segments += 1;
                    let column = r.column;
                    assert!(
                        !occludes_segment(&view, None, h.point, l, ll, tol, light.location),
                        "{} case {case}: the quiet hit at ({column}, {row}) on object {} is \
                         shadowed from light {j}:\n{text}",
                        S::NAME,
                        h.index
                    );
                }
            });
        }
    }
    (hits, segments)
}

/// Quiet planes (`Primary::quiet_planes`): a plane with the eye, every light and the
/// row's screen points strictly on one side is crossed by no ray of the row before its
/// hit, so a plane hit within `t_max` whose other planes are all quiet and out of the
/// epsilon's margin lies on the lights' side of each of them, and the kernel makes no
/// segment test for it (`quiet_hit`). Checked against the definition's segment test at
/// every such hit of 300 random scenes lit by one or two lights (tens of thousands of
/// hits), in I16F16 and I20F12 (both with exact quotients, the shortcut's premise).
#[test]
fn no_shadow_segment_from_a_quiet_hit_is_stopped() {
    let (hits, segments) = quiet_hits_unshadowed::<I16F16>(200, 0x5EED_0001_0001);
    assert!(hits > 30_000 && segments > 45_000, "{hits} {segments}");
    let (hits, segments) = quiet_hits_unshadowed::<I20F12>(100, 0x5EED_0001_0002);
    assert!(hits > 15_000 && segments > 25_000, "{hits} {segments}");
}

/// What [`frame_fits_holds`] saw: frames whose terms fit, pixels stepped in them, and
/// frames where a checked step failed.
#[derive(Debug, Default)]
struct Fits {
    frames: usize,
    pixels: usize,
    overflowing: usize,
}

/// Every scanline of `scenes` random wide scenes in format `S`, stepped by the frame's
/// `Primary` and by a copy told that its terms do not fit (every step checked): where
/// `frame_fits` holds, each checked step succeeds and the unchecked one gives its terms
/// bit for bit (`Primary::advance`, and `Primary::advance_one` of one term); where a
/// checked step fails, the frame was not said to fit.
fn frame_fits_holds<S: Scalar>(scenes: usize, seed: u64) -> Fits
where
    S::Acc: PartialEq,
{
    let mut rng = Rng(seed);
    let mut seen = Fits::default();
    for case in 0..scenes {
        let m = root_of_range::<S>();
        let k = m * rng.uniform(0.2, 2.0);
        let text = wide_scene(&mut rng, k, m);
        let Ok(scene) = Scene::<S>::parse(&text) else {
            continue;
        };
        let view = scene.view();
        let Some(p) = Primary::new(&view) else {
            continue;
        };
        let mut checked = p.clone();
        checked.fits = false;
        let mut failed = false;
        for row in 0..view.camera.height {
            let mut state: Option<(Row<S>, Row<S>)> = None;
            for column in 0..view.camera.width {
                let at = || format!("{} case {case} ({column}, {row}):\n{text}", S::NAME);
                let Some((a, b)) = state
                    .as_mut()
                    .filter(|_| column % resync_pixels::<S>() != 0)
                else {
                    // A restart forms the terms afresh (checked), as both rows do.
                    state = p
                        .row(&view, row, column)
                        .zip(checked.row(&view, row, column));
                    continue;
                };
                let n = column % u16::try_from(a.nd.len().max(1)).unwrap_or(1);
                let (mut one_a, mut one_b) = (a.clone(), b.clone());
                let one = p.advance_one(&mut one_a, usize::from(n));
                let one_checked = checked.advance_one(&mut one_b, usize::from(n));
                let stepped = p.advance(a);
                let stepped_checked = checked.advance(b);
                if !p.fits {
                    failed |= stepped_checked.is_none();
                    if stepped_checked.is_none() {
                        state = None;
                    }
                    continue;
                }
                assert!(
                    stepped_checked.is_some() && one_checked.is_some(),
                    "the frame fits, yet a checked step fails at {}",
                    at()
                );
                assert!(stepped.is_some() && one.is_some(), "{}", at());
                assert!(a.nd == b.nd && a.acc == b.acc, "advance: {}", at());
                assert!(
                    one_a.nd == one_b.nd && one_a.acc == one_b.acc,
                    "advance_one: {}",
                    at()
                );
                assert_eq!((a.dir, a.column), (b.dir, b.column), "{}", at());
                seen.pixels += 1;
            }
        }
        seen.frames += usize::from(p.fits);
        seen.overflowing += usize::from(failed);
    }
    seen
}

/// `frame_fits`: a frame's every term is affine in `D`, so where it rounds into the
/// format at the four corners of the frame's range of `D` (the stepped drift included)
/// it does at every pixel, and a step needs no overflow test
/// (`KernelArith::acc_step_fitting`). Checked at every pixel of random scenes seen from
/// far, whose spheres' terms `oc·D` reach the format's range at some pixels and not at
/// others (800 frames in I16F16, I20F12 and I32F32): every step of a frame said to fit
/// is the checked step, bit for bit, and never one that fails; among the frames are
/// hundreds where a checked step does fail (none of them said to fit).
#[test]
fn a_frame_that_fits_steps_as_the_checked_steps() {
    let i16 = frame_fits_holds::<I16F16>(400, 0x5EED_0002_0001);
    assert!(
        i16.frames > 100 && i16.pixels > 40_000 && i16.overflowing > 80,
        "{i16:?}"
    );
    let i20 = frame_fits_holds::<I20F12>(200, 0x5EED_0002_0002);
    assert!(i20.frames > 60 && i20.overflowing > 40, "{i20:?}");
    let i32 = frame_fits_holds::<I32F32>(200, 0x5EED_0002_0003);
    assert!(i32.frames > 50 && i32.overflowing > 40, "{i32:?}");
}

/// What [`boxes_hold`] saw: spheres whose box leaves out some of the frame, pixels
/// outside a box (each sphere's own), pixels inside one where the sphere is hit, and
/// the rows and pixels a sphere's chord of the row leaves out of its box.
#[derive(Debug, Default)]
struct Boxes {
    bounded: usize,
    outside: usize,
    hit_inside: usize,
    /// Rows where a sphere's chord is narrower than its box, and the pixels between.
    chords: usize,
    outside_chord: usize,
}

/// At every pixel of `scenes` random sphere scenes in format `S` outside a sphere's box
/// on the screen (its term's rows and columns), or inside it but outside the sphere's
/// chord of the row (`sphere_chord`), the sphere's exact test with that
/// pixel's stepped `oc·D` and `D·D`, as the search forms them (`sphere_root`), finds no
/// hit beyond the screen.
fn boxes_hold<S: Scalar>(scenes: usize, seed: u64) -> Boxes {
    let mut rng = Rng(seed);
    let mut seen = Boxes::default();
    for case in 0..scenes {
        let text = sphere_scene(&mut rng);
        let Ok(scene) = Scene::<S>::parse(&text) else {
            continue;
        };
        let view = scene.view();
        let Some(p) = Primary::new(&view) else {
            continue;
        };
        let (w, h) = (view.camera.width, view.camera.height);
        let spheres: Vec<(usize, super::Term<S>)> = p
            .terms
            .iter()
            .copied()
            .enumerate()
            .filter(|(_, t)| t.sphere)
            .collect();
        let whole = ((0, h - 1), (0, w - 1));
        seen.bounded += spheres
            .iter()
            .filter(|(_, t)| (t.rows, t.columns) != whole)
            .count();
        for row in 0..h {
            // Each sphere's chord of the row (its box's columns where none is certified).
            let dir = view
                .camera
                .screen_y(row)
                .and_then(|y| y.checked_sub(view.camera.viewpoint.y))
                .map(|dy| (dy, p.dz));
            let chords: Vec<(u16, u16)> = spheres
                .iter()
                .map(|(_, t)| {
                    let chord = dir.and_then(|dir| super::boxes::sphere_chord(&view, &p, t, dir));
                    seen.chords += usize::from(chord.is_some_and(|c| c != t.columns));
                    chord.unwrap_or(t.columns)
                })
                .collect();
            each_pixel(&view, &p, row, |r| {
                let d = r.dir;
                let dd = S::acc_mul(d.x, d.x)
                    .and_then(|xx| S::acc_add(r.yz, xx))
                    .and_then(S::acc_round);
                for ((i, t), chord) in spheres.iter().zip(&chords) {
                    let root = dd.map(|a| sphere_root(t.num, r.nd[*i], a));
                    let inside = (t.rows.0..=t.rows.1).contains(&row)
                        && (t.columns.0..=t.columns.1).contains(&r.column);
                    if inside && !(chord.0..=chord.1).contains(&r.column) {
                        seen.outside_chord += 1;
                        assert!(
                            matches!(root, Some(Ok(None))),
                            "{} case {case}: sphere {i} (chord {chord:?}) at ({}, {row}) \
                             outside its chord: {root:?}\n{text}",
                            S::NAME,
                            r.column
                        );
                        continue;
                    }
                    if inside {
                        seen.hit_inside += usize::from(matches!(root, Some(Ok(Some(_)))));
                        continue;
                    }
                    seen.outside += 1;
                    assert!(
                        matches!(root, Some(Ok(None))),
                        "{} case {case}: sphere {i} ({:?} rows, {:?} columns) at ({}, {row}) \
                         outside its box: {root:?}\n{text}",
                        S::NAME,
                        t.rows,
                        t.columns,
                        r.column
                    );
                }
            });
        }
    }
    seen
}

/// A sphere's rows and columns (`sphere_rows`, `sphere_columns`): a row's (a column's)
/// rays lie in one plane through the eye, and where that plane passes farther than
/// `r·√(9/8)` from the centre every ray of it misses the sphere by a discriminant far
/// more negative than every rounding, so the search skips the sphere there. A row's
/// chord of a sphere (`sphere_chord`) narrows the box's columns to those whose own ray
/// may pass within `r·√(9/8)`. Checked at every pixel outside each sphere's box, and
/// inside it outside the row's chord, on 1,400 random scenes of one to three spheres in
/// I16F16, I20F12 and I32F32 (over 2,000 boxes smaller than the frame, over three million
/// pixels outside them, over 7,000 rows whose chord is narrower than their box and over
/// 30,000 pixels between).
#[test]
fn no_pixel_outside_a_spheres_box_or_chord_sees_it() {
    for (seen, bounded, outside) in [
        (boxes_hold::<I16F16>(600, 0x5EED_0003_0001), 750, 1_000_000),
        (boxes_hold::<I20F12>(400, 0x5EED_0003_0002), 300, 500_000),
        (boxes_hold::<I32F32>(400, 0x5EED_0003_0003), 600, 750_000),
    ] {
        assert!(
            seen.bounded >= bounded
                && seen.outside > outside
                && seen.hit_inside > 5_000
                && seen.chords > 1_500
                && seen.outside_chord > 7_000,
            "{seen:?}"
        );
    }
}

/// Every block certified for any winner (every object and the background) at every
/// block start (`block_starts`: the restarts and half-way to the next) of `scenes`
/// random plane scenes in format `S`, to the scanline's end and to the next block
/// start: at each of its pixels, stepped as the scanline steps, the block's answer
/// (`block_hit`) is `Primary::nearest`'s, the hit bit for bit. Returns the blocks
/// certified and their pixels.
fn blocks_hold<S: Scalar>(scenes: usize, seed: u64) -> (usize, usize) {
    let mut rng = Rng(seed);
    let (mut blocks, mut pixels) = (0, 0);
    for case in 0..scenes {
        let text = plane_scene(&mut rng, 0);
        let Ok(scene) = Scene::<S>::parse(&text) else {
            continue;
        };
        let view = scene.view();
        let Some(p) = Primary::new(&view) else {
            continue;
        };
        let (w, n) = (view.camera.width, view.objects.len());
        for row in 0..view.camera.height {
            each_pixel(&view, &p, row, |r| {
                let start = r.column;
                if start % block_starts::<S>() != 0 {
                    return;
                }
                let half = (w - 1).min(start + block_starts::<S>() - 1);
                for winner in (0..n).map(Some).chain([None]) {
                    for last in [w - 1, half] {
                        let mut block = Block::default();
                        p.start_block(r, winner, last, &mut block);
                        if block.is_empty() {
                            continue;
                        }
                        blocks += 1;
                        let mut s = r.clone();
                        // Up to `last` and the next restart (which resets the block).
                        loop {
                            let column = s.column;
                            let at = || {
                                format!(
                                    "{} case {case}: block of {winner:?} from ({start}, {row}) \
                                     to {last}, at column {column}:\n{text}",
                                    S::NAME
                                )
                            };
                            let Some(got) = p.block_hit(&view, &s, &block, None) else {
                                break;
                            };
                            assert_eq!(got, p.nearest(&view, &s), "{}", at());
                            pixels += 1;
                            if column == last || (column + 1) % resync_pixels::<S>() == 0 {
                                break;
                            }
                            assert!(p.advance(&mut s).is_some(), "{}", at());
                        }
                    }
                }
            });
        }
    }
    (blocks, pixels)
}

/// Certified blocks (`Primary::certify_block`, `start_block`, `block_hit`): inside a
/// block `N·D` is linear in the column and the comparisons with unrounded terms are
/// too, so where every plane keeps its side and its acceptance at both ends and the
/// winner beats every other accepted plane at both ends by more than the roundings of
/// `N·D` can move, it is the search's answer at every pixel between. Checked at every
/// pixel of every block certified, for every possible winner, on 200 random plane
/// scenes in I16F16 and I20F12 (the formats that certify blocks on the host: tens of
/// thousands of blocks).
#[test]
fn a_certified_block_answers_what_the_search_answers() {
    let (blocks, pixels) = blocks_hold::<I16F16>(120, 0x5EED_0004_0001);
    assert!(blocks > 8_000 && pixels > 60_000, "{blocks} {pixels}");
    let (blocks, pixels) = blocks_hold::<I20F12>(80, 0x5EED_0004_0002);
    assert!(blocks > 12_000 && pixels > 60_000, "{blocks} {pixels}");
}
