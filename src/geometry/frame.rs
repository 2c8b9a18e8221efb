//! A plane with coordinates on it: what tiled planes (checkerboards) and finite planes
//! (rectangles) are built on.

use super::{Plane, PlaneError, Vec3};
use crate::Scalar;

/// Why a tiled or finite plane cannot be built.
///
/// ```
/// use fixray::geometry::{PlaneFrame, PlaneFrameError, Vec3};
/// use fixray::{Scalar, I16F16};
///
/// let v = |x, y, z| Vec3::<I16F16>::from_f64([x, y, z]).unwrap();
/// let (up, origin, one) = (v(0.0, 1.0, 0.0), v(0.0, 0.0, 0.0), I16F16::ONE);
/// // `xdir` along the normal has no direction in the plane.
/// assert_eq!(PlaneFrame::new(up, origin, up, [one; 2]), Err(PlaneFrameError::XdirInvalid));
/// let (x, flat) = (v(1.0, 0.0, 0.0), [one, I16F16::ZERO]);
/// assert_eq!(PlaneFrame::new(up, origin, x, flat), Err(PlaneFrameError::NonPositiveSize));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PlaneFrameError {
    /// The plane itself cannot be built.
    Plane(PlaneError),
    /// `xdir` has no component in the plane (zero, or parallel to the normal).
    XdirInvalid,
    /// A tile or side length is not positive.
    NonPositiveSize,
}

/// How a tiled plane lays out its checkerboard.
///
/// ```
/// use fixray::geometry::{Shape, Tiling};
/// use fixray::{Scene, I16F16};
///
/// let text = "camera c { pixeldim 8 6 worlddim 8 6 viewpoint 4 3 5 }
///     material a { ambient 1 0 0 }  material b { ambient 0 0 1 }
///     tiled_plane t { material a normal 0 1 0 point 0 0 0 dimension 1 1 altmaterial b }";
/// let tiling = |text: &str| match Scene::<I16F16>::parse(text).unwrap().objects[0].shape {
///     Shape::Tiled { tiling, .. } => tiling,
///     _ => unreachable!(),
/// };
/// assert_eq!(tiling(text), Tiling::WorldXz); // no `xdir`: the course's older form
/// assert_eq!(tiling(&text.replace("altmaterial b", "altmaterial b xdir 1 0 0")), Tiling::Frame);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Tiling {
    /// Along the frame's `u` and `v` (`xdir` given): tile `(floor(a / W), floor(b / H))`
    /// with the plane coordinates from the corner (`fixray` rules) or from the world
    /// origin (`course` rules).
    Frame,
    /// The course's older form without `xdir`: tiles on world x and z,
    /// `(trunc((x + 10000) / W), trunc((z + 10000) / H))`, whatever the normal.
    WorldXz,
}

/// A plane with coordinates: the corner `point`, `u` = unit(xdir projected into the plane),
/// `v` = unit(N × u), and two lengths along them. Tiled planes (tile size) and finite
/// planes (side lengths) are built on it. The plane coordinates of a point `p` are
/// `a = (p − point)·u`, `b = (p − point)·v`.
///
/// ```
/// use fixray::geometry::{PlaneFrame, Vec3};
/// use fixray::I16F16;
///
/// let v = |x, y, z| Vec3::<I16F16>::from_f64([x, y, z]).unwrap();
/// // The floor y = 0 from the origin, u along x (so v = N × u = −z), tiles of 1 × 1.
/// let (up, origin, x) = (v(0.0, 1.0, 0.0), v(0.0, 0.0, 0.0), v(1.0, 0.0, 0.0));
/// let floor = PlaneFrame::new(up, origin, x, [I16F16::from_num(1); 2]).unwrap();
/// let p = v(2.5, 0.0, -1.5);
/// assert_eq!(floor.coords(p), Some((I16F16::from_num(2.5), I16F16::from_num(1.5))));
/// assert_eq!(floor.odd_tile(p), Some(true)); // floor(2.5) + floor(1.5) = 3
/// assert!(!floor.contains(p)); // as a rectangle it is 1 × 1
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneFrame<S> {
    plane: Plane<S>,
    corner: Vec3<S>,
    u: Vec3<S>,
    v: Vec3<S>,
    size: [S; 2],
}

