use unitpack::codecs::Spec;
use unitpack::emit::{DEFAULT_PREFIX, Lang, render};
use unitpack::measure::measured;
use unitpack::verify::*;

/// Outputs compared chunk by chunk report each mismatch with its own item's input,
/// count every one, and a path returning another number of words is an error.
#[test]
fn comparison_finds_mismatches_across_chunks() {
    let e = "oct16".parse::<Spec>().expect("spec").emitted();
    let f = e
        .functions
        .iter()
        .find(|f| f.name == "decode")
        .expect("decode");
    let (params, ret) = func_types(e.module.func(f.name).expect("traced"), "");
    let ret = ret.kind();
    let input: Vec<u32> = (0..100).collect();
    let want = expected(f, &input);
    let mut got = want.clone();
    got[3 * 70 + 1] ^= 1;
    got[3 * 71] ^= 0x8000_0000;
    let mut cmp = Comparison::new(f, (&params, ret), &input, &want);
    for chunk in got.chunks(3 * 64) {
        cmp.take(chunk);
    }
    let found = cmp.finish().expect("every word");
    assert_eq!(found.count, 2);
    let first = &found.first;
    assert_eq!(first[0].input, [70]);
    assert_eq!(first[0].actual, got[210..213]);
    assert_eq!(first[0].expected, want[210..213]);
    assert_eq!(first[1].input, [71]);
    // The sign flip of item 71 moves x by 2|x|, far more than item 70's last bit.
    let x71 = f64::from(f32::from_bits(want[3 * 71]));
    assert!(x71 != 0.0, "the test needs a nonzero x at item 71");
    let largest = found.largest.as_ref().expect("float outputs differ");
    assert_eq!(largest.at.input, [71]);
    assert_eq!(largest.difference, 2.0 * x71.abs());

    // A NaN where the model has a number is the largest difference there is.
    got[3 * 90 + 2] = f32::NAN.to_bits();
    let mut cmp = Comparison::new(f, (&params, ret), &input, &want);
    cmp.take(&got);
    let found = cmp.finish().expect("every word");
    assert_eq!(found.count, 3);
    let largest = found.largest.expect("float outputs differ");
    assert_eq!(
        (largest.at.input.as_slice(), largest.difference),
        (&[90][..], f64::INFINITY)
    );

    let mut short = Comparison::new(f, (&params, ret), &input, &want);
    short.take(&want[..297]);
    assert_eq!(
        short.finish().unwrap_err(),
        "returned 297 words for 300 expected"
    );
    let mut long = Comparison::new(f, (&params, ret), &input, &want);
    long.take(&want);
    long.take(&[0]);
    assert!(long.finish().is_err());
}

/// A function no kernel calls is still compiled: an error in it fails the include's
/// own compiling checks in every shader language (its literals, none here, still pass).
#[test]
fn whole_include_checks_uncalled_functions() {
    let broken = [
        (
            Lang::Wgsl,
            "fn f(c: u32) -> vec3<f32> { return nope(c); }\n",
        ),
        (Lang::Hlsl, "float3 f(uint c) { return nope(c); }\n"),
        (
            Lang::Glsl,
            "precision highp float;\nvec3 f(uint c) { return nope(c); }\n",
        ),
    ];
    for (lang, source) in broken {
        let checks = whole_include(lang, source);
        assert!(!checks.is_empty(), "{lang:?}");
        for (path, r) in checks {
            if path.ends_with("/literals") {
                assert!(r.is_ok(), "{path}: {r:?}");
                continue;
            }
            let e = format!("{:#}", r.expect_err(&path));
            assert!(e.contains("nope"), "{path} names the error: {e}");
        }
    }
    let spec: Spec = "oct16".parse().expect("spec");
    for lang in [Lang::Wgsl, Lang::Glsl, Lang::Hlsl] {
        let include = render(&[measured(&spec, None)], lang, DEFAULT_PREFIX, "test");
        for (path, r) in whole_include(lang, &include) {
            assert!(r.is_ok(), "{path}: {r:?}");
        }
    }
}

