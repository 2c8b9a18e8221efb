//! [`SceneError`]: what is wrong with a scene file, and where (line and column): the
//! error's kinds, the quantities and texture problems they name, and their messages.
//! What a message adds on a host (the nearest attribute, a format's range, the formats
//! that hold or resolve a number) is worked out in `hints.rs`.

use core::fmt;

use heapless::String;

use super::hints::{HINTS, beyond_range, derived, holders, nearest, write_decimal};
use super::schema::Entity;
use crate::num::Decimal;
use crate::scene::{MIN_RADIUS_SQ_DELTAS, MIN_SCALE_DELTAS};

/// Longest token quoted in an error message; longer ones are cut and end in `…`.
pub const MAX_QUOTED: usize = 24;

/// A token quoted in an error message (cut to [`MAX_QUOTED`] bytes).
///
/// ```
/// use fixray::scene::{MAX_QUOTED, Quoted, SceneErrorKind};
/// use fixray::{I16F16, Scene};
///
/// let err = Scene::<I16F16>::parse("spheres ball { }").unwrap_err();
/// let word = Quoted::try_from("spheres").unwrap();
/// assert_eq!(err.kind, SceneErrorKind::UnknownKeyword(word));
/// // A longer token is cut, and ends in `…`.
/// let err = Scene::<I16F16>::parse("a_very_long_word_that_goes_on_and_on { }").unwrap_err();
/// let SceneErrorKind::UnknownKeyword(word) = err.kind else { panic!("{err}") };
/// assert_eq!(word.as_str(), "a_very_long_word_that…");
/// assert!(word.len() <= MAX_QUOTED);
/// ```
pub type Quoted = String<MAX_QUOTED>;

/// Longest number a scale error keeps as written ([`SceneErrorKind::BelowResolution`],
/// [`SceneErrorKind::BeyondRange`]); longer ones are cut and end in `…` (and the message
/// then leaves out the hints that need the value). Shorter than [`MAX_QUOTED`]: an error
/// is returned through every frame of the parser, and its size is stack on a chip.
pub const MAX_NUMBER: usize = 20;

/// A number as a scale error keeps it (cut to [`MAX_NUMBER`] bytes).
///
/// ```
/// use fixray::scene::{QuotedNumber, SceneErrorKind};
/// use fixray::{I16F16, Scene};
///
/// let text = "camera c { pixeldim 4 3 worlddim 4 3 viewpoint 2 1.5 5 }
/// material red { ambient 1 0 0 }
/// sphere ball { material red center 0 0 -300 radius 200.0 }";
/// let err = Scene::<I16F16>::parse(text).unwrap_err();
/// let SceneErrorKind::BeyondRange { number, .. } = err.kind else { panic!("{err}") };
/// // As written: `200.0`, not `200`.
/// let written: QuotedNumber = number;
/// assert_eq!(written.as_str(), "200.0");
/// ```
pub type QuotedNumber = String<MAX_NUMBER>;