impl<S: Scalar> PlaneFrame<S> {
    /// Builds the frame.
    ///
    /// # Errors
    /// [`PlaneFrameError`] for a zero normal, an offset out of range, an `xdir` with no
    /// component in the plane, or a non-positive size.
    pub fn new(
        normal: Vec3<S>,
        point: Vec3<S>,
        xdir: Vec3<S>,
        size: [S; 2],
    ) -> Result<Self, PlaneFrameError> {
        let plane = Plane::new(normal, point).map_err(PlaneFrameError::Plane)?;
        if size[0] <= S::ZERO || size[1] <= S::ZERO {
            return Err(PlaneFrameError::NonPositiveSize);
        }
        let n = plane.normal();
        let along = n.dot(xdir).ok_or(PlaneFrameError::XdirInvalid)?;
        let u = n
            .scale(along)
            .and_then(|p| xdir.diff(p))
            .and_then(Vec3::unit)
            .ok_or(PlaneFrameError::XdirInvalid)?;
        let v = n
            .cross(u)
            .and_then(Vec3::unit)
            .ok_or(PlaneFrameError::XdirInvalid)?;
        Ok(Self {
            plane,
            corner: point,
            u,
            v,
            size,
        })
    }

    /// The underlying infinite plane.
    pub fn plane(&self) -> &Plane<S> {
        &self.plane
    }

    /// The tile or side lengths along `u` and `v`.
    pub fn size(&self) -> [S; 2] {
        self.size
    }

    /// The corner the plane coordinates start from (the scene's `point`).
    pub fn corner(&self) -> Vec3<S> {
        self.corner
    }

    /// The unit direction `u` of the first plane coordinate (`xdir` in the plane).
    pub fn u(&self) -> Vec3<S> {
        self.u
    }

    /// The plane coordinates `(a, b)` of a point.
    pub fn coords(&self, p: Vec3<S>) -> Option<(S, S)> {
        let q = p.diff(self.corner)?;
        Some((q.dot_axis(self.u)?, q.dot_axis(self.v)?))
    }

    /// Whether a point lies on the checkerboard's odd squares:
    /// `floor(a / W) + floor(b / H)` odd.
    pub fn odd_tile(&self, p: Vec3<S>) -> Option<bool> {
        let (i, j) = self.tile(p)?;
        Some((i.wrapping_add(j)) & 1 == 1)
    }

    /// The tile `(floor(a / W), floor(b / H))` a point lies on ([`PlaneFrame::odd_tile`]'s).
    pub(crate) fn tile(&self, p: Vec3<S>) -> Option<(i32, i32)> {
        let (a, b) = self.coords(p)?;
        Some((tile_index(a, self.size[0])?, tile_index(b, self.size[1])?))
    }

    /// The tile row `floor(b / H)` of every point of the line `(x, y, z)`, any `x` (a
    /// scanline's hits on a plane with `N.x = 0`), when `v` has no x component, so that
    /// `b` is the same along the line (bit for bit: `0·q.x` adds nothing); `None`
    /// otherwise, or when it does not fit.
    pub(crate) fn tile_row(&self, y: S, z: S) -> Option<i32> {
        if self.v.x != S::ZERO {
            return None;
        }
        let q = Vec3::new(
            S::ZERO,
            y.checked_sub(self.corner.y)?,
            z.checked_sub(self.corner.z)?,
        );
        tile_index(q.dot_axis(self.v)?, self.size[1])
    }

    /// [`PlaneFrame::odd_tile`] of `p` with its tile row `j` known ([`PlaneFrame::tile_row`]
    /// of its `y` and `z`): one coordinate per point.
    pub(crate) fn odd_tile_in_row(&self, p: Vec3<S>, j: i32) -> Option<bool> {
        let i = tile_index(p.diff(self.corner)?.dot_axis(self.u)?, self.size[0])?;
        Some((i.wrapping_add(j)) & 1 == 1)
    }