/// The includes' checks share glslang runs: each error stays with its own include, holding
/// its own diagnostics only, and every other include passes.
#[test]
fn whole_includes_keep_each_error_with_its_include() {
    let good: Vec<(Lang, String)> = ["oct16", "hemioct24p", "spherical24"]
        .iter()
        .flat_map(|s| {
            let spec: Spec = s.parse().expect("spec");
            [Lang::Wgsl, Lang::Glsl, Lang::Hlsl].map(|l| {
                (
                    l,
                    render(&[measured(&spec, None)], l, DEFAULT_PREFIX, "test"),
                )
            })
        })
        .collect();
    let mut items: Vec<(Lang, &str)> = good.iter().map(|(l, s)| (*l, s.as_str())).collect();
    let glsl_a = "precision highp float;\nvec3 f(uint c) { return nope_a(c); }\n";
    let glsl_b = "precision highp float;\nvec3 f(uint c) { return nope_b(c); }\n";
    let wgsl = "fn f(a: vec3<u32>, m: vec3<bool>) -> vec3<u32> { return select(a, a + 1u, m); }\n";
    for (at, item) in [
        (1, (Lang::Glsl, glsl_a)),
        (5, (Lang::Wgsl, wgsl)),
        (9, (Lang::Glsl, glsl_b)),
    ] {
        items.insert(at, item);
    }
    let checks = whole_includes(&items, None);
    assert_eq!(checks.len(), items.len());
    for (k, ((lang, _), checks)) in items.iter().zip(&checks).enumerate() {
        let paths: Vec<&str> = checks.iter().map(|(p, _)| p.as_str()).collect();
        match lang {
            Lang::Wgsl => assert_eq!(
                paths,
                ["wgsl/naga", "wgsl/naga glsl-out", "wgsl/literals"],
                "{k}"
            ),
            Lang::Glsl => assert_eq!(
                paths,
                ["glsl 330/glslang", "glsl es 300/glslang", "glsl/literals"],
                "{k}"
            ),
            Lang::Hlsl => assert_eq!(paths, ["hlsl/glslang", "hlsl/literals"], "{k}"),
            Lang::C => assert_eq!(paths, ["c/literals"], "{k}"),
        }
        for (path, r) in checks {
            let error = r.as_ref().err().map(|e| format!("{e:#}"));
            match k {
                // The broken items' literals (none) read back.
                _ if path.ends_with("/literals") => assert!(error.is_none(), "{k} {path}"),
                1 | 9 => {
                    let (own, other) = if k == 1 {
                        ("nope_a", "nope_b")
                    } else {
                        ("nope_b", "nope_a")
                    };
                    let e = error.unwrap_or_else(|| panic!("{k} {path} passed"));
                    assert!(e.contains(own) && !e.contains(other), "{k} {path}: {e}");
                }
                5 if path.contains("glsl-out") => {
                    let e = error.unwrap_or_else(|| panic!("{k} {path} passed"));
                    assert!(
                        e.contains("naga-glsl-430") && e.contains("mix"),
                        "{k} {path}: {e}"
                    );
                }
                _ => assert!(error.is_none(), "{k} {path}: {error:?}"),
            }
        }
    }
}

/// A `select` on integer vectors is valid WGSL, but naga writes it as GLSL's `mix(uvec3,
/// uvec3, bvec3)`, which GLSL 4.30 lacks: the include's naga-GLSL check fails on it, naming
/// the version, and passes once the select is lane by lane, as the WGSL back end writes it.
#[test]
fn naga_glsl_out_needs_lane_wise_integer_selects() {
    let vector =
        "fn f(a: vec3<u32>, m: vec3<bool>) -> vec3<u32> { return select(a, a + 1u, m); }\n";
    let lanes = "fn f(a: vec3<u32>, m: vec3<bool>) -> vec3<u32> {\n    let b = a + 1u;\n    \
                 return vec3<u32>(select(a.x, b.x, m.x), select(a.y, b.y, m.y), select(a.z, b.z, m.z));\n}\n";
    let glsl_out = |source: &str| {
        let checks = whole_include(Lang::Wgsl, source);
        assert!(
            checks[0].1.is_ok(),
            "naga accepts the WGSL: {:?}",
            checks[0].1
        );
        let (path, r) = checks
            .into_iter()
            .find(|(p, _)| p.contains("glsl-out"))
            .expect("a naga GLSL check");
        (path, r)
    };
    let (path, r) = glsl_out(vector);
    let e = format!("{:#}", r.expect_err(&path));
    assert!(e.contains("430") && e.contains("mix"), "{path}: {e}");
    let (path, r) = glsl_out(lanes);
    assert!(r.is_ok(), "{path}: {r:?}");
    // The specs whose WGSL had integer vector selects.
    for spec in [
        "float16x3",
        "float32x3",
        "spherical_lut16p",
        "spherical_lut16p:lut=matched",
    ] {
        let spec: Spec = spec.parse().expect("spec");
        let include = render(&[measured(&spec, None)], Lang::Wgsl, DEFAULT_PREFIX, "test");
        let (path, r) = glsl_out(&include);
        assert!(r.is_ok(), "{spec} {path}: {r:?}");
    }
}

/// A chained function's two steps ([`unitpack::codecs::functions::function::Stages`]), which
/// `verify` evaluates apart so that functions beginning with the same step run it once,
/// compute its model's bits; a precise spec's encoders all begin with the same search,
/// and a frame's TBN decoder with its decoder.
#[test]
fn chained_steps_compute_their_functions_bits() {
    use std::sync::Arc;
    use unitpack::codecs::functions::inputs;
    let (mut staged, mut shared) = (0, 0);
    for spec in unitpack::report::doc_tables::codec_specs() {
        let e = spec.emitted();
        for f in &e.functions {
            let Some(s) = &f.stages else { continue };
            staged += 1;
            let input = inputs::generate(&f.inputs, f.in_words);
            let input = &input[..input.len().min(1024 * f.in_words)];
            let items = input.len() / f.in_words;
            let mut mid = vec![0; items * s.mid_words];
            (s.first)(input, &mut mid);
            let mut got = vec![0; items * f.out_words];
            (s.then)(&mid, &mut got);
            assert!(
                got == expected(f, input),
                "{spec} {}: its steps differ from its model",
                f.name
            );
        }
        // A precise spec's encoders begin with one search.
        let first = |name: &str| {
            let f = e.functions.iter().find(|f| f.name == name)?;
            Some(f.stages.as_ref()?.first.clone())
        };
        if let (true, Some(a), Some(b)) = (spec.precise(), first("encode"), first("encode_float")) {
            assert!(Arc::ptr_eq(&a, &b), "{spec}: its encoders search apart");
            shared += 1;
        }
    }
    assert!(shared >= 100, "only {shared} precise specs search once");
    assert!(staged > 100, "only {staged} chained functions");
}