/// A scene file error at a line and column.
///
/// ```
/// use fixray::scene::SceneErrorKind;
/// use fixray::{I16F16, Scene, SceneError};
///
/// let text = "camera c { pixeldim 4 3 worlddim 4 3 viewpoint 2 1.5 5 }
/// material red { ambient 1 0 0 }
/// sphere ball { material blue center 0 0 -3 radius 1 }";
/// let err: SceneError = Scene::<I16F16>::parse(text).unwrap_err();
/// // Line 3, column 24: the word `blue`.
/// assert_eq!((err.line, err.column), (3, 24));
/// assert!(matches!(&err.kind, SceneErrorKind::UnknownMaterial(name) if name == "blue"));
/// assert_eq!(
///     err.to_string(),
///     "3:24: unknown material `blue` (a material must be defined before it is named)"
/// );
/// ```
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
///
/// ```
/// use fixray::scene::SceneErrorKind;
/// use fixray::{I16F16, Scene};
///
/// let camera = "camera c { pixeldim 4 3 worlddim 4 3 viewpoint 2 1.5 5 }\n";
/// // A misspelt attribute: the entity, the word, and the attribute it most likely meant.
/// let text = [camera, "material red { ambeint 1 0 0 }"].concat();
/// let err = Scene::<I16F16>::parse(&text).unwrap_err();
/// match &err.kind {
///     SceneErrorKind::UnknownAttribute { entity, found } => {
///         assert_eq!((*entity, found.as_str()), ("material", "ambeint"));
///     }
///     other => panic!("{other}"),
/// }
/// assert_eq!(err.kind.nearest(), Some("ambient"));
/// // The kind's message is the error's, without the line and column.
/// assert_eq!(err.to_string(), format!("2:16: {}", err.kind));
///
/// // A scene without a camera: the message shows one.
/// let err = Scene::<I16F16>::parse("material red { ambient 1 0 0 }").unwrap_err();
/// assert_eq!(err.kind, SceneErrorKind::MissingCamera);
/// assert!(err.kind.to_string().starts_with("no camera: add one, such as `camera cam {"));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub enum SceneErrorKind {
    /// A word where an entity keyword (`camera`, `plane`, ...) was expected.
    UnknownKeyword(Quoted),
    /// A word inside a block that is not one of the entity's attributes. The message lists
    /// the entity's attributes and names the one nearest to the word, if one is near
    /// enough ([`SceneErrorKind::nearest`]; not on bare metal).
    UnknownAttribute {
        /// The entity keyword.
        entity: &'static str,
        /// The word found.
        found: Quoted,
    },
    /// A block without its `}`: at the end of the input, or before the next statement
    /// (where an attribute or `}` was expected: a keyword of the format at the start of a
    /// line, or an entity keyword followed by a name and `{`). The error's position is the
    /// block's `{`, the brace that has no partner. Not looked for on bare metal (a chip's
    /// firmware reports the next statement's first word, or the end of the input).
    Unclosed {
        /// The block's keyword and name (`material red`).
        block: Quoted,
        /// The keyword that starts the next statement; `None` at the end of the input.
        next: Option<&'static str>,
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
    /// A number is outside what the chosen number format can hold. The message gives the
    /// format's range and the formats of [`MAIN`](crate::num::formats::MAIN) that hold
    /// the number (not on bare metal).
    DoesNotFit {
        /// The number as written.
        value: Quoted,
        /// The number format.
        format: &'static str,
    },
    /// A length the scene derives (a pixel's pitch, a radius or its square) below
    /// [`MIN_SCALE_DELTAS`] (a radius² in a fixed format: [`MIN_RADIUS_SQ_DELTAS`]) of the
    /// format's resolution at the scene's scale: a scene the format cannot draw
    /// ([`crate::scene::MIN_SCALE_DELTAS`] has the rule), at the number it is derived
    /// from. The message gives the length and the formats of
    /// [`MAIN`](crate::num::formats::MAIN) that resolve every scale of the scene
    /// (`formats`; not on bare metal).
    BelowResolution {
        /// What it is.
        quantity: Quantity,
        /// The number it is derived from, as written (a `worlddim`, a `radius`); empty on
        /// bare metal.
        number: QuotedNumber,
        /// What that number is divided by: the pixels across, for a pitch; 1 otherwise.
        pixels: u16,
        /// The formats of [`MAIN`](crate::num::formats::MAIN) (bit `i`: `MAIN[i]`) that
        /// resolve every pixel pitch and sphere of the scene as the scale rule asks, this
        /// length among them, as far as the scene was read (the error is returned once the
        /// parse is over, or at a later error): a format that resolves this pitch but not a
        /// sphere further on is not one. 0 on bare metal, where the error returns at once.
        formats: u8,
        /// The number format.
        format: &'static str,
    },
    /// A quantity the scene derives (a radius's square) beyond the format's range, at the
    /// number it is derived from. The message gives its value, the range and the formats
    /// of [`MAIN`](crate::num::formats::MAIN) that hold it (not on bare metal).
    BeyondRange {
        /// What it is.
        quantity: Quantity,
        /// The number it is derived from, as written (a `radius`); empty on bare metal.
        number: QuotedNumber,
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
    /// More entities of a kind than the scene's type holds.
    TooMany {
        /// The kind.
        what: &'static str,
        /// The capacity (the scene type's `OBJECTS`, `MATERIALS` or `LIGHTS`; by
        /// default [`MAX_OBJECTS`](crate::scene::MAX_OBJECTS),
        /// [`MAX_MATERIALS`](crate::scene::MAX_MATERIALS),
        /// [`MAX_LIGHTS`](crate::scene::MAX_LIGHTS)).
        capacity: usize,
        /// The const parameter of [`Scene`](crate::Scene) that sets it.
        parameter: &'static str,
    },
    /// More entities of a kind than every scene holds ([`MAX_TEXTURES`](crate::scene::MAX_TEXTURES),
    /// [`MAX_PROJECTORS`](crate::scene::MAX_PROJECTORS)).
    Full {
        /// The kind.
        what: &'static str,
        /// How many a scene holds.
        capacity: usize,
    },
    /// A texture file that cannot be had or read.
    TextureFile {
        /// The file name as written.
        file: Quoted,
        /// What is wrong with it.
        problem: TextureProblem,
    },
    /// A texture named before it was defined, or never.
    UnknownTexture(Quoted),
    /// `rules` names no rule set (`course` or `fixray`).
    UnknownRules(Quoted),
    /// An attribute that only the other rule set has (`reflective` is the crate's own;
    /// `specular R G B` the course's).
    OtherRules {
        /// The attribute.
        attribute: &'static str,
        /// The rule set that has it.
        rules: &'static str,
    },
    /// An entity or attribute of the course's format that this crate does not draw yet
    /// (`revsurf`).
    NotSupportedYet(&'static str),
    /// A valid entity or attribute whose stage this build leaves out (a firmware built
    /// without one of the cargo features `lighting`, `spheres`, `reflection`).
    NotBuiltIn {
        /// What the scene asks for.
        what: &'static str,
        /// The cargo feature that builds it in.
        feature: &'static str,
    },
}

/// A length a scene derives, whose scale the number format must resolve
/// ([`SceneErrorKind::BelowResolution`], [`SceneErrorKind::BeyondRange`]).
///
/// ```
/// use fixray::scene::{Quantity, SceneErrorKind};
/// use fixray::{I16F16, I32F32, Scene};
///
/// // A radius of 200: its square, 40000, is beyond I16F16's range (±32768).
/// let text = "camera c { pixeldim 4 3 worlddim 4 3 viewpoint 2 1.5 5 }
/// material red { ambient 1 0 0 }
/// sphere ball { material red center 0 0 -300 radius 200 }";
/// let err = Scene::<I16F16>::parse(text).unwrap_err();
/// match &err.kind {
///     SceneErrorKind::BeyondRange { quantity, number, .. } => {
///         assert_eq!((*quantity, number.as_str()), (Quantity::RadiusSq, "200"));
///     }
///     other => panic!("{other}"),
/// }
/// assert_eq!(Quantity::RadiusSq.to_string(), "radius²");
/// // I32F32 holds it.
/// assert!(Scene::<I32F32>::parse(text).is_ok());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// The camera's pixel pitch, `worlddim / pixeldim`, along either axis.
    PixelPitch,
    /// A sphere's radius.
    Radius,
    /// A sphere's radius squared (what its intersection test compares with).
    RadiusSq,
}

impl Quantity {
    /// What a message calls it.
    pub fn name(self) -> &'static str {
        match self {
            Quantity::PixelPitch => "pixel pitch",
            Quantity::Radius => "radius",
            Quantity::RadiusSq => "radius²",
        }
    }

    /// The least the scale rule asks of it, in ulps of the format: [`MIN_SCALE_DELTAS`],
    /// and [`MIN_RADIUS_SQ_DELTAS`] of a radius² (a fixed format's).
    pub(crate) fn min_deltas(self) -> i32 {
        match self {
            Quantity::PixelPitch | Quantity::Radius => MIN_SCALE_DELTAS,
            Quantity::RadiusSq => MIN_RADIUS_SQ_DELTAS,
        }
    }
}

