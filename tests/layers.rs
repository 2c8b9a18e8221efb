//! The architecture's rules, read from the source tree (`docs/architecture.md`):
//!
//! - the top-level modules of `src/` (each `src/<name>.rs` or `src/<name>/`, found in the
//!   directory) depend on each other one way: every `crate::<module>` path, in `use` items
//!   (grouped ones too), in code and in `$crate::` macro bodies, is an edge, and the graph
//!   has no cycle. Comments, string and character literals and the bodies of
//!   `#[cfg(test)]` modules name nothing (test code may reach anywhere). `lib.rs` is the
//!   root: it uses everything, and a `crate::Name` that it re-exports (`pub use
//!   geometry::Vec3`) or that a module exports as a macro (`#[macro_export]`) counts as
//!   the module it comes from. A `crate::` path this file cannot place fails the check,
//!   so that a dependency is never missed silently;
//! - files stay small: at most 800 lines in `src/`, 600 in `src/kernel/`.
//!
//! `cargo test --test layers -- --nocapture` prints the whole edge list (the layering).

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// The most lines a file of `src/` may have.
const MAX_LINES: usize = 800;
/// The most lines a file of `src/kernel/` may have (the kernels are the densest code).
const MAX_LINES_KERNEL: usize = 600;

// ---------------------------------------------------------------------------------------
// Reading source text
// ---------------------------------------------------------------------------------------

