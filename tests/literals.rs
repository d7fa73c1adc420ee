//! Every float literal the emitter writes reads back as the model's f32 on every compiler
//! (`unitpack::verify::literals`): the includes in `generated/`, the include that Tint
//! rejected before the printer kept its literals within FLT_MAX, the reading rules on
//! single literals, and the printer's literal for a seeded sample of f32 values; integer
//! masks written in hex.

use std::collections::HashSet;
use std::path::PathBuf;
use unitpack::codecs::Spec;
use unitpack::emit::Lang;
use unitpack::emit::lang::literal::f32_literal;
use unitpack::verify::literals::{Literal, check, literals, model_literals, read};

fn manifest_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Every include in `generated/` (`lut/` holds binary tables and their images, no source),
/// each literal also one the spec's traced functions use.
#[test]
fn every_generated_literal_reads_back_as_the_model() {
    let root = manifest_dir().join("generated");
    let mut models: std::collections::HashMap<String, HashSet<u32>> = Default::default();
    let (mut files, mut read_total) = (0, 0);
    let mut failures = Vec::new();
    for (dir, lang) in [
        ("wgsl", Lang::Wgsl),
        ("wesl", Lang::Wgsl),
        ("glsl", Lang::Glsl),
        ("hlsl", Lang::Hlsl),
        ("c", Lang::C),
    ] {
        let mut paths: Vec<_> = std::fs::read_dir(root.join(dir))
            .expect("a generated language folder")
            .map(|e| e.expect("directory entry").path())
            .collect();
        paths.sort();
        for path in paths {
            let id = path.file_stem().expect("a file name").to_string_lossy();
            let model = models.entry(id.to_string()).or_insert_with(|| {
                let spec: Spec = id.parse().unwrap_or_else(|e| panic!("{id}: {e}"));
                model_literals(&spec)
            });
            let text = std::fs::read_to_string(&path).expect("a text include");
            match check(lang, &text, Some(model)) {
                Ok(n) => read_total += n,
                Err(e) => failures.push(format!("{}: {e:#}", path.display())),
            }
            files += 1;
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    println!("{read_total} literals read in {files} files");
    // `generate` writes every spec of the catalogue in each of the five folders.
    assert_eq!(
        files,
        5 * Spec::all().len(),
        "every spec in every language folder"
    );
    assert!(
        read_total > 270_000,
        "{read_total} literals read in {files} files"
    );
}

/// The oct16 include as the printer wrote it with Rust's shortest round trip of f32::MAX,
/// which Tint rejected ("value cannot be represented as 'f32'"): the check fails on both
/// occurrences and names the literal, its line and what it reads back as.
#[test]
fn the_include_tint_rejected_fails() {
    let path = manifest_dir().join("tests/data/oct16_flt_max_out_of_range.wgsl");
    let text = std::fs::read_to_string(path).expect("the stored include");
    let e = format!(
        "{:#}",
        check(Lang::Wgsl, &text, None).expect_err("out of range")
    );
    assert!(e.contains("`3.4028235e38f`"), "{e}");
    assert!(e.contains("line 59, column 18"), "{e}");
    assert!(
        e.contains("0x7f7fffff") && e.contains("shader-creation error"),
        "{e}"
    );
    assert!(e.starts_with("2 of "), "{e}");
    let fixed = text.replace("3.4028235e38f", "3.4028234e38f");
    assert!(check(Lang::Wgsl, &fixed, None).is_ok());
}

/// The rules on single literals.
#[test]
fn literals_read_by_each_languages_rule() {
    let one = |lang, text: &str| check(lang, text, None).map_err(|e| format!("{e:#}"));
    // Above FLT_MAX by its exact digits, however little: each language's consequence.
    let e = one(Lang::Wgsl, "let m = 3.4028235e38f;").unwrap_err();
    assert!(
        e.contains("shader-creation error") && e.contains("line 1, column 9"),
        "{e}"
    );
    let e = one(Lang::Glsl, "float m = 3.4028235e38;").unwrap_err();
    assert!(e.contains("infinity"), "{e}");
    for text in [
        "340282346638528859811704183484516925441.0",
        "3.40282346638528859811704183484516925440001e38",
        "0.0000340282347e43",
        "1e39",
        "0x1.fffffffp127",
        "0x1p128",
    ] {
        assert!(read(Lang::Hlsl, text).is_err(), "{text}");
    }
    for (text, bits) in [
        ("3.4028234e38f", 0x7f7f_ffff),
        ("340282346638528859811704183484516925440.0f", 0x7f7f_ffff),
        ("0.34028234663852885981170418348451692544e39f", 0x7f7f_ffff),
        ("0x1.fffffep127f", 0x7f7f_ffff),
        ("1.1754944e-38f", 0x0080_0000),
        ("1.0f", 0x3f80_0000),
        (".5f", 0x3f00_0000),
        ("1e-5f", 0x3727_c5ac),
        ("1.5e+3f", 0x44bb_8000),
        ("1f", 0x3f80_0000),
        ("0x1p-3f", 0x3e00_0000),
        ("0x.8p1", 0x3f80_0000),
        ("0.0f", 0),
    ] {
        let v = read(Lang::Wgsl, text).unwrap_or_else(|e| panic!("{text}: {e:#}"));
        assert_eq!(v.to_bits(), bits, "{text}");
    }
    assert_eq!(one(Lang::Wgsl, "let m = 3.4028234e38f;"), Ok(1));
    // A nonzero literal that a flushing implementation reads as zero.
    for text in ["1e-45f", "1.1754942e-38f", "1e-50f", "0x1p-149f"] {
        let e = one(Lang::Wgsl, text).unwrap_err();
        assert!(
            e.contains("denormal") || e.contains("not zero"),
            "{text}: {e}"
        );
    }
    // A type other than f32.
    for (lang, text) in [
        (Lang::Wgsl, "1.0h"),
        (Lang::Glsl, "1.0lf"),
        (Lang::Hlsl, "1.0L"),
        (Lang::C, "1.0"),
        (Lang::C, "1.0L"),
    ] {
        let e = one(lang, text).unwrap_err();
        assert!(e.contains("not the model's f32"), "{lang:?} {text}: {e}");
    }
    // Double rounding: 4.37236101e-35 lies just above the midpoint between 0x0668797e and
    // 0x0668797f, closer to it than half an f64 ulp: read as f32 it is 0x0668797f; as f64 it
    // is the midpoint, which narrowing ties to the even 0x0668797e.
    assert_eq!(
        "4.37236101e-35".parse::<f32>().unwrap().to_bits(),
        0x0668_797f
    );
    assert_eq!(
        ("4.37236101e-35".parse::<f64>().unwrap() as f32).to_bits(),
        0x0668_797e
    );
    for lang in [Lang::Wgsl, Lang::Glsl, Lang::Hlsl] {
        let e = one(lang, "x = 4.37236101e-35;").unwrap_err();
        assert!(e.contains("double rounding"), "{e}");
    }
    // No float literal: integers, identifiers with digits, comments.
    for (lang, text) in [
        (Lang::Wgsl, "let b = 0x7f800000u + 12u + 3;"),
        (Lang::Wgsl, "fn f(v: vec2<f32>, t12: f32) -> vec3<f16> {}"),
        (
            Lang::Wgsl,
            "// 3.4028235e38 /* 1.5 */\n/* 1e-45 /* nested 2.5 */ 0.5 */ let x = 1u;",
        ),
        (
            Lang::Glsl,
            "#define UNITPACK_PRECISE\n/* 1.0 */ uint x = 0xffu; // 0.5f",
        ),
        (Lang::C, "static const uint32_t k = 0x1fu; /* 1e-45f */"),
    ] {
        assert!(literals(lang, text).is_empty(), "{text}");
    }
    // Only WGSL nests comments: in GLSL the first `*/` ends one.
    assert_eq!(
        literals(Lang::Glsl, "/* a /* b */ 2.5 */"),
        [Literal {
            line: 1,
            column: 14,
            text: "2.5"
        }]
    );
    // Lines and columns count characters, comments included.
    let found = literals(Lang::Wgsl, "// é 1.0\nlet x = vec2<f32>(0.5f, 1e-5) * .25;");
    let at: Vec<_> = found.iter().map(|l| (l.line, l.column, l.text)).collect();
    assert_eq!(at, [(2, 19, "0.5f"), (2, 25, "1e-5"), (2, 33, ".25")]);
    // A literal the model does not use.
    let model = HashSet::from([0x3f80_0000, 0xbf80_0000]);
    assert_eq!(check(Lang::Wgsl, "1.0f + 1f", Some(&model)).ok(), Some(2));
    let e = format!("{:#}", check(Lang::Wgsl, "0.5f", Some(&model)).unwrap_err());
    assert!(
        e.contains("0x3f000000") && e.contains("no literal of the model"),
        "{e}"
    );
}

/// The model's literals of a spec, each with its negation: oct16's fold compares with
/// FLT_MAX and scales by 0.25.
#[test]
fn model_literals_hold_the_traced_constants() {
    let model = model_literals(&"oct16".parse().expect("spec"));
    for v in [f32::MAX, -f32::MAX, 0.25, -0.25, 1.0, -1.0] {
        assert!(model.contains(&v.to_bits()), "{v}");
    }
}

/// The printer's literal for every sampled f32 (seeded; every finite value is possible,
/// denormals included, with ±FLT_MAX, the smallest normal and the largest denormal) reads
/// back as that value in every language. The printer is asked for any value a model
/// traces, so denormals are printed too: they read back exactly, and the check rejects
/// them as not surviving a flushing implementation.
#[test]
fn printed_literals_read_back_exactly() {
    let mut x: u64 = 0x756e_6974_7061_636b;
    let sampled = (0..1_000_000).map(|_| {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        f32::from_bits((x >> 32) as u32)
    });
    let edges = [
        f32::MAX,
        -f32::MAX,
        f32::MIN_POSITIVE,
        -f32::MIN_POSITIVE,
        f32::from_bits(0x007f_ffff),
        f32::from_bits(1),
        0.0,
        -0.0,
    ];
    let suffixed = [
        (Lang::Wgsl, "f"),
        (Lang::Glsl, ""),
        (Lang::Hlsl, ""),
        (Lang::C, "f"),
    ];
    let (mut read_n, mut denormals) = (0, 0);
    for v in edges.into_iter().chain(sampled).filter(|v| v.is_finite()) {
        let printed = f32_literal(v);
        // A negative value is printed as the negation of a literal.
        let magnitude = printed.strip_prefix('-').unwrap_or(&printed);
        for (lang, suffix) in suffixed {
            let text = format!("{magnitude}{suffix}");
            let back = read(lang, &text).unwrap_or_else(|e| panic!("{v:e}: {e:#}"));
            assert_eq!(back.to_bits(), v.abs().to_bits(), "{text}");
            let checked = check(lang, &text, None);
            if v.is_subnormal() {
                assert!(checked.is_err(), "{text}");
            } else {
                assert_eq!(checked.ok(), Some(1), "{text}");
            }
        }
        read_n += 1;
        denormals += usize::from(v.is_subnormal());
    }
    assert!(read_n > 990_000 && denormals > 1000, "{read_n} {denormals}");
    assert_eq!(f32_literal(f32::MAX), "3.4028234e38");
    assert_eq!(f32_literal(-f32::MAX), "-3.4028234e38");
}

/// Bit patterns read in hex, counts and offsets in decimal: the printer's rule on chosen
/// values, and no include in `generated/` spelling a mask in decimal.
#[test]
fn masks_are_written_in_hex() {
    use unitpack::emit::lang::literal::u32_literal;
    for (v, text) in [
        (0x7f80_0000, "0x7f800000u"),
        (0x7f80_0001, "0x7f800001u"),
        (0x8000_0000, "0x80000000u"),
        (0xffff, "0xffffu"),
        (0xff00, "0xff00u"),
        (0xff_ffff, "0xffffffu"),
        (0x3ff7ff, "0x3ff7ffu"),
        (0x100, "0x100u"),
        (255, "255u"),
        (127, "127u"),
        (0, "0u"),
        (281, "281u"),
        (1000, "1000u"),
        (32586, "32586u"),
    ] {
        assert_eq!(u32_literal(v), text, "{v}");
    }
    let root = manifest_dir().join("generated");
    let mut files = 0;
    for dir in ["wgsl", "wesl", "glsl", "hlsl", "c"] {
        for entry in std::fs::read_dir(root.join(dir)).unwrap() {
            let path = entry.unwrap().path();
            let text = std::fs::read_to_string(&path).unwrap();
            for decimal in [
                "2139095040u",
                "2147483648u",
                "16777215u",
                "65535u",
                "65280u",
            ] {
                assert!(!text.contains(decimal), "{}: {decimal}", path.display());
            }
            files += 1;
        }
    }
    assert!(files > 1000, "{files} files");
}
