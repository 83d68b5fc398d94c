//! Layers only look down. Every top-level module of the library has a place in [`LAYERS`], the
//! order of ARCHITECTURE.md's module graph; a module may import the ones before it, never one
//! after it.
//!
//! The test reads the library's source files and finds every path that starts with `crate::`,
//! `$crate::` or `super::` outside comments and literals: `use` and `pub use` items (with their
//! `{…}` groups) and fully qualified paths written inline (`crate::sim::run(…)`, also inside
//! macro calls and unit tests). `super::` is resolved against the file's module and the inline
//! modules around it. Each path is mapped to the top-level module it names, and any path that
//! names a module listed after the file's own fails the test with the file and the line.
//! Items defined in `lib.rs` itself (such as `VERSION`) belong to no layer and may be used
//! anywhere.
//!
//! The other tests keep the list and the document honest: every module `lib.rs` declares has a
//! layer and every layer a module, and ARCHITECTURE.md draws the same layers in the same order,
//! with a paragraph each and import lists equal to the imports found here.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// The layers, lowest first: the order of ARCHITECTURE.md's module graph.
const LAYERS: &[&str] = &[
    "kernel",
    "geometry",
    "algorithm",
    "protocol",
    "sensing",
    "world",
    "generate",
    "io",
    "strategy",
    "offline",
    "sim",
    "run_record",
    "render",
    "experiment",
    "pipeline",
];

/// Layers that may be absent from the source tree (none today: a layer added to the order
/// list before its module lands goes here until it does).
const OPTIONAL: &[&str] = &[];

fn crate_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn rank(module: &str) -> Option<usize> {
    LAYERS.iter().position(|&l| l == module)
}

// ---------------------------------------------------------------------------------------------
// Tokens: identifiers, `::` and single punctuation, with comments, strings and character
// literals skipped and line numbers kept.

#[derive(Debug, Clone, PartialEq)]
enum Tok {
    Ident(String),
    PathSep,
    Punct(char),
}

#[derive(Debug, Clone)]
struct Token {
    tok: Tok,
    line: usize,
}

fn is_ident_char(c: char) -> bool {
    c == '_' || c.is_alphanumeric()
}

/// Skips a string literal whose opening quote is at `c[i]`; returns the index after it.
fn skip_string(c: &[char], mut i: usize, line: &mut usize) -> usize {
    i += 1;
    while i < c.len() && c[i] != '"' {
        if c[i] == '\\' {
            i += 1;
        }
        if c.get(i) == Some(&'\n') {
            *line += 1;
        }
        i += 1;
    }
    i + 1
}

/// Skips a raw string whose first `#` or quote is at `c[i]` (after the `r`); returns the index
/// after it.
fn skip_raw_string(c: &[char], mut i: usize, line: &mut usize) -> usize {
    let mut hashes = 0;
    while c.get(i) == Some(&'#') {
        hashes += 1;
        i += 1;
    }
    i += 1; // the opening quote
    while i < c.len() {
        if c[i] == '"' && (1..=hashes).all(|k| c.get(i + k) == Some(&'#')) {
            return i + 1 + hashes;
        }
        if c[i] == '\n' {
            *line += 1;
        }
        i += 1;
    }
    i
}

/// Skips a character literal or a lifetime whose quote is at `c[i]`; returns the index after.
fn skip_quote(c: &[char], i: usize) -> usize {
    if c.get(i + 1) == Some(&'\\') {
        // An escaped character: '\n', '\'', '\u{2212}'.
        let mut j = i + 3;
        while j < c.len() && c[j] != '\'' {
            j += 1;
        }
        j + 1
    } else if c.get(i + 2) == Some(&'\'') {
        i + 3
    } else {
        // A lifetime or a loop label.
        let mut j = i + 1;
        while j < c.len() && is_ident_char(c[j]) {
            j += 1;
        }
        j
    }
}