    /// [`PlaneFrame::odd_tile_in_row`] for the hits of one scanline, which share `y`, `z`
    /// and the tile row `j` ([`RowTiles`]): `None` unless `u` lies along the world's x
    /// axis (then the point's coordinate is `±(x − corner.x)` exactly, as `dot_axis`
    /// takes it) and the row's `y − corner.y` and `z − corner.z` fit the format (where
    /// they do not, every point of the row has no tile; callers take the general lookup).
    pub(crate) fn row_tiles(&self, y: S, z: S, j: i32) -> Option<RowTiles<S>> {
        let u = self.u;
        (u.y == S::ZERO && u.z == S::ZERO).then_some(())?;
        let negate = if u.x == S::ONE {
            false
        } else if u.x.checked_neg() == Some(S::ONE) {
            true
        } else {
            return None;
        };
        y.checked_sub(self.corner.y)?;
        z.checked_sub(self.corner.z)?;
        Some(RowTiles {
            corner_x: self.corner.x,
            negate,
            size: self.size[0],
            j,
        })
    }

    /// The course's checkerboard of the frame's axes, anchored at the world origin:
    /// `floor(p·u / W) + floor(p·v / H)` odd.
    pub fn odd_tile_from_origin(&self, p: Vec3<S>) -> Option<bool> {
        let i = tile_index(p.dot_axis(self.u)?, self.size[0])?;
        let j = tile_index(p.dot_axis(self.v)?, self.size[1])?;
        Some((i.wrapping_add(j)) & 1 == 1)
    }

    /// The course's older checkerboard on world x and z:
    /// `trunc((x + 10000) / W) + trunc((z + 10000) / H)` odd (the same as `floor` for
    /// x, z > −10000, where it is used).
    pub fn odd_tile_world_xz(&self, p: Vec3<S>) -> Option<bool> {
        let (i, j) = self.tile_world_xz(p)?;
        Some((i.wrapping_add(j)) & 1 == 1)
    }

    /// The tile of [`PlaneFrame::odd_tile_world_xz`]'s checkerboard a point lies on.
    pub(crate) fn tile_world_xz(&self, p: Vec3<S>) -> Option<(i32, i32)> {
        let shift = S::from_i32(10_000)?;
        let i = tile_index(p.x.checked_add(shift)?, self.size[0])?;
        let j = tile_index(p.z.checked_add(shift)?, self.size[1])?;
        Some((i, j))
    }

    /// Whether a point lies inside the rectangle `0 <= a <= W`, `0 <= b <= H`.
    pub fn contains(&self, p: Vec3<S>) -> bool {
        self.coords(p).is_some_and(|(a, b)| {
            a >= S::ZERO && a <= self.size[0] && b >= S::ZERO && b <= self.size[1]
        })
    }
}

/// A tiled plane's checkerboard along one scanline ([`PlaneFrame::row_tiles`]): what
/// [`PlaneFrame::odd_tile_in_row`] needs of the frame when `u` lies along the x axis,
/// one subtraction and the tile index per point instead of a vector difference and a
/// dot product (a level-plane row's pixels, `kernel/rows/`).
#[derive(Debug, Clone, Copy)]
pub(crate) struct RowTiles<S> {
    corner_x: S,
    /// `u` is `−x` (its coordinate is `corner.x − x`).
    negate: bool,
    size: S,
    j: i32,
}

impl<S: Scalar> RowTiles<S> {
    /// [`PlaneFrame::odd_tile_in_row`] of the row's point with this `x`, bit for bit.
    #[cfg(test)]
    pub(crate) fn odd(&self, x: S) -> Option<bool> {
        let i = self.column(x)?;
        Some((i.wrapping_add(self.j)) & 1 == 1)
    }

