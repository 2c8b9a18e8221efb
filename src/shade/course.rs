//! Tracing under the course rules (`course/COURSE-RULES.md`): what the course tracer
//! computes, so that a real course file draws the instructor's picture.
//!
//! A pixel's colour is `Σ_k W_k · own_k / D_k` over the chain of mirror bounces: `own`
//! is a hit's ambient plus its lights' share, `D_k` the path length from the eye to the
//! k-th hit, `W_k` the product of the `specular` weights of the mirrors before it
//! (`own + K · reflected`, no `(1 − K)`). The chain stops at a miss (black), a material
//! without `specular`, a path longer than [`MAX_PATH`] units, or after
//! [`MAX_COURSE_BOUNCES`] mirrors (the course has no such limit; a bounce that far is
//! below one level in the course's pictures). It is a loop, not a recursion: a chain of
//! mirrors costs no stack.
//!
//! Per light (§6, §7; the one light loop, `light.rs`, with this rule set's `Tracer`):
//! `diffuse ⊙ emissivity · N·L / dist` with the normal as given (a surface seen from
//! behind gets no light from the viewer's side), nothing when `N·L ≤ 0`, a spotlight's
//! cone with a strict `>`, the shadow ray from the hit itself skipping the object it
//! leaves, and the glint `specular · (N·H)^shininess · emissivity` with
//! `H = unit(−d + L)`, not divided by the light distance, only with a `shininess`. Plane-type hits with `z > 0.01` are rejected for every ray, and spheres
//! take only their near root ([`Course::intersect`](crate::shade::RuleSet::intersect)).

use super::color::clamp_channel;
use super::light::{Lit, Passage, combine, light_with, spared};
use super::rules::{Course, RuleSet, Tracer};
use super::stages::{LightStages, Stages};
use super::{Incoming, Traced, nearest, surface};
use crate::geometry::{SPHERES, crossing_point, unit_ray};
use crate::scene::PixelRay;
use crate::stats::{Counters, count};
use heapless::Vec;

use crate::{Color, Hit, Light, Material, Miss, Object, Ray, RayKind, Rules, Scalar, SceneView};
use crate::{PlaneFrame, Shape, Vec3};
use embedded_graphics_core::pixelcolor::Rgb888;

/// A ray whose path from the eye is already longer than this many world units is black
/// (the course's `MAX_DIST`). The student tracer C defines it as 32; the instructor's
/// pictures say 20: spec4 (a room of facing mirrors) is 0.047 % of pixels beyond 2 levels
/// with 20 and 3.3, 3.3, 6.4 and 6.8 % with 19, 21, 24 and 32 (`docs/numerics.md`,
/// "Mirror chains").
pub const MAX_PATH: i32 = 20;

/// The most mirror bounces a course pixel follows.
pub const MAX_COURSE_BOUNCES: u8 = 16;

/// The course's screen rule: a plane-type hit with `z` above this is rejected, for every
/// ray (0.01, `COURSE-RULES.md` §5).
fn z_limit<S: Scalar>() -> S {
    S::ONE.mul_ratio(1, 100).unwrap_or(S::ZERO)
}

/// Whether the format's unit directions are too coarse for texel lookups: a pixel's unit
/// direction is off by up to `DELTA/2` per component, which moves a plane's hit by up to
/// `t/|N·d|` times that, ≈ 500 `DELTA` on a course floor seen at a grazing angle (t ≈ 20,
/// |N·d| ≈ 0.04), against texels ≈ 0.015 world units wide: below 1 % of a texel only
/// when `DELTA < 2⁻²²`. Coarser formats (I16F16, I20F12) find a pixel's textured planes
/// from its unnormalised direction, [`crate::Plane::crossing_along`]; the finer ones
/// (I32F32, the floats) take the unit ray's point, which is what the course itself
/// computes, and so break exact texel-edge ties as the course does (the measurements:
/// `docs/numerics.md`, "Translucency and textures").
fn coarse_directions<S: Scalar>() -> bool {
    S::DELTA.checked_mul_int(1 << 22).is_none_or(|d| d > S::ONE)
}

