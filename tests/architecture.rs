//! The dependency order of `src/` runs one way.
//!
//! 1. No file of `src/` imports a file that, directly or through others,
//!    imports it back (nor does a file of the ray caster or the study). Files in a circle can be neither read, tested, moved
//!    nor replaced one without the other, and layers stop meaning anything.
//! 2. The layers keep their order ([`LAYERS`]).
//!
//! The test only reads the sources. Each file loses its comments, string and
//! char literals and `#[cfg(test)]` items (unit tests may import anything);
//! then every path into the crate is collected (`use` trees, and inline paths
//! starting with `crate`, `super`, `self`, a child module or an imported
//! name) and resolved to the file that *defines* the item, following `use`
//! re-exports from module to module. A name that is not found (another
//! crate's, a glob) resolves to the module file reached so far. A module
//! file's use of its own descendants is not an edge: a module (`lib.rs`,
//! `curve/mod.rs`) is the interface of the files below it, declares them,
//! re-exports them and may call them (a trait's default methods call its
//! implementations' helpers), while they build on it.
//!
//! Limits: paths built by macros are not seen; `#[path]` is not followed
//! (the test asserts there is none); an inline non-test `mod x { … }` counts
//! as part of its file; a block comment ends at its first `*/`; an
//! identifier spelled like a name a facade re-exports counts as a use of it.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// Source texts by path relative to the package (`src/lib.rs`).
type Sources = BTreeMap<String, String>;
/// Edges file → file, each with the names that tie the two files.
type Graph = BTreeMap<String, BTreeMap<String, BTreeSet<String>>>;

/// Files under the first prefixes may not depend on files under the second:
/// the curve layer knows no rays or surfaces, `ray/` is the shared bottom of
/// every intersector, and the surface kinds are independent of each other.
const LAYERS: &[(&str, &str)] = &[
    (
        "src/curve/ src/bernstein.rs src/roots.rs src/aabb.rs src/error.rs",
        "src/ray/ src/revolution/ src/tensor/ src/mesh.rs src/surface.rs",
    ),
    ("src/ray/", "src/revolution/ src/tensor/"),
    ("src/revolution/", "src/tensor/"),
    ("src/tensor/", "src/revolution/"),
];

/// One binding of a `use`: the path as written and the name it binds.
struct Use {
    path: Vec<String>,
    name: String,
}

/// A source file, with its `#[cfg(test)]` items dropped.
struct File {
    module: Vec<String>,
    /// The tokens outside `use` statements.
    code: Vec<String>,
    uses: Vec<Use>,
    /// The names of the items the file defines.
    defs: BTreeSet<String>,
}

/// `src/lib.rs` (or `src/main.rs`) is the root, `src/a.rs` and
/// `src/a/mod.rs` are `a`, `src/a/b.rs` is `a::b`.
fn module_of(path: &str) -> Vec<String> {
    let rel = path.trim_start_matches("src/").trim_end_matches(".rs");
    let mut module: Vec<String> = rel.split('/').map(String::from).collect();
    if rel == "lib" || rel == "main" || module.last().is_some_and(|s| s == "mod") {
        module.pop();
    }
    module
}

/// The tokens of `text`: identifiers (and numbers, lifetimes), `::` and
/// single punctuation characters; comments, string and char literals are
/// dropped.
fn tokenize(text: &str) -> Vec<String> {
    let c: Vec<char> = text.chars().collect();
    let word = |ch: &char| ch.is_alphanumeric() || *ch == '_';
    let (mut tokens, mut i) = (Vec::new(), 0);
    while i < c.len() {
        let rest = &c[i..];
        let prefix = rest.iter().take(2).take_while(|ch| matches!(ch, 'b' | 'r'));
        let prefix = prefix.count();
        let raw = rest[..prefix].contains(&'r');
        let hashes = rest[prefix..].iter().take_while(|&&ch| ch == '#').count();
        let (len, keep) = if rest.starts_with(&['/', '/']) {
            let end = rest.iter().position(|&ch| ch == '\n');
            (end.unwrap_or(rest.len()), false)
        } else if rest.starts_with(&['/', '*']) {
            let end = rest[2..].windows(2).position(|w| w == ['*', '/']);
            (end.map_or(rest.len(), |k| k + 4), false)
        } else if rest.get(prefix + hashes) == Some(&'"') && (raw || hashes == 0) {
            let closes = |k: usize| rest[k + 1..].iter().take(hashes).all(|&h| h == '#');
            let mut k = prefix + hashes + 1;
            while k < rest.len() && !(rest[k] == '"' && closes(k)) {
                k += if rest[k] == '\\' && !raw { 2 } else { 1 };
            }
            (k + 1 + hashes, false)
        } else if rest[0] == '\'' && (rest.get(1) == Some(&'\\') || rest.get(2) == Some(&'\'')) {
            // A char literal (a lifetime has no closing quote).
            let from = if rest[1] == '\\' { 3 } else { 2 };
            let close = rest.iter().skip(from).position(|&ch| ch == '\'');
            (from + 1 + close.unwrap_or(0), false)
        } else if word(&rest[0]) || rest[0] == '\'' {
            // A word, or a lifetime such as `'static` (one token).
            let quote = usize::from(rest[0] == '\'');
            (
                quote + rest[quote..].iter().take_while(|ch| word(ch)).count(),
                true,
            )
        } else {
            let len = 1 + usize::from(rest.starts_with(&[':', ':']));
            (len, !rest[0].is_whitespace())
        };
        if keep {
            tokens.push(rest[..len].iter().collect());
        }
        i += len;
    }
    tokens
}

