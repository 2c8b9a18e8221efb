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
//! Per light (§6, §7; the one light loop, `light.rs`, with [`super::light::CourseLight`]):
//! `diffuse ⊙ emissivity · N·L / dist` with the normal as given (a surface seen from
//! behind gets no light from the viewer's side), nothing when `N·L ≤ 0`, a spotlight's
//! cone with a strict `>`, the shadow ray from the hit itself skipping the object it
//! leaves, and the glint `specular · (N·H)^shininess · emissivity` with
//! `H = unit(−d + L)`, not divided by the light distance, only with a `shininess`. Plane-type hits with `z > 0.01` are rejected for every ray, and spheres
//! take only their near root ([`crate::Shape::intersect_course`]).

use super::light::{CourseLight, light_with};
use super::stages::{LightStages, Stages};
use super::{Incoming, Traced, surface};
use crate::stats::{Counters, count};
use heapless::Vec;

use crate::{Hit, Material, Ray, RayKind, Scalar, SceneView, Vec3};

/// Paths from the eye longer than this many world units are black (the course's
/// `MAX_DIST`).
pub const MAX_PATH: i32 = 32;

/// The most mirror bounces a course pixel follows.
pub const MAX_COURSE_BOUNCES: u8 = 16;

/// The course's screen rule: a plane-type hit with `z` above this is rejected, for every
/// ray (0.01, `COURSE-RULES.md` §5).
fn z_limit<S: Scalar>() -> S {
    S::ONE.mul_ratio(1, 100).unwrap_or(S::ZERO)
}

/// The nearest hit of a ray under the course rules among the objects other than `skip`;
/// on equal `t` the first object in file order.
pub(crate) fn nearest_course<S: Scalar>(
    scene: &SceneView<'_, S>,
    ray: &Ray<S>,
    skip: Option<usize>,
) -> Option<(usize, Hit<S>)> {
    let z = z_limit::<S>();
    let mut best: Option<(usize, Hit<S>)> = None;
    for (i, object) in scene.objects.iter().enumerate() {
        if Some(i) == skip {
            continue;
        }
        if let Ok(hit) = object.shape.intersect_course(ray, scene.epsilon, z)
            && best.is_none_or(|(_, b)| hit.t < b.t)
        {
            best = Some((i, hit));
        }
    }
    best
}

/// Whether the format's unit directions are too coarse for texel lookups: a pixel's unit
/// direction is off by up to `DELTA/2` per component, which moves a plane's hit by up to
/// `t/|N·d|` times that, ≈ 500 `DELTA` on a course floor seen at a grazing angle (t ≈ 20,
/// |N·d| ≈ 0.04), against texels ≈ 0.015 world units wide: below 1 % of a texel only
/// when `DELTA < 2⁻²²`. Coarser formats (I16F16, I20F12) find a pixel's textured planes
/// from its unnormalised direction, [`crate::Plane::crossing_along`] (texplane3's floor
/// in I16F16: 2.7 % of its pixels on another texel than f64's with the unit direction,
/// 0.08 % with this); the finer ones (I32F32, the floats) take the unit ray's point,
/// which is what the course itself computes, and so break exact texel-edge ties as the
/// course does.
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
/// Not inlined: its locals stay out of the crate's rules' recursive mirror frames
/// (`trace_with` dispatches here), which a 16 KB chip's stack holds four deep.
///
/// A hit on a material with `specular K` and `transparency T` (filter `f`, see
/// [`filter_of`]) adds `W (1 − T) own / D` and continues along the mirror ray with weight
/// `W (1 − T) K` and along the same direction, skipping the object, with weight `W ⊙ f`
/// (`COURSE-RULES.md` §8, §11: the mirror first, then translucency). Both are followed
/// by the same loop (one of them kept in a [`MAX_COURSE_BRANCHES`] list): no recursion.
#[inline(never)]
pub(crate) fn trace_course<S: Scalar, T: Stages>(
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
        let Some((index, hit)) = nearest_course(scene, &ray, skip) else {
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
            (true, Some(d), Some(crate::Shape::Textured(slide))) => Hit {
                point: slide
                    .frame
                    .plane()
                    .crossing_along(ray.base, d)
                    .unwrap_or(hit.point),
                ..hit
            },
            _ => hit,
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
            let course = CourseLight {
                index,
                z_limit: z_limit::<S>(),
            };
            let mut leaving = (from, n);
            light_with(
                scene,
                &Incoming::from(&ray),
                object,
                &material,
                &hit,
                n,
                Some(course),
                LightStages::of::<T>(),
                &mut own,
                counters,
                Some(&mut leaving),
            );
            (from, normal) = (leaving.0, Some(leaving.1));
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
