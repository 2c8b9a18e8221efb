//! The camera: the one place that maps a pixel to the screen window and to its primary ray.

use crate::{Ray, RayKind, Scalar, Vec3};

/// The camera: image size, screen window and eye.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera<S> {
    /// Image width in pixels, `1..=4096`.
    pub width: u16,
    /// Image height in pixels, `1..=4096`.
    pub height: u16,
    /// Width of the screen window `[0, WX]` on the plane z = 0, in world units.
    pub world_width: S,
    /// Height of the screen window `[0, WY]`, in world units.
    pub world_height: S,
    /// The eye, `z > 0`.
    pub viewpoint: Vec3<S>,
}

impl<S: Scalar> Camera<S> {
    /// The primary ray through the centre of pixel (`column`, `row`), row 0 at the top:
    /// base = viewpoint, direction = unit(screen point − viewpoint) with the screen point
    /// `(WX (i + ½) / W, WY (1 − (j + ½) / H), 0)`.
    ///
    /// `None` when the direction cannot be formed in the format (the pixel then shows the
    /// background); never for a scene that [`Scene::parse`](crate::Scene::parse) accepted with an eye within
    /// the format's range of the screen.
    pub fn primary_ray(&self, column: u16, row: u16) -> Option<Ray<S>> {
        let y = self.screen_y(row)?;
        self.primary_ray_at(column, y)
    }

    /// The screen y coordinate of a pixel row (constant along a scanline),
    /// `WY (1 − (j + ½) / H)`, rounded once.
    #[inline]
    pub fn screen_y(&self, row: u16) -> Option<S> {
        let h = i32::from(self.height);
        let j = i32::from(row);
        self.world_height.mul_ratio(2 * (h - j) - 1, 2 * h)
    }

    /// The screen x coordinate of a pixel column, `WX (i + ½) / W`, rounded once: every
    /// kernel forms its primary rays from this (they must agree bit for bit).
    #[inline]
    pub fn screen_x(&self, column: u16) -> Option<S> {
        self.world_width
            .mul_ratio(2 * i32::from(column) + 1, 2 * i32::from(self.width))
    }

    /// The primary ray through pixel `column` of the scanline whose screen y is `y`.
    pub fn primary_ray_at(&self, column: u16, y: S) -> Option<Ray<S>> {
        let x = self.screen_x(column)?;
        let dir = Vec3::new(x, y, S::ZERO).diff(self.viewpoint)?.unit()?;
        Some(Ray {
            base: self.viewpoint,
            dir,
            kind: RayKind::Primary,
        })
    }
}
