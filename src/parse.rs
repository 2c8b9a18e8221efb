//! The scene parser: the keyword-block format of `scene-format.md`, no_std, no allocator.
//!
//! Every bad input ends in a [`SceneError`] that names the line and column (1-based, in
//! characters) of the token at fault; no input makes the parser panic. The whole format is
//! read and checked; entities the renderer cannot draw yet (`spotlight`, `sphere`,
//! `tiled_plane`, `fplane`, specular and reflective materials) are refused with
//! [`SceneErrorKind::NotSupported`] after their block has been checked, never ignored.
//!
//! ```
//! use fixray::{Scene, SceneErrorKind, I16F16};
//!
//! let text = "camera c {\n  pixeldim 4 0 worlddim 4 3 viewpoint 2 1.5 5\n}";
//! let err = Scene::<I16F16>::parse(text).unwrap_err();
//! assert_eq!((err.line, err.column), (2, 14));
//! assert!(matches!(err.kind, SceneErrorKind::OutOfDomain { .. }));
//! assert_eq!(
//!     format!("{err}"),
//!     "2:14: `pixeldim` must be integers in 1..=4096"
//! );
//! ```

use core::fmt;

use heapless::{String, Vec};

use core::cmp::Ordering;

use crate::decimal::Decimal;
use crate::scene::Cone;
use crate::scene::{MAX_LIGHTS, MAX_MATERIALS, MAX_OBJECTS, MAX_PIXELDIM};
use crate::{
    Camera, Color, FrameError, Light, Material, Plane, PlaneError, PlaneFrame, Scalar, Scene,
    Shape, Sphere, Vec3,
};

/// Longest token quoted in an error message; longer ones are cut and end in `…`.
pub const MAX_QUOTED: usize = 24;

/// A token quoted in an error message (cut to [`MAX_QUOTED`] bytes).
pub type Quoted = String<MAX_QUOTED>;

/// A scene file error at a line and column.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneError {
    /// 1-based line of the token at fault (for "end of input" errors: the last line).
    pub line: u32,
    /// 1-based column, in characters.
    pub column: u32,
    /// What is wrong.
    pub kind: SceneErrorKind,
}

