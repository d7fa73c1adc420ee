//! The emitted includes: every spec × language rendered once and held to its stored copy
//! in `generated/` (the one copy of each emitted file in the repository), rendered twice
//! to the same text, scanned for forbidden builtins and for unprefixed or repeated
//! function names, and renamed by a prefix; plus insta snapshots of what `generated/`
//! does not hold: the shapes of statement the printer writes and the file templates'
//! options, on a small traced module, and the spelling of edge-case literals.
//!
//! `UNITPACK_REFRESH=1` rewrites what these tests compare against instead of failing:
//! `generated/` through `unitpack generate`, and the snapshots through insta (stale
//! snapshot files of this test are removed).

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use unitpack::codecs::Spec;
use unitpack::emit::docs::file_header;
use unitpack::emit::lang::literal::f32_literal;
use unitpack::emit::lang::printer::print;
use unitpack::emit::lang::{FileOptions, Returns};
use unitpack::emit::lang::{FnView, SpecView, Wrapper};
use unitpack::emit::{DEFAULT_PREFIX, Lang, render, struct_defs};
use unitpack::measure::measured;
use unitpack::model::trace::{Module, Shape, Tf, Tu, define, define_fields, trace_module};
use unitpack::model::{Bool, Float, Lane, Uint, V2, V3, V4};

/// Whether this run rewrites the stored copies (`UNITPACK_REFRESH` set, not empty).
fn refreshing() -> bool {
    std::env::var_os("UNITPACK_REFRESH").is_some_and(|v| !v.is_empty())
}

fn manifest_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

// ---------------------------------------------------------------------------------------
// The catalogue, rendered once for every test of this file

/// The command `generate` writes into a spec's header, so that a render here differs from
/// the file in `generated/` by the error statistics alone.
fn command(spec: &Spec, lang: Lang) -> String {
    format!("unitpack gen {spec} --lang {lang}")
}

/// A spec's include without error statistics: what the emitter writes, independent of
/// measurement (the CLI tests' `generate --check` holds the figures to `generated/`).
fn rendered(spec: &Spec, lang: Lang, prefix: &str) -> String {
    render(&[measured(spec, None)], lang, prefix, &command(spec, lang))
}

struct Include {
    spec: Spec,
    lang: Lang,
    text: String,
}

/// Every spec × language with the default prefix, rendered on every core once per process
/// and shared by the tests below: the first render of a spec proves its decoders' bounds,
/// most of the time this file takes.
fn catalogue() -> &'static [Include] {
    static ALL: OnceLock<Vec<Include>> = OnceLock::new();
    ALL.get_or_init(|| {
        let specs = Spec::all();
        assert!(!specs.is_empty());
        unitpack::support::par::map(&specs, |spec| {
            Lang::ALL.map(|lang| Include {
                spec: spec.clone(),
                lang,
                text: rendered(spec, lang, DEFAULT_PREFIX),
            })
        })
        .into_iter()
        .flatten()
        .collect()
    })
}

impl Include {
    /// Where `generate` writes this include, relative to its output folder.
    fn rel(&self) -> PathBuf {
        Path::new(self.lang.name()).join(format!("{}.{}", self.spec.id(), self.lang.ext()))
    }
}

// ---------------------------------------------------------------------------------------
// generated/: the stored copy of every include

/// The doc-comment line that states a function's measured error: the one line a
/// `generate` include has that a render without statistics lacks.
/// The first line of a paragraph on the measured error: the header's on the sample, or
/// a spec's figures.
fn is_statistics_line(line: &str) -> bool {
    line.starts_with("// Round-trip error")
}

/// `text` without its paragraphs on the measured error (their continuation lines too).
fn without_statistics(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut in_statistics = false;
    for line in text.lines() {
        let continues = line.starts_with("//   ");
        in_statistics = is_statistics_line(line) || (in_statistics && continues);
        if !in_statistics {
            out.push_str(line);
            out.push('\n');
        }
    }
    out
}

