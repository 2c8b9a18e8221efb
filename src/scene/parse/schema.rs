//! The schema of the scene language: every entity with its keyword and attributes, in one
//! table ([`SCHEMA`]), and the statements outside blocks ([`STATEMENTS`]). The parser's
//! keywords, its unknown-keyword message and the size of a block's value table all come
//! from it, and so do the reference tables of the language's document
//! ([`crate::scene::language`], `docs/scene-format.md`), which
//! [`write_reference_tables`] writes (`cargo xtask scene-format` puts them in the
//! document; a test fails when the document and the schema differ).
//!
//! ```
//! use fixray::scene::schema::{Arity, Entity, SCHEMA};
//!
//! let sphere = Entity::from_keyword("sphere").unwrap();
//! assert_eq!(sphere.keyword(), "sphere");
//! let radius = sphere.attributes().iter().find(|a| a.is("radius")).unwrap();
//! assert_eq!((radius.arity, radius.required), (Arity::Numbers(1), true));
//! // `dimension` and `dimensions` are one attribute of a tiled plane.
//! let tiles = Entity::from_keyword("tiled_plane").unwrap();
//! assert!(tiles.attributes().iter().any(|a| a.is("dimension") && a.is("dimensions")));
//! assert_eq!(SCHEMA.len(), 14);
//! ```
//!
//! A new entity is a variant of [`Entity`], a row of [`SCHEMA`], an arm of the builder
//! (`builder.rs`) and its descriptions for the reference (below [`write_reference_tables`]
//! in this file; a unit test names any attribute left without one).

use core::fmt;

use crate::scene::{LargeScene, MAX_PIXELDIM, MAX_PROJECTORS, MAX_TEXTURES, Scene};

/// The entity kinds of the scene language (in the order of [`SCHEMA`]).
///
/// ```
/// use fixray::scene::schema::Entity;
///
/// let sphere = Entity::from_keyword("sphere").unwrap();
/// assert_eq!(sphere, Entity::Sphere);
/// assert_eq!(sphere.keyword(), "sphere");
/// let names: Vec<&str> = sphere.attributes().iter().map(|a| a.name).collect();
/// assert_eq!(names, ["material", "center", "radius"]);
/// assert_eq!(Entity::from_keyword("ball"), None);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Entity {
    /// `camera`: the image size, the screen window and the eye.
    Camera,
    /// `material`: a surface's colours and finish.
    Material,
    /// `light`: a point light.
    Light,
    /// `spotlight`: a point light limited to a cone.
    Spotlight,
    /// `plane`: an infinite plane.
    Plane,
    /// `sphere`: a sphere.
    Sphere,
    /// `tiled_plane`: an infinite plane tiled in a checkerboard of two materials.
    TiledPlane,
    /// `fplane`: a finite rectangle of a plane.
    FPlane,
    /// `triangle`: a triangle given by `vertex1`, `vertex2`, `vertex3`.
    Triangle,
    /// `tri`: a triangle given by `v0`, `v1`, `v2`.
    Tri,
    /// `texture`: an image file for textured planes and projectors.
    Texture,
    /// `texplane`: a finite rectangle with a texture on it.
    TexPlane,
    /// `projector`: a light that shines through a textured rectangle.
    Projector,
    /// `revsurf`: a surface of revolution.
    Revsurf,
}

/// How an attribute's value is written.
///
/// ```
/// use fixray::scene::schema::{Arity, Entity};
///
/// let arity = |entity: Entity, word: &str| {
///     entity.attributes().iter().find(|a| a.is(word)).map(|a| a.arity)
/// };
/// assert_eq!(arity(Entity::Sphere, "material"), Some(Arity::Name));
/// assert_eq!(arity(Entity::Sphere, "center"), Some(Arity::Numbers(3)));
/// assert_eq!(arity(Entity::Texture, "filename"), Some(Arity::Path));
/// assert_eq!(arity(Entity::Material, "specular"), Some(Arity::OneOrThree));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Arity {
    /// A name (of a material or a texture).
    Name,
    /// A file path: any token but a brace.
    Path,
    /// This many numbers.
    Numbers(u8),
    /// One number, or three under the course rules (`specular R G B`, the course's
    /// older files).
    OneOrThree,
}

