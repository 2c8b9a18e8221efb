//! ASCII-pattern render tests on tiny scenes (MockDisplay also catches overdraw and
//! out-of-bounds writes), plus the streaming contract: one `fill_contiguous` per scanline,
//! the same pixels through `render`, `render_line`, a `Framebuffer` and Rgb565.

mod common;
use common::{assert_pattern_everywhere, top_left_pixel};
use embedded_graphics::framebuffer::{Framebuffer, buffer_size};
use embedded_graphics::image::GetPixel;
use embedded_graphics::mock_display::MockDisplay;
use embedded_graphics::pixelcolor::raw::{LittleEndian, RawU16};
use embedded_graphics::pixelcolor::{Rgb565, Rgb888, RgbColor};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use fixray::scene::Rules;
use fixray::{I16F16, Scalar, Scene, render, render_line};

/// Camera for the 4×4 pattern scenes: screen [0,4]², eye at (2, 2, 5). Screen rows are at
/// y = 3.5, 2.5, 1.5, 0.5 from the top.
const CAM4: &str = "camera c { pixeldim 4 4 worlddim 4 4 viewpoint 2 2 5 }\n";

#[test]
fn the_nearest_plane_wins() {
    // A green back wall at z = −5 and a red floor at y = 0.4: row 3 meets the floor just
    // behind the screen (z ≈ −0.33), row 2 would meet it at z = −11, behind the wall.
    let text = format!(
        "{CAM4}material red {{ ambient 1 0 0 }} material green {{ ambient 0 1 0 }}
         plane wall {{ material green normal 0 0 1 point 0 0 -5 }}
         plane floor {{ material red normal 0 1 0 point 0 0.4 0 }}"
    );
    assert_pattern_everywhere(&text, &["GGGG", "GGGG", "GGGG", "RRRR"]);
}

#[test]
fn planes_in_front_of_the_screen_are_not_drawn() {
    // A blue plane at z = 2, between the eye and the screen, hides nothing.
    let text = format!(
        "{CAM4}material green {{ ambient 0 1 0 }} material blue {{ ambient 0 0 1 }}
         plane glass {{ material blue normal 0 0 1 point 0 0 2 }}
         plane wall {{ material green normal 0 0 1 point 0 0 -5 }}"
    );
    assert_pattern_everywhere(&text, &["GGGG", "GGGG", "GGGG", "GGGG"]);
}

#[test]
fn empty_scenes_show_the_background() {
    let text = format!("{CAM4}background 0 1 1");
    assert_pattern_everywhere(&text, &["CCCC", "CCCC", "CCCC", "CCCC"]);
}

#[test]
fn a_side_wall_is_cut_by_the_screen_rule() {
    // The wall x = 2.7 seen from x = 2. Columns look through x = 0.5, 1.5, 2.5, 3.5 on
    // the screen. Columns 0 and 1 head away from the wall (t < 0). Column 2 reaches
    // x = 2.7 behind the screen (z = −2): drawn. Column 3 crosses x = 2.7 before the
    // screen (z ≈ 2.67 > 0): rejected by the primary-ray rule.
    let text = format!(
        "{CAM4}material white {{ ambient 1 1 1 }}
         plane side {{ material white normal -1 0 0 point 2.7 0 0 }}"
    );
    assert_pattern_everywhere(&text, &["KKWK", "KKWK", "KKWK", "KKWK"]);
}

#[test]
fn an_occluding_plane_casts_a_shadow() {
    // A white diffuse floor at y = 0.4 under a strong light at y = 10: lit to full white
    // (rows 2 and 3 see it).
    let lit = format!(
        "{CAM4}material floor_m {{ diffuse 1 1 1 }}
         light sun {{ location 2 10 -5 emissivity 100 100 100 }}
         plane floor {{ material floor_m normal 0 1 0 point 0 0.4 0 }}"
    );
    assert_pattern_everywhere(&lit, &["KKKK", "KKKK", "WWWW", "WWWW"]);
    // A blue roof at y = 3 between floor and light: the floor is in its shadow (black).
    // Row 1 sees the roof, lit from above but seen from below (N·L < 0 for the facing
    // normal): its ambient blue. Row 0 crosses y = 3 in front of the screen: background.
    let shadowed = format!(
        "{lit}material roof_m {{ ambient 0 0 1 diffuse 1 1 1 }}
         plane roof {{ material roof_m normal 0 1 0 point 0 3 0 }}"
    );
    assert_pattern_everywhere(&shadowed, &["KKKK", "BBBB", "KKKK", "KKKK"]);
}