/// The includes whose copy in `generated/` is missing or differs from the render (error
/// statistics aside), with the first line that differs.
fn stale_in_generated(root: &Path) -> Vec<String> {
    let mut stale = Vec::new();
    for inc in catalogue() {
        let path = root.join(inc.rel());
        let Ok(stored) = std::fs::read_to_string(&path) else {
            stale.push(format!("{}: missing", path.display()));
            continue;
        };
        let stored = without_statistics(&stored);
        if stored != inc.text {
            let (n, (was, now)) = stored
                .lines()
                .chain(std::iter::repeat("<end of file>"))
                .zip(inc.text.lines().chain(std::iter::repeat("<end of file>")))
                .enumerate()
                .find(|(_, (a, b))| a != b)
                .expect("texts that differ differ in a line");
            stale.push(format!(
                "{} line {}:\n  stored:   {was}\n  rendered: {now}",
                path.display(),
                n + 1
            ));
        }
    }
    stale
}

/// Every spec × language has its copy in `generated/`, equal to what the emitter writes
/// now but for the measured error figures: `generated/` is the one stored copy of each
/// include. The CLI tests hold the whole files, figures included, to `generate --check`;
/// this test needs neither the binary nor the measurement (but to refresh), and names the
/// first line that differs.
#[test]
fn generated_holds_every_rendered_include() {
    for inc in catalogue() {
        assert!(
            !inc.text.lines().any(is_statistics_line),
            "{}: a render without statistics has a statistics line",
            inc.rel().display()
        );
    }
    let root = manifest_dir().join("generated");
    let mut stale = stale_in_generated(&root);
    if !stale.is_empty() && refreshing() {
        regenerate(&root);
        stale = stale_in_generated(&root);
    }
    assert!(
        stale.is_empty(),
        "{} of {} includes in generated/ are not what the emitter writes; rewrite them with `UNITPACK_REFRESH=1 cargo test --release` (or `cargo run --release -- generate`):\n{}",
        stale.len(),
        catalogue().len(),
        stale[..stale.len().min(5)].join("\n")
    );
}

/// Rewrites `root` with the tool's own `generate`, its figures cached in the build's
/// temporary folder.
fn regenerate(root: &Path) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_unitpack"))
        .env(
            "UNITPACK_CACHE_DIR",
            Path::new(env!("CARGO_TARGET_TMPDIR")).join("snapshots-figure-cache"),
        )
        .arg("generate")
        .arg("--out")
        .arg(root)
        .output()
        .expect("run unitpack generate");
    assert!(
        out.status.success(),
        "unitpack generate --out {}: {}{}",
        root.display(),
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}

// ---------------------------------------------------------------------------------------
// Properties of every include

#[test]
fn rendering_is_deterministic() {
    for inc in catalogue() {
        assert_eq!(
            rendered(&inc.spec, inc.lang, DEFAULT_PREFIX),
            inc.text,
            "{}",
            inc.rel().display()
        );
    }
    for lang in Lang::ALL {
        let all: Vec<_> = Spec::all().iter().map(|s| measured(s, None)).collect();
        assert_eq!(
            render(&all, lang, DEFAULT_PREFIX, "x"),
            render(&all, lang, DEFAULT_PREFIX, "x"),
            "{lang}: every spec in one include"
        );
    }
}

/// Code lines: everything but comment lines (doc comments may mention "pack", "fma", ...).
fn code_lines(text: &str) -> impl Iterator<Item = &str> {
    text.lines().filter(|l| !l.trim_start().starts_with("//"))
}

/// Every identifier in the code lines, and whether it is followed by `(` (a call).
fn identifiers(text: &str) -> Vec<(String, bool)> {
    let mut out = Vec::new();
    for line in code_lines(text) {
        let b = line.as_bytes();
        let mut i = 0;
        while i < b.len() {
            let c = b[i];
            if c.is_ascii_alphabetic() || c == b'_' {
                let start = i;
                while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_') {
                    i += 1;
                }
                // Skip swizzles and member accesses: `.xy`, `.x`.
                let member = start > 0 && b[start - 1] == b'.';
                let mut j = i;
                while j < b.len() && b[j] == b' ' {
                    j += 1;
                }
                if !member {
                    out.push((line[start..i].to_string(), j < b.len() && b[j] == b'('));
                }
            } else if c.is_ascii_digit() {
                // A number literal, including suffixes like `1.0f`, `8u`, `1e-5`.
                while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'.') {
                    i += 1;
                }
            } else {
                i += 1;
            }
        }
    }
    out
}

