//! The lights' share of a hit's colour: diffuse, specular glints, spotlight cones and
//! shadow rays.

use super::color::{add_sat, term};
use super::rules::Tracer;
use super::stages::LightStages;
use super::{Incoming, in_own_plane, light_tolerance};
use crate::stats::{Counters, count};
use crate::{Beam, Color, Hit, Light, Material, Object, Ray, RayKind, Scalar, SceneView, Vec3};

/// A light's share of a hit, as one light path works it out: `(255·cos/dist,
/// 255·(N·H)^shininess/dist, the light's filter)`; `None` when the light does not light
/// the point.
type Terms<S> = Option<(S, S, Option<[S; 3]>)>;

/// What a shadow test found between a hit and a light, by a rule set's `Tracer`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Passage<S> {
    /// `None`: in shadow. Otherwise what passes: the occluders' filter (`None`: passes
    /// everything) and, for the course, the share of the segment at which it enters the
    /// translucent sphere nearest the light, where that sets the falloff.
    pub(crate) lit: Option<(Option<[S; 3]>, Option<S>)>,
    /// The course's shadow ray went on past a translucent occluder: the hit moves
    /// (`Tracer::moved_hit`). Never set by the crate's rules.
    pub(crate) continues: bool,
}

impl<S> Passage<S> {
    /// Nothing in the way.
    pub(crate) const CLEAR: Self = Self {
        lit: Some((None, None)),
        continues: false,
    };
    /// In shadow.
    pub(crate) const SHADOWED: Self = Self {
        lit: None,
        continues: false,
    };
}

/// The lights' share of a hit's colour under the rule set `R`, added to `color` (see
/// [`crate::shade::Fixray`]'s and [`crate::shade::Course`]'s tracers). `at.normal` is the one
/// the rules light with (facing the ray, or as given). Not inlined: its locals are not part of the
/// frames of the tracers' loops.
///
/// A light whose `L = light − hit` squares within the format is lit by [`segment_terms`]
/// (no square root, one division per light for diffuse light, shadow segments decided
/// by comparisons), any other by [`ray_terms`] (the normalised direction to the light
/// and a shadow ray along it), under either rule set.
///
/// Under the course rules a sphere's hit can move while its lights are summed
/// (`Tracer::moved_hit`): the lights after that one are lit from the new point, and the
/// point and normal it moved to are returned (`None`: it stayed), for the rays leaving
/// the hit.
#[inline(never)]
pub(super) fn light_with<S: Scalar, R: Tracer>(
    mut at: Lit<'_, '_, S>,
    color: &mut Color<S>,
    counters: &mut Counters,
) -> Option<(Vec3<S>, Vec3<S>)> {
    at.specular = at.stages.specular && R::glints(at.material);
    if at.material.diffuse == [S::ZERO; 3] && !at.specular {
        return None;
    }
    // How far the hit may lie off its surface: the segment tests' tolerance.
    let tol = R::segment_tolerance(at.stages, at.ray, &at.hit);
    let mut moved = None;
    for (j, light) in at.scene.lights.iter().enumerate() {
        let Some(to_light) = light.location.diff(at.hit.point) else {
            continue;
        };
        let (terms, continues) = match (to_light.dot(to_light), tol) {
            (Some(ll), Some(tol)) if ll > S::ZERO => {
                segment_terms::<S, R>(&at, (j, light), to_light, ll, tol, counters)
            }
            _ => ray_terms::<S, R>(&at, light, to_light, counters),
        };
        if continues
            && let Some((point, normal)) = R::moved_hit(at.object, at.hit.point, light.location)
        {
            at.hit.point = point;
            at.normal = normal;
            moved = Some((point, normal));
        }
        let Some((diffuse_falloff, glint, filter)) = terms else {
            continue;
        };
        count(&mut counters.diffuse);
        let mut emissivities = light.emissivity;
        if let Some(f) = filter {
            for (e, fk) in emissivities.iter_mut().zip(f) {
                *e = e.checked_mul(fk).unwrap_or(S::ZERO);
            }
        }
        for ((c, diffuse), emissivity) in
            color.iter_mut().zip(at.material.diffuse).zip(emissivities)
        {
            *c = add_sat(*c, term([emissivity, diffuse, diffuse_falloff]));
            if at.specular {
                *c = add_sat(*c, term([emissivity, at.material.specular, glint]));
            }
        }
    }
    moved
}

