//! What every module runs the binary with: [`Run`] and the ways to get one, the figure
//! cache all runs share, and the temporary trees and file listings the checks compare.

use std::collections::BTreeSet;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use unitpack::codecs::Spec;
use unitpack::codecs::core::spec::TableFormat;
use unitpack::emit::Lang;

#[derive(Clone)]
pub struct Run {
    pub code: i32,
    pub stdout: String,
    /// stdout as bytes (binary formats).
    pub out: Vec<u8>,
    pub stderr: String,
}

impl std::fmt::Debug for Run {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "exit {}\n--- stdout ---\n{}\n--- stderr ---\n{}",
            self.code, self.stdout, self.stderr
        )
    }
}

/// Every run shares one figure cache in the build's temporary folder (never the user's):
/// the whole catalogue is proven once per build, not once per `generate`. The runs whose
/// point is the proving itself switch it off ([`uncached`]). The first run fills the cache
/// before any other starts, so that no two tests prove the catalogue side by side.
pub fn unitpack() -> Command {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_unitpack"));
    cmd.env("UNITPACK_CACHE_DIR", &filled_cache().cache);
    cmd
}

/// The shared figure cache and the tree written by the `generate` that filled it.
pub struct Filled {
    pub cache: PathBuf,
    pub tree: PathBuf,
    pub run: Run,
}

/// Fills the shared cache with one `generate` that starts from no cache file, so that it
/// proves every figure and bound afresh: [`generate_is_deterministic`] holds its tree to
/// the committed one.
pub fn filled_cache() -> &'static Filled {
    static FILLED: std::sync::OnceLock<Filled> = std::sync::OnceLock::new();
    FILLED.get_or_init(|| {
        // Both in the build's temporary folder, left by the last run of this binary.
        let tmp = Path::new(env!("CARGO_TARGET_TMPDIR"));
        let (cache, tree) = (tmp.join("cli-figure-cache"), tmp.join("cli-figure-fill"));
        for gone in [
            std::fs::remove_file(cache.join("figures.txt")),
            std::fs::remove_dir_all(&tree),
        ] {
            if let Err(e) = gone {
                assert_eq!(e.kind(), std::io::ErrorKind::NotFound, "{e}");
            }
        }
        let mut fill = Command::new(env!("CARGO_BIN_EXE_unitpack"));
        fill.env("UNITPACK_CACHE_DIR", &cache)
            .arg("generate")
            .arg("--out")
            .arg(&tree);
        let run = run_cmd(fill, b"");
        assert_eq!(run.code, 0, "filling the figure cache: {run:?}");
        assert!(
            cache.join("figures.txt").is_file(),
            "filling the figure cache: {run:?}"
        );
        Filled { cache, tree, run }
    })
}

/// `args` run with the figure cache off: every bound proven, every figure measured here.
pub fn uncached(dir: Option<&Path>, args: &[&str]) -> Run {
    let mut cmd = unitpack();
    cmd.env("UNITPACK_CACHE_DIR", "").args(args);
    if let Some(d) = dir {
        cmd.current_dir(d);
    }
    run_cmd(cmd, b"")
}

/// Runs `cmd` with `stdin` written from another thread (so that large inputs and outputs
/// cannot deadlock on full pipes).
pub fn run_cmd(mut cmd: Command, stdin: &[u8]) -> Run {
    cmd.stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    let mut child = cmd.spawn().expect("spawn unitpack");
    let mut si = child.stdin.take().expect("stdin");
    let input = stdin.to_vec();
    // The binary may exit before reading stdin (bad spec): ignore a broken pipe.
    let writer = std::thread::spawn(move || {
        let _ = si.write_all(&input);
    });
    let out = child.wait_with_output().expect("wait for unitpack");
    writer.join().expect("stdin writer");
    Run {
        code: out
            .status
            .code()
            .expect("exit code (not killed by a signal)"),
        stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
        out: out.stdout,
        stderr: String::from_utf8(out.stderr).expect("stderr is UTF-8"),
    }
}

pub fn run_in(dir: Option<&Path>, args: &[&str], stdin: &str) -> Run {
    let mut cmd = unitpack();
    cmd.args(args);
    if let Some(d) = dir {
        cmd.current_dir(d);
    }
    run_cmd(cmd, stdin.as_bytes())
}

