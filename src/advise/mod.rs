//! The advisor: for a scene, a core and an error budget, the cheapest number format and
//! sampling mode that hold the budget, with their figures (cargo feature `advise`, on a
//! host).
//!
//! Accuracy is measured, not modelled: every candidate (each main format, exact and in
//! each sampling mode of [`MODES`]) is drawn on the host, which draws the chip's pixels
//! bit for bit, and compared with the `f64` exact frame. Cost is a linear model of what
//! the frame does, calibrated on the chips: [`work`] counts it on the host (rays by kernel,
//! shadow rays, lights' terms, tile and texel lookups, blocks' corners and filled pixels,
//! the [`Work`] features), and each core × format has one coefficient per feature, fitted
//! by `cargo xtask calibrate` to the instructions the firmware counts under QEMU for the
//! shipped scenes, exact and sampled. [`Model::error`] states how far the model's
//! prediction lay from the count, each scene left out of the fit in turn. The RP2040's
//! cycles are the Cortex-M0 model's instructions times the cycles per instruction the
//! emulated board measures ([`RP2040_CYCLES_PER_INSTRUCTION`]).
//!
//! ```
//! use fixray::advise::{Budget, Core, advise};
//!
//! let text = include_str!("../../scenes/spheres.scene");
//! let advice = advise(text, Core::CortexM4F, Budget::Beyond { levels: 2, percent: 1.0 })?;
//! let choice = advice.choice().expect("the f64-accurate formats hold a 1 % budget");
//! assert!(choice.beyond <= 1.0);
//! // Nothing that holds the budget is cheaper.
//! assert!(advice.candidates.iter().filter(|c| c.holds).all(|c| c.cost >= choice.cost));
//! # Ok::<(), fixray::advise::AdviseError>(())
//! ```

mod model;

use std::fmt;
use std::vec::Vec;

use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};

use crate::num::formats::{MAIN, REFERENCE};
use crate::scene::LargeScene;
use crate::stats::Counters;
use crate::{AsView, BlockSize, Frame, KernelKind, Sampling, Scalar, SceneError};

pub use model::{MODELS, RP2040_CYCLES_PER_INSTRUCTION};

/// A core the advisor prices a frame on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Core {
    /// Cortex-M0 (ARMv6-M, no FPU): QEMU's micro:bit (16 KB of RAM; a firmware that
    /// draws sampled frames is given 64 KB).
    CortexM0,
    /// Cortex-M4F (single-precision FPU): QEMU's MPS2 AN386.
    CortexM4F,
    /// RISC-V rv32imc (no FPU): QEMU's virt.
    RiscV,
    /// The RP2040's Cortex-M0+ at 200 MHz, in cycles (the emulated board's).
    Rp2040,
}

impl Core {
    /// Every core, in this order.
    pub const ALL: [Core; 4] = [Core::CortexM0, Core::CortexM4F, Core::RiscV, Core::Rp2040];

    /// The name the firmware reports and the tools take (`cortex-m0`, `cortex-m4f`,
    /// `riscv32imc`, `rp2040`).
    pub fn name(self) -> &'static str {
        match self {
            Core::CortexM0 => "cortex-m0",
            Core::CortexM4F => "cortex-m4f",
            Core::RiscV => "riscv32imc",
            Core::Rp2040 => "rp2040",
        }
    }

    /// The core named `name` ([`Core::name`]).
    pub fn from_name(name: &str) -> Option<Core> {
        Core::ALL.into_iter().find(|c| c.name() == name)
    }

    /// What its cost counts: `instructions` on the QEMU cores, `cycles` on the RP2040.
    pub fn unit(self) -> &'static str {
        match self {
            Core::Rp2040 => "cycles",
            _ => "instructions",
        }
    }

    /// The core whose instruction counts the model was fitted to.
    fn measured(self) -> &'static str {
        match self {
            Core::Rp2040 => Core::CortexM0.name(),
            c => c.name(),
        }
    }
}

/// How far from the `f64` frame a setting may draw.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Budget {
    /// At most `percent` % of pixels with a channel more than `levels` levels off.
    Beyond {
        /// Levels (0..=255) a channel may be off.
        levels: u8,
        /// Share of pixels, in %, allowed beyond them.
        percent: f64,
    },
    /// A PSNR of at least this many dB.
    Psnr(f64),
}

impl fmt::Display for Budget {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Budget::Beyond { levels, percent } => {
                write!(
                    f,
                    "at most {percent} % of pixels beyond {levels} levels of f64"
                )
            }
            Budget::Psnr(db) => write!(f, "PSNR at least {db} dB against f64"),
        }
    }
}

