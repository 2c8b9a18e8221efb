//! [`Counters`]: rays and stage evaluations, counted with the `stats` feature.

/// Rays and stage evaluations of a frame (or line), counted when the crate is built with
/// the `stats` feature (otherwise every count stays 0 and costs nothing).
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
}

#[inline(always)]
pub(crate) fn count(field: &mut u32) {
    if cfg!(feature = "stats") {
        *field = field.wrapping_add(1);
    }
}

/// Counts `n` primary rays at once (the pure-geometry kernel's scanlines).
#[inline(always)]
pub(crate) fn count_primary(counters: &mut Counters, n: u16) {
    if cfg!(feature = "stats") {
        counters.primary_rays = counters.primary_rays.wrapping_add(u32::from(n));
    }
}