fn is_ident(token: &str) -> bool {
    token.starts_with(|ch: char| ch.is_alphabetic() || ch == '_')
}

fn is(t: &[String], k: usize, token: &str) -> bool {
    t.get(k).is_some_and(|s| s == token)
}

/// The index after the bracket group (of any kind) opening at `t[open]`.
fn group_end(t: &[String], open: usize) -> usize {
    let mut depth = 0;
    for (k, token) in t.iter().enumerate().skip(open) {
        depth += i32::from(matches!(token.as_str(), "(" | "[" | "{"));
        depth -= i32::from(matches!(token.as_str(), ")" | "]" | "}"));
        if depth == 0 {
            return k + 1;
        }
    }
    t.len()
}

/// `t` without its `#[cfg(test)]` items (a `mod tests { … }` block, a
/// test-only `fn`, `impl`, `use`, `mod x;`…), with their other attributes.
fn drop_test_items(t: &[String]) -> Vec<String> {
    const ITEMS: &str = "mod fn impl struct enum trait use const static type macro_rules let";
    let cfg_test = ["#", "[", "cfg", "(", "test", ")", "]"].map(String::from);
    let (mut out, mut i) = (Vec::new(), 0);
    while i < t.len() {
        let gated = t[i..].starts_with(&cfg_test);
        let mut k = i + cfg_test.len();
        while gated && is(t, k, "#") {
            k = group_end(t, k + 1);
        }
        k += usize::from(gated && is(t, k, "pub"));
        if gated && is(t, k, "(") {
            k = group_end(t, k);
        }
        let item = ITEMS.split(' ').any(|item| is(t, k, item));
        if !gated || !item {
            out.push(t[i].clone());
            i += 1;
            continue;
        }
        let mut depth = 0;
        while k < t.len() && !(depth == 0 && (t[k] == ";" || t[k] == "{")) {
            depth += i32::from(t[k] == "(" || t[k] == "[") - i32::from(t[k] == ")" || t[k] == "]");
            k += 1;
        }
        i = group_end(t, k); // past the `;`, or past the `{ … }` block
    }
    out
}

/// Reads one use tree at `t[*at]` below `path`, its bindings into `out`.
fn use_tree(t: &[String], at: &mut usize, mut path: Vec<String>, out: &mut Vec<Use>) {
    while let Some(token) = t.get(*at) {
        *at += 1;
        if token == "{" {
            while t.get(*at).is_some_and(|s| s != "}") {
                use_tree(t, at, path.clone(), out);
                *at += usize::from(is(t, *at, ","));
            }
            *at += 1;
            return;
        } else if token != "::" && token != "*" && !is_ident(token) {
            return;
        } else if token == "::" || is(t, *at, "::") {
            path.extend((token != "::").then(|| token.clone()));
            continue;
        }
        path.extend((token != "self").then(|| token.clone()));
        let mut name = path.last().cloned().unwrap_or_default();
        if is(t, *at, "as") {
            name = t.get(*at + 1).cloned().unwrap_or_default();
            *at += 2;
        }
        return out.push(Use { path, name });
    }
}

