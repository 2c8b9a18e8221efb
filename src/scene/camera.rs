//! The camera: the one place that maps a pixel to the screen window and to its primary ray.

use crate::{Ray, RayKind, Scalar, Vec3};

/// The camera: image size, screen window and eye.
///
/// [`Scene::parse`](crate::Scene::parse) refuses a window whose pixel pitch the number
/// format cannot resolve ([`MIN_SCALE_DELTAS`](crate::scene::MIN_SCALE_DELTAS)); a camera
/// built in code is taken as it is.
///
/// ```
/// use fixray::{Scalar, Scene, I16F16};
///
/// let scene = Scene::<I16F16>::parse(
///     "rules fixray  camera c { pixeldim 4 2 worlddim 8 4 viewpoint 4 2 5 }",
/// )?;
/// let camera = &scene.camera;
/// assert_eq!((camera.width, camera.height), (4, 2));
/// // Pixel (0, 0) looks through the centre of its cell, (1, 3) on the screen z = 0.
/// assert_eq!(camera.screen_x(0), Some(I16F16::ONE));
/// assert_eq!(camera.screen_y(0), Some(I16F16::from_num(3)));
/// let ray = camera.primary_ray(0, 0).unwrap();
/// assert_eq!(ray.base, camera.viewpoint);
/// # Ok::<(), fixray::SceneError>(())
/// ```
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
///
/// ```
/// use fixray::scene::{PixelGrid, Rules};
/// use fixray::{Scene, I16F16};
///
/// let text = "camera c { pixeldim 4 3 worlddim 8 4 viewpoint 4 2 5 }";
/// let course = Scene::<I16F16>::parse_as(text, Rules::Course)?;
/// let ours = Scene::<I16F16>::parse_as(text, Rules::Fixray)?;
/// assert_eq!(course.camera.grid, PixelGrid::Corners);
/// assert_eq!(ours.camera.grid, PixelGrid::Centres);
/// // The last of 4 columns: the window's right edge, or the middle of the last cell.
/// assert_eq!(course.camera.screen_x(3), Some(I16F16::from_num(8)));
/// assert_eq!(ours.camera.screen_x(3), Some(I16F16::from_num(7)));
/// # Ok::<(), fixray::SceneError>(())
/// ```
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

    /// The unit `u` of the screen x coordinates when every column's is a whole multiple
    /// of it, in a format whose products are exact (`KernelArith::EXACT_PRODUCTS`): the
    /// window's width divides exactly (`u·2W = WX` on the pixel-centre grid, `u·(W − 1) =
    /// WX` on the corner grid), so that [`Camera::screen_x`] is `u·(2i + 1)` (or `u·i`),
    /// bit for bit ([`Camera::screen_x_in`]): a product where it is otherwise a division
    /// (a 128-pixel row 8 units wide in I16F16, say). `None` otherwise.
    pub(crate) fn x_unit(&self) -> Option<S> {
        let w = i32::from(self.width);
        let den = match self.grid {
            PixelGrid::Centres => 2 * w,
            PixelGrid::Corners => w - 1,
        };
        let u = self.world_width.mul_ratio(1, den).filter(|_| den > 0)?;
        (S::EXACT_PRODUCTS && u.checked_mul_int(den) == Some(self.world_width)).then_some(u)
    }

    /// [`Camera::screen_x`] given [`Camera::x_unit`]'s `unit` (`None`: as `screen_x`).
    /// With a unit there is no remainder in `mul_ratio`'s division: its quotient times
    /// the column's numerator is the same value, checked the same way.
    #[inline]
    pub(crate) fn screen_x_in(&self, unit: Option<S>, column: u16) -> Option<S> {
        let Some(u) = unit else {
            return self.screen_x(column);
        };
        let i = i32::from(column);
        match self.grid {
            PixelGrid::Centres => u.checked_mul_int(2 * i + 1),
            PixelGrid::Corners => u.checked_mul_int(i),
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{I16F16, I20F12, I32F32};

    /// `screen_x_in` with the camera's unit is `screen_x` at every column, for windows
    /// that divide exactly and ones that do not, both grids, the fixed formats; floats
    /// have no unit.
    fn screen_x_by_unit<S: Scalar>() -> usize {
        let mut exact = 0;
        for width in [1u16, 2, 3, 7, 64, 100, 128, 160, 320, 640] {
            for ww in [1.0, 3.0, 4.0, 8.0, 10.0, 12.5, 0.75] {
                for grid in [PixelGrid::Centres, PixelGrid::Corners] {
                    let camera = Camera {
                        width,
                        height: 4,
                        world_width: S::from_f64(ww).unwrap(),
                        world_height: S::ONE,
                        viewpoint: Vec3::new(S::ONE, S::ONE, S::ONE),
                        grid,
                    };
                    let unit = camera.x_unit();
                    exact += usize::from(unit.is_some());
                    for column in 0..width {
                        assert_eq!(
                            camera.screen_x_in(unit, column),
                            camera.screen_x(column),
                            "{} {width} px, {ww} wide, {grid:?}, column {column}",
                            S::NAME
                        );
                    }
                }
            }
        }
        exact
    }

    #[test]
    fn screen_x_by_the_unit_is_screen_x() {
        // 8 units over 128 pixels (boing) divides in every fixed format.
        assert!(screen_x_by_unit::<I16F16>() > 10);
        assert!(screen_x_by_unit::<I20F12>() > 10);
        assert!(screen_x_by_unit::<I32F32>() > 10);
        assert_eq!(screen_x_by_unit::<f32>(), 0);
    }
}
