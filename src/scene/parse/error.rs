//! [`SceneError`]: what is wrong with a scene file, and where (line and column).

use core::fmt;

use heapless::String;

use super::schema::Entity;
use crate::num::Decimal;
use crate::num::formats::MAIN;
use crate::scene::{MIN_RADIUS_SQ_DELTAS, MIN_SCALE_DELTAS};

/// Whether the parser looks for hints and its messages carry them: the entity's
/// attributes and the nearest one, a format's range, the value of a derived length and
/// the formats that hold or resolve it, invisible characters escaped, an example camera,
/// and where a block that is not closed ends ([`SceneErrorKind::Unclosed`]). Everywhere
/// but on bare metal (`target_os = "none"`: a chip's firmware), where their code, some
/// 8 KB, is more flash than a 64 KB chip has to spare. There a block that is not closed
/// is reported at its next statement's first word, or at the end of the input,
/// [`SceneErrorKind::nearest`] is `None`, a scale error keeps no number nor formats (it
/// returns at once: on a host the parse reads on, for the formats that resolve the whole
/// scene), and every other error is the same kind at the same position, its message
/// without the hint.
pub(super) const HINTS: bool = cfg!(not(target_os = "none"));

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
    /// format's range and the formats of [`MAIN`] that hold the number (not on bare
    /// metal).
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
    /// from. The message gives the length and the formats of [`MAIN`] that resolve every
    /// scale of the scene (`formats`; not on bare metal).
    BelowResolution {
        /// What it is.
        quantity: Quantity,
        /// The number it is derived from, as written (a `worlddim`, a `radius`); empty on
        /// bare metal.
        number: QuotedNumber,
        /// What that number is divided by: the pixels across, for a pitch; 1 otherwise.
        pixels: u16,
        /// The formats of [`MAIN`] (bit `i`: `MAIN[i]`) that resolve every pixel pitch
        /// and sphere of the scene as the scale rule asks, this length among them, as
        /// far as the scene was read (the error is returned once the parse is over, or
        /// at a later error): a format that resolves this pitch but not a sphere further
        /// on is not one. 0 on bare metal, where the error returns at once.
        formats: u8,
        /// The number format.
        format: &'static str,
    },
    /// A quantity the scene derives (a radius's square) beyond the format's range, at the
    /// number it is derived from. The message gives its value, the range and the formats
    /// of [`MAIN`] that hold it (not on bare metal).
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

/// ` (range ±…); {holders} hold it`: the hint of a number beyond the range of `format`
/// (the holders when the number is known).
fn beyond_range(f: &mut fmt::Formatter<'_>, format: &str, number: Option<Decimal>) -> fmt::Result {
    f.write_str(" (range ±")?;
    match Shape::of(format) {
        Some(Shape::Fixed { int, .. }) => write!(f, "{}", 1u32 << int.saturating_sub(1).min(31))?,
        Some(Shape::Float { max, .. }) => f.write_str(max)?,
        None => f.write_str("?")?,
    }
    f.write_str(")")?;
    match number {
        Some(n) => {
            f.write_str("; ")?;
            holders(f, format, |_, s| s.holds(&n), "and", ("holds", "hold"))
        }
        None => Ok(()),
    }
}

/// The value of a derived quantity from the number it is derived from, as written (a
/// pitch's `worlddim`, over `pixels`; a radius): to 18 significant digits, a square to 9.
/// `None` without [`HINTS`], or when the number was cut to be quoted.
fn derived(quantity: Quantity, number: &str, pixels: u16) -> Option<Decimal> {
    if !HINTS {
        return None;
    }
    Some(derive(quantity, Decimal::parse(number)?, pixels))
}

/// The value of a derived quantity from the number `d` it is derived from ([`derived`]).
fn derive(quantity: Quantity, mut d: Decimal, pixels: u16) -> Decimal {
    match quantity {
        Quantity::PixelPitch => {
            while let Some(m) = d.mantissa.checked_mul(10).filter(|m| *m < u64::MAX / 10) {
                d.mantissa = m;
                d.exponent = d.exponent.saturating_sub(1);
            }
            d.mantissa /= u64::from(pixels.max(1));
        }
        Quantity::Radius => {}
        Quantity::RadiusSq => {
            while d.mantissa > u64::from(u32::MAX) {
                d.mantissa /= 10;
                d.exponent = d.exponent.saturating_add(1);
            }
            d.mantissa *= d.mantissa;
            d.exponent = d.exponent.saturating_mul(2);
        }
    }
    d
}