impl Budget {
    /// Reads `2:1` (levels:percent) or `40dB`.
    pub fn parse(text: &str) -> Option<Budget> {
        if let Some(db) = text.strip_suffix("dB") {
            let db: f64 = db.trim().parse().ok()?;
            return db.is_finite().then_some(Budget::Psnr(db));
        }
        let (levels, percent) = text.split_once(':')?;
        let percent: f64 = percent.trim().trim_end_matches('%').parse().ok()?;
        (percent.is_finite() && percent >= 0.0).then_some(Budget::Beyond {
            levels: levels.trim().parse().ok()?,
            percent,
        })
    }

    fn holds(self, beyond: f64, psnr: f64) -> bool {
        match self {
            Budget::Beyond { percent, .. } => beyond <= percent,
            Budget::Psnr(db) => psnr >= db,
        }
    }

    fn levels(self) -> u8 {
        match self {
            Budget::Beyond { levels, .. } => levels,
            Budget::Psnr(_) => 2,
        }
    }
}

/// The sampling modes the advisor tries: the exact frame, and each block size at bounds
/// 1, 2, 4 and 8 levels.
pub const MODES: [Sampling; 13] = [
    Sampling::Exact,
    Sampling::blocks(BlockSize::Two, 1),
    Sampling::blocks(BlockSize::Two, 2),
    Sampling::blocks(BlockSize::Two, 4),
    Sampling::blocks(BlockSize::Two, 8),
    Sampling::blocks(BlockSize::Four, 1),
    Sampling::blocks(BlockSize::Four, 2),
    Sampling::blocks(BlockSize::Four, 4),
    Sampling::blocks(BlockSize::Four, 8),
    Sampling::blocks(BlockSize::Eight, 1),
    Sampling::blocks(BlockSize::Eight, 2),
    Sampling::blocks(BlockSize::Eight, 4),
    Sampling::blocks(BlockSize::Eight, 8),
];

/// The features of the cost model, in the order of [`Work::counts`] and of
/// [`Model::coefficients`]. A ray's cost grows with the objects it is tested against:
/// those features are rays times objects.
pub const FEATURES: [&str; 15] = [
    "pixels",
    "pure-geometry rays",
    "level-plane rays × objects",
    "fast rays × objects",
    "reference rays × objects",
    "shadow rays × objects",
    "diffuse terms",
    "specular terms",
    "tile lookups",
    "reflected rays × objects",
    "cone tests",
    "transmitted rays × objects",
    "texel lookups",
    "blocks' corners × objects",
    "filled pixels",
];

/// What a frame does, counted on the host ([`work`]): the model's features.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Work {
    /// One count per entry of [`FEATURES`].
    pub counts: [f64; FEATURES.len()],
    /// Whether the frame was drawn in blocks ([`Frame::sampled`]): a mode whose blocks
    /// the scene's kind refuses draws the exact frame.
    pub sampled: bool,
}

impl Work {
    /// The frame's pixels.
    pub fn pixels(&self) -> f64 {
        self.counts[0]
    }
}

/// Draws `scene` with `sampling` as the firmware does (bands of 8 rows, [`Frame::bands`]:
/// each band's bottom corners kept for the next) and counts its [`Work`]; returns the
/// pixels, row after row, with it.
pub fn work<S: Scalar>(scene: &impl AsView<S>, sampling: Sampling) -> (Vec<Rgb888>, Work) {
    const BAND: u16 = 8;
    let view = scene.view();
    let (w, h) = (view.camera.width, view.camera.height);
    let objects = view.objects.len() as f64;
    let frame: Frame<'_, S> = Frame::new(scene).with_sampling(sampling);
    let mut pixels = std::vec![Rgb888::BLACK; usize::from(w) * usize::from(h)];
    let mut c = [0.0; FEATURES.len()];
    let mut filled = 0usize;
    let mut top = 0;
    let mut bands = frame.bands();
    while top < h {
        let rows = top..top.saturating_add(BAND).min(h);
        let at = usize::from(top) * usize::from(w);
        let mut counters = Counters::default();
        filled += bands.render_rows_counted(rows.clone(), &mut pixels[at..], &mut counters);
        // The band's rays go to the kernel that draws its first row (a row the level-plane
        // kernel cannot decide once goes to the fast kernel, `Frame::row_kernel`).
        let rays = f64::from(counters.primary_rays);
        match frame.row_kernel(top) {
            KernelKind::Flat => c[1] += rays,
            KernelKind::Rows => c[2] += rays * objects,
            KernelKind::Fast => c[3] += rays * objects,
            KernelKind::Reference => c[4] += rays * objects,
        }
        c[5] += f64::from(counters.shadow_rays) * objects;
        c[6] += f64::from(counters.diffuse);
        c[7] += f64::from(counters.specular);
        c[8] += f64::from(counters.tile_lookups);
        c[9] += f64::from(counters.reflection_rays) * objects;
        c[10] += f64::from(counters.cone_tests);
        c[11] += f64::from(counters.transmitted_rays) * objects;
        c[12] += f64::from(counters.texel_lookups);
        c[13] += f64::from(counters.corners) * objects;
        top = rows.end;
    }
    c[0] = f64::from(w) * f64::from(h);
    c[14] = filled as f64;
    (
        pixels,
        Work {
            counts: c,
            sampled: frame.sampled(),
        },
    )
}

