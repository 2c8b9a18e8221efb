//! A reader of binary PPM images (`P6`), the course's texture format: no_std, no
//! allocator, no copy (the pixels stay in the caller's bytes, e.g. an `include_bytes!`
//! in flash).
//!
//! The header is the magic `P6`, the width, the height and the largest sample value
//! (`maxval`, 1 ..= 65535), separated by whitespace, with `#` comments to the end of a
//! line anywhere before `maxval`; one whitespace byte, then `width × height` pixels of
//! three samples each, one byte per sample (two, big-endian, when `maxval > 255`). Bytes
//! after the last pixel are ignored. Every malformed, truncated or lying header is a
//! [`PpmError`], never a panic and never a read out of bounds.
//!
//! ```
//! use fixray::ppm::{Ppm, PpmError};
//!
//! let bytes = b"P6\n# a 2x1 picture\n2 1\n255\n\xff\x00\x00\x00\x00\xff";
//! let image = Ppm::parse(bytes).unwrap();
//! assert_eq!((image.width(), image.height()), (2, 1));
//! assert_eq!(image.pixel(1, 0), Some([0, 0, 255]));
//! assert_eq!(image.pixel(2, 0), None);
//!
//! // A header that promises more pixels than the file holds:
//! let err = Ppm::parse(b"P6 4 4 255\n\x00\x00\x00").unwrap_err();
//! assert_eq!(err, PpmError::Truncated { expected: 48, found: 3 });
//! ```

use core::fmt;

/// The largest width or height read (a larger one is [`PpmError::TooLarge`]).
pub const MAX_SIDE: u32 = 16_384;

/// What is wrong with a PPM file.
///
/// ```
/// use fixray::ppm::{Ppm, PpmError};
///
/// assert_eq!(Ppm::parse(b"P3 1 1 255\n0 0 0").unwrap_err(), PpmError::NotPpm); // ASCII PPM
/// assert_eq!(Ppm::parse(b"P6 0 1 255\n").unwrap_err(), PpmError::ZeroSize);
/// assert_eq!(
///     Ppm::parse(b"P6 1 1 255\n\x00").unwrap_err(),
///     PpmError::Truncated { expected: 3, found: 1 }
/// );
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PpmError {
    /// It does not start with `P6` (a binary PPM).
    NotPpm,
    /// The header ends, or holds something else, where a number was expected.
    ExpectedNumber(&'static str),
    /// A width or height of 0.
    ZeroSize,
    /// A width or height above [`MAX_SIDE`].
    TooLarge,
    /// `maxval` outside 1 ..= 65535.
    MaxvalOutOfRange,
    /// No whitespace byte between `maxval` and the pixels.
    NoSeparator,
    /// Fewer pixel bytes than the header promises.
    Truncated {
        /// Bytes the header promises.
        expected: usize,
        /// Bytes the file holds after the header.
        found: usize,
    },
}

impl fmt::Display for PpmError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PpmError::NotPpm => write!(f, "not a binary PPM (it must start with `P6`)"),
            PpmError::ExpectedNumber(what) => write!(f, "the PPM header has no {what}"),
            PpmError::ZeroSize => write!(f, "the PPM is 0 pixels wide or high"),
            PpmError::TooLarge => write!(f, "the PPM is over {MAX_SIDE} pixels wide or high"),
            PpmError::MaxvalOutOfRange => write!(f, "the PPM's maxval is not in 1..=65535"),
            PpmError::NoSeparator => write!(f, "no whitespace between the PPM header and pixels"),
            PpmError::Truncated { expected, found } => write!(
                f,
                "the PPM is truncated: its header promises {expected} bytes of pixels, it holds {found}"
            ),
        }
    }
}

impl core::error::Error for PpmError {}

/// A binary PPM image borrowed from its bytes ([`Ppm::parse`]).
///
/// ```
/// use fixray::ppm::Ppm;
///
/// // Two bytes a sample where maxval is above 255, scaled to 0 ..= 255.
/// let image = Ppm::parse(b"P6 1 1 65535\n\xff\xff\x80\x00\x00\x10").unwrap();
/// assert_eq!(image.maxval(), 65535);
/// assert_eq!(image.pixel(0, 0), Some([255, 128, 0]));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Ppm<'a> {
    width: u32,
    height: u32,
    maxval: u16,
    /// Exactly `width × height × 3` samples (× 2 bytes when `maxval > 255`).
    data: &'a [u8],
}