/// Builtins the emitted code must never call (`fma` may not appear at all): results would differ between drivers
/// (fused multiply-add, approximate trig and normalize, packing builtins with their own
/// rounding), or NaN handling differs (min, max, clamp, sign).
const FORBIDDEN_ALL: &[&str] = &[
    "fma",
    "sign",
    "atan",
    "atan2",
    "sin",
    "cos",
    "tan",
    "asin",
    "acos",
    "sincos",
    "normalize",
    "length",
    "distance",
    "inverseSqrt",
    "inversesqrt",
    "rsqrt",
    "min",
    "max",
    "clamp",
    "saturate",
    "mad",
    "exp",
    "exp2",
    "log",
    "log2",
    "pow",
    "smoothstep",
    "step",
    "dot",
    "cross",
    "f32tof16",
    "f16tof32",
    // C's spellings; `roundf` rounds halves away from zero.
    "fmaf",
    "fminf",
    "fmaxf",
    "sinf",
    "cosf",
    "tanf",
    "atanf",
    "atan2f",
    "acosf",
    "asinf",
    "roundf",
    "lroundf",
    "hypotf",
    "expf",
    "logf",
    "powf",
    "copysignf",
];

fn forbidden(name: &str) -> bool {
    FORBIDDEN_ALL.contains(&name)
        || name.starts_with("pack")
        || name.starts_with("unpack")
        || name.starts_with("quantizeTo")
}

fn check_no_forbidden_calls(lang: Lang) -> BTreeSet<String> {
    let mut called = BTreeSet::new();
    for inc in catalogue().iter().filter(|i| i.lang == lang) {
        for (name, is_call) in identifiers(&inc.text) {
            assert!(
                !(forbidden(&name) && (is_call || name == "fma")),
                "{} uses the forbidden `{name}`{}",
                inc.rel().display(),
                if is_call { " call" } else { "" }
            );
            if is_call && !name.starts_with(DEFAULT_PREFIX) {
                called.insert(name);
            }
        }
    }
    called
}

#[test]
fn wgsl_calls_no_forbidden_builtins() {
    let called = check_no_forbidden_calls(Lang::Wgsl);
    // The scan sees real calls (it is not vacuous): the emitter's own vocabulary.
    for f in ["sqrt", "select", "abs", "floor", "round"] {
        assert!(
            called.contains(f),
            "expected a `{f}(` call somewhere in WGSL; saw {called:?}"
        );
    }
}

#[test]
fn glsl_calls_no_forbidden_builtins() {
    let called = check_no_forbidden_calls(Lang::Glsl);
    for f in ["sqrt", "abs", "floor"] {
        assert!(
            called.contains(f),
            "expected a `{f}(` call somewhere in GLSL; saw {called:?}"
        );
    }
}

#[test]
fn hlsl_calls_no_forbidden_builtins() {
    let called = check_no_forbidden_calls(Lang::Hlsl);
    for f in ["sqrt", "abs", "floor"] {
        assert!(
            called.contains(f),
            "expected a `{f}(` call somewhere in HLSL; saw {called:?}"
        );
    }
}

#[test]
fn the_token_scan_catches_forbidden_calls() {
    let text = "// pack, fma and normalize in a comment are fine\nfn unitpack_x(v: vec3<f32>) -> u32 {\n    let a = normalize (v);\n    return pack4x8snorm(vec4<f32>(a.xyz, 1.0f));\n}\n";
    let bad: Vec<(String, bool)> = identifiers(text)
        .into_iter()
        .filter(|(n, _)| forbidden(n))
        .collect();
    assert_eq!(
        bad,
        [
            ("normalize".to_string(), true),
            ("pack4x8snorm".to_string(), true)
        ]
    );
    // Swizzles, literals and prefixed names are not calls of builtins.
    let ok = "fn unitpack_pack(v: vec2<f32>) -> f32 {\n    return v.x * 1e-5f + unitpack_min(v.yx);\n}\n";
    assert!(
        identifiers(ok).iter().all(|(n, _)| !forbidden(n)),
        "{:?}",
        identifiers(ok)
    );
}