/// One core × format's cost model: instructions per frame = Σ coefficient × count.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Model {
    /// The core ([`Core::name`]).
    pub core: &'static str,
    /// The number format.
    pub format: &'static str,
    /// Instructions per unit of each feature of [`FEATURES`].
    pub coefficients: [f64; FEATURES.len()],
    /// Whether sampled frames were counted on this core in this format (an I32F32
    /// firmware with the sampling code and the shipped scenes overflows the Arm boards'
    /// 256 KB of flash): without them the advisor offers only the exact frame.
    pub sampled: bool,
    /// The frames measured.
    pub frames: usize,
    /// The median and largest |predicted − counted| / counted over those frames, each
    /// scene left out of the fit that predicts it.
    pub error: (f64, f64),
}

impl Model {
    /// The model of `core` in `format`, if calibrated.
    pub fn of(core: Core, format: &str) -> Option<&'static Model> {
        MODELS
            .iter()
            .find(|m| m.core == core.measured() && m.format == format)
    }

    /// Instructions per pixel predicted for `work`.
    pub fn per_pixel(&self, work: &Work) -> f64 {
        let total: f64 = self
            .coefficients
            .iter()
            .zip(work.counts)
            .map(|(a, x)| a * x)
            .sum();
        total / work.pixels().max(1.0)
    }
}

/// One format × mode the advisor tried.
#[derive(Debug, Clone, PartialEq)]
pub struct Candidate {
    /// The number format.
    pub format: &'static str,
    /// The sampling mode.
    pub sampling: Sampling,
    /// Whether the frame was drawn in blocks ([`Frame::sampled`]): a scene the blocks'
    /// certificates do not cover is drawn exact in every mode.
    pub sampled: bool,
    /// Predicted cost per pixel, in the core's [`Core::unit`].
    pub cost: f64,
    /// The cost's relative error: the model's stated largest (scenes left out), or 0
    /// for a count.
    pub cost_error: f64,
    /// Share of pixels, in %, with a channel beyond the budget's levels of `f64`.
    pub beyond: f64,
    /// PSNR against the `f64` exact frame, in dB (infinite when equal).
    pub psnr: f64,
    /// Whether it holds the budget.
    pub holds: bool,
}

/// The advisor's answer: every candidate tried, cheapest first.
#[derive(Debug, Clone, PartialEq)]
pub struct Advice {
    /// The core priced.
    pub core: Core,
    /// The budget.
    pub budget: Budget,
    /// Every format × mode with a cost model, cheapest first.
    pub candidates: Vec<Candidate>,
}

impl Advice {
    /// The cheapest candidate that holds the budget, if any does.
    pub fn choice(&self) -> Option<&Candidate> {
        self.candidates.iter().find(|c| c.holds)
    }
}

/// Why the advisor could not answer.
#[derive(Debug, Clone, PartialEq)]
pub enum AdviseError {
    /// The scene does not parse in `f64`, the reference (every format would refuse it).
    Scene(SceneError),
    /// No format parses the scene but `f64`, or no model is calibrated for the core.
    NoCandidate,
}

impl fmt::Display for AdviseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            AdviseError::Scene(e) => write!(f, "the scene does not parse: {e}"),
            AdviseError::NoCandidate => write!(
                f,
                "no number format draws this scene on this core (each refused it, or has no \
                 cost model): try `render --format f64` to see the scene's own errors"
            ),
        }
    }
}

impl std::error::Error for AdviseError {}

/// The frame drawn in the reference format, exact: what every candidate is compared with.
fn reference(text: &str) -> Result<Vec<Rgb888>, AdviseError> {
    let scene = LargeScene::<f64>::parse(text).map_err(AdviseError::Scene)?;
    Ok(work(&scene, Sampling::Exact).0)
}

