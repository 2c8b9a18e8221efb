//! `cargo xtask figures [--check]`: the measured figures of `README.md` and `docs/`,
//! written from measurements, never by hand.
//!
//! Each table of figures in those documents sits between `<!-- figures: NAME -->` and
//! `<!-- end figures -->`. Its rows come from:
//! - the reports the firmware tests leave in `target/` (`cargo test --release --test
//!   firmware -- --ignored`): instructions counted under QEMU's `-icount shift=0`, flash
//!   and RAM, all deterministic for one toolchain and lock file;
//! - the RP2040 board's emulated run, `target/board-report.md` (`cargo test --release
//!   --test board -- --ignored`): cycles counted by rp2040js, deterministic too;
//! - the Cortex-M0 firmware's own output, `target/firmware-m0.txt` (`cargo run --release
//!   --example firmware --target thumbv6m-none-eabi > target/firmware-m0.txt`);
//! - host renders (the share of pixels that differ from f64: deterministic), and the
//!   course's table, `target/course-table.md` (`course/table.sh > target/course-table.md`).
//!
//! Without `--check` the blocks are rewritten in place. With it nothing is written and the
//! command fails, naming the block, when a committed block differs from what the
//! measurements give: a word, a hash, or a number by more than [`NUMBER_TOLERANCE`]
//! (CI runs it after the firmware tests).

use std::fmt::Write as _;

use fixray::{Scalar, Scene, compare::compare};

/// A report file in `target/`, or the reason it is missing.
fn report(name: &str) -> Result<String, String> {
    let path = crate::root().join("target").join(name);
    std::fs::read_to_string(&path).map_err(|e| {
        format!(
            "target/{name}: {e} (run `cargo test --release --test firmware -- --ignored`, \
             `cargo test --release --test board -- --ignored` and `cargo run --release \
             --example firmware --target thumbv6m-none-eabi > target/firmware-m0.txt` first)"
        )
    })
}

/// The rows of a markdown table whose first cells are `keys`.
fn rows<'a>(table: &'a str, keys: &[&str]) -> Vec<Vec<&'a str>> {
    table
        .lines()
        .map(|l| {
            l.trim()
                .trim_matches('|')
                .split('|')
                .map(str::trim)
                .collect::<Vec<_>>()
        })
        .filter(|cells| cells.len() >= keys.len() && cells.iter().zip(keys).all(|(c, k)| c == k))
        .collect()
}

/// The share of pixels of `text` drawn in `S` that differ from its f64 render, in %.
fn differ_from_f64<S: Scalar>(text: &str) -> f64 {
    let fixed = Scene::<S>::parse(text).expect("a shipped scene parses");
    let reference = Scene::<f64>::parse(text).expect("a shipped scene parses");
    100.0 * compare(&fixed, &reference, |_, _, _, _| {}).differing_share()
}

/// `2^k` written with a superscript exponent.
fn power_of_two(k: f64) -> String {
    let digits: String = format!("{k}")
        .chars()
        .map(|c| match c {
            '-' => '⁻',
            '0' => '⁰',
            '1' => '¹',
            '2' => '²',
            '3' => '³',
            '4' => '⁴',
            '5' => '⁵',
            '6' => '⁶',
            '7' => '⁷',
            '8' => '⁸',
            '9' => '⁹',
            c => c,
        })
        .collect();
    format!("2{digits}")
}

/// A format's range and resolution, as `(±MAX, DELTA)` written for people.
fn range_and_delta<S: Scalar>() -> (String, String) {
    let max = S::MAX.to_f64();
    let k = max.log2().round();
    let range = if (max - k.exp2()).abs() <= max * 1e-9 {
        power_of_two(k)
    } else {
        format!("{max:.1e}")
    };
    (
        format!("±{range}"),
        power_of_two(S::DELTA.to_f64().log2().round()),
    )
}

