//! Animation: a scene's sphere moved along a bounce path, frame by frame, in the scene
//! itself (no re-parsing), so that a chip draws a moving ball from one parsed scene.
//!
//! A [`Bounce`] moves the first sphere of a scene. Frame `k` of `n` places its centre at
//!
//! ```text
//! x = x₀ + sway · (1 − |2k − n| / n)              out and back once per loop
//! y = y₀ + height · 4 p (n − p) / n²,  p = (k · bounces) mod n     a parabola per bounce
//! z = z₀
//! ```
//!
//! where `(x₀, y₀, z₀)` is the centre the scene file gives (the ball at rest, touching
//! the floor). Each offset is one [`Scalar::mul_ratio`] of integers (one rounding) added
//! to the rest position (exact in the fixed formats, a second rounding in the float
//! ones), the same operations on a host and on a chip: a frame's scene is the same bit
//! for bit on both, and the frames loop (frame `n` is frame 0).
//!
//! ```
//! use fixray::anim::Bounce;
//! use fixray::{Scalar, Scene, I16F16};
//! use fixray::geometry::Shape;
//!
//! let mut scene = Scene::<I16F16>::parse(include_str!("../scenes/boing.scene"))?;
//! let bounce = Bounce::boing(&scene.objects)?;
//! assert_eq!(bounce.frames(), 16);
//! bounce.apply(&mut scene, 4)?; // a quarter through the loop: the top of the first bounce
//! let Shape::Sphere(ball) = scene.objects[bounce.object()].shape else { unreachable!() };
//! assert_eq!(ball.center().y, I16F16::from_num(1 + 2)); // at rest y = 1, height 2
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use core::fmt;

use crate::{Object, Scalar, Scene, Shape, Sphere, Vec3};

/// Why a [`Bounce`] cannot be made or applied.
///
/// ```
/// use fixray::anim::{AnimError, Bounce};
/// use fixray::{Scene, I16F16};
///
/// let planes = Scene::<I16F16>::parse(include_str!("../scenes/planes.scene"))?;
/// assert_eq!(Bounce::boing(&planes.objects), Err(AnimError::NoSphere));
/// # Ok::<(), fixray::SceneError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AnimError {
    /// The scene has no sphere to move.
    NoSphere,
    /// The loop has no frames, more than [`Bounce::MAX_FRAMES`], or no bounce.
    BadFrames,
    /// The object the bounce moves is not a sphere (any more) in this scene.
    NotASphere,
    /// A centre on the path does not fit the number format.
    OutOfRange,
}

impl fmt::Display for AnimError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            AnimError::NoSphere => "the scene has no sphere to bounce",
            AnimError::BadFrames => "a bounce needs 1 to 1024 frames and at least one bounce",
            AnimError::NotASphere => "the bounced object is not a sphere in this scene",
            AnimError::OutOfRange => "the bounce path leaves the number format's range",
        })
    }
}

impl core::error::Error for AnimError {}

/// A sphere bouncing along a floor (see the module documentation for the path).
///
/// ```
/// use fixray::anim::Bounce;
/// use fixray::{Scene, I16F16};
///
/// let mut scene = Scene::<I16F16>::parse(include_str!("../scenes/boing.scene"))?;
/// let bounce = Bounce::boing(&scene.objects)?;
/// let start = scene.objects[bounce.object()];
/// bounce.apply(&mut scene, 5)?;
/// assert_ne!(scene.objects[bounce.object()], start);
/// bounce.apply(&mut scene, bounce.frames())?; // frame n is frame 0: the loop closes
/// assert_eq!(scene.objects[bounce.object()], start);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounce<S> {
    object: usize,
    rest: Vec3<S>,
    radius: S,
    height: S,
    sway: S,
    frames: u16,
    bounces: u16,
}

impl<S: Scalar> Bounce<S> {
    /// The most frames a loop may have (so that `4 p (n − p)` and `n²` fit an `i32`).
    pub const MAX_FRAMES: u16 = 1024;

    /// A bounce of the first sphere among `objects`, resting where the scene puts it:
    /// `bounces` parabolas of `height` per loop of `frames` frames, while it moves `sway`
    /// along x and back.
    ///
    /// # Errors
    /// [`AnimError::NoSphere`] without a sphere, [`AnimError::BadFrames`] for 0 or more
    /// than [`Bounce::MAX_FRAMES`] frames or no bounce, [`AnimError::OutOfRange`] when a
    /// centre on the path does not fit the format.
    pub fn new(
        objects: &[Object<S>],
        height: S,
        sway: S,
        frames: u16,
        bounces: u16,
    ) -> Result<Self, AnimError> {
        if frames == 0 || frames > Self::MAX_FRAMES || bounces == 0 {
            return Err(AnimError::BadFrames);
        }
        let (object, sphere) = objects
            .iter()
            .enumerate()
            .find_map(|(i, o)| match o.shape {
                Shape::Sphere(s) => Some((i, s)),
                _ => None,
            })
            .ok_or(AnimError::NoSphere)?;
        let bounce = Self {
            object,
            rest: sphere.center(),
            radius: sphere.radius(),
            height,
            sway,
            frames,
            bounces,
        };
        // Every centre of the loop must fit: check them once here, so that `apply`
        // fails only on a scene the bounce was not made for.
        for k in 0..frames {
            bounce.centre(k)?;
        }
        Ok(bounce)
    }