impl File {
    fn parse(path: &str, text: &str) -> File {
        let all = tokenize(text);
        let path_attr = all.windows(3).any(|w| w == ["#", "[", "path"]);
        assert!(!path_attr, "{path}: #[path] is new; teach this test");
        let t = drop_test_items(&all);
        let (mut code, mut uses, mut defs, mut i) = (vec![], vec![], BTreeSet::new(), 0);
        while i < t.len() {
            if t[i] == "use" {
                i += 1;
                use_tree(&t, &mut i, Vec::new(), &mut uses);
                continue;
            }
            match t[i].as_str() {
                "struct" | "enum" | "trait" | "fn" | "const" | "static" | "type" | "mod" => {
                    defs.extend(t.get(i + 1).filter(|s| is_ident(s)).cloned());
                }
                "macro_rules" => defs.extend(t.get(i + 2).cloned()),
                _ => {}
            }
            code.push(t[i].clone());
            i += 1;
        }
        let module = module_of(path);
        File {
            module,
            code,
            uses,
            defs,
        }
    }
}

/// `path`, written in `module`, as the module it starts from and the names
/// left to look up there.
fn absolute(module: &[String], path: &[String]) -> (Vec<String>, Vec<String>) {
    let (mut base, mut rest) = (module.to_vec(), path);
    match path.first().map(String::as_str) {
        Some("crate") => (base, rest) = (Vec::new(), &path[1..]),
        Some("self") => rest = &path[1..],
        _ => {}
    }
    while rest.first().is_some_and(|s| s == "super") {
        base.pop();
        rest = &rest[1..];
    }
    (base, rest.to_vec())
}

/// The crate: the files by path and the file of each module.
struct Crate {
    files: BTreeMap<String, File>,
    modules: BTreeMap<Vec<String>, String>,
}

impl Crate {
    /// The file defining `names` looked up in `module`, and the name that
    /// was found there (or the first that was not).
    fn resolve(&self, module: &[String], names: &[String], depth: usize) -> (String, String) {
        let path = &self.modules[module];
        let Some(first) = names.first() else {
            let name = module.last().map_or("crate", String::as_str);
            return (path.clone(), name.to_string());
        };
        let child = [module, &names[..1]].concat();
        if self.modules.contains_key(&child) {
            return self.resolve(&child, &names[1..], depth);
        }
        let file = &self.files[path];
        match file.uses.iter().find(|u| &u.name == first) {
            Some(u) if !file.defs.contains(first) && depth < 32 => {
                let (base, rest) = absolute(module, &u.path);
                self.resolve(&base, &[rest.as_slice(), &names[1..]].concat(), depth + 1)
            }
            _ => (path.clone(), first.clone()),
        }
    }

    /// Every file `f` depends on, with a name that ties the two.
    fn dependencies(&self, f: &File) -> Vec<(String, String)> {
        let mut out = Vec::new();
        for u in &f.uses {
            let (base, rest) = absolute(&f.module, &u.path);
            let (to, name) = self.resolve(&base, &rest, 0);
            out.push((to, name));
        }
        let t = &f.code;
        for (i, first) in t.iter().enumerate() {
            if (i > 0 && t[i - 1] == "::") || !is_ident(first) || !is(t, i + 1, "::") {
                continue;
            }
            let mut names = vec![first.clone()];
            while let [colons, name, ..] = &t[(i + 2 * names.len() - 1).min(t.len())..] {
                if colons != "::" || !is_ident(name) {
                    break;
                }
                names.push(name.clone());
            }
            let child = [f.module.as_slice(), &names[..1]].concat();
            let (base, rest) = if matches!(first.as_str(), "crate" | "self" | "super") {
                absolute(&f.module, &names)
            } else if let Some(u) = f.uses.iter().find(|u| &u.name == first) {
                let (base, rest) = absolute(&f.module, &u.path);
                (base, [rest.as_slice(), &names[1..]].concat())
            } else if self.modules.contains_key(&child) {
                (f.module.clone(), names)
            } else {
                continue;
            };
            out.push(self.resolve(&base, &rest, 0));
        }
        out
    }
}

/// The dependency graph of `sources` (paths `src/…` → texts), without
/// self-edges.
fn graph_of(sources: &Sources) -> Graph {
    let parse = |(path, text): (&String, &String)| (path.clone(), File::parse(path, text));
    let files: BTreeMap<_, _> = sources.iter().map(parse).collect();
    let modules = files.iter().map(|(p, f)| (f.module.clone(), p.clone()));
    let krate = Crate {
        modules: modules.collect(),
        files,
    };
    let mut graph = Graph::new();
    for (path, file) in &krate.files {
        let edges = graph.entry(path.clone()).or_default();
        for (to, name) in krate.dependencies(file) {
            let below = &krate.files[&to].module;
            let descendant = below.len() > file.module.len() && below.starts_with(&file.module);
            if &to != path && !descendant {
                edges.entry(to).or_default().insert(name);
            }
        }
    }
    graph
}

