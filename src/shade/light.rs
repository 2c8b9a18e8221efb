//! The lights' share of a hit's colour: diffuse, specular glints, spotlight cones and
//! shadow rays.

use super::color::{add_sat, term};
use super::stages::LightStages;
use super::{Incoming, PlaneSides, in_own_plane, light_tolerance, occludes};
use crate::geometry::surface_tolerance;
use crate::stats::{Counters, count};
use crate::{Beam, Color, Hit, Light, Material, Object, Ray, RayKind, Scalar, SceneView, Vec3};
use core::cell::Cell;

/// How the course rules light a hit where the crate's own differ (`COURSE-RULES.md` §6,
/// §7, §9): the shadow ray starts on the hit and skips its object (`index`), plane-type
/// occluders keep the screen rule (`z_limit`), the cone is strict, the glint needs a
/// `shininess` and is not divided by the light distance.
#[derive(Debug, Clone, Copy)]
pub(super) struct CourseLight<S> {
    /// The object the hit is on.
    pub(super) index: usize,
    /// The course's screen rule for occluders.
    pub(super) z_limit: S,
}

/// The lights' share of a hit's colour, added to `color` (see [`shade_with`]), by the
/// crate's rules (`course: None`) or the course's. `normal` is the one the rules light
/// with (facing the ray, or as given). Not inlined: its locals are not part of the
/// recursive frames of mirror reflections (on a 16 KB chip in I32F32 they decide whether
/// four reflections fit the stack).
///
/// A light whose `L = light − hit` squares within the format is lit by [`segment_terms`]
/// (no square root, one division per light for diffuse light, shadow segments decided
/// by comparisons), any other by [`ray_terms`] (the normalised direction to the light
/// and a shadow ray along it), under either rule set.
///
/// Under the course rules a sphere's hit can move while its lights are summed (see
/// [`moved_hit`]): the lights after that one are lit from the new point, and `leaving`
/// (the point and normal the rays leaving the hit start from, the hit's own when given)
/// ends where it moved. The crate's rules pass `None`: their recursive mirror frames
/// keep no room for it.
#[inline(never)]
#[allow(clippy::too_many_arguments)]
pub(super) fn light_with<S: Scalar>(
    scene: &SceneView<'_, S>,
    ray: &Incoming<'_, S>,
    object: &Object<S>,
    material: &Material<S>,
    hit: &Hit<S>,
    normal: Vec3<S>,
    course: Option<CourseLight<S>>,
    stages: LightStages,
    color: &mut Color<S>,
    counters: &mut Counters,
    mut leaving: Option<&mut (Vec3<S>, Vec3<S>)>,
) {
    let specular = stages.specular
        && match course {
            None => material.specular > S::ZERO,
            Some(_) => material.specular != S::ZERO && material.shininess > S::ZERO,
        };
    if material.diffuse == [S::ZERO; 3] && !specular {
        return;
    }
    // How far the hit may lie off its surface: the segment tests' tolerance.
    let tol = if stages.shadows && course.is_none() {
        let m = ray.base.max_abs().max(hit.point.max_abs());
        surface_tolerance(hit.t, m)
    } else {
        None
    };
    let mut at = Lit {
        scene,
        ray,
        object,
        material,
        hit: *hit,
        normal,
        specular,
        stages,
        continues: Cell::new(false),
    };
    for (j, light) in scene.lights.iter().enumerate() {
        let Some(to_light) = light.location.diff(at.hit.point) else {
            continue;
        };
        let terms = match to_light.dot(to_light) {
            Some(ll) if ll > S::ZERO && (course.is_some() || tol.is_some() || !stages.shadows) => {
                segment_terms(&at, (j, light), to_light, ll, tol, course, counters)
            }
            _ => ray_terms(&at, light, to_light, course, counters),
        };
        if at.continues.replace(false)
            && let Some((point, normal)) = moved_hit(object, at.hit.point, light.location)
        {
            at.hit.point = point;
            at.normal = normal;
            if let Some(l) = leaving.as_mut() {
                **l = (point, normal);
            }
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
        for ((c, diffuse), emissivity) in color.iter_mut().zip(material.diffuse).zip(emissivities) {
            *c = add_sat(*c, term([emissivity, diffuse, diffuse_falloff]));
            if specular {
                *c = add_sat(*c, term([emissivity, material.specular, glint]));
            }
        }
    }
}

/// What every light of a hit shares.
struct Lit<'a, 'b, S> {
    scene: &'a SceneView<'b, S>,
    ray: &'a Incoming<'b, S>,
    object: &'a Object<S>,
    material: &'a Material<S>,
    hit: Hit<S>,
    normal: Vec3<S>,
    specular: bool,
    stages: LightStages,
    /// Set by [`passage`]: a course shadow ray went on past a translucent occluder (see
    /// [`moved_hit`]).
    continues: Cell<bool>,
}

/// Where the course's record of a sphere's hit is after a shadow ray of it went on past
/// a translucent occluder (`COURSE-RULES.md` §11): the course intersects the shadow ray
/// again from the occluder with every object but the occluder, the lit sphere among
/// them, and a sphere stores the point of its near root before it rejects a negative
/// one. Seen from beyond the sphere along the line to the light, that root is the
/// line's crossing behind the hit. The lights after this one, the transmitted ray and
/// the mirror ray then start from that point, with its normal; the light itself was
/// summed at the hit. Fitted on texplane3, where three translucent spheres light each
/// other (1.259 % of pixels beyond 2 levels without it, 0.163 % with it; `docs/numerics.md`).
/// Other shapes keep their hit: a plane-type test forms its point only for `t ≥ 0`
/// (the lecture's `plane_hits()`). `None`: the hit stays.
fn moved_hit<S: Scalar>(
    object: &Object<S>,
    point: Vec3<S>,
    light: Vec3<S>,
) -> Option<(Vec3<S>, Vec3<S>)> {
    let crate::Shape::Sphere(sphere) = &object.shape else {
        return None;
    };
    let behind = sphere.near_crossing(point, light.diff(point)?.unit()?)?;
    Some((behind, sphere.normal_at(behind)?))
}

/// 255 in the format (or its largest value).
fn channel_max<S: Scalar>() -> S {
    S::from_i32(255).unwrap_or(S::MAX)
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

/// One light's `(255·cos/dist, 255·(N·H)^shininess/dist)` with `L = light − hit`
/// unnormalised and `ll = L·L`: `cos/dist = (N·L)/|L|²` (one division, no square root);
/// the cone test compares `(−L·axis)²` with `cos²θ·|L|²`; the shadow test asks each
/// object whether it meets the segment from the hit to the light: by the crate's rules
/// [`crate::Shape::meets_segment`] (within `tol` of the hit's surface nothing counts), by
/// the course's [`crate::Shape::meets_segment_course`] (skipping the hit's object, the
/// strict cone, the glint without the distance). Only a specular glint normalises `L`
/// (its half vector needs the unit direction). `None` when the light does not light the
/// point. Not inlined (nor is [`ray_terms`]): the two would share the light loop's
/// frame, which lies under the deepest of a mirror recursion's leaves (an I32F32
/// mirror scene on a 16 KB Cortex-M0).
#[inline(never)]
#[allow(clippy::too_many_arguments)]
fn segment_terms<S: Scalar>(
    at: &Lit<'_, '_, S>,
    (index, light): (usize, &Light<S>),
    to_light: Vec3<S>,
    ll: S,
    tol: Option<S>,
    course: Option<CourseLight<S>>,
    counters: &mut Counters,
) -> Option<(S, S, Option<[S; 3]>)> {
    let nl = at.normal.dot(to_light).filter(|c| *c > S::ZERO)?;
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
        // The course's cone is strict (`>`), the crate's takes its edge (`>=`).
        let inside = match (cone.cos_theta >= S::ZERO, course.is_some()) {
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
        let from = at.hit.point;
        match course {
            None => {
                let sides = at.ray.sides.map(|s| (s, index));
                if occludes_segment(at.scene, sides, from, to_light, ll, tol?, light.location) {
                    return None;
                }
            }
            Some(c) => {
                let (f, e) = segment_passage(at, c, light, from, to_light, ll)?;
                filter = combine(filter, f);
                entered = e;
            }
        }
    }
    // 255·(N·L)/|L|², scaled to channel units before the division where that fits (the
    // quotient then keeps the format's relative precision).
    let k = channel_max::<S>();
    let mut diffuse_falloff = match nl.checked_mul(k) {
        Some(knl) => knl.checked_div(ll),
        None => nl.checked_div(ll).and_then(|q| q.checked_mul(k)),
    }
    .unwrap_or(S::MAX);
    // Through a translucent sphere (see `entry` above): cos/dist' with
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
                match course {
                    None => n.divide(g),
                    Some(_) => Some(g),
                }
            })
            .unwrap_or(S::ZERO)
    } else {
        S::ZERO
    };
    Some((diffuse_falloff, glint, filter))
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

