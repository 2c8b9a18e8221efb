//! What a frame must redraw of the frame before it (`Frame::changes_since`): every frame of
//! the boing ball drawn over the frame before from its changed columns alone is the frame,
//! bit for bit, in every format; frames the certificate does not cover change everywhere.

use embedded_graphics::pixelcolor::Rgb888;
use fixray::anim::Bounce;
use fixray::{Frame, KernelKind, Scalar, Scene};

/// The whole frame, row by row.
fn whole<S: Scalar>(frame: &Frame<'_, S>, width: u16, height: u16) -> Vec<Vec<Rgb888>> {
    (0..height)
        .map(|row| {
            let mut line = vec![Rgb888::new(0, 0, 0); usize::from(width)];
            frame.render_line(row, &mut line);
            line
        })
        .collect()
}

/// Every frame of `text`'s bounce drawn over the frame before from its changes: checks it
/// is the frame ([`redraw_is_exact`]), and returns the mean share of pixels redrawn.
fn bounce_over_the_frame_before<S: Scalar>(text: &str) -> f64 {
    let scene = Scene::<S>::parse(text).unwrap();
    let bounce = Bounce::boing(&scene.objects).unwrap();
    let mut shares = 0.0;
    for k in 0..bounce.frames() {
        let (mut a, mut b) = (scene.clone(), scene.clone());
        bounce.apply(&mut a, k).unwrap();
        bounce.apply(&mut b, k + 1).unwrap();
        assert_eq!(Frame::<S>::new(&b).kernel(), KernelKind::Rows);
        assert!(
            !Frame::<S>::new(&b)
                .changes_since(&Frame::<S>::new(&a))
                .everywhere()
        );
        shares += redraw_is_exact(&a, &b, &format!("frame {} over frame {k}", k + 1));
    }
    shares / f64::from(bounce.frames())
}

#[test]
fn the_boing_balls_frames_redrawn_where_they_change_are_the_frames_in_every_format() {
    // 128x64 in every format; the whole panel in three. The ball's box and where its
    // shadow can fall: under 30 % of the narrow picture, under a fifth of the panel.
    let cases = fixray::num::formats::FORMATS
        .iter()
        .map(|f| (*f, include_str!("../scenes/boing.scene"), 0.3))
        .chain(
            ["i16f16", "i32f32", "f32"]
                .map(|f| (f, include_str!("../scenes/boing-240x240.scene"), 0.2)),
        );
    for (format, text, most) in cases {
        let mean = fixray::with_format!(format, bounce_over_the_frame_before(text)).unwrap();
        println!("{format}: {:.1} % of pixels redrawn a frame", 100.0 * mean);
        assert!(mean < most, "{format}: {mean}");
    }
}

#[test]
fn the_same_scene_changes_nowhere_and_another_scene_everywhere() {
    let text = include_str!("../scenes/boing.scene");
    let scene = Scene::<fixray::I16F16>::parse(text).unwrap();
    let (a, b) = (Frame::<_>::new(&scene), Frame::<_>::new(&scene));
    let same = a.changes_since(&b);
    assert!(!same.everywhere());
    assert!((0..64).all(|row| same.columns(row).is_none()));
    // A light moved: the certificate covers moved spheres only.
    let mut lit = scene.clone();
    lit.lights[0].location.x += fixray::I16F16::from_num(1);
    let other = Frame::<_>::new(&lit);
    let changes = other.changes_since(&a);
    assert!(changes.everywhere());
    assert!((0..64).all(|row| changes.columns(row) == Some(0..128)));
    assert_eq!(changes.columns(64), None, "no row below the picture");
}

#[test]
fn a_moved_sphere_another_kernel_draws_changes_whole_rows() {
    // A mirror sees the sphere anywhere: the fast kernel draws the scene, and its frames
    // are redrawn whole.
    let text = include_str!("../scenes/mirror.scene");
    let scene = Scene::<fixray::I16F16>::parse(text).unwrap();
    let bounce = Bounce::boing(&scene.objects).unwrap();
    let mut next = scene.clone();
    bounce.apply(&mut next, 3).unwrap();
    let (a, b) = (Frame::<_>::new(&scene), Frame::<_>::new(&next));
    assert_ne!(b.kernel(), KernelKind::Rows);
    let changes = b.changes_since(&a);
    assert!(!changes.everywhere());
    let width = scene.camera.width;
    assert!((0..scene.camera.height).all(|row| changes.columns(row) == Some(0..width)));
}

