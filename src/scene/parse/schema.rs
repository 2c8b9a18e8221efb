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
//! (`builder.rs`) and its descriptions for the reference (beside [`write_reference_tables`],
//! in `reference.rs`; a unit test names any attribute left without one).

pub use super::reference::{TABLES_BEGIN, TABLES_END, write_reference_tables};

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