#[test]
fn rgb565_targets_get_the_same_picture() {
    let text = format!(
        "{CAM4}material red {{ ambient 1 0 0 }} material green {{ ambient 0 1 0 }}
         plane wall {{ material green normal 0 0 1 point 0 0 -5 }}
         plane floor {{ material red normal 0 1 0 point 0 0.4 0 }}"
    );
    let scene = Scene::<I16F16>::parse_as(&text, Rules::Fixray).unwrap();
    let mut display = MockDisplay::<Rgb565>::new();
    render(&scene, &mut display).unwrap();
    display.assert_pattern(&["GGGG", "GGGG", "GGGG", "RRRR"]);
}

/// A target that records every `fill_contiguous` call.
struct Recorder {
    size: Size,
    calls: Vec<(Rectangle, Vec<Rgb888>)>,
}

impl OriginDimensions for Recorder {
    fn size(&self) -> Size {
        self.size
    }
}

impl DrawTarget for Recorder {
    type Color = Rgb888;
    type Error = core::convert::Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb888>>>(
        &mut self,
        _: I,
    ) -> Result<(), Self::Error> {
        panic!("the renderer must stream through fill_contiguous, not draw_iter");
    }
    fn fill_contiguous<I: IntoIterator<Item = Rgb888>>(
        &mut self,
        area: &Rectangle,
        colors: I,
    ) -> Result<(), Self::Error> {
        self.calls.push((*area, colors.into_iter().collect()));
        Ok(())
    }
}

const DEFAULT: &str = include_str!("../scenes/default.scene");

#[test]
fn one_fill_contiguous_per_scanline_matching_render_line() {
    let scene = Scene::<I16F16>::parse_as(DEFAULT, Rules::Fixray).unwrap();
    let (w, h) = (scene.camera.width, scene.camera.height);
    let mut target = Recorder {
        size: Size::new(u32::from(w), u32::from(h)),
        calls: Vec::new(),
    };
    render(&scene, &mut target).unwrap();
    assert_eq!(target.calls.len(), usize::from(h));
    let mut line = vec![Rgb888::BLACK; usize::from(w)];
    for (row, (area, pixels)) in (0..h).zip(&target.calls) {
        assert_eq!(
            *area,
            Rectangle::new(Point::new(0, i32::from(row)), Size::new(u32::from(w), 1))
        );
        render_line(&scene, row, &mut line);
        assert_eq!(pixels, &line, "row {row}");
    }
}

#[test]
fn a_smaller_target_gets_the_visible_part_only() {
    // 160×120 scene into a 64×64 MockDisplay (which panics on out-of-bounds writes and on
    // drawing a pixel twice).
    let scene = Scene::<I16F16>::parse_as(DEFAULT, Rules::Fixray).unwrap();
    let mut display = MockDisplay::<Rgb888>::new();
    render(&scene, &mut display).unwrap();
    assert_eq!(
        display.affected_area(),
        Rectangle::new(Point::zero(), Size::new(64, 64))
    );
    // The same pixels as the full render's top-left corner.
    let mut line = vec![Rgb888::BLACK; 64];
    render_line(&scene, 10, &mut line);
    for (x, c) in line.iter().enumerate() {
        assert_eq!(
            display.get_pixel(Point::new(i32::try_from(x).unwrap(), 10)),
            Some(*c)
        );
    }
}

#[test]
fn framebuffer_targets_hold_the_same_picture() {
    const W: usize = 160;
    const H: usize = 120;
    let scene = Scene::<I16F16>::parse_as(DEFAULT, Rules::Fixray).unwrap();
    let mut fb =
        Framebuffer::<Rgb565, RawU16, LittleEndian, W, H, { buffer_size::<Rgb565>(W, H) }>::new();
    render(&scene, &mut fb).unwrap();
    let mut line = vec![Rgb565::BLACK; W];
    for row in [0u16, 37, 119] {
        render_line(&scene, row, &mut line);
        for (x, c) in line.iter().enumerate() {
            let p = Point::new(i32::try_from(x).unwrap(), i32::from(row));
            assert_eq!(fb.pixel(p), Some(*c), "{p:?}");
        }
    }
}

#[test]
fn render_line_leaves_pixels_outside_the_image_untouched() {
    let scene =
        Scene::<I16F16>::parse_as(&format!("{CAM4}background 1 1 1"), Rules::Fixray).unwrap();
    let mut line = [Rgb888::RED; 6];
    render_line(&scene, 0, &mut line);
    assert_eq!(
        line,
        [
            Rgb888::WHITE,
            Rgb888::WHITE,
            Rgb888::WHITE,
            Rgb888::WHITE,
            Rgb888::RED,
            Rgb888::RED
        ]
    );
    let mut line = [Rgb888::RED; 4];
    render_line(&scene, 4, &mut line); // row 4 of a 4-row image
    assert_eq!(line, [Rgb888::RED; 4]);
}