fn tokens(src: &str) -> Vec<Token> {
    let c: Vec<char> = src.chars().collect();
    let mut out = Vec::new();
    let (mut i, mut line) = (0, 1);
    while i < c.len() {
        let ch = c[i];
        let next = c.get(i + 1).copied();
        if ch == '\n' {
            line += 1;
            i += 1;
        } else if ch.is_whitespace() {
            i += 1;
        } else if ch == '/' && next == Some('/') {
            while i < c.len() && c[i] != '\n' {
                i += 1;
            }
        } else if ch == '/' && next == Some('*') {
            let mut depth = 0;
            while i < c.len() {
                if c[i] == '/' && c.get(i + 1) == Some(&'*') {
                    depth += 1;
                    i += 2;
                } else if c[i] == '*' && c.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    if c[i] == '\n' {
                        line += 1;
                    }
                    i += 1;
                }
            }
        } else if ch == '"' {
            i = skip_string(&c, i, &mut line);
        } else if ch == '\'' {
            i = skip_quote(&c, i);
        } else if ch == ':' && next == Some(':') {
            out.push(Token { tok: Tok::PathSep, line });
            i += 2;
        } else if is_ident_char(ch) {
            let start = i;
            while i < c.len() && is_ident_char(c[i]) {
                i += 1;
            }
            let word: String = c[start..i].iter().collect();
            let after = c.get(i).copied();
            let after2 = c.get(i + 1).copied();
            match (word.as_str(), after) {
                ("r" | "br" | "cr", Some('"')) => i = skip_raw_string(&c, i, &mut line),
                ("r" | "br" | "cr", Some('#')) if matches!(after2, Some('"' | '#')) => {
                    i = skip_raw_string(&c, i, &mut line);
                }
                ("r", Some('#')) => {} // a raw identifier: `r#type` reads as `r`, `#`, `type`
                ("b" | "c", Some('"')) => i = skip_string(&c, i, &mut line),
                ("b", Some('\'')) => i = skip_quote(&c, i),
                _ if ch.is_ascii_digit() => {} // a number
                _ => out.push(Token { tok: Tok::Ident(word), line }),
            }
        } else {
            out.push(Token { tok: Tok::Punct(ch), line });
            i += 1;
        }
    }
    out
}

// ---------------------------------------------------------------------------------------------
// Paths: every `crate::`, `$crate::` and `super::` path, resolved to the top-level module it
// names.

/// One path into the crate: where it is and the top-level module (or root item) it names.
#[derive(Debug, Clone, PartialEq)]
struct Import {
    line: usize,
    top: String,
}

fn ident(toks: &[Token], i: usize) -> Option<&str> {
    match toks.get(i).map(|t| &t.tok) {
        Some(Tok::Ident(s)) => Some(s),
        _ => None,
    }
}

fn is(toks: &[Token], i: usize, tok: &Tok) -> bool {
    toks.get(i).is_some_and(|t| &t.tok == tok)
}

/// The first segment of each item of the `{…}` group whose brace is at `toks[open]`.
fn group_heads(toks: &[Token], open: usize) -> Vec<String> {
    let mut heads = Vec::new();
    let mut depth = 0;
    let mut item_start = true;
    for (k, t) in toks.iter().enumerate().skip(open) {
        match &t.tok {
            Tok::Punct('{') => {
                depth += 1;
                if depth > 1 {
                    item_start = false;
                }
            }
            Tok::Punct('}') => {
                depth -= 1;
                if depth == 0 {
                    break;
                }
            }
            Tok::Punct(',') if depth == 1 => item_start = true,
            Tok::Punct('*') if depth == 1 && item_start => {
                heads.push("*".into());
                item_start = false;
            }
            Tok::Ident(s) if depth == 1 && item_start => {
                if s != "self" && !is(toks, k - 1, &Tok::PathSep) {
                    heads.push(s.clone());
                }
                item_start = false;
            }
            _ => {}
        }
    }
    heads
}

