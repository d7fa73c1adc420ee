//! `--help`, `--version` and usage errors: what every verb says about itself.

use crate::common::*;

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
        (
            "encode",
            "Encode vectors (or tangent frames) read from stdin",
        ),
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

#[test]
fn every_spec_argument_documents_the_grammar() {
    for verb in ["gen", "encode", "decode", "transcode", "verify"] {
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
    for verb in ["encode", "decode", "transcode"] {
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