/// One attribute of an entity.
///
/// ```
/// use fixray::scene::schema::{Arity, Entity};
///
/// let attributes = Entity::FPlane.attributes();
/// let dimensions = attributes.iter().find(|a| a.name == "dimensions").unwrap();
/// assert_eq!((dimensions.arity, dimensions.required), (Arity::Numbers(2), true));
/// // Real files also write `dimension`.
/// assert!(dimensions.either_number);
/// assert!(dimensions.is("dimension") && !dimensions.is("dim"));
/// // Every attribute of a material is optional (each has a default).
/// assert!(Entity::Material.attributes().iter().all(|a| !a.required));
/// ```
#[derive(Debug)]
#[non_exhaustive]
pub struct AttrSpec {
    /// The attribute's keyword, as the reference spells it.
    pub name: &'static str,
    /// How its value is written.
    pub arity: Arity,
    /// Whether a block must give it (an optional one has a default).
    pub required: bool,
    /// Real files also spell it with a final `s` added or dropped (`dimension` /
    /// `dimensions`). A flag, not the other spelling: the table is in a chip's flash, and
    /// without a second string an entry takes 12 bytes instead of 28.
    pub either_number: bool,
}

impl AttrSpec {
    /// Whether `word` names this attribute (either spelling, when it has two).
    pub fn is(&self, word: &str) -> bool {
        self.name == word || self.either_number && stem(self.name) == stem(word)
    }
}

/// A word without its final `s`, if it has one.
fn stem(word: &str) -> &str {
    word.strip_suffix('s').unwrap_or(word)
}

const fn numbers(name: &'static str, n: u8) -> AttrSpec {
    AttrSpec {
        name,
        either_number: false,
        arity: Arity::Numbers(n),
        required: true,
    }
}
const fn optional(name: &'static str, n: u8) -> AttrSpec {
    AttrSpec {
        name,
        either_number: false,
        arity: Arity::Numbers(n),
        required: false,
    }
}
const fn material(name: &'static str) -> AttrSpec {
    AttrSpec {
        name,
        either_number: false,
        arity: Arity::Name,
        required: true,
    }
}
/// A texture's name.
const fn texname() -> AttrSpec {
    AttrSpec {
        name: "texname",
        either_number: false,
        arity: Arity::Name,
        required: true,
    }
}
/// Two numbers that real files spell either way (`dimension`, `dimensions`).
const fn dimensions(name: &'static str) -> AttrSpec {
    AttrSpec {
        name,
        either_number: true,
        arity: Arity::Numbers(2),
        required: true,
    }
}

/// An entity: its kind, keyword and attributes.
///
/// ```
/// use fixray::scene::schema::{Entity, EntitySpec, SCHEMA};
///
/// let light: &EntitySpec = Entity::Light.spec();
/// assert_eq!((light.entity, light.keyword), (Entity::Light, "light"));
/// assert_eq!(light.attributes.len(), 2);
/// // The attributes a `camera` block must give, in the reference's order.
/// let camera = SCHEMA.iter().find(|s| s.keyword == "camera").unwrap();
/// let required = camera.attributes.iter().filter(|a| a.required).map(|a| a.name);
/// assert!(required.eq(["pixeldim", "worlddim", "viewpoint"]));
/// ```
#[derive(Debug)]
#[non_exhaustive]
pub struct EntitySpec {
    /// The kind.
    pub entity: Entity,
    /// The keyword that starts its blocks.
    pub keyword: &'static str,
    /// Its attributes, in the reference's order (a block may give them in any order).
    pub attributes: &'static [AttrSpec],
}

