//! Tracing under the crate's own rules (`docs/scene-format.md`): the nearest root of every
//! shape, secondary rays spawned off the surface by its computed error bound, the normal
//! facing the ray, glints divided by the light distance, and mirrors that show
//! `(1 − K) own + K reflected` to [`MAX_REFLECTION_DEPTH`].
//!
//! A chain of mirrors is followed by a loop, not a recursion: each mirror's own colour
//! and weight wait in a list of [`MAX_REFLECTION_DEPTH`] entries and are blended from
//! the deepest back, in the order (and with the rounding) of the nested definition
//! `c₀ = (1 − K₀) own₀ + K₀ ((1 − K₁) own₁ + K₁ (…))`. A chain costs that list, not a
//! stack frame per bounce.

use heapless::Vec;

use super::color::{add_sat, to_rgb888};
use super::light::{Lit, Passage, light_with, spared};
use super::rules::{Fixray, RuleSet, Tracer};
use super::stages::{LightStages, Stages};
use super::{Incoming, MAX_REFLECTION_DEPTH, PlaneSides, Traced, surface};
use crate::geometry::{ShadowCone, sides_differ, surface_tolerance};
use crate::scene::PixelRay;
use crate::stats::{Counters, count};
use crate::{
    Color, Hit, Light, Material, Miss, PlaneFrame, Ray, Rules, Scalar, SceneView, Shape, Vec3,
};
use embedded_graphics_core::pixelcolor::Rgb888;

/// The mirrors a chain holds: [`MAX_REFLECTION_DEPTH`] (a `u8` widened at compile time;
/// `usize::from` is not `const`).
const CHAIN: usize = MAX_REFLECTION_DEPTH as usize;

/// A mirror's reflected ray (`None` when it does not fit the format: the mirror then
/// shows the background) and its weight `K`.
type Mirror<S> = (Option<Ray<S>>, S);

/// The colour of a hit on `objects[index]` with the stages of `T`, its mirror chain
/// included (see the module documentation). `ray` is the ray that arrived: on the fast
/// kernel an unnormalised direction with the planes' sides (`Incoming`); the reflected
/// rays are the reference path's.
pub(crate) fn shade<S: Scalar, T: Stages>(
    scene: &SceneView<'_, S>,
    ray: &Incoming<'_, S>,
    index: usize,
    hit: &Hit<S>,
    counters: &mut Counters,
) -> Color<S> {
    let (mut own, mirror) = own_color::<S, T>(scene, ray, index, hit, 0, counters);
    // Without reflection (`own_color` then finds no mirror) the mirror loop below is not
    // compiled: its locals would sit in this frame under every shading call (stack).
    let Some(mut mirror) = mirror.filter(|_| T::REFLECTION) else {
        return own;
    };
    // Every mirror's own colour and weight, the nearest first: at most
    // MAX_REFLECTION_DEPTH of them reflect (`own_color`), so the list holds them all.
    let mut chain: Vec<(Color<S>, S), CHAIN> = Vec::new();
    let mut depth = 0;
    let mut seen = loop {
        let _ = chain.push((own, mirror.1));
        depth += 1;
        let Some(reflected) = mirror.0 else {
            break scene.background;
        };
        let Some((i, h)) = nearest(scene, &reflected) else {
            break scene.background;
        };
        let (c, m) = own_color::<S, T>(scene, &Incoming::from(&reflected), i, &h, depth, counters);
        match m {
            Some(m) => (own, mirror) = (c, m),
            None => break c,
        }
    };
    for &(own, k) in chain.iter().rev() {
        seen = blend(own, k, seen);
    }
    seen
}

/// `(1 − K) own + K seen` per channel, each product saturating (a mirror's share). Not
/// inlined: its locals would deepen the mirror loop's frame.
#[inline(never)]
fn blend<S: Scalar>(mut own: Color<S>, k: S, seen: Color<S>) -> Color<S> {
    let keep = S::ONE.checked_sub(k).unwrap_or(S::ZERO);
    for (c, s) in own.iter_mut().zip(seen) {
        *c = add_sat(
            c.checked_mul(keep).unwrap_or(S::MAX),
            s.checked_mul(k).unwrap_or(S::MAX),
        );
    }
    own
}