/// The most rays a course pixel keeps waiting: a hit both mirror and translucent
/// continues along one and keeps the other here (no material of the course's files is
/// both); a branch beyond this many is dropped (it would add black).
pub const MAX_COURSE_BRANCHES: usize = 4;

/// A ray of a course pixel still to be followed: where it starts, what it skips, the
/// path length so far and the weight per channel of what it sees.
#[derive(Debug, Clone, Copy)]
struct Branch<S> {
    ray: Ray<S>,
    skip: Option<usize>,
    travelled: S,
    weight: [S; 3],
}

/// A translucent material's filter, `T · diffuse / max(diffuse)` per channel
/// (`COURSE-RULES.md` §11: what it passes of the light and of what lies behind it);
/// `None` for an opaque material. A material without diffuse colour passes nothing.
pub(crate) fn filter_of<S: Scalar>(m: &Material<S>) -> Option<[S; 3]> {
    if m.transparency <= S::ZERO {
        return None;
    }
    let top = m.diffuse[0].max(m.diffuse[1]).max(m.diffuse[2]);
    let mut f = [S::ZERO; 3];
    if top > S::ZERO {
        for (fk, d) in f.iter_mut().zip(m.diffuse) {
            *fk = d
                .max(S::ZERO)
                .checked_div(top)
                .and_then(|q| q.checked_mul(m.transparency))
                .unwrap_or(S::ZERO);
        }
    }
    Some(f)
}