/// What every light of a hit shares.
pub(crate) struct Lit<'a, 'b, S> {
    pub(crate) scene: &'a SceneView<'b, S>,
    pub(crate) ray: &'a Incoming<'b, S>,
    pub(crate) object: &'a Object<S>,
    /// The object's index (the course's shadow rays skip it).
    #[cfg_attr(not(feature = "course"), allow(dead_code))] // read by the course's rules only
    pub(crate) index: usize,
    pub(crate) material: &'a Material<S>,
    pub(crate) hit: Hit<S>,
    pub(crate) normal: Vec3<S>,
    /// Whether the material shows a glint (set by [`light_with`]).
    pub(crate) specular: bool,
    pub(crate) stages: LightStages,
}

/// 255 in the format (or its largest value).
pub(crate) fn channel_max<S: Scalar>() -> S {
    S::from_i32(255).unwrap_or(S::MAX)
}

/// A light's diffuse term in channel units, `255·(N·L)/|L|²` (`nl = N·L`, `ll = |L|²`),
/// scaled to channel units before the division where that fits (the quotient then keeps
/// the format's relative precision); the largest value when it does not fit.
/// `knl` is `255·N·L` where it fits (a kernel that knows it for a whole row passes it).
#[inline]
pub(crate) fn diffuse_falloff<S: Scalar>(nl: S, knl: Option<S>, ll: S) -> S {
    match knl {
        Some(knl) => knl.checked_div(ll),
        None => nl
            .checked_div(ll)
            .and_then(|q| q.checked_mul(channel_max::<S>())),
    }
    .unwrap_or(S::MAX)
}

/// [`diffuse_falloff`] as the general light loop calls it: out of line in the 64-bit
/// formats, the fast kernel's copy ([`diffuse_falloff_outlined`]: their 128-bit
/// division once in flash), inlined in the others, where it is short.
#[inline(always)]
pub(crate) fn diffuse_falloff_in_loop<S: Scalar>(nl: S, knl: Option<S>, ll: S) -> S {
    if core::mem::size_of::<S>() > 4 {
        diffuse_falloff_outlined(nl, knl, ll)
    } else {
        diffuse_falloff(nl, knl, ll)
    }
}

/// [`diffuse_falloff`] out of line: what the fast kernel's plane hits call (inlined into
/// their light loop, the division crowds its registers), and the general light loop in
/// the 64-bit formats ([`diffuse_falloff_in_loop`]).
#[inline(never)]
pub(crate) fn diffuse_falloff_outlined<S: Scalar>(nl: S, knl: Option<S>, ll: S) -> S {
    diffuse_falloff(nl, knl, ll)
}

/// Whether a light at `light` lies in the plane of the surface it would light (see
/// [`in_own_plane`]); asked only where the plan found a light on a surface.
fn on_own_plane<S: Scalar>(at: &Lit<'_, '_, S>, light: Vec3<S>) -> bool {
    at.scene.lights_on_surfaces
        && in_own_plane(
            &at.object.shape,
            light,
            light_tolerance(at.scene.epsilon, light, at.scene.camera.viewpoint),
        )
}