#[test]
fn diffuse_light_follows_the_formula() {
    // A wall at z = −5 facing the eye; a light 4 units in front of the hit point, on its
    // normal: cos = 1, dist = 4. diffuse 0.5 × emissivity 2 × 1 / 4 = 0.25 → 63.75 → 64.
    let text = "camera c { pixeldim 1 1 worlddim 1 1 viewpoint 0.5 0.5 5 }
        material m { diffuse 0.5 0.5 0.5 }
        light l { location 0.5 0.5 -1 emissivity 2 2 2 }
        plane wall { material m normal 0 0 1 point 0 0 -5 }";
    for (format, c) in top_left_pixel(text) {
        assert_eq!(c, Rgb888::new(64, 64, 64), "{format}");
    }
    // Ambient adds: 0.1 × 255 = 25.5, + 63.75 = 89.25 → 89.
    let text = text.replace(
        "diffuse 0.5 0.5 0.5",
        "diffuse 0.5 0.5 0.5 ambient 0.1 0.1 0.1",
    );
    for (format, c) in top_left_pixel(&text) {
        assert_eq!(c, Rgb888::new(89, 89, 89), "{format}");
    }
}

#[test]
fn a_strong_far_light_is_not_saturated_by_overflow() {
    // emissivity × diffuse × 255 overflows I16F16 unless the distance divides it first,
    // which would turn a dim pixel white. 200 × 1 × 1 / 1000 = 0.2 → 51.
    let text = "camera c { pixeldim 1 1 worlddim 1 1 viewpoint 0.5 3 5 }
        material m { diffuse 1 1 1 }
        light l { location 0.5 999 -3 emissivity 200 200 200 }
        plane p { material m normal 0 1 0 point 0 -1 0 }";
    for (format, c) in top_left_pixel(text) {
        assert_eq!(c, Rgb888::new(51, 51, 51), "{format}");
    }
}

/// The one pixel of a 1×1 scene in format `S`.
fn only_pixel<S: Scalar>(text: &str) -> Rgb888 {
    let scene = Scene::<S>::parse_as(text, Rules::Fixray).unwrap();
    let mut line = [Rgb888::BLACK];
    render_line(&scene, 0, &mut line);
    line[0]
}

#[test]
fn a_light_beyond_the_format_range_still_lights() {
    // The distance to this light (≈ 42000) does not fit I16F16, yet the light counts:
    // cos / dist is computed in two overflow-free divisions.
    // Hit (0.5, −1, −3); light (0.5, 29999, 29997): dist = 30000·√2 ≈ 42426, cos = 1/√2.
    // 30000 × 0.7071 / 42426 = 0.5 → 127.5: a tie, so only check it is lit, not dark.
    let text = "camera c { pixeldim 1 1 worlddim 1 1 viewpoint 0.5 3 5 }
        material m { diffuse 1 1 1 }
        light l { location 0.5 29999 29997 emissivity 30000 30000 30000 }
        plane p { material m normal 0 1 0 point 0 -1 0 }";
    // The pixel is emissivity × 255·cos/dist, and 255·cos/dist ≈ 0.0043 is formed with
    // two roundings (a product, a division) of up to one DELTA each: within
    // ½ + 30000 · 2 DELTA levels of the tie, in every format of the one list. I16F16
    // (1.4 levels) and the finer formats: 127 or 128. I20F12, which keeps only 17 DELTAs
    // of the quotient: 127.5 ± 15.
    fn tolerance<S: Scalar>() -> f64 {
        0.5 + 30000.0 * 2.0 * S::DELTA.to_f64()
    }
    for format in fixray::num::formats::FORMATS {
        let c = fixray::with_format!(format, only_pixel(text)).unwrap();
        let tolerance = fixray::with_format!(format, tolerance()).unwrap();
        assert!(
            (f64::from(c.r()) - 127.5).abs() <= tolerance,
            "{format}: {c:?}, tolerance {tolerance}"
        );
    }
}

#[test]
fn a_far_eye_does_not_lose_a_plane() {
    // N·b ≈ 42426 does not fit I16F16 although t ≈ 30000 and the hit do; the plane still
    // shows: D' − N·b is computed in one wide step.
    let text = "camera c { pixeldim 1 1 worlddim 32000 32000 viewpoint 30000 30000 5000 }
        material m { ambient 1 0 0 }
        plane p { material m normal 1 1 0 point 10000 10000 0 }";
    // Formats whose dot products round once (wide): `i16f16n`'s narrow dot products are
    // the overflow this guards against (`common::probes::dot_rounds_once`).
    fn wide<S: Scalar>() -> bool {
        common::probes::dot_rounds_once::<S>()
    }
    for (format, c) in top_left_pixel(text) {
        if fixray::with_format!(format, wide()).unwrap() {
            assert_eq!(c, Rgb888::RED, "{format}");
        }
    }
}