impl fmt::Display for Quantity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// What is wrong with a texture file.
///
/// ```
/// # #[cfg(feature = "textures")] {
/// use fixray::ppm::PpmError;
/// use fixray::scene::{SceneErrorKind, TextureProblem};
/// use fixray::{I16F16, Scene};
///
/// let text = "camera c { pixeldim 4 3 worlddim 4 3 viewpoint 2 1.5 5 }
/// texture wall { filename wall.ppm }";
/// // `Scene::parse` reads no files: the file is not found.
/// let err = Scene::<I16F16>::parse(text).unwrap_err();
/// assert!(matches!(
///     err.kind,
///     SceneErrorKind::TextureFile { problem: TextureProblem::NotFound, .. }
/// ));
/// // A file that is not a binary PPM.
/// let mut scene = Scene::<I16F16>::empty();
/// let err = scene.read_with(text, None, &mut |_| Some(&b"P3 1 1 255 0 0 0"[..])).unwrap_err();
/// match &err.kind {
///     SceneErrorKind::TextureFile { file, problem } => {
///         assert_eq!(file.as_str(), "wall.ppm");
///         assert_eq!(*problem, TextureProblem::Ppm(PpmError::NotPpm));
///     }
///     other => panic!("{other}"),
/// }
/// assert_eq!((err.line, err.column), (2, 25));
/// # }
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TextureProblem {
    /// The file source has no such file ([`Scene::parse`](crate::Scene::parse) reads no
    /// files: see [`Scene::read_with`](crate::Scene::read_with)).
    NotFound,
    /// The file is not a well-formed binary PPM.
    Ppm(crate::ppm::PpmError),
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}: {}", self.line, self.column, self.kind)
    }
}