pub fn run_bytes(args: &[&str], stdin: &[u8]) -> Run {
    let mut cmd = unitpack();
    cmd.args(args);
    run_cmd(cmd, stdin)
}

pub fn run(args: &[&str]) -> Run {
    run_in(None, args, "")
}

pub fn run_stdin(args: &[&str], stdin: &str) -> Run {
    run_in(None, args, stdin)
}

pub fn ok(args: &[&str]) -> Run {
    let r = run(args);
    assert_eq!(r.code, 0, "unitpack {args:?} should succeed: {r:?}");
    r
}

/// A failure with exit status 2 (error), nothing on stdout; returns stderr.
pub fn fails(args: &[&str], stdin: &str) -> String {
    let r = run_stdin(args, stdin);
    assert_eq!(
        r.code, 2,
        "unitpack {args:?} should fail with status 2: {r:?}"
    );
    assert!(
        r.stdout.is_empty(),
        "unitpack {args:?} failed but wrote to stdout: {r:?}"
    );
    assert!(
        !r.stderr.trim().is_empty(),
        "unitpack {args:?} failed silently: {r:?}"
    );
    r.stderr
}

/// A failure with exit status 2 and a one-line error, after `before` was written to
/// stdout (encode/decode write the lines before a bad one); returns stderr.
pub fn fails_after(args: &[&str], stdin: &str, before: &str) -> String {
    let r = run_stdin(args, stdin);
    assert_eq!(
        r.code, 2,
        "unitpack {args:?} should fail with status 2: {r:?}"
    );
    assert_eq!(r.stdout, before, "unitpack {args:?}: {r:?}");
    assert_eq!(r.stderr.lines().count(), 1, "one line: {r:?}");
    assert!(r.stderr.starts_with("error: "), "{r:?}");
    r.stderr
}

/// `gen SPEC --lang wgsl` must fail with status 2; returns stderr.
pub fn bad_spec(spec: &str) -> String {
    fails(&["gen", spec, "--lang", "wgsl"], "")
}

pub fn manifest_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

pub fn tempdir() -> tempfile::TempDir {
    tempfile::tempdir().expect("temporary directory")
}

/// Every file below `dir`, relative, sorted.
pub fn tree(dir: &Path) -> BTreeSet<PathBuf> {
    fn walk(root: &Path, d: &Path, out: &mut BTreeSet<PathBuf>) {
        for e in std::fs::read_dir(d).expect("read_dir") {
            let p = e.expect("dir entry").path();
            if p.is_dir() {
                walk(root, &p, out);
            } else {
                out.insert(p.strip_prefix(root).expect("below root").to_path_buf());
            }
        }
    }
    let mut out = BTreeSet::new();
    walk(dir, dir, &mut out);
    out
}

/// The files `generate` must write: `<lang>/<id>.<lang>` for every spec and language,
/// `wesl/<id>.wesl` for every spec, the tables and the manifest.
pub fn expected_files() -> BTreeSet<PathBuf> {
    let mut s = BTreeSet::from([
        PathBuf::from(".unitpack-manifest"),
        PathBuf::from("README.md"),
    ]);
    for lang in Lang::ALL {
        for spec in Spec::all() {
            s.insert(PathBuf::from(lang.name()).join(format!("{}.{}", spec.id(), lang.ext())));
        }
    }
    for spec in Spec::all() {
        s.insert(PathBuf::from("wesl").join(format!("{}.wesl", spec.id())));
        for t in spec.family().tables(&spec) {
            // A texture is written as a PNG too; an integer table as raw words only.
            let exts: &[&str] = match t.format {
                TableFormat::Unorm8 => &["png", "bin"],
                TableFormat::Uint32 => &["bin"],
            };
            for ext in exts {
                s.insert(PathBuf::from("lut").join(format!("{}.{ext}", t.stem)));
            }
        }
    }
    s
}

pub fn generate_into(dir: &Path) -> Run {
    generated_into(
        dir,
        ok(&["generate", "--out", dir.to_str().expect("UTF-8 path")]),
    )
}