/// README: every format, its range, its resolution, its accuracy on the default and boing
/// scenes, and its cost on the three cores.
fn formats() -> Result<String, String> {
    let firmware = report("firmware-report.md")?;
    let default = include_str!("../../scenes/default.scene");
    let boing = include_str!("../../scenes/boing.scene");
    let mut out = String::from(
        "| format | what | range | resolution (`DELTA`) | pixels ≠ f64, default | pixels ≠ f64, \
         boing | Cortex-M0 | Cortex-M4F | RISC-V |\n|---|---|---|---|---|---|---|---|---|\n",
    );
    for (name, what) in fixray::num::formats::DESCRIBED {
        let (range, delta) = fixray::with_format!(name, range_and_delta()).expect("listed");
        let d = fixray::with_format!(name, differ_from_f64(default)).expect("listed");
        let b = fixray::with_format!(name, differ_from_f64(boing)).expect("listed");
        let cost = |core: &str| {
            rows(&firmware, &[core, name, "default"])
                .first()
                .map_or("—".to_string(), |r| r[4].to_string())
        };
        writeln!(
            out,
            "| `{name}` | {what} | {range} | {delta} | {d:.3} % | {b:.3} % | {} | {} | {} |",
            cost("cortex-m0"),
            cost("cortex-m4f"),
            cost("riscv32imc")
        )
        .unwrap();
    }
    Ok(out)
}

/// README: the M0 firmware's lines for the default scene and the boing ball's first frame,
/// in I16F16, as it prints them.
fn sample() -> Result<String, String> {
    let output = report("firmware-m0.txt")?;
    let pick = |scene: &str, frame: Option<&str>| {
        output
            .lines()
            .find(|l| {
                let words: Vec<&str> = l.split_whitespace().collect();
                words.contains(&"format=i16f16")
                    && words.contains(&format!("scene={scene}").as_str())
                    && frame.is_none_or(|k| words.contains(&format!("frame={k}").as_str()))
            })
            .map(str::to_string)
            .ok_or(format!(
                "target/firmware-m0.txt has no i16f16 line for {scene}"
            ))
    };
    Ok(format!(
        "```text\n{}\n{}\n```\n",
        pick("default", None)?,
        pick("boing", Some("0"))?
    ))
}

/// README: the boing ball's mean cost per core, in I16F16 and f32.
fn boing() -> Result<String, String> {
    let table = report("boing-report.md")?;
    let mut out =
        String::from("| format | Cortex-M0 | Cortex-M4F | RISC-V rv32imc |\n|---|---|---|---|\n");
    for format in ["i16f16", "f32"] {
        let row = rows(&table, &[format, "**mean**"]);
        let row = row
            .first()
            .ok_or(format!("boing-report.md has no mean for {format}"))?;
        let plain = |cell: &str| cell.trim_matches('*').to_string();
        writeln!(
            out,
            "| {format} | {} | {} | {} |",
            plain(row[2]),
            plain(row[3]),
            plain(row[4])
        )
        .unwrap();
    }
    Ok(out)
}

/// One block: its document, its name, and how its text is made.
type Block = (&'static str, &'static str, fn() -> Result<String, String>);

/// A report in `target/` as it is (a table the firmware tests wrote).
macro_rules! verbatim {
    ($file:literal) => {
        || report($file)
    };
}

const BLOCKS: [Block; 15] = [
    ("README.md", "formats", formats),
    ("README.md", "sample", sample),
    ("README.md", "boing", boing),
    ("README.md", "board", verbatim!("board-report.md")),
    (
        "docs/performance.md",
        "cores",
        verbatim!("firmware-report.md"),
    ),
    ("docs/performance.md", "boing", verbatim!("boing-report.md")),
    ("docs/performance.md", "board", verbatim!("board-report.md")),
    (
        "docs/performance.md",
        "orbit",
        verbatim!("board-orbit-report.md"),
    ),
    (
        "docs/performance.md",
        "features",
        verbatim!("effects-report.md"),
    ),
    ("docs/performance.md", "lean", verbatim!("lean-report.md")),
    (
        "docs/performance.md",
        "entities",
        verbatim!("course-entities-report.md"),
    ),
    ("docs/course.md", "course", verbatim!("course-table.md")),
    (
        "docs/accuracy.md",
        "sampling",
        || Ok(crate::blocks::table()),
    ),
    ("docs/advisor.md", "advice", crate::advice::table),
    (
        "docs/accuracy.md",
        "sampling-cost",
        crate::advice::sampling_costs,
    ),
];

const END: &str = "<!-- end figures -->";

/// How far a committed number may lie from the measured one, relative: the instruction
/// counts are exact for one emulator, but QEMU's timer (the Arm cores count SysTick ticks
/// of 40 or 62.5 instructions) differs slightly between QEMU versions. Hashes, names and
/// every other word must be equal.
const NUMBER_TOLERANCE: f64 = 0.005;

