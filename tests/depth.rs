//! Frames drawn for a display's colour depth (`Frame::with_depth`): a depth's key is the
//! colour `embedded-graphics` converts a pixel to, and a frame drawn for a depth shows,
//! in that depth, the exact frame: every boing frame at 240×240, still and in the orbit,
//! whole and from other columns, drawn line by line, in bands and streamed to a display,
//! in the fixed formats.

use embedded_graphics::mock_display::MockDisplay;
use embedded_graphics::pixelcolor::{
    Bgr555, Bgr565, Bgr666, Bgr888, Rgb555, Rgb565, Rgb666, Rgb888, RgbColor,
};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use fixray::anim::{Bounce, Orbit};
use fixray::{Depth, Frame, I16F16, I20F12, Scalar, Scene};

/// `C`'s depth is `Depth::of::<C>()`, and its key is `C`'s conversion: two pixels have
/// one key exactly where they convert to one `C`, for every value of each channel (the
/// others held at values of every kind).
fn key_is_conversion<C: RgbColor + From<Rgb888>>() {
    let depth = Depth::of::<C>();
    assert_eq!(depth.max(), [C::MAX_R, C::MAX_G, C::MAX_B]);
    for v in 0..=255u8 {
        for w in [0u8, 1, 127, 128, 254, 255] {
            for pixel in [
                Rgb888::new(v, w, w),
                Rgb888::new(w, v, w),
                Rgb888::new(w, w, v),
            ] {
                let c = C::from(pixel);
                let key = depth.key(pixel);
                let parts = [(key >> 16) & 0xFF, (key >> 8) & 0xFF, key & 0xFF];
                let channels = [c.r(), c.g(), c.b()].map(u32::from);
                assert_eq!(parts, channels, "{depth:?} {pixel:?}");
            }
        }
    }
}

#[test]
fn a_depths_key_is_embedded_graphics_conversion() {
    key_is_conversion::<Rgb565>();
    key_is_conversion::<Bgr565>();
    key_is_conversion::<Rgb555>();
    key_is_conversion::<Bgr555>();
    key_is_conversion::<Rgb666>();
    key_is_conversion::<Bgr666>();
    key_is_conversion::<Rgb888>();
    key_is_conversion::<Bgr888>();
    assert_eq!(Depth::of::<Rgb565>(), Depth::RGB565);
    assert_eq!(Depth::of::<Rgb888>(), Depth::RGB888);
    assert_eq!(Depth::default(), Depth::RGB888);
}

/// Each channel's key never decreases as the channel grows (what the spans' certificate
/// rests on), for every depth of 1 to 8 bits a channel.
#[test]
fn a_depths_key_grows_with_each_channel() {
    for bits in 1..=8u32 {
        let max = u8::try_from((1u32 << bits) - 1).unwrap();
        let depth = Depth::new(max, max, max);
        let mut last = 0;
        for v in 0..=255u8 {
            let k = depth.key(Rgb888::new(v, v, v));
            let parts = [k >> 16, (k >> 8) & 0xFF, k & 0xFF];
            assert!(parts.iter().all(|p| *p >= last && *p <= u32::from(max)));
            last = parts[0];
        }
        assert_eq!(last, u32::from(max));
    }
}

/// The boing scene at 240×240, moved to each of its bounce's frames and to each of its
/// orbit's frames, in format `S`.
fn boing_frames<S: Scalar>() -> Vec<(String, Scene<S>)> {
    let text = include_str!("../scenes/boing-240x240.scene");
    let base = Scene::<S>::parse(text).unwrap();
    let bounce = Bounce::boing(&base.objects).unwrap();
    let orbit = Orbit::boing(&base.objects).unwrap();
    let mut all = Vec::new();
    for k in (0..bounce.frames()).step_by(3) {
        let mut scene = base.clone();
        bounce.apply(&mut scene, k).unwrap();
        all.push((format!("bounce {k}"), scene));
    }
    for k in (0..orbit.frames()).step_by(5) {
        let mut scene = base.clone();
        bounce.apply(&mut scene, k % bounce.frames()).unwrap();
        orbit.apply(&mut scene, k).unwrap();
        all.push((format!("orbit {k}"), scene));
    }
    all
}

/// Every frame of [`boing_frames`] drawn for `depth`, in bands of 8 rows, against the
/// exact frame: one colour in the depth at every pixel; returns the pixels that differ
/// in Rgb888 (drawn from a span's ends).
fn frames_agree_in<S: Scalar>(depth: Depth) -> usize {
    let mut unlike = 0;
    for (name, scene) in boing_frames::<S>() {
        let (w, h) = (usize::from(scene.camera.width), scene.camera.height);
        let black = Rgb888::new(0, 0, 0);
        let (mut exact, mut panel) = (vec![black; w * 8], vec![black; w * 8]);
        let frame = Frame::<_, Rgb888>::new(&scene);
        let shallow = Frame::<_, Rgb888>::new(&scene).with_depth(depth);
        for top in (0..h).step_by(8) {
            frame.render_rows(top..top + 8, &mut exact);
            shallow.render_rows(top..top + 8, &mut panel);
            for (i, (a, b)) in exact.iter().zip(&panel).enumerate() {
                let at = (i % w, usize::from(top) + i / w);
                assert_eq!(depth.key(*a), depth.key(*b), "{name} {} at {at:?}", S::NAME);
                unlike += usize::from(a != b);
            }
        }
    }
    unlike
}

#[test]
fn boing_frames_for_a_panel_are_the_exact_frames_there() {
    for depth in [Depth::RGB565, Depth::RGB666] {
        let unlike = frames_agree_in::<I16F16>(depth);
        assert!(unlike > 10_000, "{depth:?}: {unlike}");
        let unlike = frames_agree_in::<I20F12>(depth);
        assert!(unlike > 10_000, "{depth:?}: {unlike}");
    }
    // The exact depth draws the exact pixels.
    assert_eq!(frames_agree_in::<I16F16>(Depth::RGB888), 0);
}

/// Drawn to an `Rgb565` display from other columns than the first (a display area that
/// does not start at x = 0, streamed by `Frame::draw`): the exact frame's colours.
#[test]
fn a_frame_streamed_for_its_depth_shows_the_exact_frame() {
    let text = include_str!("../scenes/boing-240x240.scene").replace(
        "pixeldim 240 240 worlddim 7 7",
        "pixeldim 60 60 worlddim 7 7",
    );
    let scene = Scene::<I16F16>::parse(&text).unwrap();
    let frame: Frame<'_, I16F16, Rgb565> = Frame::new(&scene);
    let shallow: Frame<'_, I16F16, Rgb565> = Frame::new(&scene).with_depth(Depth::RGB565);
    for x in [0, 3, 7, 13] {
        let (mut a, mut b) = (MockDisplay::<Rgb565>::new(), MockDisplay::<Rgb565>::new());
        a.set_allow_overdraw(true);
        b.set_allow_overdraw(true);
        let area = Rectangle::new(Point::new(x, 0), Size::new(60 - x as u32, 60));
        frame.draw(&mut a.clipped(&area)).unwrap();
        shallow.draw(&mut b.clipped(&area)).unwrap();
        a.assert_eq(&b);
    }
}