/// What `generate` into `dir` reported, checked.
pub fn generated_into(dir: &Path, r: Run) -> Run {
    assert_eq!(r.code, 0, "{r:?}");
    assert!(
        r.stdout.contains(&format!(
            "{} files in {}: ",
            expected_files().len(),
            dir.display()
        )),
        "{r:?}"
    );
    r
}

pub fn check(dir: &Path) -> Run {
    run(&[
        "generate",
        "--out",
        dir.to_str().expect("UTF-8 path"),
        "--check",
    ])
}

pub fn parse_vec(line: &str) -> [f32; 3] {
    let v: Vec<f32> = line
        .split_whitespace()
        .map(|t| t.parse::<f32>().expect("decode prints f32"))
        .collect();
    assert_eq!(v.len(), 3, "decode line {line:?} should hold three numbers");
    [v[0], v[1], v[2]]
}

pub fn angle_deg(a: [f32; 3], b: [f32; 3]) -> f64 {
    let d = |v: [f32; 3]| v.map(f64::from);
    let (a, b) = (d(a), d(b));
    let dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let la = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    let lb = (b[0] * b[0] + b[1] * b[1] + b[2] * b[2]).sqrt();
    (dot / (la * lb)).clamp(-1.0, 1.0).acos().to_degrees()
}

pub fn is_hex_code(line: &str, digits: usize) -> bool {
    line.strip_prefix("0x").is_some_and(|h| {
        h.len() == digits
            && h.chars()
                .all(|c| c.is_ascii_digit() || ('a'..='f').contains(&c))
    })
}

/// Lists `rel` in `dir`'s manifest, as an earlier run that wrote it would have.
pub fn add_to_manifest(dir: &Path, rel: &str) {
    let m = dir.join(".unitpack-manifest");
    let mut text = std::fs::read_to_string(&m).unwrap_or_default();
    text.push_str(rel);
    text.push('\n');
    std::fs::write(&m, text).unwrap();
}

/// `generate --out dir`, which must succeed (without depending on its summary's wording,
/// so that the tests of what it does to files test only that).
pub fn generate_plain(dir: &Path) -> Run {
    ok(&["generate", "--out", dir.to_str().expect("UTF-8 path")])
}

/// Every file below `dir` with its contents.
pub fn snapshot(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    tree(dir)
        .into_iter()
        .map(|rel| {
            let bytes = std::fs::read(dir.join(&rel)).unwrap();
            (rel, bytes)
        })
        .collect()
}

