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
//!     camera cam { pixeldim 4 4 worlddim 4 4 viewpoint 2 2 5 }
//!     material red { ambient 1 0 0 }
//!     plane floor { material red normal 0 1 0 point 0 0.4 0 }   # y = 0.4: the lower half
//! ";
//! let scene = Scene::<I16F16>::parse(text).unwrap();
//! let mut display = MockDisplay::<Rgb888>::new();
//! render(&scene, &mut display).unwrap();
//! display.assert_pattern(&["KKKK", "KKKK", "RRRR", "RRRR"]);
//! ```
#![cfg_attr(not(test), no_std)]
#![forbid(unsafe_code)]
#![deny(missing_docs)]

pub mod compare;
pub mod decimal;
pub mod fast;
pub mod flat;
pub mod geometry;
pub mod hash;
pub mod parse;
pub mod render;
pub mod scalar;
pub mod scene;
pub mod variants;
pub mod vec3;

/// The README's examples, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;

pub use flat::PlaneMode;
pub use geometry::{
    FrameError, Hit, Miss, Plane, PlaneError, PlaneFrame, Ray, RayKind, Shape, Sphere, SphereError,
};
pub use parse::{SceneError, SceneErrorKind};
pub use render::{
    Counters, Frame, Traced, pixel, render, render_counted, render_line, render_line_counted,
    trace, trace_pixel,
};
pub use scalar::{EPSILON_DELTAS, I16F16, I20F12, I32F32, Scalar};
pub use scene::{Camera, Color, Cone, Light, Material, Object, Plan, Scene};
pub use vec3::{Normalized, Vec3};