/// What is wrong with a scene file.
#[derive(Debug, Clone, PartialEq)]
pub enum SceneErrorKind {
    /// A word where an entity keyword (`camera`, `plane`, ...) was expected.
    UnknownKeyword(Quoted),
    /// A word inside a block that is not one of the entity's attributes.
    UnknownAttribute {
        /// The entity keyword.
        entity: &'static str,
        /// The word found.
        found: Quoted,
    },
    /// An attribute given twice in one block.
    DuplicateAttribute(&'static str),
    /// A required attribute is missing from a block.
    MissingAttribute {
        /// The entity keyword.
        entity: &'static str,
        /// The missing attribute.
        attribute: &'static str,
    },
    /// Something else where a name was expected (names are `[A-Za-z_][A-Za-z0-9_]*`).
    ExpectedName(Quoted),
    /// Something else where `{` was expected.
    ExpectedOpenBrace(Quoted),
    /// Something else where a number was expected.
    ExpectedNumber(Quoted),
    /// The input ended in the middle of something.
    UnexpectedEnd(&'static str),
    /// A number is outside what the chosen number format can hold.
    DoesNotFit {
        /// The number as written.
        value: Quoted,
        /// The number format.
        format: &'static str,
    },
    /// A number outside the attribute's domain (`pixeldim 0`, `radius -1`, ...).
    OutOfDomain {
        /// The attribute.
        attribute: &'static str,
        /// The rule it breaks, as the format states it.
        rule: &'static str,
    },
    /// A name used twice for one kind of entity.
    DuplicateName {
        /// The entity keyword.
        entity: &'static str,
        /// The name.
        name: Quoted,
    },
    /// A material named before it was defined, or never.
    UnknownMaterial(Quoted),
    /// A normal that is zero (or rounds to zero in the number format).
    ZeroNormal,
    /// A derived quantity (such as a plane's `N·point`) does not fit the number format.
    DerivedDoesNotFit {
        /// What it is.
        what: &'static str,
        /// The number format.
        format: &'static str,
    },
    /// A second `camera`, `background` or `precision`.
    Duplicate(&'static str),
    /// No `camera` in the file.
    MissingCamera,
    /// More entities of a kind than the crate's capacity.
    TooMany {
        /// The kind.
        what: &'static str,
        /// The capacity ([`MAX_MATERIALS`], [`MAX_LIGHTS`], [`MAX_OBJECTS`]).
        capacity: usize,
    },
    /// A valid entity or attribute whose stage this build leaves out (a firmware built
    /// without one of the cargo features `lighting`, `spheres`, `reflection`).
    NotBuiltIn {
        /// What the scene asks for.
        what: &'static str,
        /// The cargo feature that builds it in.
        feature: &'static str,
    },
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}: {}", self.line, self.column, self.kind)
    }
}

impl core::error::Error for SceneError {}

impl fmt::Display for SceneErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use SceneErrorKind as K;
        match self {
            K::UnknownKeyword(w) => write!(
                f,
                "unknown keyword `{w}` (expected camera, material, light, spotlight, plane, \
                 sphere, tiled_plane, fplane, background or precision)"
            ),
            K::UnknownAttribute { entity, found } => {
                write!(f, "`{found}` is not an attribute of {entity}")
            }
            K::DuplicateAttribute(a) => write!(f, "`{a}` given twice in one block"),
            K::MissingAttribute { entity, attribute } => {
                write!(f, "{entity} is missing its `{attribute}`")
            }
            K::ExpectedName(w) => write!(f, "expected a name, found `{w}`"),
            K::ExpectedOpenBrace(w) => write!(f, "expected `{{`, found `{w}`"),
            K::ExpectedNumber(w) => write!(f, "expected a number, found `{w}`"),
            K::UnexpectedEnd(what) => write!(f, "unexpected end of input: expected {what}"),
            K::DoesNotFit { value, format } => {
                write!(f, "`{value}` does not fit in the {format} number format")
            }
            K::OutOfDomain { attribute, rule } => write!(f, "`{attribute}` must be {rule}"),
            K::DuplicateName { entity, name } => write!(f, "{entity} `{name}` is defined twice"),
            K::UnknownMaterial(m) => write!(
                f,
                "unknown material `{m}` (a material must be defined before it is named)"
            ),
            K::ZeroNormal => write!(f, "the normal is zero"),
            K::DerivedDoesNotFit { what, format } => {
                write!(f, "{what} does not fit in the {format} number format")
            }
            K::Duplicate(what) => write!(f, "a second `{what}` (only one is allowed)"),
            K::MissingCamera => write!(f, "the scene has no camera"),
            K::TooMany { what, capacity } => {
                write!(f, "too many {what} (this build holds {capacity})")
            }
            K::NotBuiltIn { what, feature } => write!(
                f,
                "{what} not built into this program (cargo feature `{feature}`)"
            ),
        }
    }
}

/// A position in the source text.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
struct Pos {
    line: u32,
    column: u32,
}

impl Pos {
    fn error(self, kind: SceneErrorKind) -> SceneError {
        SceneError {
            line: self.line,
            column: self.column,
            kind,
        }
    }
}

#[derive(Debug, Clone, Copy)]
struct Token<'a> {
    text: &'a str,
    pos: Pos,
}

/// Splits the text into tokens: `{`, `}` and runs of other non-space characters; `#`
/// comments run to the end of the line.
struct Lexer<'a> {
    rest: &'a str,
    pos: Pos,
}

impl<'a> Lexer<'a> {
    fn new(text: &'a str) -> Self {
        Self {
            rest: text,
            pos: Pos { line: 1, column: 1 },
        }
    }

