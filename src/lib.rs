//! # fixray
//!
//! A `no_std` ray caster for microcontrollers: ray/plane intersections in fixed-point
//! arithmetic with an explicit precision epsilon, rendered scanline by scanline into any
//! [`embedded-graphics`](https://docs.rs/embedded-graphics) `DrawTarget`, with no
//! allocator and no framebuffer.
//!
//! Everything is generic over a number format [`Scalar`]: [`I16F16`], [`I20F12`],
//! [`I32F32`], `f32` and `f64` (the reference). Choose the format where you parse the scene:
//!
//! ```
//! use embedded_graphics::{mock_display::MockDisplay, pixelcolor::Rgb888};
//! use fixray::{render, Scene, I16F16};
//!
//! let text = "
//!     rules fixray
//!     camera cam { pixeldim 4 4 worlddim 4 4 viewpoint 2 2 5 }
//!     material red { ambient 1 0 0 }
//!     plane floor { material red normal 0 1 0 point 0 0.4 0 }   # y = 0.4: the lower half
//! ";
//! let scene = Scene::<I16F16>::parse(text).unwrap();
//! let mut display = MockDisplay::<Rgb888>::new();
//! render(&scene, &mut display).unwrap();
//! display.assert_pattern(&["KKKK", "KKKK", "RRRR", "RRRR"]);
//! ```
//!
//! The crate root holds what a first program needs: a [`Scene`] (parsed in one of the
//! formats [`I16F16`], [`I20F12`], [`I32F32`], or any [`Scalar`]) and its [`SceneError`],
//! and the renderer: [`render`] and [`render_line`], and [`Frame`], an
//! `embedded-graphics` `Drawable` (`frame.draw(&mut display)`), with its drawing option
//! [`PlaneMode`] and the [`KernelKind`] it reports. Everything else lives in its module.
//!
//! The modules, in the order they depend on each other (each uses only those above it):
//! [`num`] (number formats), [`geometry`] (rays and shapes), [`scene`] (scene, camera,
//! lights, plan, parser), [`shade`] (the colour of a hit, tracing a ray), the crate's
//! private kernels, the renderer (at the crate root) with its [`stats`], and the tools
//! [`ppm`], [`anim`], [`compare`] and [`hash`].
#![cfg_attr(not(any(test, feature = "std")), no_std)]
#![forbid(unsafe_code)]
#![deny(missing_docs)]

pub mod num;
pub mod ppm;

pub mod geometry;
pub mod scene;

pub mod stats;

pub mod shade;

mod kernel;

mod render;

#[cfg(feature = "advise")]
pub mod advise;
pub mod anim;
pub mod compare;
pub mod hash;

/// The README's examples, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;

/// The advisor's document's example, compiled and run as a doc test.
#[cfg(all(doctest, feature = "advise"))]
#[doc = include_str!("../docs/advisor.md")]
pub struct AdvisorDoctests;

pub use kernel::KernelKind;
pub use kernel::flat::PlaneMode;
#[cfg(feature = "sampling")]
pub use kernel::sampling::{BlockSize, Sampling, UnknownSampling};
pub use num::{I16F16, I20F12, I32F32, Scalar};
pub use render::{Bands, Changes, Frame, render, render_line};
pub use scene::{Scene, SceneError};
pub use shade::Depth;

// Shorthands for the crate's own modules, which name these items from the root; their
// public homes are the modules named here.
pub(crate) use geometry::{
    Hit, Miss, Plane, PlaneError, PlaneFrame, PlaneFrameError, Ray, RayKind, Revsurf, RevsurfError,
    Shape, Slide, Sphere, TexMode, Tiling, Triangle, TriangleError, Vec3,
};
pub(crate) use scene::{
    AsView, Beam, Camera, Color, Light, Material, Object, PixelGrid, Plan, Rules, SceneView,
};
pub(crate) use shade::Traced;

/// Kernel internals for the crate's own tests and benchmarks: not part of the API, and
/// they may change at any time. The kernels' per-frame parts (what the tests of a kernel
/// against the reference path and the accuracy report's kernel comparison step through),
/// and a scanline drawn with the ambient-only stage set (the benchmark of compiled-out
/// stages).
#[doc(hidden)]
pub mod internals {
    pub use crate::kernel::fast::Primary;
    pub use crate::kernel::flat::Flat;
    pub use crate::render::{render_columns_with, render_line_ambient};
}