/// A hit's own colour (ambient and lights) and, for a mirror below
/// [`MAX_REFLECTION_DEPTH`], the reflected ray and its weight. Not inlined: its locals
/// (the normal, the lights' terms) stay out of the mirror loop's frame.
#[inline(never)]
fn own_color<S: Scalar, T: Stages>(
    scene: &SceneView<'_, S>,
    ray: &Incoming<'_, S>,
    index: usize,
    hit: &Hit<S>,
    depth: u8,
    counters: &mut Counters,
) -> (Color<S>, Option<Mirror<S>>) {
    // An index comes from a hit; a material index out of the scene shows black.
    let Some((object, material)) = surface(scene, index, hit.point, counters) else {
        return ([S::ZERO; 3], None);
    };
    let mut color = material.ambient;
    let lit = T::LIGHTING && !scene.lights.is_empty();
    let mirror = T::REFLECTION && material.reflective > S::ZERO && depth < MAX_REFLECTION_DEPTH;
    if !lit && !mirror {
        return (color, None);
    }
    let Some(surface_normal) = object.shape.normal_at(hit.point) else {
        return (color, None);
    };
    // The normal facing the incoming ray.
    let facing = if ray
        .dir
        .dot_axis(surface_normal)
        .is_some_and(|d| d > S::ZERO)
    {
        surface_normal.checked_neg().unwrap_or(surface_normal)
    } else {
        surface_normal
    };
    if lit {
        let at = Lit {
            scene,
            ray,
            object,
            index,
            material: &material,
            hit: *hit,
            normal: facing,
            specular: false,
            stages: LightStages::of::<T, S>(scene),
        };
        // The crate's hits never move.
        let _ = light_with::<S, Fixray>(at, &mut color, counters);
    }
    if !mirror {
        return (color, None);
    }
    count(&mut counters.reflection_rays);
    // r = d − 2 (N·d) N
    let reflected = surface_normal
        .dot(ray.dir)
        .and_then(|nd| nd.checked_add(nd))
        .and_then(|two_nd| surface_normal.scale(two_nd))
        .and_then(|n2| ray.dir.diff(n2))
        .and_then(Vec3::unit)
        .and_then(|r| object.shape.spawn_from(ray.base, hit, r));
    (color, Some((reflected, material.reflective)))
}

/// The nearest hit of a ray by the crate's rules. Not inlined: the intersections' locals
/// stay out of the tracer's and the mirror loop's frames.
#[inline(never)]
fn nearest<S: Scalar>(scene: &SceneView<'_, S>, ray: &Ray<S>) -> Option<(usize, Hit<S>)> {
    super::nearest::<S, Fixray>(scene, ray, None)
}

/// Traces a ray with the stages of `T`: its nearest hit and colour.
fn trace<S: Scalar, T: Stages>(
    scene: &SceneView<'_, S>,
    ray: &Ray<S>,
    counters: &mut Counters,
) -> Traced<S> {
    let hit = nearest(scene, ray);
    let color = match &hit {
        Some((i, h)) => shade::<S, T>(scene, &Incoming::from(ray), *i, h, counters),
        None => scene.background,
    };
    Traced { hit, color }
}

/// Whether any object shadows the light at `light` from the shadow ray `ray` (unit
/// direction, the light `dist` along it): [`Shape::occludes`] (the first hit is enough,
/// and planes need no division), and for a light on a surface [`RuleSet::shadows`].
/// The ray starts off the surface it leaves by its computed error bound
/// ([`Shape::spawn`]), so that surface cannot shadow itself.
#[inline(never)] // its locals stay out of the light loop's frame
fn occludes<S: Scalar>(scene: &SceneView<'_, S>, ray: &Ray<S>, dist: S, light: Vec3<S>) -> bool {
    let eps = scene.epsilon;
    scene.objects.iter().any(|o| {
        o.shape.occludes(ray, eps, dist) && !spared(scene, ray.base, ray.dir, light, &o.shape)
    })
}

