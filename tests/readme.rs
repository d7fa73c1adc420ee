//! The README and `docs/` say what the tools do, so they are checked like code:
//!
//! - the README's complete consumers (one per language, a fenced block whose first line
//!   names its file, `// normals.wgsl`) are written out as the README shows them and built
//!   with the commands in the `sh` block that follows: glslang for GLSL and HLSL, the C
//!   and C++ compilers for C, and for WGSL, which has no include, the concatenation the
//!   README gives, validated with naga; where a `text` block follows the commands, their
//!   output must be it;
//! - every example session (a `text` or `console` block whose first line starts with
//!   `$ `) is run with the built `unitpack` and must print what the block shows (a line
//!   `...` stands for any number of lines, a line ending in `…` for any line starting with
//!   the text before it);
//! - the README's figures are the tools': the codec recommendations are what `choose`
//!   ranks first (a generated block), the crate count is what `cargo tree` counts;
//! - each generated block is in the file `src/report/doc_tables.rs` names, once;
//! - every relative link resolves, to a file and to a heading;
//! - the README stays a user's guide of at most 400 lines.
//!
//! A missing tool fails the test, naming the Debian package that provides it.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::Command;
use unitpack::report::doc_tables::{BLOCKS, markers};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The README and every Markdown file under `docs/`, as paths relative to the root.
fn documents() -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        let mut entries: Vec<_> = std::fs::read_dir(dir)
            .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
            .map(|e| e.unwrap().path())
            .collect();
        entries.sort();
        for p in entries {
            if p.is_dir() {
                walk(&p, out);
            } else if p.extension().is_some_and(|e| e == "md") {
                out.push(p.strip_prefix(root()).unwrap().to_path_buf());
            }
        }
    }
    let mut docs = vec![PathBuf::from("README.md")];
    walk(&root().join("docs"), &mut docs);
    docs
}

/// A fenced code block: its info string, its lines (the fence's indentation removed)
/// and the line number of its opening fence (1-based).
#[derive(Debug)]
struct Fence {
    info: String,
    body: Vec<String>,
    line: usize,
}

/// The fenced blocks of a Markdown text, in order, and the text's other lines (with their
/// line numbers).
fn parse(text: &str) -> (Vec<Fence>, Vec<(usize, String)>) {
    let mut fences = Vec::new();
    let mut prose = Vec::new();
    let mut open: Option<(usize, String, Fence)> = None;
    for (i, line) in text.lines().enumerate() {
        let trimmed = line.trim_start();
        let indent = line.len() - trimmed.len();
        match open.take() {
            None if trimmed.starts_with("```") => {
                let fence = Fence {
                    info: trimmed.trim_start_matches('`').trim().to_string(),
                    body: Vec::new(),
                    line: i + 1,
                };
                open = Some((indent, " ".repeat(indent), fence));
            }
            None => prose.push((i + 1, line.to_string())),
            Some((_, _, fence)) if trimmed.starts_with("```") => fences.push(fence),
            Some((n, pad, mut fence)) => {
                fence.body.push(
                    line.strip_prefix(pad.as_str())
                        .unwrap_or(trimmed)
                        .to_string(),
                );
                open = Some((n, pad, fence));
            }
        }
    }
    assert!(open.is_none(), "an unclosed code fence");
    (fences, prose)
}

/// The Debian package that provides `program`, for the message when it is missing.
fn package_of(program: &str) -> &'static str {
    match program {
        "glslangValidator" => "glslang-tools",
        "spirv-val" | "spirv-opt" => "spirv-tools",
        "cc" | "gcc" => "gcc",
        "c++" | "g++" => "g++",
        "cargo" => "cargo",
        _ => "coreutils",
    }
}

/// Whether `program` is on PATH.
fn on_path(program: &str) -> bool {
    std::env::var_os("PATH")
        .is_some_and(|paths| std::env::split_paths(&paths).any(|dir| dir.join(program).is_file()))
}

/// Runs one shell command line in `dir`, with the built `unitpack` first on PATH, and
/// returns its stdout and stderr; fails naming the package of a missing program.
fn sh(dir: &Path, line: &str, cache: &Path) -> std::process::Output {
    for word in line
        .split(['|', '&', ';'])
        .filter_map(|part| part.split_whitespace().next())
    {
        if !word.contains('/') && !on_path(word) && word != "unitpack" && !is_builtin(word) {
            panic!(
                "`{word}` (in `{line}`) is not on PATH: install the Debian package `{}`",
                package_of(word)
            );
        }
    }
    let bin = Path::new(env!("CARGO_BIN_EXE_unitpack")).parent().unwrap();
    let path = std::env::join_paths(std::iter::once(bin.to_path_buf()).chain(
        std::env::split_paths(&std::env::var_os("PATH").unwrap_or_default()),
    ))
    .unwrap();
    Command::new("sh")
        .arg("-c")
        .arg(line)
        .current_dir(dir)
        .env("PATH", path)
        .env("UNITPACK_CACHE_DIR", cache)
        .output()
        .unwrap_or_else(|e| panic!("sh -c {line:?}: {e}"))
}