#[test]
fn a_part_of_a_scanline_is_the_whole_scanlines_pixels_from_any_column() {
    let scene = Scene::<fixray::I16F16>::parse(include_str!("../scenes/boing.scene")).unwrap();
    let frame = Frame::<_>::new(&scene);
    for row in [0, 20, 40, 63] {
        let mut line = [Rgb888::new(0, 0, 0); 128];
        frame.render_line(row, &mut line);
        for (start, end) in [
            (0, 128),
            (0, 40),
            (1, 2),
            (37, 100),
            (64, 128),
            (100, 200),
            (127, 128),
        ] {
            let mut part = [Rgb888::new(1, 2, 3); 128];
            frame.render_columns(row, start..end, &mut part);
            let end = end.min(128);
            let n = usize::from(end - start);
            assert_eq!(
                &part[..n],
                &line[usize::from(start)..usize::from(end)],
                "{row}: {start}..{end}"
            );
            assert!(part[n..].iter().all(|&c| c == Rgb888::new(1, 2, 3)));
        }
    }
}

/// Frame `after` drawn over frame `before` from its changes is `after`, bit for bit;
/// returns the share of pixels redrawn.
fn redraw_is_exact<S: Scalar>(before: &Scene<S>, after: &Scene<S>, what: &str) -> f64 {
    let (width, height) = (after.camera.width, after.camera.height);
    let (a, b) = (Frame::new(before), Frame::new(after));
    let changes = b.changes_since(&a);
    let mut shown = whole(&a, width, height);
    let expected = whole(&b, width, height);
    let mut redrawn = 0;
    for (row, line) in (0..height).zip(shown.iter_mut()) {
        if let Some(columns) = changes.columns(row) {
            redrawn += columns.len();
            let span = usize::from(columns.start)..usize::from(columns.end);
            b.render_columns(row, columns, &mut line[span]);
        }
    }
    for (row, (got, want)) in shown.iter().zip(&expected).enumerate() {
        assert_eq!(got, want, "{what}: row {row}");
    }
    redrawn as f64 / (f64::from(width) * f64::from(height))
}

/// A seeded sweep of the hard cases of a change region: a ball moved anywhere over the
/// boing room (small or large, near the floor, the wall or the light, partly off the
/// screen), lit from anywhere above the floor (shadows long and grazing on either
/// plane), in the coarsest fixed formats.
fn a_sweep_of_moved_balls<S: Scalar>() {
    let text = include_str!("../scenes/boing.scene");
    let mut seed = 0x2545_f491_4f6c_dd1d_u64;
    let mut uniform = |lo: f64, hi: f64| {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        lo + (hi - lo) * ((seed >> 11) as f64 / (1u64 << 53) as f64)
    };
    let mut checked = 0;
    for case in 0..60 {
        let r = uniform(0.25, 1.6);
        let place = |x: f64, y: f64, z: f64| {
            format!("sphere ball {{ material ball center {x:.4} {y:.4} {z:.4} radius {r:.4} }}")
        };
        let light = format!(
            "light lamp {{ location {:.3} {:.3} {:.3} emissivity 9 9 9 }}",
            uniform(-4.0, 12.0),
            uniform(1.0, 12.0),
            uniform(-5.0, 6.0)
        );
        let (x, y, z) = (uniform(-1.0, 9.0), uniform(r, 4.0), uniform(-5.0, 1.0));
        let (dx, dy, dz) = (uniform(-0.6, 0.6), uniform(-0.6, 0.6), uniform(-0.3, 0.3));
        let scene_at = |x: f64, y: f64, z: f64| {
            let mut lines: Vec<String> = text
                .lines()
                .filter(|l| !l.starts_with("sphere") && !l.starts_with("light"))
                .map(str::to_string)
                .collect();
            lines.push(light.clone());
            lines.push(place(x, y, z));
            Scene::<S>::parse(&lines.join("\n"))
        };
        let (Ok(before), Ok(after)) =
            (scene_at(x, y, z), scene_at(x + dx, (y + dy).max(r), z + dz))
        else {
            continue;
        };
        if Frame::<S>::new(&after).kernel() != KernelKind::Rows {
            continue;
        }
        redraw_is_exact(&before, &after, &format!("case {case}: {light}"));
        checked += 1;
    }
    println!("{checked} cases");
    assert!(
        checked >= 40,
        "{checked} cases drawn by the level-plane kernel"
    );
}

#[test]
fn a_ball_moved_anywhere_under_any_light_is_redrawn_exactly() {
    a_sweep_of_moved_balls::<fixray::I16F16>();
    a_sweep_of_moved_balls::<fixray::I20F12>();
    a_sweep_of_moved_balls::<f32>();
}