/// Every path into the crate in one file whose module path is `module` (`[]` for `lib.rs`).
fn imports(module: &[String], toks: &[Token]) -> Vec<Import> {
    let mut out = Vec::new();
    // Inline modules open around the current token: (name, brace depth of their body).
    let mut inline: Vec<(String, usize)> = Vec::new();
    let mut depth = 0;
    for i in 0..toks.len() {
        match &toks[i].tok {
            Tok::Punct('{') => {
                depth += 1;
                if i >= 2
                    && ident(toks, i - 2) == Some("mod")
                    && let Some(name) = ident(toks, i - 1)
                {
                    inline.push((name.to_string(), depth));
                }
                continue;
            }
            Tok::Punct('}') => {
                if inline.last().is_some_and(|m| m.1 == depth) {
                    inline.pop();
                }
                depth -= 1;
                continue;
            }
            _ => {}
        }
        let start = ident(toks, i);
        if !matches!(start, Some("crate" | "super"))
            || !is(toks, i + 1, &Tok::PathSep)
            || (i > 0 && is(toks, i - 1, &Tok::PathSep))
        {
            continue;
        }
        // The absolute module path the prefix names.
        let mut base: Vec<String> = Vec::new();
        let mut j = i + 1; // at the `::` after the prefix
        if start == Some("super") {
            base = module.to_vec();
            base.extend(inline.iter().map(|m| m.0.clone()));
            base.pop();
            while is(toks, j, &Tok::PathSep) && ident(toks, j + 1) == Some("super") {
                base.pop();
                j += 2;
            }
        }
        let line = toks[i].line;
        if let Some(top) = base.first() {
            out.push(Import { line, top: top.clone() });
        } else if let Some(name) = ident(toks, j + 1) {
            out.push(Import { line, top: name.to_string() });
        } else if is(toks, j + 1, &Tok::Punct('{')) {
            out.extend(group_heads(toks, j + 1).into_iter().map(|top| Import { line, top }));
        } else if is(toks, j + 1, &Tok::Punct('*')) {
            out.push(Import { line, top: "*".into() });
        }
    }
    out
}

// ---------------------------------------------------------------------------------------------
// The library's files and the document.

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<PathBuf> =
        std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()).collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}

/// The module path of a source file relative to `src/`: `world/grid/mod.rs` is
/// `["world", "grid"]`, `sim/team.rs` is `["sim", "team"]`, `lib.rs` is `[]`.
fn module_path(rel: &Path) -> Vec<String> {
    let mut parts: Vec<String> =
        rel.iter().map(|s| s.to_string_lossy().trim_end_matches(".rs").to_string()).collect();
    if matches!(parts.last().map(String::as_str), Some("mod" | "lib")) {
        parts.pop();
    }
    parts
}

/// Names the crate root defines itself (`VERSION`): usable from any layer.
fn root_items(lib: &str) -> BTreeSet<String> {
    let toks = tokens(lib);
    let mut items = BTreeSet::new();
    let mut depth = 0;
    for (i, t) in toks.iter().enumerate() {
        match &t.tok {
            Tok::Punct('{') => depth += 1,
            Tok::Punct('}') => depth -= 1,
            Tok::Ident(kw)
                if depth == 0
                    && matches!(
                        kw.as_str(),
                        "const" | "static" | "fn" | "struct" | "enum" | "type" | "trait"
                    ) =>
            {
                if let Some(name) = ident(&toks, i + 1) {
                    items.insert(name.to_string());
                }
            }
            _ => {}
        }
    }
    items
}

/// The modules `lib.rs` declares.
fn declared_modules(lib: &str) -> Vec<String> {
    let toks = tokens(lib);
    (1..toks.len())
        .filter(|&i| ident(&toks, i - 1) == Some("mod") && is(&toks, i + 1, &Tok::Punct(';')))
        .filter_map(|i| ident(&toks, i).map(String::from))
        .collect()
}