/// Traces a ray under the course rules with the stages of `T` (see the module
/// documentation): the first hit and the colour in channel units.
///
/// A hit on a material with `specular K` and `transparency T` (filter `f`, see
/// [`filter_of`]) adds `W (1 − T) own / D` and continues along the mirror ray with weight
/// `W (1 − T) K` and along the same direction, skipping the object, with weight `W ⊙ f`
/// (`COURSE-RULES.md` §8, §11: the mirror first, then translucency). Both are followed
/// by the same loop (one of them kept in a [`MAX_COURSE_BRANCHES`] list): no recursion.
#[inline(never)]
fn trace<S: Scalar, T: Stages>(
    scene: &SceneView<'_, S>,
    ray: &Ray<S>,
    toward: Option<Vec3<S>>,
    counters: &mut Counters,
) -> Traced<S> {
    let max_path = S::from_i32(MAX_PATH).unwrap_or(S::MAX);
    let mut next = Some(Branch {
        ray: Ray {
            kind: RayKind::Secondary,
            ..*ray
        },
        skip: None,
        travelled: S::ZERO,
        weight: [S::ONE; 3],
    });
    let mut waiting: Vec<Branch<S>, MAX_COURSE_BRANCHES> = Vec::new();
    let mut color = [S::ZERO; 3];
    let mut first = None;
    let mut bounces = 0u8;
    let mut primary = true;
    while let Some(branch) = next.take().or_else(|| waiting.pop()) {
        let Branch {
            ray,
            skip,
            travelled,
            weight,
        } = branch;
        let was_primary = core::mem::replace(&mut primary, false);
        if travelled > max_path || bounces > MAX_COURSE_BOUNCES {
            continue;
        }
        bounces += 1;
        let Some((index, hit)) = nearest::<S, Course>(scene, &ray, skip) else {
            // The course has no background: a miss is black. A primary miss shows the
            // scene's `background` (black unless the file sets one, which course files
            // never do).
            if was_primary {
                color = scene.background;
            }
            continue;
        };
        if was_primary {
            first = Some((index, hit));
        }
        // In a coarse format a pixel's textured plane takes its point (and so its texel)
        // from the pixel's unnormalised direction (see `coarse_directions`).
        let refine = was_primary && coarse_directions::<S>();
        let hit = match (refine, toward, scene.objects.get(index).map(|o| &o.shape)) {
            (true, Some(d), Some(Shape::Textured(slide))) => Hit {
                point: slide
                    .frame
                    .plane()
                    .crossing_along(ray.base, d)
                    .unwrap_or(hit.point),
                ..hit
            },
            (..) => hit,
        };
        let Some((object, material)) = surface(scene, index, hit.point, counters) else {
            continue;
        };
        let Some(travelled) = travelled.checked_add(hit.t) else {
            continue;
        };
        let mut normal = object.shape.normal_at(hit.point);
        let mut own = material.ambient;
        // Where the rays leaving the hit start: the hit, or where a shadow ray of its
        // lights moved the course's record of it (`light::moved_hit`).
        let mut from = hit.point;
        if T::LIGHTING
            && let Some(n) = normal
        {
            let at = Lit {
                scene,
                ray: &Incoming::from(&ray),
                object,
                index,
                material: &material,
                hit,
                normal: n,
                specular: false,
                stages: LightStages::of::<T, S>(scene),
            };
            if let Some((point, moved)) = light_with::<S, Course>(at, &mut own, counters) {
                (from, normal) = (point, Some(moved));
            }
        }
        // A translucent surface keeps (1 − T) of its own colour and of its mirror image.
        let filter = if T::TRANSPARENCY {
            filter_of(&material)
        } else {
            None
        };
        let kept = match filter {
            Some(_) => S::ONE.checked_sub(material.transparency).unwrap_or(S::ZERO),
            None => S::ONE,
        };
        // W · (1 − T) · own / D per channel (D > 0: every accepted t is).
        for ((c, o), w) in color.iter_mut().zip(own).zip(weight) {
            let share = o
                .checked_mul(w)
                .and_then(|wo| wo.checked_mul(kept))
                .and_then(|wo| wo.checked_div(travelled))
                .unwrap_or(if o < S::ZERO { S::ZERO } else { S::MAX });
            *c = c.checked_add(share).unwrap_or(S::MAX);
        }
        if let Some(f) = filter {
            count(&mut counters.transmitted_rays);
            let mut w = weight;
            for (wk, fk) in w.iter_mut().zip(f) {
                *wk = wk.checked_mul(fk).unwrap_or(S::ZERO);
            }
            if w != [S::ZERO; 3] {
                next = Some(Branch {
                    ray: Ray {
                        base: from,
                        dir: ray.dir,
                        kind: RayKind::Secondary,
                    },
                    skip: Some(index),
                    travelled,
                    weight: w,
                });
            }
        }
        let k = material.specular;
        if !T::REFLECTION || k == S::ZERO {
            continue;
        }
        let Some(n) = normal else {
            continue;
        };
        count(&mut counters.reflection_rays);
        // r = d − 2 (d·N) N
        let Some(dir) = n
            .dot(ray.dir)
            .and_then(|nd| nd.checked_add(nd))
            .and_then(|two_nd| n.scale(two_nd))
            .and_then(|n2| ray.dir.diff(n2))
            .and_then(Vec3::unit)
        else {
            continue;
        };
        let Some(k) = k.checked_mul(kept) else {
            continue;
        };
        let mut w = weight;
        for wk in &mut w {
            *wk = wk.checked_mul(k).unwrap_or(S::ZERO);
        }
        if w == [S::ZERO; 3] {
            continue;
        }
        let mirror = Branch {
            ray: Ray {
                base: from,
                dir,
                kind: RayKind::Secondary,
            },
            skip: Some(index),
            travelled,
            weight: w,
        };
        // The mirror ray first; a transmitted ray of the same hit waits.
        if let Some(t) = next.replace(mirror) {
            let _ = waiting.push(t);
        }
    }
    Traced { hit: first, color }
}