/// Whether `c` can be part of an identifier.
fn is_ident(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

/// If a raw string (`r"…"`, `r#"…"#`, `br"…"`, `cr"…"`) starts at `i`: its number of
/// `#`s and the index of its opening quote. A raw identifier (`r#name`) is not one.
fn raw_string_at(s: &[char], i: usize) -> Option<(usize, usize)> {
    if i > 0 && is_ident(s[i - 1]) {
        return None;
    }
    let mut j = i;
    if s.get(j).is_some_and(|&c| c == 'b' || c == 'c') {
        j += 1;
    }
    if s.get(j) != Some(&'r') {
        return None;
    }
    j += 1;
    let mut hashes = 0;
    while s.get(j) == Some(&'#') {
        hashes += 1;
        j += 1;
    }
    (s.get(j) == Some(&'"')).then_some((hashes, j))
}

/// `text` with every comment (line, doc and nested block comments) and every string and
/// character literal replaced by spaces. Newlines stay, so line numbers hold.
fn strip_comments_and_literals(text: &str) -> String {
    let s: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let blank = |out: &mut String, c: char| out.push(if c == '\n' { '\n' } else { ' ' });
    let mut i = 0;
    while i < s.len() {
        let c = s[i];
        let next = s.get(i + 1).copied();
        if c == '/' && next == Some('/') {
            while i < s.len() && s[i] != '\n' {
                blank(&mut out, s[i]);
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            let mut depth = 0;
            while i < s.len() {
                if s[i] == '/' && s.get(i + 1) == Some(&'*') {
                    depth += 1;
                    out.push_str("  ");
                    i += 2;
                } else if s[i] == '*' && s.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    out.push_str("  ");
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    blank(&mut out, s[i]);
                    i += 1;
                }
            }
        } else if let Some((hashes, quote)) = raw_string_at(&s, i) {
            // Up to the quote that `hashes` `#`s follow; no escapes inside.
            let mut j = quote + 1;
            while j < s.len() {
                if s[j] == '"' && (1..=hashes).all(|k| s.get(j + k) == Some(&'#')) {
                    j += 1 + hashes;
                    break;
                }
                j += 1;
            }
            for &c in &s[i..j.min(s.len())] {
                blank(&mut out, c);
            }
            i = j;
        } else if c == '"' {
            blank(&mut out, c);
            i += 1;
            while i < s.len() && s[i] != '"' {
                let step = if s[i] == '\\' { 2 } else { 1 };
                for &c in &s[i..(i + step).min(s.len())] {
                    blank(&mut out, c);
                }
                i += step;
            }
            if i < s.len() {
                blank(&mut out, s[i]);
                i += 1;
            }
        } else if c == '\'' && (next == Some('\\') || s.get(i + 2) == Some(&'\'')) {
            // A character literal (`'x'`, `'\n'`, `'\''`, `'\u{…}'`); a lifetime or a
            // label (`'a`) has no closing quote after one character and stays.
            let mut j = if next == Some('\\') { i + 3 } else { i + 2 };
            while j < s.len() && s[j] != '\'' {
                j += 1;
            }
            for &c in &s[i..(j + 1).min(s.len())] {
                blank(&mut out, c);
            }
            i = j + 1;
        } else if is_ident(c) {
            // A whole word, so that a word ending in `r` or `b` never starts a literal.
            while i < s.len() && is_ident(s[i]) {
                out.push(s[i]);
                i += 1;
            }
        } else {
            out.push(c);
            i += 1;
        }
    }
    out
}

/// A token of stripped code: an identifier (or number), or one punctuation character.
#[derive(Debug, Clone)]
struct Token {
    text: String,
    line: usize,
}

/// The tokens of `code` (already stripped of comments and literals), with 1-based lines.
fn tokens(code: &str) -> Vec<Token> {
    let mut out = Vec::new();
    let mut line = 1;
    let mut chars = code.chars().peekable();
    while let Some(c) = chars.next() {
        if c == '\n' {
            line += 1;
        } else if is_ident(c) {
            let mut text = c.to_string();
            while let Some(&d) = chars.peek().filter(|&&d| is_ident(d)) {
                text.push(d);
                chars.next();
            }
            out.push(Token { text, line });
        } else if !c.is_whitespace() {
            out.push(Token {
                text: c.to_string(),
                line,
            });
        }
    }
    out
}

/// The index of the token that closes the bracket opened at `open` (or the end).
fn matching(toks: &[Token], open: usize) -> usize {
    let (o, c) = match toks[open].text.as_str() {
        "{" => ("{", "}"),
        "[" => ("[", "]"),
        _ => ("(", ")"),
    };
    let mut depth = 0;
    for (k, t) in toks.iter().enumerate().skip(open) {
        if t.text == o {
            depth += 1;
        } else if t.text == c {
            depth -= 1;
            if depth == 0 {
                return k;
            }
        }
    }
    toks.len()
}

/// Whether the attribute `#[…]` whose `[` is at `open` makes its item test-only:
/// `#[cfg(test)]`, or `#[cfg(all(test, …))]` (never under `not` or `any`).
fn is_test_cfg(toks: &[Token], open: usize) -> bool {
    let close = matching(toks, open);
    let inner: Vec<&str> = toks[open + 1..close]
        .iter()
        .map(|t| t.text.as_str())
        .collect();
    inner.first() == Some(&"cfg")
        && inner.contains(&"test")
        && !inner.contains(&"not")
        && !inner.contains(&"any")
}

/// What is left of a file's tokens once its test modules are cut out: every
/// `#[cfg(test)] mod name { … }` loses its body. Also the names of test modules declared
/// out of line (`#[cfg(test)] mod name;`), whose files are test code too.
fn without_test_modules(toks: Vec<Token>) -> (Vec<Token>, Vec<String>) {
    let mut keep = Vec::with_capacity(toks.len());
    let mut out_of_line = Vec::new();
    let mut i = 0;
    while i < toks.len() {
        if toks[i].text == "#" && toks.get(i + 1).is_some_and(|t| t.text == "[") {
            // The attributes in a row, then the item they apply to.
            let mut test = false;
            let mut j = i;
            while toks.get(j).is_some_and(|t| t.text == "#")
                && toks.get(j + 1).is_some_and(|t| t.text == "[")
            {
                test |= is_test_cfg(&toks, j + 1);
                j = matching(&toks, j + 1) + 1;
            }
            if toks.get(j).is_some_and(|t| t.text == "pub") {
                j += 1;
                if toks.get(j).is_some_and(|t| t.text == "(") {
                    j = matching(&toks, j) + 1;
                }
            }
            let is_mod = toks.get(j).is_some_and(|t| t.text == "mod");
            if test && is_mod {
                match toks.get(j + 2).map(|t| t.text.as_str()) {
                    Some("{") => {
                        i = matching(&toks, j + 2) + 1;
                        continue;
                    }
                    Some(";") => out_of_line.push(toks[j + 1].text.clone()),
                    _ => {}
                }
            }
        }
        keep.push(toks[i].clone());
        i += 1;
    }
    (keep, out_of_line)
}

/// The code tokens of a file's text that count: no comments, literals or test modules.
fn code_tokens(text: &str) -> (Vec<Token>, Vec<String>) {
    without_test_modules(tokens(&strip_comments_and_literals(text)))
}

/// Every `crate::` path in `toks` by the first name after `crate::` (the top-level module
/// or root item it reaches), with its line. A group `crate::{a::B, c::{D, e::F}}` gives
/// each of its items' first names (`a`, `c`); `self` names the root itself and is
/// skipped; a glob of the root gives `*`.
fn crate_paths(toks: &[Token]) -> Vec<(String, usize)> {
    let mut out = Vec::new();
    for i in 0..toks.len() {
        let path_sep = |k: usize| {
            toks.get(k).is_some_and(|t| t.text == ":")
                && toks.get(k + 1).is_some_and(|t| t.text == ":")
        };
        if toks[i].text != "crate" || !path_sep(i + 1) {
            continue;
        }
        let Some(first) = toks.get(i + 3) else {
            continue;
        };
        if first.text != "{" {
            out.push((first.text.clone(), first.line));
            continue;
        }
        // A group: the first name of each item at its top level.
        let close = matching(toks, i + 3);
        let mut at_item_start = true;
        let mut depth = 0;
        for t in &toks[i + 4..close.min(toks.len())] {
            match t.text.as_str() {
                "{" => depth += 1,
                "}" => depth -= 1,
                "," if depth == 0 => at_item_start = true,
                name if at_item_start && depth == 0 => {
                    if name != "self" {
                        out.push((name.to_string(), t.line));
                    }
                    at_item_start = false;
                }
                _ => {}
            }
        }
    }
    out
}

// ---------------------------------------------------------------------------------------
// The crate root: what a `crate::Name` that is not a module stands for
// ---------------------------------------------------------------------------------------

/// What a name at the crate root is.
#[derive(Debug, Clone, PartialEq, Eq)]
enum RootName {
    /// Brought in by a `use` of lib.rs whose path starts with this name (a top-level
    /// module, an external crate, or another root name).
    Use(String),
    /// Defined in lib.rs itself (an inline module, a type): no edge.
    Root,
}

/// The names one `use` tree of lib.rs brings into the root, each with the first name of
/// its whole path, from `toks[*i]` to the tree's end (`;`, `,` or `}`); `prefix` is the
/// path of the groups the tree sits in.
fn use_tree(toks: &[Token], i: &mut usize, prefix: &[String], out: &mut Vec<(String, String)>) {
    let mut path = prefix.to_vec();
    while let Some(t) = toks.get(*i) {
        match t.text.as_str() {
            ":" => *i += 1,
            "{" => {
                *i += 1;
                loop {
                    use_tree(toks, i, &path, out);
                    match toks.get(*i).map(|t| t.text.as_str()) {
                        Some(",") => *i += 1,
                        Some("}") => {
                            *i += 1;
                            break;
                        }
                        _ => break,
                    }
                }
                // Nothing of this tree follows its group.
                return;
            }
            "as" => {
                if let (Some(alias), Some(head)) = (toks.get(*i + 1), path.first()) {
                    out.push((alias.text.clone(), head.clone()));
                }
                *i += 2;
                return;
            }
            ";" | "," | "}" => {
                // A glob (`x::*`) brings no name this check can list.
                if path.len() > prefix.len() && path.last().is_some_and(|l| l != "*") {
                    out.push((path[path.len() - 1].clone(), path[0].clone()));
                }
                return;
            }
            // `crate::`, `self::` and a leading `::` add nothing at the root.
            "crate" | "self" if path.is_empty() => *i += 1,
            // `x::{self}` brings `x` itself.
            "self" => {
                if let Some(last) = path.last().cloned() {
                    path.push(last);
                }
                *i += 1;
            }
            name => {
                path.push(name.to_string());
                *i += 1;
            }
        }
    }
}

/// The names at the root of the crate (lib.rs): for each, where it comes from.
fn root_names(lib_text: &str) -> BTreeMap<String, RootName> {
    let (toks, _) = code_tokens(lib_text);
    let mut names = BTreeMap::new();
    let mut depth = 0;
    let mut i = 0;
    while i < toks.len() {
        let t = &toks[i].text;
        match t.as_str() {
            "{" => depth += 1,
            "}" => depth -= 1,
            "use" if depth == 0 => {
                i += 1;
                let mut found = Vec::new();
                use_tree(&toks, &mut i, &[], &mut found);
                for (name, head) in found {
                    names.insert(name, RootName::Use(head));
                }
                continue;
            }
            "mod" | "struct" | "enum" | "union" | "trait" | "type" | "fn" | "const" | "static"
                if depth == 0 =>
            {
                if let Some(name) = toks.get(i + 1) {
                    names.entry(name.text.clone()).or_insert(RootName::Root);
                }
            }
            _ => {}
        }
        i += 1;
    }
    names
}

/// The names of the macros `toks` exports at the crate root (`#[macro_export]
/// macro_rules! name`).
fn exported_macros(toks: &[Token]) -> Vec<String> {
    let mut out = Vec::new();
    for i in 0..toks.len() {
        if toks[i].text != "macro_rules" || toks.get(i + 1).is_none_or(|t| t.text != "!") {
            continue;
        }
        // Back over the attributes just before it.
        let mut k = i;
        let mut exported = false;
        while k >= 2 && toks[k - 1].text == "]" {
            let mut depth = 0;
            let mut open = k - 1;
            loop {
                match toks[open].text.as_str() {
                    "]" => depth += 1,
                    "[" => depth -= 1,
                    _ => {}
                }
                if depth == 0 || open == 0 {
                    break;
                }
                open -= 1;
            }
            if open == 0 || toks[open - 1].text != "#" {
                break;
            }
            exported |= toks[open..k].iter().any(|t| t.text == "macro_export");
            k = open - 1;
        }
        if exported && let Some(name) = toks.get(i + 2) {
            out.push(name.text.clone());
        }
    }
    out
}

// ---------------------------------------------------------------------------------------
// The module graph
// ---------------------------------------------------------------------------------------

/// Where a reference was read: a file (relative to the crate) and a line.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
struct Evidence {
    file: String,
    line: usize,
}

impl std::fmt::Display for Evidence {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}:{}", self.file, self.line)
    }
}

