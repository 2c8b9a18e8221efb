//! The schema of the scene format: every entity with its keyword and attributes, as
//! `scene-format.md` lists them, in one table ([`SCHEMA`]). The lexer's keywords, the
//! unknown-keyword message and the size of a block's value table all come from it.
//!
//! A new entity is a variant of [`Entity`], a row of [`SCHEMA`] and an arm of the builder
//! (`builder.rs`).

/// The entity kinds of the scene format (in the order of [`SCHEMA`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Entity {
    Camera,
    Material,
    Light,
    Spotlight,
    Plane,
    Sphere,
    TiledPlane,
    FPlane,
    Triangle,
    Tri,
    Texture,
    TexPlane,
    Projector,
    Revsurf,
}

/// How an attribute's value is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Arity {
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
pub(super) struct AttrSpec {
    pub(super) name: &'static str,
    pub(super) arity: Arity,
    pub(super) required: bool,
    /// Real files also spell it with a final `s` added or dropped (`dimension` /
    /// `dimensions`). A flag, not the other spelling: the table is in a chip's flash, and
    /// without a second string an entry takes 12 bytes instead of 28.
    pub(super) either_number: bool,
}

impl AttrSpec {
    /// Whether `word` names this attribute.
    pub(super) fn is(&self, word: &str) -> bool {
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
pub(super) struct EntitySpec {
    pub(super) entity: Entity,
    pub(super) keyword: &'static str,
    pub(super) attributes: &'static [AttrSpec],
}

/// Every entity of the format.
pub(super) const SCHEMA: [EntitySpec; 14] = [
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

/// The statements outside blocks (`background R G B`, `precision EPS`, `rules NAME`).
pub(super) const STATEMENTS: [&str; 3] = ["background", "precision", "rules"];

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
    pub(super) fn from_keyword(word: &str) -> Option<Self> {
        SCHEMA.iter().find(|s| s.keyword == word).map(|s| s.entity)
    }

    fn spec(self) -> &'static EntitySpec {
        // SCHEMA is in the order of the variants (checked at compile time, above).
        &SCHEMA[self as usize]
    }

    /// The keyword.
    pub(super) fn keyword(self) -> &'static str {
        self.spec().keyword
    }

    /// The attributes, as `scene-format.md` lists them.
    pub(super) fn attributes(self) -> &'static [AttrSpec] {
        self.spec().attributes
    }
}

/// Every keyword that may start a statement: the entities', then the statements'.
pub(super) fn keywords() -> impl Iterator<Item = &'static str> + Clone {
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

    /// Regression: the block's value table was sized by a constant kept in step with the
    /// attribute lists by hand.
    #[test]
    fn table_sizes_come_from_the_schema() {
        let most = SCHEMA.iter().map(|s| s.attributes.len()).max();
        assert_eq!(Some(MAX_ATTRS), most);
        assert_eq!(MAX_ATTRS, 8);
        assert_eq!(MAX_NUMBERS, 3);
    }
}
