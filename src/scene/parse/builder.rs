//! The builder: each parsed block becomes the scene's values (converted into the number
//! format, checked against the attribute's domain), with the error at the token at fault.
//! A number's conversion and domains are in `domain.rs`, the scale rule's checks of the
//! lengths a scene derives in `scale.rs`.

use core::cmp::Ordering;

use super::domain::{
    channel_colour, colour3, convert, in_domain, non_negative_value, positive, positive_value,
    vector,
};
use super::error::{Quantity, SceneError, SceneErrorKind, TextureProblem};
use super::scale::{Scales, radius_sq_beyond};
use super::schema::Entity;
use super::too_many;
use super::{Block, Parser, Result, Value, quote};
use crate::num::Decimal;
use crate::ppm::Ppm;
use crate::scene::{Beam, Cone, MAX_PIXELDIM, MAX_PROJECTORS, MAX_TEXTURES, Object};
use crate::{
    Camera, Light, Material, Plane, PlaneError, PlaneFrame, PlaneFrameError, Revsurf, RevsurfError,
    Rules, Scalar, Shape, Slide, Sphere, TexMode, Tiling, Triangle, TriangleError, Vec3,
};

impl<'a, S: Scalar, const O: usize, const M: usize, const L: usize> Parser<'a, '_, S, O, M, L> {
    // Out of line: one copy in flash, not one per call.
    #[inline(never)]
    pub(super) fn entity(&mut self, b: &Block<'a>) -> Result<()> {
        match b.entity {
            Entity::Camera => {
                if self.camera.is_some() {
                    return Err(b.error(SceneErrorKind::Duplicate("camera")));
                }
                self.camera = Some(camera(b, &mut self.scales)?);
            }
            Entity::Material => {
                // The course allows a name twice; a lookup takes the first.
                if self.rules == Rules::Fixray && self.material_names.contains(&b.name.text) {
                    return Err(b.name.pos.error(SceneErrorKind::DuplicateName {
                        entity: "material",
                        name: quote(b.name.text),
                    }));
                }
                // An object names its material by a byte: at most 256 materials.
                let capacity = M.min(usize::from(u8::MAX) + 1);
                let full = || too_many(b, "materials", capacity, "MATERIALS");
                // Both lists have the same capacity and length: check once, push both.
                if self.scene.materials.len() >= capacity {
                    return Err(full());
                }
                self.scene
                    .materials
                    .push(material_of(b, self.rules)?)
                    .map_err(|_| full())?;
                self.material_names.push(b.name.text).map_err(|_| full())?;
            }
            Entity::Light | Entity::Spotlight => {
                if !cfg!(feature = "lighting") {
                    return Err(b.error(SceneErrorKind::NotBuiltIn {
                        what: "lights are",
                        feature: "lighting",
                    }));
                }
                self.register(b)?;
                let location = vector(b.required("location")?)?;
                let beam = if b.entity == Entity::Spotlight {
                    Beam::Cone(cone::<S>(b, location)?)
                } else {
                    Beam::Everywhere
                };
                let light = Light {
                    location,
                    emissivity: colour3(b.required("emissivity")?, "emissivity", self.rules)?,
                    beam,
                };
                self.scene
                    .lights
                    .push(light)
                    .map_err(|_| too_many(b, "lights", L, "LIGHTS"))?;
            }
            Entity::Plane => {
                self.register(b)?;
                let material = self.material_index(b, "material")?;
                let normal = b.required("normal")?;
                let plane = Plane::new(vector(normal)?, vector(b.required("point")?)?)
                    .map_err(|e| plane_error::<S>(b, normal, e))?;
                self.push(b, Shape::Plane(plane), material)?;
            }
            Entity::Sphere => {
                if !cfg!(feature = "spheres") {
                    return Err(b.error(SceneErrorKind::NotBuiltIn {
                        what: "spheres are",
                        feature: "spheres",
                    }));
                }
                self.register(b)?;
                let material = self.material_index(b, "material")?;
                // Checked against the format's scale: in a fixed format the radius²
                // (`MIN_RADIUS_SQ_DELTAS`; its ulp is DELTA at every magnitude), in a
                // float the radius at the magnitude of the sphere's coordinates
                // (`MIN_SCALE_DELTAS`; its square's error is relative).
                let center = vector::<S>(b.required("center")?)?;
                let r = &b.required("radius")?.nums[0];
                let radius = positive::<S>(r, "radius")?;
                let sphere =
                    Sphere::new(center, radius).map_err(|_| radius_sq_beyond(r, S::NAME))?;
                let magnitude = center.max_abs().max(radius);
                if S::INT_BITS > 0 {
                    let radius_sq = sphere.radius_sq();
                    self.scales
                        .check(radius_sq, magnitude, r, Quantity::RadiusSq, 1)?;
                } else {
                    self.scales
                        .check(radius, magnitude, r, Quantity::Radius, 1)?;
                }
                self.push(b, Shape::Sphere(sphere), material)?;
            }
            Entity::TiledPlane | Entity::FPlane => {
                self.register(b)?;
                let material = self.material_index(b, "material")?;
                let dims = if b.entity == Entity::FPlane {
                    "dimensions"
                } else {
                    "dimension"
                };
                let normal = b.required("normal")?;
                let d = b.required(dims)?;
                let size = [
                    positive::<S>(&d.nums[0], dims)?,
                    positive::<S>(&d.nums[1], dims)?,
                ];
                let point = vector(b.required("point")?)?;
                let n = vector::<S>(normal)?;
                // A tiled plane without `xdir` (the course's older form) tiles world x/z;
                // its frame's own axes are then unused, any direction in the plane does.
                let (xdir, given, tiling) = match b.get("xdir") {
                    Some(x) => (vector(x)?, x, Tiling::Frame),
                    None => {
                        let x = Vec3::new(S::ONE, S::ZERO, S::ZERO);
                        let z = Vec3::new(S::ZERO, S::ZERO, S::ONE);
                        let along_x = n.x.abs() >= n.y.abs().max(n.z.abs());
                        (if along_x { z } else { x }, normal, Tiling::WorldXz)
                    }
                };
                let frame = PlaneFrame::new(n, point, xdir, size)
                    .map_err(|e| frame_error::<S>(b, [normal, given, d], dims, e))?;
                let shape = if b.entity == Entity::FPlane {
                    Shape::Finite(frame)
                } else {
                    Shape::Tiled {
                        frame,
                        alt: self.material_index(b, "altmaterial")?,
                        tiling,
                    }
                };
                self.push(b, shape, material)?;
            }
            Entity::Triangle | Entity::Tri => self.triangle(b)?,
            Entity::Texture => self.texture(b)?,
            Entity::Revsurf => self.revsurf(b)?,
            Entity::TexPlane => self.texplane(b)?,
            Entity::Projector => self.projector(b)?,
        }
        Ok(())
    }

    /// Not inlined, as every arm with large locals: the parser's frames are the deepest
    /// stack of a firmware (a 16 KB chip holds a `Scene<I32F32>` beside them).
    #[inline(never)]
    fn texplane(&mut self, b: &Block<'a>) -> Result<()> {
        self.textures_built_in(b)?;
        self.register(b)?;
        let material = self.material_index(b, "material")?;
        let slide = self.slide(b)?;
        self.push(b, Shape::Textured(slide), material)?;
        Ok(())
    }

    #[inline(never)]
    fn projector(&mut self, b: &Block<'a>) -> Result<()> {
        self.textures_built_in(b)?;
        if !cfg!(feature = "lighting") {
            return Err(b.error(SceneErrorKind::NotBuiltIn {
                what: "lights are",
                feature: "lighting",
            }));
        }
        self.register(b)?;
        let slide = self.slide(b)?;
        let full = || {
            b.error(SceneErrorKind::Full {
                what: "projectors",
                capacity: MAX_PROJECTORS,
            })
        };
        let index = u8::try_from(self.scene.projectors.len()).map_err(|_| full())?;
        self.scene.projectors.push(slide).map_err(|_| full())?;
        let light = Light {
            location: vector(b.required("location")?)?,
            emissivity: colour3(b.required("emissivity")?, "emissivity", self.rules)?,
            beam: Beam::Projector(index),
        };
        self.scene
            .lights
            .push(light)
            .map_err(|_| too_many(b, "lights", L, "LIGHTS"))?;
        Ok(())
    }

    #[inline(never)]
    fn revsurf(&mut self, b: &Block<'a>) -> Result<()> {
        self.register(b)?;
        let material = self.material_index(b, "material")?;
        let surfer = &b.required("surfer")?.nums[0];
        let direction = b.required("direction")?;
        let height = positive::<S>(&b.required("height")?.nums[0], "height")?;
        let k = surfer.value.to_integer().unwrap_or(-1);
        let shape = Revsurf::new(k, vector(b.required("base")?)?, vector(direction)?, height)
            .map_err(|e| match e {
                RevsurfError::UnknownProfile => surfer.pos.error(SceneErrorKind::OutOfDomain {
                    attribute: "surfer",
                    rule: "1, 2 or 3 (the cone, the hourglass and the vase: the \
                       course's profiles)",
                }),
                RevsurfError::ZeroDirection => direction.pos.error(SceneErrorKind::OutOfDomain {
                    attribute: "direction",
                    rule: "a non-zero vector",
                }),
                RevsurfError::NonPositiveHeight => b.error(SceneErrorKind::OutOfDomain {
                    attribute: "height",
                    rule: "> 0",
                }),
                RevsurfError::OutOfRange => b.error(SceneErrorKind::DerivedDoesNotFit {
                    what: "the profile's slope",
                    format: S::NAME,
                }),
            })?;
        self.push(b, Shape::Revsurf(shape), material)?;
        Ok(())
    }

    fn textures_built_in(&self, b: &Block<'a>) -> Result<()> {
        if cfg!(feature = "textures") {
            Ok(())
        } else {
            Err(b.error(SceneErrorKind::NotBuiltIn {
                what: "textures are",
                feature: "textures",
            }))
        }
    }

    /// `texture NAME { filename PATH }`: the file's bytes from the caller's source, read
    /// as a binary PPM.
    #[inline(never)]
    fn texture(&mut self, b: &Block<'a>) -> Result<()> {
        self.textures_built_in(b)?;
        let name = b.name.text;
        if self.rules == Rules::Fixray && self.texture_names.contains(&name) {
            return Err(b.name.pos.error(SceneErrorKind::DuplicateName {
                entity: "texture",
                name: quote(name),
            }));
        }
        let file = b
            .required("filename")?
            .name
            .ok_or_else(|| b.error(SceneErrorKind::ExpectedName(quote("filename"))))?;
        let error = |problem| {
            file.pos.error(SceneErrorKind::TextureFile {
                file: quote(file.text),
                problem,
            })
        };
        let bytes = (self.files)(file.text).ok_or_else(|| error(TextureProblem::NotFound))?;
        let image = Ppm::parse(bytes).map_err(|e| error(TextureProblem::Ppm(e)))?;
        let full = || {
            b.error(SceneErrorKind::Full {
                what: "textures",
                capacity: MAX_TEXTURES,
            })
        };
        self.scene.textures.push(image).map_err(|_| full())?;
        self.texture_names.push(name).map_err(|_| full())?;
        Ok(())
    }

    /// A textured rectangle: `normal`, `point`, `xdir`, `dimensions`, `texname`, `mode`.
    fn slide(&self, b: &Block<'a>) -> Result<Slide<S>> {
        let normal = b.required("normal")?;
        let xdir = b.required("xdir")?;
        let d = b.required("dimensions")?;
        let size = [
            positive::<S>(&d.nums[0], "dimensions")?,
            positive::<S>(&d.nums[1], "dimensions")?,
        ];
        let frame = PlaneFrame::new(
            vector(normal)?,
            vector(b.required("point")?)?,
            vector(xdir)?,
            size,
        )
        .map_err(|e| frame_error::<S>(b, [normal, xdir, d], "dimensions", e))?;
        let t = b
            .required("texname")?
            .name
            .ok_or_else(|| b.error(SceneErrorKind::ExpectedName(quote("texname"))))?;
        let texture = self
            .texture_names
            .iter()
            .position(|n| *n == t.text)
            .and_then(|i| u8::try_from(i).ok())
            .ok_or_else(|| t.pos.error(SceneErrorKind::UnknownTexture(quote(t.text))))?;
        let mode = match b.get("mode") {
            None => TexMode::Fit,
            Some(v) => match v.nums[0].value.to_integer() {
                Some(0) => TexMode::Fit,
                Some(1) => TexMode::Tile,
                _ => {
                    return Err(v.nums[0].pos.error(SceneErrorKind::OutOfDomain {
                        attribute: "mode",
                        rule: "0 (fit) or 1 (tile)",
                    }));
                }
            },
        };
        Ok(Slide {
            frame,
            texture,
            mode,
        })
    }

    fn triangle(&mut self, b: &Block<'a>) -> Result<()> {
        self.register(b)?;
        let material = self.material_index(b, "material")?;
        let names = if b.entity == Entity::Tri {
            ["v0", "v1", "v2"]
        } else {
            ["vertex1", "vertex2", "vertex3"]
        };
        let mut vertices = [Vec3::new(S::ZERO, S::ZERO, S::ZERO); 3];
        for (v, name) in vertices.iter_mut().zip(names) {
            *v = vector(b.required(name)?)?;
        }
        let triangle = Triangle::new(vertices).map_err(|e| match e {
            TriangleError::Degenerate => b.error(SceneErrorKind::OutOfDomain {
                attribute: names[0],
                rule: "one of three vertices that span a triangle (not on one line)",
            }),
            TriangleError::OffsetOutOfRange => b.error(SceneErrorKind::DerivedDoesNotFit {
                what: "the triangle's offset N·vertex",
                format: S::NAME,
            }),
        })?;
        self.push(b, Shape::Triangle(triangle), material)
    }

    // Out of line: one copy in flash, not one per call.
    #[inline(never)]
    fn push(&mut self, b: &Block<'a>, shape: Shape<S>, material: u8) -> Result<()> {
        self.scene
            .objects
            .push(Object { shape, material })
            .map_err(|_| too_many(b, "objects", O, "OBJECTS"))
    }
}

