//! The whole catalogue on lavapipe: every emitted function on every path (WGSL via naga,
//! GLSL via naga and glslang, HLSL via glslang with -Od and default optimization and via
//! Slang's four routes, GLSL on the OpenGL driver, C and C++), and the model's own four-lane
//! evaluation that the CPU batches run, each compared as raw bits with the f32 model on
//! every code up to 24 bits and 2^20 seeded vectors plus the edge cases, plus the static
//! checks; then the same SPIR-V again on SwiftShader and the includes in headless Chromium
//! (WGSL through WebGPU's Tint, GLSL ES through WebGL 2's ANGLE), each on a seeded sample
//! of 2^16 items per function plus the edge cases. With no Vulkan adapter or no Chromium
//! this fails and names the package to install.

use std::collections::HashMap;
use unitpack::Generator;
use unitpack::codecs::Spec;
use unitpack::emit::Lang;

#[test]
fn every_function_is_bit_exact_on_every_path() {
    let report = unitpack::verify::run(&Spec::all(), &Lang::ALL, false)
        .unwrap_or_else(|e| panic!("cannot verify: {e:#}"));
    let table = report.table();
    println!("{table}");
    assert!(
        report.rows.len() > 1000,
        "every spec × function × path is checked"
    );
    let functions: usize = Spec::all()
        .iter()
        .map(|s| s.emitted().functions.len())
        .sum();
    for (path, what) in [
        ("cpu/4 lanes", "four SSE2 lanes"),
        ("cpu/8 lanes", "eight AVX2 lanes"),
    ] {
        let lanes = report.rows.iter().filter(|r| r.path == path);
        assert_eq!(
            lanes.filter(|r| r.tested >= 1 << 15).count(),
            functions,
            "every function on {what}"
        );
    }
    assert!(
        report.all_passed(),
        "mismatches or compile errors:\n{table}"
    );
    every_include_is_checked_whole(&report);
    shared_rows_repeat_identical_code(&report);
    sampled_paths_run_their_sample(&report);
    slang_routes_hold_what_the_readme_says(&report);
    browser_and_swiftshader_paths_hold_what_they_promise(&report);
    hostile_inputs_encode_as_documented_on_the_new_paths(&report);
}

/// Zero, NaN and infinite vectors and frames are among the items every sampled path runs
/// (the sample's first half is the inputs' head, where the edge items stand), so on the
/// browser and SwiftShader paths every packed code of a hostile input is the model's (the
/// rows pass), and no float output became NaN or changed an infinity where the model's
/// did not: no row's largest difference is infinite.
fn hostile_inputs_encode_as_documented_on_the_new_paths(report: &unitpack::verify::Report) {
    use unitpack::codecs::functions::inputs::{edge_frames, edge_vectors};
    use unitpack::verify::GL_ITEMS;
    let edges = edge_vectors();
    assert!(edges.len() <= GL_ITEMS / 2, "{} edge vectors", edges.len());
    for hostile in [[0.0, 0.0, 0.0], [f32::NAN; 3], [f32::INFINITY, 0.0, 0.0]] {
        let bits = hostile.map(f32::to_bits);
        assert!(
            edges.iter().any(|v| v.map(f32::to_bits) == bits),
            "{hostile:?} is an edge vector"
        );
    }
    let frames = edge_frames();
    assert!(frames.len() <= GL_ITEMS / 2, "{} edge frames", frames.len());
    for (what, hostile) in [
        (
            "a normal with a NaN",
            (|x: f32| x.is_nan()) as fn(f32) -> bool,
        ),
        ("an infinite normal", |x: f32| x.is_infinite()),
    ] {
        assert!(
            frames.iter().any(|f| f[..3].iter().any(|&x| hostile(x))),
            "{what} is an edge frame"
        );
    }
    assert!(
        frames.iter().any(|f| f[..3] == [0.0; 3]),
        "a zero normal is an edge frame"
    );
    let new = |p: &str| p == "wgsl/tint" || p == "glsl/angle" || p.ends_with(" on swiftshader");
    let rows: Vec<_> = report.rows.iter().filter(|r| new(&r.path)).collect();
    assert!(rows.len() > 5000, "{} rows on the new paths", rows.len());
    for r in rows {
        if let Some(l) = &r.largest {
            assert!(
                l.difference.is_finite(),
                "{} {} on {}: {:?}",
                r.spec,
                r.function,
                r.path,
                l.at
            );
        }
    }
}

