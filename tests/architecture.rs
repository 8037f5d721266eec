//! The module graph of the library, read from its own `use crate::…`, `super::…` and `self::…`
//! paths (outside `#[cfg(test)]` items), against the layers of ARCHITECTURE.md:
//!
//! 1. no import cycle between top-level modules;
//! 2. no import cycle between the sibling modules of any folder (a sibling folder counts with
//!    everything inside it);
//! 3. no module importing from a higher layer, or from another module of its own layer, per
//!    the layer table of ARCHITECTURE.md (between `<!-- layers -->` and `<!-- /layers -->`:
//!    rows `| N | `module` | …`), which is declared there once and read here;
//! 4. every top-level module of `src/lib.rs` in exactly one layer, and at most
//!    [`MAX_TOP_LEVEL`] of them.
//!
//! A path is attributed to the deepest module it names (`crate::model::system::System` → the
//! module `model::system`); a path through a re-export counts as an import of the re-exporting
//! module. `src/main.rs` and its modules in `src/main/` (the CLI) are not part of the
//! library's graph.
//!
//! The checker was verified to fail on a cycle planted in the sources (a `use
//! crate::analysis::simulate::Report;` added to `src/model/system.rs`: rule 1 and rule 3 both
//! report it, naming the file and the path), and [`checker_finds_planted_cycles`] keeps that
//! property under test on a made-up crate.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The issue's bound on the number of top-level modules.
const MAX_TOP_LEVEL: usize = 14;

/// A module path, e.g. `["model", "system"]`; the crate root is empty.
type ModPath = Vec<String>;

/// One import: the path as written and the file it is in.
#[derive(Debug, Clone)]
struct Import {
    file: String,
    path: String,
}

/// The module graph: every module, and per (from, to) pair of modules the imports.
#[derive(Debug, Default)]
struct Graph {
    modules: BTreeSet<ModPath>,
    edges: BTreeMap<(ModPath, ModPath), Vec<Import>>,
}

fn module_of(rel: &Path) -> ModPath {
    let mut parts: Vec<String> = rel
        .iter()
        .map(|p| p.to_string_lossy().into_owned())
        .collect();
    let last = parts.pop().expect("a file name");
    let stem = last.trim_end_matches(".rs").to_string();
    if stem != "mod" && !(parts.is_empty() && stem == "lib") {
        parts.push(stem);
    }
    parts
}