fn plane_error<S: Scalar>(b: &Block<'_>, normal: &Value<'_>, e: PlaneError) -> SceneError {
    match e {
        PlaneError::ZeroNormal => normal.pos.error(SceneErrorKind::ZeroNormal),
        PlaneError::OffsetOutOfRange => b.error(SceneErrorKind::DerivedDoesNotFit {
            what: "the plane's offset N·point",
            format: S::NAME,
        }),
    }
}

/// A spotlight's cone: the unit axis towards `point` and cos θ (θ in degrees, (0, 90]).
fn cone<S: Scalar>(b: &Block<'_>, location: Vec3<S>) -> Result<Cone<S>> {
    let point = b.required("point")?;
    let axis = vector::<S>(point)?
        .diff(location)
        .and_then(Vec3::unit)
        .ok_or_else(|| {
            point.pos.error(SceneErrorKind::OutOfDomain {
                attribute: "point",
                rule: "a point other than the spotlight's location",
            })
        })?;
    let theta = &b.required("theta")?.nums[0];
    let ok = |d: &Decimal| positive_value(d) && d.cmp_int(90) != Ordering::Greater;
    in_domain(theta, ok, "theta", "in (0, 90]")?;
    // θ π / 180 in the format, π from its decimal digits (no float on the way).
    let pi = Decimal {
        negative: false,
        mantissa: 3_141_592_653_589_793_238,
        exponent: -18,
    };
    let cos_theta = S::from_decimal(pi)
        .and_then(|pi| convert::<S>(theta, 1).ok()?.checked_mul(pi))
        .and_then(|x| x.checked_div(S::from_i32(180)?))
        .and_then(S::cos)
        .ok_or_else(|| {
            theta.pos.error(SceneErrorKind::DerivedDoesNotFit {
                what: "cos θ",
                format: S::NAME,
            })
        })?;
    Ok(Cone { axis, cos_theta })
}

