//! The level-plane kernel's invariants, each tested on its own.
//!
//! A lean row draws most of its pixels by a shortcut of the general path's
//! [`plane_color`]: [`lean_color`] (the same operations without the general cases, and
//! on cores where it pays the last light's term by `KernelArith::quick_pixel`),
//! [`quick_step`] (a pixel of a one-light row outside the spheres' columns, its `D`
//! stepped alone) and [`Pixels::quick_run`] (up to 32 such pixels a call). Inside the
//! spheres' columns a pixel tests the spheres against the row's plane alone
//! ([`Primary::nearest_over_level`]) instead of every term ([`Primary::nearest`]). Each test
//! draws the boing ball's frames (`anim::Bounce`) and seeded random level-plane scenes,
//! and compares every pixel a shortcut returns with the exact one.

extern crate std;
use std::format;
use std::string::String;
use std::vec::Vec;

use embedded_graphics_core::pixelcolor::Rgb888;
use fixed::types::{I16F16, I20F12, I32F32};

use super::super::fast::{Primary, Row, resync_pixels};
use super::super::{Kernel, select};
use super::lean::{LeanRow, lean_color, lean_row, quick_step};
use super::level::{Level, Memo, level, plane_color};
use super::{Rows, scanline};
use crate::Depth;
use crate::anim::Bounce;
use crate::num::Rng;
use crate::shade::color::to_pixel;
use crate::shade::stages::{DiffuseShadows, Shading, shading_for};
use crate::stats::Counters;
use crate::{Scalar, Scene, SceneView};

/// A random scene of the level-plane kernel's kind: a tiled floor (its tiles along x,
/// or turned about y), a back wall (plain or tiled), up to two spheres and one or two
/// lights, now and then one just over the floor (where `|L|² < 1` at the hits below
/// it, which the quick term leaves to the exact one, as a sphere's shadow cone does
/// where there is one).
fn level_scene(rng: &mut Rng) -> String {
    let (w, h) = (48 + rng.below(40), 24 + rng.below(24));
    let mut text = format!(
        "rules fixray\ncamera c {{ pixeldim {w} {h} worlddim 8 5 viewpoint {:.2} {:.2} {:.2} }}\n",
        rng.uniform(2.0, 6.0),
        rng.uniform(1.0, 5.0),
        rng.uniform(5.0, 9.0)
    );
    text += "background 0.1 0.1 0.2\n";
    for i in 0..3 {
        text += &format!(
            "material m{i} {{ ambient {:.2} {:.2} {:.2} diffuse {:.2} {:.2} {:.2} }}\n",
            rng.uniform(0.0, 0.3),
            rng.uniform(0.0, 0.3),
            rng.uniform(0.0, 0.3),
            rng.uniform(0.1, 1.0),
            rng.uniform(0.1, 1.0),
            rng.uniform(0.1, 1.0)
        );
    }
    let floor = rng.uniform(-1.0, 0.5);
    for j in 0..1 + rng.below(2) {
        let y = if rng.below(3) == 0 {
            floor + rng.uniform(0.3, 1.2)
        } else {
            rng.uniform(3.0, 12.0)
        };
        text += &format!(
            "light l{j} {{ location {:.2} {y:.2} {:.2} emissivity {:.1} {:.1} {:.1} }}\n",
            rng.uniform(-2.0, 10.0),
            rng.uniform(-6.0, 4.0),
            rng.uniform(1.0, 12.0),
            rng.uniform(1.0, 12.0),
            rng.uniform(1.0, 12.0)
        );
    }
    let xdir = if rng.below(3) == 0 {
        "1 0 0.3"
    } else {
        "1 0 0"
    };
    text += &format!(
        "tiled_plane floor {{ material m0 altmaterial m1 normal 0 1 0 point {:.2} {floor:.2} {:.2} xdir {xdir} dimension {:.2} {:.2} }}\n",
        rng.uniform(-1.0, 1.0),
        rng.uniform(-1.0, 1.0),
        rng.uniform(0.5, 2.0),
        rng.uniform(0.5, 2.0)
    );
    let back = rng.uniform(-12.0, -5.0);
    text += &if rng.below(2) == 0 {
        format!("plane back {{ material m2 normal 0 0 1 point 0 0 {back:.2} }}\n")
    } else {
        format!(
            "tiled_plane back {{ material m1 altmaterial m2 normal 0 0 1 point 0 0 {back:.2} xdir 1 0 0 dimension 1 1 }}\n"
        )
    };
    for i in 0..rng.below(3) {
        let r = rng.uniform(0.4, 1.5);
        text += &format!(
            "sphere s{i} {{ material m{i} center {:.2} {:.2} {:.2} radius {r:.2} }}\n",
            rng.uniform(0.0, 8.0),
            floor + r + rng.uniform(0.0, 2.0),
            rng.uniform(-6.0, 0.0)
        );
    }
    text
}