/// The groups of files that reach each other (the strongly connected
/// components of more than one file), each sorted.
fn cycles(graph: &Graph) -> Vec<Vec<String>> {
    fn reach<'g>(graph: &'g Graph, from: &'g String) -> BTreeSet<&'g String> {
        let (mut seen, mut todo) = (BTreeSet::new(), vec![from]);
        while let Some(file) = todo.pop() {
            todo.extend(graph[file].keys().filter(|to| seen.insert(*to)));
        }
        seen
    }
    let reach: BTreeMap<_, _> = graph.keys().map(|f| (f, reach(graph, f))).collect();
    let mutual = |f: &String, g: &String| reach[f].contains(g) && reach[g].contains(f);
    let component = |f| graph.keys().filter(|g| mutual(f, g)).cloned().collect();
    let found: BTreeSet<Vec<String>> = graph.keys().map(component).collect();
    found.into_iter().filter(|c| c.len() > 1).collect()
}

/// `  from -> to: names` and a newline.
fn edge_line(graph: &Graph, from: &str, to: &str) -> String {
    let names: Vec<&str> = graph[from][to].iter().map(String::as_str).collect();
    format!("  {from} -> {to}: {}\n", names.join(", "))
}

/// Each circle with the edges inside it, or "" if there is none.
fn circle_report(graph: &Graph) -> String {
    let mut report = String::new();
    for cycle in cycles(graph) {
        report += &format!("import circle among {}:\n", cycle.join(", "));
        for from in &cycle {
            for to in graph[from].keys().filter(|to| cycle.contains(to)) {
                report += &edge_line(graph, from, to);
            }
        }
    }
    report
}

/// The edges against [`LAYERS`], or "" if there is none.
fn layer_report(graph: &Graph) -> String {
    let under = |file: &str, prefixes: &str| prefixes.split(' ').any(|p| file.starts_with(p));
    let mut report = String::new();
    for (from, edges) in graph {
        for to in edges.keys() {
            for (lower, upper) in LAYERS {
                if under(from, lower) && under(to, upper) {
                    report += &format!("{lower} may not depend on {upper}:\n");
                    report += &edge_line(graph, from, to);
                }
            }
        }
    }
    report
}

/// Every `.rs` file under the library's `src/`, keyed `src/…`.
fn read_src() -> Sources {
    let sources = read_package(".");
    assert!(sources.contains_key("src/lib.rs"), "src/lib.rs not found");
    sources
}

/// Every `.rs` file under `src/` of the workspace member at `dir`
/// (relative to the repository's root), keyed `src/…`.
fn read_package(dir: &str) -> Sources {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join(dir);
    let root = root.as_path();
    let (mut sources, mut dirs) = (Sources::new(), vec![root.join("src")]);
    while let Some(dir) = dirs.pop() {
        for entry in std::fs::read_dir(dir).expect("a readable directory") {
            let path = entry.expect("a directory entry").path();
            if path.is_dir() {
                dirs.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let key = path.strip_prefix(root).expect("a path in the package");
                let text = std::fs::read_to_string(&path).expect("a readable source file");
                sources.insert(key.to_string_lossy().replace('\\', "/"), text);
            }
        }
    }
    sources
}

#[test]
fn no_import_circles() {
    let report = circle_report(&graph_of(&read_src()));
    let hint = "files of src/ import each other; move what ties them";
    assert!(report.is_empty(), "{hint}:\n{report}");
}

#[test]
fn no_import_circles_in_the_ray_caster_and_the_study() {
    for dir in ["apps/raycast", "studies/accuracy_cost"] {
        let sources = read_package(dir);
        assert!(
            sources.contains_key("src/main.rs"),
            "{dir}/src/main.rs not found"
        );
        let report = circle_report(&graph_of(&sources));
        let hint = format!("files of {dir}/src/ import each other; move what ties them");
        assert!(report.is_empty(), "{hint}:\n{report}");
    }
}

#[test]
fn layers_keep_their_order() {
    let report = layer_report(&graph_of(&read_src()));
    let hint = "dependencies against the layering";
    assert!(report.is_empty(), "{hint}:\n{report}");
}