fn is_builtin(word: &str) -> bool {
    matches!(word, "echo" | "printf" | "cd" | "true")
}

/// A scratch directory in which `generated` is the repository's.
fn scratch() -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("temporary directory");
    std::os::unix::fs::symlink(root().join("generated"), dir.path().join("generated"))
        .expect("link generated/");
    dir
}

#[test]
fn readme_consumers_compile_as_the_readme_says() {
    let (fences, _) = parse(&read(&root().join("README.md")));
    let cache = tempfile::tempdir().unwrap();
    let mut built = BTreeSet::new();
    for (i, fence) in fences.iter().enumerate() {
        if !["wgsl", "glsl", "hlsl", "c"].contains(&fence.info.as_str()) {
            continue;
        }
        let Some(file) = fence.body.first().and_then(|l| l.strip_prefix("// ")) else {
            continue;
        };
        if file.contains(' ') || !file.contains('.') {
            continue;
        }
        let commands = fences
            .get(i + 1)
            .filter(|f| f.info == "sh")
            .unwrap_or_else(|| {
                panic!(
                    "README.md line {}: the {} consumer {file} is not followed by the `sh` block that builds it",
                    fence.line, fence.info
                )
            });
        let dir = scratch();
        std::fs::write(dir.path().join(file), fence.body.join("\n") + "\n").unwrap();
        let before: BTreeSet<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        let mut stdout = String::new();
        for line in &commands.body {
            let out = sh(dir.path(), line, cache.path());
            assert!(
                out.status.success(),
                "README.md line {}: `{line}` failed for {file} ({}):\n{}{}",
                commands.line,
                out.status,
                String::from_utf8_lossy(&out.stdout),
                String::from_utf8_lossy(&out.stderr)
            );
            // glslang names the file it compiled on stdout; that is not the program's output.
            if !line.starts_with("glslangValidator") {
                stdout.push_str(&String::from_utf8_lossy(&out.stdout));
            }
        }
        if fence.info == "wgsl" {
            // WGSL has no include: the commands put the generated file ahead of the
            // consumer, and naga validates what they wrote.
            let mut validated = 0;
            for entry in std::fs::read_dir(dir.path()).unwrap() {
                let entry = entry.unwrap();
                let name = entry.file_name();
                if before.contains(&name) || !name.to_string_lossy().ends_with(".wgsl") {
                    continue;
                }
                let source = read(&entry.path());
                assert!(
                    source.contains("fn unitpack_"),
                    "{name:?} holds no generated function"
                );
                unitpack::verify::tools::naga_wgsl(&source)
                    .unwrap_or_else(|e| panic!("README.md's {file} as {name:?}: {e:#}"));
                validated += 1;
            }
            assert!(validated > 0, "the WGSL commands wrote no .wgsl file");
        }
        if let Some(expected) = fences.get(i + 2).filter(|f| f.info == "text") {
            assert_eq!(
                stdout.trim_end(),
                expected.body.join("\n").trim_end(),
                "README.md line {}: what {file} prints",
                expected.line
            );
        }
        built.insert(fence.info.clone());
    }
    let want: BTreeSet<String> = ["c", "glsl", "hlsl", "wgsl"].map(String::from).into();
    assert_eq!(built, want, "one complete consumer per language");
}

/// Whether `actual` lines match the `expected` lines of an example session: a line `...`
/// stands for any number of lines, and `…` within a line for any text (a count every new
/// codec changes, say, which a document should not state by hand).
fn session_matches(expected: &[String], actual: &[&str]) -> bool {
    match expected.split_first() {
        None => actual.is_empty(),
        Some((e, rest)) if e == "..." => {
            (0..=actual.len()).any(|skip| session_matches(rest, &actual[skip..]))
        }
        Some((e, rest)) => actual
            .split_first()
            .is_some_and(|(a, more)| line_matches(e, a) && session_matches(rest, more)),
    }
}

/// Whether `actual` is `expected` with each `…` standing for any text (the pieces between
/// found in order, the first at the start and the last at the end).
fn line_matches(expected: &str, actual: &str) -> bool {
    let mut pieces = expected.split('…');
    let first = pieces.next().unwrap_or("");
    let Some(mut rest) = actual.strip_prefix(first) else {
        return false;
    };
    let pieces: Vec<&str> = pieces.collect();
    let Some((last, middle)) = pieces.split_last() else {
        return rest.is_empty();
    };
    for piece in middle {
        match rest.find(piece) {
            Some(at) => rest = &rest[at + piece.len()..],
            None => return false,
        }
    }
    rest.ends_with(last)
}