/// The course's shadow segment from `from` to the light at `from + l` ([`passage`] with
/// the segment tests), and the share of the segment at which it enters the translucent
/// sphere nearest the light, where that sets the falloff. Not inlined: its locals stay
/// out of the crate's rules' light loop (a mirror recursion's leaf frames on a 16 KB
/// chip).
#[inline(never)]
#[allow(clippy::type_complexity)]
fn segment_passage<S: Scalar>(
    at: &Lit<'_, '_, S>,
    c: CourseLight<S>,
    light: &Light<S>,
    from: Vec3<S>,
    to_light: Vec3<S>,
    ll: S,
) -> Option<(Option<[S; 3]>, Option<S>)> {
    let blocks = |o: &Object<S>| {
        o.shape
            .meets_segment_course(from, to_light, ll, at.scene.epsilon, c.z_limit)
            && !spared(at.scene, from, to_light, light.location, &o.shape)
    };
    // The open case of §11, settled by the pictures (`docs/numerics.md`,
    // "Translucency"): a light in front of the screen seen through a translucent sphere
    // falls off from where the segment enters it.
    let entry = |o: &Object<S>| match &o.shape {
        crate::Shape::Sphere(s) if light.location.z > S::ZERO => {
            s.segment_entry(from, to_light, ll)
        }
        _ => None,
    };
    let distance = |o: &Object<S>| {
        o.shape
            .distance_course(from, to_light, at.scene.epsilon, c.z_limit)
    };
    passage(at, c, blocks, entry, distance)
}

