//! Accuracy of one number format against another (normally the `f64` reference), pixel by
//! pixel: the pixels are those the renderer draws (a [`Frame`] per scene, line by line),
//! the hit errors those of the reference path's primary rays ([`Frame::trace_pixel`](crate::Frame::trace_pixel)), which is
//! what `t` and the hit point are defined by. No image and no line is stored: 64 columns
//! of each scene at a time (384 bytes of stack for both).
//!
//! ```
//! use fixray::{compare::compare, Scene, I16F16};
//!
//! let text = "camera c { pixeldim 8 6 worlddim 8 6 viewpoint 4 3 5 }
//!             material m { ambient 0.7 0.3 0.1 }
//!             plane p { material m normal 0 0 1 point 0 0 -5 }";
//! let fixed = Scene::<I16F16>::parse(text).unwrap();
//! let reference = Scene::<f64>::parse(text).unwrap();
//! let c = compare(&fixed, &reference, |_, _, _, _| {});
//! assert_eq!(c.pixels, 48);
//! assert_eq!(c.differing_pixels, 0);
//! assert!(c.max_dt < 1e-3);
//! ```

use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};

use crate::{AsView, Frame, Scalar, Traced};

/// How a render in one format differs from a reference render of the same scene.
///
/// ```
/// use fixray::compare::compare;
/// use fixray::{Scene, I16F16};
///
/// let text = include_str!("../scenes/default.scene");
/// let c = compare(&Scene::<I16F16>::parse(text)?, &Scene::<f64>::parse(text)?, |_, _, _, _| {});
/// assert_eq!(c.pixels, 160 * 120);
/// assert!(c.differing_share() < 0.05); // I16F16 draws the default scene as f64 does, nearly
/// assert!(c.psnr() > 40.0);
/// # Ok::<(), fixray::SceneError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Comparison {
    /// Pixels compared (the smaller of the two cameras).
    pub pixels: u32,
    /// Pixels where any channel differs.
    pub differing_pixels: u32,
    /// Largest difference of one channel, 0..=255.
    pub max_channel_error: u8,
    /// Sum over pixels and channels of the squared channel difference.
    pub squared_error: u64,
    /// Pixels whose primary rays see different objects (or one hits and one misses).
    pub object_disagreements: u32,
    /// Largest |Δt| in world units over pixels where both see the same object.
    pub max_dt: f64,
    /// Sum of |Δt| over those pixels (for the mean).
    pub sum_dt: f64,
    /// Largest distance between the two hit points, in world units, over those pixels.
    pub max_hit_error: f64,
    /// Sum of those distances (for the mean).
    pub sum_hit_error: f64,
    /// Number of pixels where both see the same object.
    pub same_object_pixels: u32,
}

impl Comparison {
    /// Share of pixels that differ, 0.0 ..= 1.0.
    pub fn differing_share(&self) -> f64 {
        if self.pixels == 0 {
            return 0.0;
        }
        f64::from(self.differing_pixels) / f64::from(self.pixels)
    }

    /// Peak signal-to-noise ratio in dB over all channels; infinite for identical images.
    pub fn psnr(&self) -> f64 {
        if self.squared_error == 0 || self.pixels == 0 {
            return f64::INFINITY;
        }
        // u64 → f64 rounds above 2^53 squared-error units, far beyond any image here.
        #[allow(clippy::cast_precision_loss)]
        let mse = self.squared_error as f64 / (3.0 * f64::from(self.pixels));
        10.0 * libm::log10(255.0 * 255.0 / mse)
    }

    /// Mean |Δt| in world units over pixels where both see the same object.
    pub fn mean_dt(&self) -> f64 {
        if self.same_object_pixels == 0 {
            return 0.0;
        }
        self.sum_dt / f64::from(self.same_object_pixels)
    }

    /// Mean hit-point distance in world units over pixels where both see the same object.
    pub fn mean_hit_error(&self) -> f64 {
        if self.same_object_pixels == 0 {
            return 0.0;
        }
        self.sum_hit_error / f64::from(self.same_object_pixels)
    }
}