/// The scenes: the boing ball's frames (every `step`-th of its loop) and `random` seeded
/// level-plane scenes, as `(name, text, frame)` (`frame`: the bounce's, for boing).
pub(super) fn scenes(step: u16, random: usize, seed: u64) -> Vec<(String, String, Option<u16>)> {
    let boing = String::from(include_str!("../../../scenes/boing.scene"));
    let mut all: Vec<_> = (0..16)
        .step_by(usize::from(step))
        .map(|k| (format!("boing frame {k}"), boing.clone(), Some(k)))
        .collect();
    let mut rng = Rng(seed);
    all.extend((0..random).map(|n| (format!("random scene {n}"), level_scene(&mut rng), None)));
    all
}

/// `text` parsed in format `S`, at the bounce's `frame` if it has one (`None`: a radius
/// the format does not resolve, or a scene the format's range refuses).
fn parse<S: Scalar>(text: &str, frame: Option<u16>) -> Option<Scene<S>> {
    let mut scene = Scene::<S>::parse(text).ok()?;
    if let Some(k) = frame {
        Bounce::boing(&scene.objects)
            .ok()?
            .apply(&mut scene, k)
            .ok()?;
    }
    Some(scene)
}

/// The frame of `scene` as `Frame` sets it up (the plan's lights on surfaces, its stage
/// set, the kernel `select` chooses), where that is the level-plane kernel.
fn frame<S: Scalar>(scene: &Scene<S>) -> Option<(SceneView<'_, S>, Rows<S>)> {
    let mut view = scene.view();
    let plan = view.plan();
    view.lights_on_surfaces = plan.lights_on_surfaces;
    if shading_for(&plan) != Shading::DiffuseShadows {
        return None;
    }
    match select::<S, DiffuseShadows>(&view, &plan).kernel {
        Kernel::Rows(rows) => Some((view, rows)),
        _ => None,
    }
}

/// Calls `visit` with every lean row of `scenes` in format `S` (the scene's name and
/// text, its view and fast-kernel frame, the row, and the row's first pixel, plane and
/// lean part as the scanline forms them: [`lean_of`]).
#[allow(clippy::type_complexity)]
fn each_lean_row<S: Scalar>(
    scenes: &[(String, String, Option<u16>)],
    mut visit: impl FnMut(
        (&str, &str),
        &SceneView<'_, S>,
        &Primary<S>,
        u16,
        (&Row<S>, &Level<S>, &LeanRow<S>),
    ),
) {
    for (name, text, k) in scenes {
        let Some(scene) = parse::<S>(text, *k) else {
            continue;
        };
        let Some((view, rows)) = frame(&scene) else {
            continue;
        };
        for row in 0..view.camera.height {
            if let Some((first, l, f)) = lean_of(&view, &rows.primary, row) {
                visit((name, text), &view, &rows.primary, row, (&first, &l, &f));
            }
        }
    }
}