/// ARCHITECTURE.md's module graph: the code block under "## Module graph". A line that starts
/// with a letter names a layer (its first word); a later line that starts with `└` lists the
/// layers it imports directly, comma-separated (a name may be followed by a remark in
/// parentheses, without commas), or says
/// `every layer below`. No such line: it imports none; `└ any layer`: not checked.
fn architecture_graph(doc: &str) -> Vec<(String, Option<BTreeSet<String>>)> {
    let after = doc.split_once("## Module graph").expect("ARCHITECTURE.md has a module graph").1;
    let block = after.split("```").nth(1).expect("the module graph is a code block");
    let mut graph: Vec<(String, Option<BTreeSet<String>>)> = Vec::new();
    for line in block.lines() {
        if line.starts_with(|c: char| c.is_ascii_lowercase()) {
            let name = line.split_whitespace().next().unwrap_or_default();
            graph.push((name.to_string(), Some(BTreeSet::new())));
        } else if let Some(list) = line.trim_start().strip_prefix('└') {
            let below: BTreeSet<String> = graph.iter().rev().skip(1).map(|g| g.0.clone()).collect();
            let (_, edges) = graph.last_mut().expect("an import list follows a layer");
            if list.trim() == "any layer" {
                *edges = None;
                continue;
            }
            if list.trim() == "every layer below" {
                *edges = Some(below);
                continue;
            }
            // A word in parentheses after a name is a remark: `generate (unit tests)`.
            let set = edges.as_mut().expect("one import list per layer");
            set.extend(
                list.split(',')
                    .map(|w| w.split('(').next().unwrap_or_default().trim().to_string())
                    .filter(|w| !w.is_empty()),
            );
        }
    }
    graph
}

/// One path into the crate, found in a layer's file.
struct Found {
    /// `src/FILE:LINE: the line`.
    at: String,
    /// The file's layer.
    own: String,
    /// The top-level module (or root item) the path names.
    top: String,
}

/// Every path into the crate in the library's layers (`lib.rs` aside), and the problems with
/// files themselves.
fn scan_library() -> (Vec<Found>, Vec<String>) {
    let src = crate_dir().join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut found = Vec::new();
    let mut problems = Vec::new();
    for file in &files {
        let rel = file.strip_prefix(&src).unwrap();
        let module = module_path(rel);
        let Some(own) = module.first() else { continue }; // lib.rs is the root, not a layer
        if rank(own).is_none() {
            problems.push(format!("src/{}: module `{own}` is in no layer", rel.display()));
        }
        let text = std::fs::read_to_string(file).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        let toks = tokens(&text);
        if toks.windows(3).any(|w| {
            w[0].tok == Tok::Punct('#')
                && w[1].tok == Tok::Punct('[')
                && w[2].tok == Tok::Ident("path".into())
        }) {
            problems
                .push(format!("src/{}: #[path] makes files and modules disagree", rel.display()));
        }
        for imp in imports(&module, &toks) {
            found.push(Found {
                at: format!("src/{}:{}: {}", rel.display(), imp.line, lines[imp.line - 1].trim()),
                own: own.clone(),
                top: imp.top,
            });
        }
    }
    (found, problems)
}

// ---------------------------------------------------------------------------------------------

#[test]
fn no_module_imports_a_layer_above_its_own() {
    let lib = std::fs::read_to_string(crate_dir().join("src/lib.rs")).unwrap();
    let root = root_items(&lib);
    let (found, mut problems) = scan_library();
    assert!(found.len() > 300, "only {} paths found: is the scanner broken?", found.len());
    for f in &found {
        if f.top == f.own || root.contains(&f.top) {
            continue;
        }
        match (rank(&f.own), rank(&f.top)) {
            _ if f.top == "*" => problems.push(format!("{}\n    a glob of the crate root", f.at)),
            (_, None) => problems.push(format!("{}\n    `{}` is in no layer", f.at, f.top)),
            (Some(own), Some(top)) if top > own => problems.push(format!(
                "{}\n    `{}` imports `{}`, which is listed after it",
                f.at, f.own, f.top
            )),
            _ => {}
        }
    }
    assert!(
        problems.is_empty(),
        "imports that go up the layers ({}):\n{}",
        LAYERS.join(" < "),
        problems.join("\n")
    );
}

#[test]
fn every_module_has_a_layer_and_every_layer_a_module() {
    let src = crate_dir().join("src");
    let lib = std::fs::read_to_string(src.join("lib.rs")).unwrap();
    let declared = declared_modules(&lib);
    for m in &declared {
        assert!(rank(m).is_some(), "lib.rs declares `{m}`, which LAYERS does not list");
    }
    for layer in LAYERS {
        let present = declared.iter().any(|m| m == layer);
        let file =
            src.join(format!("{layer}.rs")).exists() || src.join(layer).join("mod.rs").exists();
        assert_eq!(present, file, "`{layer}`: declared in lib.rs and its file disagree");
        assert!(present || OPTIONAL.contains(layer), "layer `{layer}` has no module");
    }
}