/// No local or parameter takes a builtin function's name (it would hide the builtin for
/// the rest of its scope in GLSL and WGSL, and reads as a call) or a bare positional name
/// (`a0`): every identifier that is not a call names a type, a field, a swizzle or one of
/// the spec's own values.
#[test]
fn no_value_is_named_after_a_builtin() {
    const BUILTINS: &[&str] = &[
        "abs",
        "atan",
        "atan2",
        "ceil",
        "clamp",
        "cos",
        "cross",
        "distance",
        "dot",
        "exp",
        "floor",
        "fract",
        "inverse",
        "length",
        "lerp",
        "log",
        "max",
        "min",
        "mix",
        "normalize",
        "pow",
        "reflect",
        "round",
        "saturate",
        "select",
        "sign",
        "sin",
        "smoothstep",
        "sqrt",
        "step",
        "trunc",
    ];
    let positional =
        |n: &str| n.len() > 1 && n.starts_with('a') && n[1..].bytes().all(|b| b.is_ascii_digit());
    let mut checked = 0;
    for inc in catalogue() {
        for (name, is_call) in identifiers(&inc.text) {
            if is_call {
                continue;
            }
            assert!(
                !BUILTINS.contains(&name.as_str()) && !positional(&name),
                "{}: a value named `{name}`",
                inc.rel().display()
            );
            checked += 1;
        }
    }
    assert!(checked > 100_000, "{checked} identifiers");
}

#[test]
fn every_function_name_is_prefixed_and_unique() {
    for inc in catalogue() {
        let (spec, lang) = (&inc.spec, inc.lang);
        let mut seen = BTreeSet::new();
        for line in code_lines(&inc.text) {
            let is_def = match lang {
                Lang::Wgsl => line.starts_with("fn "),
                // A signature on one line, or the first line of one broken into lines.
                Lang::Glsl | Lang::Hlsl | Lang::C => {
                    !line.starts_with([' ', '#', ')'])
                        && !line.starts_with("precision")
                        && !line.starts_with("typedef")
                        && (line.ends_with(") {") || line.ends_with('('))
                }
            };
            if !is_def {
                continue;
            }
            let head = line.split('(').next().unwrap();
            let name = head.split_whitespace().last().unwrap();
            assert!(
                name.starts_with(DEFAULT_PREFIX),
                "{}.{lang}: {line:?}",
                spec.id()
            );
            assert!(
                seen.insert(name.to_string()),
                "{}.{lang}: {name} defined twice",
                spec.id()
            );
        }
        // Every emitted function is among the definitions found (helpers add more).
        let emitted = spec.emitted().functions.len();
        assert!(
            emitted >= 1 && seen.len() >= emitted,
            "{}.{lang}: found only {seen:?}",
            spec.id()
        );
    }
}

/// Names and, with their lengths, where long lines break: compared without the layout's
/// whitespace and comment markers.
#[test]
fn prefix_changes_names_only() {
    let unlaid = |s: &str| -> String { s.replace("//", "").split_whitespace().collect() };
    for inc in catalogue() {
        let mine = rendered(&inc.spec, inc.lang, "my_");
        let expected = inc
            .text
            .replace(DEFAULT_PREFIX, "my_")
            .replace("UNITPACK_", "MY_");
        assert_eq!(unlaid(&mine), unlaid(&expected), "{}", inc.rel().display());
    }
}

// ---------------------------------------------------------------------------------------
// Snapshots of what generated/ does not hold

/// Every snapshot this file asserts, by name: `tests/snapshots/snapshots__{name}.snap`.
const SNAPSHOTS: [&str; 5] = [
    "printer_shapes.wgsl",
    "printer_shapes.glsl",
    "printer_shapes.hlsl",
    "printer_shapes.h",
    "literals",
];

/// `insta::assert_snapshot!` under the name `name` (one of [`SNAPSHOTS`]); with
/// `UNITPACK_REFRESH` set, insta writes the new text in place and passes
/// (`INSTA_UPDATE=always`, which insta reads at its first assertion in the process).
fn assert_stored(name: &str, text: &str) {
    assert!(SNAPSHOTS.contains(&name), "{name} is not in SNAPSHOTS");
    static MODE: std::sync::Once = std::sync::Once::new();
    MODE.call_once(|| {
        if refreshing() {
            // SAFETY: every snapshot assertion of this process passes through here
            // first, and the other threads of this test binary read the environment
            // through std alone (std::env::var), which std's environment lock orders
            // with this write; none calls C code that reads it.
            unsafe { std::env::set_var("INSTA_UPDATE", "always") };
        }
    });
    insta::assert_snapshot!(name, text);
}

/// The header names the crate version; keep it out of the snapshots so that a version
/// bump does not rewrite them.
fn without_version(text: &str) -> String {
    let versioned = format!("Generated by unitpack {} ", env!("CARGO_PKG_VERSION"));
    assert!(text.contains(&versioned), "header line missing: {text}");
    text.replacen(&versioned, "Generated by unitpack [version] ", 1)
}