/// Scanline `row`'s first pixel, plane ([`level`]) and lean part ([`lean_row`]), as the
/// scanline forms them, where the row is a lean one.
fn lean_of<S: Scalar>(
    view: &SceneView<'_, S>,
    p: &Primary<S>,
    row: u16,
) -> Option<(Row<S>, Level<S>, LeanRow<S>)> {
    let first = p.row(view, row, 0)?;
    let l = level::<S, DiffuseShadows>(view, p, &first)??;
    let mut f = LeanRow::empty();
    let d = Primary::dir(&first);
    lean_row(view, p, &l, (d.y, d.z), &mut f)?;
    Some((first, l, f))
}

/// The row at each column of scanline `row` (from `first`, its column 0) as the general
/// path steps a lean row's `D`: from the exact screen x at every resync column (and
/// after a step that fails), by `Primary::advance_dir` between; with the row at the
/// column before (`None` at column 0 and after a failed step).
fn each_column<S: Scalar>(
    view: &SceneView<'_, S>,
    p: &Primary<S>,
    row: u16,
    first: &Row<S>,
    mut f: impl FnMut(u16, Option<&Row<S>>, &Row<S>),
) {
    let dy = Primary::dir(first).y;
    let mut state = first.clone();
    let mut before: Option<Row<S>> = None;
    for column in 0..view.camera.width {
        let stepped = match &before {
            None if column == 0 => Some(()),
            Some(_) if column % resync_pixels::<S>() != 0 => p.advance_dir(&mut state),
            _ => p.restart_dir_in_row(view, row, dy, column, &mut state),
        };
        if stepped.is_none() {
            before = None;
            continue;
        }
        f(column, before.as_ref(), &state);
        before = Some(state.clone());
    }
}

/// Whether format `S` takes quick pixels on this target (`KernelArith::QUICK_PIXEL`).
fn quick_pixels<S: Scalar>() -> bool {
    S::QUICK_PIXEL
}

/// What a shortcut answered over the scenes: pixels it drew quickly, colours it formed,
/// and pixels it left to the general path.
#[derive(Debug, Default)]
struct Answers {
    quick: usize,
    colors: usize,
    general: usize,
}

/// Every column of every lean row of `scenes` in format `S`: where [`lean_color`]
/// returns a pixel it is the pixel of [`plane_color`]'s colour for that column, and
/// where it returns a colour it is that colour, bit for bit.
fn lean_colors_hold<S: Scalar>(scenes: &[(String, String, Option<u16>)]) -> Answers {
    let mut seen = Answers::default();
    each_lean_row(scenes, |(name, text), view, p, row, (first, l, f)| {
        let mut counters = Counters::default();
        let mut memo = Memo::default();
        let y = view.camera.screen_y(row);
        each_column(view, p, row, first, |column, _, state| {
            let lean = lean_color(view, state, l, f, &mut counters);
            let want = plane_color::<S, DiffuseShadows>(
                view,
                p,
                state,
                Some(l),
                &mut memo,
                y,
                column,
                &mut counters,
            );
            let at = || format!("{} {name} at ({column}, {row})\n{text}", S::NAME);
            match lean {
                Some(Ok(pixel)) => {
                    seen.quick += 1;
                    assert_eq!(pixel, to_pixel(view.rules(), want), "{}", at());
                }
                Some(Err(color)) => {
                    seen.colors += 1;
                    assert_eq!(color, want, "{}", at());
                }
                None => seen.general += 1,
            }
        });
    });
    seen
}