pub fn gen_to(path: &Path, extra: &[&str]) -> Run {
    let mut args = vec![
        "gen",
        "oct16",
        "--lang",
        "wgsl",
        "--out",
        path.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    run(&args)
}

/// A tree as `generate --out dir` writes it, copied from the one [`filled_cache`]'s run
/// wrote (`generate` is deterministic: `generate_is_deterministic`), for the tests whose
/// subject is what comes after: a copy costs a fraction of a run.
pub fn generated_copy(dir: &Path) {
    let from = &filled_cache().tree;
    for rel in tree(from) {
        let to = dir.join(&rel);
        std::fs::create_dir_all(to.parent().expect("below dir")).expect("create folder");
        std::fs::copy(from.join(&rel), &to).expect("copy a generated file");
    }
}

/// Whether this run rewrites the stored files the tests compare with (the project's one
/// refresh command: `UNITPACK_REFRESH=1 cargo test --release`).
pub fn refreshing() -> bool {
    std::env::var_os("UNITPACK_REFRESH").is_some()
}

/// The committed `generated/` folder. When [`refreshing`], `generate` rewrites it first,
/// once per run, so that every test that holds it to the code (up to date, deterministic,
/// its manifest, its Regenerate lines) reads the rewritten tree and passes.
pub fn committed_generated() -> PathBuf {
    static REFRESHED: std::sync::OnceLock<()> = std::sync::OnceLock::new();
    let dir = manifest_dir().join("generated");
    if refreshing() {
        REFRESHED.get_or_init(|| {
            let r = run_in(Some(&manifest_dir()), &["generate"], "");
            assert_eq!(r.code, 0, "refreshing generated/: {r:?}");
        });
    }
    dir
}

/// Holds `actual` to the stored file `rel` (below tests/cli/), which this test wrote from
/// the tool's output. When [`refreshing`], the file is rewritten instead, and the test
/// passes.
pub fn matches_stored(rel: &str, actual: &str) {
    let path = manifest_dir().join("tests/cli").join(rel);
    if refreshing() {
        std::fs::write(&path, actual)
            .unwrap_or_else(|e| panic!("cannot rewrite {}: {e}", path.display()));
        return;
    }
    let stored = std::fs::read_to_string(&path).unwrap_or_default();
    if stored != actual {
        let line = stored
            .lines()
            .zip(actual.lines())
            .position(|(a, b)| a != b)
            .unwrap_or(stored.lines().count().min(actual.lines().count()));
        panic!(
            "{} differs from the output, first at line {}:\n  stored: {:?}\n  now:    {:?}\n\
             if the change is intended, run `UNITPACK_REFRESH=1 cargo test --release`",
            path.display(),
            line + 1,
            stored.lines().nth(line).unwrap_or("(end of file)"),
            actual.lines().nth(line).unwrap_or("(end of output)"),
        );
    }
}

/// Runs `args` on a pseudo-terminal, as a person at a terminal runs them: `script`
/// (util-linux; Debian's bsdutils) gives the binary a terminal as stdin, stdout and
/// stderr. Returns the exit status and everything the terminal showed.
pub fn on_a_terminal(dir: Option<&Path>, args: &[&str]) -> (i32, String) {
    let quote = |s: &str| format!("'{}'", s.replace('\'', r"'\''"));
    let line: Vec<String> = std::iter::once(env!("CARGO_BIN_EXE_unitpack"))
        .chain(args.iter().copied())
        .map(quote)
        .collect();
    let mut cmd = Command::new("script");
    cmd.args(["-q", "-e", "-c", &line.join(" "), "/dev/null"])
        .env("UNITPACK_CACHE_DIR", &filled_cache().cache)
        .env("TERM", "xterm");
    if let Some(d) = dir {
        cmd.current_dir(d);
    }
    let out = cmd.stdin(Stdio::null()).output().unwrap_or_else(|e| {
        panic!("cannot run `script` ({e}): install util-linux (Debian: bsdutils)")
    });
    (
        out.status.code().expect("not killed by a signal"),
        String::from_utf8_lossy(&out.stdout).into_owned(),
    )
}

/// Every row `choose ARGS --limit 0 --json` ranks, in order.
pub fn chosen(args: &[&str]) -> Vec<serde_json::Value> {
    let r = ok(&[&["choose"][..], args, &["--limit", "0", "--json"]].concat());
    serde_json::from_str::<serde_json::Value>(&r.stdout)
        .expect("choose --json is JSON")
        .as_array()
        .expect("an array")
        .clone()
}

/// The `data-value` attributes of a report row's cells, in order.
pub fn values(row: &str) -> Vec<String> {
    row.split("data-value=\"")
        .skip(1)
        .map(|s| s.split('"').next().unwrap().to_string())
        .collect()
}

/// The cell values of frame spec `id`'s row on a report's frames page.
pub fn frame_row_values(page: &str, id: &str) -> Vec<String> {
    let row = page
        .lines()
        .find(|l| l.starts_with(&format!("<tr id=\"{id}\"")))
        .unwrap_or_else(|| panic!("{id} on the frames page"));
    values(row)
}

/// A GLB of `json` and the BIN chunk `bin`, each padded to 4 bytes as the container asks.
pub fn glb(json: &serde_json::Value, bin: &[u8]) -> Vec<u8> {
    let mut j = json.to_string().into_bytes();
    j.resize(j.len().next_multiple_of(4), b' ');
    let mut b = bin.to_vec();
    b.resize(b.len().next_multiple_of(4), 0);
    let total = 12 + 8 + j.len() + 8 + b.len();
    let mut out = Vec::new();
    out.extend(b"glTF");
    out.extend(2u32.to_le_bytes());
    out.extend((total as u32).to_le_bytes());
    out.extend((j.len() as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend(&j);
    out.extend((b.len() as u32).to_le_bytes());
    out.extend(b"BIN\0");
    out.extend(&b);
    out
}
