//! Animation: a scene's sphere moved along a bounce path, and the camera carried round
//! it, frame by frame, in the scene itself (no re-parsing), so that a chip draws a moving
//! ball from one parsed scene.
//!
//! An [`Orbit`] turns the whole scene about a vertical axis (see its documentation). A
//! [`Bounce`] moves the first sphere of a scene. Frame `k` of `n` places its centre at
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
    /// An orbit cannot turn this kind of object or light ([`Orbit::apply`]).
    CannotTurn,
}

impl fmt::Display for AnimError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            AnimError::NoSphere => "the scene has no sphere to bounce",
            AnimError::BadFrames => "a bounce needs 1 to 1024 frames and at least one bounce",
            AnimError::NotASphere => "the bounced object is not a sphere in this scene",
            AnimError::OutOfRange => "the animation's path leaves the number format's range",
            AnimError::CannotTurn => {
                "an orbit turns only infinite planes, spheres, point lights and spotlights"
            }
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
        let (object, sphere) = first_sphere(objects)?;
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

/// The first sphere among `objects`, with its index.
fn first_sphere<S: Scalar>(objects: &[Object<S>]) -> Result<(usize, Sphere<S>), AnimError> {
    objects
        .iter()
        .enumerate()
        .find_map(|(i, o)| match o.shape {
            Shape::Sphere(s) => Some((i, s)),
            _ => None,
        })
        .ok_or(AnimError::NoSphere)
}

/// The camera circling a point: the scene turned about the vertical axis through
/// `pivot`, frame by frame, which is what the eye sees from a camera carried round it
/// the other way (the camera of the scene language looks along −z through a window at
/// z = 0; turning the world keeps that camera and turns everything it sees).
///
/// Frame `k` of `n` turns by the angle `θ` with `tan(θ/2) = swing · s(k)`, where `s` runs
/// 0 → 1 → 0 → −1 → 0 over the loop (linear between), so the camera swings to one
/// side, back, to the other and back. The turn is `cos θ = (1 − t²)/(1 + t²)`, `sin θ
/// = 2t/(1 + t²)` for `t = tan(θ/2)`: two divisions a frame, no trigonometry, the same
/// operations on a host and on a chip. Every object's geometry and every light's place
/// (and a spotlight's axis) turn; a plane's normal and tiles turn with it.
///
/// Each frame turns a scene as parsed (with a [`Bounce`] applied first, for the
/// bouncing ball seen from the circling camera), not the frame before: turns do not
/// accumulate roundings.
///
/// ```
/// use fixray::anim::{Bounce, Orbit};
/// use fixray::{Frame, KernelKind, Scene, I16F16};
///
/// let base = Scene::<I16F16>::parse(include_str!("../scenes/boing.scene"))?;
/// let (bounce, orbit) = (Bounce::boing(&base.objects)?, Orbit::boing(&base.objects)?);
/// let mut scene = base.clone();
/// bounce.apply(&mut scene, 5)?;
/// orbit.apply(&mut scene, 5)?;
/// // The back wall no longer faces the camera square on: the fast kernel draws it.
/// assert_eq!(Frame::<_>::new(&scene).kernel(), KernelKind::Fast);
/// orbit.apply(&mut scene, 0)?; // frame 0 does not turn
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Orbit<S> {
    pivot: Vec3<S>,
    swing: S,
    frames: u16,
}

impl<S: Scalar> Orbit<S> {
    /// An orbit about the vertical axis through `pivot` whose largest turn has
    /// `tan(θ/2) = swing`, over a loop of `frames` frames.
    ///
    /// # Errors
    /// [`AnimError::BadFrames`] for 0 or more than [`Bounce::MAX_FRAMES`] frames,
    /// [`AnimError::OutOfRange`] when a turn does not fit the format.
    pub fn new(pivot: Vec3<S>, swing: S, frames: u16) -> Result<Self, AnimError> {
        if frames == 0 || frames > Bounce::<S>::MAX_FRAMES {
            return Err(AnimError::BadFrames);
        }
        let orbit = Self {
            pivot,
            swing,
            frames,
        };
        for k in 0..frames {
            orbit.turn(k)?;
        }
        Ok(orbit)
    }

    /// The boing ball's orbit: about the vertical axis through the first sphere's place
    /// at rest, 16 frames, turns of up to 2·atan(3/8) ≈ 41°.
    ///
    /// # Errors
    /// [`AnimError::NoSphere`] without a sphere; as [`Orbit::new`].
    pub fn boing(objects: &[Object<S>]) -> Result<Self, AnimError> {
        let pivot = first_sphere(objects)?.1.center();
        let swing = S::ONE.mul_ratio(3, 8).ok_or(AnimError::OutOfRange)?;
        Self::new(pivot, swing, 16)
    }