/// Lean colours (`lean_color`): a lean row's pixel takes [`plane_color`]'s operations in
/// its order without the general cases (checked once per row by `lean_row`, or sent
/// back: a cone that does not clear the pixel, a value out of range), and its last
/// light's quick term only where the reciprocal's error bound and the exact arithmetic's
/// truncations (`|L|² ≥ 1`) keep each channel on one pixel value. Checked at every
/// column of every lean row of eight boing frames and 60 random level-plane scenes, in
/// I16F16 and I20F12 (quick pixels on the host) and I32F32 (none: its colours only).
#[test]
fn a_lean_colour_is_the_general_paths() {
    let all = scenes(2, 60, 0x5EED_0005_0001);
    assert!(quick_pixels::<I16F16>() && quick_pixels::<I20F12>() && !quick_pixels::<I32F32>());
    let i16 = lean_colors_hold::<I16F16>(&all);
    assert!(i16.quick > 100_000 && i16.colors > 500, "{i16:?}");
    let i20 = lean_colors_hold::<I20F12>(&all);
    assert!(i20.quick > 100_000 && i20.colors > 500, "{i20:?}");
    let i32 = lean_colors_hold::<I32F32>(&all);
    assert!(i32.quick == 0 && i32.colors > 100_000, "{i32:?}");
}

/// Every column of every one-light lean row of `scenes` in format `S`, from the row the
/// general path leaves at the column before: where [`quick_step`] returns a pixel, it is
/// the pixel of [`plane_color`]'s colour for the column, and the row is stepped to the
/// column as the general path steps it. Returns the quick steps taken, and those that
/// found their pixel shadowed.
fn quick_steps_hold<S: Scalar>(scenes: &[(String, String, Option<u16>)]) -> (usize, usize) {
    let (mut quick, mut shadowed) = (0, 0);
    each_lean_row(scenes, |(name, text), view, p, row, (first, l, f)| {
        let [light] = f.lights.as_slice() else {
            return;
        };
        let mut counters = Counters::default();
        let mut memo = Memo::default();
        let (y, dy) = (view.camera.screen_y(row), Primary::dir(first).y);
        each_column(view, p, row, first, |column, before, state| {
            let Some(mut s) = before.cloned() else {
                return;
            };
            let Some((pixel, lit, _)) =
                quick_step(view, p, l, f, light, &mut s, (row, dy), (column, true))
            else {
                return;
            };
            let want = plane_color::<S, DiffuseShadows>(
                view,
                p,
                state,
                Some(l),
                &mut memo,
                y,
                column,
                &mut counters,
            );
            let at = || format!("{} {name} at ({column}, {row})\n{text}", S::NAME);
            assert_eq!(pixel, to_pixel(view.rules(), want), "{}", at());
            assert_eq!(Primary::dir(&s), Primary::dir(state), "{}", at());
            assert_eq!(Primary::column(&s), column, "{}", at());
            quick += 1;
            shadowed += usize::from(!lit);
        });
    });
    (quick, shadowed)
}

/// Quick steps (`quick_step`): a one-light lean row's pixel outside the spheres' columns
/// steps its `D` as the general path does (from the column before, or a restart at a
/// resync column), takes [`lean_color`]'s operations for the quick term and a sphere's
/// exact segment test where its cone does not clear the pixel, as [`plane_color`] does.
/// Checked at every column of every such row of eight boing frames and 60 random
/// scenes (shadowed pixels among them) in I16F16 and I20F12; I32F32 has no quick term,
/// and takes none.
#[test]
fn a_quick_step_is_the_general_paths_pixel() {
    let all = scenes(2, 60, 0x5EED_0005_0002);
    let (quick, shadowed) = quick_steps_hold::<I16F16>(&all);
    assert!(quick > 80_000 && shadowed > 2_000, "{quick} {shadowed}");
    let (quick, shadowed) = quick_steps_hold::<I20F12>(&all);
    assert!(quick > 80_000 && shadowed > 2_000, "{quick} {shadowed}");
    assert_eq!(quick_steps_hold::<I32F32>(&all), (0, 0));
}