    /// The tile column `floor(±(x − corner.x) / W)` of the row's point with this `x`
    /// ([`RowTiles::odd`]'s): monotone in `x` (a difference, a sign, a truncated quotient
    /// and a floor), so two points of one tile column have every point between them in it.
    #[inline(always)]
    pub(crate) fn column(&self, x: S) -> Option<i32> {
        let a = x.checked_sub(self.corner_x)?;
        let a = if self.negate { a.checked_neg()? } else { a };
        tile_index(a, self.size)
    }

    /// Whether tile column `i` of the row is an odd tile ([`RowTiles::odd`]).
    #[inline(always)]
    pub(crate) fn odd_column(&self, i: i32) -> bool {
        (i.wrapping_add(self.j)) & 1 == 1
    }
}

/// How a texture lies on a [`Slide`]'s rectangle (the course's `mode`).
///
/// ```
/// # #[cfg(feature = "textures")] {
/// use fixray::geometry::{Shape, TexMode};
/// use fixray::{Scene, I16F16};
///
/// static CHECKER: &[u8] = b"P6 2 2 255\n\xff\xff\xff\x00\x00\x00\x00\x00\x00\xff\xff\xff";
/// let text = "camera c { pixeldim 4 3 worlddim 4 3 viewpoint 2 1.5 5 }
///     material m { ambient 1 1 1 }
///     texture checker { filename checker.ppm }
///     texplane wall { material m normal 0 0 1 point 0 0 -1 xdir 1 0 0
///                     dimensions 4 3 texname checker mode 1 }";
/// let mut scene = Scene::<I16F16>::empty();
/// scene.read_with(text, None, &mut |_| Some(CHECKER)).unwrap();
/// let Shape::Textured(slide) = scene.objects[0].shape else { unreachable!() };
/// assert_eq!((slide.mode, slide.texture), (TexMode::Tile, 0)); // `mode 1`: repeated
/// assert_eq!(slide.frame.size(), [I16F16::from_num(4), I16F16::from_num(3)]);
/// # }
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TexMode {
    /// `mode 0`: the texture is stretched over the rectangle.
    Fit,
    /// `mode 1`: the texture repeats, one texel per screen pixel's size in world units.
    Tile,
}

/// A rectangle of a plane with a texture on it: a textured plane (`texplane`) or a
/// projector's slide. The texture is the scene's `textures[texture]`.
///
/// ```
/// # #[cfg(feature = "textures")] {
/// use fixray::geometry::{Shape, Slide};
/// use fixray::{Scene, I16F16};
///
/// static CHECKER: &[u8] = b"P6 2 2 255\n\xff\xff\xff\x00\x00\x00\x00\x00\x00\xff\xff\xff";
/// let text = "camera c { pixeldim 4 3 worlddim 4 3 viewpoint 2 1.5 5 }
///     material m { ambient 1 1 1 }
///     texture checker { filename checker.ppm }
///     texplane wall { material m normal 0 0 1 point 0 0 -1 xdir 1 0 0
///                     dimensions 4 3 texname checker mode 0 }";
/// let mut scene = Scene::<I16F16>::empty();
/// scene.read_with(text, None, &mut |_| Some(CHECKER)).unwrap();
/// let Shape::Textured(Slide { frame, texture, .. }) = scene.objects[0].shape else {
///     unreachable!()
/// };
/// assert_eq!(scene.textures[usize::from(texture)].width(), 2);
/// assert!(frame.contains(fixray::geometry::Vec3::from_f64([1.0, 1.0, -1.0]).unwrap()));
/// # }
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Slide<S> {
    /// The rectangle.
    pub frame: PlaneFrame<S>,
    /// Index into the scene's textures.
    pub texture: u8,
    /// How the texture lies on it.
    pub mode: TexMode,
}