    /// Frames per loop.
    pub fn frames(&self) -> u16 {
        self.frames
    }

    /// `(cos θ, sin θ)` of frame `frame`'s turn (taken modulo the loop).
    ///
    /// # Errors
    /// [`AnimError::OutOfRange`] when it does not fit the format.
    pub fn turn(&self, frame: u16) -> Result<(S, S), AnimError> {
        let n = i32::from(self.frames);
        let k = i32::from(frame % self.frames);
        // s(k)·n as an integer: 0 → n → 0 → −n → 0.
        let q = 4 * k;
        let s = if q <= n {
            q
        } else if q <= 3 * n {
            2 * n - q
        } else {
            q - 4 * n
        };
        let turn = || -> Option<(S, S)> {
            let t = self.swing.mul_ratio(s, n)?;
            let tt = t.checked_mul(t)?;
            let den = S::ONE.checked_add(tt)?;
            let cos = S::ONE.checked_sub(tt)?.checked_div(den)?;
            let sin = t.checked_mul_int(2)?.checked_div(den)?;
            Some((cos, sin))
        };
        turn().ok_or(AnimError::OutOfRange)
    }

    /// Turns every object and light of `scene` by frame `frame`'s turn (see the type's
    /// documentation: apply it to a scene as parsed, not to the frame before).
    ///
    /// # Errors
    /// [`AnimError::CannotTurn`] for a finite plane, a textured plane, a triangle, a
    /// surface of revolution, a checkerboard laid on world x and z (a `tiled_plane`
    /// without `xdir`) or a projector (only infinite planes, tiled along their own axes or
    /// plain, spheres, point lights and spotlights turn); [`AnimError::OutOfRange`] when a
    /// turned quantity does not fit the format. On an error the scene may be part
    /// turned.
    #[inline(never)]
    pub fn apply<const O: usize, const M: usize, const L: usize>(
        &self,
        scene: &mut Scene<S, O, M, L>,
        frame: u16,
    ) -> Result<(), AnimError> {
        let (cos, sin) = self.turn(frame)?;
        let about = |p: Vec3<S>| self.turned(p, cos, sin, true);
        let along = |v: Vec3<S>| self.turned(v, cos, sin, false);
        for object in scene.objects.iter_mut() {
            object.shape = match object.shape {
                Shape::Sphere(s) => Shape::Sphere(
                    Sphere::new(about(s.center())?, s.radius())
                        .map_err(|_| AnimError::OutOfRange)?,
                ),
                Shape::Plane(p) => {
                    let normal = along(p.normal())?;
                    let point = about(p.normal().scale(p.offset()).ok_or(AnimError::OutOfRange)?)?;
                    Shape::Plane(
                        crate::Plane::new(normal, point).map_err(|_| AnimError::OutOfRange)?,
                    )
                }
                Shape::Tiled {
                    tiling: crate::geometry::Tiling::WorldXz,
                    ..
                } => return Err(AnimError::CannotTurn),
                Shape::Tiled { frame, alt, tiling } => {
                    let turned = crate::PlaneFrame::new(
                        along(frame.plane().normal())?,
                        about(frame.corner())?,
                        along(frame.u())?,
                        frame.size(),
                    )
                    .map_err(|_| AnimError::OutOfRange)?;
                    Shape::Tiled {
                        frame: turned,
                        alt,
                        tiling,
                    }
                }
                Shape::Finite(_) | Shape::Textured(_) | Shape::Triangle(_) | Shape::Revsurf(_) => {
                    return Err(AnimError::CannotTurn);
                }
            };
        }
        for light in scene.lights.iter_mut() {
            light.location = about(light.location)?;
            match &mut light.beam {
                crate::scene::Beam::Everywhere => {}
                crate::scene::Beam::Cone(cone) => cone.axis = along(cone.axis)?,
                crate::scene::Beam::Projector(_) => return Err(AnimError::CannotTurn),
            }
        }
        Ok(())
    }

