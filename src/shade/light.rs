//! The lights' share of a hit's colour: diffuse, specular glints, spotlight cones and
//! shadow rays.

use super::color::{add_sat, term};
use super::stages::Stages;
use super::{Incoming, in_own_plane, light_tolerance, occludes};
use crate::stats::{Counters, count};
use crate::{Color, Hit, Material, Object, Ray, RayKind, Scalar, SceneView, Vec3};

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
#[inline(never)]
#[allow(clippy::too_many_arguments)]
pub(super) fn light_with<S: Scalar, T: Stages>(
    scene: &SceneView<'_, S>,
    ray: &Incoming<S>,
    object: &Object<S>,
    material: &Material<S>,
    hit: &Hit<S>,
    normal: Vec3<S>,
    course: Option<CourseLight<S>>,
    color: &mut Color<S>,
    counters: &mut Counters,
) {
    let channel_max = S::from_i32(255).unwrap_or(S::MAX);
    let specular = T::SPECULAR
        && match course {
            None => material.specular > S::ZERO,
            Some(_) => material.specular != S::ZERO && material.shininess > S::ZERO,
        };
    if material.diffuse != [S::ZERO; 3] || specular {
        for light in scene.lights {
            let Some(to_light) = light.location.diff(hit.point).and_then(Vec3::normalize) else {
                continue;
            };
            let l = to_light.unit;
            let Some(cos) = normal.dot(l).filter(|c| *c > S::ZERO) else {
                continue;
            };
            if scene.lights_on_surfaces
                && in_own_plane(
                    &object.shape,
                    light.location,
                    light_tolerance(scene.epsilon, light.location, scene.camera.viewpoint),
                )
            {
                continue;
            }
            if T::CONES
                && let Some(cone) = light.cone
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
                    continue;
                }
            }
            if T::SHADOWS {
                count(&mut counters.shadow_rays);
                // The distance itself may not fit (a far light): nothing lies beyond it.
                let dist = to_light.length().unwrap_or(S::MAX);
                let shadowed = match course {
                    None => object
                        .shape
                        .spawn_from(ray.base, hit, l)
                        .is_some_and(|r| occludes(scene, &r, dist, light.location, None, None)),
                    Some(c) => {
                        let from = Ray {
                            base: hit.point,
                            dir: l,
                            kind: RayKind::Secondary,
                        };
                        occludes(
                            scene,
                            &from,
                            dist,
                            light.location,
                            Some(c.index),
                            Some(c.z_limit),
                        )
                    }
                };
                if shadowed {
                    continue;
                }
            }
            count(&mut counters.diffuse);
            // 255 cos / dist and 255 (N·H)^shininess / dist, without forming dist; scaled
            // to channel units first so that the quotient keeps the format's relative
            // precision (cos / dist alone is small: in I20F12 it would keep 10 bits).
            let diffuse_falloff = cos
                .checked_mul(channel_max)
                .and_then(|k| to_light.divide(k))
                .unwrap_or(S::MAX);
            let glint = if specular {
                count(&mut counters.specular);
                let shine = ray
                    .dir
                    .checked_neg()
                    .and_then(|v| l.sum(v))
                    .and_then(Vec3::unit)
                    .and_then(|h| normal.dot(h))
                    .filter(|nh| *nh > S::ZERO)
                    .and_then(|nh| nh.pow_unit(material.shininess))
                    .and_then(|p| p.checked_mul(channel_max));
                match course {
                    None => shine.and_then(|k| to_light.divide(k)),
                    Some(_) => shine,
                }
                .unwrap_or(S::ZERO)
            } else {
                S::ZERO
            };
            for ((c, diffuse), emissivity) in
                color.iter_mut().zip(material.diffuse).zip(light.emissivity)
            {
                *c = add_sat(*c, term([emissivity, diffuse, diffuse_falloff]));
                if specular {
                    *c = add_sat(*c, term([emissivity, material.specular, glint]));
                }
            }
        }
    }
}
