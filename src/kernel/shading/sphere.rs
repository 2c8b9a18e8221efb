//! The fast shading of a lit sphere hit ([`lit_sphere_color`]): the crate's shading of it
//! flattened, as `shading.rs` flattens a lit plane hit's, with its own sphere left out of
//! its shadow test where a certificate decides it ([`own_sphere_clear`]).

use super::{LightTerms, light_plane_hit, segment_tolerance, shadowed_but_own};
use crate::kernel::fast;
use crate::kernel::memo::Weights;
use crate::shade::stages::Stages;
use crate::shade::{PlaneSides, channel_max, diffuse_falloff_outlined, occludes_segment};
use crate::stats::Counters;
use crate::{Beam, Color, Light, Scalar, SceneView, Shape};

/// The colour of the fast kernel's hit `h` on a sphere under a diffuse stage set (lights,
/// with or without shadows: no glint, cone, mirror or translucence) in a fixed format
/// (`None` for any other, in a build without the kernels, or for another shape; a float
/// format keeps the general shading alone, whose copy a Cortex-M0 firmware holds anyway:
/// flash): the crate's shading of it
/// (`own_color`, `light_with` and `segment_terms` of `shade/`) flattened to what such a
/// hit needs, the same operations in the same order, so the same colour bit for bit
/// (tested against the general shading, `kernel/fast/invariants.rs`): the sphere's own
/// material, its normal at the hit (`Sphere::normal_at`) turned to face the ray, then
/// each light's `L`, `|L|²`, `N·L`, shadow segment (`occludes_segment`, with the planes'
/// sides the caller formed) and term (its `emissivity × diffuse` from `weights`, the
/// scanline's, where the caller keeps them). `None` where the pixel needs the general shading:
/// a light on a surface, a projector, a light whose `|L|²` does not fit or is not
/// positive (the general path's ray terms; the statistics then count the earlier lights
/// twice, as for plane hits), or a segments' tolerance that does not fit.
#[inline(always)]
pub(in crate::kernel) fn lit_sphere_color<S: Scalar, T: Stages>(
    scene: &SceneView<'_, S>,
    h: &fast::FastHit<S>,
    sides: Option<PlaneSides<'_, S>>,
    weights: Option<&mut Weights<S>>,
    counters: &mut Counters,
) -> Option<Color<S>> {
    let diffuse_set = T::LIGHTING && !T::SPECULAR && !T::CONES && !T::REFLECTION;
    if !(crate::kernel::KERNELS && S::EXACT_PRODUCTS && diffuse_set && !T::TRANSPARENCY) {
        return None;
    }
    let shadows = T::SHADOWS && scene.shadows;
    lit_sphere_with(scene, h, sides, weights, shadows, counters)
}