/// `floor(x / size)`, the tile a coordinate falls in. A tile of size 1 (the usual one)
/// takes no division: `x / 1` is `x` exactly in every format whose division is exact, so
/// the index is the same bit for bit, and two divisions (dear on the Cortex-M0:
/// `docs/performance.md`) are saved per tiled pixel. (`i16f16r`'s reciprocal division
/// returns `x − 1 DELTA` for `x / 1` (toward zero): without it, a whole-number
/// coordinate falls in its own tile, as in f64, not the one below.)
#[inline]
fn tile_index<S: Scalar>(x: S, size: S) -> Option<i32> {
    if size == S::ONE {
        x.floor_to_i32()
    } else {
        x.checked_div(size)?.floor_to_i32()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{I16F16, I20F12, I32F32};

    /// A row's tiles say what the frame's own lookup says at every `x`, for frames whose
    /// `u` is `+x` or `−x`, tiles of size 1 and not, a corner off the origin, and rows
    /// whose tile row is negative; frames whose `u` is not along x have none.
    fn row_tiles_agree<S: Scalar>() -> usize {
        let mut rows = 0;
        let v = |x: f64, y: f64, z: f64| {
            Vec3::new(
                S::from_f64(x).unwrap(),
                S::from_f64(y).unwrap(),
                S::from_f64(z).unwrap(),
            )
        };
        let frames = [
            (v(0.0, 1.0, 0.0), v(0.0, 0.0, 0.0), v(1.0, 0.0, 0.0), 1.0),
            (v(0.0, 1.0, 0.0), v(0.3, 0.0, -2.25), v(-1.0, 0.0, 0.0), 1.5),
            (
                v(0.0, 0.0, 1.0),
                v(-1.75, 0.5, -6.0),
                v(1.0, 0.0, 0.0),
                0.75,
            ),
            (v(0.0, -1.0, 0.0), v(2.0, 4.0, 1.0), v(-1.0, 0.0, 0.0), 2.0),
        ];
        for (normal, corner, xdir, size) in frames {
            let size = S::from_f64(size).unwrap();
            let frame = PlaneFrame::new(normal, corner, xdir, [size, size]).unwrap();
            for (y, z) in [(0.0, -3.3), (0.0, 7.9), (4.0, -0.2), (0.5, -6.0)] {
                let (y, z) = (S::from_f64(y).unwrap(), S::from_f64(z).unwrap());
                let Some(j) = frame.tile_row(y, z) else {
                    continue;
                };
                let Some(tiles) = frame.row_tiles(y, z, j) else {
                    // Only a frame whose `u` did not come out exactly `±x` (a format
                    // whose unit vectors round: `i16f16r`) has no row tiles.
                    let u = frame.u;
                    let along_x = u.y == S::ZERO
                        && u.z == S::ZERO
                        && (u.x == S::ONE || u.x.checked_neg() == Some(S::ONE));
                    assert!(!along_x, "{}: u {u:?} lies along x", S::NAME);
                    continue;
                };
                rows += 1;
                for k in -400..400 {
                    let x = S::from_f64(f64::from(k) * 0.0371).unwrap();
                    assert_eq!(
                        tiles.odd(x),
                        frame.odd_tile_in_row(Vec3::new(x, y, z), j),
                        "{} x={x:?} y={y:?} z={z:?}",
                        S::NAME
                    );
                }
            }
        }
        let slanted = PlaneFrame::new(
            v(0.0, 1.0, 0.0),
            v(0.0, 0.0, 0.0),
            v(1.0, 0.0, 1.0),
            [S::ONE, S::ONE],
        )
        .unwrap();
        assert!(slanted.row_tiles(S::ZERO, S::ZERO, 0).is_none());
        rows
    }

    #[test]
    fn row_tiles_are_the_frames_lookup() {
        // Every frame's `u` is exactly `±x` in these formats: every row is compared.
        let all = row_tiles_agree::<f64>();
        assert!(all >= 8, "{all}");
        assert_eq!(row_tiles_agree::<I16F16>(), all);
        assert_eq!(row_tiles_agree::<I20F12>(), all);
        assert_eq!(row_tiles_agree::<I32F32>(), all);
        assert_eq!(row_tiles_agree::<f32>(), all);
        // The variants: every row that has row tiles agrees.
        row_tiles_agree::<crate::num::variants::I16F16Narrow>();
        row_tiles_agree::<crate::num::variants::I16F16Recip>();
        row_tiles_agree::<crate::num::variants::F32Micro>();
    }
}