impl<'a> Ppm<'a> {
    /// Reads the header and checks that the pixels are all there.
    ///
    /// # Errors
    /// A [`PpmError`] for a file that is not a well-formed binary PPM.
    pub fn parse(bytes: &'a [u8]) -> Result<Self, PpmError> {
        if bytes.get(..2) != Some(b"P6") {
            return Err(PpmError::NotPpm);
        }
        let mut at = 2;
        let width = header_number(bytes, &mut at, "width")?;
        let height = header_number(bytes, &mut at, "height")?;
        let maxval = header_number(bytes, &mut at, "maxval")?;
        if width == 0 || height == 0 {
            return Err(PpmError::ZeroSize);
        }
        if width > MAX_SIDE || height > MAX_SIDE {
            return Err(PpmError::TooLarge);
        }
        let maxval = u16::try_from(maxval)
            .ok()
            .filter(|m| *m > 0)
            .ok_or(PpmError::MaxvalOutOfRange)?;
        // Exactly one whitespace byte ends the header.
        if !bytes.get(at).is_some_and(u8::is_ascii_whitespace) {
            return Err(PpmError::NoSeparator);
        }
        let pixels = bytes.get(at + 1..).unwrap_or(&[]);
        let sample = if maxval > 255 { 2 } else { 1 };
        // ≤ 16384² × 6 < 2^31: fits a 32-bit usize (checked all the same).
        let expected = usize::try_from(width)
            .ok()
            .and_then(|w| w.checked_mul(usize::try_from(height).ok()?))
            .and_then(|n| n.checked_mul(3 * sample))
            .ok_or(PpmError::TooLarge)?;
        let data = pixels.get(..expected).ok_or(PpmError::Truncated {
            expected,
            found: pixels.len(),
        })?;
        Ok(Self {
            width,
            height,
            maxval,
            data,
        })
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The largest sample value.
    pub fn maxval(&self) -> u16 {
        self.maxval
    }

    /// The pixel at column `x`, row `y` (row 0 is the file's first, the top), each sample
    /// scaled to 0 ..= 255 (`round(255 v / maxval)`; as stored when `maxval` is 255);
    /// `None` outside the image.
    pub fn pixel(&self, x: u32, y: u32) -> Option<[u8; 3]> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let (x, y, w) = (
            usize::try_from(x).ok()?,
            usize::try_from(y).ok()?,
            usize::try_from(self.width).ok()?,
        );
        let index = y.checked_mul(w)?.checked_add(x)?.checked_mul(3)?;
        let mut out = [0u8; 3];
        for (k, o) in out.iter_mut().enumerate() {
            let v = if self.maxval > 255 {
                let hi = *self.data.get(2 * (index + k))?;
                let lo = *self.data.get(2 * (index + k) + 1)?;
                u32::from(u16::from_be_bytes([hi, lo]))
            } else {
                u32::from(*self.data.get(index + k)?)
            };
            let m = u32::from(self.maxval);
            // v ≤ maxval after the clamp: the quotient is ≤ 255.
            let scaled = if m == 255 {
                v
            } else {
                (v.min(m) * 255 + m / 2) / m
            };
            *o = u8::try_from(scaled).ok()?;
        }
        Some(out)
    }
}