    fn advance(&mut self, c: char) {
        // `c` is the first char of `rest`: the cut is on a char boundary (`get` keeps the
        // impossible panic path, and its formatting code, out of the firmware).
        self.rest = self.rest.get(c.len_utf8()..).unwrap_or("");
        if c == '\n' {
            self.pos.line = self.pos.line.saturating_add(1);
            self.pos.column = 1;
        } else {
            self.pos.column = self.pos.column.saturating_add(1);
        }
    }

    fn next_token(&mut self) -> Option<Token<'a>> {
        // Skip white space and comments.
        loop {
            let c = self.rest.chars().next()?;
            if c == '#' {
                while let Some(c) = self.rest.chars().next() {
                    if c == '\n' {
                        break;
                    }
                    self.advance(c);
                }
            } else if c.is_whitespace() {
                self.advance(c);
            } else {
                break;
            }
        }
        let start = self.rest;
        let pos = self.pos;
        let first = start.chars().next()?;
        self.advance(first);
        if first != '{' && first != '}' {
            while let Some(c) = self.rest.chars().next() {
                if c.is_whitespace() || c == '{' || c == '}' || c == '#' {
                    break;
                }
                self.advance(c);
            }
        }
        let len = start.len() - self.rest.len();
        Some(Token {
            text: start.get(..len).unwrap_or(""),
            pos,
        })
    }
}

fn quote(text: &str) -> Quoted {
    let mut q = Quoted::new();
    for c in text.chars() {
        if q.len() + c.len_utf8() > MAX_QUOTED - '…'.len_utf8() {
            // Room for the ellipsis is kept above, so this push cannot fail.
            let _ = q.push('…');
            break;
        }
        let _ = q.push(c);
    }
    q
}

fn is_name(s: &str) -> bool {
    let mut chars = s.chars();
    matches!(chars.next(), Some(c) if c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// The entity kinds of the scene format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Entity {
    Camera,
    Material,
    Light,
    Spotlight,
    Plane,
    Sphere,
    TiledPlane,
    FPlane,
}

impl Entity {
    const ALL: [Self; 8] = [
        Self::Camera,
        Self::Material,
        Self::Light,
        Self::Spotlight,
        Self::Plane,
        Self::Sphere,
        Self::TiledPlane,
        Self::FPlane,
    ];

    fn keyword(self) -> &'static str {
        match self {
            Self::Camera => "camera",
            Self::Material => "material",
            Self::Light => "light",
            Self::Spotlight => "spotlight",
            Self::Plane => "plane",
            Self::Sphere => "sphere",
            Self::TiledPlane => "tiled_plane",
            Self::FPlane => "fplane",
        }
    }

    /// The attributes, as `scene-format.md` lists them.
    fn attributes(self) -> &'static [AttrSpec] {
        match self {
            Self::Camera => {
                const {
                    &[
                        numbers("pixeldim", 2),
                        numbers("worlddim", 2),
                        numbers("viewpoint", 3),
                    ]
                }
            }
            Self::Material => {
                const {
                    &[
                        optional("ambient", 3),
                        optional("diffuse", 3),
                        optional("specular", 1),
                        optional("shininess", 1),
                        optional("reflective", 1),
                    ]
                }
            }
            Self::Light => const { &[numbers("location", 3), numbers("emissivity", 3)] },
            Self::Spotlight => {
                const {
                    &[
                        numbers("location", 3),
                        numbers("emissivity", 3),
                        numbers("point", 3),
                        numbers("theta", 1),
                    ]
                }
            }
            Self::Plane => {
                const {
                    &[
                        material("material"),
                        numbers("normal", 3),
                        numbers("point", 3),
                    ]
                }
            }
            Self::Sphere => {
                const {
                    &[
                        material("material"),
                        numbers("center", 3),
                        numbers("radius", 1),
                    ]
                }
            }
            Self::TiledPlane => {
                const {
                    &[
                        material("material"),
                        material("altmaterial"),
                        numbers("normal", 3),
                        numbers("point", 3),
                        numbers("xdir", 3),
                        numbers("dimension", 2),
                    ]
                }
            }
            Self::FPlane => {
                const {
                    &[
                        material("material"),
                        numbers("normal", 3),
                        numbers("point", 3),
                        numbers("xdir", 3),
                        numbers("dimensions", 2),
                    ]
                }
            }
        }
    }
}