/// The colour of a heat map of the error between two pixels: black where they are equal,
/// then blue → yellow → red for a largest channel error of 1 → 255 levels (log scale).
pub fn heat_color(pixel: Rgb888, reference: Rgb888) -> Rgb888 {
    let error = pixel
        .r()
        .abs_diff(reference.r())
        .max(pixel.g().abs_diff(reference.g()))
        .max(pixel.b().abs_diff(reference.b()));
    if error == 0 {
        return Rgb888::BLACK;
    }
    // 0 for 1 level, 1 for 256 levels, in sixteenths (integer arithmetic, no float).
    let t = (u8::BITS - error.leading_zeros()) * 2 - 2;
    let lerp = |a: u32, b: u32, s: u32, n: u32| -> u8 {
        let v = if b >= a {
            a + (b - a) * s / n
        } else {
            a - (a - b) * s / n
        };
        u8::try_from(v).unwrap_or(u8::MAX)
    };
    if t < 8 {
        Rgb888::new(lerp(40, 255, t, 8), lerp(60, 230, t, 8), lerp(255, 0, t, 8))
    } else {
        Rgb888::new(255, lerp(230, 0, t - 8, 8), 0)
    }
}

/// Columns compared at a time: the pure-geometry kernel's block (a multiple of the fast
/// kernel's resync step), so that each chunk is drawn exactly as `render_line` draws it.
const CHUNK: usize = crate::kernel::flat::BLOCK;
const _: () = assert!(CHUNK.is_multiple_of(crate::kernel::fast::RESYNC_PIXELS as usize));

/// Renders both scenes and compares them (the pixels [`crate::render`] draws, the hits of
/// the reference path); `on_pixel(column, row, pixel,
/// reference_pixel)` sees every pair (for a heat map), row by row.
pub fn compare<S: Scalar, R: Scalar>(
    scene: &impl AsView<S>,
    reference: &impl AsView<R>,
    mut on_pixel: impl FnMut(u16, u16, Rgb888, Rgb888),
) -> Comparison {
    let (scene, reference) = (&scene.view(), &reference.view());
    let mut c = Comparison::default();
    let width = scene.camera.width.min(reference.camera.width);
    let height = scene.camera.height.min(reference.camera.height);
    let (frame, ref_frame) = (Frame::<S>::new(scene), Frame::<R>::new(reference));
    let (mut chunk, mut ref_chunk) = ([Rgb888::BLACK; CHUNK], [Rgb888::BLACK; CHUNK]);
    for row in 0..height {
        for column in 0..width {
            let at = usize::from(column) % CHUNK;
            if at == 0 {
                frame.render_chunk(row, column, &mut chunk);
                ref_frame.render_chunk(row, column, &mut ref_chunk);
            }
            let Traced { hit, .. } = frame.trace_pixel(column, row);
            let Traced { hit: ref_hit, .. } = ref_frame.trace_pixel(column, row);
            let (px, ref_px) = (chunk[at], ref_chunk[at]);
            match (hit, ref_hit) {
                (Some((i, h)), Some((j, g))) if i == j => {
                    let dt = libm::fabs(h.t.to_f64() - g.t.to_f64());
                    let (p, q) = (h.point.to_f64(), g.point.to_f64());
                    let d = [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
                    let dist = libm::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
                    c.max_hit_error = c.max_hit_error.max(dist);
                    c.sum_hit_error += dist;
                    c.max_dt = c.max_dt.max(dt);
                    c.sum_dt += dt;
                    c.same_object_pixels += 1;
                }
                (None, None) => {}
                _ => c.object_disagreements += 1,
            }
            let diffs = [
                px.r().abs_diff(ref_px.r()),
                px.g().abs_diff(ref_px.g()),
                px.b().abs_diff(ref_px.b()),
            ];
            if diffs != [0; 3] {
                c.differing_pixels += 1;
            }
            for d in diffs {
                c.max_channel_error = c.max_channel_error.max(d);
                c.squared_error += u64::from(d) * u64::from(d);
            }
            c.pixels += 1;
            on_pixel(column, row, px, ref_px);
        }
    }
    c
}