/// Skips whitespace and `#` comments, then reads a decimal number (at most 10 digits).
fn header_number(bytes: &[u8], at: &mut usize, what: &'static str) -> Result<u32, PpmError> {
    loop {
        match bytes.get(*at) {
            Some(b) if b.is_ascii_whitespace() => *at += 1,
            Some(b'#') => {
                while bytes.get(*at).is_some_and(|b| *b != b'\n' && *b != b'\r') {
                    *at += 1;
                }
            }
            _ => break,
        }
    }
    let start = *at;
    let mut value: u64 = 0;
    while let Some(b) = bytes.get(*at).filter(|b| b.is_ascii_digit()) {
        value = value * 10 + u64::from(b - b'0');
        *at += 1;
        if *at - start > 10 {
            return Err(PpmError::TooLarge);
        }
    }
    if *at == start {
        return Err(PpmError::ExpectedNumber(what));
    }
    // A number must end at whitespace or a comment (or the end, caught later).
    if bytes
        .get(*at)
        .is_some_and(|b| !b.is_ascii_whitespace() && *b != b'#')
    {
        return Err(PpmError::ExpectedNumber(what));
    }
    u32::try_from(value).map_err(|_| PpmError::TooLarge)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::vec::Vec;

    fn image(header: &str, pixels: usize) -> Vec<u8> {
        let mut v = header.as_bytes().to_vec();
        v.extend((0..pixels).map(|i| (i * 7 % 256) as u8));
        v
    }

    #[test]
    fn reads_a_header_with_comments_and_its_pixels() {
        let bytes = image("P6\n# made by hand\n3 # three wide\n2\n255\n", 18);
        let p = Ppm::parse(&bytes).unwrap();
        assert_eq!((p.width(), p.height(), p.maxval()), (3, 2, 255));
        let start = bytes.len() - 18;
        assert_eq!(
            p.pixel(2, 1),
            Some([bytes[start + 15], bytes[start + 16], bytes[start + 17]])
        );
        assert_eq!(p.pixel(0, 2), None);
        assert_eq!(p.pixel(3, 0), None);
    }

    #[test]
    fn sixteen_bit_samples_are_scaled_to_bytes() {
        let mut bytes = b"P6 1 1 65535\n".to_vec();
        bytes.extend([0xff, 0xff, 0x80, 0x00, 0x00, 0x00]);
        let p = Ppm::parse(&bytes).unwrap();
        assert_eq!(p.pixel(0, 0), Some([255, 128, 0]));
        let bytes = b"P6 1 1 15\n\x0f\x07\x00";
        assert_eq!(Ppm::parse(bytes).unwrap().pixel(0, 0), Some([255, 119, 0]));
        // A sample above maxval (a lying file) shows as maxval.
        let bytes = b"P6 1 1 15\n\xff\x07\x00";
        assert_eq!(Ppm::parse(bytes).unwrap().pixel(0, 0), Some([255, 119, 0]));
    }

    #[test]
    fn bad_headers_are_errors() {
        let cases: [(&[u8], PpmError); 12] = [
            (b"", PpmError::NotPpm),
            (b"P3 1 1 255\n000", PpmError::NotPpm),
            (b"P6", PpmError::ExpectedNumber("width")),
            (b"P6 1", PpmError::ExpectedNumber("height")),
            (b"P6 1 1", PpmError::ExpectedNumber("maxval")),
            (b"P6 1x 1 255\n000", PpmError::ExpectedNumber("width")),
            (b"P6 -1 1 255\n000", PpmError::ExpectedNumber("width")),
            (b"P6 0 1 255\n", PpmError::ZeroSize),
            (b"P6 16385 1 255\n", PpmError::TooLarge),
            (b"P6 99999999999 1 255\n", PpmError::TooLarge),
            (b"P6 1 1 0\n000", PpmError::MaxvalOutOfRange),
            (b"P6 1 1 255", PpmError::NoSeparator),
        ];
        for (bytes, want) in cases {
            assert_eq!(
                Ppm::parse(bytes),
                Err(want),
                "{:?}",
                core::str::from_utf8(bytes)
            );
        }
        assert_eq!(
            Ppm::parse(b"P6 1 1 65536\n"),
            Err(PpmError::MaxvalOutOfRange)
        );
    }

    #[test]
    fn truncated_and_lying_headers_are_errors() {
        let full = image("P6 4 3 255\n", 36);
        assert!(Ppm::parse(&full).is_ok());
        for cut in 0..36 {
            let bytes = &full[..full.len() - 36 + cut];
            assert_eq!(
                Ppm::parse(bytes),
                Err(PpmError::Truncated {
                    expected: 36,
                    found: cut
                })
            );
        }
        // A header that lies about its size: the largest it may claim.
        let lying = image("P6 16384 16384 65535\n", 100);
        assert_eq!(
            Ppm::parse(&lying),
            Err(PpmError::Truncated {
                expected: 16384 * 16384 * 6,
                found: 100
            })
        );
        // Trailing bytes are ignored.
        let long = image("P6 1 1 255\n", 10);
        assert_eq!(Ppm::parse(&long).unwrap().data.len(), 3);
    }

    #[test]
    fn course_textures_are_read() {
        for (name, w, h) in [
            ("mike", 256, 256),
            ("oak", 128, 128),
            ("brick8", 384, 384),
            ("halfmoonbay", 1024, 768),
        ] {
            let path = std::format!("{}/course/images/{name}.ppm", env!("CARGO_MANIFEST_DIR"));
            let bytes = std::fs::read(&path).unwrap();
            let p = Ppm::parse(&bytes).unwrap();
            assert_eq!((p.width(), p.height()), (w, h), "{name}");
            assert!(p.pixel(p.width() - 1, p.height() - 1).is_some());
        }
    }
}