impl core::error::Error for SceneError {}

impl SceneErrorKind {
    /// The attribute an [`SceneErrorKind::UnknownAttribute`] most likely meant: the
    /// entity's attribute nearest to the word found, at most a third of its letters (at
    /// least one) added, dropped, changed or swapped with a neighbour. `None` for other
    /// kinds, for a word no attribute is that near, and on bare metal (a chip's firmware).
    ///
    /// ```
    /// use fixray::{I16F16, Scene};
    ///
    /// let text = "camera c { pixeldim 4 3 worlddim 4 3 viewpoint 2 1.5 5 pixeldims 4 3 }";
    /// let err = Scene::<I16F16>::parse(text).unwrap_err();
    /// assert_eq!(err.kind.nearest(), Some("pixeldim"));
    /// ```
    pub fn nearest(&self) -> Option<&'static str> {
        match self {
            SceneErrorKind::UnknownAttribute { entity, found } if HINTS => {
                // The word as it reads: without the escapes of invisible characters.
                let mut word = Quoted::new();
                let mut rest = found.as_str();
                while let Some(c) = rest.chars().next() {
                    rest = match rest.strip_prefix("\\u{").and_then(|r| r.split_once('}')) {
                        Some((_, after)) => after,
                        None => {
                            let _ = word.push(c);
                            rest.get(c.len_utf8()..).unwrap_or("")
                        }
                    };
                }
                let names = Entity::from_keyword(entity)?.attributes().iter();
                nearest(&word, names.map(|a| a.name))
            }
            _ => None,
        }
    }
}