/// Every entity of the language, in the order of [`Entity`]'s variants (checked at compile
/// time). The rows are linked into a firmware that parses scenes: they hold what the
/// parser needs and nothing else (the reference's descriptions are in
/// [`write_reference_tables`], which a firmware does not call).
pub const SCHEMA: [EntitySpec; 14] = [
    EntitySpec {
        entity: Entity::Camera,
        keyword: "camera",
        attributes: &[
            numbers("pixeldim", 2),
            numbers("worlddim", 2),
            numbers("viewpoint", 3),
        ],
    },
    EntitySpec {
        entity: Entity::Material,
        keyword: "material",
        attributes: &[
            optional("ambient", 3),
            optional("diffuse", 3),
            AttrSpec {
                name: "specular",
                either_number: false,
                arity: Arity::OneOrThree,
                required: false,
            },
            optional("shininess", 1),
            optional("reflective", 1),
            optional("transparency", 1),
        ],
    },
    EntitySpec {
        entity: Entity::Light,
        keyword: "light",
        attributes: &[numbers("location", 3), numbers("emissivity", 3)],
    },
    EntitySpec {
        entity: Entity::Spotlight,
        keyword: "spotlight",
        attributes: &[
            numbers("location", 3),
            numbers("emissivity", 3),
            numbers("point", 3),
            numbers("theta", 1),
        ],
    },
    EntitySpec {
        entity: Entity::Plane,
        keyword: "plane",
        attributes: &[
            material("material"),
            numbers("normal", 3),
            numbers("point", 3),
        ],
    },
    EntitySpec {
        entity: Entity::Sphere,
        keyword: "sphere",
        attributes: &[
            material("material"),
            numbers("center", 3),
            numbers("radius", 1),
        ],
    },
    EntitySpec {
        entity: Entity::TiledPlane,
        keyword: "tiled_plane",
        attributes: &[
            material("material"),
            material("altmaterial"),
            numbers("normal", 3),
            numbers("point", 3),
            // Optional: without it the tiles lie on world x/z (the course's older form).
            optional("xdir", 3),
            dimensions("dimension"),
        ],
    },
    EntitySpec {
        entity: Entity::FPlane,
        keyword: "fplane",
        attributes: &[
            material("material"),
            numbers("normal", 3),
            numbers("point", 3),
            numbers("xdir", 3),
            dimensions("dimensions"),
        ],
    },
    EntitySpec {
        entity: Entity::Triangle,
        keyword: "triangle",
        attributes: &[
            material("material"),
            // The course reads them and draws the triangle's own plane (§14).
            optional("normal", 3),
            optional("point", 3),
            numbers("vertex1", 3),
            numbers("vertex2", 3),
            numbers("vertex3", 3),
        ],
    },
    EntitySpec {
        entity: Entity::Tri,
        keyword: "tri",
        attributes: &[
            material("material"),
            numbers("v0", 3),
            numbers("v1", 3),
            numbers("v2", 3),
        ],
    },
    EntitySpec {
        entity: Entity::Texture,
        keyword: "texture",
        attributes: &[AttrSpec {
            name: "filename",
            either_number: false,
            arity: Arity::Path,
            required: true,
        }],
    },
    EntitySpec {
        entity: Entity::TexPlane,
        keyword: "texplane",
        attributes: &[
            material("material"),
            numbers("normal", 3),
            numbers("point", 3),
            numbers("xdir", 3),
            dimensions("dimensions"),
            texname(),
            // 0 (fit) when absent, as the course's zeroed structures read it.
            optional("mode", 1),
        ],
    },
    EntitySpec {
        entity: Entity::Projector,
        keyword: "projector",
        attributes: &[
            numbers("location", 3),
            numbers("emissivity", 3),
            numbers("point", 3),
            numbers("normal", 3),
            numbers("xdir", 3),
            dimensions("dimensions"),
            texname(),
            optional("mode", 1),
        ],
    },
    EntitySpec {
        entity: Entity::Revsurf,
        keyword: "revsurf",
        attributes: &[
            material("material"),
            numbers("surfer", 1),
            numbers("base", 3),
            numbers("direction", 3),
            numbers("height", 1),
        ],
    },
];

// The table is in the order of the variants, so `Entity::spec` indexes it in bounds.
const _: () = {
    let mut i = 0;
    while i < SCHEMA.len() {
        assert!(
            SCHEMA[i].entity as usize == i,
            "SCHEMA is out of the variants' order"
        );
        i += 1;
    }
};

/// The statements outside blocks (`background R G B`, `precision EPS`, `rules NAME`): each
/// a keyword and its arguments, at most once per file.
pub const STATEMENTS: [&str; 3] = ["background", "precision", "rules"];

/// What real course files have that this crate does not draw yet: entities and material
/// attributes, refused with [`super::SceneErrorKind::NotSupportedYet`] at their
/// `line:column`, never silently ignored (none left; the list stays for the next).
pub(super) const NOT_YET: [&str; 0] = [];

/// Whether `word` is a keyword of the format (it cannot be a name).
pub(super) fn is_keyword(word: &str) -> bool {
    keywords().any(|k| k == word) || NOT_YET.contains(&word)
}

/// The most attributes any entity has: the size of a block's value table.
pub(super) const MAX_ATTRS: usize = {
    let mut max = 0;
    let mut i = 0;
    while i < SCHEMA.len() {
        if SCHEMA[i].attributes.len() > max {
            max = SCHEMA[i].attributes.len();
        }
        i += 1;
    }
    max
};

/// The most numbers any attribute has: the size of an attribute's number table.
pub(super) const MAX_NUMBERS: usize = {
    let mut max = 0;
    let mut i = 0;
    while i < SCHEMA.len() {
        let mut j = 0;
        while j < SCHEMA[i].attributes.len() {
            let n = match SCHEMA[i].attributes[j].arity {
                // Lossless (`usize::from` is not const).
                Arity::Numbers(n) => n as usize,
                Arity::OneOrThree => 3,
                Arity::Name | Arity::Path => 0,
            };
            if n > max {
                max = n;
            }
            j += 1;
        }
        i += 1;
    }
    max
};

impl Entity {
    /// The entity whose keyword is `word`.
    pub fn from_keyword(word: &str) -> Option<Self> {
        SCHEMA.iter().find(|s| s.keyword == word).map(|s| s.entity)
    }

    /// Its row of [`SCHEMA`].
    pub fn spec(self) -> &'static EntitySpec {
        // SCHEMA is in the order of the variants (checked at compile time, above).
        &SCHEMA[self as usize]
    }

    /// The keyword.
    pub fn keyword(self) -> &'static str {
        self.spec().keyword
    }

    /// The attributes, in the reference's order.
    pub fn attributes(self) -> &'static [AttrSpec] {
        self.spec().attributes
    }
}

