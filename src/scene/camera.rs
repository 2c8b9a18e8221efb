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
    /// Where pixels look through the window (set by the scene's [`crate::Rules`]).
    pub grid: PixelGrid,
}

/// Where pixel (i, j) looks through the screen window `[0, WX] × [0, WY]`, row 0 at the
/// top.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PixelGrid {
    /// Pixel centres, `(WX (i + ½) / W, WY (1 − (j + ½) / H))` (the `fixray` rules).
    Centres,
    /// The window's corners are pixels, `(WX i / (W − 1), WY (H − 1 − j) / (H − 1))` (the
    /// `course` rules; a single column or row looks through x = 0 or y = 0).
    Corners,
}

impl<S: Scalar> Camera<S> {
    /// The primary ray of pixel (`column`, `row`), row 0 at the top: base = viewpoint,
    /// direction = unit(screen point − viewpoint), the screen point as [`Camera::grid`]
    /// says (`(WX (i + ½) / W, WY (1 − (j + ½) / H), 0)` for pixel centres).
    ///
    /// `None` when the direction cannot be formed in the format (the pixel then shows the
    /// background); never for a scene that [`Scene::parse`](crate::Scene::parse) accepted with an eye within
    /// the format's range of the screen.
    pub fn primary_ray(&self, column: u16, row: u16) -> Option<Ray<S>> {
        let y = self.screen_y(row)?;
        self.primary_ray_at(column, y)
    }

    /// The screen y coordinate of a pixel row (constant along a scanline),
    /// `WY (1 − (j + ½) / H)` (or `WY (H − 1 − j) / (H − 1)` on the corner grid), rounded
    /// once.
    #[inline]
    pub fn screen_y(&self, row: u16) -> Option<S> {
        let h = i32::from(self.height);
        let j = i32::from(row);
        match self.grid {
            PixelGrid::Centres => self.world_height.mul_ratio(2 * (h - j) - 1, 2 * h),
            PixelGrid::Corners => corner(self.world_height, h - 1 - j, h - 1),
        }
    }

    /// The screen x coordinate of a pixel column, `WX (i + ½) / W` (or `WX i / (W − 1)`
    /// on the corner grid), rounded once: every kernel forms its primary rays from this
    /// (they must agree bit for bit).
    #[inline]
    pub fn screen_x(&self, column: u16) -> Option<S> {
        let i = i32::from(column);
        let w = i32::from(self.width);
        match self.grid {
            PixelGrid::Centres => self.world_width.mul_ratio(2 * i + 1, 2 * w),
            PixelGrid::Corners => corner(self.world_width, i, w - 1),
        }
    }

    /// The primary ray through pixel `column` of the scanline whose screen y is `y`.
    pub fn primary_ray_at(&self, column: u16, y: S) -> Option<Ray<S>> {
        self.pixel_ray_at(column, y).map(|p| p.ray)
    }

    /// [`Camera::primary_ray_at`] with the unnormalised direction it is made from.
    pub(crate) fn pixel_ray_at(&self, column: u16, y: S) -> Option<PixelRay<S>> {
        let x = self.screen_x(column)?;
        let toward = Vec3::new(x, y, S::ZERO).diff(self.viewpoint)?;
        Some(PixelRay {
            ray: Ray {
                base: self.viewpoint,
                dir: toward.unit()?,
                kind: RayKind::Primary,
            },
            toward,
        })
    }
}

/// A pixel's primary ray and the unnormalised direction it is made from, screen point −
/// viewpoint: exact to one rounding of the screen point, where the unit direction carries
/// the rounding of a normalisation (`course::trace_course` finds its textured planes'
/// points from it).
#[derive(Debug, Clone, Copy)]
pub(crate) struct PixelRay<S> {
    pub(crate) ray: Ray<S>,
    #[cfg_attr(not(feature = "course"), allow(dead_code))] // read by the course's rules only
    pub(crate) toward: Vec3<S>,
}

/// `size · k / n` on the corner grid; a single pixel (`n = 0`) looks through 0.
fn corner<S: Scalar>(size: S, k: i32, n: i32) -> Option<S> {
    if n <= 0 {
        Some(S::ZERO)
    } else {
        size.mul_ratio(k, n)
    }
}