/// Two filters one after the other (`None`: passes everything).
fn combine<S: Scalar>(a: Option<[S; 3]>, b: Option<[S; 3]>) -> Option<[S; 3]> {
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

/// The course's shadow along a segment or ray: every object but the hit's own that
/// `blocks` it either stops the light (opaque) or, with the `transparency` stage,
/// filters it by its material's filter (`COURSE-RULES.md` §11: a second translucent
/// occluder filters again). `None`: in shadow; `Some(None)`: unfiltered.
///
/// For a sphere's hit with the `transparency` stage it also records in `at.continues`
/// whether the course's shadow ray goes on past a translucent occluder, that is whether
/// the occluder nearest the hit is translucent (see [`moved_hit`]); `distance` orders
/// the occluders where both kinds meet the segment.
#[allow(clippy::option_option)]
fn passage<S: Scalar>(
    at: &Lit<'_, '_, S>,
    course: CourseLight<S>,
    blocks: impl Fn(&Object<S>) -> bool,
    entry: impl Fn(&Object<S>) -> Option<S>,
    distance: impl Fn(&Object<S>) -> Option<S>,
) -> Option<(Option<[S; 3]>, Option<S>)> {
    let scene = at.scene;
    // Only a sphere's hit can move, and only past a translucent occluder.
    let track = at.stages.transparency && matches!(at.object.shape, crate::Shape::Sphere(_));
    let mut filter = None;
    let mut last: Option<S> = None;
    let (mut translucent, mut opaque) = (false, false);
    for (i, o) in scene.objects.iter().enumerate() {
        if i == course.index || !blocks(o) {
            continue;
        }
        let Some(f) = occluder_filter(at, o) else {
            if !track {
                return None;
            }
            opaque = true;
            continue;
        };
        translucent = true;
        filter = combine(filter, Some(f));
        if let Some(e) = entry(o) {
            last = Some(last.map_or(e, |l: S| l.max(e)));
        }
    }
    if translucent && track {
        // Which kind lies nearest the hit (only where both meet the segment).
        let continues = !opaque || translucent_nearest(at, course.index, &blocks, &distance);
        at.continues.set(continues);
    }
    (!opaque).then_some((filter, last))
}

/// The filter of an occluder of a course shadow segment: its material's, with the
/// `transparency` stage (`None`: it stops the light).
fn occluder_filter<S: Scalar>(at: &Lit<'_, '_, S>, o: &Object<S>) -> Option<[S; 3]> {
    if !at.stages.transparency {
        return None;
    }
    at.scene
        .materials
        .get(usize::from(o.material))
        .and_then(super::course::filter_of)
}

/// Whether the nearest of the objects but `skip` that `blocks` a course shadow segment
/// is translucent, by `distance` ([`passage`], where both kinds meet it). Out of line,
/// with the tests as trait objects: the common case's loop keeps them inlined.
#[inline(never)]
fn translucent_nearest<S: Scalar>(
    at: &Lit<'_, '_, S>,
    skip: usize,
    blocks: &dyn Fn(&Object<S>) -> bool,
    distance: &dyn Fn(&Object<S>) -> Option<S>,
) -> bool {
    let scene = at.scene;
    let nearest = |want: bool| {
        scene
            .objects
            .iter()
            .enumerate()
            .filter(|&(i, o)| i != skip && occluder_filter(at, o).is_some() == want && blocks(o))
            .filter_map(|(_, o)| distance(o))
            .reduce(S::min)
    };
    match (nearest(true), nearest(false)) {
        (Some(t), Some(o)) => t < o,
        (t, _) => t.is_some(),
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

/// Whether any object meets the segment from `from` to the light at `from + l` (the
/// crate's shadow test, [`crate::Shape::meets_segment`]; a light on a surface: as in
/// [`occludes`]). `sides`: the planes' sides the fast kernel knows, and the light's index.
#[inline(never)]
fn occludes_segment<S: Scalar>(
    scene: &SceneView<'_, S>,
    sides: Option<(PlaneSides<'_, S>, usize)>,
    from: Vec3<S>,
    l: Vec3<S>,
    ll: S,
    tol: S,
    light: Vec3<S>,
) -> bool {
    let eps = scene.epsilon;
    let spared = |shape: &crate::Shape<S>| spared(scene, from, l, light, shape);
    // The kernel's sides of every object at the hit and at this light, if it has them.
    let known = sides.and_then(|(s, j)| {
        let n = s.at_hit.len();
        // j < lights and n ≤ MAX_OBJECTS: the product is small (a checked one would call
        // the 64-bit multiply helper on a Cortex-M0).
        let at_light = s.at_lights.get(j * n..)?.get(..n)?;
        (n == scene.objects.len()).then_some((s.at_hit, at_light))
    });
    match known {
        Some((at_hit, at_light)) => {
            scene
                .objects
                .iter()
                .zip(at_hit.iter().zip(at_light))
                .any(|(o, (&a0, &a1))| {
                    o.shape
                        .meets_segment_with(Some((a0, a1)), from, l, ll, tol, eps)
                        && !spared(&o.shape)
                })
        }
        None => scene
            .objects
            .iter()
            .any(|o| o.shape.meets_segment_with(None, from, l, ll, tol, eps) && !spared(&o.shape)),
    }
}

/// A light on a surface (only where the plan found one): whether `shape`, which meets
/// the shadow segment from `from` along `l`, spares it (as in [`occludes`]).
fn spared<S: Scalar>(
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

/// One light's `(255·cos/dist, 255·(N·H)^shininess/dist)` along the normalised direction
/// to the light, with a shadow ray along it, for a light whose `|L|²` does not fit the
/// format: under the course's rules (`course`: from the hit, skipping its object, the
/// strict cone, the glint without the distance) and the crate's (spawned off the
/// surface). `None` when the light does not light the point.
#[inline(never)]
fn ray_terms<S: Scalar>(
    at: &Lit<'_, '_, S>,
    light: &Light<S>,
    to_light: Vec3<S>,
    course: Option<CourseLight<S>>,
    counters: &mut Counters,
) -> Option<(S, S, Option<[S; 3]>)> {
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
            .is_some_and(|c| match course {
                None => c >= cone.cos_theta,
                Some(_) => c > cone.cos_theta,
            });
        if !inside {
            return None;
        }
    }
    if at.stages.shadows {
        count(&mut counters.shadow_rays);
        // The distance itself may not fit (a far light): nothing lies beyond it.
        let dist = to_light.length().unwrap_or(S::MAX);
        match course {
            None => {
                let shadowed = at
                    .object
                    .shape
                    .spawn_from(at.ray.base, &at.hit, l)
                    .is_some_and(|r| occludes(at.scene, &r, dist, light.location, None, None));
                if shadowed {
                    return None;
                }
            }
            Some(c) => {
                let from = Ray {
                    base: at.hit.point,
                    dir: l,
                    kind: RayKind::Secondary,
                };
                let eps = at.scene.epsilon;
                let blocks = |o: &Object<S>| {
                    o.shape
                        .intersect_course(&from, eps, c.z_limit)
                        .is_ok_and(|h| h.t < dist)
                        && !spared(at.scene, from.base, l, light.location, &o.shape)
                };
                let distance = |o: &Object<S>| {
                    o.shape
                        .intersect_course(&from, eps, c.z_limit)
                        .ok()
                        .map(|h| h.t)
                };
                filter = combine(filter, passage(at, c, blocks, |_| None, distance)?.0);
            }
        }
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
        match course {
            None => shine.and_then(|g| to_light.divide(g)),
            Some(_) => shine,
        }
        .unwrap_or(S::ZERO)
    } else {
        S::ZERO
    };
    Some((diffuse_falloff, glint, filter))
}