/// Every keyword that may start a statement: the entities', then the statements'.
pub fn keywords() -> impl Iterator<Item = &'static str> + Clone {
    SCHEMA
        .iter()
        .map(|s| s.keyword)
        .chain(STATEMENTS.iter().copied())
}

/// The comment that opens the generated part of the language's document.
pub const TABLES_BEGIN: &str = "<!-- schema tables: generated by `cargo xtask scene-format` from fixray::scene::schema; do not edit by hand -->";

/// The comment that closes the generated part of the language's document.
pub const TABLES_END: &str = "<!-- end of schema tables -->";

/// Writes the reference tables of the scene language in Markdown: the statements, every
/// entity with its attributes (arguments, whether required, default, meaning) and the
/// capacities of a scene. The attributes, their arguments' count and whether they are
/// required come from [`SCHEMA`] and [`STATEMENTS`], the capacities from the crate's
/// constants; the words (units, domains, defaults) are kept beside this function, out of
/// the schema's rows, so that a firmware, which never calls it, links none of them.
///
/// `cargo xtask scene-format` writes them into `docs/scene-format.md` between
/// [`TABLES_BEGIN`] and [`TABLES_END`] ([`crate::scene::language`] shows the result).
///
/// # Errors
/// What `out` returns.
///
/// ```
/// let mut tables = String::new();
/// fixray::scene::schema::write_reference_tables(&mut tables).unwrap();
/// assert!(tables.contains("| `radius` | `R` | yes | — |"));
/// ```
pub fn write_reference_tables(out: &mut impl fmt::Write) -> fmt::Result {
    out.write_str(
        "### Statements\n\n\
         Outside blocks, each at most once per file, anywhere at the top level.\n\n\
         | statement | arguments | default | meaning |\n\
         |---|---|---|---|\n",
    )?;
    for name in STATEMENTS {
        let d = describe_statement(name);
        write!(out, "| `{name}` | `{}` | ", d.args)?;
        cell(out, d.default)?;
        out.write_str(" | ")?;
        cell(out, d.meaning)?;
        out.write_str(" |\n")?;
    }
    for spec in &SCHEMA {
        let keyword = spec.keyword;
        write!(
            out,
            "\n### `{keyword}`\n\n`{keyword} NAME {{ … }}`: {}\n\n\
             | attribute | arguments | required | default | meaning |\n\
             |---|---|---|---|---|\n",
            summary(spec.entity)
        )?;
        for attr in spec.attributes {
            let d = describe(spec.entity, attr.name);
            write!(out, "| `{}`", attr.name)?;
            if attr.either_number {
                match attr.name.strip_suffix('s') {
                    Some(singular) => write!(out, " (or `{singular}`)")?,
                    None => write!(out, " (or `{}s`)", attr.name)?,
                }
            }
            write!(out, " | `{}`", d.args)?;
            if attr.arity == Arity::OneOrThree {
                out.write_str(" (`rules course`: or `R G B`)")?;
            }
            let (required, default) = if attr.required {
                ("yes", "—")
            } else {
                ("no", d.default)
            };
            write!(out, " | {required} | ")?;
            cell(out, default)?;
            out.write_str(" | ")?;
            cell(out, d.meaning)?;
            out.write_str(" |\n")?;
        }
    }
    write_capacities(out)
}

/// Writes `text` as a table cell's content: a `|` (in `|N·d|`) escaped.
fn cell(out: &mut impl fmt::Write, text: &str) -> fmt::Result {
    let mut parts = text.split('|');
    out.write_str(parts.next().unwrap_or(""))?;
    for part in parts {
        out.write_str("\\|")?;
        out.write_str(part)?;
    }
    Ok(())
}

