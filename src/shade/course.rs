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
use crate::{Hit, Ray, RayKind, Scalar, SceneView, Vec3};

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

/// Traces a ray under the course rules with the stages of `T` (see the module
/// documentation): the first hit and the colour in channel units.
/// Not inlined: its locals stay out of the crate's rules' recursive mirror frames
/// (`trace_with` dispatches here), which a 16 KB chip's stack holds four deep.
#[inline(never)]
pub(crate) fn trace_course<S: Scalar, T: Stages>(
    scene: &SceneView<'_, S>,
    ray: &Ray<S>,
    counters: &mut Counters,
) -> Traced<S> {
    let max_path = S::from_i32(MAX_PATH).unwrap_or(S::MAX);
    let mut ray = Ray {
        kind: RayKind::Secondary,
        ..*ray
    };
    let mut skip = None;
    let mut travelled = S::ZERO;
    let mut weight = S::ONE;
    let mut color = [S::ZERO; 3];
    let mut first = None;
    for bounce in 0..=MAX_COURSE_BOUNCES {
        if travelled > max_path {
            break;
        }
        let Some((index, hit)) = nearest_course(scene, &ray, skip) else {
            // The course has no background: a miss is black. A primary miss shows the
            // scene's `background` (black unless the file sets one, which course files
            // never do).
            if bounce == 0 {
                color = scene.background;
            }
            break;
        };
        if bounce == 0 {
            first = Some((index, hit));
        }
        let Some((object, material)) = surface(scene, index, hit.point, counters) else {
            break;
        };
        let Some(d) = travelled.checked_add(hit.t) else {
            break;
        };
        travelled = d;
        let normal = object.shape.normal_at(hit.point);
        let mut own = material.ambient;
        if T::LIGHTING
            && let Some(n) = normal
        {
            let course = CourseLight {
                index,
                z_limit: z_limit::<S>(),
            };
            light_with(
                scene,
                &Incoming::from(&ray),
                object,
                material,
                &hit,
                n,
                Some(course),
                LightStages::of::<T>(),
                &mut own,
                counters,
            );
        }
        // W · own / D per channel (D > 0: every accepted t is).
        for (c, o) in color.iter_mut().zip(own) {
            let share = o
                .checked_mul(weight)
                .and_then(|wo| wo.checked_div(travelled))
                .unwrap_or(if o < S::ZERO { S::ZERO } else { S::MAX });
            *c = c.checked_add(share).unwrap_or(S::MAX);
        }
        let k = material.specular;
        if !T::REFLECTION || k == S::ZERO {
            break;
        }
        let Some(n) = normal else {
            break;
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
            break;
        };
        let Some(w) = weight.checked_mul(k).filter(|w| *w != S::ZERO) else {
            break;
        };
        weight = w;
        ray = Ray {
            base: hit.point,
            dir,
            kind: RayKind::Secondary,
        };
        skip = Some(index);
    }
    Traced { hit: first, color }
}
