//! The `unitpack` binary end to end: every verb, every bad-input case, exit statuses and
//! the text a user relies on. Runs the built binary with std::process::Command.

use std::collections::BTreeSet;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use unitpack::codecs::{FAMILIES, Spec};
use unitpack::emit::Lang;

struct Run {
    code: i32,
    stdout: String,
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

fn run_in(dir: Option<&Path>, args: &[&str], stdin: &str) -> Run {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_unitpack"));
    cmd.args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    if let Some(d) = dir {
        cmd.current_dir(d);
    }
    let mut child = cmd.spawn().expect("spawn unitpack");
    {
        let mut si = child.stdin.take().expect("stdin");
        // The binary may exit before reading stdin (bad spec): ignore a broken pipe.
        let _ = si.write_all(stdin.as_bytes());
    }
    let out = child.wait_with_output().expect("wait for unitpack");
    Run {
        code: out
            .status
            .code()
            .expect("exit code (not killed by a signal)"),
        stdout: String::from_utf8(out.stdout).expect("stdout is UTF-8"),
        stderr: String::from_utf8(out.stderr).expect("stderr is UTF-8"),
    }
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

/// The files `generate` must write: `<lang>/<id>.<lang>` for every spec and language.
fn expected_files() -> BTreeSet<PathBuf> {
    let mut s = BTreeSet::new();
    for lang in Lang::ALL {
        for spec in Spec::all() {
            s.insert(PathBuf::from(lang.name()).join(format!("{}.{}", spec.id(), lang.ext())));
        }
    }
    s
}

fn generate_into(dir: &Path) -> Run {
    let r = ok(&["generate", "--out", dir.to_str().expect("UTF-8 path")]);
    assert!(
        r.stdout
            .contains(&format!("wrote {} files", expected_files().len())),
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
    for verb in ["list", "gen", "generate", "encode", "decode", "verify"] {
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
        ("decode", "Decode hex codes read from stdin"),
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
    for col in ["codec", "domain", "precise", "source"] {
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
fn gen_out_into_a_missing_directory_fails_and_writes_nothing() {
    let err = fails(
        &[
            "gen",
            "oct16",
            "--lang",
            "wgsl",
            "--out",
            "/nonexistent-dir/x.wgsl",
        ],
        "",
    );
    assert!(err.contains("cannot write"), "{err}");
    assert!(
        err.contains("/nonexistent-dir/x.wgsl"),
        "the message should name the file: {err}"
    );
    assert!(!Path::new("/nonexistent-dir/x.wgsl").exists());

    let dir = tempdir();
    let path = dir.path().join("missing").join("x.wgsl");
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
    assert!(err.contains("cannot write"), "{err}");
    assert!(tree(dir.path()).is_empty(), "nothing may be left behind");
}

#[test]
fn gen_out_onto_a_directory_fails_and_leaves_it_alone() {
    let dir = tempdir();
    let err = fails(
        &[
            "gen",
            "oct16",
            "--lang",
            "wgsl",
            "--out",
            dir.path().to_str().unwrap(),
        ],
        "",
    );
    assert!(err.contains("cannot write"), "{err}");
    assert!(dir.path().is_dir());
    assert!(
        tree(dir.path()).is_empty(),
        "no temporary file may be left behind"
    );
}

#[test]
fn gen_with_one_bad_spec_prints_nothing() {
    let err = fails(&["gen", "oct16", "octt16", "--lang", "wgsl"], "");
    assert!(err.contains("unknown codec 'octt16'"), "{err}");
}

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
    // snorm3 is spelled by component size (snorm8x3...), so its family name is not a spec.
    for c in FAMILIES
        .iter()
        .map(|f| f.info())
        .filter(|c| c.name != "snorm3")
    {
        assert!(
            valid.contains(c.name),
            "valid codecs lack {}: {err}",
            c.name
        );
    }
    assert!(
        !valid.contains("snorm3"),
        "snorm3 alone does not parse: {err}"
    );
    for id in ["snorm8x3", "snorm10x3", "snorm16x3"] {
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
    // The family name and a precise form are not specs.
    let err = bad_spec("snorm3");
    assert!(err.contains("snorm8x3"), "{err}");
    bad_spec("snorm8x3p");
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
    let err = bad_spec("hemioct24:layout=rgb8");
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
        let digits = if spec.bits() > 32 { 12 } else { 8 };
        assert!(
            enc.stdout.lines().all(|l| is_hex_code(l, digits)),
            "{name}: {enc:?}"
        );
        let dec = run_stdin(&["decode", &arg], &enc.stdout);
        assert_eq!(dec.code, 0, "{name}: {dec:?}");
        let out: Vec<[f32; 3]> = dec.stdout.lines().map(parse_vec).collect();
        assert_eq!(out.len(), input.len(), "{name}: {dec:?}");
        let tol = if spec.bits() <= 16 { 3.0 } else { 1.0 };
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

#[test]
fn encode_ignores_blank_lines_and_counts_them() {
    let r = run_stdin(&["encode", "oct16"], "\n  0 0 1  \n\n1\t0\t0");
    assert_eq!(r.code, 0, "{r:?}");
    assert_eq!(r.stdout.lines().count(), 2, "{r:?}");
    let err = fails(&["encode", "oct16"], "0 0 1\n\n1 2\n");
    assert!(err.contains("line 3"), "blank lines still count: {err}");
    // Empty input: no output, success.
    let r = run_stdin(&["encode", "oct16"], "");
    assert_eq!((r.code, r.stdout.as_str()), (0, ""), "{r:?}");
}

#[test]
fn encode_malformed_line_fails_with_no_partial_output() {
    let err = fails(&["encode", "oct16"], "0 0 1\n1 2\n0 1 0\n");
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
fn decode_malformed_line_fails_with_no_partial_output() {
    let err = fails(&["decode", "oct16"], "zz\n");
    assert!(err.contains("line 1"), "{err}");
    let err = fails(&["decode", "oct16"], "0x00000000\n0x7f\n0xg\n");
    assert!(err.contains("line 3"), "{err}");
    // A single-word code holds at most 8 hex digits.
    let err = fails(&["decode", "oct16"], "0x100000000\n");
    assert!(err.contains("line 1") && err.contains("8"), "{err}");
    let err = fails(&["decode", "snorm16x3"], "0x10000000000000000\n");
    assert!(err.contains("line 1"), "{err}");
}

#[test]
fn decode_accepts_codes_with_or_without_prefix() {
    let r = run_stdin(&["decode", "oct16"], "0x0000007f\n7f\n0X7F\n  0x7f  \n");
    assert_eq!(r.code, 0, "{r:?}");
    let lines: Vec<&str> = r.stdout.lines().collect();
    assert_eq!(lines.len(), 4, "{r:?}");
    for l in lines {
        assert_eq!(parse_vec(l), [1.0, 0.0, 0.0], "{r:?}");
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

#[test]
fn packing_helper_has_no_encode_or_decode() {
    for verb in ["encode", "decode"] {
        let err = fails(&[verb, "snorm12x2"], "0 0 1\n");
        assert!(
            err.contains("snorm12x2 is a packing helper, not a codec"),
            "{verb}: {err}"
        );
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
    // Every file starts with the generated-file header.
    for rel in expected_files() {
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

#[test]
fn generate_check_names_an_extra_file() {
    let dir = tempdir();
    generate_into(dir.path());
    std::fs::write(dir.path().join("wgsl/oct17.wgsl"), "fn x() {}\n").unwrap();
    let r = check(dir.path());
    assert_eq!(r.code, 1, "{r:?}");
    assert!(
        r.stdout
            .lines()
            .any(|l| l.starts_with("extra:") && l.ends_with("wgsl/oct17.wgsl")),
        "{r:?}"
    );
    assert!(
        !r.stdout.contains("changed:") && !r.stdout.contains("missing:"),
        "{r:?}"
    );
    // `generate` removes what `--check` called extra, and leaves other files alone.
    std::fs::write(dir.path().join("wgsl/notes.txt"), "mine\n").unwrap();
    generate_into(dir.path());
    assert!(!dir.path().join("wgsl/oct17.wgsl").exists());
    assert!(dir.path().join("wgsl/notes.txt").exists());
    assert_eq!(check(dir.path()).code, 0);
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
    let (a, b) = (tempdir(), tempdir());
    generate_into(a.path());
    generate_into(b.path());
    let files = tree(a.path());
    assert_eq!(files, tree(b.path()));
    for rel in &files {
        let (x, y) = (
            std::fs::read(a.path().join(rel)).unwrap(),
            std::fs::read(b.path().join(rel)).unwrap(),
        );
        assert!(x == y, "{} differs between two runs", rel.display());
    }
    // Regenerating over an existing tree leaves it identical.
    generate_into(a.path());
    for rel in &files {
        assert_eq!(
            std::fs::read(a.path().join(rel)).unwrap(),
            std::fs::read(b.path().join(rel)).unwrap()
        );
    }
    assert_eq!(tree(a.path()), files);
}

#[test]
fn committed_generated_directory_is_up_to_date() {
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

// ---------------------------------------------------------------------------------------
// verify (GPU: Mesa lavapipe)

#[test]
fn verify_oct16_wgsl_on_lavapipe() {
    let r = run(&["verify", "oct16", "--lang", "wgsl"]);
    assert_eq!(r.code, 0, "{r:?}");
    assert!(r.stdout.lines().any(|l| l.starts_with("adapter:")), "{r:?}");
    let rows: Vec<&str> = r
        .stdout
        .lines()
        .filter(|l| l.starts_with("oct16 "))
        .collect();
    assert!(!rows.is_empty(), "{r:?}");
    assert!(rows.iter().all(|l| l.contains("wgsl/naga")), "{r:?}");
    for f in ["encode", "decode"] {
        assert!(
            rows.iter().any(|l| l.split_whitespace().nth(1) == Some(f)),
            "no row for {f}: {r:?}"
        );
    }
    assert!(r.stdout.contains(" 0 failed"), "{r:?}");
}

#[test]
fn verify_rejects_bad_specs() {
    let err = fails(&["verify", "octt16", "--lang", "wgsl"], "");
    assert!(err.contains("unknown codec 'octt16'"), "{err}");
}

/// Every committed include names the command that wrote it, and running that command
/// reproduces the file byte for byte.
#[test]
fn every_generated_file_regenerates_from_its_header() {
    let root = manifest_dir().join("generated");
    let mut checked = 0;
    for lang in Lang::ALL {
        let dir = root.join(lang.name());
        for entry in std::fs::read_dir(&dir).expect("generated language folder") {
            let path = entry.unwrap().path();
            let text = std::fs::read_to_string(&path).unwrap();
            let cmd = text
                .lines()
                .find_map(|l| l.split("Regenerate: ").nth(1))
                .unwrap_or_else(|| panic!("{} has no Regenerate line", path.display()));
            let args: Vec<&str> = cmd.split_whitespace().collect();
            assert_eq!(args[0], "unitpack", "{cmd}");
            let spec = args[2];
            let stem = path.file_stem().unwrap().to_str().unwrap();
            assert_eq!(
                spec.parse::<Spec>().unwrap().id(),
                stem,
                "{}: the header's spec is not the file's",
                path.display()
            );
            // The file name (the id) is a spec too.
            assert_eq!(stem.parse::<Spec>(), spec.parse::<Spec>());
            let r = ok(&args[1..]);
            assert!(
                r.stdout == text,
                "{cmd} does not reproduce {}",
                path.display()
            );
            checked += 1;
        }
    }
    assert_eq!(checked, Spec::all().len() * Lang::ALL.len());
}
