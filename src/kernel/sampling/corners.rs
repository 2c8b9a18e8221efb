//! A block's corners: each traced to its nearest hit, what it sees there (its plane,
//! tile and occluders per light) and its colour by the diffuse model the certificates
//! bound.

use embedded_graphics_core::pixelcolor::Rgb888;

use super::{FACES_AWAY, LIGHTS};
use crate::geometry::{ShadowCone, Tiling, surface_tolerance};
use crate::kernel::fast::Primary;
use crate::kernel::shading::segment_tolerance;
use crate::shade::color::to_pixel;
use crate::shade::nearest;
use crate::shade::rules::Fixray;
use crate::{Scalar, SceneView, Shape, Vec3};

/// What a block's corner sees.
#[derive(Debug, Clone, Copy)]
pub(super) enum Sees<S> {
    /// Something no certificate covers (a sphere, a ray that cannot be formed).
    Other,
    /// Nothing: the background.
    Background,
    /// An infinite plane.
    Plane {
        object: u8,
        tile: (i32, i32),
        point: Vec3<S>,
        /// Per light: the occluders between the point and the light (bit `k`: object
        /// `k`), or [`FACES_AWAY`].
        shadows: [u32; LIGHTS],
        /// Per light lighting the point: its diffuse term there, `255·|N·L|/|L|²` in
        /// channel units per unit of emissivity and diffuse; zero for the others.
        terms: [S; LIGHTS],
    },
}

/// A block's four corners' light terms (`Sees::Plane`'s), in the corners' order.
pub(super) type CornerTerms<S> = [[S; LIGHTS]; 4];

/// A traced corner: its colour and what it sees.
#[derive(Debug, Clone, Copy)]
pub(super) struct Corner<S> {
    pub(super) color: Rgb888,
    pub(super) sees: Sees<S>,
}

/// Pixel (`column`, `row`): its nearest hit, what it sees there and, on a plane, its
/// colour by the diffuse model the certificates bound ([`plane_color`]). The hit is the
/// one the frame's kernel finds there where it has the fast kernel's per-frame part
/// (`primary`: its search of the pixel's unnormalised ray, the point and the shadow
/// segments' tolerance its shading takes), otherwise, or where that search hands the
/// pixel on, the reference path's (the definition's normalised ray).
pub(super) fn corner<S: Scalar>(
    scene: &SceneView<'_, S>,
    primary: Option<&Primary<S>>,
    column: u16,
    row: u16,
) -> Corner<S> {
    let other = Corner {
        color: Rgb888::new(0, 0, 0),
        sees: Sees::Other,
    };
    let background = Corner {
        color: to_pixel(scene.rules, scene.background),
        sees: Sees::Background,
    };
    if let Some(p) = primary
        && let Some(r) = p.row(scene, row, column)
        && let Ok(found) = p.nearest(scene, &r)
    {
        let Some(h) = found else {
            return background;
        };
        let eye = scene.camera.viewpoint;
        return segment_tolerance(eye, h.point, h.t_bound, None)
            .and_then(|tol| plane_seen(scene, primary, h.index, h.point, tol))
            .unwrap_or(other);
    }
    let Some(ray) = scene.camera.primary_ray(column, row) else {
        return other;
    };
    match nearest::<S, Fixray>(scene, &ray, None) {
        None => background,
        Some((index, hit)) => surface_tolerance(hit.t, hit.point.max_abs())
            .and_then(|tol| plane_seen(scene, None, index, hit.point, tol))
            .unwrap_or(other),
    }
}

/// A corner whose ray met `objects[index]` at `point`, if it is a plane: its tile, its
/// occluders per light (each object's exact segment test with tolerance `tol`, but where
/// a sphere's shadow cone from the fast kernel's `primary` clears the segment, which that
/// test then finds clear: `ShadowCone::clears`), and its colour.
fn plane_seen<S: Scalar>(
    scene: &SceneView<'_, S>,
    primary: Option<&Primary<S>>,
    index: usize,
    point: Vec3<S>,
    tol: S,
) -> Option<Corner<S>> {
    let object = scene.objects.get(index)?;
    let (tile, material) = match &object.shape {
        Shape::Plane(_) => ((0, 0), object.material),
        Shape::Tiled { frame, tiling, alt } => {
            let tile = match tiling {
                Tiling::Frame => frame.tile(point)?,
                Tiling::WorldXz => frame.tile_world_xz(point)?,
            };
            let odd = (tile.0.wrapping_add(tile.1)) & 1 == 1;
            (tile, if odd { *alt } else { object.material })
        }
        _ => return None,
    };
    let plane = object.shape.plane()?;
    // The side the eye sees: a light lights the point only from that side.
    let eye_side = plane.normal().dot(scene.camera.viewpoint.diff(point)?)?;
    let cones = primary.map_or(&[][..], |p| p.cones());
    // Per light: its occluders, and where none stands between, its diffuse term,
    // `255·|N·L|/|L|²` in channel units per unit of emissivity and diffuse (zero for the
    // others).
    let (mut shadows, mut terms) = ([0; LIGHTS], [S::ZERO; LIGHTS]);
    let channel = S::from_i32(255)?;
    for (j, ((state, term), light)) in shadows
        .iter_mut()
        .zip(terms.iter_mut())
        .zip(scene.lights)
        .enumerate()
    {
        let l = light.location.diff(point)?;
        let nl = plane.normal().dot(l)?;
        if nl == S::ZERO || (nl > S::ZERO) != (eye_side > S::ZERO) {
            *state = FACES_AWAY;
            continue;
        }
        let ll = l.dot(l)?;
        for (k, o) in scene.objects.iter().enumerate() {
            if k != index
                && !ShadowCone::any_clears(cones, j, k, l, ll)
                && o.shape.meets_segment(point, l, ll, tol, scene.epsilon)
            {
                *state |= 1 << k;
            }
        }
        if *state == 0 {
            *term = nl.abs().checked_mul(channel)?.checked_div(ll)?;
        }
    }
    let lit = shadows.map(|s| s == 0);
    let color = plane_color(
        scene,
        scene.materials.get(usize::from(material))?,
        &terms,
        lit,
    )?;
    Some(Corner {
        color,
        sees: Sees::Plane {
            object: u8::try_from(index).ok()?,
            tile,
            point,
            shadows,
            terms,
        },
    })
}

/// The colour of `material` under the lights `lit`, whose diffuse terms at the point are
/// `terms` (`Sees::Plane`'s): its ambient plus each light's `emissivity · diffuse ·
/// term` (the crate's diffuse model, each term rounded in its own order: within a level
/// of the kernels' pixel).
pub(super) fn plane_color<S: Scalar>(
    scene: &SceneView<'_, S>,
    material: &crate::Material<S>,
    terms: &[S; LIGHTS],
    lit: [bool; LIGHTS],
) -> Option<Rgb888> {
    let mut c = material.ambient;
    for ((light, _), f) in scene
        .lights
        .iter()
        .zip(lit)
        .zip(terms)
        .filter(|((_, l), _)| *l)
    {
        for ((c, e), d) in c.iter_mut().zip(light.emissivity).zip(material.diffuse) {
            *c = c.checked_add(e.checked_mul(d)?.checked_mul(*f)?)?;
        }
    }
    Some(to_pixel(scene.rules, c))
}