/// The course's shadow segment from `from` to the light at `from + l` ([`passage`] with
/// the segment tests), and the share of the segment at which it enters the translucent
/// sphere nearest the light, where that sets the falloff. Not inlined: its locals stay
/// out of the light loop's frame.
#[inline(never)]
#[allow(clippy::type_complexity)]
fn segment_passage<S: Scalar>(
    at: &Lit<'_, '_, S>,
    light: &Light<S>,
    to_light: Vec3<S>,
    ll: S,
) -> Passage<S> {
    let from = at.hit.point;
    let eps = at.scene.epsilon;
    let blocks = |o: &Object<S>| {
        Course::meets_segment(&o.shape, from, to_light, ll, S::ZERO, eps)
            && !spared(at.scene, from, to_light, light.location, &o.shape)
    };
    // The open case of §11, settled by the pictures (`docs/numerics.md`,
    // "Translucency"): a light in front of the screen seen through a translucent sphere
    // falls off from where the segment enters it.
    let entry = |o: &Object<S>| {
        if let Shape::Sphere(s) = &o.shape
            && light.location.z > S::ZERO
        {
            s.segment_entry(from, to_light, ll)
        } else {
            None
        }
    };
    let distance = |o: &Object<S>| distance(&o.shape, from, to_light, eps);
    passage(at, blocks, entry, distance)
}