#[test]
fn architecture_md_draws_these_layers_and_their_imports() {
    let doc = std::fs::read_to_string(crate_dir().join("../../ARCHITECTURE.md")).unwrap();
    let graph = architecture_graph(&doc);
    let names: Vec<&str> = graph.iter().map(|g| g.0.as_str()).collect();
    assert_eq!(names, LAYERS, "ARCHITECTURE.md's module graph and LAYERS");
    for layer in LAYERS {
        assert!(
            doc.contains(&format!("**{layer}**")),
            "ARCHITECTURE.md has no paragraph on `{layer}`"
        );
    }
    // The drawn imports are the real ones, no more and no fewer.
    let (found, _) = scan_library();
    let mut wrong = Vec::new();
    for (layer, drawn) in &graph {
        let Some(drawn) = drawn else { continue };
        let real: BTreeSet<String> = found
            .iter()
            .filter(|f| &f.own == layer && &f.top != layer && rank(&f.top).is_some())
            .map(|f| f.top.clone())
            .collect();
        if &real != drawn {
            wrong.push(format!(
                "{layer}: drawn {:?}, imported {:?} (missing from the drawing: {:?}; not imported: {:?})",
                drawn,
                real,
                real.difference(drawn).collect::<Vec<_>>(),
                drawn.difference(&real).collect::<Vec<_>>()
            ));
        }
    }
    assert!(wrong.is_empty(), "ARCHITECTURE.md's import lists are wrong:\n{}", wrong.join("\n"));
}

/// The scanner itself, on text made to trip it.
#[test]
fn the_scanner_finds_paths_and_only_paths() {
    let src = r##"
//! Docs mention crate::sim::Team and super::super::render: not imports.
use crate::{kernel::Point, world::{grid, polygon}};
pub use crate::protocol::CostModel;
use super::{Agent, Arena};
use super::super::strategy::X;
pub(crate) fn f<'a>(x: &'a str) -> char {
    let s = "crate::offline::y";
    let r = r#"crate::render::{"x"}"#;
    let c = '{';
    let q = '\'';
    /* crate::experiment::z /* nested */ crate::io */
    let _ = crate::offline::polygon::optimum(x);
    let _ = matches!(x, super::Thing);
    '}'
}
#[cfg(test)]
mod tests {
    use super::*;
    use super::super::super::generate::spiral;
    fn g() { $crate::sim::run(); }
}
"##;
    let module = vec!["world".to_string(), "grid".to_string()];
    let found: Vec<(usize, String)> =
        imports(&module, &tokens(src)).into_iter().map(|i| (i.line, i.top)).collect();
    let expect: Vec<(usize, String)> = [
        (3, "kernel"),
        (3, "world"),
        (4, "protocol"),
        (5, "world"),
        (6, "strategy"),
        (13, "offline"),
        (14, "world"),
        (19, "world"),
        (20, "generate"),
        (21, "sim"),
    ]
    .into_iter()
    .map(|(l, t)| (l, t.to_string()))
    .collect();
    assert_eq!(found, expect);
    assert_eq!(module_path(Path::new("world/grid/mod.rs")), ["world", "grid"]);
    assert_eq!(module_path(Path::new("sim/team.rs")), ["sim", "team"]);
    assert!(module_path(Path::new("lib.rs")).is_empty());
    let doc = "x\n## Module graph\n\n```\nkernel   a\n         b\ngeometry c\n  └ kernel (tests), io\n\
               io d\n  └ every layer below\npipeline e\n  └ any layer\n```\nkernel2\n";
    let set = |v: &[&str]| Some(v.iter().map(ToString::to_string).collect::<BTreeSet<_>>());
    assert_eq!(
        architecture_graph(doc),
        [
            ("kernel".to_string(), set(&[])),
            ("geometry".to_string(), set(&["kernel", "io"])),
            ("io".to_string(), set(&["kernel", "geometry"])),
            ("pipeline".to_string(), None)
        ]
    );
}
