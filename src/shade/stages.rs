//! Stage sets: the shading loop is compiled once per set, and the plan picks one.

use crate::{AsView, Plan, Scalar, SceneView};

/// A set of shading stages, fixed at compile time: the renderer is instantiated once per
/// set, and a stage that is `false` is not in that loop at all (no per-pixel test). The
/// plan of a scene picks the set (`shading_for`). Each stage is also compiled out of
/// every set when its cargo feature (`lighting`, `reflection`) is off. Without the cargo
/// feature `kernels` one set, [`Full`], is compiled and draws every scene
/// ([`Shading::compiled`]): its stages then ask the scene, per light or material, and
/// the view for its shadows ([`stage`]).
pub trait Stages {
    /// Diffuse lighting.
    const LIGHTING: bool;
    /// Shadow rays.
    const SHADOWS: bool;
    /// Specular glints.
    const SPECULAR: bool;
    /// Spotlight cones.
    const CONES: bool;
    /// Mirror reflection.
    const REFLECTION: bool;
    /// Translucent materials (the course's `transparency`): transmitted rays and light
    /// filtered through translucent occluders.
    const TRANSPARENCY: bool;
}

/// The lighting stages of a set as values: the light loop (`light.rs`) is compiled once
/// and asks these per light (a branch), not once per stage set (kilobytes of flash on a
/// 64 KB chip); a stage that is off still does no work.
#[derive(Debug, Clone, Copy)]
pub(crate) struct LightStages {
    /// Shadow rays.
    pub(crate) shadows: bool,
    /// Spotlight cones.
    pub(crate) cones: bool,
    /// Specular glints.
    pub(crate) specular: bool,
    /// Light filtered through translucent occluders.
    #[cfg_attr(not(feature = "course"), allow(dead_code))] // read by the course's rules only
    pub(crate) transparency: bool,
}

impl LightStages {
    /// The lighting stages of the set `T` for `scene`: its shadows are also the chosen
    /// set's ([`stage`]; the same as `T`'s where `T` is the chosen set, and what one
    /// compiled set drawing every scene needs).
    pub(crate) const fn of<T: Stages, S>(scene: &SceneView<'_, S>) -> Self {
        Self {
            shadows: T::SHADOWS && scene.shadows,
            cones: T::CONES,
            specular: T::SPECULAR,
            transparency: T::TRANSPARENCY,
        }
    }
}

/// Ambient only: pure geometry.
pub struct AmbientOnly;
/// Diffuse point lights, nothing between them and the surface.
pub struct Diffuse;
/// Diffuse point lights with shadow rays.
pub struct DiffuseShadows;
/// Everything the scene format has.
pub struct Full;

impl Stages for AmbientOnly {
    const LIGHTING: bool = false;
    const SHADOWS: bool = false;
    const SPECULAR: bool = false;
    const CONES: bool = false;
    const REFLECTION: bool = false;
    const TRANSPARENCY: bool = false;
}
impl Stages for Diffuse {
    const LIGHTING: bool = cfg!(feature = "lighting");
    const SHADOWS: bool = false;
    const SPECULAR: bool = false;
    const CONES: bool = false;
    const REFLECTION: bool = false;
    const TRANSPARENCY: bool = false;
}
impl Stages for DiffuseShadows {
    const LIGHTING: bool = cfg!(feature = "lighting");
    const SHADOWS: bool = cfg!(feature = "lighting");
    const SPECULAR: bool = false;
    const CONES: bool = false;
    const REFLECTION: bool = false;
    const TRANSPARENCY: bool = false;
}
impl Stages for Full {
    const LIGHTING: bool = cfg!(feature = "lighting");
    const SHADOWS: bool = cfg!(feature = "lighting");
    const SPECULAR: bool = cfg!(feature = "lighting");
    const CONES: bool = cfg!(feature = "lighting");
    const REFLECTION: bool = cfg!(feature = "reflection");
    const TRANSPARENCY: bool = true;
}

/// Which stage set a plan needs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Shading {
    /// [`AmbientOnly`].
    AmbientOnly,
    /// [`Diffuse`].
    Diffuse,
    /// [`DiffuseShadows`].
    DiffuseShadows,
    /// [`Full`].
    Full,
}

impl Shading {
    /// Whether the set casts shadows (what a view drawn with it is set to,
    /// `SceneView::shadows`, by [`stage`]).
    const fn shadows(self) -> bool {
        match self {
            Shading::AmbientOnly => AmbientOnly::SHADOWS,
            Shading::Diffuse => Diffuse::SHADOWS,
            Shading::DiffuseShadows => DiffuseShadows::SHADOWS,
            Shading::Full => Full::SHADOWS,
        }
    }

    /// The set compiled for this one: itself, or [`Full`] in a build without the kernels
    /// (cargo feature `kernels` off), which compiles one set for flash. [`Full`] then
    /// draws what the chosen set draws: its other stages ask the scene (a glint, a cone,
    /// a mirror, a translucent material per light or material, no lights at all), and
    /// its shadows the view ([`stage`]).
    pub(crate) const fn compiled(self) -> Self {
        if cfg!(feature = "kernels") {
            self
        } else {
            Shading::Full
        }
    }
}

