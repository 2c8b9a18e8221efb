//! The scene parser: the scene language ([`crate::scene::language`]), no_std, no allocator.
//! `lexer.rs` splits the text into tokens, `schema.rs` says which entities and attributes
//! there are (`reference.rs` writes the language's reference tables from it), this file
//! reads blocks by the schema, `builder.rs` turns each block into the scene's values
//! (`domain.rs` converts and checks each number, `scale.rs` holds the scale rule) and
//! `error.rs` says what went wrong where (`hints.rs` works out what a host's messages
//! add).
//!
//! Every bad input ends in a [`SceneError`] that names the line and column (1-based, in
//! characters) of the token at fault; no input makes the parser panic. The whole format is
//! read and checked; an entity whose stage this build leaves out (a cargo feature) is
//! refused with [`SceneErrorKind::NotBuiltIn`] after its block has been checked, never
//! ignored. A byte order mark that starts the text is skipped.
//!
//! A message is one line and says what to do where it can: the attributes an entity has
//! and the one a misspelt word most likely meant, the range of a number format and the
//! formats that hold a number beyond it, where a block that is not closed was opened
//! (at its `{`), an example camera for a scene without one, invisible characters
//! escaped (`\u{feff}`). A scene whose scale the format cannot resolve is refused
//! ([`crate::scene::MIN_SCALE_DELTAS`], [`crate::scene::MIN_RADIUS_SQ_DELTAS`]), naming
//! the formats that resolve every pitch and sphere of it. On bare metal (a chip's
//! firmware) the messages leave these hints out, for flash.
//!
//! ```
//! use fixray::{Scene, I16F16};
//! use fixray::scene::SceneErrorKind;
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

mod builder;
mod domain;
mod error;
mod hints;
mod lexer;
mod reference;
mod scale;
pub mod schema;

use heapless::Vec;

pub use error::{
    MAX_NUMBER, MAX_QUOTED, Quantity, Quoted, QuotedNumber, SceneError, SceneErrorKind,
    TextureProblem,
};