/// `fold`: a helper the encoder calls. Vector compare (`greaterThanEqual` in GLSL) and
/// lane-wise select of literal splats, a swizzle, `1.0 - v` with the literal broadcast.
fn fold(p: V2<Tf>) -> V2<Tf> {
    let side = V2::sel(
        p.ge(V2::splat(Tf::c(0.0))),
        V2::splat(Tf::c(1.0)),
        V2::splat(Tf::c(-1.0)),
    )
    .named("side");
    let a = (V2::splat(Tf::c(1.0)) - p.yx().abs()).named("a");
    a * side
}

/// A small module that takes the printer's paths: named and numbered temporaries, a
/// value named after a reserved word (`target`), a repeated name, vector operations
/// built lane by lane, a call, selects with scalar and vector masks, conversions both
/// ways, bitcasts both ways, shifts and masks, boolean logic, negative literals in
/// operands, literal vectors, constructors from runs of lanes (`vec3(p, z)`,
/// `vec3(d.yz, w)`), four lanes (C's separate struct guard), literals at the ends of
/// the f32 range, and two values returned as a struct. Not a codec: its arithmetic only has to be valid.
fn shapes() -> Module {
    trace_module(|| {
        define("encode", &["v"], |v: V3<Tf>| -> Tu {
            let one = Tf::c(1.0);
            let n = v
                .normalize_or(V3::new(Tf::c(0.0), Tf::c(0.0), one))
                .named("n");
            let l1 = (n.x.abs() + n.y.abs() + n.z.abs()).named("target");
            let p = (V2::new(n.x, n.y) / l1).named("p");
            let folded = Tf::call("fold", &["p"], p, fold);
            let q = V2::sel_all(n.z.le(Tf::c(-0.0)), folded, p).named("q");
            let q = q.clamped(Tf::c(-1.0), one).named("q");
            let c = ((q * Tf::c(32767.0)).round() + Tf::c(32768.0)).named("c");
            let u = c.to_u().named("u");
            let code = (u.x | u.y.shl(16)).named("code");
            let finite = v.x.abs().le(Tf::c(f32::MAX));
            let tiny = l1.lt(Tf::c(f32::from_bits(1)));
            let ok = finite.and(tiny.not()).or(v.y.eq(v.z));
            let sign = v.z.to_bits().shr(31);
            Tu::sel(ok, code, Tu::c(0x8000_8000) | sign)
        });
        define("decode", &["code"], |code: Tu| -> V3<Tf> {
            let x = (code & Tu::c(0xffff)).to_f();
            let y = code.shr(16).to_f();
            let p = (V2::new(x, y) * Tf::c(1.0 / 32767.0) + Tf::c(-32768.0 / 32767.0)).named("p");
            let z = (Tf::c(1.0) - p.x.abs() - p.y.abs()).named("z");
            let d = V3::new(p.x, p.y, z).named("d");
            let seam = p.x.eq(p.y).or(z.lt(Tf::c(0.0)));
            let w = Tf::sel(seam, (Tu::c(0x3f80_0000) | code.shr(31)).as_float(), z);
            V3::new(d.y, d.z, w)
        });
        define("texel", &["code"], |code: Tu| -> V4<Tf> {
            let mask = Tu::c(0xff);
            let bytes = V4::new(
                code & mask,
                code.shr(8) & mask,
                code.shr(16) & mask,
                code.shr(24),
            );
            bytes.to_f() * Tf::c(1.0 / 255.0)
        });
        // Two values returned as a struct's fields, one of them also a lane's source.
        let frame = Shape {
            name: "frame",
            fields: &["n", "t"],
        };
        define_fields(
            "unpack_frame",
            &["code"],
            frame,
            |code: Tu| -> (V3<Tf>, V4<Tf>) {
                let s = (code.shr(31).to_f() * Tf::c(2.0) - Tf::c(1.0)).named("s");
                let a = (code & Tu::c(0xffff)).to_f() * Tf::c(1.0 / 65535.0);
                let n = V3::new(a, Tf::c(0.0), Tf::c(1.0) - a).named("n");
                (n, V4::new(n.z, n.y, -a, s))
            },
        );
    })
}

