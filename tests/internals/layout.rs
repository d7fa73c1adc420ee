//! The source tree's layout holds what docs/ARCHITECTURE.md says of it: no import circles
//! among the modules of `src/`, a `src/codecs/` whose top holds the registry and folders,
//! and every family in a file named after it.
//!
//! The import graph is read from the source text: a module depends on another where its
//! code (comments and string literals removed) names a path into it, `crate::a::b::Item`,
//! `super::b`, `self::b` or a `use` group `crate::a::{b, c::D}`, resolved to the longest
//! module path that exists. A module naming one of its own ancestors is not an edge: an
//! ancestor's items (the codec registry, re-exports) are the module's own namespace.
//! A circle is a strongly connected component of more than one module.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// `a::b` for src/a/b.rs and src/a/b/mod.rs; "" for lib.rs and main.rs.
fn module_of(root: &Path, file: &Path) -> Vec<String> {
    let rel = file.strip_prefix(root).unwrap().with_extension("");
    let mut parts: Vec<String> = rel
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    if matches!(
        parts.last().map(String::as_str),
        Some("mod" | "lib" | "main")
    ) {
        parts.pop();
    }
    parts
}

/// The text without comments, string and char literals (a doc link is no dependency).
fn code_only(text: &str) -> String {
    scan(text).0
}

fn ident(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

/// Every path the code names from `crate`, `super` or `self`, made absolute, with the
/// items of `use` groups expanded (one level of braces, nested paths kept whole).
fn paths(code: &str, module: &[String]) -> Vec<Vec<String>> {
    let chars: Vec<char> = code.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let starts = |w: &str| {
            chars[i..].starts_with(&w.chars().collect::<Vec<_>>())
                && (i == 0 || !ident(chars[i - 1]))
        };
        let Some(root) = ["crate::", "super::", "self::"]
            .into_iter()
            .find(|w| starts(w))
        else {
            i += 1;
            continue;
        };
        // The segments up to a non-path character or a brace group.
        let mut segs: Vec<String> = vec![root.trim_end_matches(':').to_string()];
        i += root.len();
        let mut cur = String::new();
        let mut group = None;
        while i < chars.len() {
            let c = chars[i];
            if ident(c) {
                cur.push(c);
                i += 1;
            } else if chars[i..].starts_with(&[':', ':']) {
                segs.push(std::mem::take(&mut cur));
                i += 2;
            } else if c == '{' && cur.is_empty() {
                let end = (i..chars.len()).find(|&j| chars[j] == '}').unwrap();
                group = Some(chars[i + 1..end].iter().collect::<String>());
                i = end + 1;
                break;
            } else {
                break;
            }
        }
        if !cur.is_empty() {
            segs.push(cur);
        }
        // Absolute: `crate` is the root, `super` the module's parent, `self` the module.
        let mut base: Vec<String> = match segs[0].as_str() {
            "crate" => Vec::new(),
            _ => module.to_vec(),
        };
        let mut rest = &segs[1..];
        if segs[0] == "super" {
            base.pop();
            while rest.first().is_some_and(|s| s == "super") {
                base.pop();
                rest = &rest[1..];
            }
        }
        base.extend(rest.iter().cloned());
        match group {
            Some(g) => {
                for item in g.split(',') {
                    let item = item.split(" as ").next().unwrap().trim();
                    if !item.is_empty() {
                        let mut p = base.clone();
                        p.extend(item.split("::").map(|s| s.trim().to_string()));
                        out.push(p);
                    }
                }
            }
            None => out.push(base),
        }
    }
    out
}

type Graph = BTreeMap<String, BTreeSet<String>>;

/// The modules under `root` and the modules each names, and the same between folders:
/// a folder (`codecs/core`, `emit`, "" for the top of src/) names another where one of its
/// files names a module of the other, an ancestor's module included (a family naming the
/// registry in `codecs/mod.rs` climbs back up as surely as a sibling's module).
fn import_graphs(root: &Path) -> (Graph, Graph) {
    let mut files = Vec::new();
    rust_files(root, &mut files);
    let modules: BTreeMap<Vec<String>, &PathBuf> =
        files.iter().map(|f| (module_of(root, f), f)).collect();
    let folder = |f: &Path| {
        let d = f.parent().unwrap().strip_prefix(root).unwrap();
        d.to_string_lossy().replace('\\', "/")
    };
    let mut graph: Graph = BTreeMap::new();
    let mut folders: Graph = BTreeMap::new();
    for f in &files {
        let m = module_of(root, f);
        let code = code_only(&std::fs::read_to_string(f).unwrap());
        let deps = graph.entry(m.join("::")).or_default();
        for p in paths(&code, &m) {
            let Some(target) = (1..=p.len())
                .rev()
                .map(|n| p[..n].to_vec())
                .find(|c| modules.contains_key(c))
            else {
                continue;
            };
            if target != m && !m.starts_with(&target) {
                deps.insert(target.join("::"));
            }
            let (from, to) = (folder(f), folder(modules[&target]));
            if from != to {
                folders.entry(from).or_default().insert(to);
            }
        }
    }
    (graph, folders)
}