/// How an attribute's value is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Arity {
    /// A material name.
    Name,
    /// This many numbers.
    Numbers(usize),
}

struct AttrSpec {
    name: &'static str,
    arity: Arity,
    required: bool,
}

const fn numbers(name: &'static str, n: usize) -> AttrSpec {
    AttrSpec {
        name,
        arity: Arity::Numbers(n),
        required: true,
    }
}
const fn optional(name: &'static str, n: usize) -> AttrSpec {
    AttrSpec {
        name,
        arity: Arity::Numbers(n),
        required: false,
    }
}
const fn material(name: &'static str) -> AttrSpec {
    AttrSpec {
        name,
        arity: Arity::Name,
        required: true,
    }
}

/// The most attributes any entity has.
const MAX_ATTRS: usize = 6;

/// A number as written, where it was written.
#[derive(Debug, Clone, Copy, Default)]
struct Number<'a> {
    value: Decimal,
    pos: Pos,
    text: &'a str,
}

/// One attribute's value: up to three numbers or a material name.
#[derive(Debug, Clone, Copy, Default)]
struct Value<'a> {
    /// Where the attribute's keyword is.
    pos: Pos,
    nums: [Number<'a>; 3],
    name: Option<Token<'a>>,
}

/// A parsed block: its entity, name and attribute values (indexed like its attributes).
struct Block<'a> {
    entity: Entity,
    pos: Pos,
    name: Token<'a>,
    values: [Option<Value<'a>>; MAX_ATTRS],
}