    /// `v` turned about the vertical axis through the pivot (`point`) or about the y
    /// axis (a direction): `x' = c + (x − c) cos θ − (z − c) sin θ`, `z' = c + (x −
    /// c) sin θ + (z − c) cos θ`.
    fn turned(&self, v: Vec3<S>, cos: S, sin: S, point: bool) -> Result<Vec3<S>, AnimError> {
        let (cx, cz) = if point {
            (self.pivot.x, self.pivot.z)
        } else {
            (S::ZERO, S::ZERO)
        };
        let turn = || -> Option<Vec3<S>> {
            let (dx, dz) = (v.x.checked_sub(cx)?, v.z.checked_sub(cz)?);
            let x = dx.checked_mul(cos)?.checked_sub(dz.checked_mul(sin)?)?;
            let z = dx.checked_mul(sin)?.checked_add(dz.checked_mul(cos)?)?;
            Some(Vec3::new(x.checked_add(cx)?, v.y, z.checked_add(cz)?))
        };
        turn().ok_or(AnimError::OutOfRange)
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

    /// The orbit: no turn in frame 0 and halfway, turns of opposite signs a quarter and
    /// three quarters of the way, the loop closes, and a turned scene keeps its
    /// distances (a sphere's from the pivot, a light's height) within a few DELTAs.
    #[test]
    fn the_camera_swings_round_and_back() {
        fn check<S: Scalar>() {
            let base = Scene::<S>::parse(include_str!("../scenes/boing.scene")).unwrap();
            let orbit = Orbit::boing(&base.objects).unwrap();
            assert_eq!(orbit.turn(0).unwrap(), (S::ONE, S::ZERO));
            assert_eq!(orbit.turn(8).unwrap(), (S::ONE, S::ZERO));
            let (c4, s4) = orbit.turn(4).unwrap();
            let (c12, s12) = orbit.turn(12).unwrap();
            assert_eq!((c4, s4), (c12, s12.checked_neg().unwrap()), "{}", S::NAME);
            // tan(θ/2) = 3/8: cos θ = 55/73, sin θ = 48/73.
            assert!((c4.to_f64() - 55.0 / 73.0).abs() < 1e-3, "{}", S::NAME);
            assert!((s4.to_f64() - 48.0 / 73.0).abs() < 1e-3, "{}", S::NAME);
            assert_eq!(orbit.turn(16).unwrap(), orbit.turn(0).unwrap());
            let mut same = base.clone();
            orbit.apply(&mut same, 0).unwrap();
            assert_eq!(
                same.objects,
                base.objects,
                "{}: frame 0 turns nothing",
                S::NAME
            );
            let mut turned = base.clone();
            orbit.apply(&mut turned, 4).unwrap();
            let Shape::Sphere(ball) = turned.objects[2].shape else {
                panic!("the ball")
            };
            let Shape::Sphere(rest) = base.objects[2].shape else {
                panic!("the ball")
            };
            // The pivot is the ball at rest: it stays where it was.
            let (a, b) = (ball.center().to_f64(), rest.center().to_f64());
            assert!((0..3).all(|i| (a[i] - b[i]).abs() < 1e-3), "{}", S::NAME);
            let light = |s: &Scene<S>| s.lights[0].location.to_f64();
            let (l, m) = (light(&turned), light(&base));
            assert_eq!(l[1], m[1], "{}: a light keeps its height", S::NAME);
            let r = |p: [f64; 3]| ((p[0] - b[0]).powi(2) + (p[2] - b[2]).powi(2)).sqrt();
            assert!((r(l) - r(m)).abs() < 1e-3, "{}: and its distance", S::NAME);
            assert_ne!(turned.objects, base.objects);
        }
        check::<I16F16>();
        check::<I32F32>();
        check::<f32>();
        check::<f64>();
    }

    #[test]
    fn an_orbit_refuses_what_it_cannot_turn() {
        let base = Scene::<I16F16>::parse(include_str!("../scenes/boing.scene")).unwrap();
        let orbit = Orbit::boing(&base.objects).unwrap();
        let pivot = Vec3::new(I16F16::ZERO, I16F16::ZERO, I16F16::ZERO);
        assert_eq!(Orbit::new(pivot, I16F16::ONE, 0), Err(AnimError::BadFrames));
        assert_eq!(
            Orbit::new(pivot, I16F16::MAX, 16),
            Err(AnimError::OutOfRange)
        );
        assert_eq!(Orbit::boing(&base.objects[..2]), Err(AnimError::NoSphere));
        let mut tiles = Scene::<I16F16>::parse(include_str!("../scenes/tiles.scene")).unwrap();
        assert_eq!(orbit.apply(&mut tiles, 3), Err(AnimError::CannotTurn));
    }
}