/// The browser paths (Tint through WebGPU, ANGLE through WebGL 2) and every SPIR-V route
/// again on SwiftShader run every function a spec owns on their sample; packed codes,
/// indices and what a code decodes to are the model's bits there, and float forms (float
/// in, float out), which SwiftShader's flushing of denormals moves, are measured: some of
/// them do move, and only on denormal or zero items (`tests/portability.rs` holds the
/// model's `denorm` class to SwiftShader's outputs). The lean tier promises its codes only
/// where denormals are kept, so its encoders are measured there too.
fn browser_and_swiftshader_paths_hold_what_they_promise(report: &unitpack::verify::Report) {
    use unitpack::model::Kind;
    use unitpack::verify::{GL_ITEMS, Path, func_types};
    // Each path, and whether its compiler also regroups products (Slang's optimizing
    // routes), which moves float outputs beyond the denormals.
    let mut paths: Vec<(String, bool)> = vec![
        (Path::WgslTint.to_string(), false),
        (Path::GlslAngle.to_string(), false),
    ];
    paths.extend(
        Path::ALL
            .into_iter()
            .filter(|p| p.on_vulkan())
            .map(|p| (format!("{p} on swiftshader"), p.regroups())),
    );
    assert_eq!(
        paths.len(),
        2 + 9,
        "two browser paths and nine SPIR-V routes"
    );
    let every = tested_on_c(report);
    let owned = report
        .rows
        .iter()
        .filter(|r| r.path == "wgsl/naga" && r.function != "(whole include)" && r.same_as.is_none())
        .count();
    assert!(owned > 500, "{owned} functions run on their own");
    let emitted: Vec<(String, _)> = Spec::all()
        .into_iter()
        .map(|s| (s.to_string(), s.emitted()))
        .collect();
    // Whether each function is a float form, whether its spec is the lean tier's, and
    // whether it returns floats (measured where a path regroups products).
    let may_move: HashMap<(&str, &str), (bool, bool, bool)> = emitted
        .iter()
        .flat_map(|(id, e)| {
            let spec: Spec = id.parse().expect("a listed spec");
            let lean = unitpack::codecs::core::ieee::asked(&spec);
            e.functions.iter().map(move |f| {
                let (params, ret) = func_types(e.module.func(f.name).expect("traced"), "");
                let float_form =
                    ret.kind() == Kind::F32 && params.iter().any(|t| t.kind == Kind::F32);
                (
                    (id.as_str(), f.name),
                    (float_form, lean, ret.kind() == Kind::F32),
                )
            })
        })
        .collect();
    let mut moved = 0;
    for (path, regroups) in &paths {
        let rows: Vec<_> = report
            .rows
            .iter()
            .filter(|r| &r.path == path && r.function != "(whole include)" && r.same_as.is_none())
            .collect();
        assert_eq!(rows.len(), owned, "{path} runs every function a spec owns");
        for r in rows {
            let what = format!("{} {} on {path}", r.spec, r.function);
            assert!(r.error.is_none(), "{what}: {:?}", r.error);
            let all = every[&(r.spec.as_str(), r.function.as_str())];
            assert_eq!(r.tested, all.min(GL_ITEMS), "{what}");
            let (float_form, lean, float_out) = may_move[&(r.spec.as_str(), r.function.as_str())];
            if !r.measured {
                assert_eq!(r.mismatches, 0, "{what}: {:?}", r.first);
            } else {
                assert!(
                    float_form || lean || (*regroups && float_out),
                    "{what}: a code or a decoded output is held, not measured"
                );
                moved += usize::from(r.mismatches > 0);
                for m in r.first.iter().filter(|_| !regroups) {
                    assert!(
                        m.input
                            .iter()
                            .chain(&m.expected)
                            .chain(&m.actual)
                            .any(|&w| f32::from_bits(w).is_subnormal() || w & 0x7fff_ffff == 0),
                        "{what}: a change with no denormal or zero in sight: {m:?}"
                    );
                }
            }
        }
    }
    assert!(moved > 0, "SwiftShader flushes some float output");
}