use crate::num::Decimal;
use crate::{Camera, Color, Rules, Scalar, Scene, Vec3};
use domain::{channel_colour, precision};
use error::Pos;
use lexer::{Lexer, Token, is_name, quote};
use schema::{Arity, Entity, MAX_ATTRS, MAX_NUMBERS};

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
    nums: [Number<'a>; MAX_NUMBERS],
    /// How many numbers were written (`specular S` or `specular R G B`).
    count: usize,
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
    // Out of line: one copy in flash, not one per call.
    #[inline(never)]
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
    // Out of line: one copy in flash, not one per call.
    #[inline(never)]
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
struct Parser<'a, 's, S, const O: usize, const M: usize, const L: usize> {
    lexer: Lexer<'a>,
    camera: Option<Camera<S>>,
    background: Option<Color<S>>,
    epsilon: Option<S>,
    /// The rule set, found before the blocks are read ([`rules_of`]).
    rules: Rules,
    /// The scene under construction (its camera is a placeholder until the end).
    scene: &'s mut Scene<S, O, M, L>,
    material_names: Vec<&'a str, M>,
    /// Names of every entity but materials, with their kind, for the uniqueness rule.
    object_names: Vec<(Entity, &'a str), O>,
    /// Names of the lights, with their kind.
    light_names: Vec<(Entity, &'a str), L>,
    /// Names of the textures.
    texture_names: Vec<&'a str, { crate::scene::MAX_TEXTURES }>,
    /// Where texture files come from ([`Scene::read_with`]).
    files: &'s mut dyn FnMut(&str) -> Option<&'static [u8]>,
    /// The scale rule's lengths ([`scale::Scales`]).
    scales: scale::Scales,
}

type Result<T> = core::result::Result<T, SceneError>;

impl<'a, S: Scalar, const O: usize, const M: usize, const L: usize> Parser<'a, '_, S, O, M, L> {
    fn expect(&mut self, what: &'static str) -> Result<Token<'a>> {
        let end = self.lexer.pos;
        self.lexer
            .next_token()
            .ok_or_else(|| end.error(SceneErrorKind::UnexpectedEnd(what)))
    }

    // Out of line: one copy in flash, not one per call.
    #[inline(never)]
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
        // The course reads a name with `%s`: any token but a brace (tri1 names a
        // triangle `tri`); the crate's own rules keep keywords and numbers out of names.
        let course_name = self.rules == Rules::Course && t.text != "{" && t.text != "}";
        if course_name || is_name(t.text) {
            Ok(t)
        } else {
            Err(t.pos.error(SceneErrorKind::ExpectedName(quote(t.text))))
        }
    }

    /// Reads a block into `out` (its entity and position set): in place, since a block's
    /// value table is the parser's largest local (a copy of it is stack on a chip).
    #[inline(never)]
    fn block(&mut self, out: &mut Block<'a>) -> Result<()> {
        let (entity, pos) = (out.entity, out.pos);
        let specs = entity.attributes();
        let name = self.name()?;
        let open = self.expect("`{`")?;
        if open.text != "{" {
            return Err(open
                .pos
                .error(SceneErrorKind::ExpectedOpenBrace(quote(open.text))));
        }
        out.name = name;
        let values = &mut out.values;
        // The attribute just read if its value was a name: `material m` followed by `{`
        // is the next block.
        let mut named: Option<&'static str> = None;
        let block = (entity, name, open.pos);
        loop {
            let end = self.lexer.pos;
            let Some(t) = self.lexer.next_token() else {
                if hints::HINTS
                    && let Some(e) = self.unclosed(None, (None, false), block)
                {
                    return Err(e);
                }
                return Err(end.error(SceneErrorKind::UnexpectedEnd("an attribute or `}`")));
            };
            if t.text == "}" {
                break;
            }
            let Some(i) = specs.iter().position(|s| s.is(t.text)) else {
                let after = if t.text == "{" { named } else { None };
                if hints::HINTS
                    && let Some(e) = self.unclosed(Some(&t), (after, false), block)
                {
                    return Err(e);
                }
                if let Some(what) = schema::NOT_YET.iter().find(|w| **w == t.text) {
                    return Err(t.pos.error(SceneErrorKind::NotSupportedYet(what)));
                }
                return Err(t.pos.error(SceneErrorKind::UnknownAttribute {
                    entity: entity.keyword(),
                    found: quote(t.text),
                }));
            };
            // The course reads a repeated attribute over the earlier one.
            if values[i].is_some() && self.rules == Rules::Fixray {
                // Unless it starts the next block (`material m {`).
                let keyword = Some(specs[i].name);
                if hints::HINTS
                    && let Some(e) = self.unclosed(Some(&t), (keyword, true), block)
                {
                    return Err(e);
                }
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
                Arity::Path => {
                    let t = self.expect("a file name")?;
                    if t.text == "{" || t.text == "}" {
                        return Err(t.pos.error(SceneErrorKind::ExpectedName(quote(t.text))));
                    }
                    v.name = Some(t);
                }
                Arity::Numbers(n) => {
                    let n = usize::from(n);
                    for slot in v.nums.iter_mut().take(n) {
                        *slot = self.number()?;
                    }
                    v.count = n;
                }
                Arity::OneOrThree => {
                    v.nums[0] = self.number()?;
                    v.count = 1;
                    let mut ahead = self.lexer.clone();
                    if let Some(next) = ahead.next_token()
                        && Decimal::parse(next.text).is_some()
                    {
                        if self.rules == Rules::Fixray {
                            return Err(next.pos.error(SceneErrorKind::OtherRules {
                                attribute: "specular R G B",
                                rules: "course",
                            }));
                        }
                        v.nums[1] = self.number()?;
                        v.nums[2] = self.number()?;
                        v.count = 3;
                    }
                }
            }
            values[i] = Some(v);
            if hints::HINTS {
                named = (specs[i].arity == Arity::Name).then_some(specs[i].name);
            }
        }
        for (spec, value) in specs.iter().zip(values.iter()) {
            if spec.required && value.is_none() {
                return Err(pos.error(SceneErrorKind::MissingAttribute {
                    entity: entity.keyword(),
                    attribute: spec.name,
                }));
            }
        }
        Ok(())
    }

    /// The error of a block of `entity` named `name`, opened at `open`, that is not
    /// closed, if `t`, read where the block expects an attribute or `}`, shows it: the end
    /// of the input (`t` is `None`), or the start of the next statement. That is a keyword
    /// of the format at the start of a line, an entity keyword followed by a name and `{`,
    /// or a block whose keyword was read as an attribute (`keyword`: at its `{`, or, with
    /// `ahead`, when a name and `{` follow: `material m {`). The error is at the block's
    /// `{`. Not looked for on bare metal ([`hints::HINTS`]: the end of the input and the
    /// next statement's first word are then reported as they are). Out of line: only ever
    /// on the way to an error.
    #[cold]
    #[inline(never)]
    fn unclosed(
        &self,
        t: Option<&Token<'a>>,
        (keyword, ahead): (Option<&'static str>, bool),
        (entity, name, open): (Entity, Token<'a>, Pos),
    ) -> Option<SceneError> {
        if !hints::HINTS {
            return None;
        }
        let next = match t {
            None => None,
            Some(t) => Some(match keyword {
                Some(k) => self::keyword(k).filter(|_| !ahead || self.opens_block())?,
                None => {
                    self::keyword(t.text).filter(|_| t.pos.column == 1 || self.opens_block())?
                }
            }),
        };
        // `keyword name`, cut to a quoted token's length.
        let mut block = Quoted::new();
        let _ = block.push_str(entity.keyword());
        let _ = block.push(' ');
        for c in quote(name.text).chars() {
            if block.len() + c.len_utf8() > MAX_QUOTED - '…'.len_utf8() {
                let _ = block.push('…');
                break;
            }
            let _ = block.push(c);
        }
        Some(open.error(SceneErrorKind::Unclosed { block, next }))
    }

    /// Whether the next two tokens are a name and `{`.
    #[inline(never)]
    fn opens_block(&self) -> bool {
        let mut ahead = self.lexer.clone();
        ahead
            .next_token()
            .is_some_and(|n| n.text != "{" && n.text != "}")
            && ahead.next_token().is_some_and(|b| b.text == "{")
    }

    /// Registers a name for the uniqueness rule (materials have their own list).
    fn register(&mut self, block: &Block<'a>) -> Result<()> {
        // The course allows a name twice (a lookup takes the first).
        if self.rules == Rules::Course {
            return Ok(());
        }
        let name = block.name.text;
        let light = matches!(
            block.entity,
            Entity::Light | Entity::Spotlight | Entity::Projector
        );
        let taken =
            |list: &[(Entity, &str)]| list.iter().any(|&(e, n)| e == block.entity && n == name);
        let duplicate = if light {
            taken(&self.light_names)
        } else {
            taken(&self.object_names)
        };
        if duplicate {
            return Err(block.name.pos.error(SceneErrorKind::DuplicateName {
                entity: block.entity.keyword(),
                name: quote(name),
            }));
        }
        // The lists have the capacities of the scene's: full here is full there.
        let entry = (block.entity, name);
        let pushed = if light {
            self.light_names.push(entry).is_ok()
        } else {
            self.object_names.push(entry).is_ok()
        };
        if pushed {
            Ok(())
        } else if light {
            Err(too_many(block, "lights", L, "LIGHTS"))
        } else {
            Err(too_many(block, "objects", O, "OBJECTS"))
        }
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
        // A length the format does not resolve, kept on a host, comes first.
        let statements = self.statements();
        self.scales.finish(statements)?;
        let camera = self
            .camera
            .ok_or_else(|| self.lexer.pos.error(SceneErrorKind::MissingCamera))?;
        self.scene.camera = camera;
        self.scene.background = self.background.unwrap_or([S::ZERO; 3]);
        self.scene.epsilon = self.epsilon.unwrap_or(S::DEFAULT_EPSILON);
        self.scene.set_rules(self.rules);
        Ok(())
    }

    /// Reads every statement of the text into the scene. Inlined: its frame is the
    /// parse's, as one function's (stack on a chip).
    #[inline(always)]
    fn statements(&mut self) -> Result<()> {
        while let Some(t) = self.lexer.next_token() {
            match t.text {
                "background" => {
                    let mut nums = [Number::default(); MAX_NUMBERS];
                    for n in &mut nums {
                        *n = self.number()?;
                    }
                    let c = channel_colour(&nums, "background", self.rules)?;
                    if self.background.replace(c).is_some() {
                        return Err(t.pos.error(SceneErrorKind::Duplicate("background")));
                    }
                }
                "rules" => {
                    // Read (and checked) before the blocks: `rules_of`.
                    self.expect("a rule set")?;
                }
                "precision" => {
                    let eps = precision::<S>(&self.number()?)?;
                    if self.epsilon.replace(eps).is_some() {
                        return Err(t.pos.error(SceneErrorKind::Duplicate("precision")));
                    }
                }
                _ => {
                    if let Some(what) = schema::NOT_YET.iter().find(|w| **w == t.text) {
                        return Err(t.pos.error(SceneErrorKind::NotSupportedYet(what)));
                    }
                    let Some(entity) = Entity::from_keyword(t.text) else {
                        return Err(t.pos.error(SceneErrorKind::UnknownKeyword(quote(t.text))));
                    };
                    let mut block = Block {
                        entity,
                        pos: t.pos,
                        name: t,
                        values: [None; MAX_ATTRS],
                    };
                    self.block(&mut block)?;
                    self.entity(&block)?;
                }
            }
        }
        Ok(())
    }
}

/// The keyword of the format that `word` is, as the schema spells it.
fn keyword(word: &str) -> Option<&'static str> {
    schema::keywords().find(|k| *k == word)
}

/// The rule set of a scene text: its top-level `rules` statement, [`Rules::Course`]
/// without one. Found before anything else is read, since it decides how the blocks are
/// read (wherever the statement stands).
fn rules_of(text: &str) -> Result<Rules> {
    let mut lexer = Lexer::new(text);
    let mut depth = 0u32;
    let mut found: Option<Rules> = None;
    while let Some(t) = lexer.next_token() {
        match t.text {
            "{" => depth = depth.saturating_add(1),
            "}" => depth = depth.saturating_sub(1),
            "rules" if depth == 0 => {
                let end = lexer.pos;
                let name = lexer
                    .next_token()
                    .ok_or_else(|| end.error(SceneErrorKind::UnexpectedEnd("a rule set")))?;
                let rules = name.text.parse::<Rules>().map_err(|_| {
                    name.pos
                        .error(SceneErrorKind::UnknownRules(quote(name.text)))
                })?;
                if found.replace(rules).is_some() {
                    return Err(t.pos.error(SceneErrorKind::Duplicate("rules")));
                }
            }
            _ => {}
        }
    }
    Ok(found.unwrap_or(Rules::Course))
}

fn placeholder_camera<S: Scalar>() -> Camera<S> {
    Camera {
        width: 1,
        height: 1,
        world_width: S::ONE,
        world_height: S::ONE,
        viewpoint: Vec3::new(S::ZERO, S::ZERO, S::ONE),
        grid: crate::PixelGrid::Centres,
    }
}

/// The error of a block beyond a capacity of the scene's type.
fn too_many(
    block: &Block<'_>,
    what: &'static str,
    capacity: usize,
    parameter: &'static str,
) -> SceneError {
    block.error(SceneErrorKind::TooMany {
        what,
        capacity,
        parameter,
    })
}

impl<S: Scalar, const O: usize, const M: usize, const L: usize> Scene<S, O, M, L> {
    /// Reads a scene in the scene language ([`crate::scene::language`]).
    ///
    /// # Errors
    /// A [`SceneError`] with the line and column of the first problem.
    pub fn parse(text: &str) -> core::result::Result<Self, SceneError> {
        let mut scene = Scene::empty();
        scene.read(text)?;
        Ok(scene)
    }

    /// Reads a scene by the rule set `rules`, whatever its `rules` statement says (a
    /// tool's `--rules` override): the file is read as that rule set reads it (the
    /// course's duplicates, `specular R G B`, its glint without `shininess`, ...) and
    /// drawn by it.
    ///
    /// # Errors
    /// A [`SceneError`] with the line and column of the first problem.
    ///
    /// ```
    /// use fixray::{Scene, I16F16};
    /// use fixray::scene::Rules;
    ///
    /// let text = "rules course camera c { pixeldim 4 3 worlddim 4 3 viewpoint 2 1.5 5 }";
    /// let scene = Scene::<I16F16>::parse_as(text, Rules::Fixray).unwrap();
    /// assert_eq!(scene.rules(), Rules::Fixray);
    /// ```
    pub fn parse_as(text: &str, rules: Rules) -> core::result::Result<Self, SceneError> {
        let mut scene = Scene::empty();
        scene.read_by(text, Some(rules))?;
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
        self.textures.clear();
        self.projectors.clear();
        self.background = [S::ZERO; 3];
        self.epsilon = S::DEFAULT_EPSILON;
        self.set_rules(Rules::Fixray);
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
    pub fn read(&mut self, text: &str) -> core::result::Result<(), SceneError> {
        self.read_by(text, None)
    }

    /// [`Scene::read`] by the rule set `rules` if given ([`Scene::parse_as`]), else by
    /// the file's.
    fn read_by(
        &mut self,
        text: &str,
        rules: Option<Rules>,
    ) -> core::result::Result<(), SceneError> {
        self.read_with(text, rules, &mut |_| None)
    }

    /// Reads a scene whose `texture` entities name image files: `files` returns the bytes
    /// of the file a `filename` names (a binary PPM, borrowed for the program's life:
    /// `include_bytes!` on a chip, or bytes the caller leaks or keeps in a `static`), or
    /// `None` when there is no such file. [`Scene::read`] and [`Scene::parse`] read no
    /// files: there a `texture` is an error that names its file. On a host,
    /// `fixray::scene::files::beside` (cargo feature `std`) reads the files beside the
    /// scene file. `rules` overrides the file's rule set, as in [`Scene::parse_as`].
    ///
    /// # Errors
    /// A [`SceneError`] with the line and column of the first problem (a missing or
    /// malformed image: [`SceneErrorKind::TextureFile`], at its file name); the scene is
    /// then left empty.
    ///
    /// ```
    /// # #[cfg(feature = "textures")] {
    /// use fixray::{Scene, I16F16};
    ///
    /// static CHECKER: &[u8] = b"P6 2 2 255\n\xff\xff\xff\x00\x00\x00\x00\x00\x00\xff\xff\xff";
    /// let text = "camera c { pixeldim 4 3 worlddim 4 3 viewpoint 2 1.5 5 }
    ///     material m { ambient 1 1 1 }
    ///     texture checker { filename checker.ppm }
    ///     texplane wall { material m normal 0 0 1 point 0 0 -1 xdir 1 0 0
    ///                     dimensions 4 3 texname checker mode 0 }";
    /// let mut scene = Scene::<I16F16>::empty();
    /// scene
    ///     .read_with(text, None, &mut |name| (name == "checker.ppm").then_some(CHECKER))
    ///     .unwrap();
    /// assert_eq!(scene.textures[0].width(), 2);
    /// let err = Scene::<I16F16>::parse(text).unwrap_err();
    /// assert_eq!((err.line, err.column), (3, 32));
    /// # }
    /// ```
    #[inline(never)]
    pub fn read_with(
        &mut self,
        text: &str,
        rules: Option<Rules>,
        files: &mut dyn FnMut(&str) -> Option<&'static [u8]>,
    ) -> core::result::Result<(), SceneError> {
        self.clear();
        // A byte order mark that starts the text is skipped (some editors write one; it
        // is not part of the scene): the first character after it is at column 1.
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let found = rules_of(text);
        let result = found.map(|r| rules.unwrap_or(r)).and_then(|rules| {
            // Without the course's tracer, a course file is refused at its start.
            if rules == Rules::Course && !cfg!(feature = "course") {
                return Err(Lexer::new(text).pos.error(SceneErrorKind::NotBuiltIn {
                    what: "the course's rules (a file without `rules fixray` is read by them) are",
                    feature: "course",
                }));
            }
            Parser {
                lexer: Lexer::new(text),
                camera: None,
                background: None,
                epsilon: None,
                rules,
                scene: self,
                material_names: Vec::new(),
                object_names: Vec::new(),
                light_names: Vec::new(),
                texture_names: Vec::new(),
                files,
                scales: scale::Scales::new(),
            }
            .parse()
        });
        if result.is_err() {
            self.clear();
        }
        result
    }
}
