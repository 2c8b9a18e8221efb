//! The scene language's reference, `docs/scene-format.md`, against the crate: its
//! generated tables must be what the schema writes now, and every `scene` example in it
//! must be a complete scene that the parser reads, in f64 and in I16F16.
//!
//! ```text
//! cargo test --test scene_format
//! ```

use fixray::scene::schema::{self, SCHEMA, TABLES_BEGIN, TABLES_END};
use fixray::{I16F16, Scalar, Scene, SceneError};

/// The document, as the repository holds it.
const DOC: &str = include_str!("../docs/scene-format.md");

/// A 2×2 binary PPM: every texture file an example names is this image.
static TEXTURE: &[u8] = b"P6 2 2 255\n\xff\xff\xff\x00\x00\x00\x00\x00\x00\xff\xff\xff";

/// The part of `doc` between the marker lines, and the line of `doc` it starts on.
fn generated_part(doc: &str) -> (&str, usize) {
    let begin = doc
        .find(&format!("{TABLES_BEGIN}\n"))
        .expect("docs/scene-format.md has no begin marker line")
        + TABLES_BEGIN.len()
        + 1;
    let end = doc[begin..]
        .find(&format!("\n{TABLES_END}\n"))
        .map(|i| begin + i + 1)
        .or_else(|| doc[begin..].starts_with(TABLES_END).then_some(begin))
        .expect("docs/scene-format.md has no end marker line after the begin marker");
    (&doc[begin..end], doc[..begin].lines().count() + 1)
}

/// Where `doc`'s generated part differs from `tables`: `None` when it does not, else a
/// message naming the first differing line.
fn tables_mismatch(doc: &str, tables: &str) -> Option<String> {
    let (part, first_line) = generated_part(doc);
    if part == tables {
        return None;
    }
    let mut doc_lines = part.lines();
    let mut schema_lines = tables.lines();
    let mut line = first_line;
    loop {
        match (doc_lines.next(), schema_lines.next()) {
            (Some(a), Some(b)) if a == b => line += 1,
            (a, b) => {
                return Some(format!(
                    "docs/scene-format.md's schema tables differ from the schema: run \
                     `cargo xtask scene-format`\n  line {line} of the document:\n    {}\n  \
                     the schema writes:\n    {}",
                    a.unwrap_or("(the end of the tables)"),
                    b.unwrap_or("(the end of the tables)"),
                ));
            }
        }
    }
}

fn reference_tables() -> String {
    let mut tables = String::new();
    schema::write_reference_tables(&mut tables).expect("writing to a String cannot fail");
    tables
}

#[test]
fn the_documents_tables_are_the_schemas() {
    if let Some(message) = tables_mismatch(DOC, &reference_tables()) {
        panic!("{message}");
    }
}

/// The check above catches a table edited by hand, a row the schema no longer has, and a
/// generated part left empty.
#[test]
fn an_edited_table_is_caught() {
    let tables = reference_tables();
    let edited = DOC.replacen("| `radius` | `R` | yes |", "| `radius` | `R` | no |", 1);
    assert_ne!(edited, DOC, "the document has a row for `radius`");
    let message = tables_mismatch(&edited, &tables).expect("an edited row is a mismatch");
    assert!(
        message.contains("run `cargo xtask scene-format`"),
        "{message}"
    );
    let radius_line = 1 + DOC
        .lines()
        .position(|l| l.starts_with("| `radius` |"))
        .expect("a row for `radius`");
    assert!(
        message.contains(&format!("line {radius_line} of the document:\n")),
        "{message}"
    );

    let (part, _) = generated_part(DOC);
    let emptied = DOC.replacen(part, "", 1);
    assert!(tables_mismatch(&emptied, &tables).is_some());
    let extra = DOC.replacen(part, &format!("{part}| `extra` | | | | |\n"), 1);
    assert!(tables_mismatch(&extra, &tables).is_some());
}

/// A ```scene block of the document: its text and the line of its first scene line.
struct Example {
    text: String,
    line: usize,
}

/// Every fenced block labelled `scene`.
fn examples(doc: &str) -> Vec<Example> {
    let mut found = Vec::new();
    let mut current: Option<Example> = None;
    for (i, line) in doc.lines().enumerate() {
        match current.as_mut() {
            None if line.trim_start().starts_with("```scene") => {
                current = Some(Example {
                    text: String::new(),
                    line: i + 2,
                });
            }
            None => {}
            Some(_) if line.trim_start().starts_with("```") => {
                found.extend(current.take());
            }
            Some(example) => {
                example.text.push_str(line);
                example.text.push('\n');
            }
        }
    }
    assert!(current.is_none(), "a ```scene block is not closed");
    found
}