/// Share of pixels (%) beyond `levels` in some channel, and the PSNR (dB).
fn accuracy(pixels: &[Rgb888], reference: &[Rgb888], levels: u8) -> (f64, f64) {
    let mut beyond = 0usize;
    let mut squared = 0u64;
    for (a, b) in pixels.iter().zip(reference) {
        let d = [
            a.r().abs_diff(b.r()),
            a.g().abs_diff(b.g()),
            a.b().abs_diff(b.b()),
        ];
        if d.iter().any(|&d| d > levels) {
            beyond += 1;
        }
        squared += d.iter().map(|&d| u64::from(d) * u64::from(d)).sum::<u64>();
    }
    let n = pixels.len().max(1) as f64;
    let mse = squared as f64 / (3.0 * n);
    let psnr = if mse == 0.0 {
        f64::INFINITY
    } else {
        10.0 * (255.0f64 * 255.0 / mse).log10()
    };
    (100.0 * beyond as f64 / n, psnr)
}

/// How a candidate is priced: its format, mode, whether it is drawn in blocks and its
/// work, to its cost per pixel and that cost's relative error; `None` leaves it out.
pub type Price<'a> = dyn FnMut(&'static str, Sampling, bool, &Work) -> Option<(f64, f64)> + 'a;

/// The candidates of format `S`: each mode of [`MODES`] `price` prices, or none when the
/// format refuses the scene.
fn candidates<S: Scalar>(
    text: &str,
    budget: Budget,
    reference: &[Rgb888],
    price: &mut Price<'_>,
) -> Vec<Candidate> {
    let Ok(scene) = LargeScene::<S>::parse(text) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for sampling in MODES {
        let (pixels, work) = work(&scene, sampling);
        let sampled = work.sampled;
        let Some((cost, cost_error)) = price(S::NAME, sampling, sampled, &work) else {
            continue;
        };
        let (beyond, psnr) = accuracy(&pixels, reference, budget.levels());
        out.push(Candidate {
            format: S::NAME,
            sampling,
            sampled,
            cost,
            cost_error,
            beyond,
            psnr,
            holds: budget.holds(beyond, psnr),
        });
    }
    out
}

/// The price of a candidate on `core` by its calibrated model ([`Model`]): `None` when
/// the core × format has none, or the frame is drawn in blocks and none was counted.
pub fn model_price(core: Core, format: &str, sampled: bool, work: &Work) -> Option<(f64, f64)> {
    let model = Model::of(core, format)?;
    if sampled && !model.sampled {
        return None;
    }
    let scale = match core {
        Core::Rp2040 => RP2040_CYCLES_PER_INSTRUCTION,
        _ => 1.0,
    };
    Some((model.per_pixel(work) * scale, model.error.1))
}

/// The cheapest main format and sampling mode that draw the scene `text` within `budget`
/// on `core`, priced by the calibrated models ([`model_price`]), with every candidate's
/// figures ([`Advice`]). Texture files are not read: a scene that names one is refused
/// by every format.
pub fn advise(text: &str, core: Core, budget: Budget) -> Result<Advice, AdviseError> {
    advise_with(text, core, budget, &mut |format, _, sampled, work| {
        model_price(core, format, sampled, work)
    })
}

/// [`advise`] with the candidates priced by `price` (counts measured on the chip, for
/// instance: `cargo xtask advise` counts each candidate's frame under QEMU).
pub fn advise_with(
    text: &str,
    core: Core,
    budget: Budget,
    price: &mut Price<'_>,
) -> Result<Advice, AdviseError> {
    let reference = reference(text)?;
    let mut all: Vec<Candidate> = Vec::new();
    for format in MAIN.into_iter().filter(|f| *f != REFERENCE) {
        all.extend(
            crate::with_format!(format, candidates(text, budget, &reference, price))
                .unwrap_or_default(),
        );
    }
    if all.is_empty() {
        return Err(AdviseError::NoCandidate);
    }
    all.sort_by(|a, b| a.cost.total_cmp(&b.cost));
    Ok(Advice {
        core,
        budget,
        candidates: all,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn modes_and_budgets_read_back() {
        for m in MODES {
            assert_eq!(m.to_string().parse(), Ok(m));
        }
        assert_eq!(
            Budget::parse("2:1"),
            Some(Budget::Beyond {
                levels: 2,
                percent: 1.0
            })
        );
        assert_eq!(Budget::parse("40dB"), Some(Budget::Psnr(40.0)));
        assert_eq!(Budget::parse("2:-1"), None);
        assert_eq!(Budget::parse("fast"), None);
        for c in Core::ALL {
            assert_eq!(Core::from_name(c.name()), Some(c));
        }
    }

    #[test]
    fn accuracy_counts_pixels_beyond_the_levels() {
        let a = [Rgb888::new(10, 10, 10), Rgb888::new(0, 0, 0)];
        let b = [Rgb888::new(13, 10, 10), Rgb888::new(0, 0, 1)];
        let (beyond, psnr) = accuracy(&a, &b, 2);
        assert_eq!(beyond, 50.0);
        assert!(psnr.is_finite() && psnr > 40.0);
        assert_eq!(accuracy(&a, &a, 0), (0.0, f64::INFINITY));
    }
}