/// The edges between top-level modules, each with every reference that makes it.
type Edges = BTreeMap<(String, String), Vec<Evidence>>;

/// The crate's directory.
fn crate_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Every `.rs` file under `dir`, sorted.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut entries: Vec<PathBuf> = fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("reading {}: {e}", dir.display()))
        .map(|e| e.expect("a directory entry").path())
        .collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            out.extend(rust_files(&path));
        } else if path.extension().is_some_and(|x| x == "rs") {
            out.push(path);
        }
    }
    out
}

/// The top-level modules of `src/` and their files: `src/<name>.rs` and everything under
/// `src/<name>/`. The crate root (`lib.rs`, `main.rs`) and `src/bin/` are not modules.
fn top_level_modules(src: &Path) -> BTreeMap<String, Vec<PathBuf>> {
    let mut modules: BTreeMap<String, Vec<PathBuf>> = BTreeMap::new();
    for entry in fs::read_dir(src).expect("src/ is readable") {
        let path = entry.expect("a directory entry").path();
        let name = path
            .file_stem()
            .and_then(|s| s.to_str())
            .expect("a file name in src/")
            .to_string();
        if path.is_dir() && name != "bin" {
            modules.entry(name).or_default().extend(rust_files(&path));
        } else if path.extension().is_some_and(|x| x == "rs") && name != "lib" && name != "main" {
            modules.entry(name).or_default().push(path);
        }
    }
    for files in modules.values_mut() {
        files.sort();
    }
    modules
}