// Out of line: one copy in flash, not one per call.
#[inline(never)]
fn camera<S: Scalar>(b: &Block<'_>, scales: &mut Scales) -> Result<Camera<S>> {
    let pixeldim = b.required("pixeldim")?;
    let mut dims = [0u16; 2];
    for (d, n) in dims.iter_mut().zip(&pixeldim.nums) {
        *d = n
            .value
            .to_integer()
            .and_then(|i| u16::try_from(i).ok())
            .filter(|i| (1..=MAX_PIXELDIM).contains(i))
            .ok_or_else(|| {
                n.pos.error(SceneErrorKind::OutOfDomain {
                    attribute: "pixeldim",
                    rule: "integers in 1..=4096",
                })
            })?;
    }
    let worlddim = b.required("worlddim")?;
    let viewpoint = b.required("viewpoint")?;
    let eye = vector::<S>(viewpoint)?;
    in_domain(&viewpoint.nums[2], positive_value, "viewpoint", "at z > 0")?;
    // The pixel pitch along each axis against the format's scale (`MIN_SCALE_DELTAS`), at
    // the magnitude of the window and of the eye's coordinate along it (`screen − eye` is
    // rounded there).
    let [nx, ny] = [&worlddim.nums[0], &worlddim.nums[1]];
    let wx = positive::<S>(nx, "worlddim")?;
    scales.check(wx, wx.max(eye.x.abs()), nx, Quantity::PixelPitch, dims[0])?;
    let wy = positive::<S>(ny, "worlddim")?;
    scales.check(wy, wy.max(eye.y.abs()), ny, Quantity::PixelPitch, dims[1])?;
    Ok(Camera {
        width: dims[0],
        height: dims[1],
        world_width: wx,
        world_height: wy,
        viewpoint: Vec3::new(eye.x, eye.y, positive(&viewpoint.nums[2], "viewpoint")?),
        // Set from the scene's rules once the file is read.
        grid: crate::PixelGrid::Centres,
    })
}