fn import_graph() -> Graph {
    import_graphs(&src()).0
}

/// Tarjan's strongly connected components of more than one module.
fn circles(graph: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    struct T<'a> {
        g: &'a BTreeMap<String, BTreeSet<String>>,
        index: BTreeMap<&'a str, (usize, usize)>,
        stack: Vec<&'a str>,
        on: BTreeSet<&'a str>,
        out: Vec<Vec<String>>,
    }
    fn visit<'a>(t: &mut T<'a>, v: &'a str) {
        let n = t.index.len();
        t.index.insert(v, (n, n));
        t.stack.push(v);
        t.on.insert(v);
        for w in t.g.get(v).into_iter().flatten() {
            if !t.index.contains_key(w.as_str()) {
                visit(t, w);
                let low = t.index[w.as_str()].1.min(t.index[v].1);
                t.index.get_mut(v).unwrap().1 = low;
            } else if t.on.contains(w.as_str()) {
                let low = t.index[w.as_str()].0.min(t.index[v].1);
                t.index.get_mut(v).unwrap().1 = low;
            }
        }
        if t.index[v].0 == t.index[v].1 {
            let mut c = Vec::new();
            loop {
                let w = t.stack.pop().unwrap();
                t.on.remove(w);
                c.push(w.to_string());
                if w == v {
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
        g: graph,
        index: BTreeMap::new(),
        stack: Vec::new(),
        on: BTreeSet::new(),
        out: Vec::new(),
    };
    for v in graph.keys() {
        if !t.index.contains_key(v.as_str()) {
            visit(&mut t, v);
        }
    }
    t.out
}

#[test]
fn no_import_circles_among_the_modules_of_src() {
    let graph = import_graph();
    // The reader sees the edges the tree has: a sample that must be there.
    assert!(graph["codecs::octahedral::oct"].contains("codecs::core::codec"));
    assert!(graph["measure::quality"].contains("support::sampling"));
    let found = circles(&graph);
    assert!(found.is_empty(), "import circles in src/: {found:?}");
}

/// Layers only point down: no two folders of src/ name each other, through any chain.
/// Following a spec from the command line to its emitted text never returns to a folder
/// it has left: emission prints the figures it is handed, naming nothing in `measure/`
/// but the plain record of them (`measure::figures`), and no codec names `emit/`.
#[test]
fn no_import_circles_among_the_folders_of_src() {
    let (files, folders) = import_graphs(&src());
    assert!(folders["codecs/octahedral"].contains("codecs/core"));
    let found = circles(&folders);
    assert!(found.is_empty(), "folder circles in src/: {found:?}");
    assert!(files["emit::docs"].contains("measure::figures"));
    for (from, to) in files
        .iter()
        .flat_map(|(a, b)| b.iter().map(move |b| (a, b)))
    {
        assert!(
            !(from.starts_with("emit") && to.starts_with("measure") && to != "measure::figures"),
            "{from} names {to}: emission prints figures measured before it"
        );
    }
    for (from, to) in folders
        .iter()
        .flat_map(|(a, b)| b.iter().map(move |b| (a, b)))
    {
        assert!(
            !(from.starts_with("codecs") && (to.starts_with("emit") || to.starts_with("measure"))),
            "{from} names {to}: a codec knows nothing of how it is printed or measured"
        );
        let floor = from.starts_with("support") || (from.starts_with("model") && to != "support");
        assert!(
            !floor,
            "{from} names {to}: support/ and model/ are the floor"
        );
    }
}

/// The folder check fails on a planted circle that no pair of files shows: `a/x.rs` names
/// `b::y`, and `b/z.rs` names `a::w`.
#[test]
fn the_folder_check_finds_a_planted_circle() {
    let root = std::env::temp_dir().join(format!("unitpack-layout-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    for (file, text) in [
        ("lib.rs", "pub mod a; pub mod b;"),
        ("a/mod.rs", "pub mod w; pub mod x;"),
        ("a/w.rs", ""),
        ("a/x.rs", "use crate::b::y::Y;"),
        ("b/mod.rs", "pub mod y; pub mod z;"),
        ("b/y.rs", "pub struct Y;"),
        ("b/z.rs", "use crate::a::w;"),
    ] {
        let path = root.join(file);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap();
    }
    let (files, folders) = import_graphs(&root);
    std::fs::remove_dir_all(&root).unwrap();
    assert!(circles(&files).is_empty(), "no file circle: {files:?}");
    assert_eq!(circles(&folders), vec![vec!["a", "b"]]);
}

#[test]
fn the_circle_finder_finds_a_circle() {
    let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (a, b) in [("a", "b"), ("b", "c"), ("c", "a"), ("c", "d")] {
        g.entry(a.into()).or_default().insert(b.into());
    }
    assert_eq!(circles(&g), vec![vec!["a", "b", "c"]]);
    let code = code_only("use crate::x::{y, z::W}; // crate::q\nlet s = \"crate::r\";");
    assert_eq!(
        paths(&code, &["m".into()]),
        vec![vec!["x", "y"], vec!["x", "z", "W"]]
    );
}

#[test]
fn codecs_top_holds_the_registry_and_folders_and_families_are_named_after_their_files() {
    let codecs = src().join("codecs");
    let top: Vec<String> = std::fs::read_dir(&codecs)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".rs"))
        .collect();
    assert!(
        top.len() <= 10,
        "src/codecs/ holds {} files: {top:?}",
        top.len()
    );
    let mut files = Vec::new();
    rust_files(&codecs, &mut files);
    let stems: BTreeSet<String> = files
        .iter()
        .map(|f| f.file_stem().unwrap().to_string_lossy().into_owned())
        .collect();
    // A combination family lives in its generic definition, which names it.
    let generic = std::fs::read_to_string(codecs.join("azimuthal/disk_square.rs")).unwrap();
    // A file may hold the sizes of one format as families named after it
    // (engine/meshopt.rs: meshopt_oct8, meshopt_oct16).
    let holds = |name: &str| {
        files.iter().any(|f| {
            let stem = f.file_stem().unwrap().to_string_lossy();
            name.starts_with(stem.as_ref())
                && std::fs::read_to_string(f)
                    .unwrap()
                    .contains(&format!("name: \"{name}\""))
        })
    };
    for f in unitpack::codecs::FAMILIES {
        let name = f.info().name;
        assert!(
            stems.contains(name) || generic.contains(&format!("\"{name}\"")) || holds(name),
            "no file src/codecs/<kind>/{name}.rs for the family {name}"
        );
    }
}