/// The files of a test module declared out of line in `file` (`#[cfg(test)] mod name;`).
fn test_module_files(file: &Path, name: &str) -> [PathBuf; 2] {
    let stem = file.file_stem().and_then(|s| s.to_str()).unwrap_or("");
    let dir = file.parent().expect("a file has a directory");
    let dir = if stem == "mod" || stem == "lib" {
        dir.to_path_buf()
    } else {
        dir.join(stem)
    };
    [
        dir.join(format!("{name}.rs")),
        dir.join(name).join("mod.rs"),
    ]
}

/// The graph of the crate in `crate_root`: its edges, and the `crate::` paths that name
/// nothing this check can place.
fn module_graph(crate_root: &Path) -> (BTreeSet<String>, Edges, Vec<String>) {
    let src = crate_root.join("src");
    let rel = |p: &Path| {
        p.strip_prefix(crate_root)
            .unwrap_or(p)
            .to_string_lossy()
            .replace('\\', "/")
    };
    let modules = top_level_modules(&src);
    let lib = fs::read_to_string(src.join("lib.rs")).expect("src/lib.rs is readable");
    let mut roots = root_names(&lib);

    // Read every file once: its code tokens, and what it exports as macros.
    let mut read: Vec<(String, PathBuf, Vec<Token>)> = Vec::new();
    let mut test_files: BTreeSet<PathBuf> = BTreeSet::new();
    for (module, files) in &modules {
        for file in files {
            let text = fs::read_to_string(file).expect("a source file is readable");
            let (toks, test_mods) = code_tokens(&text);
            for name in test_mods {
                test_files.extend(test_module_files(file, &name));
            }
            for name in exported_macros(&toks) {
                roots.insert(name, RootName::Use(module.clone()));
            }
            read.push((module.clone(), file.clone(), toks));
        }
    }

    // The top-level module a first name after `crate::` stands for: `Ok(None)` for the
    // root itself or an external crate, `Err` for a name this check cannot place.
    let resolve = |name: &str| -> Result<Option<String>, ()> {
        let mut name = name.to_string();
        for _ in 0..8 {
            if modules.contains_key(&name) {
                return Ok(Some(name));
            }
            match roots.get(&name) {
                Some(RootName::Root) => return Ok(None),
                Some(RootName::Use(head))
                    if roots.contains_key(head) || modules.contains_key(head) =>
                {
                    if *head == name {
                        return Ok(None);
                    }
                    name = head.clone();
                }
                // A re-export from another crate (`pub use fixed::types::I16F16`).
                Some(RootName::Use(_)) => return Ok(None),
                None => return Err(()),
            }
        }
        Err(())
    };

    let mut edges = Edges::new();
    let mut unplaced = Vec::new();
    for (module, file, toks) in &read {
        if test_files.contains(file) {
            continue;
        }
        for (name, line) in crate_paths(toks) {
            let evidence = Evidence {
                file: rel(file),
                line,
            };
            match resolve(&name) {
                Ok(Some(to)) if to != *module => edges
                    .entry((module.clone(), to))
                    .or_default()
                    .push(evidence),
                Ok(_) => {}
                Err(()) => unplaced.push(format!(
                    "{evidence}: `crate::{name}` is neither a top-level module nor a name \
                     src/lib.rs re-exports or defines"
                )),
            }
        }
    }
    for list in edges.values_mut() {
        list.sort();
    }
    (modules.keys().cloned().collect(), edges, unplaced)
}

