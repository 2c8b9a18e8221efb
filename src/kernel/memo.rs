//! What a fast-kernel scanline keeps from pixel to pixel for its lit plane hits
//! ([`PlaneMemo`]), and which stage sets keep it ([`KernelStages`]).

use super::fast::{self, Primary, Row};
use crate::shade::stages::{AmbientOnly, Diffuse, DiffuseShadows, Full, Stages};
use crate::{Scalar, SceneView};

/// A stage set as the kernels draw it: [`Stages`] and what a fast-kernel scanline drawn
/// with the set keeps from pixel to pixel for its lit plane hits (`Memo`): a
/// [`PlaneMemo`] for the diffuse sets that take the flattened plane shading, nothing
/// (`()`) for the others, so that their scanlines carry no room for it (the deepest
/// I32F32 stack on a 16 KB chip is theirs).
pub(crate) trait KernelStages: Stages {
    /// The scanline's memo.
    type Memo<S: Scalar>: MemoSlot<S> + 'static;
}

impl KernelStages for AmbientOnly {
    type Memo<S: Scalar> = ();
}
impl KernelStages for Diffuse {
    type Memo<S: Scalar> = PlaneMemo<S>;
}
impl KernelStages for DiffuseShadows {
    type Memo<S: Scalar> = PlaneMemo<S>;
}
impl KernelStages for Full {
    type Memo<S: Scalar> = ();
}

/// A plane's normal facing the eye (whether it is the plane's normal turned), and the
/// world axis it lies along if it does (`Vec3::world_axis`).
pub(super) type Facing = (bool, Option<(u8, bool)>);

/// How many lights' weights a [`PlaneMemo`] keeps (the others' terms take both
/// products): one, as every shipped scene of the crate's rules has (a scanline of a
/// scene drawn on the reference path carries the memo too, and the deepest I32F32
/// stack on a 16 KB chip, the course's, would have almost nothing to spare with two).
const MEMO_LIGHTS: usize = 1;

/// The material last shaded and, for the first [`MEMO_LIGHTS`] lights, `emissivity ×
/// diffuse` per channel, the first product of every diffuse term, the same for every hit
/// that shows that material (bit `3 × light + channel` of `overflow`: the product does
/// not fit, the term saturates): what a scanline keeps from pixel to pixel for its lit
/// hits, planes' and spheres' (`kernel::shading`).
#[derive(Debug, Clone)]
pub struct Weights<S> {
    /// The material (`None`: none yet).
    material: Option<u8>,
    overflow: u8,
    weights: [[S; 3]; MEMO_LIGHTS],
}

impl<S: Scalar> Default for Weights<S> {
    fn default() -> Self {
        Self {
            material: None,
            overflow: 0,
            weights: [[S::ZERO; 3]; MEMO_LIGHTS],
        }
    }
}

/// What a fast-kernel scanline of a diffuse stage set keeps from pixel to pixel for its
/// lit plane hits (`kernel::shading`; `KernelStages::Memo`): the material's
/// [`Weights`], and the last still plane's hit.
#[derive(Debug, Clone)]
pub struct PlaneMemo<S> {
    pub(super) weights: Weights<S>,
    /// The last still plane's hit (`fast::HitMemo`).
    pub(super) hits: fast::HitMemo<S>,
    /// The quiet planes (`Primary::quiet_planes`) of the scanline it last looked at.
    pub(super) quiet: Option<(u16, fast::Quiet<S>)>,
    /// The last plane shaded: its index and [`Facing`].
    pub(super) facing: Option<(u8, Facing)>,
    /// Whether the scene's lights send every plane hit to the general shading (a light
    /// on a surface, a projector), once asked.
    pub(super) general: Option<bool>,
    /// How the scanline steps its certified blocks ([`fast::Stepping`]): a pixel of a
    /// block whose hit needs only its plane steps that plane's term alone.
    pub(super) stepping: fast::Stepping,
}

impl<S: Scalar> Default for PlaneMemo<S> {
    fn default() -> Self {
        Self {
            weights: Weights::default(),
            hits: fast::HitMemo::default(),
            quiet: None,
            facing: None,
            general: None,
            stepping: fast::Stepping::default(),
        }
    }
}

impl<S: Scalar> PlaneMemo<S> {
    /// The quiet planes of `r`'s scanline, looked for at its first lit plane hit.
    #[inline(always)]
    pub(super) fn quiet(
        &mut self,
        scene: &SceneView<'_, S>,
        p: &Primary<S>,
        r: &Row<S>,
    ) -> fast::Quiet<S> {
        let row = Primary::row_index(r);
        match self.quiet {
            Some((k, q)) if k == row => q,
            _ => {
                let q = p.quiet_planes(scene, r);
                self.quiet = Some((row, q));
                q
            }
        }
    }
}

impl<S: Scalar> Weights<S> {
    /// The weights of material `index` (`material`), formed where they were another's:
    /// one per light of the first [`MEMO_LIGHTS`] ([`Weights::weight`]).
    #[inline(always)]
    pub(super) fn of(
        &mut self,
        scene: &SceneView<'_, S>,
        index: u8,
        material: &crate::Material<S>,
    ) -> &Self {
        if self.material != Some(index) {
            self.overflow = 0;
            for (j, (w, light)) in self.weights.iter_mut().zip(scene.lights).enumerate() {
                for (k, ((w, e), d)) in w
                    .iter_mut()
                    .zip(light.emissivity)
                    .zip(material.diffuse)
                    .enumerate()
                {
                    match e.checked_mul(d) {
                        Some(v) => *w = v,
                        None => self.overflow |= 1 << (3 * j + k),
                    }
                }
            }
            self.material = Some(index);
        }
        self
    }

    /// Light `j`'s weights for the material kept ([`Weights::of`]), and their
    /// three overflow bits; `None` beyond the first [`MEMO_LIGHTS`].
    #[inline(always)]
    pub(super) fn weight(&self, scene: &SceneView<'_, S>, j: usize) -> Option<([S; 3], u8)> {
        if j >= scene.lights.len() {
            return None;
        }
        let w = *self.weights.get(j)?;
        Some((w, (self.overflow >> (3 * j)) & 7))
    }
}

/// A stage set's room for a [`PlaneMemo`] (`KernelStages::Memo`): the memo itself, or `()`
/// where the set's plane hits take the general shading.
pub trait MemoSlot<S>: Default {
    /// The memo, if the set keeps one.
    fn memo(&mut self) -> Option<&mut PlaneMemo<S>>;
}

impl<S> MemoSlot<S> for () {
    #[inline(always)]
    fn memo(&mut self) -> Option<&mut PlaneMemo<S>> {
        None
    }
}

impl<S: Scalar> MemoSlot<S> for PlaneMemo<S> {
    #[inline(always)]
    fn memo(&mut self) -> Option<&mut PlaneMemo<S>> {
        Some(self)
    }
}
