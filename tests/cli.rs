//! The `unitpack` binary end to end: every verb, every bad-input case, exit statuses and
//! the text a user relies on. Runs the built binary with std::process::Command.

use std::collections::BTreeSet;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use unitpack::codecs::core::info::Sizes;
use unitpack::codecs::core::spec::TableFormat;
use unitpack::codecs::{FAMILIES, Spec};
use unitpack::emit::Lang;

#[derive(Clone)]
struct Run {
    code: i32,
    stdout: String,
    /// stdout as bytes (binary formats).
    out: Vec<u8>,
    stderr: String,
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
fn unitpack() -> Command {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_unitpack"));
    cmd.env("UNITPACK_CACHE_DIR", &filled_cache().cache);
    cmd
}

/// The shared figure cache and the tree written by the `generate` that filled it.
struct Filled {
    cache: PathBuf,
    tree: PathBuf,
    run: Run,
}

/// Fills the shared cache with one `generate` that starts from no cache file, so that it
/// proves every figure and bound afresh: [`generate_is_deterministic`] holds its tree to
/// the committed one.
fn filled_cache() -> &'static Filled {
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
fn uncached(dir: Option<&Path>, args: &[&str]) -> Run {
    let mut cmd = unitpack();
    cmd.env("UNITPACK_CACHE_DIR", "").args(args);
    if let Some(d) = dir {
        cmd.current_dir(d);
    }
    run_cmd(cmd, b"")
}

/// Runs `cmd` with `stdin` written from another thread (so that large inputs and outputs
/// cannot deadlock on full pipes).
fn run_cmd(mut cmd: Command, stdin: &[u8]) -> Run {
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

fn run_in(dir: Option<&Path>, args: &[&str], stdin: &str) -> Run {
    let mut cmd = unitpack();
    cmd.args(args);
    if let Some(d) = dir {
        cmd.current_dir(d);
    }
    run_cmd(cmd, stdin.as_bytes())
}

fn run_bytes(args: &[&str], stdin: &[u8]) -> Run {
    let mut cmd = unitpack();
    cmd.args(args);
    run_cmd(cmd, stdin)
}

fn run(args: &[&str]) -> Run {
    run_in(None, args, "")
}

fn run_stdin(args: &[&str], stdin: &str) -> Run {
    run_in(None, args, stdin)
}

fn ok(args: &[&str]) -> Run {
    let r = run(args);
    assert_eq!(r.code, 0, "unitpack {args:?} should succeed: {r:?}");
    r
}

/// A failure with exit status 2 (error), nothing on stdout; returns stderr.
fn fails(args: &[&str], stdin: &str) -> String {
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
fn fails_after(args: &[&str], stdin: &str, before: &str) -> String {
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
fn bad_spec(spec: &str) -> String {
    fails(&["gen", spec, "--lang", "wgsl"], "")
}

fn manifest_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn tempdir() -> tempfile::TempDir {
    tempfile::tempdir().expect("temporary directory")
}

/// Every file below `dir`, relative, sorted.
fn tree(dir: &Path) -> BTreeSet<PathBuf> {
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
/// and the manifest.
fn expected_files() -> BTreeSet<PathBuf> {
    let mut s = BTreeSet::from([PathBuf::from(".unitpack-manifest")]);
    for lang in Lang::ALL {
        for spec in Spec::all() {
            s.insert(PathBuf::from(lang.name()).join(format!("{}.{}", spec.id(), lang.ext())));
        }
    }
    for spec in Spec::all() {
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

fn generate_into(dir: &Path) -> Run {
    generated_into(
        dir,
        ok(&["generate", "--out", dir.to_str().expect("UTF-8 path")]),
    )
}

/// What `generate` into `dir` reported, checked.
fn generated_into(dir: &Path, r: Run) -> Run {
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

fn check(dir: &Path) -> Run {
    run(&[
        "generate",
        "--out",
        dir.to_str().expect("UTF-8 path"),
        "--check",
    ])
}

fn parse_vec(line: &str) -> [f32; 3] {
    let v: Vec<f32> = line
        .split_whitespace()
        .map(|t| t.parse::<f32>().expect("decode prints f32"))
        .collect();
    assert_eq!(v.len(), 3, "decode line {line:?} should hold three numbers");
    [v[0], v[1], v[2]]
}

fn angle_deg(a: [f32; 3], b: [f32; 3]) -> f64 {
    let d = |v: [f32; 3]| v.map(f64::from);
    let (a, b) = (d(a), d(b));
    let dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let la = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    let lb = (b[0] * b[0] + b[1] * b[1] + b[2] * b[2]).sqrt();
    (dot / (la * lb)).clamp(-1.0, 1.0).acos().to_degrees()
}

fn is_hex_code(line: &str, digits: usize) -> bool {
    line.strip_prefix("0x").is_some_and(|h| {
        h.len() == digits
            && h.chars()
                .all(|c| c.is_ascii_digit() || ('a'..='f').contains(&c))
    })
}

// ---------------------------------------------------------------------------------------
// help, version, usage errors

#[test]
fn top_level_help_lists_every_verb() {
    let r = ok(&["--help"]);
    assert!(
        r.stdout.contains("Compact unit-vector (normal) codecs"),
        "{r:?}"
    );
    for verb in [
        "list",
        "gen",
        "generate",
        "encode",
        "decode",
        "verify",
        "convert-normal-map",
    ] {
        assert!(
            r.stdout
                .lines()
                .any(|l| l.trim_start().starts_with(&format!("{verb} "))),
            "--help should list `{verb}`: {r:?}"
        );
    }
}

#[test]
fn every_verb_has_help_with_a_description() {
    let cases = [
        ("list", "List every codec"),
        ("gen", "Print the include for one or more specs"),
        ("generate", "Write every codec × language"),
        ("encode", "Encode vectors read from stdin"),
        ("decode", "Decode codes read from stdin"),
        ("verify", "Prove emitted code bit-exact"),
    ];
    for (verb, description) in cases {
        let r = ok(&[verb, "--help"]);
        assert!(
            r.stdout.contains(description),
            "`{verb} --help` should describe the verb: {r:?}"
        );
        assert!(
            r.stdout.contains(&format!("Usage: unitpack {verb}")),
            "`{verb} --help` usage line: {r:?}"
        );
    }
    // The spec syntax is documented where specs are typed.
    let r = ok(&["gen", "--help"]);
    assert!(r.stdout.contains("NAME[BITS][p][:key=value,...]"), "{r:?}");
    assert!(
        r.stdout.contains("--prefix") && r.stdout.contains("--out") && r.stdout.contains("--lang"),
        "{r:?}"
    );
    let r = ok(&["generate", "--help"]);
    assert!(
        r.stdout.contains("--check") && r.stdout.contains("[default: generated]"),
        "{r:?}"
    );
}

#[test]
fn version() {
    let r = ok(&["--version"]);
    assert_eq!(
        r.stdout.trim(),
        format!("unitpack {}", env!("CARGO_PKG_VERSION"))
    );
}

#[test]
fn usage_errors_exit_2() {
    for args in [
        &[][..],
        &["bogus"][..],
        &["gen", "oct16"][..],                       // --lang is required
        &["gen", "--lang", "wgsl"][..],              // a spec is required
        &["gen", "oct16", "--lang", "cuda"][..],     // unknown language
        &["encode"][..],                             // spec required
        &["decode"][..],                             // spec required
        &["verify", "oct16", "--lang", "spirv"][..], // unknown language
    ] {
        let r = run(args);
        assert_eq!(r.code, 2, "unitpack {args:?}: {r:?}");
        assert!(
            r.stderr.contains("Usage: unitpack")
                || r.stderr.contains("For more information, try '--help'"),
            "unitpack {args:?} should explain the usage error: {r:?}"
        );
    }
    let r = run(&["gen", "oct16", "--lang", "cuda"]);
    assert!(
        r.stderr.contains("wgsl") && r.stderr.contains("glsl") && r.stderr.contains("hlsl"),
        "{r:?}"
    );
}

// ---------------------------------------------------------------------------------------
// list

#[test]
fn list_names_every_codec_with_its_bit_sizes() {
    let r = ok(&["list"]);
    assert!(r.stderr.is_empty(), "{r:?}");
    let header = r.stdout.lines().next().expect("header line");
    for col in ["family", "domain", "precise", "source"] {
        assert!(header.contains(col), "list header {header:?} lacks {col}");
    }
    for f in FAMILIES {
        let c = f.info();
        let line = r
            .stdout
            .lines()
            .find(|l| l.split_whitespace().next() == Some(c.name))
            .unwrap_or_else(|| panic!("list has no line for {}: {r:?}", c.name));
        // Every spelling a user types is listed, and each one parses.
        for (spelled, _) in c.spellings() {
            assert!(
                r.stdout.contains(&spelled),
                "list lacks the spec {spelled}: {r:?}"
            );
            spelled.parse::<Spec>().expect("listed specs parse");
        }
        assert!(
            line.contains(c.source),
            "list line for {} lacks its source: {line:?}",
            c.name
        );
        assert!(
            r.stdout.contains(c.title),
            "list lacks the title of {}",
            c.name
        );
        for o in c.options {
            assert!(
                r.stdout.contains(&format!("option {}=", o.key)) && r.stdout.contains(o.help),
                "list lacks option {} of {}",
                o.key,
                c.name
            );
        }
    }
}

#[test]
fn list_snapshot() {
    let r = ok(&["list"]);
    insta::assert_snapshot!("list", r.stdout);
}

// ---------------------------------------------------------------------------------------
// gen

#[test]
fn gen_wgsl_defines_encode_and_decode() {
    let r = ok(&["gen", "oct16", "--lang", "wgsl"]);
    assert!(r.stdout.contains("fn unitpack_oct16_encode("), "{r:?}");
    assert!(r.stdout.contains("fn unitpack_oct16_decode("), "{r:?}");
    assert!(
        r.stdout
            .contains("// Regenerate: unitpack gen oct16 --lang wgsl\n"),
        "{r:?}"
    );
    assert!(r.stderr.is_empty(), "{r:?}");
}

#[test]
fn gen_glsl_and_hlsl_signatures() {
    let r = ok(&["gen", "oct16", "--lang", "glsl"]);
    assert!(
        r.stdout.contains("uint unitpack_oct16_encode(vec3 v)"),
        "{r:?}"
    );
    assert!(
        r.stdout.contains("vec3 unitpack_oct16_decode(uint code)"),
        "{r:?}"
    );
    assert!(r.stdout.contains("#ifndef UNITPACK_OCT16_GLSL"), "{r:?}");
    let r = ok(&["gen", "oct16", "--lang", "hlsl"]);
    assert!(
        r.stdout.contains("uint unitpack_oct16_encode(float3 v)"),
        "{r:?}"
    );
    assert!(
        r.stdout.contains("float3 unitpack_oct16_decode(uint code)"),
        "{r:?}"
    );
    assert!(r.stdout.contains("#ifndef UNITPACK_OCT16_HLSL"), "{r:?}");
}

#[test]
fn gen_several_specs_in_one_include() {
    let r = ok(&["gen", "oct16", "hemioct24p", "snorm8x3", "--lang", "wgsl"]);
    for f in [
        "unitpack_oct16_encode",
        "unitpack_hemioct24p_encode",
        "unitpack_snorm8x3_decode",
    ] {
        assert!(r.stdout.contains(&format!("fn {f}(")), "missing {f}: {r:?}");
    }
    assert!(
        r.stdout
            .contains("// Regenerate: unitpack gen oct16 hemioct24p snorm8x3 --lang wgsl\n"),
        "{r:?}"
    );
}

#[test]
fn gen_options_reach_the_output() {
    let r = ok(&["gen", "oct24:layout=rgb8", "--lang", "wgsl"]);
    assert!(r.stdout.contains("fn unitpack_oct24_rgb8_encode("), "{r:?}");
    assert!(r.stdout.contains("fn unitpack_oct24_rgb8_decode("), "{r:?}");
    // layout=snorm is the default: same text as no option.
    assert_eq!(
        ok(&["gen", "oct24:layout=snorm", "--lang", "wgsl"]).stdout,
        ok(&["gen", "oct24", "--lang", "wgsl"]).stdout
    );
    // A non-default scale is part of the spec's displayed name and changes the code.
    let scaled = ok(&["gen", "stereo_scaled16:scale=2", "--lang", "wgsl"]);
    let default = ok(&["gen", "stereo_scaled16", "--lang", "wgsl"]);
    assert!(
        scaled
            .stdout
            .contains("unitpack gen stereo_scaled16:scale=2 --lang wgsl"),
        "{scaled:?}"
    );
    assert_ne!(scaled.stdout, default.stdout);
}

#[test]
fn gen_spec_names_are_case_insensitive() {
    assert_eq!(
        ok(&["gen", "OCT16P", "--lang", "wgsl"]).stdout,
        ok(&["gen", "oct16p", "--lang", "wgsl"]).stdout
    );
}

#[test]
fn gen_prefix_renames_every_function() {
    let r = ok(&["gen", "oct16", "--lang", "wgsl", "--prefix", "my_"]);
    assert!(r.stdout.contains("fn my_oct16_encode("), "{r:?}");
    assert!(r.stdout.contains("fn my_oct16_decode("), "{r:?}");
    assert!(
        !r.stdout.contains("unitpack_oct16"),
        "default prefix left behind: {r:?}"
    );
    assert!(
        r.stdout.contains("--prefix my_"),
        "the regenerate line should repeat the prefix: {r:?}"
    );
    let r = ok(&["gen", "oct16", "--lang", "glsl", "--prefix", "my_"]);
    assert!(r.stdout.contains("#ifndef MY_OCT16_GLSL"), "{r:?}");
    // An empty prefix is allowed: bare names.
    let r = ok(&["gen", "oct16", "--lang", "wgsl", "--prefix", ""]);
    assert!(r.stdout.contains("fn oct16_encode("), "{r:?}");
}

#[test]
fn gen_rejects_invalid_prefixes() {
    for prefix in ["9bad", "a__b", "my-", "_x", "é_", "a b"] {
        let err = fails(&["gen", "oct16", "--lang", "wgsl", "--prefix", prefix], "");
        assert!(
            err.contains(&format!("invalid prefix '{prefix}'")),
            "prefix {prefix:?}: {err}"
        );
    }
}

#[test]
fn gen_out_writes_what_stdout_shows() {
    let dir = tempdir();
    let path = dir.path().join("oct16.wgsl");
    let r = ok(&[
        "gen",
        "oct16",
        "--lang",
        "wgsl",
        "--out",
        path.to_str().unwrap(),
    ]);
    assert!(
        r.stdout.is_empty(),
        "with --out nothing goes to stdout: {r:?}"
    );
    let written = std::fs::read_to_string(&path).expect("--out file");
    assert_eq!(written, ok(&["gen", "oct16", "--lang", "wgsl"]).stdout);
    assert_eq!(
        tree(dir.path()),
        BTreeSet::from([PathBuf::from("oct16.wgsl")]),
        "no temporary files left"
    );
}

#[test]
fn gen_out_replaces_an_existing_file_atomically() {
    let dir = tempdir();
    let path = dir.path().join("normals.glsl");
    std::fs::write(
        &path,
        "old contents that are longer than nothing\n".repeat(500),
    )
    .unwrap();
    #[cfg(unix)]
    let old_inode = std::os::unix::fs::MetadataExt::ino(&std::fs::metadata(&path).unwrap());
    ok(&[
        "gen",
        "hemioct16",
        "--lang",
        "glsl",
        "--out",
        path.to_str().unwrap(),
    ]);
    assert_eq!(
        std::fs::read_to_string(&path).unwrap(),
        ok(&["gen", "hemioct16", "--lang", "glsl"]).stdout
    );
    // Replaced by a rename, not rewritten in place: readers never see a half-written file.
    #[cfg(unix)]
    assert_ne!(
        std::os::unix::fs::MetadataExt::ino(&std::fs::metadata(&path).unwrap()),
        old_inode
    );
    assert_eq!(
        tree(dir.path()),
        BTreeSet::from([PathBuf::from("normals.glsl")]),
        "no temporary files left"
    );
}

#[test]
fn gen_out_creates_missing_directories() {
    let dir = tempdir();
    let path = dir.path().join("new").join("dir").join("x.wgsl");
    ok(&[
        "gen",
        "oct16",
        "--lang",
        "wgsl",
        "--out",
        path.to_str().unwrap(),
    ]);
    assert_eq!(
        std::fs::read_to_string(&path).unwrap(),
        ok(&["gen", "oct16", "--lang", "wgsl"]).stdout
    );
    assert_eq!(
        tree(dir.path()),
        BTreeSet::from([PathBuf::from("new/dir/x.wgsl")])
    );
}

/// A failed write names the user's path, never the temporary file beside it, and leaves
/// nothing behind.
#[test]
fn gen_out_errors_name_the_file_not_a_temporary_one() {
    let dir = tempdir();
    std::fs::write(dir.path().join("plain"), "a file, not a directory\n").unwrap();
    let path = dir.path().join("plain").join("x.wgsl");
    let err = fails(
        &[
            "gen",
            "oct16",
            "--lang",
            "wgsl",
            "--out",
            path.to_str().unwrap(),
        ],
        "",
    );
    assert!(
        err.contains(&format!("cannot write {}", path.display())),
        "{err}"
    );
    // The temporary directory's own name may contain "tmp"; nothing after it may.
    let rest = err.replace(dir.path().to_str().unwrap(), "DIR");
    assert!(!rest.contains("tmp"), "a temporary file is named: {err}");
    assert_eq!(tree(dir.path()), BTreeSet::from([PathBuf::from("plain")]));
    // /proc refuses new files even to root: the temporary file cannot be created.
    #[cfg(target_os = "linux")]
    {
        let err = fails(
            &[
                "gen",
                "oct16",
                "--lang",
                "wgsl",
                "--out",
                "/proc/self/x.wgsl",
            ],
            "",
        );
        assert!(err.contains("cannot write /proc/self/x.wgsl"), "{err}");
        assert!(!err.contains("tmp"), "a temporary file is named: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
    }
}

#[test]
fn gen_out_onto_a_directory_writes_into_it() {
    let dir = tempdir();
    ok(&[
        "gen",
        "oct16",
        "--lang",
        "wgsl",
        "--out",
        dir.path().to_str().unwrap(),
    ]);
    assert_eq!(
        tree(dir.path()),
        BTreeSet::from([PathBuf::from("oct16.wgsl")])
    );
    assert_eq!(
        std::fs::read_to_string(dir.path().join("oct16.wgsl")).unwrap(),
        ok(&["gen", "oct16", "--lang", "wgsl"]).stdout
    );
    // A directory where the file would go is never replaced.
    let other = tempdir();
    std::fs::create_dir(other.path().join("oct16.wgsl")).unwrap();
    let err = fails(
        &[
            "gen",
            "oct16",
            "--lang",
            "wgsl",
            "--out",
            other.path().to_str().unwrap(),
        ],
        "",
    );
    assert!(err.contains("it is a directory"), "{err}");
    assert!(other.path().join("oct16.wgsl").is_dir());
    assert!(
        tree(other.path()).is_empty(),
        "no temporary file may be left behind"
    );
}

#[test]
fn gen_with_one_bad_spec_prints_nothing() {
    let err = fails(&["gen", "oct16", "octt16", "--lang", "wgsl"], "");
    assert!(err.contains("unknown codec 'octt16'"), "{err}");
}

/// `gen SPEC` writes exactly the file `generate` writes for it, Regenerate line included.
#[test]
fn gen_writes_exactly_the_generated_file() {
    let dir = tempdir();
    generate_into(dir.path());
    for (spec, lang) in [
        ("oct16", Lang::Wgsl),
        ("spherical24p", Lang::Glsl),
        ("snorm16x3", Lang::Hlsl),
        ("oct24p_rgb8", Lang::C),
    ] {
        let g = ok(&["gen", spec, "--lang", lang.name()]).stdout;
        let f = std::fs::read_to_string(
            dir.path()
                .join(lang.name())
                .join(format!("{spec}.{}", lang.ext())),
        )
        .unwrap();
        // The header names `gen` itself, so the two are the same bytes.
        assert_eq!(g, f, "{spec}.{lang}");
    }
}

// ---------------------------------------------------------------------------------------
// spec errors

#[test]
fn unknown_codec_suggests_the_nearest_and_lists_all() {
    let err = bad_spec("octt16");
    assert!(err.contains("unknown codec 'octt16'"), "{err}");
    let after = err
        .split("did you mean ")
        .nth(1)
        .unwrap_or_else(|| panic!("no suggestion: {err}"));
    let first: String = after
        .chars()
        .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
        .collect();
    assert_eq!(first, "oct", "nearest match first: {err}");
    let valid = err
        .split("Valid codecs: ")
        .nth(1)
        .unwrap_or_else(|| panic!("no list of codecs: {err}"));
    let valid: BTreeSet<&str> = valid.trim().split(", ").collect();
    // Families spelled by component size (snorm8x3, float16x3) list those spellings; their
    // family names are not specs.
    for c in FAMILIES.iter().map(|f| f.info()) {
        if let Sizes::PerComponent { .. } = c.sizes {
            assert!(
                !valid.contains(c.name),
                "{} alone does not parse: {err}",
                c.name
            );
            for (id, _) in c.spellings() {
                assert!(valid.contains(id.as_str()), "valid codecs lack {id}: {err}");
            }
        } else {
            assert!(
                valid.contains(c.name),
                "valid codecs lack {}: {err}",
                c.name
            );
        }
    }
    for id in ["snorm8x3", "snorm10x3", "snorm16x3", "float16x3"] {
        assert!(valid.contains(id), "valid codecs lack {id}: {err}");
    }

    let err = bad_spec("hemiokt16");
    let first = err.split("did you mean ").nth(1).unwrap();
    assert!(first.starts_with("hemioct"), "{err}");
    let err = bad_spec("");
    assert!(err.contains("unknown codec ''"), "{err}");
}

#[test]
fn invalid_bits_name_the_allowed_sizes() {
    let err = bad_spec("oct17");
    assert!(err.contains("oct has no 17-bit form"), "{err}");
    assert!(err.contains("allowed sizes: 16, 20, 22, 24, 32"), "{err}");
    let err = bad_spec("hemioct20p");
    assert!(err.contains("allowed sizes: 16, 24, 32"), "{err}");
    // Bits are required.
    let err = bad_spec("oct");
    assert!(err.contains("allowed sizes: 16, 20, 22, 24, 32"), "{err}");
    let err = bad_spec("lambert16pp");
    assert!(err.contains("after lambert16 comes nothing"), "{err}");
}

#[test]
fn snorm3_is_spelled_by_component_size() {
    let err = bad_spec("snorm9x3");
    for id in ["snorm8x3", "snorm10x3", "snorm16x3"] {
        assert!(err.contains(id), "{err}");
    }
    for id in ["snorm8x3", "snorm10x3", "snorm16x3"] {
        let r = ok(&["gen", id, "--lang", "wgsl"]);
        assert!(
            r.stdout.contains(&format!("fn unitpack_{id}_encode(")),
            "{r:?}"
        );
    }
    // The family name is not a spec; the precise form (Best Fit Normals) is.
    let err = bad_spec("snorm3");
    assert!(err.contains("snorm8x3"), "{err}");
    let r = ok(&["gen", "snorm8x3p", "--lang", "wgsl"]);
    assert!(r.stdout.contains("fn unitpack_snorm8x3p_encode("), "{r:?}");
    bad_spec("snorm8x3pp");
    bad_spec("snorm0x3");
}

#[test]
fn snorm12x2_takes_no_bits_or_precise_suffix() {
    let r = ok(&["gen", "snorm12x2", "--lang", "wgsl"]);
    assert!(
        r.stdout.contains("fn unitpack_snorm12x2_to_unorm8x3("),
        "{r:?}"
    );
    assert!(
        r.stdout.contains("fn unitpack_unorm8x3_to_snorm12x2("),
        "{r:?}"
    );
    bad_spec("snorm12x2p");
    bad_spec("snorm12x3");
    let err = bad_spec("snorm12x2:foo=1");
    assert!(err.contains("'foo'"), "{err}");
}

#[test]
fn layout_rgb8_is_oct24_only() {
    for spec in ["oct16:layout=rgb8", "oct32p:layout=rgb8"] {
        let err = bad_spec(spec);
        assert!(
            err.contains("rgb8") && err.contains("oct24"),
            "{spec}: {err}"
        );
    }
    let err = bad_spec("oct24:layout=rgb9");
    assert!(
        err.contains("'rgb9'") && err.contains("expected snorm or rgb8"),
        "{err}"
    );
    // hemioct's layout option is the texel one, without rgb8; lambert has none.
    let err = bad_spec("hemioct24:layout=rgb8");
    assert!(err.contains("expected snorm or rg or dxt5nm"), "{err}");
    let err = bad_spec("lambert24:layout=rgb8");
    assert!(err.contains("no option 'layout'"), "{err}");
}

#[test]
fn stereo_scale_must_be_a_positive_finite_number() {
    // Also bounded, so that the literals derived from it (2s, -s, 0.5/s) stay finite.
    for v in ["-1", "0", "-0", "inf", "nan", "3e38", "1e-39"] {
        let err = bad_spec(&format!("stereo_scaled16:scale={v}"));
        assert!(
            err.contains(&format!("'{v}'")) && err.contains("[0.001, 1000]"),
            "scale={v}: {err}"
        );
    }
    for v in ["abc", ""] {
        let err = bad_spec(&format!("stereo_scaled16:scale={v}"));
        assert!(err.contains("expected a number"), "scale={v}: {err}");
    }
    ok(&["gen", "stereo_scaled24p:scale=1.5", "--lang", "hlsl"]);
}

#[test]
fn unknown_options_are_named() {
    let err = bad_spec("stereo_scaled16:foo=1");
    assert!(err.contains("no option 'foo'"), "{err}");
    assert!(
        err.contains("scale="),
        "the valid options should be listed: {err}"
    );
    let err = bad_spec("oct16:scale=2");
    assert!(
        err.contains("no option 'scale'") && err.contains("layout="),
        "{err}"
    );
}

// ---------------------------------------------------------------------------------------
// encode / decode

#[test]
fn encode_prints_one_hex_code_per_line() {
    let r = run_stdin(&["encode", "oct16"], "0 0 1\n1 0 0\n");
    assert_eq!(r.code, 0, "{r:?}");
    let lines: Vec<&str> = r.stdout.lines().collect();
    assert_eq!(lines.len(), 2, "{r:?}");
    for l in &lines {
        assert!(is_hex_code(l, 8), "{l:?} is not 0x + 8 hex digits");
    }
    assert_ne!(lines[0], lines[1]);
}

/// The texel layouts' example: x in alpha (0.6·½ + ½ = 204/255), y in green, R = 1, and a
/// layout on any size but 16 bits is a clear error.
#[test]
fn encode_writes_a_dxt5nm_texel() {
    let r = run_stdin(&["encode", "xy16:layout=dxt5nm"], "0.6 0 0.8\n");
    assert_eq!(r.code, 0, "{r:?}");
    let t = u32::from_str_radix(r.stdout.trim().trim_start_matches("0x"), 16).unwrap();
    assert_eq!(t >> 24, 0xcc, "alpha of {t:#010x}");
    assert_eq!(t >> 8 & 0xff, 0x80, "green of {t:#010x}: 127.5 ties up");
    assert_eq!(
        (t & 0xff, t >> 16 & 0xff),
        (0xff, 0),
        "red and blue of {t:#010x}"
    );
    let r = run_stdin(&["encode", "xy24:layout=dxt5nm"], "0 0 1\n");
    assert_eq!(r.code, 2, "{r:?}");
    assert!(r.stderr.contains("16-bit form only"), "{r:?}");
}

#[test]
fn decode_inverts_encode() {
    let input = [
        [0.0, 0.0, 1.0],
        [1.0, 0.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.48, -0.6, 0.64],
        [-0.36, 0.48, -0.8],
    ];
    let text: String = input
        .iter()
        .map(|v| format!("{} {} {}\n", v[0], v[1], v[2]))
        .collect();
    let enc = run_stdin(&["encode", "oct16"], &text);
    assert_eq!(enc.code, 0, "{enc:?}");
    let dec = run_stdin(&["decode", "oct16"], &enc.stdout);
    assert_eq!(dec.code, 0, "{dec:?}");
    let out: Vec<[f32; 3]> = dec.stdout.lines().map(parse_vec).collect();
    assert_eq!(out.len(), input.len(), "{dec:?}");
    // Axes are exact in oct16; the documented maximum error is below 1°.
    assert_eq!(&out[..2], &[[0.0, 0.0, 1.0], [1.0, 0.0, 0.0]]);
    for (a, b) in input.iter().zip(&out) {
        assert!(angle_deg(*a, *b) < 1.0, "{a:?} → {b:?}");
        let len = b.iter().map(|x| x * x).sum::<f32>().sqrt();
        assert!(
            (len - 1.0).abs() < 1e-6,
            "oct decodes to unit vectors: {b:?}"
        );
    }
}

#[test]
fn encode_and_decode_round_trip_for_every_codec() {
    // Vectors in the +Z hemisphere, away from every codec's singular region.
    let input: Vec<[f32; 3]> = vec![
        [0.0, 0.0, 1.0],
        [0.6, 0.0, 0.8],
        [0.0, -0.6, 0.8],
        [-0.48, 0.36, 0.8],
        [0.3, 0.3, 0.9055385],
    ];
    let text: String = input
        .iter()
        .map(|v| format!("{} {} {}\n", v[0], v[1], v[2]))
        .collect();
    for spec in Spec::all().iter().filter(|s| s.info().domain.is_some()) {
        let name = spec.to_string();
        let arg = name.replace("_rgb8", ":layout=rgb8");
        let enc = run_stdin(&["encode", &arg], &text);
        assert_eq!(enc.code, 0, "{name}: {enc:?}");
        let digits = if spec.bits() > 32 {
            spec.bits().div_ceil(4) as usize
        } else {
            8
        };
        assert!(
            enc.stdout.lines().all(|l| is_hex_code(l, digits)),
            "{name}: {enc:?}"
        );
        let dec = run_stdin(&["decode", &arg], &enc.stdout);
        assert_eq!(dec.code, 0, "{name}: {dec:?}");
        let out: Vec<[f32; 3]> = dec.stdout.lines().map(parse_vec).collect();
        assert_eq!(out.len(), input.len(), "{name}: {dec:?}");
        // The seed's method 3a tables misread its own codes near the poles by several
        // degrees (README, "The first seed's method 3a"; sample max 7.2°), with either encoder.
        let tol = match spec.bits() {
            _ if spec.fast().id() == "spherical_lut16" => 8.0,
            0..=16 => 3.0,
            _ => 1.0,
        };
        for (a, b) in input.iter().zip(&out) {
            assert!(
                angle_deg(*a, *b) < tol,
                "{name}: {a:?} → {b:?} ({}°)",
                angle_deg(*a, *b)
            );
        }
    }
}

#[test]
fn encode_degenerate_input_gives_the_plus_z_code() {
    let plus_z = run_stdin(&["encode", "oct16"], "0 0 1\n");
    assert_eq!(plus_z.code, 0, "{plus_z:?}");
    let r = run_stdin(
        &["encode", "oct16"],
        "0 0 0\nnan nan nan\ninf 0 0\n-inf 1 0\n0 NaN 1\n",
    );
    assert_eq!(r.code, 0, "{r:?}");
    let lines: Vec<&str> = r.stdout.lines().collect();
    assert_eq!(lines.len(), 5, "{r:?}");
    for l in lines {
        assert!(is_hex_code(l, 8), "{l:?}");
        // oct's documented policy: zero, NaN and infinite input encode as +Z.
        assert_eq!(l, plus_z.stdout.trim());
    }
}

/// Output line N answers input line N: blank and `#` lines pass through unchanged.
#[test]
fn blank_and_comment_lines_pass_through_so_lines_correspond() {
    let plus_z = run_stdin(&["encode", "oct16"], "0 0 1\n").stdout;
    let plus_x = run_stdin(&["encode", "oct16"], "1 0 0\n").stdout;
    let r = run_stdin(
        &["encode", "oct16"],
        "\n  0 0 1  \n# a comment\n\n   # indented\n1\t0\t0",
    );
    assert_eq!(r.code, 0, "{r:?}");
    assert_eq!(
        r.stdout,
        format!("\n{plus_z}# a comment\n\n   # indented\n{plus_x}"),
        "{r:?}"
    );
    let r = run_stdin(&["decode", "oct16"], "# codes\n0x0000007f\n\n127\n");
    assert_eq!(r.code, 0, "{r:?}");
    assert_eq!(r.stdout, "# codes\n1.0 0.0 0.0\n\n1.0 0.0 0.0\n", "{r:?}");
    // Blank lines still count in error messages.
    let err = fails_after(
        &["encode", "oct16"],
        "0 0 1\n\n1 2\n",
        &format!("{plus_z}\n"),
    );
    assert!(err.contains("line 3"), "blank lines still count: {err}");
    // Empty input: no output, success.
    let r = run_stdin(&["encode", "oct16"], "");
    assert_eq!((r.code, r.stdout.as_str()), (0, ""), "{r:?}");
    // \r\n line ends are read; output lines end in \n.
    let r = run_stdin(&["encode", "oct16"], "0 0 1\r\n# c\r\n");
    assert_eq!(r.stdout, format!("{plus_z}# c\n"), "{r:?}");
}

/// On stdout, the output of every line before a bad one has been written (as the help
/// says); the error names the line and quotes it.
#[test]
fn encode_malformed_line_fails_after_the_lines_before_it() {
    let plus_z = run_stdin(&["encode", "oct16"], "0 0 1\n").stdout;
    let err = fails_after(&["encode", "oct16"], "0 0 1\n1 2\n0 1 0\n", &plus_z);
    assert!(err.contains("line 2"), "{err}");
    assert!(
        err.contains("\"1 2\""),
        "the bad line should be quoted: {err}"
    );
    for bad in ["1 2 3 4", "a b c", "1,0,0", "0x1 0 0"] {
        let err = fails(&["encode", "oct16"], &format!("{bad}\n"));
        assert!(err.contains("line 1"), "{bad:?}: {err}");
    }
}

#[test]
fn encode_names_numbers_outside_the_f32_range() {
    for bad in ["1e39 0 0", "0 -3.5e38 0", "0 0 1e400"] {
        let err = fails(&["encode", "oct16"], &format!("{bad}\n"));
        assert!(
            err.contains("line 1") && err.contains("outside the f32 range"),
            "{bad:?}: {err}"
        );
    }
    // Spelled infinities are accepted (and encode as +Z), as is f32::MAX.
    let r = run_stdin(&["encode", "oct16"], "inf 0 0\n3.4028235e38 0 0\n");
    assert_eq!(r.code, 0, "{r:?}");
}

#[test]
fn a_byte_order_mark_at_the_start_is_accepted() {
    let plain = run_stdin(&["encode", "oct16"], "0 0 1\n");
    let r = run_stdin(&["encode", "oct16"], "\u{feff}0 0 1\n");
    assert_eq!((r.code, &r.stdout), (0, &plain.stdout), "{r:?}");
    let r = run_stdin(&["decode", "oct16"], "\u{feff}0x7f\n");
    assert_eq!((r.code, r.stdout.as_str()), (0, "1.0 0.0 0.0\n"), "{r:?}");
    // Only at the start.
    let err = fails_after(
        &["encode", "oct16"],
        "0 0 1\n\u{feff}0 0 1\n",
        &plain.stdout,
    );
    assert!(err.contains("line 2"), "{err}");
}

#[test]
fn invalid_utf8_is_an_error_naming_its_line() {
    let r = run_bytes(&["encode", "oct16"], b"0 0 1\n0 1 0\n\xff\xfe 0 0\n");
    assert_eq!(r.code, 2, "{r:?}");
    assert!(
        r.stderr.contains("line 3") && r.stderr.contains("UTF-8"),
        "{r:?}"
    );
    assert_eq!(r.stdout.lines().count(), 2, "{r:?}");
    let r = run_bytes(&["decode", "oct16"], b"0x7f\n0x\xc3\n");
    assert_eq!(r.code, 2, "{r:?}");
    assert!(
        r.stderr.contains("line 2") && r.stderr.contains("UTF-8"),
        "{r:?}"
    );
}

/// A bad line is quoted cut to about 80 characters, whatever its length.
#[test]
fn errors_quote_at_most_80_characters_of_a_line() {
    for verb in ["encode", "decode"] {
        let line = format!("0 0 {}\n", "9".repeat(5000));
        let err = fails(&[verb, "oct16"], &line);
        assert!(err.contains("line 1"), "{err}");
        assert!(
            err.len() < 400,
            "{verb}: {} bytes of error: {err}",
            err.len()
        );
        assert!(err.contains("5004 bytes"), "{verb}: {err}");
    }
    // 10 MB without a line end: still a short error, and quickly.
    let huge = "x".repeat(10 << 20);
    let err = fails(&["encode", "oct16"], &huge);
    assert!(err.contains("line 1") && err.len() < 400, "{err}");
}

#[test]
fn decode_malformed_line_fails_after_the_lines_before_it() {
    let err = fails(&["decode", "oct16"], "zz\n");
    assert!(err.contains("line 1"), "{err}");
    let err = fails_after(
        &["decode", "oct16"],
        "0x00000000\n0x7f\n0xg\n",
        "0.0 0.0 1.0\n1.0 0.0 0.0\n",
    );
    assert!(err.contains("line 3"), "{err}");
    let err = fails(&["decode", "oct16"], "0x100000000\n");
    assert!(err.contains("line 1") && err.contains("16 bits"), "{err}");
    let err = fails(&["decode", "snorm16x3"], "0x10000000000000000\n");
    assert!(err.contains("line 1") && err.contains("48 bits"), "{err}");
}

/// One grammar: `0x` + hex digits, or decimal digits; nothing else.
#[test]
fn decode_reads_0x_hex_or_decimal_and_nothing_else() {
    let r = run_stdin(
        &["decode", "oct16"],
        "0x0000007f\n0X7F\n  0x7f  \n127\n\t0127\n",
    );
    assert_eq!(r.code, 0, "{r:?}");
    let lines: Vec<&str> = r.stdout.lines().collect();
    assert_eq!(lines.len(), 5, "{r:?}");
    for l in lines {
        assert_eq!(parse_vec(l), [1.0, 0.0, 0.0], "{r:?}");
    }
    // 123 is decimal 123, not 0x123.
    assert_eq!(
        run_stdin(&["decode", "oct16"], "123\n").stdout,
        run_stdin(&["decode", "oct16"], "0x7b\n").stdout
    );
    assert_ne!(
        run_stdin(&["decode", "oct16"], "123\n").stdout,
        run_stdin(&["decode", "oct16"], "0x123\n").stdout
    );
    for bad in [
        "0b101", "+ff", "0x+ff", "-1", "+1", "7f", "0x", "1_000", "0o17", "0x7f 1", "1.0",
    ] {
        let err = fails(&["decode", "oct16"], &format!("{bad}\n"));
        assert!(
            err.contains("line 1") && err.contains("0x followed by hex digits"),
            "{bad:?}: {err}"
        );
    }
}

/// A decoder ignores bits above its width, so such a code is refused rather than
/// decoded as another.
#[test]
fn decode_rejects_codes_wider_than_the_spec() {
    for (spec, ok_code, bad, bits) in [
        ("oct16", "0xffff", "0x1ffff", 16),
        ("oct16", "65535", "65536", 16),
        ("oct24", "0xffffff", "0x1000000", 24),
        ("oct24:layout=rgb8", "0xffffff", "0x1000000", 24),
        ("snorm10x3", "0x3fffffff", "0x40000000", 30),
        ("oct32", "0xffffffff", "0x100000000", 32),
        ("snorm16x3", "0xffffffffffff", "0x1000000000000", 48),
        ("snorm16x3", "281474976710655", "18446744073709551616", 48),
    ] {
        let r = run_stdin(&["decode", spec], &format!("{ok_code}\n"));
        assert_eq!(r.code, 0, "{spec} {ok_code}: {r:?}");
        let err = fails(&["decode", spec], &format!("{bad}\n"));
        assert!(
            err.contains("line 1") && err.contains(&format!("width of {bits} bits")),
            "{spec} {bad}: {err}"
        );
    }
}

/// Every code `encode` prints fits the spec's width, so `decode` accepts it.
#[test]
fn every_encoded_code_fits_the_spec_width() {
    use unitpack::codecs::core::function::{Inputs, Role};
    let mut vs = unitpack::sampling::random_unit_vectors(5, 4096, false);
    vs.extend([
        [0.0, 0.0, -1.0],
        [-1.0, -1.0, -1.0],
        [0.0, 0.0, 0.0],
        [f32::NAN; 3],
    ]);
    for spec in Spec::all().iter().filter(|s| s.info().domain.is_some()) {
        let e = spec.emitted();
        // The code's width: the spec's bits, or a texel layout's whole RGBA8 texel.
        let width = if unitpack::codecs::toolkit::texel::layout(spec).is_some() {
            32
        } else {
            spec.bits()
        };
        // Every encoder of a vector alone (a lookup-table codec's CPU encoder, not its
        // emitted `encode(v, fetched)`, which takes the fetch as well).
        let encoders = e.cpu.iter().chain(&e.functions);
        for f in encoders.filter(|f| f.role == Role::Encode && f.inputs == Inputs::Vectors) {
            let mut code = vec![0u32; f.out_words];
            for v in &vs {
                (f.eval)(&v.map(f32::to_bits), &mut code);
                let c = code
                    .iter()
                    .rev()
                    .fold(0u128, |a, w| (a << 32) | u128::from(*w));
                assert!(c >> width == 0, "{spec} {}: {v:?} → {c:#x}", f.name);
            }
        }
    }
}

#[test]
fn snorm16x3_codes_have_12_hex_digits() {
    let enc = run_stdin(&["encode", "snorm16x3"], "0 0 1\n");
    assert_eq!(enc.code, 0, "{enc:?}");
    assert_eq!(enc.stdout, "0x7fff00000000\n");
    let dec = run_stdin(&["decode", "snorm16x3"], "0x7fff00000000\n0x123456789abc\n");
    assert_eq!(dec.code, 0, "{dec:?}");
    let out: Vec<[f32; 3]> = dec.stdout.lines().map(parse_vec).collect();
    assert_eq!(out.len(), 2);
    assert_eq!(out[0], [0.0, 0.0, 1.0]);
    let len = out[1].iter().map(|x| x * x).sum::<f32>().sqrt();
    assert!(
        (len - 1.0).abs() < 1e-5,
        "snorm3 decode re-normalizes: {:?}",
        out[1]
    );
}

/// float32x3 codes are three words: 24 hex digits (z's word highest) in text, 12 bytes
/// (x's word first) in binary, and back.
#[test]
fn float32x3_codes_are_three_words() {
    let enc = run_stdin(&["encode", "float32x3"], "0 -2 0\n");
    assert_eq!(enc.code, 0, "{enc:?}");
    assert_eq!(enc.stdout, "0x00000000bf80000000000000\n");
    let dec = run_stdin(&["decode", "float32x3"], "0x3f800000000000003f000000\n");
    assert_eq!(dec.code, 0, "{dec:?}");
    assert_eq!(dec.stdout, "0.5 0.0 1.0\n");
    let err = fails(&["decode", "float32x3"], "0x1000000000000000000000000\n");
    assert!(err.contains("96 bits"), "{err}");
    let bin = run_stdin(
        &["encode", "float32x3", "--output-format", "binary"],
        "0 0 -1\n",
    );
    assert_eq!(bin.code, 0, "{bin:?}");
    let words: Vec<u8> = [0u32, 0, 0xbf80_0000]
        .iter()
        .flat_map(|w| w.to_le_bytes())
        .collect();
    assert_eq!(bin.out, words);
    let back = run_bytes(&["decode", "float32x3", "--input-format", "binary"], &words);
    assert_eq!(back.code, 0, "{back:?}");
    assert_eq!(back.stdout, "0.0 0.0 -1.0\n");
    let short = run_bytes(
        &["decode", "float32x3", "--input-format", "binary"],
        &words[..8],
    );
    assert_ne!(short.code, 0);
    assert!(
        short.stderr.contains("a code is 12 bytes, 3×u32"),
        "{short:?}"
    );
}

#[test]
fn helpers_have_no_encode_or_decode() {
    for verb in ["encode", "decode"] {
        for helper in ["snorm12x2", "paraboloid_pd"] {
            let err = fails(&[verb, helper], "0 0 1\n");
            assert!(
                err.contains(&format!("{helper} is a helper, not a codec")),
                "{verb}: {err}"
            );
        }
    }
}

#[test]
fn encode_and_decode_reject_bad_specs() {
    for verb in ["encode", "decode"] {
        let err = fails(&[verb, "octt16"], "0 0 1\n");
        assert!(err.contains("unknown codec 'octt16'"), "{verb}: {err}");
        let err = fails(&[verb, "oct16:layout=rgb8"], "0 0 1\n");
        assert!(err.contains("oct24"), "{verb}: {err}");
    }
}

// ---------------------------------------------------------------------------------------
// generate

#[test]
fn generate_writes_every_spec_and_language_then_checks_clean() {
    let dir = tempdir();
    generate_into(dir.path());
    assert_eq!(
        tree(dir.path()),
        expected_files(),
        "exactly the catalogue's files, nothing temporary"
    );
    let r = check(dir.path());
    assert_eq!(r.code, 0, "{r:?}");
    assert!(r.stdout.contains("up to date"), "{r:?}");
    // Every include starts with the generated-file header (tables, binary, have none:
    // the manifest records their hashes).
    for rel in expected_files()
        .into_iter()
        .filter(|r| r != Path::new(".unitpack-manifest") && !r.starts_with("lut"))
    {
        let text = std::fs::read_to_string(dir.path().join(&rel)).unwrap();
        assert!(
            text.starts_with("// Generated by unitpack"),
            "{}",
            rel.display()
        );
    }
}

#[test]
fn generate_check_names_a_changed_file() {
    let dir = tempdir();
    generate_into(dir.path());
    let p = dir.path().join("wgsl/oct16.wgsl");
    let mut text = std::fs::read_to_string(&p).unwrap();
    text = text.replacen("0.0f", "0.5f", 1);
    std::fs::write(&p, &text).unwrap();
    let r = check(dir.path());
    assert_eq!(r.code, 1, "{r:?}");
    assert!(
        r.stdout
            .lines()
            .any(|l| l.starts_with("changed:") && l.ends_with("wgsl/oct16.wgsl")),
        "{r:?}"
    );
    assert_eq!(
        r.stdout.lines().filter(|l| l.contains(':')).count(),
        1,
        "only that file: {r:?}"
    );
    assert!(
        r.stdout
            .contains(&format!("1 of {} generated files", expected_files().len())),
        "{r:?}"
    );
    assert_eq!(
        std::fs::read_to_string(&p).unwrap(),
        text,
        "--check must not write"
    );
}

#[test]
fn generate_check_names_a_missing_file() {
    let dir = tempdir();
    generate_into(dir.path());
    std::fs::remove_file(dir.path().join("glsl/hemioct24p.glsl")).unwrap();
    let r = check(dir.path());
    assert_eq!(r.code, 1, "{r:?}");
    assert!(
        r.stdout
            .lines()
            .any(|l| l.starts_with("missing:") && l.ends_with("glsl/hemioct24p.glsl")),
        "{r:?}"
    );
    assert!(
        !dir.path().join("glsl/hemioct24p.glsl").exists(),
        "--check must not write"
    );
}

/// A file is extra (and pruned) only when the manifest lists it and it has the header.
#[test]
fn generate_check_names_an_extra_file() {
    let dir = tempdir();
    generate_into(dir.path());
    let stale = dir.path().join("wgsl/oct17.wgsl");
    std::fs::write(&stale, "// Generated by unitpack 0.0.1 — do not edit.\n").unwrap();
    add_to_manifest(dir.path(), "wgsl/oct17.wgsl");
    let r = check(dir.path());
    assert_eq!(r.code, 1, "{r:?}");
    assert!(
        r.stdout
            .lines()
            .any(|l| l.starts_with("extra:") && l.contains("wgsl/oct17.wgsl")),
        "{r:?}"
    );
    // Only the manifest (which lists the stale file) differs from what generate writes.
    let changed: Vec<&str> = r
        .stdout
        .lines()
        .filter(|l| l.starts_with("changed:") || l.starts_with("missing:"))
        .collect();
    assert!(
        changed.len() == 1 && changed[0].ends_with(".unitpack-manifest"),
        "{r:?}"
    );
    // `generate` removes what `--check` called extra, and leaves other files alone.
    std::fs::write(dir.path().join("wgsl/notes.txt"), "mine\n").unwrap();
    let r = generate_into(dir.path());
    assert!(
        r.stdout.contains("removed ") && r.stdout.contains("oct17.wgsl"),
        "{r:?}"
    );
    assert!(!stale.exists());
    assert!(dir.path().join("wgsl/notes.txt").exists());
    let r = check(dir.path());
    assert_eq!(r.code, 0, "user files do not make the check fail: {r:?}");
    assert!(
        r.stdout.contains("kept: ") && r.stdout.contains("notes.txt"),
        "{r:?}"
    );
}

#[test]
fn generate_check_of_an_empty_directory_names_every_file_missing() {
    let dir = tempdir();
    let r = check(dir.path());
    assert_eq!(r.code, 1, "{r:?}");
    let n = expected_files().len();
    assert_eq!(
        r.stdout
            .lines()
            .filter(|l| l.starts_with("missing:"))
            .count(),
        n,
        "{r:?}"
    );
    assert!(tree(dir.path()).is_empty(), "--check must not write");
}

#[test]
fn generate_is_deterministic() {
    // One run proving every figure and bound afresh writes, byte for byte, the tree an
    // earlier process wrote: the committed `generated/` (which
    // `committed_generated_directory_is_up_to_date` also holds to the current code).
    let fill = filled_cache();
    let a = fill.tree.as_path();
    generated_into(a, fill.run.clone());
    let committed = manifest_dir().join("generated");
    let files = tree(a);
    assert_eq!(files, tree(&committed));
    let same_as_committed = |dir: &Path| {
        for rel in &files {
            let (x, y) = (
                std::fs::read(dir.join(rel)).unwrap(),
                std::fs::read(committed.join(rel)).unwrap(),
            );
            assert!(x == y, "{} differs between two runs", rel.display());
        }
    };
    same_as_committed(a);
    // Regenerating over an existing tree leaves it identical, and so do the figures
    // cached by a run before (the second of two runs on the test binary's shared cache
    // reads them all from it).
    generate_into(a);
    generate_into(a);
    same_as_committed(a);
    assert_eq!(tree(a), files);
}

#[test]
fn committed_generated_directory_is_up_to_date() {
    // The figures may come from the test binary's shared cache: `generate_is_deterministic`
    // holds a run that proves them all afresh to the same tree.
    let r = run_in(Some(&manifest_dir()), &["generate", "--check"], "");
    assert_eq!(
        r.code, 0,
        "generated/ is stale; run `cargo run --release -- generate`: {r:?}"
    );
    assert!(
        r.stdout.contains("files in generated are up to date"),
        "{r:?}"
    );
}

/// `gen` and `generate` keep the figures they state (proven bounds, error statistics) in
/// `$UNITPACK_CACHE_DIR/figures.txt` for the next run of the same executable: a run reads
/// them from there, a file of another build is replaced, a damaged one is ignored, a
/// file that is not the cache is never touched, and set empty the variable writes nothing.
#[test]
fn gen_keeps_its_figures_for_the_next_run() {
    let home = tempdir();
    let dir = home.path().join("cache");
    let file = dir.join("figures.txt");
    let gen_with = |cache: &Path| {
        let mut cmd = unitpack();
        cmd.env("UNITPACK_CACHE_DIR", cache)
            .args(["gen", "oct16", "--lang", "wgsl"]);
        let r = run_cmd(cmd, b"");
        assert_eq!(r.code, 0, "{r:?}");
        r.stdout
    };
    let plain = uncached(None, &["gen", "oct16", "--lang", "wgsl"]).stdout;
    assert!(plain.contains("mean 0.33696°"), "{plain}");
    assert_eq!(gen_with(&dir), plain, "a first run states what it proves");
    let text = std::fs::read_to_string(&file).expect("the first run writes the cache");
    let header = text.lines().next().unwrap().to_string();
    assert!(
        header.starts_with("unitpack figure cache v2 exe="),
        "{header}"
    );
    assert!(text.lines().any(|l| l.starts_with("bound ")), "{text}");

    // The next run takes the figures from the file: one edited there shows in the include.
    let line = text
        .lines()
        .find(|l| l.starts_with("stats ") && l.split(' ').nth(2) == Some("oct16"))
        .expect("oct16's statistics");
    let mut words: Vec<&str> = line.split(' ').collect();
    words[3] = "4029000000000000"; // a mean of 12.5°
    std::fs::write(&file, text.replace(line, &words.join(" "))).unwrap();
    let edited = gen_with(&dir);
    assert!(edited.contains("mean 12.50000°"), "{edited}");
    assert_eq!(edited.replace("mean 12.50000°", "mean 0.33696°"), plain);

    // Another build's file, an older format's, or a damaged one, is not read, and is
    // replaced by this one's.
    for foreign in [
        text.replacen(&header, "unitpack figure cache v2 exe=0123456789abcdef", 1),
        text.replacen(&header, "unitpack figure cache v1 exe=0123456789abcdef", 1),
        format!("{text}bound zz\n"),
    ] {
        std::fs::write(&file, &foreign).unwrap();
        assert_eq!(gen_with(&dir), plain);
        let now = std::fs::read_to_string(&file).unwrap();
        assert!(now.starts_with(&format!("{header}\n")), "{now}");
    }

    // A file of the user's at that path stays as it was.
    std::fs::write(&file, "my notes\n").unwrap();
    assert_eq!(gen_with(&dir), plain);
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "my notes\n");

    // Set empty, the variable turns the cache off.
    let off = home.path().join("off");
    let mut cmd = unitpack();
    cmd.env("UNITPACK_CACHE_DIR", "")
        .env("HOME", &off)
        .env("XDG_CACHE_HOME", &off);
    cmd.args(["gen", "oct16", "--lang", "wgsl"]);
    assert_eq!(run_cmd(cmd, b"").stdout, plain);
    assert!(!off.exists(), "nothing written with the cache off");
}

// ---------------------------------------------------------------------------------------
// verify (GPU: Mesa lavapipe)

#[test]
fn verify_oct16_wgsl_on_lavapipe() {
    // Without XDG_RUNTIME_DIR Mesa complains on stderr; that noise is not unitpack's.
    let mut cmd = unitpack();
    cmd.args(["verify", "oct16", "--lang", "wgsl"])
        .env_remove("XDG_RUNTIME_DIR");
    let r = run_cmd(cmd, b"");
    assert_eq!(r.code, 0, "{r:?}");
    assert!(!r.stderr.contains("XDG_RUNTIME_DIR"), "{r:?}");
    assert!(r.stdout.lines().any(|l| l.starts_with("adapter:")), "{r:?}");
    let rows: Vec<&str> = r
        .stdout
        .lines()
        .filter(|l| l.starts_with("oct16 "))
        .collect();
    assert!(!rows.is_empty(), "{r:?}");
    // The WGSL path, and the model's own four- and eight-lane paths, which need no language.
    assert!(
        rows.iter().all(|l| l.contains("wgsl/naga")
            || l.contains("cpu/4 lanes")
            || l.contains("cpu/8 lanes")),
        "{r:?}"
    );
    for lanes in ["cpu/4 lanes", "cpu/8 lanes"] {
        assert!(rows.iter().any(|l| l.contains(lanes)), "{lanes}: {r:?}");
    }
    for f in ["encode", "decode"] {
        assert!(
            rows.iter().any(|l| l.split_whitespace().nth(1) == Some(f)),
            "no row for {f}: {r:?}"
        );
    }
    assert!(r.stdout.contains(" 0 failed"), "{r:?}");
}

/// `--adapter gpu` runs the shader paths on the machine's own GPU, never on lavapipe: where
/// there is none (CI), it fails naming the adapters it found and what to install.
#[test]
fn verify_on_the_hardware_adapter_never_falls_back_to_lavapipe() {
    let r = run(&["verify", "oct16", "--lang", "wgsl", "--adapter", "gpu"]);
    let adapter = r.stdout.lines().find(|l| l.starts_with("adapter:"));
    match adapter {
        Some(line) => assert!(!line.contains("llvmpipe"), "{r:?}"),
        None => {
            assert_eq!(r.code, 2, "{r:?}");
            assert!(
                r.stderr
                    .contains("no hardware Vulkan adapter found (adapters: ")
                    && r.stderr.contains("llvmpipe")
                    && r.stderr.contains("libvulkan1"),
                "{r:?}"
            );
        }
    }
    let err = fails(&["verify", "oct16", "--adapter", "npu"], "");
    assert!(err.contains("invalid value 'npu'"), "{err}");
}

#[test]
fn verify_rejects_bad_specs() {
    let err = fails(&["verify", "octt16", "--lang", "wgsl"], "");
    assert!(err.contains("unknown codec 'octt16'"), "{err}");
}

/// Every committed include names the command that writes it, `unitpack gen <spec> --lang
/// <lang>`, and that command reproduces the file byte for byte (run for each spec in one
/// language, the languages in turn; `generate --check` compares every file).
#[test]
fn every_generated_file_regenerates_from_its_header() {
    let root = manifest_dir().join("generated");
    let ids: Vec<String> = Spec::all().iter().map(Spec::id).collect();
    let (mut checked, mut ran) = (0, 0);
    for (l, lang) in Lang::ALL.into_iter().enumerate() {
        let dir = root.join(lang.name());
        for entry in std::fs::read_dir(&dir).expect("generated language folder") {
            let path = entry.unwrap().path();
            let text = std::fs::read_to_string(&path).unwrap();
            let cmd = text
                .lines()
                .find_map(|l| l.split("Regenerate: ").nth(1))
                .unwrap_or_else(|| panic!("{} has no Regenerate line", path.display()));
            let args: Vec<&str> = cmd.split_whitespace().collect();
            let stem = path.file_stem().unwrap().to_str().unwrap();
            // The header regenerates the file's spec (named as the catalogue writes it,
            // `oct24:layout=rgb8` for `oct24_rgb8`) in the folder's language.
            assert_eq!(args.len(), 5, "{cmd}");
            assert_eq!(args[..2], ["unitpack", "gen"], "{cmd}");
            assert_eq!(args[3..], ["--lang", lang.name()], "{cmd}");
            let spec: Spec = args[2].parse().unwrap();
            assert_eq!(spec.id(), stem, "{}: the header's spec", path.display());
            // The file name (the id) is a spec too.
            assert_eq!(stem.parse::<Spec>().unwrap(), spec);
            // Each spec's command runs in one language, the languages taking turns: the
            // four differ only in `--lang`, and running all would prove every decoder
            // bound four times over.
            let k = ids.iter().position(|i| i == stem).expect("a catalogue id");
            if k % Lang::ALL.len() == l {
                let r = ok(&args[1..]);
                assert!(
                    r.stdout == text,
                    "{cmd} does not reproduce {}",
                    path.display()
                );
                ran += 1;
            }
            checked += 1;
        }
    }
    assert_eq!(checked, ids.len() * Lang::ALL.len());
    assert_eq!(ran, ids.len());
}

// ---------------------------------------------------------------------------------------
// generate never loses a user's file (issue 6, item 1)

/// Lists `rel` in `dir`'s manifest, as an earlier run that wrote it would have.
fn add_to_manifest(dir: &Path, rel: &str) {
    let m = dir.join(".unitpack-manifest");
    let mut text = std::fs::read_to_string(&m).unwrap_or_default();
    text.push_str(rel);
    text.push('\n');
    std::fs::write(&m, text).unwrap();
}

/// `generate --out dir`, which must succeed (without depending on its summary's wording,
/// so that the tests of what it does to files test only that).
fn generate_plain(dir: &Path) -> Run {
    ok(&["generate", "--out", dir.to_str().expect("UTF-8 path")])
}

/// Every file below `dir` with its contents.
fn snapshot(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    tree(dir)
        .into_iter()
        .map(|rel| {
            let bytes = std::fs::read(dir.join(&rel)).unwrap();
            (rel, bytes)
        })
        .collect()
}

#[test]
fn generate_keeps_files_it_did_not_write() {
    let dir = tempdir();
    let d = dir.path();
    std::fs::create_dir_all(d.join("wgsl")).unwrap();
    std::fs::create_dir_all(d.join("glsl")).unwrap();
    std::fs::write(d.join("wgsl/lighting.wgsl"), "fn light() {}\n").unwrap();
    std::fs::write(d.join("glsl/pbr.glsl"), "void pbr() {}\n").unwrap();
    let r = generate_plain(d);
    for f in ["wgsl/lighting.wgsl", "glsl/pbr.glsl"] {
        assert!(d.join(f).exists(), "{f} was removed: {r:?}");
        assert!(
            r.stdout
                .lines()
                .any(|l| l.starts_with("kept: ") && l.contains(f)),
            "{f} should be reported as kept: {r:?}"
        );
    }
    assert!(!r.stdout.contains("removed"), "{r:?}");
    assert_eq!(
        std::fs::read_to_string(d.join("wgsl/lighting.wgsl")).unwrap(),
        "fn light() {}\n"
    );
    // A file with unitpack's header that no manifest lists (from `gen --out`) is kept too.
    let mine = d.join("hlsl/mine.hlsl");
    ok(&[
        "gen",
        "oct16",
        "--lang",
        "hlsl",
        "--out",
        mine.to_str().unwrap(),
    ]);
    let r = generate_plain(d);
    assert!(mine.exists(), "{r:?}");
    assert!(
        r.stdout.contains("kept: ") && r.stdout.contains("mine.hlsl"),
        "{r:?}"
    );
    // A listed file whose header was removed was taken over by the user: kept.
    std::fs::write(d.join("wgsl/taken.wgsl"), "// my own now\n").unwrap();
    add_to_manifest(d, "wgsl/taken.wgsl");
    let r = generate_plain(d);
    assert!(d.join("wgsl/taken.wgsl").exists(), "{r:?}");
    assert!(
        r.stdout.contains("taken.wgsl") && r.stdout.contains("header"),
        "{r:?}"
    );
    assert_eq!(check(d).code, 0, "kept files do not make --check fail");
}

#[test]
fn generate_prunes_only_inside_its_folders() {
    let outer = tempdir();
    let d = outer.path().join("out");
    generate_plain(&d);
    let victim = outer.path().join("victim.wgsl");
    std::fs::write(
        &victim,
        "// Generated by unitpack, but not in its folders\n",
    )
    .unwrap();
    for entry in [
        "../victim.wgsl",
        "/etc/passwd",
        "wgsl/../../victim.wgsl",
        "victim.wgsl",
    ] {
        add_to_manifest(&d, entry);
    }
    generate_plain(&d);
    assert!(
        victim.exists(),
        "a manifest entry outside DIR/<lang>/ was followed"
    );
}

#[test]
fn generate_refuses_to_replace_a_users_file_at_a_catalogue_path() {
    let dir = tempdir();
    let d = dir.path();
    generate_plain(d);
    let stale = d.join("glsl/oct16.glsl");
    let mut text = std::fs::read_to_string(&stale).unwrap();
    text.push_str("// stale\n");
    std::fs::write(&stale, &text).unwrap();
    let user = d.join("wgsl/oct16.wgsl");
    std::fs::write(&user, "// my own oct16\n").unwrap();
    let before = snapshot(d);
    let err = fails(&["generate", "--out", d.to_str().unwrap()], "");
    assert!(
        err.contains("nothing written")
            && err.contains("wgsl/oct16.wgsl")
            && err.contains("--force"),
        "{err}"
    );
    assert_eq!(snapshot(d), before, "a refused generate must write nothing");
    let r = check(d);
    assert!(
        r.stdout.contains("not written by unitpack") && r.stdout.contains("wgsl/oct16.wgsl"),
        "{r:?}"
    );
    ok(&["generate", "--out", d.to_str().unwrap(), "--force"]);
    assert_eq!(check(d).code, 0);
}

/// Tables carry no header: the manifest's contents hash is what makes one ours. A table
/// replaced by the user is refused without --force; one that left the catalogue is
/// removed while it still has its recorded hash and kept once it has changed.
#[test]
fn generate_knows_its_tables_by_their_recorded_hash() {
    let dir = tempdir();
    let d = dir.path();
    generate_plain(d);
    let table = d.join("lut/spherical_lut16_atan.png");
    assert!(table.is_file());
    std::fs::write(&table, b"my own atan table").unwrap();
    let before = snapshot(d);
    let err = fails(&["generate", "--out", d.to_str().unwrap()], "");
    assert!(
        err.contains("nothing written")
            && err.contains("lut/spherical_lut16_atan.png")
            && err.contains("--force"),
        "{err}"
    );
    assert_eq!(snapshot(d), before, "a refused generate must write nothing");
    ok(&["generate", "--out", d.to_str().unwrap(), "--force"]);
    assert_eq!(check(d).code, 0);
    // A table the manifest records but the catalogue no longer has: ours while it has
    // its hash (removed), the user's once changed (kept).
    let (old, mine) = (d.join("lut/retired.bin"), d.join("lut/taken.bin"));
    for p in [&old, &mine] {
        std::fs::write(p, b"\x00\x01\x02").unwrap();
    }
    let hash = unitpack_hash(b"\x00\x01\x02");
    add_to_manifest(d, &format!("lut/retired.bin {hash:016x}"));
    add_to_manifest(d, &format!("lut/taken.bin {hash:016x}"));
    std::fs::write(&mine, b"changed").unwrap();
    let r = generate_plain(d);
    assert!(!old.exists(), "{r:?}");
    assert!(mine.exists(), "{r:?}");
    assert!(
        r.stdout.contains("kept: ") && r.stdout.contains("taken.bin"),
        "{r:?}"
    );
}

/// The manifest's table hash, FNV-1a 64, written out here.
fn unitpack_hash(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in bytes {
        h = (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3);
    }
    h
}

/// Everything is prepared before anything is replaced: a folder that cannot take a file
/// leaves the others as they were.
#[cfg(target_os = "linux")]
#[test]
fn generate_writes_nothing_when_a_folder_is_unwritable() {
    let dir = tempdir();
    let d = dir.path();
    generate_plain(d);
    // Make wgsl/ stale, then make glsl/ a folder no one (not even root) can create in.
    let w = d.join("wgsl/oct16.wgsl");
    let stale = std::fs::read_to_string(&w).unwrap() + "// stale\n";
    std::fs::write(&w, &stale).unwrap();
    std::fs::remove_dir_all(d.join("glsl")).unwrap();
    std::os::unix::fs::symlink("/proc/self", d.join("glsl")).unwrap();
    let r = run(&["generate", "--out", d.to_str().unwrap()]);
    assert_eq!(r.code, 2, "{r:?}");
    assert_eq!(
        std::fs::read_to_string(&w).unwrap(),
        stale,
        "wgsl/ was rewritten"
    );
    assert!(r.stderr.contains("nothing written"), "{r:?}");
    assert!(
        tree(&d.join("wgsl"))
            .iter()
            .all(|p| !p.to_string_lossy().starts_with('.')),
        "temporary files left behind"
    );
    // A directory where a file goes is found before anything is written, too.
    std::fs::remove_file(d.join("glsl")).unwrap();
    std::fs::create_dir_all(d.join("glsl/oct16.glsl")).unwrap();
    let err = fails(&["generate", "--out", d.to_str().unwrap()], "");
    assert!(err.contains("glsl/oct16.glsl"), "{err}");
    assert_eq!(
        std::fs::read_to_string(&w).unwrap(),
        stale,
        "wgsl/ was rewritten"
    );
}

#[test]
fn generate_runs_in_parallel_on_one_folder() {
    let dir = tempdir();
    let d = dir.path();
    generate_plain(d);
    for round in 0..2 {
        // Stale files from an "older catalogue", which every run will try to prune.
        for i in 0..60 {
            let rel = format!("wgsl/old{round}_{i}.wgsl");
            std::fs::write(d.join(&rel), "// Generated by unitpack 0.0.1\n").unwrap();
            add_to_manifest(d, &rel);
        }
        std::fs::write(
            d.join("glsl/oct16.glsl"),
            "// Generated by unitpack, stale\n",
        )
        .unwrap();
        let children: Vec<_> = (0..4)
            .map(|_| {
                unitpack()
                    .args(["generate", "--out", d.to_str().unwrap()])
                    .stdout(Stdio::piped())
                    .stderr(Stdio::piped())
                    .spawn()
                    .unwrap()
            })
            .collect();
        for c in children {
            let out = c.wait_with_output().unwrap();
            assert!(
                out.status.success(),
                "a parallel generate failed: {}",
                String::from_utf8_lossy(&out.stderr)
            );
        }
        assert_eq!(tree(d), expected_files(), "round {round}");
        assert_eq!(check(d).code, 0);
    }
}

#[test]
fn generate_help_and_readme_say_what_it_prunes() {
    let r = ok(&["generate", "--help"]);
    for s in [
        ".unitpack-manifest",
        "removes a file only if",
        "Generated by unitpack",
        "kept",
    ] {
        assert!(r.stdout.contains(s), "generate --help lacks {s:?}: {r:?}");
    }
    let readme = std::fs::read_to_string(manifest_dir().join("README.md")).unwrap();
    for s in [".unitpack-manifest", "removes a file only if"] {
        assert!(readme.contains(s), "README lacks {s:?}");
    }
}

#[test]
fn committed_generated_directory_has_its_manifest() {
    let m = std::fs::read_to_string(manifest_dir().join("generated/.unitpack-manifest"))
        .expect("generated/.unitpack-manifest is committed");
    // A table's line ends in its contents hash.
    let listed: BTreeSet<PathBuf> = m
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| PathBuf::from(l.split(' ').next().unwrap()))
        .collect();
    let mut want = expected_files();
    want.remove(Path::new(".unitpack-manifest"));
    assert_eq!(listed, want);
}

// ---------------------------------------------------------------------------------------
// writing files (item 6)

fn gen_to(path: &Path, extra: &[&str]) -> Run {
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

#[cfg(unix)]
#[test]
fn gen_out_through_a_symlink_replaces_the_target_and_keeps_the_link() {
    let dir = tempdir();
    let d = dir.path();
    std::fs::create_dir(d.join("real")).unwrap();
    std::fs::write(d.join("real/normals.wgsl"), "old\n").unwrap();
    // A chain: link → link2 → real/normals.wgsl (relative targets).
    std::os::unix::fs::symlink("real/normals.wgsl", d.join("link2")).unwrap();
    std::os::unix::fs::symlink("link2", d.join("link")).unwrap();
    let r = gen_to(&d.join("link"), &[]);
    assert_eq!(r.code, 0, "{r:?}");
    let want = ok(&["gen", "oct16", "--lang", "wgsl"]).stdout;
    assert_eq!(
        std::fs::read_to_string(d.join("real/normals.wgsl")).unwrap(),
        want
    );
    for l in ["link", "link2"] {
        assert!(
            std::fs::symlink_metadata(d.join(l))
                .unwrap()
                .file_type()
                .is_symlink(),
            "{l} is no longer a link"
        );
    }
    // A dangling link: its target is created.
    std::os::unix::fs::symlink("made.wgsl", d.join("dangling")).unwrap();
    assert_eq!(gen_to(&d.join("dangling"), &[]).code, 0);
    assert_eq!(std::fs::read_to_string(d.join("made.wgsl")).unwrap(), want);
    assert!(
        std::fs::symlink_metadata(d.join("dangling"))
            .unwrap()
            .file_type()
            .is_symlink()
    );
}

#[cfg(unix)]
#[test]
fn gen_out_never_carries_setuid_or_setgid_bits() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempdir();
    let p = dir.path().join("x.wgsl");
    std::fs::write(&p, "old\n").unwrap();
    std::fs::set_permissions(&p, std::fs::Permissions::from_mode(0o6755)).unwrap();
    assert_eq!(
        std::fs::metadata(&p).unwrap().permissions().mode() & 0o7777,
        0o6755
    );
    assert_eq!(gen_to(&p, &[]).code, 0);
    assert_eq!(
        std::fs::metadata(&p).unwrap().permissions().mode() & 0o7777,
        0o755,
        "the permission bits stay, setuid and setgid go"
    );
}

/// A rename only needs the folder to be writable, so without a check a read-only file
/// would be replaced silently. Tests run as root, whom access(2) lets write anything, so
/// this checks the mode-bit rule (no write bit at all), which holds for root too.
#[cfg(unix)]
#[test]
fn gen_out_refuses_a_read_only_file_unless_forced() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempdir();
    let p = dir.path().join("x.wgsl");
    std::fs::write(&p, "keep me\n").unwrap();
    std::fs::set_permissions(&p, std::fs::Permissions::from_mode(0o444)).unwrap();
    let r = gen_to(&p, &[]);
    assert_eq!(r.code, 2, "{r:?}");
    assert!(
        r.stderr.contains("read-only") && r.stderr.contains("--force"),
        "{r:?}"
    );
    assert_eq!(std::fs::read_to_string(&p).unwrap(), "keep me\n");
    let r = gen_to(&p, &["--force"]);
    assert_eq!(r.code, 0, "{r:?}");
    assert_eq!(
        std::fs::read_to_string(&p).unwrap(),
        ok(&["gen", "oct16", "--lang", "wgsl"]).stdout
    );
    assert_eq!(
        std::fs::metadata(&p).unwrap().permissions().mode() & 0o777,
        0o444
    );
    // encode/decode --out follow the same rule.
    let out = dir.path().join("codes.txt");
    std::fs::write(&out, "old\n").unwrap();
    std::fs::set_permissions(&out, std::fs::Permissions::from_mode(0o444)).unwrap();
    let err = fails(
        &["encode", "oct16", "--out", out.to_str().unwrap()],
        "0 0 1\n",
    );
    assert!(err.contains("read-only"), "{err}");
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "old\n");
}

/// The access(2) half of the rule: a file whose mode lets others write it but not this
/// user. Root may write anything, so as root the binary runs as `nobody` (setpriv, from
/// util-linux) in a world-writable folder, where a rename could replace root's file.
#[cfg(target_os = "linux")]
#[test]
fn gen_out_refuses_a_file_the_user_may_not_write() {
    use std::os::unix::fs::PermissionsExt;
    if std::fs::read_to_string("/proc/self/status")
        .unwrap()
        .lines()
        .any(|l| l.starts_with("Uid:") && l.split_whitespace().nth(2) != Some("0"))
    {
        // Not root: nobody else's file can be set up here; the mode-bit test above covers
        // the refusal for this user.
        return;
    }
    let dir = tempdir();
    std::fs::set_permissions(dir.path(), std::fs::Permissions::from_mode(0o777)).unwrap();
    let p = dir.path().join("roots.wgsl");
    std::fs::write(&p, "root's\n").unwrap();
    std::fs::set_permissions(&p, std::fs::Permissions::from_mode(0o644)).unwrap();
    let as_nobody = |extra: &[&str]| {
        let mut cmd = Command::new("setpriv");
        cmd.args(["--reuid=65534", "--regid=65534", "--clear-groups", "--"])
            .arg(env!("CARGO_BIN_EXE_unitpack"))
            .args([
                "gen",
                "oct16",
                "--lang",
                "wgsl",
                "--out",
                p.to_str().unwrap(),
            ])
            .args(extra);
        run_cmd(cmd, b"")
    };
    let r = as_nobody(&[]);
    assert_eq!(r.code, 2, "{r:?}");
    assert!(
        r.stderr.contains("not writable by you") && r.stderr.contains("--force"),
        "{r:?}"
    );
    assert_eq!(std::fs::read_to_string(&p).unwrap(), "root's\n");
    let r = as_nobody(&["--force"]);
    assert_eq!(r.code, 0, "{r:?}");
    assert_eq!(
        std::fs::read_to_string(&p).unwrap(),
        ok(&["gen", "oct16", "--lang", "wgsl"]).stdout
    );
}

#[test]
fn gen_out_into_a_full_device_is_a_one_line_error() {
    let err = fails(
        &["gen", "oct16", "--lang", "wgsl", "--out", "/dev/full"],
        "",
    );
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("/dev/full") && err.contains("No space left"),
        "{err}"
    );
    assert!(Path::new("/dev/full").exists(), "the device is still there");
}

// ---------------------------------------------------------------------------------------
// gen with several languages (item 7)

#[test]
fn gen_takes_a_comma_list_of_languages_into_a_directory() {
    let dir = tempdir();
    let out = format!("{}/", dir.path().join("shaders").display());
    ok(&[
        "gen",
        "oct16",
        "hemioct24p",
        "--lang",
        "wgsl,glsl",
        "--out",
        &out,
    ]);
    assert_eq!(
        tree(dir.path()),
        BTreeSet::from([
            PathBuf::from("shaders/oct16-hemioct24p.glsl"),
            PathBuf::from("shaders/oct16-hemioct24p.wgsl"),
        ])
    );
    for lang in ["wgsl", "glsl"] {
        assert_eq!(
            std::fs::read_to_string(dir.path().join(format!("shaders/oct16-hemioct24p.{lang}")))
                .unwrap(),
            ok(&["gen", "oct16", "hemioct24p", "--lang", lang]).stdout,
            "{lang}"
        );
    }
    // --name picks the stem; a repeated --lang works as a list too.
    let named = tempdir();
    ok(&[
        "gen",
        "oct16",
        "--lang",
        "hlsl",
        "--lang",
        "wgsl",
        "--name",
        "normals",
        "--out",
        named.path().to_str().unwrap(),
    ]);
    assert_eq!(
        tree(named.path()),
        BTreeSet::from([PathBuf::from("normals.hlsl"), PathBuf::from("normals.wgsl")])
    );
    // Several languages on stdout would be one file of mixed languages: refused.
    let err = fails(&["gen", "oct16", "--lang", "wgsl,glsl"], "");
    assert!(err.contains("--out DIR/"), "{err}");
    for bad in ["../x", ".hidden", ""] {
        let err = fails(
            &[
                "gen",
                "oct16",
                "--lang",
                "wgsl",
                "--name",
                bad,
                "--out",
                named.path().to_str().unwrap(),
            ],
            "",
        );
        assert!(err.contains("--name"), "{bad:?}: {err}");
    }
}

// ---------------------------------------------------------------------------------------
// help and JSON (item 7)

#[test]
fn every_spec_argument_documents_the_grammar() {
    for verb in ["gen", "encode", "decode", "verify"] {
        let r = ok(&[verb, "--help"]);
        for s in [
            "NAME[BITS][p][:key=value,...]",
            "oct24p",
            "snorm8x3",
            "oct24:layout=rgb8",
        ] {
            assert!(r.stdout.contains(s), "`{verb} --help` lacks {s:?}: {r:?}");
        }
    }
    for verb in ["encode", "decode"] {
        let r = ok(&[verb, "--help"]);
        for s in [
            "x y z",
            "0x followed by hex digits",
            "decimal",
            "3 × f32",
            "u32 per word",
            "little-endian",
            "copied unchanged",
            "--out FILE nothing is written",
            "before the bad one has been written",
        ] {
            assert!(r.stdout.contains(s), "`{verb} --help` lacks {s:?}: {r:?}");
        }
    }
    let r = ok(&["gen", "--help"]);
    assert!(r.stdout.contains("comma-separated"), "{r:?}");
}

#[test]
fn list_json_has_every_spelling_a_user_types() {
    let r = ok(&["list", "--json"]);
    let v: serde_json::Value = serde_json::from_str(&r.stdout).expect("list --json is JSON");
    assert_eq!(v["grammar"], "NAME[BITS][p][:key=value,...]");
    let fams = v["families"].as_array().unwrap();
    assert_eq!(fams.len(), FAMILIES.len());
    let mut typed = BTreeSet::new();
    for f in fams {
        for s in f["specs"].as_array().unwrap() {
            let spec = s["spec"].as_str().unwrap();
            spec.parse::<Spec>()
                .unwrap_or_else(|e| panic!("{spec}: {e}"));
            typed.insert(spec.to_string());
            if let Some(p) = s["precise"].as_str() {
                assert!(p.parse::<Spec>().unwrap().precise(), "{p}");
            }
        }
    }
    assert!(
        typed.contains("snorm8x3") && !typed.contains("snorm3"),
        "{typed:?}"
    );
    let oct = fams.iter().find(|f| f["family"] == "oct").unwrap();
    assert_eq!(oct["options"][0]["key"], "layout");
    assert_eq!(oct["options"][0]["default"], "snorm");
    // The table shows the same spellings, and the grammar.
    let table = ok(&["list"]).stdout;
    for t in &typed {
        assert!(table.contains(t.as_str()), "{t}");
    }
    assert!(table.contains("NAME[BITS][p][:key=value,...]"));
}

#[test]
fn verify_json_reports_every_row() {
    let r = ok(&["verify", "oct16", "oct16p", "--lang", "wgsl,glsl", "--json"]);
    assert!(!r.stderr.contains("XDG_RUNTIME_DIR"), "{r:?}");
    let v: serde_json::Value = serde_json::from_str(&r.stdout).expect("verify --json is JSON");
    assert_eq!(v["passed"], true, "{r:?}");
    assert_eq!(v["failed"], 0);
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(v["checks"].as_u64().unwrap() as usize, rows.len());
    // oct16p's decoders are oct16's code: run once per path, their rows repeat oct16's;
    // the items counted are those run.
    let shared = |r: &&serde_json::Value| !r["same_code_as"].is_null();
    let items: u64 = rows
        .iter()
        .filter(|r| !shared(r))
        .map(|r| r["tested"].as_u64().unwrap())
        .sum();
    assert_eq!(v["items"].as_u64().unwrap(), items);
    let copies: Vec<_> = rows.iter().filter(shared).collect();
    assert_eq!(
        copies.len(),
        2 * 5,
        "two decoders on three shader paths and the four- and eight-lane paths"
    );
    for c in copies {
        assert_eq!(c["spec"], "oct16p");
        let owner = format!("oct16 {}", c["function"].as_str().unwrap());
        assert_eq!(c["same_code_as"].as_str(), Some(owner.as_str()));
    }
    let paths: BTreeSet<&str> = rows.iter().map(|r| r["path"].as_str().unwrap()).collect();
    for p in ["wgsl/naga", "glsl/naga", "glsl/glslang"] {
        assert!(paths.contains(p), "{paths:?}");
    }
    assert!(
        rows.iter()
            .all(|r| (r["spec"] == "oct16" || r["spec"] == "oct16p") && r["error"].is_null())
    );
}

// ---------------------------------------------------------------------------------------
// pipes and full disks (item 5)

fn closed_pipe() -> Stdio {
    let (reader, writer) = std::io::pipe().expect("pipe");
    drop(reader);
    Stdio::from(writer)
}

fn dev_full() -> Stdio {
    Stdio::from(
        std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .expect("/dev/full"),
    )
}

/// Runs `args` with stdout going to `out`; returns (exit status, stderr).
fn run_into(args: &[&str], stdin: &[u8], out: Stdio) -> (i32, String) {
    let mut child = unitpack()
        .args(args)
        .stdin(Stdio::piped())
        .stdout(out)
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn");
    let mut si = child.stdin.take().unwrap();
    let input = stdin.to_vec();
    let w = std::thread::spawn(move || {
        let _ = si.write_all(&input);
    });
    let o = child.wait_with_output().unwrap();
    w.join().unwrap();
    (
        o.status.code().expect("not killed by a signal"),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// Every verb into a closed pipe (ends quietly) and into a full device (one-line error).
#[test]
fn every_verb_into_a_closed_pipe_and_a_full_device() {
    let gen_dir = tempdir();
    generate_plain(gen_dir.path());
    let g = gen_dir.path().to_str().unwrap().to_string();
    let vectors = "0.48 -0.6 0.64\n".repeat(20_000);
    let codes = "0x00001234\n".repeat(20_000);
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["list"], ""),
        (vec!["list", "--json"], ""),
        (vec!["gen", "oct24p", "--lang", "wgsl"], ""),
        (vec!["generate", "--out", &g], ""),
        (vec!["generate", "--out", &g, "--check"], ""),
        (vec!["encode", "oct16"], &vectors),
        (vec!["encode", "oct16", "--format", "binary"], ""),
        (
            vec!["encode", "oct16", "--output-format", "binary"],
            &vectors,
        ),
        (vec!["decode", "oct16"], &codes),
        (vec!["verify", "oct16", "--lang", "wgsl"], ""),
        (vec!["verify", "oct16", "--lang", "wgsl", "--json"], ""),
        (vec!["--help"], ""),
        (vec!["--version"], ""),
        (vec!["gen", "--help"], ""),
    ];
    for (args, stdin) in &cases {
        let (code, err) = run_into(args, stdin.as_bytes(), closed_pipe());
        assert_eq!(code, 0, "{args:?} into a closed pipe: {err}");
        assert!(err.is_empty(), "{args:?} into a closed pipe printed: {err}");
    }
    for (args, stdin) in &cases {
        // `encode --format binary` with no input writes nothing, so nothing can fail.
        if stdin.is_empty() && args.contains(&"encode") {
            continue;
        }
        let (code, err) = run_into(args, stdin.as_bytes(), dev_full());
        assert_eq!(code, 2, "{args:?} into /dev/full: {err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(
            err.starts_with("error: ") && err.contains("No space left on device"),
            "{args:?}: {err}"
        );
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
}

// ---------------------------------------------------------------------------------------
// streaming (item 4)

/// Runs `args` over `input` with stdout discarded; returns (exit status, peak RSS in KiB).
/// The peak is the child's VmHWM, sampled every few milliseconds until it exits (a lower
/// bound of the true peak, which a program holding its whole input keeps for seconds).
/// Neither wait4's ru_maxrss nor /proc before exec will do: both count the parent's
/// memory, which the child shares until it runs `unitpack`.
#[cfg(target_os = "linux")]
fn peak_rss_kib(args: &[&str], input: Vec<u8>) -> (i32, u64) {
    let mut child = unitpack()
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let mut si = child.stdin.take().unwrap();
    let w = std::thread::spawn(move || {
        let _ = si.write_all(&input);
    });
    let status_file = format!("/proc/{}/status", child.id());
    let mut peak = 0;
    let status = loop {
        if let Ok(s) = std::fs::read_to_string(&status_file) {
            let ours = s
                .lines()
                .any(|l| l.split_whitespace().eq(["Name:", "unitpack"]));
            let hwm = s.lines().find_map(|l| l.strip_prefix("VmHWM:"));
            if let (true, Some(v)) = (ours, hwm) {
                let kib: u64 = v.trim().trim_end_matches("kB").trim().parse().unwrap();
                peak = peak.max(kib);
            }
        }
        if let Some(st) = child.try_wait().unwrap() {
            break st;
        }
        std::thread::sleep(std::time::Duration::from_millis(3));
    };
    w.join().unwrap();
    assert!(peak > 0, "no sample of the child's memory");
    (status.code().expect("not killed"), peak)
}

/// 48 MB of input in, peak memory far below it: nothing holds the whole input.
#[cfg(target_os = "linux")]
#[test]
fn encode_and_decode_stream_in_bounded_memory() {
    let vectors = "0.48 -0.6 0.64\n".repeat(3_200_000).into_bytes();
    let (code, kib) = peak_rss_kib(&["encode", "oct16"], vectors);
    assert_eq!(code, 0);
    assert!(
        kib < 32 * 1024,
        "encode peaked at {kib} KiB on 48 MB of input"
    );
    let codes = "0x00001234\n".repeat(4_400_000).into_bytes();
    let (code, kib) = peak_rss_kib(&["decode", "oct16"], codes);
    assert_eq!(code, 0);
    assert!(
        kib < 32 * 1024,
        "decode peaked at {kib} KiB on 48 MB of input"
    );
}

#[test]
fn encode_out_file_is_written_only_when_every_line_is_good() {
    let dir = tempdir();
    let p = dir.path().join("codes.txt");
    std::fs::write(&p, "previous\n").unwrap();
    let err = fails(
        &["encode", "oct16", "--out", p.to_str().unwrap()],
        "0 0 1\n1 0 0\nbad\n",
    );
    assert!(err.contains("line 3"), "{err}");
    assert_eq!(std::fs::read_to_string(&p).unwrap(), "previous\n");
    assert_eq!(
        tree(dir.path()),
        BTreeSet::from([PathBuf::from("codes.txt")])
    );
    let r = run_stdin(
        &["encode", "oct16", "--out", p.to_str().unwrap()],
        "0 0 1\n1 0 0\n",
    );
    assert_eq!((r.code, r.stdout.as_str()), (0, ""), "{r:?}");
    assert_eq!(
        std::fs::read_to_string(&p).unwrap(),
        run_stdin(&["encode", "oct16"], "0 0 1\n1 0 0\n").stdout
    );
    assert_eq!(
        tree(dir.path()),
        BTreeSet::from([PathBuf::from("codes.txt")])
    );
}

fn f32s_le(v: &[[f32; 3]]) -> Vec<u8> {
    v.iter().flatten().flat_map(|x| x.to_le_bytes()).collect()
}

#[test]
fn binary_formats_are_raw_little_endian_records() {
    let vs = [[0.0f32, 0.0, 1.0], [0.48, -0.6, 0.64], [-0.36, 0.48, -0.8]];
    let text: String = vs
        .iter()
        .map(|v| format!("{} {} {}\n", v[0], v[1], v[2]))
        .collect();
    for (spec, width) in [("oct16", 4), ("oct24p", 4), ("snorm16x3", 8)] {
        let hex = run_stdin(&["encode", spec], &text);
        let want: Vec<u8> = hex
            .stdout
            .lines()
            .flat_map(|l| {
                let v = u64::from_str_radix(&l[2..], 16).unwrap();
                v.to_le_bytes()[..width].to_vec()
            })
            .collect();
        // text → binary, binary → binary
        let r = run_stdin(&["encode", spec, "--output-format", "binary"], &text);
        assert_eq!((r.code, &r.out), (0, &want), "{spec}: {r:?}");
        let r = run_bytes(&["encode", spec, "--format", "binary"], &f32s_le(&vs));
        assert_eq!((r.code, &r.out), (0, &want), "{spec}: {r:?}");
        // binary codes → text vectors equals text → text
        let r = run_bytes(&["decode", spec, "--input-format", "binary"], &want);
        assert_eq!(r.code, 0, "{r:?}");
        assert_eq!(r.stdout, run_stdin(&["decode", spec], &hex.stdout).stdout);
        // binary → binary: 12 bytes per vector, the same floats
        let r = run_bytes(&["decode", spec, "--format", "binary"], &want);
        assert_eq!(r.out.len(), 12 * vs.len(), "{spec}");
        let floats: Vec<[f32; 3]> = r
            .out
            .chunks_exact(12)
            .map(|c| [0, 4, 8].map(|i| f32::from_le_bytes(c[i..i + 4].try_into().unwrap())))
            .collect();
        let text_floats: Vec<[f32; 3]> = run_stdin(&["decode", spec], &hex.stdout)
            .stdout
            .lines()
            .map(parse_vec)
            .collect();
        assert_eq!(floats, text_floats, "{spec}");
    }
    // A partial record is an error naming the record; so is a code above the width.
    let r = run_bytes(
        &["encode", "oct16", "--format", "binary"],
        &[0u8; 12 * 2 + 5],
    );
    assert_eq!(r.code, 2, "{r:?}");
    assert!(
        r.stderr.contains("record 3") && r.stderr.contains("12 bytes"),
        "{r:?}"
    );
    // The two whole records before the partial one are written (to stdout).
    assert_eq!(r.out.len(), 2 * 4, "{r:?}");
    // A bad code in the second block of 8192 records: every record before it is
    // written, each the code's decode, and the error names record 8193.
    let mut codes: Vec<u8> = (0..8192u32)
        .flat_map(|i| ((i * 7) & 0xffff).to_le_bytes())
        .collect();
    codes.extend(0x1_0000u32.to_le_bytes());
    codes.extend(5u32.to_le_bytes());
    let r = run_bytes(&["decode", "oct16", "--format", "binary"], &codes);
    assert_eq!(r.code, 2, "{r:?}");
    assert!(r.stderr.contains("record 8193"), "{}", r.stderr);
    assert_eq!(r.out.len(), 8192 * 12, "{}", r.stderr);
    let whole = run_bytes(
        &["decode", "oct16", "--format", "binary"],
        &codes[..8192 * 4],
    );
    assert_eq!(whole.code, 0, "{}", whole.stderr);
    assert_eq!(r.out, whole.out);
    let r = run_bytes(
        &["decode", "oct16", "--format", "binary"],
        &0x1_0000u32.to_le_bytes(),
    );
    assert_eq!(r.code, 2, "{r:?}");
    assert!(
        r.stderr.contains("record 1") && r.stderr.contains("16 bits"),
        "{r:?}"
    );
    // Blank and comment lines of text input produce no record.
    let r = run_stdin(
        &["encode", "oct16", "--output-format", "binary"],
        "# c\n\n0 0 1\n",
    );
    assert_eq!(r.out.len(), 4, "{r:?}");
}

// ---------------------------------------------------------------------------------------
// honest figures (item 9)

#[test]
fn doc_comments_call_the_maximum_a_sample_maximum() {
    let r = ok(&["gen", "oct16", "--lang", "wgsl"]);
    let line = r
        .stdout
        .lines()
        .find(|l| l.contains("Round-trip error"))
        .expect("an error figure");
    for s in [
        "65536 seeded unit vectors",
        "seed 0x756e69747061636b5f766563746f7273",
        "sample max",
        "not a bound",
    ] {
        assert!(line.contains(s), "{line}");
    }
    assert!(!line.contains(", max "), "{line}");
    let readme = std::fs::read_to_string(manifest_dir().join("README.md")).unwrap();
    assert!(readme.contains("sample max"), "README");
    assert!(
        readme.contains("0x756e69747061636b5f766563746f7273"),
        "README names the seed"
    );
}

#[test]
fn gen_writes_c_headers_and_wgsl_import_paths() {
    let r = ok(&["gen", "oct16", "--lang", "c"]);
    assert!(
        r.stdout
            .contains("static inline uint32_t unitpack_oct16_encode(const float v[3]) {"),
        "{r:?}"
    );
    let r = ok(&[
        "gen",
        "oct16",
        "--lang",
        "wgsl",
        "--wgsl-import-path",
        "unitpack::normals",
    ]);
    assert!(
        r.stdout
            .starts_with("#define_import_path unitpack::normals\n"),
        "{r:?}"
    );
    assert!(
        r.stdout.contains(
            "Regenerate: unitpack gen oct16 --lang wgsl --wgsl-import-path unitpack::normals"
        ),
        "{r:?}"
    );
    let err = fails(
        &[
            "gen",
            "oct16",
            "--lang",
            "wgsl",
            "--wgsl-import-path",
            "a b",
        ],
        "",
    );
    assert!(err.contains("invalid WGSL import path"), "{err}");
}

/// `verify --portable` evaluates the model under the deviations the APIs allow. Every
/// packed encoder decides its codes portably (the spherical ones with fixed-point
/// trigonometry), so the report says so and exits 0; its float outputs still move.
#[test]
fn verify_portable_reports_codes_that_allowed_deviations_change() {
    let r = run(&["verify", "--portable", "spherical16", "--json"]);
    assert_eq!(r.code, 0, "{r:?}");
    assert!(
        r.stdout.contains("\"packed_encoders_portable\":true"),
        "{r:?}"
    );
    assert!(
        r.stdout.contains(
            "\"role\":\"DecodeFloat\",\"class\":\"fma\",\"items\":16384,\"changed\":3274"
        ),
        "{r:?}"
    );
    let r = run(&["verify", "--portable", "oct16", "--json"]);
    assert_eq!(r.code, 0, "{r:?}");
    assert!(
        r.stdout.contains("\"packed_encoders_portable\":true"),
        "{r:?}"
    );
    for class in ["div", "sqrt", "fma", "denorm", "zero", "excess"] {
        assert!(r.stdout.contains(&format!("\"{class}\"")), "{class}: {r:?}");
    }
    let r = run(&["verify", "--portable", "snorm12x2"]);
    assert_eq!(r.code, 0, "helpers have no packed encoder: {r:?}");
    assert!(r.stdout.contains("snorm12x2"), "{r:?}");
}