/// A small RGB8 tangent-space normal map, for the examples that convert `rock_n.png`.
fn write_normal_map(path: &Path) {
    let file = std::fs::File::create(path).unwrap();
    let mut enc = png::Encoder::new(file, 4, 4);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    let mut w = enc.write_header().unwrap();
    let mut data = Vec::new();
    for i in 0..16u8 {
        data.extend_from_slice(&[128 + i, 128 - i, 250]);
    }
    w.write_image_data(&data).unwrap();
}

#[test]
fn example_sessions_print_what_the_docs_show() {
    let cache = tempfile::tempdir().unwrap();
    let mut sessions = 0;
    for doc in documents() {
        let (fences, _) = parse(&read(&root().join(&doc)));
        for fence in fences {
            if !["text", "console"].contains(&fence.info.as_str())
                || !fence.body.first().is_some_and(|l| l.starts_with("$ "))
            {
                continue;
            }
            let dir = scratch();
            write_normal_map(&dir.path().join("rock_n.png"));
            let mut lines = fence.body.iter().peekable();
            while let Some(line) = lines.next() {
                let command = line
                    .strip_prefix("$ ")
                    .unwrap_or_else(|| panic!("{}: {line:?} is not a command", doc.display()));
                let mut expected = Vec::new();
                while let Some(l) = lines.next_if(|l| !l.starts_with("$ ")) {
                    expected.push(l.clone());
                }
                let out = sh(dir.path(), command, cache.path());
                let text = format!(
                    "{}{}",
                    String::from_utf8_lossy(&out.stdout),
                    String::from_utf8_lossy(&out.stderr)
                );
                let actual: Vec<&str> = text.lines().collect();
                assert!(
                    session_matches(&expected, &actual),
                    "{} line {}: `{command}` printed\n{text}\nwhere the document shows\n{}",
                    doc.display(),
                    fence.line,
                    expected.join("\n")
                );
                sessions += 1;
            }
        }
    }
    assert!(sessions >= 10, "only {sessions} example commands found");
}

#[test]
fn readme_figures_are_the_tools() {
    let readme = read(&root().join("README.md"));
    // The recommendations: what `choose` ranks first for each case, from the catalogue
    // file as it is on disk, which the binary compiles in (tests/figures/tables.rs holds
    // the two equal; tests/cli/choose.rs runs each command).
    use unitpack::choice::catalogue::{self, Catalogue};
    let file = read(&root().join(catalogue::PATH));
    let table = unitpack::choice::recommend::table(
        &Catalogue::parse(&file).expect("src/choice/catalogue.json parses"),
    );
    let fresh =
        unitpack::report::doc_tables::replace_block(&readme, "readme", "recommendations", &table)
            .expect("README.md has the recommendations block");
    if unitpack::report::doc_tables::refreshing() {
        if fresh != readme {
            std::fs::write(root().join("README.md"), &fresh).unwrap();
        }
    } else {
        assert!(
            fresh == readme,
            "README.md's recommendations are not what `choose` answers: run \
             `UNITPACK_REFRESH=1 cargo test --release --test readme`"
        );
    }

    // The crate count of a build-script user, with the command the README quotes.
    let out = Command::new(env!("CARGO"))
        .args([
            "tree",
            "--offline",
            "-e",
            "normal",
            "--no-default-features",
            "--prefix",
            "none",
        ])
        .current_dir(root())
        .output()
        .expect("run cargo tree");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let crates: BTreeSet<&str> = std::str::from_utf8(&out.stdout)
        .unwrap()
        .lines()
        .filter_map(|l| l.split(' ').next())
        .filter(|c| !c.is_empty())
        .collect();
    let said = format!(
        "Its build graph is {} crates, unitpack included",
        crates.len()
    );
    assert!(
        readme.contains(&said),
        "README.md should say \"{said}\" ({crates:?})"
    );
    assert!(
        readme.contains("cargo tree -e normal --no-default-features --prefix none"),
        "README.md names the command that counts the crates"
    );
}

#[test]
fn generated_blocks_are_where_doc_tables_says() {
    let mut found = Vec::new();
    for doc in documents() {
        let text = read(&root().join(&doc));
        for line in text.lines().filter(|l| l.starts_with("<!-- generated: ")) {
            let name = line["<!-- generated: ".len()..]
                .split(' ')
                .next()
                .unwrap()
                .to_string();
            let block = BLOCKS
                .iter()
                .find(|b| b.name == name)
                .unwrap_or_else(|| panic!("{}: no test writes a block {name}", doc.display()));
            assert_eq!(
                Path::new(block.file),
                doc,
                "the {name} block belongs in {}",
                block.file
            );
            let (begin, end) = markers(block.test, block.name);
            assert_eq!(line, begin, "{}: the {name} marker", doc.display());
            assert_eq!(text.matches(&end).count(), 1, "{}: {end}", doc.display());
            found.push(name);
        }
    }
    found.sort();
    let mut want: Vec<String> = BLOCKS.iter().map(|b| b.name.to_string()).collect();
    want.sort();
    assert_eq!(found, want, "each generated block exactly once");
}