/// Every elementary cycle of the graph, each once, starting and ending at its smallest
/// node (`[a, b, a]`), in order.
fn cycles(edges: &BTreeSet<(String, String)>) -> Vec<Vec<String>> {
    let mut next: BTreeMap<&str, Vec<&str>> = BTreeMap::new();
    for (from, to) in edges {
        next.entry(from).or_default().push(to);
    }
    // Paths from `start` through nodes greater than it back to `start`: each cycle is
    // found from its smallest node only.
    fn walk<'a>(
        next: &BTreeMap<&'a str, Vec<&'a str>>,
        start: &'a str,
        path: &mut Vec<&'a str>,
        found: &mut Vec<Vec<String>>,
    ) {
        let here = *path.last().expect("a path has a node");
        for &to in next.get(here).map(Vec::as_slice).unwrap_or(&[]) {
            if to == start {
                let mut cycle: Vec<String> = path.iter().map(|s| s.to_string()).collect();
                cycle.push(start.to_string());
                found.push(cycle);
            } else if to > start && !path.contains(&to) {
                path.push(to);
                walk(next, start, path, found);
                path.pop();
            }
        }
    }
    let mut found = Vec::new();
    let nodes: BTreeSet<&str> = next.keys().copied().collect();
    for start in nodes {
        walk(&next, start, &mut vec![start], &mut found);
    }
    found
}

// ---------------------------------------------------------------------------------------
// The checks
// ---------------------------------------------------------------------------------------