/// [`shapes`] as a complete include in `lang`, through the language's file template with
/// the options `generate` never uses: the prefix `my_` and, in WGSL, an import path.
fn shapes_include(lang: Lang) -> String {
    let prefix = "my_";
    let backend = lang.backend(prefix);
    let public = |local: &str| format!("{prefix}shapes_{local}");
    let defined = |local: &str| backend.impl_name(&public(local));
    let module = shapes();
    let functions = module
        .funcs
        .iter()
        .map(|f| {
            let p = print(backend.as_ref(), f, &defined);
            // The helper is not public: C gives it no array-based wrapper.
            let wrapper = (f.name != "fold")
                .then(|| {
                    backend.public_abi(
                        &public(&f.name),
                        &p.name,
                        &f.params,
                        &Returns::of(f, &public("")),
                    )
                })
                .flatten()
                .map(|(signature, body)| Wrapper {
                    name: public(&f.name),
                    signature,
                    body,
                });
            FnView {
                doc: vec![format!(
                    "{}: the printer's shapes, `{}`.",
                    public(&f.name),
                    f.name
                )],
                name: p.name,
                params: p.params,
                ret_ty: p.ret_ty,
                body: p.body,
                wrapper,
            }
        })
        .collect();
    let view = SpecView {
        guard: format!("MY_SHAPES_{}", lang.ext()).to_ascii_uppercase(),
        title: "shapes: every statement shape the printer writes".into(),
        doc: vec!["Source: the printer's test.".into()],
        portable: false,
        types: struct_defs(backend.as_ref(), &module.funcs, &defined),
        functions,
    };
    let header = file_header("unitpack test: printer shapes", false, false);
    let options = FileOptions {
        header: &header,
        prefix,
        import_path: (lang == Lang::Wgsl).then_some("my::shapes"),
    };
    without_version(&backend.render(&[view], &options))
}

#[test]
fn printer_shapes() {
    for lang in Lang::ALL {
        let text = shapes_include(lang);
        // The fixture is under the same rules as the catalogue.
        for (name, is_call) in identifiers(&text) {
            assert!(
                !(forbidden(&name) && (is_call || name == "fma")),
                "{lang}: `{name}`"
            );
        }
        assert_eq!(text, shapes_include(lang), "{lang}: deterministic");
        assert_stored(&format!("printer_shapes.{}", lang.ext()), &text);
    }
}

/// Literals at the edges: zeros, the shortest spelling that round-trips through f32 and
/// through f64, integers past 2^24, the largest finite value, the smallest normal and
/// denormals.
#[test]
fn literals() {
    let values = [
        0.0,
        -0.0,
        1.0,
        -1.0,
        0.1,
        1.0 / 3.0,
        32767.0,
        1.0 / 32767.0,
        16_777_216.0,
        16_777_218.0,
        1e10,
        1e-7,
        f32::MAX,
        f32::MIN_POSITIVE,
        f32::from_bits(0x007f_ffff),
        f32::from_bits(1),
    ];
    let mut text = String::new();
    for v in values {
        text.push_str(&format!("{:#010x} {}\n", v.to_bits(), f32_literal(v)));
    }
    assert_stored("literals", &text);
}

/// No snapshot file of this test is left that no assertion reads (with
/// `UNITPACK_REFRESH`, they are removed, with any pending `.snap.new` of this test).
#[test]
fn every_stored_snapshot_is_asserted() {
    let dir = manifest_dir().join("tests").join("snapshots");
    let asserted: BTreeSet<String> = SNAPSHOTS
        .iter()
        .map(|n| format!("snapshots__{n}.snap"))
        .collect();
    let mut orphans = Vec::new();
    for entry in std::fs::read_dir(&dir).expect("tests/snapshots") {
        let name = entry.expect("directory entry").file_name();
        let name = name.to_string_lossy().into_owned();
        if !name.starts_with("snapshots__") {
            continue;
        }
        let unread = name.ends_with(".snap") && !asserted.contains(&name);
        let pending = name.ends_with(".snap.new");
        if unread || (pending && refreshing()) {
            orphans.push(name);
        }
    }
    if refreshing() {
        for name in &orphans {
            std::fs::remove_file(dir.join(name)).expect("remove a stale snapshot");
        }
        return;
    }
    assert!(
        orphans.is_empty(),
        "{} snapshot files that no test asserts: {orphans:?}; remove them with `UNITPACK_REFRESH=1 cargo test --release`",
        orphans.len()
    );
}

