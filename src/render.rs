//! Streaming renderer: one scanline at a time into any `embedded-graphics` [`DrawTarget`].
//!
//! # RAM
//! The library keeps no framebuffer. [`render`] hands each scanline to the target's
//! `fill_contiguous` as an iterator that traces one pixel per step, so its RAM is O(1)
//! beyond the scene: no line buffer at all. [`render_line`] fills a caller's buffer of
//! `width` pixels (O(width), the caller's RAM), for drivers that want whole lines.
//!
//! # Shading
//! A pixel shows the object with the smallest accepted `t` along its primary ray, or the
//! background. Its colour is the material's ambient colour plus, for every light not in
//! shadow, `diffuse × emissivity × max(0, N·L) / dist` (see `scene-format.md`). Lighting
//! work is done only when the scene has lights; a scene without lights costs one
//! intersection per object per pixel and nothing more.

use embedded_graphics_core::pixelcolor::{PixelColor, Rgb888};
use embedded_graphics_core::prelude::{DrawTarget, Point, Size};
use embedded_graphics_core::primitives::Rectangle;

use crate::{Color, Hit, Object, Ray, RayKind, Scalar, Scene, Vec3};

/// The nearest accepted hit of a ray among the scene's objects, with the object's index.
pub fn nearest_hit<S: Scalar>(scene: &Scene<S>, ray: &Ray<S>) -> Option<(usize, Hit<S>)> {
    let mut best: Option<(usize, Hit<S>)> = None;
    for (i, object) in scene.objects.iter().enumerate() {
        if let Ok(hit) = object.shape.intersect(ray, scene.epsilon)
            && best.is_none_or(|(_, b)| hit.t < b.t)
        {
            best = Some((i, hit));
        }
    }
    best
}

/// Whether an object other than `except` lies on the segment from `ray.base` to
/// `ray.base + dist·ray.dir` (a shadow test: the first hit is enough).
///
/// A plane cannot shadow its own points, so the object the ray leaves is skipped instead
/// of offsetting the base by a tolerance; hits at `t = 0` (the ray starts on another
/// object, at a crease) do not count either.
pub fn occludes<S: Scalar>(scene: &Scene<S>, ray: &Ray<S>, dist: S, except: usize) -> bool {
    scene.objects.iter().enumerate().any(|(i, object)| {
        i != except
            && object
                .shape
                .intersect(ray, scene.epsilon)
                .is_ok_and(|hit| hit.t > S::ZERO && hit.t < dist)
    })
}

/// Adds two non-negative colour terms; a sum beyond the format saturates (it is far above
/// 255 channel units, so the pixel is at full intensity either way).
fn add_sat<S: Scalar>(a: S, b: S) -> S {
    a.checked_add(b).unwrap_or(S::MAX)
}

/// The colour of a hit on `objects[index]`, lit by the scene's lights, in channel units.
///
/// Per light: `255 × diffuse × emissivity × cos / dist`, evaluated as
/// `emissivity × cos` (≤ emissivity, cos ≤ 1), divided by the distance in its two
/// overflow-free parts ([`crate::Normalized::divide`]), times the diffuse reflectance,
/// times 255. A product that overflows is far above 255 and saturates; a light exactly at
/// the hit point gives no direction and lights nothing there.
pub fn shade<S: Scalar>(scene: &Scene<S>, ray: &Ray<S>, index: usize, hit: &Hit<S>) -> Color<S> {
    let Some(object): Option<&Object<S>> = scene.objects.get(index) else {
        return scene.background;
    };
    let Some(material) = scene.materials.get(usize::from(object.material)) else {
        return [S::ZERO; 3];
    };
    let mut color = material.ambient;
    if scene.lights.is_empty() || material.diffuse == [S::ZERO; 3] {
        return color;
    }
    let channel_max = S::from_i32(255).unwrap_or(S::MAX);
    // The normal facing the incoming ray.
    let mut normal = object.shape.normal_at(hit.point);
    if normal.dot(ray.dir).is_some_and(|d| d > S::ZERO) {
        normal = Vec3::ZERO.diff(normal).unwrap_or(normal);
    }
    for light in &scene.lights {
        let Some(to_light) = light.location.diff(hit.point).and_then(Vec3::normalize) else {
            continue;
        };
        let Some(cos) = normal.dot(to_light.unit).filter(|c| *c > S::ZERO) else {
            continue;
        };
        let shadow_ray = Ray {
            base: hit.point,
            dir: to_light.unit,
            kind: RayKind::Secondary,
        };
        // The distance itself may not fit (a far light): then nothing lies beyond it.
        let dist = to_light.length().unwrap_or(S::MAX);
        if occludes(scene, &shadow_ray, dist, index) {
            continue;
        }
        for ((c, diffuse), emissivity) in
            color.iter_mut().zip(material.diffuse).zip(light.emissivity)
        {
            let term = emissivity
                .checked_mul(cos)
                .and_then(|ec| to_light.divide(ec))
                .and_then(|irradiance| irradiance.checked_mul(diffuse))
                .and_then(|k| k.checked_mul(channel_max))
                .unwrap_or(S::MAX);
            *c = add_sat(*c, term);
        }
    }
    color
}

/// Converts a colour in channel units to a pixel: `round(clamp(c, 0, 255))` per channel,
/// ties away from zero.
pub fn to_rgb888<S: Scalar>(c: Color<S>) -> Rgb888 {
    let channel = |v: S| -> u8 {
        let max = S::from_i32(255).unwrap_or(S::MAX);
        let v = v.max(S::ZERO).min(max);
        v.round_to_i32()
            .and_then(|i| u8::try_from(i).ok())
            .unwrap_or(u8::MAX)
    };
    Rgb888::new(channel(c[0]), channel(c[1]), channel(c[2]))
}