/// Every scanline of `scenes` in format `S`, whole and from column 7, drawn pixel by
/// pixel as [`Pixels`]' iterator draws it, with each quick run ([`Pixels::quick_run`])
/// taken where the iterator would take it: every pixel a run returns or draws ahead is
/// the fast kernel's pixel there (and so is every other). Returns the pixels of quick
/// runs.
fn quick_runs_hold<S: Scalar>(
    scenes: &[(String, String, Option<u16>)],
    depth: Depth,
) -> (usize, usize) {
    let (mut quick, mut unlike) = (0, 0);
    for (name, text, k) in scenes {
        let Some(scene) = parse::<S>(text, *k) else {
            continue;
        };
        let Some((view, mut rows)) = frame(&scene) else {
            continue;
        };
        rows.depth = depth;
        let w = view.camera.width;
        for (row, start) in (0..view.camera.height).flat_map(|row| [(row, 0), (row, 7)]) {
            let mut c = Counters::default();
            let want: Vec<Rgb888> = super::super::scanline::scanline::<S, DiffuseShadows, _>(
                &view,
                Some(&rows.primary),
                row,
                start..w,
                &mut c,
            )
            .collect();
            let mut counters = Counters::default();
            let Ok(mut px) =
                scanline::<S, DiffuseShadows>(&view, &rows, row, start..w, &mut counters)
            else {
                continue;
            };
            let want_at = |column: u16| want[usize::from(column - start)];
            let at = |column: u16| {
                let name = format!("{} {name}", S::NAME);
                format!("{name} at ({column}, {row}) from {start}\n{text}")
            };
            while let Some(column) = px.columns.next() {
                // `Pixels::pixel`'s own test for a quick run.
                let in_spheres = column >= px.spheres.0 && column <= px.spheres.1;
                let runs = S::QUICK_PIXEL
                    && S::EXACT_SUMS
                    && S::EXACT_PRODUCTS
                    && px.lazy
                    && !in_spheres
                    && !px.fresh
                    && px.valid
                    && px.lean_built == Some(true)
                    && px.lean.runs;
                let pixel = match runs.then(|| px.quick_run(column)).flatten() {
                    Some(pixel) => {
                        quick += 1 + usize::from(px.run_len);
                        pixel
                    }
                    None => px.pixel(column),
                };
                let same = |a: Rgb888, b: Rgb888| depth.key(a) == depth.key(b);
                assert!(same(pixel, want_at(column)), "{}", at(column));
                unlike += usize::from(pixel != want_at(column));
                // The pixels a run drew ahead, the next columns, handed out here.
                let mut next = column;
                while px.run_at < px.run_len {
                    next += 1;
                    let ahead = px.run[usize::from(px.run_at)];
                    assert!(same(ahead, want_at(next)), "drawn ahead: {}", at(next));
                    unlike += usize::from(ahead != want_at(next));
                    px.run_at += 1;
                }
            }
        }
    }
    (quick, unlike)
}

/// Quick runs (`Pixels::quick_run`): on a one-light lean row the pixels outside the
/// spheres' columns come up to 32 a call, each a [`quick_step`] from the one before,
/// the run ending where a pixel needs the general path or a sphere's columns begin; so
/// each is the pixel the general path draws, the fast kernel's. Checked on every
/// scanline of eight boing frames and 40 random scenes, whole and from column 7, in
/// I16F16 and I20F12 (I32F32 has no quick pixel, so no quick run).
#[test]
fn a_quick_run_draws_the_fast_kernels_pixels() {
    let all = scenes(2, 40, 0x5EED_0005_0003);
    for (quick, unlike) in [
        quick_runs_hold::<I16F16>(&all, Depth::RGB888),
        quick_runs_hold::<I20F12>(&all, Depth::RGB888),
    ] {
        assert!(quick > 100_000 && unlike == 0, "{quick} {unlike}");
    }
}