/// The string literals of `text` outside comments, each with the code just before it.
fn literals(text: &str) -> Vec<(String, String)> {
    scan(text).1
}

/// `text` without comments and with every string literal emptied, and the literals
/// (outside comments), each with the 24 bytes of code before it. A char literal is
/// skipped whole ('"' among them); a lifetime has no closing quote.
fn scan(text: &str) -> (String, Vec<(String, String)>) {
    let b = text.as_bytes();
    let (mut code, mut literals, mut i) = (String::with_capacity(b.len()), Vec::new(), 0);
    let lossy = |r: std::ops::Range<usize>| String::from_utf8_lossy(&b[r]).into_owned();
    while i < b.len() {
        if b[i..].starts_with(b"//") {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
        } else if b[i..].starts_with(b"/*") {
            i += 2;
            while i + 1 < b.len() && !b[i..].starts_with(b"*/") {
                i += 1;
            }
            i += 2;
        } else if b[i] == b'\'' && i + 2 < b.len() && (b[i + 2] == b'\'' || b[i + 1] == b'\\') {
            let end = if b[i + 1] == b'\\' { i + 4 } else { i + 3 };
            code.push_str(&lossy(i..end.min(b.len())));
            i = end;
        } else if b[i] == b'"' {
            let start = i + 1;
            i += 1;
            while i < b.len() && b[i] != b'"' {
                i += if b[i] == b'\\' { 2 } else { 1 };
            }
            literals.push((
                lossy(start.saturating_sub(24)..start - 1),
                lossy(start..i.min(b.len())),
            ));
            i += 1;
            code.push_str("\"\"");
        } else {
            let n = text[i..].chars().next().map_or(1, char::len_utf8);
            code.push_str(&text[i..i + n]);
            i += n;
        }
    }
    (code, literals)
}

/// Every fact about a family (its seam, whether its float form filters, its baseline)
/// lives in the family's own file: no other file spells a family's name as a string,
/// where a match on it would silently miss a new family. A traced value's name
/// (`.named("xy")`) is not a family's.
#[test]
fn no_family_name_is_a_string_literal_outside_its_own_file() {
    let sample = literals("let a = \"oct\"; // \"hemioct\"\nf(\"x\".named(\"xy\"), '\"');");
    let texts: Vec<&str> = sample.iter().map(|(_, l)| l.as_str()).collect();
    assert_eq!(texts, ["oct", "x", "xy"], "no comment, no char literal");
    assert!(sample[2].0.ends_with(".named(") && !sample[0].0.ends_with(".named("));
    let mut files = Vec::new();
    rust_files(&src(), &mut files);
    let names: BTreeSet<&str> = unitpack::codecs::FAMILIES
        .iter()
        .map(|f| f.info().name)
        .collect();
    let mut found = Vec::new();
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap();
        for (before, literal) in literals(&text) {
            // disk_square.rs defines its six families through a macro.
            let own = text.contains(&format!("name: \"{literal}\""))
                || file.ends_with("azimuthal/disk_square.rs");
            if names.contains(literal.as_str()) && !own && !before.ends_with(".named(") {
                found.push(format!("{}: \"{literal}\"", file.display()));
            }
        }
    }
    assert!(
        found.is_empty(),
        "family names outside their files: {found:#?}"
    );
}