    /// The boing ball's bounce (`scenes/boing.scene`, the firmware and the viewer): 16
    /// frames, two bounces of height 2, a sway of 2 along x.
    ///
    /// # Errors
    /// As [`Bounce::new`].
    pub fn boing(objects: &[Object<S>]) -> Result<Self, AnimError> {
        let two = S::from_i32(2).ok_or(AnimError::OutOfRange)?;
        Self::new(objects, two, two, 16, 2)
    }

    /// Frames per loop.
    pub fn frames(&self) -> u16 {
        self.frames
    }

    /// The index of the moved object in the scene's objects.
    pub fn object(&self) -> usize {
        self.object
    }

    /// The sphere's centre in frame `frame` (taken modulo the loop).
    ///
    /// # Errors
    /// [`AnimError::OutOfRange`] when it does not fit the format.
    pub fn centre(&self, frame: u16) -> Result<Vec3<S>, AnimError> {
        let n = i32::from(self.frames);
        let k = i32::from(frame % self.frames);
        let p = (k * i32::from(self.bounces)) % n;
        let out = n - (2 * k - n).abs();
        let dx = self.sway.mul_ratio(out, n);
        let dy = self.height.mul_ratio(4 * p * (n - p), n * n);
        let x = dx.and_then(|d| self.rest.x.checked_add(d));
        let y = dy.and_then(|d| self.rest.y.checked_add(d));
        match (x, y) {
            (Some(x), Some(y)) => Ok(Vec3::new(x, y, self.rest.z)),
            _ => Err(AnimError::OutOfRange),
        }
    }

    /// Moves the sphere of `scene` to its place in frame `frame`.
    ///
    /// # Errors
    /// [`AnimError::NotASphere`] when the bounced object is not a sphere in `scene`,
    /// [`AnimError::OutOfRange`] as [`Bounce::centre`].
    ///
    /// Out of line: its temporaries (a sphere built anew) are not in the frame of the
    /// caller's frame loop, under which the renderer runs (stack on a 16 KB chip).
    #[inline(never)]
    pub fn apply<const O: usize, const M: usize, const L: usize>(
        &self,
        scene: &mut Scene<S, O, M, L>,
        frame: u16,
    ) -> Result<(), AnimError> {
        let centre = self.centre(frame)?;
        let object = scene
            .objects
            .get_mut(self.object)
            .ok_or(AnimError::NotASphere)?;
        if !matches!(object.shape, Shape::Sphere(_)) {
            return Err(AnimError::NotASphere);
        }
        let sphere = Sphere::new(centre, self.radius).map_err(|_| AnimError::OutOfRange)?;
        object.shape = Shape::Sphere(sphere);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{I16F16, I32F32};

    fn boing<S: Scalar>() -> (Scene<S>, Bounce<S>) {
        let scene = Scene::<S>::parse(include_str!("../scenes/boing.scene")).unwrap();
        let bounce = Bounce::boing(&scene.objects).unwrap();
        (scene, bounce)
    }

    /// The path: at rest in frame 0, at the top of a bounce a quarter of the way, back on
    /// the floor halfway (the second bounce starts), furthest along x halfway, and the
    /// loop closes. The same points in every fixed format (the ratios are exact here).
    #[test]
    fn the_ball_bounces_twice_and_sways_out_and_back() {
        fn check<S: Scalar>() {
            let (scene, b) = boing::<S>();
            let rest = b.centre(0).unwrap();
            let Shape::Sphere(s) = scene.objects[b.object()].shape else {
                panic!("the bounce moves a sphere")
            };
            assert_eq!(rest, s.center());
            let f = |k| b.centre(k).unwrap().to_f64();
            let r = rest.to_f64();
            assert_eq!(f(4)[1], r[1] + 2.0, "{}: top of the first bounce", S::NAME);
            assert_eq!(f(8)[1], r[1], "{}: on the floor halfway", S::NAME);
            assert_eq!(f(12)[1], r[1] + 2.0, "{}: top of the second", S::NAME);
            assert_eq!(f(8)[0], r[0] + 2.0, "{}: furthest along x", S::NAME);
            assert_eq!(f(16), r, "{}: the loop closes", S::NAME);
            // Never below the rest height, and every frame differs from the one before.
            for k in 1..16 {
                assert!(f(k)[1] >= r[1]);
                assert_ne!(f(k), f(k - 1));
            }
        }
        check::<I16F16>();
        check::<I32F32>();
        check::<f32>();
        check::<f64>();
    }

    #[test]
    fn bad_bounces_are_errors_not_panics() {
        let (mut scene, b) = boing::<I16F16>();
        let two = I16F16::from_num(2);
        assert_eq!(
            Bounce::new(&scene.objects, two, two, 0, 1),
            Err(AnimError::BadFrames)
        );
        assert_eq!(
            Bounce::new(&scene.objects, two, two, 1025, 1),
            Err(AnimError::BadFrames)
        );
        assert_eq!(
            Bounce::new(&scene.objects, two, two, 16, 0),
            Err(AnimError::BadFrames)
        );
        assert_eq!(
            Bounce::new(&scene.objects[..2], two, two, 16, 2),
            Err(AnimError::NoSphere)
        );
        // A height the format cannot add to the centre.
        assert_eq!(
            Bounce::new(&scene.objects, I16F16::MAX, two, 16, 2),
            Err(AnimError::OutOfRange)
        );
        // The object is no longer a sphere.
        scene.objects[b.object()].shape = scene.objects[0].shape;
        assert_eq!(b.apply(&mut scene, 3), Err(AnimError::NotASphere));
        scene.objects.clear();
        assert_eq!(b.apply(&mut scene, 3), Err(AnimError::NotASphere));
    }
}