/// One light's terms with `L = light − hit` unnormalised and `ll = L·L`: `cos/dist =
/// (N·L)/|L|²` (one division, no square root); the cone test compares `(−L·axis)²` with
/// `cos²θ·|L|²`; the shadow test is the rule set's segment test
/// (`Tracer::segment_shadow`). Only a specular glint normalises `L` (its half vector
/// needs the unit direction). The `bool`: whether the course's hit moves
/// ([`Passage::continues`]). Not inlined (nor is [`ray_terms`]): the two would share
/// the light loop's frame.
#[inline(never)]
fn segment_terms<S: Scalar, R: Tracer>(
    at: &Lit<'_, '_, S>,
    (index, light): (usize, &Light<S>),
    to_light: Vec3<S>,
    ll: S,
    tol: S,
    counters: &mut Counters,
) -> (Terms<S>, bool) {
    let mut continues = false;
    let mut terms = || -> Terms<S> {
        let nl = to_light.dot_axis(at.normal).filter(|c| *c > S::ZERO)?;
        if on_own_plane(at, light.location) {
            return None;
        }
        if at.stages.cones
            && let Some(cone) = light.cone()
        {
            count(&mut counters.cone_tests);
            // cos(angle) = (−L·axis)/|L| ≥ cos θ, squared with the signs kept.
            let c = to_light.dot(cone.axis)?.checked_neg()?;
            let cos2 = cone.cos_theta.checked_mul(cone.cos_theta)?;
            let beyond = S::cmp_products(c, c, cos2, ll);
            use core::cmp::Ordering::{Greater, Less};
            let inside = match (cone.cos_theta >= S::ZERO, R::STRICT_CONE) {
                (true, false) => c >= S::ZERO && beyond != Some(Less),
                (true, true) => c > S::ZERO && beyond == Some(Greater),
                (false, false) => c >= S::ZERO || beyond != Some(Greater),
                (false, true) => c >= S::ZERO || beyond == Some(Less),
            };
            if !inside {
                return None;
            }
        }
        let mut filter = match light.beam {
            Beam::Projector(_) => projected(at.scene, light, to_light, counters)?,
            _ => None,
        };
        let mut entered = None;
        if at.stages.shadows {
            count(&mut counters.shadow_rays);
            let passage = R::segment_shadow(at, (index, light), to_light, ll, tol);
            continues = passage.continues;
            let (f, e) = passage.lit?;
            filter = combine(filter, f);
            entered = e;
        }
        let k = channel_max::<S>();
        let mut diffuse_falloff = diffuse_falloff_in_loop(nl, nl.checked_mul(k), ll);
        // Through a translucent sphere (the course's, `Passage::lit`): cos/dist' with
        // dist' = (1 − s)|L| from the entry point nearest the light, s its share of L.
        if let Some(e) = entered {
            diffuse_falloff = S::ONE
                .checked_sub(e)
                .and_then(|r| diffuse_falloff.checked_div(r))
                .unwrap_or(S::MAX);
        }
        let glint = if at.specular {
            count(&mut counters.specular);
            to_light
                .normalize()
                .and_then(|n| {
                    let g = glint_of(at, n.unit)?.checked_mul(k)?;
                    if R::GLINT_FALLOFF {
                        n.divide(g)
                    } else {
                        Some(g)
                    }
                })
                .unwrap_or(S::ZERO)
        } else {
            S::ZERO
        };
        Some((diffuse_falloff, glint, filter))
    };
    let terms = terms();
    (terms, continues)
}

/// A projector's filter for the point `light − to_light`: the texel where the ray from
/// the projector to the point crosses its slide's plane (ahead of the projector, no
/// screen rule), as a share of 255 per channel; `None` when the crossing misses the
/// slide (the projector does not light the point). `Some(None)` for other lights.
#[allow(clippy::option_option)]
#[inline(never)]
fn projected<S: Scalar>(
    scene: &SceneView<'_, S>,
    light: &Light<S>,
    to_light: Vec3<S>,
    counters: &mut Counters,
) -> Option<Option<[S; 3]>> {
    let Beam::Projector(i) = light.beam else {
        return Some(None);
    };
    // Without the `textures` feature no scene has a projector (the parser refuses them):
    // the texel lookup is not linked.
    if !cfg!(feature = "textures") {
        return None;
    }
    count(&mut counters.texel_lookups);
    let slide = scene.projectors.get(usize::from(i))?;
    let plane = slide.frame.plane();
    // x = light + s (point − light) = light − s L with N·x = D'.
    let num = S::sub_dot3(
        plane.offset(),
        plane.normal().to_array(),
        light.location.to_array(),
    )?;
    let den = plane.normal().dot(to_light)?.checked_neg()?;
    let s = num.checked_div(den).filter(|s| *s > S::ZERO)?;
    let x = light.location.diff(to_light.scale(s)?)?;
    if !slide.frame.contains(x) {
        return None;
    }
    let t = super::texture::texel(scene, slide, x)?;
    let share = |v: u8| S::ONE.mul_ratio(i32::from(v), 255).unwrap_or(S::ZERO);
    Some(Some([share(t[0]), share(t[1]), share(t[2])]))
}