/// [`lit_sphere_color`] with the stage set's shadows as a value (`shadows`: the set's
/// and the scene's, `LightStages::of`): one copy per format.
#[inline(never)]
fn lit_sphere_with<S: Scalar>(
    scene: &SceneView<'_, S>,
    h: &fast::FastHit<S>,
    sides: Option<PlaneSides<'_, S>>,
    weights: Option<&mut Weights<S>>,
    shadows: bool,
    counters: &mut Counters,
) -> Option<Color<S>> {
    let object = scene.objects.get(h.index)?;
    let Shape::Sphere(sphere) = &object.shape else {
        return None;
    };
    if scene.lights_on_surfaces
        || scene
            .lights
            .iter()
            .any(|l| matches!(l.beam, Beam::Projector(_)))
    {
        return None;
    }
    // The tolerance `light_with` forms before its loop (`Fixray::segment_tolerance`);
    // where it does not fit, every light takes the general path's ray terms.
    let tol = if shadows {
        segment_tolerance(scene.camera.viewpoint, h.point, h.t_bound, None)?
    } else {
        S::ZERO
    };
    // As `surface` (a sphere's material is its own; one out of the scene shows black).
    let Some(material) = scene.materials.get(usize::from(object.material)) else {
        return Some([S::ZERO; 3]);
    };
    let color = material.ambient;
    if scene.lights.is_empty() {
        return Some(color);
    }
    let Some((normal, excess)) = sphere.normal_and_excess(h.point) else {
        return Some(color);
    };
    // The normal facing the incoming ray.
    let turned = h.dir.dot_axis(normal).is_some_and(|d| d > S::ZERO);
    let facing = if turned {
        normal.checked_neg().unwrap_or(normal)
    } else {
        normal
    };
    // Where the sphere's own segment test is decided without it ([`own_sphere_clear`]),
    // the other objects alone are tested.
    let own = excess.filter(|_| !turned);
    if material.diffuse == [S::ZERO; 3] {
        return Some(color);
    }
    let kept = weights.map(|w| w.of(scene, object.material, material));
    let k = channel_max::<S>();
    let terms = |_: usize, light: &Light<S>| {
        let Some(to_light) = light.location.diff(h.point) else {
            return Some(None);
        };
        let ll = to_light.dot(to_light).filter(|ll| *ll > S::ZERO)?;
        Some(
            to_light
                .dot_axis(facing)
                .filter(|c| *c > S::ZERO)
                .map(|nl| LightTerms {
                    to_light,
                    ll,
                    nl,
                    knl: None,
                }),
        )
    };
    let shadowed = |j: usize, light: &Light<S>, t: &LightTerms<S>| match (sides, own) {
        (Some(_), Some(excess)) if own_sphere_clear(sphere, excess, tol, t) => {
            shadowed_but_own(scene, sides, h, (j, light), t)
        }
        _ => {
            let sides = sides.map(|s| (s, j));
            let (point, to_light) = (h.point, t.to_light);
            Some(occludes_segment(
                scene,
                sides,
                point,
                to_light,
                t.ll,
                tol,
                light.location,
            ))
        }
    };
    light_plane_hit(
        scene,
        color,
        material.diffuse,
        shadows,
        (
            terms,
            shadowed,
            |j| {
                let (w, overflow) = kept.and_then(|w| w.weight(scene, j))?;
                Some((w, u16::from(overflow)))
            },
            |t: &LightTerms<S>| diffuse_falloff_outlined(t.nl, t.nl.checked_mul(k), t.ll),
        ),
        counters,
    )
}

/// Whether the segment from a hit on `sphere` towards a light (`t`: `L`, `|L|²` and
/// `N·L` with the sphere's normal, not turned, from its three products in a fixed format,
/// [`Sphere::normal_and_excess`] with `excess = r² − |P − C|²`; `tol` the segments'
/// tolerance) is certainly not stopped by the sphere itself: `Sphere::meets_segment`
/// says no. With `N` within `1/64` of `(P − C)/r` per component and `N·L` rounded once,
/// `64·(N·L − DELTA) > ‖L‖₁` makes `(P − C)·L` positive, so its `b` is not negative;
/// with `f₀ = −excess ≥ −(2r + tol)·tol` (on the surface within the tolerance, or
/// outside it) and `b ≥ 0` the test says no wherever its quantities fit, which `4·|L|²`
/// and `4·r²` fitting ensures (`|f₁| ≤ |f₀| + |P − C|² + 2|L|²`). Tested with the
/// sphere's shading against the general one (`kernel/tests.rs`).
#[inline(always)]
pub(in crate::kernel) fn own_sphere_clear<S: Scalar>(
    sphere: &crate::Sphere<S>,
    excess: S,
    tol: S,
    t: &LightTerms<S>,
) -> bool {
    let clear = || -> Option<bool> {
        let band = sphere
            .radius()
            .checked_add(sphere.radius())?
            .checked_add(tol)?
            .checked_mul(tol)?;
        t.ll.checked_mul_int(4)?;
        sphere.radius_sq().checked_mul_int(4)?;
        let l1 = t.to_light.x.abs().checked_add(t.to_light.y.abs())?;
        let l1 = l1.checked_add(t.to_light.z.abs())?;
        let margin = t.nl.checked_sub(S::DELTA)?.checked_mul_int(64)?;
        Some(excess <= band && margin > l1)
    };
    clear() == Some(true)
}