#[test]
fn top_level_modules_depend_one_way() {
    let (modules, edges, unplaced) = module_graph(&crate_dir());
    // A reader that found nothing would pass any tree: the crate has layers to find.
    assert!(
        modules.len() >= 2 && !edges.is_empty(),
        "no dependency between top-level modules found in src/ (modules: {modules:?}): \
         the reader of this check is broken"
    );

    println!(
        "top-level modules: {}",
        modules.iter().cloned().collect::<Vec<_>>().join(", ")
    );
    println!("their dependencies (user -> used: references, the first):");
    let width = edges
        .keys()
        .map(|(a, b)| a.len() + b.len() + 4)
        .max()
        .unwrap_or(0);
    for ((from, to), evidence) in &edges {
        println!(
            "  {:<width$} {:>3}  {}",
            format!("{from} -> {to}"),
            evidence.len(),
            evidence[0]
        );
    }

    let mut problems = Vec::new();
    if !unplaced.is_empty() {
        problems.push(format!(
            "{} `crate::` path(s) this check cannot place: bring the name to the root \
             in src/lib.rs (`pub(crate) use module::Name;`), or teach this check the form \
             that brings it there:\n  {}",
            unplaced.len(),
            unplaced.join("\n  ")
        ));
    }
    let found = cycles(&edges.keys().cloned().collect());
    if !found.is_empty() {
        let mut text = format!(
            "the top-level modules' dependencies form {} cycle(s); they must run one way \
             (docs/architecture.md):",
            found.len()
        );
        for cycle in &found {
            text.push_str(&format!("\n  {}", cycle.join(" -> ")));
            for pair in cycle.windows(2) {
                let evidence = &edges[&(pair[0].clone(), pair[1].clone())][0];
                text.push_str(&format!("\n    {} -> {}: {evidence}", pair[0], pair[1]));
            }
        }
        problems.push(text);
    }
    assert!(problems.is_empty(), "{}", problems.join("\n\n"));
}

#[test]
fn files_stay_small() {
    let root = crate_dir();
    let src = root.join("src");
    let mut over = Vec::new();
    for file in rust_files(&src) {
        let lines = fs::read_to_string(&file)
            .expect("a source file is readable")
            .lines()
            .count();
        let (limit, place) = if file.starts_with(src.join("kernel")) {
            (MAX_LINES_KERNEL, "src/kernel/")
        } else {
            (MAX_LINES, "src/")
        };
        if lines > limit {
            let name = file
                .strip_prefix(&root)
                .unwrap_or(&file)
                .display()
                .to_string();
            over.push(format!(
                "  {name}: {lines} lines (at most {limit} in {place})"
            ));
        }
    }
    assert!(
        over.is_empty(),
        "{} file(s) over the size limit; split each by concept, one concept a file \
         (docs/architecture.md lists the files and what each holds):\n{}",
        over.len(),
        over.join("\n")
    );
}

// ---------------------------------------------------------------------------------------
// The check's own parts, on small inputs (so that the check cannot pass by reading
// nothing)
// ---------------------------------------------------------------------------------------

/// The first names after `crate::` in `text`, as a sorted set.
fn first_names(text: &str) -> BTreeSet<String> {
    crate_paths(&code_tokens(text).0)
        .into_iter()
        .map(|(name, _)| name)
        .collect()
}

fn set(names: &[&str]) -> BTreeSet<String> {
    names.iter().map(|s| s.to_string()).collect()
}

#[test]
fn a_grouped_use_names_each_first_module() {
    assert_eq!(
        first_names("use crate::{a::B, c::{D, e::F}};"),
        set(&["a", "c"])
    );
    assert_eq!(
        first_names("use crate::{\n    self,\n    g::{h::{I, J}, K},\n    L as M,\n};"),
        set(&["g", "L"])
    );
    assert_eq!(first_names("use crate::a::b::C;"), set(&["a"]));
    assert_eq!(
        first_names("fn f() -> crate::x::Y { $crate::z::w!() }"),
        set(&["x", "z"])
    );
    // `pub(crate)` is a visibility, not a path.
    assert_eq!(first_names("pub(crate) fn f() {}"), set(&[]));
    // Lines are counted through stripped comments and strings.
    let toks = code_tokens("/* a\n b */ \"c\nd\"\n// e\nuse crate::m::N;").0;
    assert_eq!(crate_paths(&toks), vec![("m".to_string(), 5)]);
}