/// Source text with comments, string and character literals blanked out (replaced by
/// spaces, so that offsets and braces inside them do not count).
fn code_only(text: &str) -> String {
    let b = text.as_bytes();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    let blank = |out: &mut String, s: &[u8]| {
        for &c in s {
            out.push(if c == b'\n' { '\n' } else { ' ' });
        }
    };
    while i < b.len() {
        let c = b[i];
        if c == b'/' && b.get(i + 1) == Some(&b'/') {
            let end = text[i..].find('\n').map_or(b.len(), |k| i + k);
            blank(&mut out, &b[i..end]);
            i = end;
        } else if c == b'/' && b.get(i + 1) == Some(&b'*') {
            let mut depth = 0;
            let start = i;
            while i < b.len() {
                if b[i] == b'/' && b.get(i + 1) == Some(&b'*') {
                    depth += 1;
                    i += 2;
                } else if b[i] == b'*' && b.get(i + 1) == Some(&b'/') {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
            blank(&mut out, &b[start..i.min(b.len())]);
        } else if c == b'r'
            && (b.get(i + 1) == Some(&b'"') || b.get(i + 1) == Some(&b'#'))
            && (i == 0 || !(b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_'))
        {
            // raw string r"…" / r#"…"#
            let mut j = i + 1;
            let mut hashes = 0;
            while b.get(j) == Some(&b'#') {
                hashes += 1;
                j += 1;
            }
            if b.get(j) != Some(&b'"') {
                out.push(c as char);
                i += 1;
                continue;
            }
            let close: String = std::iter::once('"')
                .chain(std::iter::repeat_n('#', hashes))
                .collect();
            let end = text[j + 1..]
                .find(&close)
                .map_or(b.len(), |k| j + 1 + k + close.len());
            blank(&mut out, &b[i..end]);
            i = end;
        } else if c == b'"' {
            let start = i;
            i += 1;
            while i < b.len() && b[i] != b'"' {
                i += if b[i] == b'\\' { 2 } else { 1 };
            }
            i = (i + 1).min(b.len());
            blank(&mut out, &b[start..i]);
        } else if c == b'\'' {
            // a character literal ('x', '\n', '{'), not a lifetime ('a)
            let is_char = b.get(i + 1) == Some(&b'\\')
                || (b.get(i + 2) == Some(&b'\'') && b.get(i + 1) != Some(&b'\''))
                || text[i + 1..].chars().next().is_some_and(|ch| {
                    ch.len_utf8() > 1 && text[i + 1 + ch.len_utf8()..].starts_with('\'')
                });
            if is_char {
                let start = i;
                i += 1;
                while i < b.len() && b[i] != b'\'' {
                    i += if b[i] == b'\\' { 2 } else { 1 };
                }
                i = (i + 1).min(b.len());
                blank(&mut out, &b[start..i]);
            } else {
                out.push('\'');
                i += 1;
            }
        } else {
            // copy one whole character
            let ch = text[i..].chars().next().expect("a character");
            out.push(ch);
            i += ch.len_utf8();
        }
    }
    out
}

/// `code` without its `#[cfg(test)]` items; the names of `#[cfg(test)] mod name;` (test-only
/// module files).
fn without_test_items(code: &str) -> (String, Vec<String>) {
    let mut out = String::with_capacity(code.len());
    let mut test_mods = Vec::new();
    let mut rest = code;
    while let Some(k) = rest.find("#[cfg(test)]") {
        out.push_str(&rest[..k]);
        let item = &rest[k..];
        let b = item.as_bytes();
        // the item ends at its first `;` before any `{`, or at the `}` matching that `{`
        let mut i = "#[cfg(test)]".len();
        let mut depth = 0usize;
        let mut end = b.len();
        while i < b.len() {
            match b[i] {
                b'[' | b'(' if depth == 0 => {
                    // another attribute or a visibility: skip its brackets
                    let (open, close) = if b[i] == b'[' {
                        (b'[', b']')
                    } else {
                        (b'(', b')')
                    };
                    let mut d = 0;
                    while i < b.len() {
                        if b[i] == open {
                            d += 1;
                        } else if b[i] == close {
                            d -= 1;
                            if d == 0 {
                                break;
                            }
                        }
                        i += 1;
                    }
                }
                b';' if depth == 0 => {
                    end = i + 1;
                    break;
                }
                b'{' => depth += 1,
                b'}' => {
                    depth -= 1;
                    if depth == 0 {
                        end = i + 1;
                        break;
                    }
                }
                _ => {}
            }
            i += 1;
        }
        let head = &item[..end.min(item.len())];
        let words: Vec<&str> = head
            .split(|c: char| !(c.is_alphanumeric() || c == '_'))
            .filter(|w| !w.is_empty())
            .collect();
        if head.trim_end().ends_with(';')
            && let Some(p) = words.iter().position(|w| *w == "mod")
            && let Some(name) = words.get(p + 1)
        {
            test_mods.push(name.to_string());
        }
        out.extend(head.chars().map(|c| if c == '\n' { '\n' } else { ' ' }));
        rest = &item[end.min(item.len())..];
    }
    out.push_str(rest);
    (out, test_mods)
}

fn is_ident(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// Every path starting with `crate`, `super` or `self` in `code`, with `use` groups expanded
/// (`crate::a::{b, c::d}` → `crate::a::b`, `crate::a::c::d`).
fn paths(code: &str) -> Vec<String> {
    let mut found = Vec::new();
    let b = code.as_bytes();
    let mut i = 0;
    while i < b.len() {
        let starts_word = i == 0 || !(is_ident(b[i - 1] as char) || b[i - 1] == b':');
        let head = ["crate::", "super::", "self::"]
            .into_iter()
            .any(|h| b[i..].starts_with(h.as_bytes()));
        if head && starts_word {
            // (an ASCII match: `i` is at a character boundary)
            let (tree, len) = use_tree(&code[i..]);
            found.extend(tree);
            i += len.max(1);
        } else {
            i += 1;
        }
    }
    found
}

/// The paths of the use tree (or plain path) at the start of `s`, and its length in bytes.
fn use_tree(s: &str) -> (Vec<String>, usize) {
    let b = s.as_bytes();
    let mut i = 0;
    let mut prefix = String::new();
    loop {
        // an identifier
        let start = i;
        while i < b.len() && is_ident(b[i] as char) {
            i += 1;
        }
        if i == start {
            break;
        }
        prefix.push_str(&s[start..i]);
        // `::` then another segment or a group
        let mut j = i;
        while j < b.len() && b[j].is_ascii_whitespace() {
            j += 1;
        }
        if !s[j..].starts_with("::") {
            return (vec![prefix], i);
        }
        j += 2;
        while j < b.len() && b[j].is_ascii_whitespace() {
            j += 1;
        }
        if b.get(j) == Some(&b'{') {
            // a group: split at top-level commas
            let mut depth = 0;
            let mut k = j;
            let mut items = Vec::new();
            let mut item_start = j + 1;
            while k < b.len() {
                match b[k] {
                    b'{' => depth += 1,
                    b'}' => {
                        depth -= 1;
                        if depth == 0 {
                            items.push(&s[item_start..k]);
                            break;
                        }
                    }
                    b',' if depth == 1 => {
                        items.push(&s[item_start..k]);
                        item_start = k + 1;
                    }
                    _ => {}
                }
                k += 1;
            }
            let mut out = Vec::new();
            for item in items {
                let item = item.trim();
                if item.is_empty() || item == "*" || item == "self" || item.starts_with("self ") {
                    out.push(prefix.clone());
                } else {
                    let (sub, _) = use_tree(item);
                    out.extend(sub.into_iter().map(|p| format!("{prefix}::{p}")));
                }
            }
            return (out, k + 1);
        }
        if b.get(j) == Some(&b'*') {
            return (vec![prefix], j + 1);
        }
        if !b.get(j).is_some_and(|&c| is_ident(c as char)) {
            return (vec![prefix], i);
        }
        prefix.push_str("::");
        i = j;
    }
    (vec![prefix], i)
}

/// The module a path names, resolved from module `at`: the deepest existing module prefix.
fn resolve(path: &str, at: &ModPath, modules: &BTreeSet<ModPath>) -> Option<ModPath> {
    let parts: Vec<&str> = path.split("::").map(str::trim).collect();
    let mut full: ModPath;
    let mut rest = &parts[..];
    if rest.first() == Some(&"crate") {
        full = Vec::new();
        rest = &rest[1..];
    } else {
        full = at.clone();
        while let Some(&p) = rest.first() {
            match p {
                "self" => {}
                "super" => {
                    full.pop();
                }
                _ => break,
            }
            rest = &rest[1..];
        }
    }
    full.extend(rest.iter().map(|s| s.to_string()));
    (0..=full.len())
        .rev()
        .map(|k| full[..k].to_vec())
        .find(|m| modules.contains(m))
}

/// The graph of the sources `files` (module path → (file name, text)).
fn graph(files: &BTreeMap<ModPath, (String, String)>) -> Graph {
    let mut g = Graph {
        modules: files.keys().cloned().collect(),
        ..Graph::default()
    };
    // test-only module files: those declared under #[cfg(test)], and everything inside them
    let mut test_only: BTreeSet<ModPath> = BTreeSet::new();
    let mut cleaned = BTreeMap::new();
    for (m, (_, text)) in files {
        let (code, test_mods) = without_test_items(&code_only(text));
        for t in test_mods {
            let mut p = m.clone();
            p.push(t);
            test_only.insert(p);
        }
        cleaned.insert(m.clone(), code);
    }
    for (m, code) in &cleaned {
        if test_only.iter().any(|t| m.starts_with(t)) {
            continue;
        }
        for p in paths(code) {
            let Some(to) = resolve(&p, m, &g.modules) else {
                continue;
            };
            if &to != m && !m.starts_with(&to) {
                g.edges.entry((m.clone(), to)).or_default().push(Import {
                    file: files[m].0.clone(),
                    path: p.split_whitespace().collect(),
                });
            }
        }
    }
    g
}

fn name(m: &[String]) -> String {
    if m.is_empty() {
        "crate".to_string()
    } else {
        m.join("::")
    }
}

/// The strongly connected components of more than one node (Tarjan).
fn cycles(
    nodes: &BTreeSet<ModPath>,
    adj: &BTreeMap<ModPath, BTreeSet<ModPath>>,
) -> Vec<Vec<ModPath>> {
    struct T<'a> {
        adj: &'a BTreeMap<ModPath, BTreeSet<ModPath>>,
        index: BTreeMap<ModPath, usize>,
        low: BTreeMap<ModPath, usize>,
        stack: Vec<ModPath>,
        on: BTreeSet<ModPath>,
        out: Vec<Vec<ModPath>>,
    }
    fn strong(t: &mut T, v: &ModPath) {
        let i = t.index.len();
        t.index.insert(v.clone(), i);
        t.low.insert(v.clone(), i);
        t.stack.push(v.clone());
        t.on.insert(v.clone());
        for w in t.adj.get(v).into_iter().flatten() {
            if !t.index.contains_key(w) {
                strong(t, w);
                let l = t.low[v].min(t.low[w]);
                t.low.insert(v.clone(), l);
            } else if t.on.contains(w) {
                let l = t.low[v].min(t.index[w]);
                t.low.insert(v.clone(), l);
            }
        }
        if t.low[v] == t.index[v] {
            let mut c = Vec::new();
            loop {
                let w = t.stack.pop().expect("on the stack");
                t.on.remove(&w);
                c.push(w.clone());
                if &w == v {
                    break;
                }
            }
            if c.len() > 1 {
                c.sort();
                t.out.push(c);
            }
        }
    }
    let mut t = T {
        adj,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on: BTreeSet::new(),
        out: Vec::new(),
    };
    for v in nodes {
        if !t.index.contains_key(v) {
            strong(&mut t, v);
        }
    }
    t.out
}

/// Rules 1 and 2: per folder (the crate root first), the cycles between its children, each
/// child with everything inside it; one message per cycle, with the imports that make it.
fn cycle_errors(g: &Graph) -> Vec<String> {
    let folders: BTreeSet<ModPath> = g
        .modules
        .iter()
        .filter(|m| !m.is_empty())
        .map(|m| m[..m.len() - 1].to_vec())
        .collect();
    let mut errors = Vec::new();
    for folder in folders {
        let n = folder.len();
        let child = |m: &ModPath| -> Option<ModPath> {
            (m.len() > n && m.starts_with(&folder)).then(|| m[..=n].to_vec())
        };
        let nodes: BTreeSet<ModPath> = g.modules.iter().filter_map(child).collect();
        let mut adj: BTreeMap<ModPath, BTreeSet<ModPath>> = BTreeMap::new();
        let mut why: BTreeMap<(ModPath, ModPath), Vec<&Import>> = BTreeMap::new();
        for ((a, b), imports) in &g.edges {
            if let (Some(ca), Some(cb)) = (child(a), child(b))
                && ca != cb
            {
                adj.entry(ca.clone()).or_default().insert(cb.clone());
                why.entry((ca, cb)).or_default().extend(imports);
            }
        }
        for c in cycles(&nodes, &adj) {
            let mut msg = format!(
                "import cycle between the modules of {}: {}",
                name(&folder),
                c.iter().map(|m| name(m)).collect::<Vec<_>>().join(" <-> ")
            );
            for ((a, b), imports) in &why {
                if c.contains(a) && c.contains(b) {
                    let i = imports[0];
                    msg.push_str(&format!(
                        "\n    {} -> {}: {} uses `{}`{}",
                        name(a),
                        name(b),
                        i.file,
                        i.path,
                        if imports.len() > 1 {
                            format!(" (and {} more)", imports.len() - 1)
                        } else {
                            String::new()
                        }
                    ));
                }
            }
            errors.push(msg);
        }
    }
    errors
}

/// Rule 3: every import between top-level modules goes to a strictly lower layer.
fn layer_errors(g: &Graph, layers: &BTreeMap<String, u32>) -> Vec<String> {
    let mut errors = Vec::new();
    for ((a, b), imports) in &g.edges {
        let (Some(ta), Some(tb)) = (a.first(), b.first()) else {
            continue;
        };
        if ta == tb {
            continue;
        }
        let (Some(&la), Some(&lb)) = (layers.get(ta), layers.get(tb)) else {
            continue; // reported by rule 4
        };
        if lb >= la {
            let i = &imports[0];
            errors.push(format!(
                "{} (layer {la}) imports {} (layer {lb}{}): {} uses `{}`",
                name(a),
                name(b),
                if lb == la {
                    ", the same layer"
                } else {
                    ", higher"
                },
                i.file,
                i.path
            ));
        }
    }
    errors
}

/// The layer table of ARCHITECTURE.md: module → layer.
fn layer_table(doc: &str) -> BTreeMap<String, u32> {
    let start = doc
        .find("<!-- layers -->")
        .expect("ARCHITECTURE.md has a `<!-- layers -->` table");
    let end = doc[start..]
        .find("<!-- /layers -->")
        .expect("ARCHITECTURE.md closes its layer table with `<!-- /layers -->`")
        + start;
    let mut table = BTreeMap::new();
    for line in doc[start..end].lines() {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        // | N | `module` | …
        if cells.len() < 3 {
            continue;
        }
        let Ok(layer) = cells[1].parse::<u32>() else {
            continue;
        };
        let module = cells[2].trim_matches('`');
        let prev = table.insert(module.to_string(), layer);
        assert!(
            prev.is_none(),
            "ARCHITECTURE.md: `{module}` is in two layers"
        );
    }
    assert!(
        !table.is_empty(),
        "ARCHITECTURE.md: the layer table has no rows"
    );
    table
}

fn read_sources(src: &Path) -> BTreeMap<ModPath, (String, String)> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for e in std::fs::read_dir(dir).expect("src/ is readable") {
            let p = e.expect("a directory entry").path();
            if p.is_dir() {
                walk(&p, out);
            } else if p.extension().is_some_and(|x| x == "rs") {
                out.push(p);
            }
        }
    }
    let mut files = Vec::new();
    walk(src, &mut files);
    let mut out = BTreeMap::new();
    for f in files {
        let rel = f.strip_prefix(src).expect("under src/");
        // the binary: src/main.rs and its modules in src/main/
        if rel == Path::new("main.rs") || rel.starts_with("main") {
            continue;
        }
        let text = std::fs::read_to_string(&f).expect("a source file is UTF-8");
        out.insert(module_of(rel), (format!("src/{}", rel.display()), text));
    }
    out
}

/// The top-level modules `src/lib.rs` declares.
fn top_level(lib: &str) -> Vec<String> {
    code_only(lib)
        .lines()
        .filter_map(|l| {
            let l = l.trim();
            let rest = l
                .strip_prefix("pub mod ")
                .or_else(|| l.strip_prefix("mod "))?;
            Some(rest.trim_end_matches(';').trim().to_string())
        })
        .collect()
}

#[test]
fn the_module_graph_follows_the_layers() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let files = read_sources(&root.join("src"));
    let doc = std::fs::read_to_string(root.join("ARCHITECTURE.md")).expect("ARCHITECTURE.md");
    let layers = layer_table(&doc);
    let top = top_level(&files[&Vec::new()].1);

    let mut errors = Vec::new();
    // rule 4
    if top.len() > MAX_TOP_LEVEL {
        errors.push(format!(
            "src/lib.rs declares {} top-level modules, more than {MAX_TOP_LEVEL}: {}",
            top.len(),
            top.join(", ")
        ));
    }
    for m in &top {
        if !layers.contains_key(m) {
            errors.push(format!(
                "the top-level module `{m}` is in no layer of ARCHITECTURE.md's table"
            ));
        }
    }
    for m in layers.keys() {
        if !top.contains(m) {
            errors.push(format!(
                "ARCHITECTURE.md's layer table names `{m}`, which src/lib.rs does not declare"
            ));
        }
    }
    let g = graph(&files);
    // the reading itself: the graph has the arrows every layer above the model must have
    assert!(
        g.edges
            .keys()
            .any(|(a, b)| a.first().is_some_and(|x| x == "integrate")
                && b.first().is_some_and(|x| x == "model")),
        "no import of `model` by `integrate` was read: the path reader is broken"
    );
    // the graph between top-level modules, by layer (`cargo test --release --test architecture
    // -- --nocapture` shows it)
    let mut uses: BTreeMap<&str, BTreeSet<&str>> = BTreeMap::new();
    for (a, b) in g.edges.keys() {
        if let (Some(x), Some(y)) = (a.first(), b.first())
            && x != y
        {
            uses.entry(x.as_str()).or_default().insert(y.as_str());
        }
    }
    let mut by_layer: Vec<(&u32, &String)> = layers.iter().map(|(m, l)| (l, m)).collect();
    by_layer.sort();
    println!("the module graph (layer, module: the top-level modules it uses)");
    for (l, m) in by_layer {
        let used: Vec<&str> = uses
            .get(m.as_str())
            .into_iter()
            .flatten()
            .copied()
            .collect();
        println!("{l:>3}  {m:<10} {}", used.join(", "));
    }
    errors.extend(cycle_errors(&g));
    errors.extend(layer_errors(&g, &layers));
    assert!(
        errors.is_empty(),
        "the module graph breaks the architecture (ARCHITECTURE.md):\n\n{}\n",
        errors.join("\n\n")
    );
}

/// A made-up crate with a cycle between top-level modules, one between siblings of a folder
/// (through a grandchild and a `use` group), an upward import and an import in a test module
/// (which does not count): the checker reports exactly the first three.
#[test]
fn checker_finds_planted_cycles() {
    let src = |m: &str, text: &str| {
        let path: ModPath = if m.is_empty() {
            Vec::new()
        } else {
            m.split("::").map(str::to_string).collect()
        };
        (path, (format!("src/{m}.rs"), text.to_string()))
    };
    let files: BTreeMap<ModPath, (String, String)> = [
        src("", "pub mod low; pub mod high; pub mod other;"),
        src("low", "pub mod a; pub mod b;\nuse crate::high::Thing; // planted: upward\n"),
        src("low::a", "use super::b::deep::{X, Y as Z};\n"),
        src("low::b", "pub mod deep;\n"),
        src("low::b::deep", "use crate::low::a::A; // planted: a <-> b\nconst S: &str = \"crate::other\";"),
        src("high", "use crate::low::a;\n"),
        src(
            "other",
            "#[cfg(test)]\nmod tests {\n    use crate::high::Thing;\n    fn f() { let _ = '{'; }\n}\n",
        ),
    ]
    .into_iter()
    .collect();
    let g = graph(&files);
    let layers: BTreeMap<String, u32> = [("low", 0), ("other", 0), ("high", 1)]
        .into_iter()
        .map(|(m, l)| (m.to_string(), l))
        .collect();
    let cyc = cycle_errors(&g);
    assert_eq!(cyc.len(), 2, "{cyc:#?}");
    assert!(cyc[0].contains("crate: high <-> low"), "{}", cyc[0]);
    assert!(
        cyc[0].contains("src/low.rs uses `crate::high::Thing`"),
        "{}",
        cyc[0]
    );
    assert!(cyc[1].contains("low: low::a <-> low::b"), "{}", cyc[1]);
    let up = layer_errors(&g, &layers);
    assert_eq!(up.len(), 1, "{up:#?}");
    assert!(
        up[0].starts_with("low (layer 0) imports high (layer 1, higher)"),
        "{}",
        up[0]
    );
    // nothing from the test module, the string or the character literal
    assert!(!g.edges.keys().any(|(a, _)| a == &vec!["other".to_string()]));
}