// ---------------------------------------------------------------------------------------
// How the stored includes read

/// Every text include in `generated/`, as (path relative to it, text).
fn stored_includes() -> Vec<(String, String)> {
    let root = manifest_dir().join("generated");
    let mut out = Vec::new();
    for lang in Lang::ALL {
        let dir = root.join(lang.name());
        let mut names: Vec<PathBuf> = std::fs::read_dir(&dir)
            .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
            .map(|e| e.expect("directory entry").path())
            .collect();
        names.sort();
        for p in names {
            let text =
                std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            let rel = p.strip_prefix(&root).expect("under generated/");
            out.push((rel.display().to_string(), text));
        }
    }
    assert!(out.len() > 900, "{} includes in generated/", out.len());
    out
}

/// The paragraphs of a file's comments: a comment line starts one unless it continues the
/// previous one (`//` and three spaces, the layout's hanging indent).
fn comment_paragraphs(text: &str) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    let mut open = false;
    for line in text.lines() {
        let Some(c) = line.trim_start().strip_prefix("//") else {
            open = false;
            continue;
        };
        match c.strip_prefix("   ") {
            Some(rest) if open => {
                let last = out.last_mut().expect("an open paragraph");
                last.push(' ');
                last.push_str(rest.trim());
            }
            _ => {
                out.push(c.trim().to_string());
                open = true;
            }
        }
    }
    out
}

/// Lines of at most 100 columns, and no long paragraph said twice in one file.
#[test]
fn stored_includes_keep_to_100_columns_and_say_each_long_paragraph_once() {
    for (rel, text) in stored_includes() {
        for (n, line) in text.lines().enumerate() {
            let columns = line.chars().count();
            assert!(
                columns <= 100,
                "{rel} line {}: {columns} columns\n{line}",
                n + 1
            );
        }
        let mut seen = BTreeSet::new();
        for p in comment_paragraphs(&text) {
            if p.chars().count() > 200 {
                assert!(
                    seen.insert(p.clone()),
                    "{rel}: a paragraph said twice:\n{p}"
                );
            }
        }
    }
}

/// The name a statement line declares, if it is a declaration: `let n =`,
/// `UNITPACK_PRECISE vec2 n =`, `precise float2 n =`, `const float n =`.
fn declared(line: &str) -> Option<&str> {
    let body = line.strip_prefix("    ")?;
    if body.starts_with(' ') || body.starts_with("return") {
        return None;
    }
    let (head, _) = body.split_once(" = ")?;
    let name = head.rsplit(' ').next()?;
    let ident = name.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_')
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    ident.then_some(name)
}

fn is_temporary(name: &str) -> bool {
    name.strip_prefix('t')
        .is_some_and(|d| !d.is_empty() && d.chars().all(|c| c.is_ascii_digit()))
}

/// The statements of function `name` in a WGSL file.
fn wgsl_statements(text: &str, name: &str) -> usize {
    let start = text
        .find(&format!("\nfn {name}("))
        .unwrap_or_else(|| panic!("{name} is not in the file"));
    let body = &text[start..];
    let end = body.find("\n}").expect("the function ends");
    body[..end].matches(';').count()
}

/// Values carry names; what is used once is folded; oct16 reads like its hand-written
/// peers (Bevy's `octahedral_decode` takes six lines).
#[test]
fn stored_includes_name_their_values_and_fold_the_rest() {
    let (mut all, mut anonymous) = (0usize, 0usize);
    for (_, text) in stored_includes() {
        for name in text.lines().filter_map(declared) {
            all += 1;
            anonymous += usize::from(is_temporary(name));
        }
    }
    assert!(all > 10_000, "{all} declarations found");
    assert!(
        anonymous * 3 <= all,
        "{anonymous} of {all} declarations in generated/ are anonymous temporaries (t1, t2, …): more than a third"
    );
    let oct16 = std::fs::read_to_string(manifest_dir().join("generated/wgsl/oct16.wgsl"))
        .expect("generated/wgsl/oct16.wgsl");
    let decode = wgsl_statements(&oct16, "unitpack_oct16_decode_float");
    let encode = wgsl_statements(&oct16, "unitpack_oct16_encode");
    assert!(
        decode <= 8,
        "unitpack_oct16_decode_float has {decode} statements"
    );
    assert!(
        encode <= 25,
        "unitpack_oct16_encode has {encode} statements"
    );
}