/// Quick runs in a depth shallower than Rgb888 (`spans.rs`): every pixel converts to the
/// fast kernel's pixel's colour in that depth, over the scenes of
/// [`a_quick_run_draws_the_fast_kernels_pixels`] and 40 random scenes with small tiles
/// (many tile edges inside a span), in I16F16 and I20F12; and some pixels are drawn from
/// a span's ends (not the exact Rgb888 pixel), so that the spans are what is checked.
#[test]
fn a_quick_run_in_a_depth_converts_to_the_exact_pixels_colour() {
    let mut all = scenes(2, 40, 0x5EED_0005_0003);
    let mut rng = Rng(0x5EED_0005_0004);
    all.extend((0..40).map(|n| {
        // Every tile a quarter of a unit wide, a few pixels on the screen.
        let text: Vec<String> = level_scene(&mut rng)
            .lines()
            .map(|line| match line.find("dimension ") {
                Some(at) => format!("{}dimension 0.25 0.3 }}", &line[..at]),
                None => String::from(line),
            })
            .collect();
        (format!("small tiles {n}"), text.join("\n"), None)
    }));
    for depth in [
        Depth::RGB565,
        Depth::RGB555,
        Depth::RGB666,
        Depth::new(3, 3, 3),
    ] {
        for (quick, unlike) in [
            quick_runs_hold::<I16F16>(&all, depth),
            quick_runs_hold::<I20F12>(&all, depth),
        ] {
            assert!(
                quick > 100_000 && unlike > quick / 20,
                "{depth:?} {quick} {unlike}"
            );
        }
    }
}

/// Every pixel inside the spheres' columns of every row the level-plane kernel decides
/// once, in `scenes` and format `S`: [`Primary::nearest_over_level`] (the spheres and
/// the row's plane) answers what [`Primary::nearest`] (every term) does: the background,
/// the row's plane, the same sphere hit, or `Err`. Returns the pixels where the plane
/// won and where a sphere did.
fn nearest_over_level_holds<S: Scalar>(scenes: &[(String, String, Option<u16>)]) -> (usize, usize) {
    let (mut planes, mut spheres) = (0, 0);
    for (name, text, k) in scenes {
        let Some(scene) = parse::<S>(text, *k) else {
            continue;
        };
        let Some((view, rows)) = frame(&scene) else {
            continue;
        };
        let p = &rows.primary;
        for row in 0..view.camera.height {
            let Some(mut state) = p.row(&view, row, 0) else {
                continue;
            };
            let Some(l) = level::<S, DiffuseShadows>(&view, p, &state) else {
                continue;
            };
            let level = l.as_ref().map(|l| (l.index, l.pq, l.t));
            let (from, to) = p.sphere_columns_on_row_of(row, u8::MAX);
            for column in from..=to.min(view.camera.width.saturating_sub(1)) {
                if p.restart(&view, row, column, &mut state).is_none() {
                    continue;
                }
                let at = || format!("{} {name} at ({column}, {row})\n{text}", S::NAME);
                let want = p.nearest(&view, &state);
                let got = p.nearest_over_level(&view, &state, level);
                match (want, got) {
                    (Ok(Some(h)), Ok(Some(None))) => {
                        assert_eq!(Some(h.index), l.as_ref().map(|l| l.index), "{}", at());
                        planes += 1;
                    }
                    (Ok(Some(h)), Ok(Some(Some(g)))) => {
                        assert_eq!(h, g, "{}", at());
                        spheres += 1;
                    }
                    (Ok(None), Ok(None)) | (Err(()), Err(())) => {}
                    (want, got) => panic!("{want:?} against {got:?}: {}", at()),
                }
            }
        }
    }
    (planes, spheres)
}

/// [`Primary::nearest_over_level`] is [`Primary::nearest`] wherever the level-plane
/// kernel asks it (inside the spheres' columns), over eight boing frames and 60 random
/// level scenes, in every fixed format.
#[test]
fn the_spheres_against_the_rows_plane_are_the_nearest_of_every_term() {
    let all = scenes(2, 60, 0x5EED_0005_0003);
    for (planes, spheres) in [
        nearest_over_level_holds::<I16F16>(&all),
        nearest_over_level_holds::<I20F12>(&all),
        nearest_over_level_holds::<I32F32>(&all),
    ] {
        assert!(planes > 3_000 && spheres > 3_000, "{planes} {spheres}");
    }
}
