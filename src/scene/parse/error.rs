//! [`SceneError`]: what is wrong with a scene file, and where (line and column).

use core::fmt;

use heapless::String;

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

/// What is wrong with a texture file.
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
            K::TooMany {
                what,
                capacity,
                parameter,
            } => write!(
                f,
                "too many {what}: the scene type holds {capacity} (raise its `{parameter}` \
                 parameter, e.g. `fixray::LargeScene`)"
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
