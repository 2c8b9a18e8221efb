//! [`FrameHash`]: a 32-bit FNV-1a hash over a frame's pixels, the same on the host and on
//! the firmware, so that a frame rendered on a chip can be compared with the host's render
//! bit for bit without sending the picture.
//!
//! FNV-1a is written out here rather than taken from a crate: it is eight lines, it must be
//! bit-identical on every target, and the hash of a frame is defined by this file alone.
//!
//! ```
//! use embedded_graphics::pixelcolor::Rgb888;
//! use fixray::hash::FrameHash;
//!
//! let mut h = FrameHash::new();
//! h.push(Rgb888::new(1, 2, 3));
//! // FNV-1a of the bytes 1, 2, 3.
//! assert_eq!(h.value(), 0x56cf_37ab);
//! ```

use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};

const OFFSET_BASIS: u32 = 0x811c_9dc5;
const PRIME: u32 = 0x0100_0193;

/// FNV-1a (32 bits) over the R, G, B bytes of each pixel, in the order pushed (row by
/// row, left to right, for a frame).
///
/// ```
/// use embedded_graphics::pixelcolor::Rgb888;
/// use fixray::hash::FrameHash;
/// use fixray::{render_line, Scene, I16F16};
///
/// let scene = Scene::<I16F16>::parse(include_str!("../scenes/planes.scene"))?;
/// let mut line = [Rgb888::new(0, 0, 0); 160];
/// let mut hash = FrameHash::new();
/// for row in 0..scene.camera.height {
///     render_line(&scene, row, &mut line);
///     line.iter().for_each(|&c| hash.push(c));
/// }
/// // What a firmware prints for the same scene in the same format, bit for bit.
/// assert_ne!(hash.value(), FrameHash::new().value());
/// # Ok::<(), fixray::SceneError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FrameHash(u32);

impl Default for FrameHash {
    fn default() -> Self {
        Self::new()
    }
}

impl FrameHash {
    /// The hash of no pixels.
    pub const fn new() -> Self {
        Self(OFFSET_BASIS)
    }

    /// Adds one pixel.
    #[inline]
    pub fn push(&mut self, c: Rgb888) {
        for byte in [c.r(), c.g(), c.b()] {
            self.0 = (self.0 ^ u32::from(byte)).wrapping_mul(PRIME);
        }
    }

    /// The hash so far.
    pub const fn value(&self) -> u32 {
        self.0
    }
}
