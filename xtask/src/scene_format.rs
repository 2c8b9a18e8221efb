//! `scene-format`: rewrites the generated part of `docs/scene-format.md`, the scene
//! language's reference tables, from the parser's schema
//! (`fixray::scene::schema::write_reference_tables`), between its two marker comments.
//! The rest of the document is written by hand. `tests/scene_format.rs` fails when the
//! document and the schema differ; then run
//!
//! ```text
//! cargo xtask scene-format
//! ```

use fixray::scene::schema::{TABLES_BEGIN, TABLES_END, write_reference_tables};

pub fn main() {
    let path = crate::root().join("docs/scene-format.md");
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    let mut tables = String::new();
    write_reference_tables(&mut tables).expect("writing to a String cannot fail");
    let updated = splice(&text, &tables).unwrap_or_else(|e| {
        eprintln!("{}: {e}", path.display());
        std::process::exit(1);
    });
    if updated == text {
        println!("{} is up to date", path.display());
    } else {
        std::fs::write(&path, &updated)
            .unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
        println!("{} rewritten", path.display());
    }
}

/// `text` with the lines between the marker lines replaced by `tables`.
fn splice(text: &str, tables: &str) -> Result<String, String> {
    let marker = |m: &str| {
        let mut lines = text.match_indices(m).filter(|&(i, _)| {
            let line_start = i == 0 || text.as_bytes()[i - 1] == b'\n';
            let line_end = text[i + m.len()..].starts_with('\n');
            line_start && line_end
        });
        match (lines.next(), lines.next()) {
            (Some((i, _)), None) => Ok(i),
            (None, _) => Err(format!("no line `{m}`")),
            (Some(_), Some(_)) => Err(format!("the line `{m}` is there twice")),
        }
    };
    let begin = marker(TABLES_BEGIN)? + TABLES_BEGIN.len() + 1;
    let end = marker(TABLES_END)?;
    if end < begin {
        return Err("the end marker comes before the begin marker".into());
    }
    Ok(format!("{}{tables}{}", &text[..begin], &text[end..]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_part_between_the_markers_changes() {
        let doc = format!("# Title\n\n{TABLES_BEGIN}\nold\nrows\n{TABLES_END}\n\nAfter.\n");
        let new = splice(&doc, "new\n").unwrap();
        assert_eq!(
            new,
            format!("# Title\n\n{TABLES_BEGIN}\nnew\n{TABLES_END}\n\nAfter.\n")
        );
        assert_eq!(splice(&new, "new\n").unwrap(), new);
    }

    #[test]
    fn missing_or_doubled_markers_are_errors() {
        assert!(splice("no markers\n", "x\n").is_err());
        let twice = format!("{TABLES_BEGIN}\n{TABLES_END}\n{TABLES_BEGIN}\n");
        assert!(splice(&twice, "x\n").is_err());
        let reversed = format!("{TABLES_END}\n{TABLES_BEGIN}\n");
        assert!(splice(&reversed, "x\n").is_err());
    }
}