/// The capacities table: how many of each entity a scene holds.
fn write_capacities(out: &mut impl fmt::Write) -> fmt::Result {
    out.write_str(
        "\n### Capacities\n\n\
         A scene's room is fixed in its type (no allocator): `Scene<S>` holds what a 16 KB \
         chip can, `LargeScene<S>` what every real course file needs; any other \
         `Scene<S, OBJECTS, MATERIALS, LIGHTS>` may be chosen. A file with more is refused \
         (`SceneErrorKind::TooMany`, which names the parameter to raise, or \
         `SceneErrorKind::Full`).\n\n\
         | what | entities | `Scene<S>` | `LargeScene<S>` | set by |\n\
         |---|---|---|---|---|\n",
    )?;
    let rows: [(Counted, &str, usize, usize, &str); 5] = [
        (
            Counted::Objects,
            "objects",
            <Scene<f64> as Capacities>::OBJECTS,
            <LargeScene<f64> as Capacities>::OBJECTS,
            "the type parameter `OBJECTS`",
        ),
        (
            Counted::Materials,
            "materials",
            <Scene<f64> as Capacities>::MATERIALS,
            <LargeScene<f64> as Capacities>::MATERIALS,
            "the type parameter `MATERIALS` (at most 256 are named: an object keeps its \
             material's index in a byte)",
        ),
        (
            Counted::Lights,
            "lights",
            <Scene<f64> as Capacities>::LIGHTS,
            <LargeScene<f64> as Capacities>::LIGHTS,
            "the type parameter `LIGHTS`",
        ),
        (
            Counted::Textures,
            "textures",
            TEXTURES_WITH_FEATURE,
            TEXTURES_WITH_FEATURE,
            "`MAX_TEXTURES`: none without the cargo feature `textures`",
        ),
        (
            Counted::Projectors,
            "projectors (lights too)",
            PROJECTORS_WITH_FEATURE,
            PROJECTORS_WITH_FEATURE,
            "`MAX_PROJECTORS`: none without the cargo feature `textures`",
        ),
    ];
    for (counted, what, scene, large, set_by) in rows {
        write!(out, "| {what} | ")?;
        let mut first = true;
        for spec in SCHEMA
            .iter()
            .filter(|s| counts(s.entity).contains(&counted))
        {
            let sep = if first { "" } else { ", " };
            write!(out, "{sep}`{}`", spec.keyword)?;
            first = false;
        }
        writeln!(out, " | {scene} | {large} | {set_by} |")?;
    }
    writeln!(
        out,
        "| cameras | `camera` | 1 | 1 | the language: exactly one |\n\
         | pixels | `pixeldim` | {MAX_PIXELDIM} × {MAX_PIXELDIM} | \
         {MAX_PIXELDIM} × {MAX_PIXELDIM} | `MAX_PIXELDIM` |"
    )
}

/// The capacities of a scene type (read off its parameters, for the reference).
trait Capacities {
    const OBJECTS: usize;
    const MATERIALS: usize;
    const LIGHTS: usize;
}

impl<S, const O: usize, const M: usize, const L: usize> Capacities for Scene<S, O, M, L> {
    const OBJECTS: usize = O;
    // An object names its material by a byte (the parser's limit).
    const MATERIALS: usize = if M < 256 { M } else { 256 };
    const LIGHTS: usize = L;
}

/// [`MAX_TEXTURES`] and [`MAX_PROJECTORS`] with the cargo feature `textures` (without it
/// they are 0): the reference states them whatever the build it is written by.
const TEXTURES_WITH_FEATURE: usize = 8;
const PROJECTORS_WITH_FEATURE: usize = 2;
const _: () = assert!(
    !cfg!(feature = "textures")
        || MAX_TEXTURES == TEXTURES_WITH_FEATURE && MAX_PROJECTORS == PROJECTORS_WITH_FEATURE,
    "the reference's texture capacities are out of step with the scene's"
);

/// What a scene's capacities count.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Counted {
    Objects,
    Materials,
    Lights,
    Textures,
    Projectors,
}

/// Which capacities an entity takes room in.
fn counts(entity: Entity) -> &'static [Counted] {
    match entity {
        Entity::Camera => &[],
        Entity::Material => &[Counted::Materials],
        Entity::Light | Entity::Spotlight => &[Counted::Lights],
        Entity::Projector => &[Counted::Lights, Counted::Projectors],
        Entity::Texture => &[Counted::Textures],
        Entity::Plane
        | Entity::Sphere
        | Entity::TiledPlane
        | Entity::FPlane
        | Entity::Triangle
        | Entity::Tri
        | Entity::TexPlane
        | Entity::Revsurf => &[Counted::Objects],
    }
}

/// What the reference says of an attribute or a statement.
#[derive(Debug, Clone, Copy)]
struct Doc {
    /// The arguments as written, one placeholder per number (`X Y Z`).
    args: &'static str,
    /// The value when absent, for an optional attribute; empty for a required one.
    default: &'static str,
    /// Meaning, units and domain.
    meaning: &'static str,
}

const fn doc(args: &'static str, default: &'static str, meaning: &'static str) -> Doc {
    Doc {
        args,
        default,
        meaning,
    }
}

/// A statement's reference entry.
fn describe_statement(name: &str) -> Doc {
    match name {
        "background" => doc(
            "R G B",
            "`0 0 0`",
            "Colour where a ray meets nothing: 1 is full intensity (255). Reals ≥ 0 (any \
             sign under `rules course`, where only primary rays that miss show it and \
             other misses are black).",
        ),
        "precision" => doc(
            "EPS",
            "the number format's `DEFAULT_EPSILON`",
            "The precision epsilon of every intersection test of the scene: a ray runs \
             parallel to a plane when `|N·d| < EPS`. A real > 0 that stays > 0 in the \
             number format.",
        ),
        "rules" => doc(
            "NAME",
            "`course`",
            "The rule set that reads and draws the file: `course` or `fixray` (see \
             *Two rule sets*). Read before anything else, wherever it stands.",
        ),
        _ => UNDOCUMENTED,
    }
}