/// Whether a committed block says what the measured one says: the same words, and numbers
/// within [`NUMBER_TOLERANCE`] of each other.
pub(crate) fn agree(committed: &str, measured: &str) -> bool {
    let number = |w: &str| -> Option<f64> {
        let w = w.trim_matches(|c: char| c == '*' || c == '(' || c == ')' || c == '%');
        let w = w.rsplit_once('=').map_or(w, |(_, v)| v);
        if w.starts_with("0x") {
            return None;
        }
        w.replace(',', "").parse().ok()
    };
    let (a, b): (Vec<&str>, Vec<&str>) = (
        committed.split_whitespace().collect(),
        measured.split_whitespace().collect(),
    );
    a.len() == b.len()
        && a.iter().zip(&b).all(|(x, y)| {
            x == y
                || x.rsplit_once('=').map(|p| p.0) == y.rsplit_once('=').map(|p| p.0)
                    && match (number(x), number(y)) {
                        (Some(u), Some(v)) => {
                            (u - v).abs() <= NUMBER_TOLERANCE * u.abs().max(v.abs())
                        }
                        _ => false,
                    }
        })
}

/// Where block `name`'s text lies in `text` (between its marker line and the end marker).
fn span(text: &str, name: &str) -> Result<std::ops::Range<usize>, String> {
    let open = format!("<!-- figures: {name} -->\n");
    let start = text
        .find(&open)
        .ok_or(format!("no `{}` marker", open.trim()))?
        + open.len();
    let end = text[start..]
        .find(END)
        .map(|e| start + e)
        .ok_or(format!("`{}` has no `{END}`", open.trim()))?;
    Ok(start..end)
}

pub fn main(args: &[String]) {
    let check = match args {
        [] => false,
        [flag] if flag == "--check" => true,
        _ => {
            eprintln!("usage: cargo xtask figures [--check]");
            std::process::exit(2);
        }
    };
    let mut failures = Vec::new();
    let mut documents: Vec<(&str, String)> = Vec::new();
    for (doc, name, make) in BLOCKS {
        if !documents.iter().any(|(d, _)| *d == doc) {
            let text = std::fs::read_to_string(crate::root().join(doc))
                .unwrap_or_else(|e| panic!("{doc}: {e}"));
            documents.push((doc, text));
        }
        let text = &mut documents
            .iter_mut()
            .find(|(d, _)| *d == doc)
            .expect("read")
            .1;
        let outcome = make().and_then(|body| Ok((span(text, name)?, body)));
        match outcome {
            Err(e) => failures.push(format!("{doc}, figures `{name}`: {e}")),
            Ok((range, body)) if text[range.clone()] != body => {
                if check && !agree(&text[range.clone()], &body) {
                    failures.push(format!(
                        "{doc}, figures `{name}` differ from the measurements (run `cargo \
                         xtask figures` and commit):\n--- committed\n{}--- measured\n{body}",
                        &text[range]
                    ));
                } else if !check {
                    text.replace_range(range, &body);
                }
            }
            Ok(_) => {}
        }
    }
    if !check {
        for (doc, text) in &documents {
            std::fs::write(crate::root().join(doc), text).unwrap_or_else(|e| panic!("{doc}: {e}"));
        }
        println!("figures written: {}", BLOCKS.len() - failures.len());
    }
    if !failures.is_empty() {
        for f in &failures {
            eprintln!("{f}");
        }
        std::process::exit(1);
    }
}

#[cfg(test)]
mod tests {
    use super::agree;

    #[test]
    fn numbers_agree_within_the_tolerance_and_words_exactly() {
        let line = "format=i16f16 hash=0x7efa0cd2 per_pixel=1922.3 | 1,943 |";
        assert!(agree(line, line));
        assert!(agree(
            line,
            "format=i16f16 hash=0x7efa0cd2 per_pixel=1922.5 | 1,944 |"
        ));
        assert!(!agree(
            line,
            "format=i16f16 hash=0x7efa0cd2 per_pixel=1950.0 | 1,943 |"
        ));
        assert!(!agree(
            line,
            "format=i16f16 hash=0x7efa0cd3 per_pixel=1922.3 | 1,943 |"
        ));
        assert!(!agree(
            line,
            "format=f32 hash=0x7efa0cd2 per_pixel=1922.3 | 1,943 |"
        ));
        assert!(!agree(
            line,
            "format=i16f16 hash=0x7efa0cd2 per_pixel=1922.3 |"
        ));
        assert!(!agree("| yes |", "| no |"));
    }
}