/// Sets `view` up for drawing with the stage set `shading` (its shadows): where a set is
/// chosen for a view, before anything is drawn with it.
pub(crate) fn stage<S>(view: &mut SceneView<'_, S>, shading: Shading) {
    view.shadows = shading.shadows();
}

/// A view of `scene` set up for the stage set its plan needs ([`stage`]), and that set:
/// where a call that draws without a `Frame` starts (it works out the plan).
pub(crate) fn planned<S: Scalar>(scene: &impl AsView<S>) -> (SceneView<'_, S>, Shading) {
    let mut view = scene.view();
    let shading = shading_for(&view.plan());
    stage(&mut view, shading);
    (view, shading)
}

/// The smallest stage set that covers a plan.
pub(crate) fn shading_for(plan: &Plan) -> Shading {
    if plan.reflection || plan.specular || plan.spotlights || plan.transparency {
        Shading::Full
    } else if plan.lighting && plan.shadows {
        Shading::DiffuseShadows
    } else if plan.lighting {
        Shading::Diffuse
    } else {
        Shading::AmbientOnly
    }
}

/// `with_stages!(shading, f::<S, More…>(args))` calls `f::<S, Set, More…>(args)` for the
/// stage set `Set` compiled for the one `shading` names ([`Shading::compiled`]): the plan
/// is looked at once per call, never per pixel. The one 4-way dispatch of the crate. The
/// view `f` draws must be set up for `shading` ([`stage`]).
macro_rules! with_stages {
    ($shading:expr, $($f:ident)::+::<$s:ty $(, $more:ty)*>($($arg:expr),*)) => {
        match $crate::shade::stages::Shading::compiled($shading) {
            $crate::shade::stages::Shading::AmbientOnly => {
                $($f)::+::<$s, $crate::shade::stages::AmbientOnly $(, $more)*>($($arg),*)
            }
            $crate::shade::stages::Shading::Diffuse => {
                $($f)::+::<$s, $crate::shade::stages::Diffuse $(, $more)*>($($arg),*)
            }
            $crate::shade::stages::Shading::DiffuseShadows => {
                $($f)::+::<$s, $crate::shade::stages::DiffuseShadows $(, $more)*>($($arg),*)
            }
            $crate::shade::stages::Shading::Full => {
                $($f)::+::<$s, $crate::shade::stages::Full $(, $more)*>($($arg),*)
            }
        }
    };
}
pub(crate) use with_stages;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shade::trace_pixel_ray;
    use crate::stats::Counters;
    use crate::{Color, I16F16, Scene};

    /// Every pixel of `view` traced on the reference path with the set `T`, and what was
    /// counted.
    fn traced<T: Stages>(view: &SceneView<'_, I16F16>) -> (Vec<Color<I16F16>>, Counters) {
        let mut counters = Counters::default();
        let mut pixels = Vec::new();
        for row in 0..view.camera.height {
            for column in 0..view.camera.width {
                let pixel = view
                    .camera
                    .screen_y(row)
                    .and_then(|y| view.camera.pixel_ray_at(column, y))
                    .expect("the ray forms");
                pixels.push(trace_pixel_ray::<I16F16, T>(view, &pixel, &mut counters).color);
            }
        }
        (pixels, counters)
    }

    /// One compiled set draws what the chosen one draws (a build without the `kernels`
    /// feature draws every scene with `Full`): a plane under a light (the `Diffuse` set:
    /// a lone plane casts no shadow) traced by `Full` on a view set up for `Diffuse` gives
    /// every pixel that `Diffuse` gives and casts no shadow; set up for `Full`, it casts
    /// them (counted with the `stats` feature, on in the tests).
    #[test]
    fn full_on_a_view_set_up_for_another_set_draws_that_set() {
        let text = "rules fixray\n\
            camera c { pixeldim 16 12 worlddim 8 6 viewpoint 4 3 6 }\n\
            material m { ambient 0.1 0.1 0.1 diffuse 0.8 0.7 0.6 }\n\
            light l { location 4 5 -3 emissivity 6 6 6 }\n\
            plane floor { material m normal 0 1 0 point 0 0 0 }\n";
        let scene = Scene::<I16F16>::parse(text).unwrap();
        let mut view = scene.view();
        let shading = shading_for(&view.plan());
        assert_eq!(shading, Shading::Diffuse);
        stage(&mut view, shading);
        let (diffuse, _) = traced::<Diffuse>(&view);
        let (full, counted) = traced::<Full>(&view);
        assert_eq!(full, diffuse);
        assert!(counted.diffuse > 0, "{counted:?}");
        assert_eq!(counted.shadow_rays, 0, "{counted:?}");
        stage(&mut view, Shading::Full);
        let (full, counted) = traced::<Full>(&view);
        assert_eq!(full, diffuse);
        assert!(counted.shadow_rays > 0, "{counted:?}");
    }
}