/// Through Slang, `-O0` and `-emit-spirv-via-glsl` give the model's bits for every
/// function; the default and `-O3` routes give every packed code and index, and measure
/// (not hold) float outputs, which Slang's optimizer does move there: were it to stop, the
/// README's account of those routes would be out of date.
fn slang_routes_hold_what_the_readme_says(report: &unitpack::verify::Report) {
    use unitpack::verify::Path;
    for path in [
        Path::HlslSlangO0,
        Path::HlslSlang,
        Path::HlslSlangO3,
        Path::HlslSlangViaGlsl,
    ] {
        let rows: Vec<_> = report
            .rows
            .iter()
            .filter(|r| r.path == path.to_string() && r.same_as.is_none())
            .collect();
        assert!(rows.len() > 500, "{path} ran every function");
        for r in &rows {
            assert!(
                r.error.is_none(),
                "{} {} on {path}: {:?}",
                r.spec,
                r.function,
                r.error
            );
            if !r.measured {
                assert_eq!(r.mismatches, 0, "{} {} on {path}", r.spec, r.function);
            }
        }
        let measured = rows.iter().filter(|r| r.measured).count();
        let moved = rows
            .iter()
            .filter(|r| r.measured && r.mismatches > 0)
            .count();
        if path.regroups() {
            assert!(
                measured > 0 && moved > 0,
                "{path}: {moved} of {measured} moved"
            );
        } else {
            assert_eq!(
                measured, 0,
                "{path} holds every function to the model's bits"
            );
        }
    }
    // The packed encoders are held on every route on lavapipe, measured nowhere.
    assert!(
        report
            .rows
            .iter()
            .filter(|r| r.function == "encode"
                && r.path.starts_with("hlsl/slang")
                && !r.path.ends_with(" on swiftshader"))
            .all(|r| !r.measured && r.mismatches == 0)
    );
}

/// Slang's direct SPIR-V at its default optimization and at `-O3` drops `precise`, and
/// its optimizer turns a product by a constant squared, `(x·k)·(x·k)`, into `(x·x)·k²`.
/// snorm11_11_10's exact rounding once squared `|n|·M` so (tests/data holds that include):
/// through Slang at `-O3` it changes codes of tie vectors, at `-O0` and through GLSL it
/// does not, and today's encoder, which squares `|n·M|`, keeps every code on every route.
#[test]
fn slang_regroups_a_squared_product_the_encoders_no_longer_offer_it() {
    use unitpack::emit::DEFAULT_PREFIX;
    use unitpack::emit::lang::Returns;
    use unitpack::model::Kind;
    use unitpack::model::trace::Ty;
    use unitpack::verify::gpu::{Adapter, Gpu, Shader};
    use unitpack::verify::slang::{Route, Slang};

    let slang = Slang::shared().unwrap_or_else(|e| panic!("{e:#}"));
    let gpu = Gpu::shared_on(Adapter::Cpu).unwrap_or_else(|e| panic!("{e:#}"));
    let spec: Spec = "snorm11_11_10".parse().unwrap();
    let e = spec.emitted();
    let encode = e.functions.iter().find(|f| f.name == "encode").unwrap();
    // Every vector of these components: (±1, ±√½, ±√½) and its kin sit on ties.
    let parts = [1.0f32, -1.0, 0.5, -0.5, 0.0, 0.75];
    let parts: Vec<f32> = parts
        .into_iter()
        .chain([
            std::f32::consts::FRAC_1_SQRT_2,
            -std::f32::consts::FRAC_1_SQRT_2,
        ])
        .collect();
    let mut input = Vec::new();
    for &x in &parts {
        for &y in &parts {
            for &z in &parts {
                input.extend([x.to_bits(), y.to_bits(), z.to_bits()]);
            }
        }
    }
    let want = unitpack::verify::expected(encode, &input);
    let funcs = [(
        "unitpack_snorm11_11_10_encode",
        vec![Ty {
            kind: Kind::F32,
            lanes: 3,
        }],
        Returns::one(Ty {
            kind: Kind::U32,
            lanes: 1,
        }),
    )];
    let today = Generator::new()
        .spec("snorm11_11_10")
        .lang(Lang::Hlsl)
        .render(Lang::Hlsl)
        .unwrap();
    let differing = |include: &str, route: Route| {
        let kernel = Lang::Hlsl.backend(DEFAULT_PREFIX).kernel(include, &funcs);
        let spv = slang
            .spirv(&kernel, route)
            .unwrap_or_else(|e| panic!("{e:#}"));
        let module = gpu
            .selecting(&Shader::SpirV(&spv))
            .unwrap_or_else(|e| panic!("{e:#}"));
        let mut got = Vec::new();
        gpu.run_selected(&module, 0, &input, 3, 1, &mut |out| {
            got.extend_from_slice(out)
        })
        .unwrap_or_else(|e| panic!("{e:#}"));
        assert_eq!(got.len(), want.len());
        got.iter().zip(&want).filter(|(a, b)| a != b).count()
    };
    let old = include_str!("data/snorm11_11_10_encode_regrouped_by_slang.hlsl");
    assert!(
        differing(old, Route::O3) > 0,
        "Slang {} no longer regroups the old encoder at -O3: this test shows nothing",
        slang.version
    );
    for route in [Route::O0, Route::ViaGlsl] {
        assert_eq!(differing(old, route), 0, "the old encoder on {route:?}");
    }
    for route in [Route::O0, Route::Default, Route::O3, Route::ViaGlsl] {
        assert_eq!(differing(&today, route), 0, "today's encoder on {route:?}");
    }
}

