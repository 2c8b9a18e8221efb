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
use crate::scene::{MAX_LIGHTS, MAX_MATERIALS, MAX_OBJECTS, MAX_PIXELDIM};
use crate::{Camera, Color, Light, Material, Plane, PlaneError, Scalar, Scene, Vec3};

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
        /// It is a colour, which is stored × 255 (in channel units).
        colour: bool,
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
    /// A valid entity or attribute that the renderer cannot draw yet.
    NotSupported(&'static str),
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
            K::DoesNotFit {
                value,
                format,
                colour,
            } => {
                write!(f, "`{value}` does not fit in the {format} number format")?;
                if *colour {
                    write!(f, " (colours are stored × 255, in channel units)")?;
                }
                Ok(())
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
            K::NotSupported(what) => write!(f, "{what} not supported yet"),
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
        self.rest = &self.rest[c.len_utf8()..];
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
            text: &start[..len],
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

const fn attr(name: &'static str, n: usize) -> AttrSpec {
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

/// The entity kinds and their attributes, as `scene-format.md` lists them.
const ENTITIES: [(&str, &[AttrSpec]); 8] = [
    (
        "camera",
        &[
            attr("pixeldim", 2),
            attr("worlddim", 2),
            attr("viewpoint", 3),
        ],
    ),
    (
        "material",
        &[
            optional("ambient", 3),
            optional("diffuse", 3),
            optional("specular", 1),
            optional("shininess", 1),
            optional("reflective", 1),
        ],
    ),
    ("light", &[attr("location", 3), attr("emissivity", 3)]),
    (
        "spotlight",
        &[
            attr("location", 3),
            attr("emissivity", 3),
            attr("point", 3),
            attr("theta", 1),
        ],
    ),
    (
        "plane",
        &[material("material"), attr("normal", 3), attr("point", 3)],
    ),
    (
        "sphere",
        &[material("material"), attr("center", 3), attr("radius", 1)],
    ),
    (
        "tiled_plane",
        &[
            material("material"),
            material("altmaterial"),
            attr("normal", 3),
            attr("point", 3),
            attr("xdir", 3),
            attr("dimension", 2),
        ],
    ),
    (
        "fplane",
        &[
            material("material"),
            attr("normal", 3),
            attr("point", 3),
            attr("xdir", 3),
            attr("dimensions", 2),
        ],
    ),
];

/// One attribute's value as written: up to three numbers or a name, with positions.
#[derive(Debug, Clone, Copy, Default)]
struct Value<'a> {
    name_pos: Pos,
    nums: [Decimal; 3],
    pos: [Pos; 3],
    /// The numbers as written, for messages.
    texts: [&'a str; 3],
    name: &'a str,
}

/// A parsed block: its keyword, name and attribute values (indexed like its specs).
struct Block<'a> {
    entity: &'static str,
    pos: Pos,
    name: Token<'a>,
    values: [Option<Value<'a>>; MAX_ATTRS],
}

impl<'a> Block<'a> {
    fn specs(&self) -> &'static [AttrSpec] {
        ENTITIES
            .iter()
            .find(|(e, _)| *e == self.entity)
            .map_or(&[], |(_, s)| *s)
    }

    /// The value of an attribute; `None` when it is optional and absent.
    fn get(&self, attribute: &'static str) -> Option<&Value<'a>> {
        let i = self.specs().iter().position(|s| s.name == attribute)?;
        self.values.get(i)?.as_ref()
    }
}

/// Builds a scene from the parsed pieces.
struct Parser<'a, S> {
    lexer: Lexer<'a>,
    /// Position of the last token read (for end-of-input errors).
    last: Pos,
    camera: Option<Camera<S>>,
    scene_background: Option<Color<S>>,
    scene_epsilon: Option<S>,
    materials: Vec<Material<S>, MAX_MATERIALS>,
    material_names: Vec<&'a str, MAX_MATERIALS>,
    /// Names of every other entity, with their keyword, for the uniqueness rule.
    names: Vec<(&'static str, &'a str), { MAX_LIGHTS + MAX_OBJECTS + 1 }>,
    lights: Vec<Light<S>, MAX_LIGHTS>,
    objects: Vec<crate::Object<S>, MAX_OBJECTS>,
}

type Result<T> = core::result::Result<T, SceneError>;

impl<'a, S: Scalar> Parser<'a, S> {
    fn next(&mut self) -> Option<Token<'a>> {
        let t = self.lexer.next_token()?;
        self.last = t.pos;
        Some(t)
    }

    fn expect(&mut self, what: &'static str) -> Result<Token<'a>> {
        self.next()
            .ok_or_else(|| self.end_pos().error(SceneErrorKind::UnexpectedEnd(what)))
    }

    fn end_pos(&self) -> Pos {
        self.lexer.pos
    }

    fn number(&mut self) -> Result<(Decimal, Token<'a>)> {
        let t = self.expect("a number")?;
        match Decimal::parse(t.text) {
            Some(d) => Ok((d, t)),
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

    fn block(
        &mut self,
        entity: &'static str,
        specs: &'static [AttrSpec],
        pos: Pos,
    ) -> Result<Block<'a>> {
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
                    entity,
                    found: quote(t.text),
                }));
            };
            if values[i].is_some() {
                return Err(t
                    .pos
                    .error(SceneErrorKind::DuplicateAttribute(specs[i].name)));
            }
            let mut v = Value {
                name_pos: t.pos,
                ..Value::default()
            };
            match specs[i].arity {
                Arity::Name => {
                    let n = self.name()?;
                    v.name = n.text;
                    v.pos[0] = n.pos;
                }
                Arity::Numbers(n) => {
                    for k in 0..n {
                        let (x, t) = self.number()?;
                        (v.nums[k], v.pos[k], v.texts[k]) = (x, t.pos, t.text);
                    }
                }
            }
            values[i] = Some(v);
        }
        for (spec, value) in specs.iter().zip(values.iter()) {
            if spec.required && value.is_none() {
                return Err(pos.error(SceneErrorKind::MissingAttribute {
                    entity,
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
        let dup = self
            .names
            .iter()
            .any(|(e, n)| *e == block.entity && *n == block.name.text);
        if dup {
            return Err(block.name.pos.error(SceneErrorKind::DuplicateName {
                entity: block.entity,
                name: quote(block.name.text),
            }));
        }
        // Capacity: every entity is stored or refused before this list could fill.
        self.names
            .push((block.entity, block.name.text))
            .map_err(|_| {
                block.pos.error(SceneErrorKind::TooMany {
                    what: "named entities",
                    capacity: MAX_LIGHTS + MAX_OBJECTS + 1,
                })
            })
    }

    fn material_index(&self, block: &Block<'a>, attribute: &'static str) -> Result<u8> {
        let Some(v) = block.get(attribute) else {
            return Err(block.pos.error(SceneErrorKind::MissingAttribute {
                entity: block.entity,
                attribute,
            }));
        };
        self.material_names
            .iter()
            .position(|n| *n == v.name)
            .and_then(|i| u8::try_from(i).ok())
            .ok_or_else(|| v.pos[0].error(SceneErrorKind::UnknownMaterial(quote(v.name))))
    }

    fn parse(mut self) -> Result<Scene<S>> {
        while let Some(t) = self.next() {
            match t.text {
                "background" => {
                    let c = self.color_values(t.pos, "background")?;
                    if self.scene_background.replace(c).is_some() {
                        return Err(t.pos.error(SceneErrorKind::Duplicate("background")));
                    }
                }
                "precision" => {
                    let (v, token) = self.number()?;
                    let eps = precision::<S>(v, token)?;
                    if self.scene_epsilon.replace(eps).is_some() {
                        return Err(t.pos.error(SceneErrorKind::Duplicate("precision")));
                    }
                }
                _ => {
                    let Some((entity, specs)) = ENTITIES.iter().find(|(e, _)| *e == t.text) else {
                        return Err(t.pos.error(SceneErrorKind::UnknownKeyword(quote(t.text))));
                    };
                    let block = self.block(entity, specs, t.pos)?;
                    self.entity(&block)?;
                }
            }
        }
        let camera = self
            .camera
            .ok_or_else(|| self.end_pos().error(SceneErrorKind::MissingCamera))?;
        Ok(Scene {
            camera,
            materials: self.materials,
            lights: self.lights,
            objects: self.objects,
            background: self.scene_background.unwrap_or([S::ZERO; 3]),
            epsilon: self.scene_epsilon.unwrap_or(S::DEFAULT_EPSILON),
        })
    }

    /// Reads three colour numbers after a bare keyword (`background R G B`).
    fn color_values(&mut self, pos: Pos, attribute: &'static str) -> Result<Color<S>> {
        let mut v = Value {
            name_pos: pos,
            ..Value::default()
        };
        for k in 0..3 {
            let (x, t) = self.number()?;
            (v.nums[k], v.pos[k], v.texts[k]) = (x, t.pos, t.text);
        }
        color(&v, attribute)
    }

    fn entity(&mut self, b: &Block<'a>) -> Result<()> {
        let not_supported = |what| Err(b.pos.error(SceneErrorKind::NotSupported(what)));
        match b.entity {
            "camera" => {
                if self.camera.is_some() {
                    return Err(b.pos.error(SceneErrorKind::Duplicate("camera")));
                }
                self.camera = Some(camera(b)?);
            }
            "material" => {
                if self.material_names.contains(&b.name.text) {
                    return Err(b.name.pos.error(SceneErrorKind::DuplicateName {
                        entity: "material",
                        name: quote(b.name.text),
                    }));
                }
                let full = || {
                    b.pos.error(SceneErrorKind::TooMany {
                        what: "materials",
                        capacity: MAX_MATERIALS,
                    })
                };
                // Both lists have the same capacity and length: check once, push both.
                if self.materials.is_full() {
                    return Err(full());
                }
                self.materials.push(material_of(b)?).map_err(|_| full())?;
                self.material_names.push(b.name.text).map_err(|_| full())?;
            }
            "light" => {
                self.register(b)?;
                let light = Light {
                    location: vector(required(b, "location")?)?,
                    emissivity: non_negative3(required(b, "emissivity")?, "emissivity", 1)?,
                };
                self.lights.push(light).map_err(|_| {
                    b.pos.error(SceneErrorKind::TooMany {
                        what: "lights",
                        capacity: MAX_LIGHTS,
                    })
                })?;
            }
            "plane" => {
                self.register(b)?;
                let material = self.material_index(b, "material")?;
                let normal = required(b, "normal")?;
                let plane = Plane::new(vector(normal)?, vector(required(b, "point")?)?).map_err(
                    |e| match e {
                        PlaneError::ZeroNormal => normal.name_pos.error(SceneErrorKind::ZeroNormal),
                        PlaneError::OffsetOutOfRange => {
                            b.pos.error(SceneErrorKind::DerivedDoesNotFit {
                                what: "the plane's offset N·point",
                                format: S::NAME,
                            })
                        }
                    },
                )?;
                self.objects
                    .push(crate::Object {
                        shape: crate::Shape::Plane(plane),
                        material,
                    })
                    .map_err(|_| {
                        b.pos.error(SceneErrorKind::TooMany {
                            what: "objects",
                            capacity: MAX_OBJECTS,
                        })
                    })?;
            }
            // The entities below are checked completely, then refused: the renderer
            // does not draw them yet.
            "spotlight" => {
                self.register(b)?;
                vector::<S>(required(b, "location")?)?;
                non_negative3::<S>(required(b, "emissivity")?, "emissivity", 1)?;
                vector::<S>(required(b, "point")?)?;
                let theta = required(b, "theta")?;
                let ok = |d: &Decimal| positive_value(d) && d.cmp_int(90) != Ordering::Greater;
                in_domain(theta, 0, ok, "theta", "in (0, 90]")?;
                return not_supported("spotlight is");
            }
            "sphere" => {
                self.register(b)?;
                self.material_index(b, "material")?;
                vector::<S>(required(b, "center")?)?;
                positive::<S>(required(b, "radius")?, 0, "radius")?;
                return not_supported("sphere is");
            }
            "tiled_plane" | "fplane" => {
                self.register(b)?;
                self.material_index(b, "material")?;
                let (dims, what) = if b.entity == "fplane" {
                    ("dimensions", "fplane is")
                } else {
                    self.material_index(b, "altmaterial")?;
                    ("dimension", "tiled_plane is")
                };
                let normal = required(b, "normal")?;
                if vector::<S>(normal)?.unit().is_none() {
                    return Err(normal.name_pos.error(SceneErrorKind::ZeroNormal));
                }
                vector::<S>(required(b, "point")?)?;
                vector::<S>(required(b, "xdir")?)?;
                let d = required(b, dims)?;
                positive::<S>(d, 0, dims)?;
                positive::<S>(d, 1, dims)?;
                return not_supported(what);
            }
            _ => {}
        }
        Ok(())
    }
}

fn required<'v, 'a>(b: &'v Block<'a>, attribute: &'static str) -> Result<&'v Value<'a>> {
    b.get(attribute).ok_or_else(|| {
        b.pos.error(SceneErrorKind::MissingAttribute {
            entity: b.entity,
            attribute,
        })
    })
}

/// Converts one number of a value into the format.
fn convert<S: Scalar>(v: &Value<'_>, k: usize, scale: u64) -> Result<S> {
    S::from_decimal(v.nums[k].times(scale)).ok_or_else(|| {
        v.pos[k].error(SceneErrorKind::DoesNotFit {
            value: quote(v.texts[k]),
            format: S::NAME,
            colour: scale != 1,
        })
    })
}

fn vector<S: Scalar>(v: &Value<'_>) -> Result<Vec3<S>> {
    Ok(Vec3::new(
        convert(v, 0, 1)?,
        convert(v, 1, 1)?,
        convert(v, 2, 1)?,
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
    v: &Value<'_>,
    k: usize,
    ok: impl Fn(&Decimal) -> bool,
    attribute: &'static str,
    rule: &'static str,
) -> Result<()> {
    if ok(&v.nums[k]) {
        Ok(())
    } else {
        Err(v.pos[k].error(SceneErrorKind::OutOfDomain { attribute, rule }))
    }
}

/// A number that must be > 0 and stay > 0 in the format.
fn positive<S: Scalar>(v: &Value<'_>, k: usize, attribute: &'static str) -> Result<S> {
    in_domain(v, k, positive_value, attribute, "> 0")?;
    let x = convert::<S>(v, k, 1)?;
    if x > S::ZERO {
        Ok(x)
    } else {
        Err(v.pos[k].error(SceneErrorKind::OutOfDomain {
            attribute,
            rule: "> 0 (it rounds to 0 in this number format)",
        }))
    }
}

/// Three reals ≥ 0, multiplied by `scale` (255 for colours in channel units).
fn non_negative3<S: Scalar>(
    v: &Value<'_>,
    attribute: &'static str,
    scale: u64,
) -> Result<Color<S>> {
    let mut c = [S::ZERO; 3];
    for (k, ck) in c.iter_mut().enumerate() {
        in_domain(v, k, non_negative_value, attribute, ">= 0")?;
        *ck = convert(v, k, scale)?;
    }
    Ok(c)
}

/// A colour in channel units.
fn color<S: Scalar>(v: &Value<'_>, attribute: &'static str) -> Result<Color<S>> {
    non_negative3(v, attribute, 255)
}

fn camera<S: Scalar>(b: &Block<'_>) -> Result<Camera<S>> {
    let pixeldim = required(b, "pixeldim")?;
    let mut dims = [0u16; 2];
    for (k, d) in dims.iter_mut().enumerate() {
        let value = pixeldim.nums[k]
            .to_integer()
            .and_then(|i| u16::try_from(i).ok())
            .filter(|i| (1..=MAX_PIXELDIM).contains(i));
        let Some(value) = value else {
            return Err(pixeldim.pos[k].error(SceneErrorKind::OutOfDomain {
                attribute: "pixeldim",
                rule: "integers in 1..=4096",
            }));
        };
        *d = value;
    }
    let worlddim = required(b, "worlddim")?;
    let viewpoint = required(b, "viewpoint")?;
    let eye = vector::<S>(viewpoint)?;
    in_domain(viewpoint, 2, positive_value, "viewpoint", "at z > 0")?;
    Ok(Camera {
        width: dims[0],
        height: dims[1],
        world_width: positive(worlddim, 0, "worlddim")?,
        world_height: positive(worlddim, 1, "worlddim")?,
        viewpoint: Vec3::new(eye.x, eye.y, positive(viewpoint, 2, "viewpoint")?),
    })
}

fn material_of<S: Scalar>(b: &Block<'_>) -> Result<Material<S>> {
    let zero = [S::ZERO; 3];
    let ambient = b.get("ambient").map(|v| color(v, "ambient")).transpose()?;
    let diffuse = b.get("diffuse").map(|v| color(v, "diffuse")).transpose()?;
    if let Some(v) = b.get("specular") {
        in_domain(v, 0, non_negative_value, "specular", ">= 0")?;
        if !v.nums[0].is_zero() {
            return Err(v
                .name_pos
                .error(SceneErrorKind::NotSupported("specular is")));
        }
    }
    if let Some(v) = b.get("shininess") {
        // Shininess only shapes a specular glint; without specular it changes nothing.
        let ok = |d: &Decimal| d.cmp_int(1) != Ordering::Less;
        in_domain(v, 0, ok, "shininess", ">= 1")?;
    }
    if let Some(v) = b.get("reflective") {
        in_domain(
            v,
            0,
            |d| non_negative_value(d) && d.cmp_int(1) != Ordering::Greater,
            "reflective",
            "in [0, 1]",
        )?;
        if !v.nums[0].is_zero() {
            return Err(v
                .name_pos
                .error(SceneErrorKind::NotSupported("reflective material is")));
        }
    }
    Ok(Material {
        ambient: ambient.unwrap_or(zero),
        diffuse: diffuse.unwrap_or(zero),
    })
}

/// The precision epsilon: a real > 0 that must stay > 0 in the format.
fn precision<S: Scalar>(value: Decimal, token: Token<'_>) -> Result<S> {
    let pos = token.pos;
    let v = Value {
        nums: [value; 3],
        pos: [pos; 3],
        texts: [token.text; 3],
        ..Value::default()
    };
    in_domain(&v, 0, positive_value, "precision", "> 0")?;
    let eps = convert::<S>(&v, 0, 1)?;
    if eps > S::ZERO {
        Ok(eps)
    } else {
        Err(pos.error(SceneErrorKind::OutOfDomain {
            attribute: "precision",
            rule: "at least the number format's resolution (it rounds to 0)",
        }))
    }
}

impl<S: Scalar> Scene<S> {
    /// Reads a scene in the keyword-block format of `scene-format.md`.
    ///
    /// # Errors
    /// A [`SceneError`] with the line and column of the first problem.
    pub fn parse(text: &str) -> core::result::Result<Self, SceneError> {
        Parser {
            lexer: Lexer::new(text),
            last: Pos::default(),
            camera: None,
            scene_background: None,
            scene_epsilon: None,
            materials: Vec::new(),
            material_names: Vec::new(),
            names: Vec::new(),
            lights: Vec::new(),
            objects: Vec::new(),
        }
        .parse()
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