/// Reads an example in format `S`, every texture file being [`TEXTURE`].
fn read<S: Scalar>(text: &str) -> Result<Scene<S>, SceneError> {
    let mut scene = Scene::<S>::empty();
    scene.read_with(text, None, &mut |_| Some(TEXTURE))?;
    Ok(scene)
}

/// Reads an example in format `S`; on an error, the line of the document it is on.
fn read_example<S: Scalar>(example: &Example) -> Result<Scene<S>, String> {
    read::<S>(&example.text).map_err(|e| {
        let line = example.line + usize::try_from(e.line).unwrap_or(1) - 1;
        format!(
            "docs/scene-format.md:{line}:{}: the example does not parse in {}: {}",
            e.column,
            S::NAME,
            e.kind
        )
    })
}

#[test]
fn every_example_is_a_valid_scene() {
    let examples = examples(DOC);
    assert!(examples.len() >= 5, "{} examples", examples.len());
    let mut errors = Vec::new();
    for example in &examples {
        let reference = read_example::<f64>(example);
        let fixed = read_example::<I16F16>(example);
        match (reference, fixed) {
            (Ok(a), Ok(b)) => {
                assert_eq!(a.objects.len(), b.objects.len(), "line {}", example.line);
                assert_eq!(a.rules(), b.rules(), "line {}", example.line);
            }
            (a, b) => errors.extend(a.err().into_iter().chain(b.err())),
        }
    }
    assert!(errors.is_empty(), "{}", errors.join("\n"));
}

/// The error message names the example's line in the document, not the scene's.
#[test]
fn an_examples_error_names_its_line_in_the_document() {
    let doc = "text\n\n```scene\nrules fixray\ncamera c { pixeldim 4 0 worlddim 4 3 viewpoint 2 1.5 5 }\n```\n";
    let examples = examples(doc);
    assert_eq!(examples.len(), 1);
    assert_eq!(examples[0].line, 4);
    let message = read_example::<f64>(&examples[0]).unwrap_err();
    assert!(
        message.starts_with("docs/scene-format.md:5:23: "),
        "{message}"
    );
}

/// Between them, the examples show every entity and statement of the language.
#[test]
fn the_examples_show_every_keyword() {
    let examples = examples(DOC);
    let words: Vec<&str> = examples
        .iter()
        .flat_map(|e| e.text.split_whitespace())
        .collect();
    let missing: Vec<&str> = schema::keywords().filter(|k| !words.contains(k)).collect();
    assert!(missing.is_empty(), "no example uses {missing:?}");
    // And both rule sets: one example without `rules` (a course file), one with `fixray`.
    let rules = |e: &Example| read::<f64>(&e.text).map(|s| s.rules()).ok();
    assert!(
        examples
            .iter()
            .any(|e| rules(e) == Some(fixray::scene::Rules::Course))
    );
    assert!(
        examples
            .iter()
            .any(|e| rules(e) == Some(fixray::scene::Rules::Fixray))
    );
}

/// Every entity has a section of its own in the document.
#[test]
fn every_entity_has_a_section() {
    for spec in &SCHEMA {
        let heading = format!("\n### `{}`\n", spec.keyword);
        assert!(DOC.contains(&heading), "no section {heading:?}");
    }
}

/// Rustdoc compiles and runs the document's unlabelled and `rust` blocks: every block is
/// labelled, and only the `rust` ones are Rust.
#[test]
fn every_code_block_is_labelled() {
    let mut open = false;
    for (i, line) in DOC.lines().enumerate() {
        let Some(rest) = line.trim_start().strip_prefix("```") else {
            continue;
        };
        if !open {
            assert!(
                ["scene", "text", "rust"].contains(&rest.trim()),
                "docs/scene-format.md:{}: a code block labelled {rest:?}",
                i + 1
            );
        }
        open = !open;
    }
    assert!(!open, "a code block is not closed");
}

/// The README's scene examples parse too (in f64 and I16F16).
#[test]
fn the_readmes_scene_examples_are_valid() {
    let readme = include_str!("../README.md");
    let examples = examples(readme);
    assert!(!examples.is_empty(), "the README shows a scene");
    for example in &examples {
        for result in [
            read_example::<f64>(example).map(|_| ()),
            read_example::<I16F16>(example).map(|_| ()),
        ] {
            result.unwrap_or_else(|e| panic!("README.md (not the scene language): {e}"));
        }
    }
}