impl fmt::Display for SceneErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use SceneErrorKind as K;
        match self {
            K::UnknownKeyword(w) => {
                write!(f, "unknown keyword `{w}` (expected ")?;
                let keywords = super::schema::keywords();
                let last = keywords.clone().count().saturating_sub(1);
                for (i, k) in keywords.enumerate() {
                    let sep = match i {
                        0 => "",
                        _ if i == last => " or ",
                        _ => ", ",
                    };
                    write!(f, "{sep}{k}")?;
                }
                write!(f, ")")
            }
            K::UnknownAttribute { entity, found } => {
                write!(f, "`{found}` is not an attribute of {entity}")?;
                if !HINTS {
                    return Ok(());
                }
                f.write_str(" (")?;
                if let Some(n) = self.nearest() {
                    write!(f, "did you mean `{n}`? ")?;
                }
                write!(f, "{entity} has: ")?;
                let names = Entity::from_keyword(entity).map_or(&[][..], Entity::attributes);
                for (i, a) in names.iter().enumerate() {
                    let sep = if i == 0 { "" } else { ", " };
                    write!(f, "{sep}{}", a.name)?;
                }
                f.write_str(")")
            }
            // Only ever made where the hints are (`Parser::unclosed`).
            K::Unclosed { .. } if !HINTS => Ok(()),
            K::Unclosed { block, next } => {
                write!(f, "`{block}` is not closed: missing `}}`")?;
                match next {
                    Some(keyword) => write!(f, " before `{keyword}`"),
                    None => Ok(()),
                }
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
                write!(f, "`{value}` does not fit {format}")?;
                if HINTS {
                    beyond_range(f, format, Decimal::parse(value))?;
                }
                Ok(())
            }
            K::BelowResolution {
                quantity,
                number,
                pixels,
                formats,
                format,
            } => {
                f.write_str(quantity.name())?;
                if let Some(v) = derived(*quantity, number, *pixels) {
                    f.write_str(" ")?;
                    write_decimal(f, &v)?;
                }
                let deltas = quantity.min_deltas().unsigned_abs();
                write!(f, " is below {deltas} DELTA of {format}")?;
                if HINTS {
                    f.write_str("; ")?;
                    let named = |i: usize| (1u32 << i) & u32::from(*formats) != 0;
                    holders(f, format, |i, _| named(i), "or", ("resolves", "resolve"))?;
                }
                Ok(())
            }
            K::BeyondRange {
                quantity,
                number,
                format,
            } => {
                f.write_str(quantity.name())?;
                let value = derived(*quantity, number, 1);
                if let Some(v) = &value {
                    f.write_str(" ")?;
                    write_decimal(f, v)?;
                }
                write!(f, " does not fit {format}")?;
                if HINTS {
                    beyond_range(f, format, value)?;
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
            K::MissingCamera if !HINTS => write!(f, "the scene has no camera"),
            K::MissingCamera => {
                // An example camera with every attribute the schema gives it.
                write!(f, "no camera: add one, such as `camera cam {{")?;
                let example = ["160 120", "4 3", "2 1.5 5"];
                for (a, v) in Entity::Camera.attributes().iter().zip(example) {
                    write!(f, " {} {v}", a.name)?;
                }
                write!(f, " }}`")
            }
            K::TooMany {
                what,
                capacity,
                parameter,
            } => write!(
                f,
                "too many {what}: the scene type holds {capacity} (raise its `{parameter}` \
                 parameter, e.g. `fixray::scene::LargeScene`)"
            ),
            K::Full { what, capacity } => {
                write!(f, "too many {what}: a scene holds {capacity}")
            }
            K::TextureFile { file, problem } => match problem {
                TextureProblem::NotFound => write!(
                    f,
                    "texture file `{file}` not found (`Scene::parse` reads no files: \
                     `Scene::read_with` takes them)"
                ),
                TextureProblem::Ppm(e) => write!(f, "texture file `{file}`: {e}"),
            },
            K::UnknownTexture(t) => write!(
                f,
                "unknown texture `{t}` (a texture must be defined before it is named)"
            ),
            K::UnknownRules(w) => {
                write!(f, "unknown rule set `{w}` (expected `course` or `fixray`)")
            }
            K::OtherRules { attribute, rules } => write!(
                f,
                "`{attribute}` belongs to the {rules} rules (write `rules {rules}` to use it)"
            ),
            K::NotSupportedYet(what) => write!(
                f,
                "`{what}` is not supported yet (fixray does not draw it; the scene is refused \
                 rather than drawn without it)"
            ),
            K::NotBuiltIn { what, feature } => write!(
                f,
                "{what} not built into this program (cargo feature `{feature}`)"
            ),
        }
    }
}

/// A position in the source text.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(super) struct Pos {
    pub(super) line: u32,
    pub(super) column: u32,
}

impl Pos {
    pub(super) fn error(self, kind: SceneErrorKind) -> SceneError {
        SceneError {
            line: self.line,
            column: self.column,
            kind,
        }
    }
}