/// The course's shadow along a segment or ray: every object but the hit's own that
/// `blocks` it either stops the light (opaque) or, with the `transparency` stage,
/// filters it by its material's filter (`COURSE-RULES.md` §11: a second translucent
/// occluder filters again).
///
/// For a sphere's hit with the `transparency` stage it also records in
/// [`Passage::continues`] whether the course's shadow ray goes on past a translucent
/// occluder, that is whether the occluder nearest the hit is translucent (see
/// [`moved_hit`]); `distance` orders the occluders where both kinds meet the segment.
fn passage<S: Scalar>(
    at: &Lit<'_, '_, S>,
    blocks: impl Fn(&Object<S>) -> bool,
    entry: impl Fn(&Object<S>) -> Option<S>,
    distance: impl Fn(&Object<S>) -> Option<S>,
) -> Passage<S> {
    let scene = at.scene;
    // Only a sphere's hit can move, and only past a translucent occluder.
    let track = at.stages.transparency && matches!(at.object.shape, Shape::Sphere(_));
    let mut filter = None;
    let mut last: Option<S> = None;
    let (mut translucent, mut opaque) = (false, false);
    for (i, o) in scene.objects.iter().enumerate() {
        if i == at.index || !blocks(o) {
            continue;
        }
        let Some(f) = occluder_filter(at, o) else {
            if !track {
                return Passage::SHADOWED;
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
    // Which kind lies nearest the hit (only where both meet the segment).
    let continues =
        translucent && track && (!opaque || translucent_nearest(at, at.index, &blocks, &distance));
    Passage {
        lit: (!opaque).then_some((filter, last)),
        continues,
    }
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
        .and_then(filter_of)
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

/// The course's screen rule's limit for a shape's plane-type hits: `z > 0.01` is
/// rejected, `z > 0` for triangles (§5, §14).
fn screen_limit<S: Scalar>(shape: &Shape<S>) -> S {
    match shape {
        Shape::Triangle(_) => S::ZERO,
        Shape::Plane(_)
        | Shape::Sphere(_)
        | Shape::Tiled { .. }
        | Shape::Finite(_)
        | Shape::Textured(_)
        | Shape::Revsurf(_) => z_limit::<S>(),
    }
}

/// The near root's hit of a ray on a sphere (§5): only the near root counts, and a
/// negative one (the base inside) is [`Miss::Behind`]. No screen rule.
fn near_root<S: Scalar>(sphere: &crate::Sphere<S>, ray: &Ray<S>) -> Result<Hit<S>, Miss> {
    let (near, _) = sphere.roots(ray)?;
    if near < S::ZERO {
        return Err(Miss::Behind);
    }
    ray.hit_at(near)
}

/// How far along the course's shadow ray from `from` towards `from + l` it meets
/// `shape` ([`Course::intersect`] on the unit ray); `None` for a miss. What orders a
/// segment's occluders where that matters (a translucent one before an opaque one).
fn distance<S: Scalar>(shape: &Shape<S>, from: Vec3<S>, l: Vec3<S>, epsilon: S) -> Option<S> {
    let (ray, _) = unit_ray(from, l)?;
    Course::intersect(shape, &ray, epsilon).ok().map(|h| h.t)
}

/// Whether the course's ray test meets `shape` before the end of the segment from
/// `from` along `l` (the segment tests' fallback where a quantity does not fit).
fn ray_meets<S: Scalar>(shape: &Shape<S>, from: Vec3<S>, l: Vec3<S>, epsilon: S) -> bool {
    unit_ray(from, l).is_some_and(|(r, dist)| Course::blocks(shape, &r, epsilon, dist))
}

impl RuleSet for Course {
    const RULES: Rules = Rules::Course;

    /// For every ray alike (§5): planes miss at `t <= 0` and reject a plane-type hit with
    /// `z > 0.01` (triangles `z > 0`, §14); spheres take only the near root, with no
    /// screen rule. The course compares `N·d` with zero exactly; `epsilon` (the plane
    /// tests' precision epsilon) keeps a grazing ray's `t` within the format.
    #[inline]
    fn intersect<S: Scalar>(shape: &Shape<S>, ray: &Ray<S>, epsilon: S) -> Result<Hit<S>, Miss> {
        let ray = Ray {
            kind: RayKind::Secondary,
            ..*ray
        };
        let hit = match shape {
            Shape::Sphere(s) if SPHERES => return near_root(s, &ray),
            Shape::Sphere(_) => return Err(Miss::NotBuiltIn),
            // A surface of revolution has no screen rule either.
            Shape::Revsurf(r) => return r.intersect(&ray),
            Shape::Plane(_)
            | Shape::Tiled { .. }
            | Shape::Finite(_)
            | Shape::Textured(_)
            | Shape::Triangle(_) => shape.intersect(&ray, epsilon)?,
        };
        if hit.t <= S::ZERO {
            Err(Miss::Behind)
        } else if hit.point.z > screen_limit(shape) {
            Err(Miss::InFrontOfScreen)
        } else {
            Ok(hit)
        }
    }

    /// A plane-type shape blocks when the segment crosses its plane strictly between the
    /// ends and the crossing point keeps the screen rule and the bounds; a sphere when
    /// its near root lies in `[0, dist)` ([`crate::Sphere::meets_segment_near`]); a
    /// surface of revolution by the unit ray's test.
    fn meets_segment<S: Scalar>(
        shape: &Shape<S>,
        from: Vec3<S>,
        l: Vec3<S>,
        ll: S,
        _tol: S,
        epsilon: S,
    ) -> bool {
        match shape {
            Shape::Revsurf(_) => ray_meets(shape, from, l, epsilon),
            Shape::Sphere(s) => {
                SPHERES
                    && s.meets_segment_near(from, l, ll)
                        .unwrap_or_else(|| ray_meets(shape, from, l, epsilon))
            }
            // Crossing the plane strictly between the ends (`Plane::crossing` with no
            // tolerance: `0 < t < dist`), at a point that keeps the screen rule and the
            // bounds.
            Shape::Plane(_)
            | Shape::Tiled { .. }
            | Shape::Finite(_)
            | Shape::Textured(_)
            | Shape::Triangle(_) => shape
                .plane()
                .and_then(|p| p.crossing(from, l, ll, S::ZERO, epsilon))
                .and_then(|c| crossing_point(from, l, c))
                .is_some_and(|x| x.z <= screen_limit(shape) && shape.bounds_contain(x)),
        }
    }

    fn blocks<S: Scalar>(shape: &Shape<S>, ray: &Ray<S>, epsilon: S, dist: S) -> bool {
        Self::intersect(shape, ray, epsilon).is_ok_and(|hit| hit.t < dist)
    }
}

impl Tracer for Course {
    const SKIPS_OWN: bool = true;
    const STRICT_CONE: bool = true;
    const GLINT_FALLOFF: bool = false;

    fn trace_pixel<S: Scalar, T: Stages>(
        scene: &SceneView<'_, S>,
        pixel: &PixelRay<S>,
        counters: &mut Counters,
    ) -> Traced<S> {
        trace::<S, T>(scene, &pixel.ray, Some(pixel.toward), counters)
    }

    fn trace<S: Scalar, T: Stages>(
        scene: &SceneView<'_, S>,
        ray: &Ray<S>,
        counters: &mut Counters,
    ) -> Traced<S> {
        trace::<S, T>(scene, ray, None, counters)
    }

    /// Truncation, `floor(clamp(c, 0, 255))` (§3).
    fn to_pixel<S: Scalar>(c: Color<S>) -> Rgb888 {
        let channel = |v: S| -> u8 {
            clamp_channel(v)
                .floor_to_i32()
                .and_then(|i| u8::try_from(i).ok())
                .unwrap_or(u8::MAX)
        };
        Rgb888::new(channel(c[0]), channel(c[1]), channel(c[2]))
    }

    /// The checkerboard anchored at the world origin, even tiles alternate (§10).
    fn shows_alt<S: Scalar>(frame: &PlaneFrame<S>, point: Vec3<S>) -> bool {
        frame.odd_tile_from_origin(point) == Some(false)
    }

    /// `specular` is the mirror weight; the glint needs a `shininess` too (§7, §8).
    fn glints<S: Scalar>(material: &Material<S>) -> bool {
        material.specular != S::ZERO && material.shininess > S::ZERO
    }

    /// The course's shadow rays start on the hit (and skip its object): no tolerance.
    fn segment_tolerance<S: Scalar>(
        _stages: LightStages,
        _ray: &Incoming<'_, S>,
        _hit: &Hit<S>,
    ) -> Option<S> {
        Some(S::ZERO)
    }

    fn segment_shadow<S: Scalar>(
        at: &Lit<'_, '_, S>,
        (_, light): (usize, &Light<S>),
        to_light: Vec3<S>,
        ll: S,
        _tol: S,
    ) -> Passage<S> {
        segment_passage(at, light, to_light, ll)
    }

    fn ray_shadow<S: Scalar>(
        at: &Lit<'_, '_, S>,
        light: &Light<S>,
        l: Vec3<S>,
        dist: S,
    ) -> Passage<S> {
        let from = Ray {
            base: at.hit.point,
            dir: l,
            kind: RayKind::Secondary,
        };
        let eps = at.scene.epsilon;
        let blocks = |o: &Object<S>| {
            Self::blocks(&o.shape, &from, eps, dist)
                && !spared(at.scene, from.base, l, light.location, &o.shape)
        };
        let distance = |o: &Object<S>| Self::intersect(&o.shape, &from, eps).ok().map(|h| h.t);
        passage(at, blocks, |_| None, distance)
    }

    fn moved_hit<S: Scalar>(
        object: &Object<S>,
        point: Vec3<S>,
        light: Vec3<S>,
    ) -> Option<(Vec3<S>, Vec3<S>)> {
        moved_hit(object, point, light)
    }
}

/// Where the course's record of a sphere's hit is after a shadow ray of it went on past
/// a translucent occluder (`COURSE-RULES.md` §11): the course intersects the shadow ray
/// again from the occluder with every object but the occluder, the lit sphere among
/// them, and a sphere stores the point of its near root before it rejects a negative
/// one. Seen from beyond the sphere along the line to the light, that root is the
/// line's crossing behind the hit. The lights after this one, the transmitted ray and
/// the mirror ray then start from that point, with its normal; the light itself was
/// summed at the hit. Fitted on texplane3 (`docs/numerics.md`, "Translucency"). Other
/// shapes keep their hit: a plane-type test forms its point only for `t ≥ 0` (the
/// lecture's `plane_hits()`). `None`: the hit stays.
fn moved_hit<S: Scalar>(
    object: &Object<S>,
    point: Vec3<S>,
    light: Vec3<S>,
) -> Option<(Vec3<S>, Vec3<S>)> {
    let Shape::Sphere(sphere) = &object.shape else {
        return None;
    };
    let behind = sphere.near_crossing(point, light.diff(point)?.unit()?)?;
    Some((behind, sphere.normal_at(behind)?))
}