/// GitHub's anchor for a heading: lower case, punctuation dropped, spaces as hyphens.
fn slug(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || matches!(c, ' ' | '-' | '_'))
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

fn anchors(text: &str) -> BTreeSet<String> {
    let (_, prose) = parse(text);
    prose
        .iter()
        .filter_map(|(_, l)| l.strip_prefix('#'))
        .map(|h| slug(h.trim_start_matches('#')))
        .collect()
}

#[test]
fn relative_links_resolve() {
    let mut checked = 0;
    for doc in documents() {
        let text = read(&root().join(&doc));
        let (_, prose) = parse(&text);
        let base = doc.parent().unwrap();
        for (n, line) in prose {
            let mut rest = line.as_str();
            while let Some(at) = rest.find("](") {
                let after = &rest[at + 2..];
                let end = after.find(')').unwrap_or(after.len());
                let target = &after[..end];
                rest = &after[end..];
                if target.contains("://") || target.starts_with("mailto:") {
                    continue;
                }
                let (file, anchor) = target.split_once('#').unwrap_or((target, ""));
                let path = if file.is_empty() {
                    doc.clone()
                } else {
                    base.join(file)
                };
                let full = root().join(&path);
                assert!(
                    full.exists(),
                    "{} line {n}: {target} does not exist",
                    doc.display()
                );
                if !anchor.is_empty() {
                    assert!(
                        anchors(&read(&full)).contains(anchor),
                        "{} line {n}: {} has no heading #{anchor}",
                        doc.display(),
                        path.display()
                    );
                }
                checked += 1;
            }
        }
    }
    assert!(checked >= 20, "only {checked} links found");
}

#[test]
fn readme_is_a_users_guide() {
    let readme = read(&root().join("README.md"));
    let lines = readme.lines().count();
    assert!(
        lines <= 400,
        "README.md has {lines} lines; the limit is 400"
    );
    for section in [
        "## Install",
        "## Set-up on a fresh machine",
        "## Quick start",
    ] {
        assert!(readme.contains(section), "README.md lacks {section}");
    }
    // The set-up commands, as `.ci/run` runs the second.
    assert!(readme.contains("```sh\ncargo run --release -- generate\n```"));
    assert!(readme.contains("```sh\ncargo test --release\n```"));
    let ci = read(&root().join(".ci/run"));
    assert!(
        ci.lines().any(|l| l == "cargo test --release"),
        ".ci/run runs the README's test command"
    );
}

#[test]
fn paths_the_docs_name_exist() {
    let mut missing = Vec::new();
    let mut checked = 0;
    for doc in documents() {
        let (_, prose) = parse(&read(&root().join(&doc)));
        let text: Vec<String> = prose.into_iter().map(|(_, l)| l).collect();
        for (k, span) in text.join("\n").split('`').enumerate() {
            // Odd pieces are inside backquotes.
            if k % 2 == 0 {
                continue;
            }
            let top = span.split('/').next().unwrap_or("");
            let named = [
                "src",
                "tests",
                "benches",
                "examples",
                "templates",
                "generated",
                "docs",
            ]
            .contains(&top)
                && span.contains('/')
                && !span.contains(|c: char| c.is_whitespace() || "<>*{}…".contains(c));
            if !named {
                continue;
            }
            // `src/codecs/toolkit/exact.rs`, or a folder, `tests/internals/`.
            let path = span.trim_end_matches('/');
            if !root().join(path).exists() {
                missing.push(format!("{}: `{span}`", doc.display()));
            }
            checked += 1;
        }
    }
    assert!(
        missing.is_empty(),
        "paths that do not exist:\n{}",
        missing.join("\n")
    );
    assert!(checked >= 20, "only {checked} paths found");
}

/// The session matcher's `…` stands for text within a line and nothing else: the text
/// around it must still match.
#[test]
fn an_ellipsis_stands_for_text_within_a_line() {
    assert!(line_matches(
        "… files in g: … written",
        "1395 files in g: 1395 written"
    ));
    assert!(line_matches("changed: …", "changed: g/wgsl/oct16.wgsl"));
    assert!(!line_matches(
        "… files in g: … written",
        "1395 files in h: 1395 written"
    ));
    assert!(!line_matches("1 of … files", "2 of 1395 files"));
    assert!(!line_matches("… written", "1395 written, 0 kept"));
    assert!(!line_matches("exact", "exactly"));
}