/// What a primary ray found: the nearest hit (object index and hit) and the colour.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Traced<S> {
    /// The nearest accepted hit, or `None` for the background.
    pub hit: Option<(usize, Hit<S>)>,
    /// The colour in channel units.
    pub color: Color<S>,
}

/// Traces one ray: its nearest hit and colour.
pub fn trace<S: Scalar>(scene: &Scene<S>, ray: &Ray<S>) -> Traced<S> {
    let hit = nearest_hit(scene, ray);
    let color = match &hit {
        Some((i, h)) => shade(scene, ray, *i, h),
        None => scene.background,
    };
    Traced { hit, color }
}

/// Traces the primary ray of pixel (`column`, `row`), row 0 at the top. A ray that cannot
/// be formed in the format (see [`crate::Camera::primary_ray`]) sees the background.
pub fn trace_pixel<S: Scalar>(scene: &Scene<S>, column: u16, row: u16) -> Traced<S> {
    trace_at(scene, column, scene.camera.screen_y(row))
}

/// Traces pixel `column` of the scanline whose screen y is `y` (computed once per row).
fn trace_at<S: Scalar>(scene: &Scene<S>, column: u16, y: Option<S>) -> Traced<S> {
    match y.and_then(|y| scene.camera.primary_ray_at(column, y)) {
        Some(ray) => trace(scene, &ray),
        None => Traced {
            hit: None,
            color: scene.background,
        },
    }
}

/// The colour of pixel (`column`, `row`), row 0 at the top.
pub fn pixel<S: Scalar>(scene: &Scene<S>, column: u16, row: u16) -> Rgb888 {
    to_rgb888(trace_pixel(scene, column, row).color)
}

/// Iterates over the pixels of scanline `row`, tracing each one when it is asked for.
fn scanline<S: Scalar, C: From<Rgb888>>(
    scene: &Scene<S>,
    row: u16,
    columns: core::ops::Range<u16>,
) -> impl Iterator<Item = C> + '_ {
    let y = scene.camera.screen_y(row);
    columns.map(move |column| C::from(to_rgb888(trace_at(scene, column, y).color)))
}

/// Renders scanline `row` into `line`: pixel `i` of `line` is column `i`. Columns beyond
/// the camera's width (or beyond `line`) are left untouched; a row beyond the camera's
/// height leaves `line` untouched.
///
/// ```
/// use embedded_graphics::pixelcolor::Rgb565;
/// use fixray::{render_line, Scene, I16F16};
///
/// let scene = Scene::<I16F16>::parse(
///     "camera c { pixeldim 4 2 worlddim 4 2 viewpoint 2 1 5 } background 0 0 1",
/// )
/// .unwrap();
/// let mut line = [Rgb565::new(0, 0, 0); 4];
/// render_line(&scene, 0, &mut line);
/// assert_eq!(line, [Rgb565::new(0, 0, 31); 4]);
/// ```
pub fn render_line<S: Scalar, C: From<Rgb888>>(scene: &Scene<S>, row: u16, line: &mut [C]) {
    if row >= scene.camera.height {
        return;
    }
    let width = u16::try_from(line.len())
        .unwrap_or(u16::MAX)
        .min(scene.camera.width);
    for (slot, color) in line.iter_mut().zip(scanline(scene, row, 0..width)) {
        *slot = color;
    }
}

/// Renders the scene into `target`, one `fill_contiguous` call per scanline, top to bottom.
///
/// The image covers the rectangle `(0, 0)`–`(width, height)` of the camera's `pixeldim`,
/// cut to the target's bounding box: only visible pixels are traced, each written once.
///
/// # Errors
/// The target's own error, from the first scanline it refused.
///
/// ```
/// use embedded_graphics::{mock_display::MockDisplay, pixelcolor::Rgb888};
/// use fixray::{render, Scene, I16F16};
///
/// let scene = Scene::<I16F16>::parse(
///     "camera c { pixeldim 3 2 worlddim 3 2 viewpoint 1.5 1 5 } background 1 0 0",
/// )
/// .unwrap();
/// let mut display = MockDisplay::<Rgb888>::new();
/// render(&scene, &mut display).unwrap();
/// display.assert_pattern(&["RRR", "RRR"]);
/// ```
pub fn render<S, D>(scene: &Scene<S>, target: &mut D) -> Result<(), D::Error>
where
    S: Scalar,
    D: DrawTarget,
    D::Color: PixelColor + From<Rgb888>,
{
    let full = Rectangle::new(
        Point::zero(),
        Size::new(
            u32::from(scene.camera.width),
            u32::from(scene.camera.height),
        ),
    );
    let area = full.intersection(&target.bounding_box());
    let Some(bottom_right) = area.bottom_right() else {
        return Ok(());
    };
    // Both corners lie inside `full`, whose coordinates fit u16.
    let to_u16 = |v: i32| u16::try_from(v).unwrap_or(0);
    let (x0, x1) = (to_u16(area.top_left.x), to_u16(bottom_right.x));
    for row in to_u16(area.top_left.y)..=to_u16(bottom_right.y) {
        let line = Rectangle::new(
            Point::new(area.top_left.x, i32::from(row)),
            Size::new(area.size.width, 1),
        );
        target.fill_contiguous(&line, scanline(scene, row, x0..x1 + 1))?;
    }
    Ok(())
}