/// The graph of a tiny in-memory crate.
fn fixture(files: &[(&str, &str)]) -> Graph {
    let sources = files.iter().map(|(p, t)| (p.to_string(), t.to_string()));
    graph_of(&sources.collect())
}

/// Every edge of `graph`, as `from -> to: names`.
fn edges(graph: &Graph) -> Vec<String> {
    let mut lines = Vec::new();
    for (from, edges) in graph {
        for to in edges.keys() {
            lines.push(edge_line(graph, from, to).trim().to_string());
        }
    }
    lines
}

#[test]
fn a_two_file_circle_is_found() {
    let a = "use crate::b::B;\npub struct A(B);\n";
    let b = "pub struct B;\nfn f() { let _ = super::a::A(B); }\n";
    let graph = fixture(&[
        ("src/lib.rs", "mod a;\nmod b;\n"),
        ("src/a.rs", a),
        ("src/b.rs", b),
    ]);
    let edges = "  src/a.rs -> src/b.rs: B\n  src/b.rs -> src/a.rs: A\n";
    let expected = format!("import circle among src/a.rs, src/b.rs:\n{edges}");
    assert_eq!(circle_report(&graph), expected);
}

#[test]
fn a_re_export_chain_is_followed_to_the_defining_file() {
    let lib = "mod outer;\nmod user;\npub use outer::{Deep as Renamed};\n";
    let outer = "mod inner;\npub(crate) use self::inner::Deep;\n";
    let user = "fn f() -> crate::Renamed { crate::Renamed }\n";
    let graph = fixture(&[
        ("src/lib.rs", lib),
        ("src/outer/mod.rs", outer),
        ("src/outer/inner.rs", "pub struct Deep;\n"),
        ("src/user.rs", user),
    ]);
    assert_eq!(edges(&graph), ["src/user.rs -> src/outer/inner.rs: Deep"]);
}

#[test]
fn test_items_comments_and_strings_are_ignored() {
    let a = "pub fn a() {}\n#[cfg(test)]\n#[allow(unused)]\nmod tests {\n    use crate::b::B;\n}\n";
    let b = "pub struct B; // crate::c::C\n/* use crate::c::C; */ const S: &str = \"crate::c\";\n\
             #[cfg(test)]\nfn t() -> [u8; 2] { crate::c::C }\nfn f() { crate::a::a() }\n";
    let lib = "mod a;\nmod b;\nmod c;\n";
    let graph = fixture(&[
        ("src/lib.rs", lib),
        ("src/a.rs", a),
        ("src/b.rs", b),
        ("src/c.rs", ""),
    ]);
    assert_eq!(edges(&graph), ["src/b.rs -> src/a.rs: a"]);
}

#[test]
fn a_grouped_multi_line_import_is_parsed() {
    let user = "pub use crate::{\n    a::A,\n    b::{B as Bee, c::{self, c as see}},\n};\n\
                fn f() { c::c() }\n";
    let graph = fixture(&[
        ("src/lib.rs", "mod a;\nmod b;\nmod user;\n"),
        ("src/a.rs", "pub struct A;\n"),
        ("src/b/mod.rs", "mod c;\npub struct B;\n"),
        ("src/b/c.rs", "use super::super::a::A;\npub fn c() {}\n"),
        ("src/user.rs", user),
    ]);
    let expected = [
        "src/b/c.rs -> src/a.rs: A",
        "src/user.rs -> src/a.rs: A",
        "src/user.rs -> src/b/c.rs: c",
        "src/user.rs -> src/b/mod.rs: B",
    ];
    assert_eq!(edges(&graph), expected);
}

#[test]
fn a_module_using_its_own_children_is_not_an_edge() {
    let lib = "pub const ROOT: u8 = 0;\nmod child;\npub use child::Thing;\nfn f(_: Thing) {}\n";
    let child = ("src/child.rs", "use super::ROOT;\npub struct Thing;\n");
    let graph = fixture(&[("src/lib.rs", lib), child]);
    assert_eq!(edges(&graph), ["src/child.rs -> src/lib.rs: ROOT"]);
    assert!(cycles(&graph).is_empty());
    // Two children using each other are a circle.
    let lib = "mod a;\nmod b;\n";
    let a = ("src/a.rs", "use crate::b::B;\npub struct A(B);\n");
    let b = (
        "src/b.rs",
        "use crate::a::A;\npub struct B(Option<Box<A>>);\n",
    );
    let graph = fixture(&[("src/lib.rs", lib), a, b]);
    assert_eq!(cycles(&graph), [["src/a.rs", "src/b.rs"]]);
}