/// Whether any object meets the segment from `from` to the light at `from + l` (the
/// crate's shadow test, [`Shape::meets_segment`]; a light on a surface: as in
/// [`occludes`]). `sides`: the planes' sides the fast kernel knows, and the light's index.
#[inline(never)]
pub(crate) fn occludes_segment<S: Scalar>(
    scene: &SceneView<'_, S>,
    sides: Option<(PlaneSides<'_, S>, usize)>,
    from: Vec3<S>,
    l: Vec3<S>,
    ll: S,
    tol: S,
    light: Vec3<S>,
) -> bool {
    let spared = |shape: &Shape<S>| spared(scene, from, l, light, shape);
    // The kernel's sides of every object at the hit and at this light, if it has them: a
    // plane whose sides at the hit and at the light have one sign (or are zero) cannot
    // meet the segment (`sides_differ` asks that first), so only the others and the
    // spheres are looked at. Without the frame's bits of this light, every object is.
    if let Some((s, j)) = sides {
        let bits = s.bits.candidates(j);
        if let Some(shadowed) = occluded_among(scene, s, j, bits, (from, l, ll, tol), spared) {
            return shadowed;
        }
    }
    let eps = scene.epsilon;
    scene
        .objects
        .iter()
        .any(|o| o.shape.meets_segment_with(None, from, l, ll, tol, eps) && !spared(&o.shape))
}

/// The shadow test of the segment `(from, l)` (`ll = |l|²`, tolerance `tol`) towards
/// light `j` over the objects of `bits` (bit `i`: object `i`), in object order, with the
/// kernel's sides: a sphere whose shadow cone from the light clearly misses `from` is
/// passed over (`ShadowCone::clears`), a plane whose sides do not differ beyond the
/// tolerance too (`sides_differ`), and the others take their exact segment test, unless
/// `spared` (a light on a surface, `occludes_segment`). `None` when the sides are not
/// every object's (the caller then tests without them). For `occludes_segment` and the
/// level-plane kernel's rows, whose bits are their occluders. Inlined into both, as
/// their own loops were (each caller is a call of its own).
#[inline(always)]
pub(crate) fn occluded_among<S: Scalar>(
    scene: &SceneView<'_, S>,
    sides: PlaneSides<'_, S>,
    j: usize,
    bits: u8,
    (from, l, ll, tol): (Vec3<S>, Vec3<S>, S, S),
    spared: impl Fn(&Shape<S>) -> bool,
) -> Option<bool> {
    let n = sides.at_hit.len();
    if n != scene.objects.len() {
        return None;
    }
    // j < lights and n ≤ FAST_OBJECTS: the product is small (a checked one would call
    // the 64-bit multiply helper on a Cortex-M0).
    let at_light = sides.at_lights.get(j * n..)?.get(..n)?;
    // Only the scene's objects (at most 8: `SideBits`).
    let mut bits = bits & u8::MAX.checked_shr(u32::try_from(8 - n.min(8)).ok()?)?;
    while bits != 0 {
        let i = usize::try_from(bits.trailing_zeros()).ok()?;
        bits &= bits - 1;
        let (o, &a0, &a1) = (
            scene.objects.get(i)?,
            sides.at_hit.get(i)?,
            at_light.get(i)?,
        );
        let maybe = match o.shape {
            Shape::Sphere(_) => !ShadowCone::any_clears(sides.cones, j, i, l, ll),
            // Both ends on one side of the plane (or one on it): no crossing, as
            // `crossing_of_sides` decides first (here without the calls).
            Shape::Plane(_)
            | Shape::Tiled { .. }
            | Shape::Finite(_)
            | Shape::Textured(_)
            | Shape::Triangle(_) => sides_differ(a0, a1, tol),
            Shape::Revsurf(_) => true,
        };
        if maybe
            && o.shape
                .meets_segment_with(Some((a0, a1)), from, l, ll, tol, scene.epsilon)
            && !spared(&o.shape)
        {
            return Some(true);
        }
    }
    Some(false)
}

impl RuleSet for Fixray {
    const RULES: Rules = Rules::Fixray;

    #[inline]
    fn intersect<S: Scalar>(shape: &Shape<S>, ray: &Ray<S>, epsilon: S) -> Result<Hit<S>, Miss> {
        shape.intersect(ray, epsilon)
    }

    fn meets_segment<S: Scalar>(
        shape: &Shape<S>,
        from: Vec3<S>,
        l: Vec3<S>,
        ll: S,
        tol: S,
        epsilon: S,
    ) -> bool {
        shape.meets_segment(from, l, ll, tol, epsilon)
    }

    fn blocks<S: Scalar>(shape: &Shape<S>, ray: &Ray<S>, epsilon: S, dist: S) -> bool {
        shape.occludes(ray, epsilon, dist)
    }
}

impl Tracer for Fixray {
    const SKIPS_OWN: bool = false;
    const STRICT_CONE: bool = false;
    const GLINT_FALLOFF: bool = true;

    fn trace_pixel<S: Scalar, T: Stages>(
        scene: &SceneView<'_, S>,
        pixel: &PixelRay<S>,
        counters: &mut Counters,
    ) -> Traced<S> {
        trace::<S, T>(scene, &pixel.ray, counters)
    }

    fn trace<S: Scalar, T: Stages>(
        scene: &SceneView<'_, S>,
        ray: &Ray<S>,
        counters: &mut Counters,
    ) -> Traced<S> {
        trace::<S, T>(scene, ray, counters)
    }

    /// Rounding, ties away from zero ([`crate::shade::to_rgb888`]).
    fn to_pixel<S: Scalar>(c: Color<S>) -> Rgb888 {
        to_rgb888(c)
    }

    /// The checkerboard anchored at the plane's `point`, odd tiles alternate.
    fn shows_alt<S: Scalar>(frame: &PlaneFrame<S>, point: Vec3<S>) -> bool {
        frame.odd_tile(point) == Some(true)
    }

    fn glints<S: Scalar>(material: &Material<S>) -> bool {
        material.specular > S::ZERO
    }

    /// How far the hit may lie off its surface (its computed error bound); with shadows
    /// and no such bound in the format, the ray path for every light.
    fn segment_tolerance<S: Scalar>(
        stages: LightStages,
        ray: &Incoming<'_, S>,
        hit: &Hit<S>,
    ) -> Option<S> {
        if stages.shadows {
            let m = ray.base.max_abs().max(hit.point.max_abs());
            surface_tolerance(hit.t, m)
        } else {
            Some(S::ZERO)
        }
    }

    fn segment_shadow<S: Scalar>(
        at: &Lit<'_, '_, S>,
        (index, light): (usize, &Light<S>),
        to_light: Vec3<S>,
        ll: S,
        tol: S,
    ) -> Passage<S> {
        let sides = at.ray.sides.map(|s| (s, index));
        let from = at.hit.point;
        if occludes_segment(at.scene, sides, from, to_light, ll, tol, light.location) {
            Passage::SHADOWED
        } else {
            Passage::CLEAR
        }
    }

    fn ray_shadow<S: Scalar>(
        at: &Lit<'_, '_, S>,
        light: &Light<S>,
        l: Vec3<S>,
        dist: S,
    ) -> Passage<S> {
        let shadowed = at
            .object
            .shape
            .spawn_from(at.ray.base, &at.hit, l)
            .is_some_and(|r| occludes(at.scene, &r, dist, light.location));
        if shadowed {
            Passage::SHADOWED
        } else {
            Passage::CLEAR
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::shade::{MAX_REFLECTION_DEPTH, trace_pixel};
    use crate::{I16F16, Scalar, Scene};

    /// Two facing mirrors (the screen's plane and one behind the eye): the centre pixel's
    /// chain goes front, back, front, back, front, the last without reflection
    /// (`MAX_REFLECTION_DEPTH`). The loop must give the nested definition
    /// `c = (1 − K) own + K · seen`, folded from the deepest mirror back, exactly in f64
    /// and bit for bit in I16F16 against the same nesting in the format.
    fn facing_mirrors<S: Scalar>() -> ([S; 3], [S; 3]) {
        let text = "rules fixray\n\
            camera c { pixeldim 3 3 worlddim 6 6 viewpoint 3 3 6 }\n\
            background 0.9 0.9 0.9\n\
            material front { ambient 0.6 0.2 0.1 reflective 0.7 }\n\
            material back { ambient 0.1 0.3 0.5 reflective 0.4 }\n\
            plane f { material front normal 0 0 1 point 0 0 -5 }\n\
            plane b { material back normal 0 0 -1 point 0 0 10 }\n";
        let scene = Scene::<S>::parse(text).unwrap();
        let got = trace_pixel(&scene, 1, 1).color;
        let m = |i: usize| scene.materials[i];
        let blend = |own: [S; 3], k: S, seen: [S; 3]| {
            let keep = S::ONE.checked_sub(k).unwrap();
            let mut c = own;
            for (c, s) in c.iter_mut().zip(seen) {
                *c = c
                    .checked_mul(keep)
                    .unwrap()
                    .checked_add(s.checked_mul(k).unwrap())
                    .unwrap();
            }
            c
        };
        assert_eq!(MAX_REFLECTION_DEPTH, 4);
        let (f, b) = (m(0), m(1));
        let mut want = f.ambient;
        for mat in [b, f, b, f] {
            want = blend(mat.ambient, mat.reflective, want);
        }
        (got, want)
    }

    #[test]
    fn a_mirror_chain_blends_as_the_nested_definition() {
        let (got, want) = facing_mirrors::<f64>();
        assert_eq!(got, want);
        let (got, want) = facing_mirrors::<I16F16>();
        assert_eq!(got, want);
    }
}