impl<'a> Block<'a> {
    /// The value of an attribute; `None` when it is optional and absent.
    fn get(&self, attribute: &'static str) -> Option<&Value<'a>> {
        let i = self
            .entity
            .attributes()
            .iter()
            .position(|s| s.name == attribute)?;
        self.values.get(i)?.as_ref()
    }

    /// The value of a required attribute (its presence was checked when the block was
    /// read; the error covers a mismatch between the tables and the code).
    fn required(&self, attribute: &'static str) -> Result<&Value<'a>> {
        self.get(attribute).ok_or_else(|| {
            self.pos.error(SceneErrorKind::MissingAttribute {
                entity: self.entity.keyword(),
                attribute,
            })
        })
    }

    fn error(&self, kind: SceneErrorKind) -> SceneError {
        self.pos.error(kind)
    }
}

/// Builds a scene from the parsed pieces, in place (a scene can be kilobytes: on a chip
/// every copy of it is stack).
struct Parser<'a, 's, S> {
    lexer: Lexer<'a>,
    camera: Option<Camera<S>>,
    background: Option<Color<S>>,
    epsilon: Option<S>,
    /// The scene under construction (its camera is a placeholder until the end).
    scene: &'s mut Scene<S>,
    material_names: Vec<&'a str, MAX_MATERIALS>,
    /// Names of every entity but materials, with their kind, for the uniqueness rule.
    names: Vec<(Entity, &'a str), { MAX_LIGHTS + MAX_OBJECTS + 1 }>,
}

type Result<T> = core::result::Result<T, SceneError>;

impl<'a, S: Scalar> Parser<'a, '_, S> {
    fn expect(&mut self, what: &'static str) -> Result<Token<'a>> {
        let end = self.lexer.pos;
        self.lexer
            .next_token()
            .ok_or_else(|| end.error(SceneErrorKind::UnexpectedEnd(what)))
    }

    fn number(&mut self) -> Result<Number<'a>> {
        let t = self.expect("a number")?;
        match Decimal::parse(t.text) {
            Some(value) => Ok(Number {
                value,
                pos: t.pos,
                text: t.text,
            }),
            None => Err(t.pos.error(SceneErrorKind::ExpectedNumber(quote(t.text)))),
        }
    }

    fn name(&mut self) -> Result<Token<'a>> {
        let t = self.expect("a name")?;
        if is_name(t.text) {
            Ok(t)
        } else {
            Err(t.pos.error(SceneErrorKind::ExpectedName(quote(t.text))))
        }
    }

    fn block(&mut self, entity: Entity, pos: Pos) -> Result<Block<'a>> {
        let specs = entity.attributes();
        let name = self.name()?;
        let open = self.expect("`{`")?;
        if open.text != "{" {
            return Err(open
                .pos
                .error(SceneErrorKind::ExpectedOpenBrace(quote(open.text))));
        }
        let mut values: [Option<Value<'a>>; MAX_ATTRS] = [None; MAX_ATTRS];
        loop {
            let t = self.expect("an attribute or `}`")?;
            if t.text == "}" {
                break;
            }
            let Some(i) = specs.iter().position(|s| s.name == t.text) else {
                return Err(t.pos.error(SceneErrorKind::UnknownAttribute {
                    entity: entity.keyword(),
                    found: quote(t.text),
                }));
            };
            if values[i].is_some() {
                return Err(t
                    .pos
                    .error(SceneErrorKind::DuplicateAttribute(specs[i].name)));
            }
            let mut v = Value {
                pos: t.pos,
                ..Value::default()
            };
            match specs[i].arity {
                Arity::Name => v.name = Some(self.name()?),
                Arity::Numbers(n) => {
                    for slot in v.nums.iter_mut().take(n) {
                        *slot = self.number()?;
                    }
                }
            }
            values[i] = Some(v);
        }
        for (spec, value) in specs.iter().zip(values.iter()) {
            if spec.required && value.is_none() {
                return Err(pos.error(SceneErrorKind::MissingAttribute {
                    entity: entity.keyword(),
                    attribute: spec.name,
                }));
            }
        }
        Ok(Block {
            entity,
            pos,
            name,
            values,
        })
    }

    /// Registers a name for the uniqueness rule (materials have their own list).
    fn register(&mut self, block: &Block<'a>) -> Result<()> {
        let name = block.name.text;
        if self
            .names
            .iter()
            .any(|&(e, n)| e == block.entity && n == name)
        {
            return Err(block.name.pos.error(SceneErrorKind::DuplicateName {
                entity: block.entity.keyword(),
                name: quote(name),
            }));
        }
        // Every light and object is stored or refused by its own capacity before this
        // list could fill; the error is the same either way.
        self.names.push((block.entity, name)).map_err(|_| {
            block.error(SceneErrorKind::TooMany {
                what: "named entities",
                capacity: MAX_LIGHTS + MAX_OBJECTS + 1,
            })
        })
    }

    fn material_index(&self, block: &Block<'a>, attribute: &'static str) -> Result<u8> {
        let name = block
            .required(attribute)?
            .name
            .ok_or_else(|| block.error(SceneErrorKind::ExpectedName(quote(attribute))))?;
        self.material_names
            .iter()
            .position(|n| *n == name.text)
            .and_then(|i| u8::try_from(i).ok())
            .ok_or_else(|| {
                name.pos
                    .error(SceneErrorKind::UnknownMaterial(quote(name.text)))
            })
    }

    fn parse(mut self) -> Result<()> {
        while let Some(t) = self.lexer.next_token() {
            match t.text {
                "background" => {
                    let mut nums = [Number::default(); 3];
                    for n in &mut nums {
                        *n = self.number()?;
                    }
                    let c = channel_colour(&nums, "background")?;
                    if self.background.replace(c).is_some() {
                        return Err(t.pos.error(SceneErrorKind::Duplicate("background")));
                    }
                }
                "precision" => {
                    let eps = precision::<S>(&self.number()?)?;
                    if self.epsilon.replace(eps).is_some() {
                        return Err(t.pos.error(SceneErrorKind::Duplicate("precision")));
                    }
                }
                _ => {
                    let Some(entity) = Entity::ALL.into_iter().find(|e| e.keyword() == t.text)
                    else {
                        return Err(t.pos.error(SceneErrorKind::UnknownKeyword(quote(t.text))));
                    };
                    let block = self.block(entity, t.pos)?;
                    self.entity(&block)?;
                }
            }
        }
        let camera = self
            .camera
            .ok_or_else(|| self.lexer.pos.error(SceneErrorKind::MissingCamera))?;
        self.scene.camera = camera;
        self.scene.background = self.background.unwrap_or([S::ZERO; 3]);
        self.scene.epsilon = self.epsilon.unwrap_or(S::DEFAULT_EPSILON);
        self.scene.replan();
        Ok(())
    }

    fn entity(&mut self, b: &Block<'a>) -> Result<()> {
        match b.entity {
            Entity::Camera => {
                if self.camera.is_some() {
                    return Err(b.error(SceneErrorKind::Duplicate("camera")));
                }
                self.camera = Some(camera(b)?);
            }
            Entity::Material => {
                if self.material_names.contains(&b.name.text) {
                    return Err(b.name.pos.error(SceneErrorKind::DuplicateName {
                        entity: "material",
                        name: quote(b.name.text),
                    }));
                }
                let full = || {
                    b.error(SceneErrorKind::TooMany {
                        what: "materials",
                        capacity: MAX_MATERIALS,
                    })
                };
                // Both lists have the same capacity and length: check once, push both.
                if self.scene.materials.is_full() {
                    return Err(full());
                }
                self.scene
                    .materials
                    .push(material_of(b)?)
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
                let cone = if b.entity == Entity::Spotlight {
                    Some(cone::<S>(b, location)?)
                } else {
                    None
                };
                let light = Light {
                    location,
                    emissivity: non_negative3(b.required("emissivity")?, "emissivity")?,
                    cone,
                };
                self.scene.lights.push(light).map_err(|_| {
                    b.error(SceneErrorKind::TooMany {
                        what: "lights",
                        capacity: MAX_LIGHTS,
                    })
                })?;
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
                let center = vector::<S>(b.required("center")?)?;
                let radius = positive::<S>(&b.required("radius")?.nums[0], "radius")?;
                let sphere = Sphere::new(center, radius).map_err(|_| {
                    b.error(SceneErrorKind::DerivedDoesNotFit {
                        what: "the sphere's radius²",
                        format: S::NAME,
                    })
                })?;
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
                let xdir = b.required("xdir")?;
                let d = b.required(dims)?;
                let size = [
                    positive::<S>(&d.nums[0], dims)?,
                    positive::<S>(&d.nums[1], dims)?,
                ];
                let frame = PlaneFrame::new(vector(normal)?, vector(b.required("point")?)?, vector(xdir)?, size)
                    .map_err(|e| match e {
                        FrameError::Plane(e) => plane_error::<S>(b, normal, e),
                        FrameError::XdirInvalid | FrameError::NonPositiveSize => {
                            xdir.pos.error(SceneErrorKind::OutOfDomain {
                                attribute: "xdir",
                                rule: "a direction with a component in the plane (not along the normal)",
                            })
                        }
                    })?;
                let shape = if b.entity == Entity::FPlane {
                    Shape::Finite(frame)
                } else {
                    Shape::Tiled {
                        frame,
                        alt: self.material_index(b, "altmaterial")?,
                    }
                };
                self.push(b, shape, material)?;
            }
        }
        Ok(())
    }

    fn push(&mut self, b: &Block<'a>, shape: Shape<S>, material: u8) -> Result<()> {
        self.scene
            .objects
            .push(crate::Object { shape, material })
            .map_err(|_| {
                b.error(SceneErrorKind::TooMany {
                    what: "objects",
                    capacity: MAX_OBJECTS,
                })
            })
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

/// Converts a number into the format, times `scale` (exact, in decimal).
fn convert<S: Scalar>(n: &Number<'_>, scale: u64) -> Result<S> {
    S::from_decimal(n.value.times(scale)).ok_or_else(|| {
        n.pos.error(SceneErrorKind::DoesNotFit {
            value: quote(n.text),
            format: S::NAME,
        })
    })
}

fn vector<S: Scalar>(v: &Value<'_>) -> Result<Vec3<S>> {
    Ok(Vec3::new(
        convert(&v.nums[0], 1)?,
        convert(&v.nums[1], 1)?,
        convert(&v.nums[2], 1)?,
    ))
}

/// `> 0`.
fn positive_value(d: &Decimal) -> bool {
    !d.negative && !d.is_zero()
}

/// `>= 0` (`-0` included).
fn non_negative_value(d: &Decimal) -> bool {
    !d.negative || d.is_zero()
}

fn in_domain(
    n: &Number<'_>,
    ok: impl Fn(&Decimal) -> bool,
    attribute: &'static str,
    rule: &'static str,
) -> Result<()> {
    if ok(&n.value) {
        Ok(())
    } else {
        Err(n.pos.error(SceneErrorKind::OutOfDomain { attribute, rule }))
    }
}

/// A number that must be > 0 and stay > 0 in the format.
fn positive<S: Scalar>(n: &Number<'_>, attribute: &'static str) -> Result<S> {
    in_domain(n, positive_value, attribute, "> 0")?;
    let x = convert::<S>(n, 1)?;
    if x > S::ZERO {
        Ok(x)
    } else {
        Err(n.pos.error(SceneErrorKind::OutOfDomain {
            attribute,
            rule: "> 0 (it rounds to 0 in this number format)",
        }))
    }
}

/// Three reals ≥ 0.
fn non_negative3<S: Scalar>(v: &Value<'_>, attribute: &'static str) -> Result<[S; 3]> {
    let mut c = [S::ZERO; 3];
    for (ck, n) in c.iter_mut().zip(&v.nums) {
        in_domain(n, non_negative_value, attribute, ">= 0")?;
        *ck = convert(n, 1)?;
    }
    Ok(c)
}

/// A displayed colour (ambient, background) in channel units: 255 × the value, computed
/// exactly in decimal. The value itself must fit the format; if 255 × it does not, it
/// saturates at the format's maximum, which displays as 255 exactly like the value would.
fn channel_colour<S: Scalar>(nums: &[Number<'_>; 3], attribute: &'static str) -> Result<Color<S>> {
    let mut c = [S::ZERO; 3];
    for (ck, n) in c.iter_mut().zip(nums) {
        in_domain(n, non_negative_value, attribute, ">= 0")?;
        convert::<S>(n, 1)?;
        *ck = convert(n, 255).unwrap_or(S::MAX);
    }
    Ok(c)
}

fn camera<S: Scalar>(b: &Block<'_>) -> Result<Camera<S>> {
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
    Ok(Camera {
        width: dims[0],
        height: dims[1],
        world_width: positive(&worlddim.nums[0], "worlddim")?,
        world_height: positive(&worlddim.nums[1], "worlddim")?,
        viewpoint: Vec3::new(eye.x, eye.y, positive(&viewpoint.nums[2], "viewpoint")?),
    })
}

fn material_of<S: Scalar>(b: &Block<'_>) -> Result<Material<S>> {
    let mut m = Material::new();
    if let Some(v) = b.get("ambient") {
        m.ambient = channel_colour(&v.nums, "ambient")?;
    }
    if let Some(v) = b.get("diffuse") {
        m.diffuse = non_negative3(v, "diffuse")?;
    }
    if let Some(v) = b.get("specular") {
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
        let ok = |d: &Decimal| d.cmp_int(1) != Ordering::Less;
        in_domain(&v.nums[0], ok, "shininess", ">= 1")?;
        m.shininess = convert(&v.nums[0], 1)?;
    }
    if let Some(v) = b.get("reflective") {
        let ok = |d: &Decimal| non_negative_value(d) && d.cmp_int(1) != Ordering::Greater;
        in_domain(&v.nums[0], ok, "reflective", "in [0, 1]")?;
        m.reflective = convert(&v.nums[0], 1)?;
        if m.reflective > S::ZERO && !cfg!(feature = "reflection") {
            return Err(v.pos.error(SceneErrorKind::NotBuiltIn {
                what: "reflective materials are",
                feature: "reflection",
            }));
        }
    }
    Ok(m)
}

/// The precision epsilon: a real > 0 that must stay > 0 in the format.
fn precision<S: Scalar>(n: &Number<'_>) -> Result<S> {
    in_domain(n, positive_value, "precision", "> 0")?;
    let eps = convert::<S>(n, 1)?;
    if eps > S::ZERO {
        Ok(eps)
    } else {
        Err(n.pos.error(SceneErrorKind::OutOfDomain {
            attribute: "precision",
            rule: "at least the number format's resolution (it rounds to 0)",
        }))
    }
}

fn placeholder_camera<S: Scalar>() -> Camera<S> {
    Camera {
        width: 1,
        height: 1,
        world_width: S::ONE,
        world_height: S::ONE,
        viewpoint: Vec3::new(S::ZERO, S::ZERO, S::ONE),
    }
}

impl<S: Scalar> Scene<S> {
    /// Reads a scene in the keyword-block format of `scene-format.md`.
    ///
    /// # Errors
    /// A [`SceneError`] with the line and column of the first problem.
    pub fn parse(text: &str) -> core::result::Result<Self, SceneError> {
        let mut scene = Scene::empty();
        scene.read(text)?;
        Ok(scene)
    }

    /// A scene with nothing in it and a 1×1 placeholder camera, to [`Scene::read`] into.
    pub fn empty() -> Self {
        Scene::new(placeholder_camera())
    }

    /// Empties the scene in place (no temporary scene on the stack).
    pub fn clear(&mut self) {
        self.camera = placeholder_camera();
        self.materials.clear();
        self.lights.clear();
        self.objects.clear();
        self.background = [S::ZERO; 3];
        self.epsilon = S::DEFAULT_EPSILON;
        self.plan = crate::Plan::default();
    }

    /// Reads a scene text into `self`, in place: [`Scene::parse`] without moving the scene
    /// (a `Scene<I32F32>` is 6 KB; on a chip with 16 KB of RAM every copy counts).
    ///
    /// # Errors
    /// A [`SceneError`] with the line and column of the first problem; the scene is then
    /// left empty.
    ///
    /// ```
    /// use fixray::{Scene, I16F16};
    ///
    /// let mut scene = Scene::<I16F16>::empty();
    /// scene.read("camera c { pixeldim 4 3 worlddim 4 3 viewpoint 2 1.5 5 }").unwrap();
    /// assert_eq!(scene.camera.width, 4);
    /// ```
    #[inline(never)]
    pub fn read(&mut self, text: &str) -> core::result::Result<(), SceneError> {
        self.clear();
        let result = Parser {
            lexer: Lexer::new(text),
            camera: None,
            background: None,
            epsilon: None,
            scene: self,
            material_names: Vec::new(),
            names: Vec::new(),
        }
        .parse();
        if result.is_err() {
            self.clear();
        }
        result
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_follow_the_format_syntax() {
        for ok in ["a", "_x", "floor_2", "Z9"] {
            assert!(is_name(ok), "{ok}");
        }
        for bad in ["", "2a", "a-b", "é", "{"] {
            assert!(!is_name(bad), "{bad}");
        }
    }

    #[test]
    fn braces_split_from_words_and_comments_end_at_newline() {
        let mut lx = Lexer::new("plane floor{ # note {\n x}");
        let toks: [&str; 5] = core::array::from_fn(|_| lx.next_token().map_or("", |t| t.text));
        assert_eq!(toks, ["plane", "floor", "{", "x", "}"]);
        let mut lx = Lexer::new("a\n  bb");
        lx.next_token();
        assert_eq!(
            lx.next_token().map(|t| t.pos),
            Some(Pos { line: 2, column: 3 })
        );
    }

    #[test]
    fn long_tokens_are_cut_in_messages() {
        let q = quote("abcdefghijklmnopqrstuvwxyz0123456789");
        assert!(q.ends_with('…'));
        assert!(q.len() <= MAX_QUOTED);
    }
}