fn material_of<S: Scalar>(b: &Block<'_>, rules: Rules) -> Result<Material<S>> {
    let mut m = Material::new();
    if rules == Rules::Course {
        // The course's glint needs `shininess`: without it there is none.
        m.shininess = S::ZERO;
    }
    if let Some(v) = b.get("ambient") {
        m.ambient = channel_colour(&v.nums, "ambient", rules)?;
    }
    if let Some(v) = b.get("diffuse") {
        m.diffuse = colour3(v, "diffuse", rules)?;
    }
    // `specular R G B` (older course files) is read and, as the course tracer that reads
    // such files does, not used.
    if let Some(v) = b.get("specular").filter(|v| v.count == 1) {
        in_domain(&v.nums[0], non_negative_value, "specular", ">= 0")?;
        m.specular = convert(&v.nums[0], 1)?;
        if m.specular > S::ZERO && !cfg!(feature = "lighting") {
            return Err(v.pos.error(SceneErrorKind::NotBuiltIn {
                what: "specular is",
                feature: "lighting",
            }));
        }
    }
    if let Some(v) = b.get("shininess") {
        let n = &v.nums[0];
        if rules == Rules::Course && n.value.is_zero() {
            m.shininess = S::ZERO;
        } else {
            let ok = |d: &Decimal| d.cmp_int(1) != Ordering::Less;
            let rule = match rules {
                Rules::Fixray => ">= 1",
                Rules::Course => "0 (no glint) or >= 1",
            };
            in_domain(n, ok, "shininess", rule)?;
            m.shininess = convert(n, 1)?;
        }
    }
    if let Some(t) = share(b, "transparency", Rules::Course, rules)? {
        m.transparency = t;
    }
    if let Some(k) = share(b, "reflective", Rules::Fixray, rules)? {
        m.reflective = k;
        if m.reflective > S::ZERO && !cfg!(feature = "reflection") {
            return Err(b
                .required("reflective")?
                .pos
                .error(SceneErrorKind::NotBuiltIn {
                    what: "reflective materials are",
                    feature: "reflection",
                }));
        }
    }
    Ok(m)
}