/// The formats of [`MAIN`] (bit `i`: `MAIN[i]`) that resolve a length the scene derives
/// from `number` among coordinates below 2^`order`, as the parser's scale rule asks of
/// each ([`Shape::resolves`]): a pixel pitch (`quantity`; `number` a `worlddim` over
/// `pixels`), or a sphere's radius (either of the other quantities: `number` the radius,
/// held to its square in a fixed format). Only where [`HINTS`] holds (the parser keeps
/// the formats there).
#[cfg(not(target_os = "none"))]
pub(super) fn resolvers(quantity: Quantity, number: &Decimal, pixels: u16, order: u8) -> u8 {
    let mut bits = 0;
    for (i, name) in MAIN.iter().enumerate() {
        if Shape::of(name).is_some_and(|s| s.resolves(quantity, number, pixels, order)) {
            bits |= 1 << i;
        }
    }
    bits
}

/// Lists the formats of [`MAIN`] other than `format` for which `ok` holds (given a
/// format's index in [`MAIN`] and its shape): `a, b and c hold it` (`last` joins the last
/// two; `verb` is the singular and plural verb), or `no number format holds it`.
fn holders(
    f: &mut fmt::Formatter<'_>,
    format: &str,
    ok: impl Fn(usize, Shape) -> bool,
    last: &str,
    (one, many): (&str, &str),
) -> fmt::Result {
    let mut names = heapless::Vec::<&str, { MAIN.len() }>::new();
    for (i, name) in MAIN.into_iter().enumerate() {
        if name != format && Shape::of(name).is_some_and(|s| ok(i, s)) {
            let _ = names.push(name);
        }
    }
    let count = names.len();
    if count == 0 {
        return write!(f, "no number format {one} it");
    }
    for (i, name) in names.iter().enumerate() {
        let sep = match i {
            0 => "",
            _ if i + 1 == count => last,
            _ => ",",
        };
        if i > 0 && i + 1 == count {
            write!(f, " {sep} ")?;
        } else if i > 0 {
            write!(f, "{sep} ")?;
        }
        f.write_str(name)?;
    }
    write!(f, " {} it", if count == 1 { one } else { many })
}

/// A number format's range and resolution, as the messages need them: its constants
/// ([`crate::Scalar::INT_BITS`] and its size), so that naming a format costs no code of
/// its arithmetic.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Shape {
    /// A fixed format: `int` integer bits (the sign's included) and `frac` fraction bits.
    Fixed { int: u32, frac: u32 },
    /// A float with `mantissa` fraction bits (`DELTA` = 2^−mantissa), holding every value
    /// below 10^`order` (a power of ten below its largest), its largest `max` written
    /// short.
    Float {
        mantissa: u32,
        order: i32,
        max: &'static str,
    },
}

impl Shape {
    /// The shape of the format named `name` ([`crate::num::formats::FORMATS`]).
    fn of(name: &str) -> Option<Self> {
        crate::with_format!(name, shape()).ok()
    }

    /// Whether the format holds `number` (floats: a conservative test, below 10^order).
    fn holds(self, number: &Decimal) -> bool {
        match self {
            Shape::Fixed { int, frac } => {
                let limit = 1i128 << (int + frac).saturating_sub(1).min(126);
                number
                    .to_fixed_bits(frac)
                    .is_some_and(|b| -limit <= b && b < limit)
            }
            Shape::Float { order, .. } => {
                let mut digits = 0i32;
                let mut m = number.mantissa;
                while m > 0 {
                    m /= 10;
                    digits += 1;
                }
                number.mantissa == 0 || number.exponent.saturating_add(digits) <= order
            }
        }
    }

    /// Whether the format resolves the length `quantity` derived from `number` (a pitch
    /// over `pixels`; a sphere's radius for either other quantity) among coordinates below
    /// 2^`order` as the parser's scale rule asks: a pitch of [`MIN_SCALE_DELTAS`] ulps
    /// (`DELTA`; a float's times 2^`order`); a radius, in a fixed format, whose square
    /// it holds, of [`MIN_RADIUS_SQ_DELTAS`] `DELTA`s, in a float of [`MIN_SCALE_DELTAS`]
    /// ulps. A fixed format must hold 2^`order` too.
    #[cfg(not(target_os = "none"))]
    fn resolves(self, quantity: Quantity, number: &Decimal, pixels: u16, order: u8) -> bool {
        let order = u32::from(order);
        let pitch = quantity == Quantity::PixelPitch;
        let (value, bits, min) = match self {
            Shape::Fixed { int, .. } if order >= int => return false,
            Shape::Fixed { frac, .. } if pitch => {
                (derive(quantity, *number, pixels), frac, MIN_SCALE_DELTAS)
            }
            Shape::Fixed { frac, .. } => {
                let square = derive(Quantity::RadiusSq, *number, 1);
                if !self.holds(&square) {
                    return false;
                }
                (square, frac, MIN_RADIUS_SQ_DELTAS)
            }
            Shape::Float { mantissa, .. } => {
                let length = if pitch { quantity } else { Quantity::Radius };
                (
                    derive(length, *number, pixels),
                    mantissa.saturating_sub(order),
                    MIN_SCALE_DELTAS,
                )
            }
        };
        // `None`: beyond i128 after the shift, far above the limit.
        value
            .to_fixed_bits(bits)
            .is_none_or(|v| v >= i128::from(min))
    }
}

