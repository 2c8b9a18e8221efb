//! [`Counters`]: rays and stage evaluations, counted with the `stats` feature, for the
//! counted forms of the renderer ([`Frame::draw_counted`](crate::Frame::draw_counted),
//! [`Frame::render_line_counted`](crate::Frame::render_line_counted)).

/// Rays and stage evaluations of a frame (or line), counted when the crate is built with
/// the `stats` feature (otherwise every count stays 0 and costs nothing).
///
/// ```
/// use embedded_graphics::{mock_display::MockDisplay, pixelcolor::Rgb888};
/// use fixray::stats::Counters;
/// use fixray::{Frame, Scene, I16F16};
///
/// let scene = Scene::<I16F16>::parse(
///     "rules fixray
///      camera c { pixeldim 4 2 worlddim 4 2 viewpoint 2 1 5 }
///      material m { ambient 0.2 0.2 0.2 diffuse 0.8 0.8 0.8 }
///      plane floor { material m normal 0 1 0 point 0 -1 0 }
///      light lamp { location 2 3 -2 emissivity 1 1 1 }",
/// )?;
/// let mut counters = Counters::default();
/// Frame::new(&scene).draw_counted(&mut MockDisplay::<Rgb888>::new(), &mut counters)?;
/// if cfg!(feature = "stats") {
///     assert_eq!(counters.primary_rays, 8); // one a pixel
/// } else {
///     assert_eq!(counters, Counters::default()); // nothing counted, nothing spent
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Counters {
    /// Primary rays traced.
    pub primary_rays: u32,
    /// Shadow rays traced.
    pub shadow_rays: u32,
    /// Reflected rays traced.
    pub reflection_rays: u32,
    /// Diffuse terms evaluated (per light per hit).
    pub diffuse: u32,
    /// Specular terms evaluated (per light per hit).
    pub specular: u32,
    /// Spotlight cone tests.
    pub cone_tests: u32,
    /// Checkerboard tile lookups.
    pub tile_lookups: u32,
    /// Rays transmitted through translucent surfaces (course rules).
    pub transmitted_rays: u32,
    /// Texel lookups of projectors.
    pub texel_lookups: u32,
    /// Blocks' corners traced by a frame sampled in blocks (`Frame::with_sampling`).
    pub corners: u32,
}

#[inline(always)]
pub(crate) fn count(field: &mut u32) {
    if cfg!(feature = "stats") {
        *field = field.wrapping_add(1);
    }
}

/// Adds `n` to a count (with the `stats` feature): a sampled frame's corners.
#[cfg(feature = "sampling")]
#[inline(always)]
pub(crate) fn count_n(field: &mut u32, n: u32) {
    if cfg!(feature = "stats") {
        *field = field.wrapping_add(n);
    }
}

/// Counts `n` primary rays at once (the pure-geometry kernel's scanlines).
#[inline(always)]
pub(crate) fn count_primary(counters: &mut Counters, n: u16) {
    if cfg!(feature = "stats") {
        counters.primary_rays = counters.primary_rays.wrapping_add(u32::from(n));
    }
}