/// A material's share in [0, 1] that only the rule set `own` has (`reflective`: the
/// crate's, `transparency`: the course's); `None` when the block has none.
// Out of line: one copy in flash, not one per call.
#[inline(never)]
fn share<S: Scalar>(
    b: &Block<'_>,
    attribute: &'static str,
    own: Rules,
    rules: Rules,
) -> Result<Option<S>> {
    let Some(v) = b.get(attribute) else {
        return Ok(None);
    };
    if rules != own {
        return Err(v.pos.error(SceneErrorKind::OtherRules {
            attribute,
            rules: match own {
                Rules::Course => "course",
                Rules::Fixray => "fixray",
            },
        }));
    }
    let ok = |d: &Decimal| non_negative_value(d) && d.cmp_int(1) != Ordering::Greater;
    in_domain(&v.nums[0], ok, attribute, "in [0, 1]")?;
    Ok(Some(convert(&v.nums[0], 1)?))
}

/// The error of a tiled or finite plane's frame, at the attribute at fault: the normal
/// (or the block, for the offset), `xdir`, or the dimensions `dims`.
fn frame_error<S: Scalar>(
    b: &Block<'_>,
    [normal, xdir, dims]: [&Value<'_>; 3],
    dims_name: &'static str,
    e: PlaneFrameError,
) -> SceneError {
    match e {
        PlaneFrameError::Plane(e) => plane_error::<S>(b, normal, e),
        PlaneFrameError::XdirInvalid => xdir.pos.error(SceneErrorKind::OutOfDomain {
            attribute: "xdir",
            rule: "a direction with a component in the plane (not along the normal)",
        }),
        PlaneFrameError::NonPositiveSize => dims.pos.error(SceneErrorKind::OutOfDomain {
            attribute: dims_name,
            rule: "> 0",
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::super::error::Pos;
    use super::*;

    /// A non-positive tile or side length is reported at the dimensions, not at `xdir`.
    #[test]
    fn a_frame_size_error_points_at_the_dimensions() {
        let at = |line, column| Value {
            pos: Pos { line, column },
            ..Value::default()
        };
        let (normal, xdir, dims) = (at(1, 10), at(1, 20), at(1, 30));
        let name = super::super::lexer::Lexer::new("t").next_token().unwrap();
        let b = Block {
            entity: Entity::FPlane,
            pos: Pos { line: 1, column: 1 },
            name,
            values: Default::default(),
        };
        let e = frame_error::<crate::I16F16>(
            &b,
            [&normal, &xdir, &dims],
            "dimensions",
            PlaneFrameError::NonPositiveSize,
        );
        assert_eq!((e.line, e.column), (1, 30));
        assert_eq!(e.to_string(), "1:30: `dimensions` must be > 0");
        let e = frame_error::<crate::I16F16>(
            &b,
            [&normal, &xdir, &dims],
            "dimensions",
            PlaneFrameError::XdirInvalid,
        );
        assert_eq!((e.line, e.column), (1, 20));
    }
}