/// The [`Shape`] of format `S`.
fn shape<S: crate::Scalar>() -> Shape {
    let bits = u32::try_from(8 * core::mem::size_of::<S>()).unwrap_or(u32::MAX);
    if S::INT_BITS > 0 {
        Shape::Fixed {
            int: S::INT_BITS,
            frac: bits.saturating_sub(S::INT_BITS),
        }
    } else if bits <= 32 {
        // IEEE binary32.
        Shape::Float {
            mantissa: 23,
            order: 38,
            max: "3.4e38",
        }
    } else {
        // IEEE binary64.
        Shape::Float {
            mantissa: 52,
            order: 308,
            max: "1.8e308",
        }
    }
}

/// Writes a decimal with up to four significant digits (the rest truncated): plainly
/// from 0.0001 to below 10^7, else as `6.25e-6`.
fn write_decimal(f: &mut fmt::Formatter<'_>, d: &Decimal) -> fmt::Result {
    let (mut m, mut e) = (d.mantissa, d.exponent);
    while m >= 10_000 || (m != 0 && m % 10 == 0) {
        m /= 10;
        e = e.saturating_add(1);
    }
    // Below 10^4: `digits` digits (1 to 4).
    let m = u32::try_from(m).unwrap_or(0);
    let digits = match m {
        0..=9 => 1,
        10..=99 => 2,
        100..=999 => 3,
        _ => 4,
    };
    if d.negative && m != 0 {
        f.write_str("-")?;
    }
    // The value is 0.m × 10^point.
    let point = e.saturating_add(digits);
    if m == 0 || (e >= 0 && point <= 7) {
        // An integer: its digits, then zeros.
        write!(f, "{m}")?;
        (0..e).try_for_each(|_| f.write_str("0"))
    } else if (-3..=0).contains(&point) {
        f.write_str("0.")?;
        (point..0).try_for_each(|_| f.write_str("0"))?;
        write!(f, "{m}")
    } else {
        // `m` with a point before its last `after` digits, then the exponent if any.
        let plain = (1..=7).contains(&point);
        let after = if plain { -e } else { digits - 1 };
        let p = 10u32.pow(u32::try_from(after).unwrap_or(0).min(3));
        write!(f, "{}", m / p)?;
        if after > 0 {
            let w = usize::try_from(after).unwrap_or(0);
            write!(f, ".{:0w$}", m % p)?;
        }
        if plain {
            return Ok(());
        }
        let x = point.saturating_sub(1);
        let sign = if x < 0 { "-" } else { "" };
        write!(f, "e{sign}{}", x.unsigned_abs())
    }
}

/// The name of `names` nearest to `word`: at most a third of its letters (at least one)
/// added, dropped, changed or swapped with a neighbour; the first of the nearest. Without
/// an allocator: three rows of the distance table on the stack.
pub(super) fn nearest(
    word: &str,
    names: impl Iterator<Item = &'static str>,
) -> Option<&'static str> {
    let mut best: Option<(&'static str, u8)> = None;
    for name in names {
        let limit = u8::try_from(name.len() / 3).unwrap_or(u8::MAX).max(1);
        if let Some(d) = distance(word, name, limit)
            && best.is_none_or(|(_, b)| d < b)
        {
            best = Some((name, d));
        }
    }
    best.map(|(name, _)| name)
}

/// Longest name [`distance`] measures, in bytes (the schema's longest is 12).
const MAX_EDIT_NAME: usize = 16;

