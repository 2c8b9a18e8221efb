//! Pictures compared pixel by pixel: a target that records what it is drawn (and how often
//! each pixel was written), the largest channel difference of pixel pairs, and the PSNR.
//! Shared by the integration tests and the accuracy report's sampling section.

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use embedded_graphics::prelude::{DrawTarget, OriginDimensions, Pixel, Size};

/// A target that records every pixel and how often it was written.
pub struct Capture {
    pub size: Size,
    pub pixels: Vec<Option<Rgb888>>,
    pub writes: Vec<u8>,
}

impl Capture {
    pub fn new(w: u16, h: u16) -> Self {
        let n = usize::from(w) * usize::from(h);
        Self {
            size: Size::new(u32::from(w), u32::from(h)),
            pixels: vec![None; n],
            writes: vec![0; n],
        }
    }
}

impl OriginDimensions for Capture {
    fn size(&self) -> Size {
        self.size
    }
}

impl DrawTarget for Capture {
    type Color = Rgb888;
    type Error = core::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb888>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Self::Error> {
        let w = self.size.width as usize;
        for Pixel(p, c) in pixels {
            let i = p.y as usize * w + p.x as usize;
            self.pixels[i] = Some(c);
            self.writes[i] = self.writes[i].saturating_add(1);
        }
        Ok(())
    }
}

/// The largest channel difference of two pixels.
pub fn difference(a: Rgb888, b: Rgb888) -> u8 {
    [
        a.r().abs_diff(b.r()),
        a.g().abs_diff(b.g()),
        a.b().abs_diff(b.b()),
    ]
    .into_iter()
    .max()
    .unwrap_or(0)
}

/// The squared error of two pictures, summed over the pixels and channels.
pub fn squared_error(a: &[Rgb888], b: &[Rgb888]) -> f64 {
    a.iter()
        .zip(b)
        .flat_map(|(x, y)| {
            [
                f64::from(x.r()) - f64::from(y.r()),
                f64::from(x.g()) - f64::from(y.g()),
                f64::from(x.b()) - f64::from(y.b()),
            ]
        })
        .map(|d| d * d)
        .sum()
}

/// PSNR in dB of a squared error summed over `pixels` pixels' three channels (infinite
/// for none).
pub fn psnr(squared: f64, pixels: usize) -> f64 {
    let mse = squared / (3 * pixels) as f64;
    10.0 * (255.0 * 255.0 / mse).log10()
}