#[test]
fn comments_and_literals_name_nothing() {
    for text in [
        "// use crate::x::Y;",
        "/// [`crate::x::Y`]",
        "//! crate::x",
        "/* crate::x /* nested */ crate::x */",
        "let s = \"crate::x::Y\";",
        "let s = \"a \\\" crate::x\";",
        "let s = r#\"crate::x \" still\"#;",
        "let s = br\"crate::x\";",
        "let q = '\"'; // crate::x \"",
        "let q = '\\''; let s = \"crate::x\";",
        "fn f<'a>(s: &'a str) -> &'a str { \"crate::x\" }",
    ] {
        assert_eq!(first_names(text), set(&[]), "{text}");
    }
    // A word that ends in `r` or `b` does not start a raw string.
    assert_eq!(
        first_names("let r = br; use crate::x::Y; let s = r\"\";"),
        set(&["x"])
    );
}

#[test]
fn test_modules_name_nothing() {
    let text = "use crate::a::A;\n#[cfg(test)]\nmod tests {\n    use crate::b::B;\n    fn f() { \
                crate::c::g() }\n}\n#[cfg(test)]\nfn helper() { crate::d::h() }\n\
                #[cfg(all(test, feature = \"std\"))]\n#[allow(unused)]\npub(crate) mod more { \
                use crate::e::E; }\n#[cfg(not(test))]\nmod real { use crate::f::F; }\n";
    assert_eq!(first_names(text), set(&["a", "d", "f"]));
    let (_, out_of_line) = code_tokens("#[cfg(test)]\nmod checks;\nmod other;");
    assert_eq!(out_of_line, vec!["checks".to_string()]);
}

#[test]
fn root_names_resolve_to_their_modules() {
    let lib = "pub mod num;\nmod kernel;\npub use kernel::flat::PlaneMode;\n\
               pub use num::{I16F16, Scalar as S};\npub(crate) use geometry::{\n    Hit,\n    \
               Ray, shape::{Shape, Slide},\n};\npub use fixed::types::I8F8;\n\
               pub use scene::parse::{self};\npub struct Doc;\npub mod internals {\n    pub use crate::kernel::fast::Primary;\n}\n";
    let names = root_names(lib);
    let used = |m: &str| Some(RootName::Use(m.to_string()));
    assert_eq!(names.get("PlaneMode").cloned(), used("kernel"));
    assert_eq!(names.get("I16F16").cloned(), used("num"));
    assert_eq!(names.get("S").cloned(), used("num"));
    assert_eq!(names.get("Scalar"), None);
    assert_eq!(names.get("Hit").cloned(), used("geometry"));
    assert_eq!(names.get("Shape").cloned(), used("geometry"));
    assert_eq!(names.get("Slide").cloned(), used("geometry"));
    assert_eq!(names.get("I8F8").cloned(), used("fixed"));
    assert_eq!(names.get("parse").cloned(), used("scene"));
    assert_eq!(names.get("Doc"), Some(&RootName::Root));
    assert_eq!(names.get("internals"), Some(&RootName::Root));
    // Only the root's own items: what an inline module re-exports is not at the root.
    assert_eq!(names.get("Primary"), None);

    let macros = code_tokens(
        "#[macro_export]\n#[doc(hidden)]\nmacro_rules! shown { () => {} }\n\
         macro_rules! local { () => {} }",
    )
    .0;
    assert_eq!(exported_macros(&macros), vec!["shown".to_string()]);
}

#[test]
fn the_cycle_finder_finds_cycles_and_only_cycles() {
    let graph = |pairs: &[(&str, &str)]| -> BTreeSet<(String, String)> {
        pairs
            .iter()
            .map(|(a, b)| (a.to_string(), b.to_string()))
            .collect()
    };
    let layered = graph(&[("b", "a"), ("c", "a"), ("c", "b"), ("d", "c"), ("d", "a")]);
    assert!(cycles(&layered).is_empty());
    let two = graph(&[("a", "b"), ("b", "a"), ("c", "a")]);
    assert_eq!(cycles(&two), vec![vec!["a", "b", "a"]]);
    let three = graph(&[("b", "c"), ("c", "a"), ("a", "b"), ("d", "a")]);
    assert_eq!(cycles(&three), vec![vec!["a", "b", "c", "a"]]);
    let both = graph(&[("a", "b"), ("b", "a"), ("b", "c"), ("c", "a")]);
    assert_eq!(
        cycles(&both),
        vec![vec!["a", "b", "a"], vec!["a", "b", "c", "a"]]
    );
}