/// The optimal-string-alignment distance (Levenshtein's, with a swap of two neighbours
/// as one edit) between `word`'s characters and the ASCII `name`'s, when it is at most
/// `limit`; `None` beyond, or for a name longer than [`MAX_EDIT_NAME`].
fn distance(word: &str, name: &str, limit: u8) -> Option<u8> {
    let name = name.as_bytes();
    let n = name.len();
    if n >= MAX_EDIT_NAME {
        return None;
    }
    // Rows i − 2, i − 1 and i of d[i][j], the distance between the word's first i
    // characters and the name's first j bytes.
    let (mut older, mut prev, mut cur) = (
        [0u8; MAX_EDIT_NAME],
        [0u8; MAX_EDIT_NAME],
        [0u8; MAX_EDIT_NAME],
    );
    for (j, d) in prev.iter_mut().enumerate() {
        *d = u8::try_from(j).unwrap_or(u8::MAX);
    }
    let mut before = '\0';
    for (i, c) in word.chars().enumerate() {
        cur[0] = u8::try_from(i + 1).unwrap_or(u8::MAX);
        let mut least = cur[0];
        for j in 1..=n {
            let b = char::from(name[j - 1]);
            let mut d = (prev[j].min(cur[j - 1]).saturating_add(1))
                .min(prev[j - 1].saturating_add(u8::from(c != b)));
            if i > 0 && j > 1 && c == char::from(name[j - 2]) && before == b {
                d = d.min(older[j - 2].saturating_add(1));
            }
            cur[j] = d;
            least = least.min(d);
        }
        // No later row is below this one's least: past the limit for good.
        if least > limit {
            return None;
        }
        (older, prev) = (prev, cur);
        before = c;
    }
    let d = prev[n];
    (d <= limit).then_some(d)
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

#[cfg(test)]
mod tests {
    use super::*;
    use std::string::ToString;

    /// The distance counts a letter changed, added, dropped, or two neighbours swapped,
    /// as one edit each; beyond the limit there is none.
    #[test]
    fn distances_count_edits() {
        for (word, name, d) in [
            ("center", "center", Some(0)),
            ("centre", "center", Some(1)),
            ("cenrte", "center", Some(2)),
            ("cetner", "center", Some(1)),
            ("cnter", "center", Some(1)),
            ("centerr", "center", Some(1)),
            ("Center", "center", Some(1)),
            ("", "v0", Some(2)),
            ("ambient\u{200b}", "ambient", Some(1)),
            ("middle", "center", None),
            ("x", "dimensions_of_it_all", None),
        ] {
            assert_eq!(distance(word, name, 2), d, "{word} {name}");
        }
        let names = || ["material", "center", "radius"].into_iter();
        assert_eq!(nearest("radious", names()), Some("radius"));
        assert_eq!(nearest("colour", names()), None);
        // At most a third of the name's letters: `v3` is one from `v0`.
        assert_eq!(nearest("v3", ["v0", "v1"].into_iter()), Some("v0"));
        assert_eq!(nearest("xy", ["v0"].into_iter()), None);
    }

    struct Shown(Decimal);
    impl fmt::Display for Shown {
        fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            write_decimal(f, &self.0)
        }
    }

    /// Decimals are written with up to four significant digits, plainly from 0.0001 to
    /// below 10^7.
    #[test]
    fn decimals_are_written_short() {
        for (text, shown) in [
            ("40000", "40000"),
            ("0.00000625", "6.25e-6"),
            ("0.0005", "0.0005"),
            ("0.00006062", "6.062e-5"),
            ("0.000016", "1.6e-5"),
            ("1.05", "1.05"),
            ("123.456", "123.4"),
            ("0.05", "0.05"),
            ("1e999", "1e999"),
            ("12345678", "1.234e7"),
            ("-2.5", "-2.5"),
            ("0", "0"),
        ] {
            let d = Decimal::parse(text).unwrap();
            assert_eq!(Shown(d).to_string(), shown, "{text}");
        }
    }

    /// The shapes of the formats, from their constants.
    #[test]
    fn formats_have_their_shapes() {
        assert_eq!(
            Shape::of("i16f16"),
            Some(Shape::Fixed { int: 16, frac: 16 })
        );
        assert_eq!(
            Shape::of("i16f16r"),
            Some(Shape::Fixed { int: 16, frac: 16 })
        );
        assert_eq!(
            Shape::of("i20f12"),
            Some(Shape::Fixed { int: 20, frac: 12 })
        );
        assert_eq!(
            Shape::of("i32f32"),
            Some(Shape::Fixed { int: 32, frac: 32 })
        );
        assert!(matches!(
            Shape::of("f32m"),
            Some(Shape::Float { mantissa: 23, .. })
        ));
        assert!(matches!(
            Shape::of("f64"),
            Some(Shape::Float { mantissa: 52, .. })
        ));
        assert_eq!(Shape::of("q15"), None);
    }
}