/// A placeholder for an attribute or statement without a reference entry (a unit test
/// makes sure there is none).
const UNDOCUMENTED: Doc = doc("?", "?", "(undocumented)");

/// One sentence on an entity, for its section of the reference.
fn summary(entity: Entity) -> &'static str {
    match entity {
        Entity::Camera => {
            "the picture is what the eye at `viewpoint` sees through the window \
             `[0, WX] × [0, WY]` of the plane z = 0, on a grid of `W × H` pixels, row 0 at \
             the top. Exactly one per file."
        }
        Entity::Material => {
            "a surface's colours and finish, named by the objects that use it (defined \
             before them). Every attribute is optional: `material m { }` is black and matte."
        }
        Entity::Light => "a point light: it shines from `location` in every direction.",
        Entity::Spotlight => {
            "a point light that lights only inside a cone: the points seen from `location` \
             within `theta` of the direction to `point`."
        }
        Entity::Plane => "an infinite plane.",
        Entity::Sphere => "a sphere.",
        Entity::TiledPlane => {
            "an infinite plane tiled in a checkerboard of two materials (see *Tiled and \
             finite planes*)."
        }
        Entity::FPlane => {
            "a rectangle of a plane: from the corner `point`, `W` along `xdir` and `H` \
             across it."
        }
        Entity::Triangle => "a triangle through three vertices (the course's instructor form).",
        Entity::Tri => "a triangle through three vertices (the course's shorter form).",
        Entity::Texture => {
            "an image for `texplane` and `projector`: a binary PPM file (`P6`, as \
             `fixray::ppm` reads it: `#` comments in the header, 8 or 16 bits a sample)."
        }
        Entity::TexPlane => {
            "a rectangle (as `fplane`) with a texture on it: its material's ambient and \
             diffuse colours are multiplied by the texel, `texel / 255` per channel."
        }
        Entity::Projector => {
            "a light that shines through a slide, a textured rectangle (as `texplane`): it \
             lights a point only where the ray from `location` to the point crosses the \
             slide, with its emissivity times the texel there. The slide itself is \
             invisible."
        }
        Entity::Revsurf => {
            "a surface of revolution about the axis from `base` along `direction`, \
             `height` long, open at both ends, with one of the course's three profiles."
        }
    }
}