/// Items each function ran on `c/cc -O2`, which runs every item: what a sampled path
/// takes its sample of.
fn tested_on_c(report: &unitpack::verify::Report) -> HashMap<(&str, &str), usize> {
    report
        .rows
        .iter()
        .filter(|r| r.path == unitpack::verify::Path::CC.to_string())
        .map(|r| ((r.spec.as_str(), r.function.as_str()), r.tested))
        .collect()
}

/// The C++ and OpenGL paths run every item of a function with at most their sample's
/// size, else exactly that many, and the C path runs every item of the same function.
fn sampled_paths_run_their_sample(report: &unitpack::verify::Report) {
    use unitpack::verify::Path;
    let every = tested_on_c(report);
    for path in [
        Path::CCpp,
        Path::GlslGl,
        Path::GlslGlPrecise,
        Path::HlslSlangO0,
        Path::HlslSlang,
        Path::HlslSlangO3,
        Path::HlslSlangViaGlsl,
    ] {
        let items = path.sampled().expect("a sampled path");
        let rows: Vec<_> = report
            .rows
            .iter()
            .filter(|r| r.path == path.to_string() && r.function != "(whole include)")
            .collect();
        assert!(!rows.is_empty(), "{path} ran");
        for r in rows {
            let all = every[&(r.spec.as_str(), r.function.as_str())];
            assert_eq!(
                r.tested,
                all.min(items),
                "{} {} on {path}",
                r.spec,
                r.function
            );
        }
    }
    assert!(
        every.values().any(|&n| n > 1 << 20),
        "the C path runs every item"
    );
}

/// Each spec's include is checked on its own in every shader language, also where every
/// function shares another spec's code and so runs no kernel of its own.
fn every_include_is_checked_whole(report: &unitpack::verify::Report) {
    for spec in Spec::all() {
        let paths: Vec<&str> = report
            .rows
            .iter()
            .filter(|r| r.spec == spec.to_string() && r.function == "(whole include)")
            .map(|r| r.path.as_str())
            .collect();
        assert_eq!(
            paths,
            [
                "wgsl/naga",
                "wgsl/naga glsl-out",
                "wgsl/literals",
                "wgsl/tint",
                "glsl 330/glslang",
                "glsl es 300/glslang",
                "glsl/literals",
                "glsl/angle",
                "hlsl/glslang",
                "hlsl/literals",
                "c/literals"
            ],
            "{spec}"
        );
    }
}