/// Two filters one after the other (`None`: passes everything).
pub(super) fn combine<S: Scalar>(a: Option<[S; 3]>, b: Option<[S; 3]>) -> Option<[S; 3]> {
    match (a, b) {
        (Some(mut a), Some(b)) => {
            for (x, y) in a.iter_mut().zip(b) {
                *x = x.checked_mul(y).unwrap_or(S::ZERO);
            }
            Some(a)
        }
        (a, None) => a,
        (None, b) => b,
    }
}

/// `(N·H)^shininess` for the unit direction `l` to the light (`H` the unit half vector
/// of `l` and the direction to the viewer); `None` when it is not positive.
fn glint_of<S: Scalar>(at: &Lit<'_, '_, S>, l: Vec3<S>) -> Option<S> {
    let to_viewer = at.ray.dir.checked_neg()?;
    let v = if at.ray.unit {
        to_viewer
    } else {
        to_viewer.unit()?
    };
    l.sum(v)
        .and_then(Vec3::unit)
        .and_then(|h| at.normal.dot(h))
        .filter(|nh| *nh > S::ZERO)
        .and_then(|nh| nh.pow_unit(at.material.shininess))
}

/// A light on a surface (only where the plan found one): whether `shape`, which meets
/// the shadow segment from `from` along `l`, spares it (as in [`occludes`]).
pub(super) fn spared<S: Scalar>(
    scene: &SceneView<'_, S>,
    from: Vec3<S>,
    l: Vec3<S>,
    light: Vec3<S>,
    shape: &crate::Shape<S>,
) -> bool {
    scene.lights_on_surfaces
        && shape.spares_light(
            &Ray {
                base: from,
                dir: l,
                kind: RayKind::Secondary,
            },
            light,
            light_tolerance(scene.epsilon, light, scene.camera.viewpoint),
        )
}

/// One light's terms along the normalised direction to the light, with the rule set's
/// shadow ray along it (`Tracer::ray_shadow`), for a light whose `|L|²` does not fit the
/// format. The `bool` as in [`segment_terms`].
#[inline(never)]
fn ray_terms<S: Scalar, R: Tracer>(
    at: &Lit<'_, '_, S>,
    light: &Light<S>,
    to_light: Vec3<S>,
    counters: &mut Counters,
) -> (Terms<S>, bool) {
    let mut continues = false;
    let mut terms = || -> Terms<S> {
        let mut filter = match light.beam {
            Beam::Projector(_) => projected(at.scene, light, to_light, counters)?,
            _ => None,
        };
        let to_light = to_light.normalize()?;
        let l = to_light.unit;
        let cos = at.normal.dot(l).filter(|c| *c > S::ZERO)?;
        if on_own_plane(at, light.location) {
            return None;
        }
        if at.stages.cones
            && let Some(cone) = light.cone()
        {
            count(&mut counters.cone_tests);
            // The angle between the axis and the direction light → point.
            let inside = l
                .checked_neg()
                .and_then(|from_light| from_light.dot(cone.axis))
                .is_some_and(|c| {
                    if R::STRICT_CONE {
                        c > cone.cos_theta
                    } else {
                        c >= cone.cos_theta
                    }
                });
            if !inside {
                return None;
            }
        }
        if at.stages.shadows {
            count(&mut counters.shadow_rays);
            // The distance itself may not fit (a far light): nothing lies beyond it.
            let dist = to_light.length().unwrap_or(S::MAX);
            let passage = R::ray_shadow(at, light, l, dist);
            continues = passage.continues;
            filter = combine(filter, passage.lit?.0);
        }
        // 255 cos / dist and 255 (N·H)^shininess / dist, without forming dist; scaled
        // to channel units first so that the quotient keeps the format's relative
        // precision (cos / dist alone is small: in I20F12 it would keep 10 bits).
        let k = channel_max::<S>();
        let diffuse_falloff = cos
            .checked_mul(k)
            .and_then(|kc| to_light.divide(kc))
            .unwrap_or(S::MAX);
        let glint = if at.specular {
            count(&mut counters.specular);
            let shine = glint_of(at, l).and_then(|p| p.checked_mul(k));
            if R::GLINT_FALLOFF {
                shine.and_then(|g| to_light.divide(g))
            } else {
                shine
            }
            .unwrap_or(S::ZERO)
        } else {
            S::ZERO
        };
        Some((diffuse_falloff, glint, filter))
    };
    let terms = terms();
    (terms, continues)
}