/// An attribute's reference entry.
fn describe(entity: Entity, attribute: &str) -> Doc {
    use Entity as E;
    const MATERIAL: Doc = doc(
        "M",
        "",
        "The object's material, by name; defined earlier in the file.",
    );
    const NORMAL: Doc = doc(
        "A B C",
        "",
        "Direction perpendicular to the plane: any length but zero (it is made unit \
         length). `N·point` must fit the number format.",
    );
    const CORNER: Doc = doc("X Y Z", "", "A corner of the rectangle, world units.");
    const XDIR: Doc = doc(
        "X Y Z",
        "",
        "Direction of the rectangle's first side, `u`: projected into the plane and made \
         unit length; not along the normal.",
    );
    const SIDES: Doc = doc(
        "W H",
        "",
        "Side lengths along `u` and along `v = N × u`, world units, > 0.",
    );
    const TEXNAME: Doc = doc(
        "T",
        "",
        "The texture, by name; defined earlier in the file.",
    );
    const MODE: Doc = doc(
        "MODE",
        "`0`",
        "`0`: the texture is stretched over the rectangle; `1`: it repeats, one texel per \
         pixel of the screen window (`WX / W` by `WY / H` world units).",
    );
    const LOCATION: Doc = doc("X Y Z", "", "Where the light is, world units.");
    const EMISSIVITY: Doc = doc(
        "R G B",
        "",
        "Intensity per channel: it multiplies a surface's `diffuse` and `specular`. \
         Reals ≥ 0 (any sign under `rules course`).",
    );
    const VERTEX: Doc = doc(
        "X Y Z",
        "",
        "A corner, world units; the three must span a triangle (not lie on one line).",
    );
    match (entity, attribute) {
        (E::Camera, "pixeldim") => doc(
            "W H",
            "",
            "Image width and height in pixels: integers in 1..=4096.",
        ),
        (E::Camera, "worlddim") => doc(
            "WX WY",
            "",
            "Width and height of the screen window on the plane z = 0, world units, > 0.",
        ),
        (E::Camera, "viewpoint") => doc(
            "X Y Z",
            "",
            "The eye, world units; `Z > 0` (the scene lies behind the screen, at z < 0).",
        ),
        (E::Material, "ambient") => doc(
            "R G B",
            "`0 0 0`",
            "Colour shown wherever the surface is seen, lit or not: 1 is full intensity \
             (255). Reals ≥ 0 (any sign under `rules course`).",
        ),
        (E::Material, "diffuse") => doc(
            "R G B",
            "`0 0 0`",
            "Diffuse reflectance per channel: each light adds \
             `diffuse × emissivity × max(0, N·L) / dist`. Reals ≥ 0 (any sign under \
             `rules course`).",
        ),
        (E::Material, "specular") => doc(
            "S",
            "`0`",
            "Weight of the glints: each light adds \
             `specular × emissivity × max(0, N·H)^shininess / dist`. A real ≥ 0. Under \
             `rules course` also the mirror weight; its `R G B` form is read and not used.",
        ),
        (E::Material, "shininess") => doc(
            "N",
            "`1` (`rules course`: `0`)",
            "Exponent of the glints, a real ≥ 1. Under `rules course` also `0`, and a \
             glint needs a `shininess`: without one there is none.",
        ),
        (E::Material, "reflective") => doc(
            "K",
            "`0`",
            "Mirror share in [0, 1]: the surface shows `(1 − K)` of its own colour and `K` \
             of what the mirrored ray sees. `rules fixray` only.",
        ),
        (E::Material, "transparency") => doc(
            "T",
            "`0`",
            "Translucency in [0, 1]: the surface shows `(1 − T)` of its own colour and \
             filters what lies behind it, and the light through it, by \
             `T × diffuse / max(diffuse)`. `rules course` only.",
        ),
        (E::Light | E::Spotlight | E::Projector, "location") => LOCATION,
        (E::Light | E::Spotlight | E::Projector, "emissivity") => EMISSIVITY,
        (E::Spotlight, "point") => doc(
            "X Y Z",
            "",
            "The point the cone's axis aims at, world units; not `location`.",
        ),
        (E::Spotlight, "theta") => doc("DEG", "", "Half-angle of the cone, degrees in (0, 90]."),
        (E::Plane, "material") => MATERIAL,
        (E::Plane | E::TiledPlane, "normal") => NORMAL,
        (E::Plane, "point") => doc("X Y Z", "", "Any point of the plane, world units."),
        (E::Sphere, "material") => MATERIAL,
        (E::Sphere, "center") => doc("X Y Z", "", "The centre, world units."),
        (E::Sphere, "radius") => doc(
            "R",
            "",
            "World units, > 0 (also once rounded to the number format, whose range must \
             hold `R²`).",
        ),
        (E::TiledPlane, "material") => doc(
            "M",
            "",
            "The material of one colour of squares (which: see *Tiled and finite planes*).",
        ),
        (E::TiledPlane, "altmaterial") => doc(
            "M",
            "",
            "The material of the other squares; defined earlier in the file.",
        ),
        (E::TiledPlane, "point") => doc(
            "X Y Z",
            "",
            "A point of the plane, world units: a corner of a square under `rules fixray` \
             with `xdir`.",
        ),
        (E::TiledPlane, "xdir") => doc(
            "X Y Z",
            "squares on world x and z",
            "Direction of the squares' first side, `u`: projected into the plane and made \
             unit length; not along the normal.",
        ),
        (E::TiledPlane, "dimension") => doc(
            "W H",
            "",
            "Square size along `u` and along `v = N × u` (without `xdir`: along world x \
             and z), world units, > 0.",
        ),
        (E::FPlane | E::TexPlane, "material") => MATERIAL,
        (E::FPlane | E::TexPlane | E::Projector, "normal") => NORMAL,
        (E::FPlane | E::TexPlane | E::Projector, "point") => CORNER,
        (E::FPlane | E::TexPlane | E::Projector, "xdir") => XDIR,
        (E::FPlane | E::TexPlane | E::Projector, "dimensions") => SIDES,
        (E::TexPlane | E::Projector, "texname") => TEXNAME,
        (E::TexPlane | E::Projector, "mode") => MODE,
        (E::Triangle | E::Tri | E::Revsurf, "material") => MATERIAL,
        (E::Triangle, "normal" | "point") => doc(
            "X Y Z",
            "not used",
            "Read and not used: the triangle's plane is its vertices' (course files give \
             them, not always on that plane).",
        ),
        (E::Triangle, "vertex1" | "vertex2" | "vertex3") | (E::Tri, "v0" | "v1" | "v2") => VERTEX,
        (E::Texture, "filename") => doc(
            "PATH",
            "",
            "The image file: any token but a brace. The program that reads the scene \
             supplies the file's bytes (`Scene::read_with`; on a host \
             `fixray::scene::files::beside` reads it relative to the scene file).",
        ),
        (E::Revsurf, "surfer") => doc(
            "K",
            "",
            "The profile, radius `r` at distance `s` along the axis: `1` a cone, \
             `r = 4 (1 − s / height)`, its apex at `base + height × direction`; `2` an \
             hourglass, `r = 1 + cos(s) / 2`; `3` a vase, `r = 1 + sin(s) / 2`.",
        ),
        (E::Revsurf, "base") => doc("X Y Z", "", "Where the axis starts, world units."),
        (E::Revsurf, "direction") => doc(
            "X Y Z",
            "",
            "Direction of the axis: any length but zero (it is made unit length).",
        ),
        (E::Revsurf, "height") => doc("H", "", "Length of the axis, world units, > 0."),
        _ => UNDOCUMENTED,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_is_in_the_order_of_the_variants() {
        for (i, spec) in SCHEMA.iter().enumerate() {
            assert_eq!(spec.entity as usize, i, "{}", spec.keyword);
            assert_eq!(Entity::from_keyword(spec.keyword), Some(spec.entity));
        }
    }

    #[test]
    fn both_spellings_of_the_dimensions_are_one_attribute() {
        for entity in [
            Entity::TiledPlane,
            Entity::FPlane,
            Entity::TexPlane,
            Entity::Projector,
        ] {
            let dims: std::vec::Vec<_> = entity
                .attributes()
                .iter()
                .filter(|a| a.is("dimension") && a.is("dimensions"))
                .collect();
            assert_eq!(dims.len(), 1, "{}", entity.keyword());
            // Only those two spellings.
            for other in ["dimensionss", "dimensio", "s", "", "Dimension"] {
                assert!(!dims[0].is(other), "{} {other}", entity.keyword());
            }
        }
    }

    /// Every attribute and statement has a reference entry whose arguments name one
    /// placeholder per number, and a default exactly when it is optional.
    #[test]
    fn every_attribute_is_described() {
        for spec in &SCHEMA {
            for attr in spec.attributes {
                let d = describe(spec.entity, attr.name);
                let what = std::format!("{} {}", spec.keyword, attr.name);
                assert_ne!(d.meaning, UNDOCUMENTED.meaning, "{what}");
                let placeholders = d.args.split_whitespace().count();
                let expected = match attr.arity {
                    Arity::Numbers(n) => usize::from(n),
                    Arity::OneOrThree | Arity::Name | Arity::Path => 1,
                };
                assert_eq!(placeholders, expected, "{what}: {:?}", d.args);
                assert_eq!(attr.required, d.default.is_empty(), "{what}");
            }
        }
        for name in STATEMENTS {
            let d = describe_statement(name);
            assert_ne!(d.meaning, UNDOCUMENTED.meaning, "{name}");
            assert!(!d.default.is_empty(), "{name}");
        }
    }

    /// The words that state a constant say its value.
    #[test]
    fn described_limits_are_the_crates() {
        let pixeldim = describe(Entity::Camera, "pixeldim").meaning;
        assert!(
            pixeldim.contains(&std::format!("1..={MAX_PIXELDIM}")),
            "{pixeldim}"
        );
        let surfer = describe(Entity::Revsurf, "surfer").meaning;
        let cone = std::format!("r = {} (1 − s / height)", crate::geometry::CONE_BASE_RADIUS);
        assert!(surfer.contains(&cone), "{surfer}");
        let mut tables = std::string::String::new();
        write_reference_tables(&mut tables).unwrap();
        let objects = std::format!("| {} | 1024 |", crate::scene::MAX_OBJECTS);
        assert!(tables.contains(&objects), "{tables}");
    }

    /// The tables are well-formed Markdown: every row of a table has its header's cells
    /// (a `|` in a text is escaped), and every entity has its section.
    #[test]
    fn the_tables_are_well_formed() {
        let mut tables = std::string::String::new();
        write_reference_tables(&mut tables).unwrap();
        let cells = |row: &str| row.replace("\\|", "").matches('|').count();
        let mut header = None;
        for line in tables.lines() {
            if !line.starts_with('|') {
                header = None;
                continue;
            }
            let n = cells(line);
            match header {
                None => header = Some(n),
                Some(h) => assert_eq!(n, h, "{line}"),
            }
        }
        for spec in &SCHEMA {
            assert!(tables.contains(&std::format!("\n### `{}`\n", spec.keyword)));
        }
        assert!(tables.ends_with('\n'));
        assert!(!tables.contains(TABLES_BEGIN) && !tables.contains(TABLES_END));
    }

    /// The block's value table is sized from the attribute lists, not by a constant kept
    /// in step with them by hand.
    #[test]
    fn table_sizes_come_from_the_schema() {
        let most = SCHEMA.iter().map(|s| s.attributes.len()).max();
        assert_eq!(Some(MAX_ATTRS), most);
        assert_eq!(MAX_ATTRS, 8);
        assert_eq!(MAX_NUMBERS, 3);
    }
}