/// A function with the code and inputs of one verified before it (a precise spec's
/// decoders are its fast spec's) repeats that function's result on every path, and only
/// where the two are the same code by the traces.
fn shared_rows_repeat_identical_code(report: &unitpack::verify::Report) {
    let mut code = HashMap::new();
    let mut function = |spec: &str, name: &str| {
        let key = format!("{spec} {name}");
        code.entry(key)
            .or_insert_with(|| {
                let e = spec.parse::<Spec>().expect("a row names a spec").emitted();
                let f = e.functions.iter().find(|f| f.name == name);
                let inputs = f.expect("a row names a function").inputs.clone();
                (e.module.identity(name), inputs)
            })
            .clone()
    };
    let shared: Vec<_> = report.rows.iter().filter(|r| r.same_as.is_some()).collect();
    assert!(
        shared
            .iter()
            .any(|r| r.spec == "oct24p" && r.same_as.as_deref() == Some("oct24 decode")),
        "oct24p's decoders are oct24's"
    );
    let run: HashMap<(String, &str), &unitpack::verify::Row> = report
        .rows
        .iter()
        .filter(|o| o.same_as.is_none())
        .map(|o| ((format!("{} {}", o.spec, o.function), o.path.as_str()), o))
        .collect();
    for path in ["wgsl/naga", "c/cc -O2", "cpu/4 lanes", "cpu/8 lanes"] {
        assert!(
            shared
                .iter()
                .any(|r| r.spec == "oct24p" && r.function == "decode" && r.path == path),
            "oct24p decode repeats oct24's on {path}"
        );
    }
    for r in shared {
        let owner = r.same_as.as_deref().unwrap();
        let o = run
            .get(&(owner.to_string(), r.path.as_str()))
            .unwrap_or_else(|| panic!("{owner} on {} was run", r.path));
        assert_eq!((r.tested, r.mismatches), (o.tested, o.mismatches));
        let (spec, name) = owner.split_once(' ').unwrap();
        assert!(
            function(&r.spec, &r.function) == function(spec, name),
            "{} {} is not the same code as {owner}",
            r.spec,
            r.function
        );
    }
}

/// The OpenGL paths exist for what a driver's own GLSL compiler does to the text: Mesa's
/// folds the float comparisons float16x3's decoder once tested NaN and infinity with
/// where no `precise` forbids it (tests/data holds that decoder). Through those paths
/// that decoder differs from the model on codes with a NaN half without `precise` and
/// agrees with it, and the decoder emitted today agrees both ways.
#[test]
fn the_opengl_paths_catch_what_mesa_folds_without_precise() {
    use unitpack::emit::DEFAULT_PREFIX;
    use unitpack::emit::lang::KERNEL_SELECT;
    use unitpack::emit::lang::glsl::Glsl;
    use unitpack::model::Kind;
    use unitpack::model::trace::Ty;
    use unitpack::verify::gl::Gl;

    let gl = Gl::shared(true, 2).unwrap_or_else(|e| panic!("{e:#}"));
    let spec: Spec = "float16x3".parse().unwrap();
    let e = spec.emitted();
    let decode = e.functions.iter().find(|f| f.name == "decode").unwrap();
    // Every combination of NaN, infinite, zero, one and finite halves.
    let halves = [
        0x7c01u32, 0x7e00, 0x7fff, 0xfe00, 0x7c00, 0xfc00, 0, 0x8000, 0x3c00, 0xbc00, 0x3555,
    ];
    let mut input = Vec::new();
    for &x in &halves {
        for &y in &halves {
            for &z in &halves {
                input.extend([x | y << 16, z]);
            }
        }
    }
    let want = unitpack::verify::expected(decode, &input);
    let funcs = [(
        "unitpack_float16x3_decode",
        vec![Ty {
            kind: Kind::U32,
            lanes: 2,
        }],
        unitpack::emit::lang::Returns::one(Ty {
            kind: Kind::F32,
            lanes: 3,
        }),
    )];
    let today = Generator::new()
        .spec("float16x3")
        .lang(Lang::Glsl)
        .render(Lang::Glsl)
        .unwrap();
    let differing = |include: &str, precise: bool| {
        let kernel = Glsl::new(DEFAULT_PREFIX).gl_kernel(include, &funcs, precise);
        let program = gl
            .program(&kernel, KERNEL_SELECT)
            .unwrap_or_else(|e| panic!("{e:#}"));
        let mut got = Vec::new();
        gl.run_selected(&program, 0, &input, 2, 3, &mut |out| {
            got.extend_from_slice(out)
        })
        .unwrap_or_else(|e| panic!("{e:#}"));
        program.delete(gl).unwrap();
        got.chunks(3)
            .zip(want.chunks(3))
            .filter(|(a, b)| a != b)
            .count()
    };
    let folded = include_str!("data/float16x3_decode_folded_by_mesa.glsl");
    let n = differing(folded, false);
    assert!(
        n > 0,
        "{}: the old decoder agrees without precise, so this driver no longer folds its \
         comparisons and the test shows nothing",
        gl.renderer
    );
    assert_eq!(differing(folded, true), 0, "with precise");
    assert_eq!(
        differing(&today, false),
        0,
        "today's decoder without precise"
    );
    assert_eq!(differing(&today, true), 0, "today's decoder with precise");
}
