//! Smoke test for the GPU-verification plumbing: one small kernel, wrapped for every path
//! (WGSL via naga, GLSL via naga, GLSL via glslang, HLSL via glslang -Od and default), run on
//! the Vulkan CPU adapter over more than one chunk of seeded inputs, compared bit for bit with
//! the same arithmetic in Rust. Also checks that shader errors come back as `Err` with the
//! compiler's message instead of panicking.

use std::time::Instant;

use unitpack::verify::gpu::{Adapter, Gpu, MAX_CHUNK_ITEMS, Shader, with_selector};
use unitpack::verify::tools::{
    GlslangInput, HlslOpt, glslang_spirv, naga_glsl, naga_wgsl, spirv_val,
};

const IN_WORDS: usize = 2;
const OUT_WORDS: usize = 3;

const WGSL: &str = r#"
@group(0) @binding(0) var<storage, read> input_words: array<u32>;
@group(0) @binding(1) var<storage, read_write> output_words: array<u32>;

const IN_WORDS: u32 = 2u;
const OUT_WORDS: u32 = 3u;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if (i >= arrayLength(&output_words) / OUT_WORDS) {
        return;
    }
    let a = bitcast<f32>(input_words[i * IN_WORDS + 0u]);
    let b = bitcast<f32>(input_words[i * IN_WORDS + 1u]);
    output_words[i * OUT_WORDS + 0u] = bitcast<u32>(a / sqrt(b));
    output_words[i * OUT_WORDS + 1u] = bitcast<u32>(floor(a));
    output_words[i * OUT_WORDS + 2u] = (bitcast<u32>(a) >> 3u) ^ bitcast<u32>(b);
}
"#;

const GLSL: &str = r#"#version 450
layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

layout(set = 0, binding = 0, std430) readonly buffer InputWords { uint input_words[]; };
layout(set = 0, binding = 1, std430) buffer OutputWords { uint output_words[]; };

const uint IN_WORDS = 2u;
const uint OUT_WORDS = 3u;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= uint(output_words.length()) / OUT_WORDS) {
        return;
    }
    float a = uintBitsToFloat(input_words[i * IN_WORDS + 0u]);
    float b = uintBitsToFloat(input_words[i * IN_WORDS + 1u]);
    output_words[i * OUT_WORDS + 0u] = floatBitsToUint(a / sqrt(b));
    output_words[i * OUT_WORDS + 1u] = floatBitsToUint(floor(a));
    output_words[i * OUT_WORDS + 2u] = (floatBitsToUint(a) >> 3u) ^ floatBitsToUint(b);
}
"#;

const HLSL: &str = r#"
[[vk::binding(0, 0)]] StructuredBuffer<uint> input_words;
[[vk::binding(1, 0)]] RWStructuredBuffer<uint> output_words;

static const uint IN_WORDS = 2u;
static const uint OUT_WORDS = 3u;

[numthreads(64, 1, 1)]
void main(uint3 id : SV_DispatchThreadID)
{
    uint out_len, out_stride;
    output_words.GetDimensions(out_len, out_stride);
    uint i = id.x;
    if (i >= out_len / OUT_WORDS) {
        return;
    }
    float a = asfloat(input_words[i * IN_WORDS + 0u]);
    float b = asfloat(input_words[i * IN_WORDS + 1u]);
    output_words[i * OUT_WORDS + 0u] = asuint(a / sqrt(b));
    output_words[i * OUT_WORDS + 1u] = asuint(floor(a));
    output_words[i * OUT_WORDS + 2u] = (asuint(a) >> 3u) ^ asuint(b);
}
"#;

/// The kernel's arithmetic in Rust; f32 `/`, `sqrt` and `floor` are correctly rounded.
fn reference(a: f32, b: f32) -> [u32; OUT_WORDS] {
    [
        (a / b.sqrt()).to_bits(),
        a.floor().to_bits(),
        (a.to_bits() >> 3) ^ b.to_bits(),
    ]
}

/// splitmix64: tiny, seeded, good enough to spread bits.
struct SplitMix(u64);
impl SplitMix {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
}

/// Random f32 bit patterns, with the exponent limited to 2^-60..2^63 so that every input and
/// every result is a finite *normal* number: Vulkan lets implementations flush denormals, and
/// this test is about the plumbing, not about denormal handling.
fn random_f32(rng: &mut SplitMix, positive: bool) -> f32 {
    let r = rng.next();
    let sign = if positive { 0 } else { (r >> 63) as u32 };
    let exponent = 127 - 60 + (((r >> 32) as u32) % 124);
    let mantissa = (r as u32) & 0x007F_FFFF;
    f32::from_bits(sign << 31 | exponent << 23 | mantissa)
}

fn inputs(items: usize) -> Vec<u32> {
    let mut rng = SplitMix(0x756E_6974_7061_636B); // "unitpack"
    let mut words = Vec::with_capacity(items * IN_WORDS);
    // A few hand-picked cases first: integers, halves, negatives near integers, exact squares.
    let special: &[(f32, f32)] = &[
        (1.0, 1.0),
        (-1.0, 4.0),
        (0.5, 2.0),
        (-0.5, 0.25),
        (2.5, 3.0),
        (-2.5, 1e-10),
        (0.0, 1.0),
        (-0.0, 1.0),
        (1.0e30, 1.0e-30),
        (-7.999_999_5, 9.0),
        (16_777_215.0, 2.0),
        (-16_777_217.0, 3.0),
    ];
    for &(a, b) in special {
        words.extend([a.to_bits(), b.to_bits()]);
    }
    while words.len() < items * IN_WORDS {
        let a = random_f32(&mut rng, false);
        let b = random_f32(&mut rng, true);
        words.extend([a.to_bits(), b.to_bits()]);
    }
    words
}

fn check(path: &str, input: &[u32], output: &[u32]) -> Result<(), String> {
    let items = input.len() / IN_WORDS;
    assert_eq!(output.len(), items * OUT_WORDS, "{path}: output length");
    let names = ["a / sqrt(b)", "floor(a)", "(bits(a) >> 3) ^ bits(b)"];
    let mut mismatches = [0usize; OUT_WORDS];
    let mut shown = 0;
    let mut report = String::new();
    for i in 0..items {
        let a = f32::from_bits(input[i * IN_WORDS]);
        let b = f32::from_bits(input[i * IN_WORDS + 1]);
        let want = reference(a, b);
        let got = &output[i * OUT_WORDS..][..OUT_WORDS];
        for k in 0..OUT_WORDS {
            if got[k] != want[k] {
                mismatches[k] += 1;
                if shown < 8 {
                    shown += 1;
                    report.push_str(&format!(
                        "  item {i}: a = {a:e} ({:#010x}), b = {b:e} ({:#010x}): {}: \
                         gpu {:e} ({:#010x}) vs rust {:e} ({:#010x})\n",
                        a.to_bits(),
                        b.to_bits(),
                        names[k],
                        f32::from_bits(got[k]),
                        got[k],
                        f32::from_bits(want[k]),
                        want[k],
                    ));
                }
            }
        }
    }
    if mismatches.iter().all(|&m| m == 0) {
        return Ok(());
    }
    let counts: Vec<String> = names
        .iter()
        .zip(mismatches)
        .map(|(n, m)| format!("{n}: {m}"))
        .collect();
    Err(format!(
        "{path}: mismatches over {items} items ({}):\n{report}",
        counts.join(", ")
    ))
}

#[test]
fn every_path_is_bit_exact_over_several_chunks() {
    let gpu = match Gpu::new() {
        Ok(gpu) => gpu,
        Err(e) => {
            let msg = format!("{e:#}");
            assert!(
                msg.contains("mesa-vulkan-drivers"),
                "Gpu::new() error must name the package to install: {msg}"
            );
            panic!("Gpu::new() failed: {msg}");
        }
    };
    println!("adapter: {}", gpu.adapter_name());
    println!("driver:  {}", gpu.driver());

    // Not a multiple of 64 and more than one chunk.
    let items = MAX_CHUNK_ITEMS + 123;
    assert!(gpu.chunk_items(IN_WORDS, OUT_WORDS) < items);
    let input = inputs(items);

    let compile = |what: &str, source: &str, input: GlslangInput, opt: HlslOpt| {
        let t = Instant::now();
        let words = glslang_spirv(source, input, opt).unwrap_or_else(|e| panic!("{what}: {e:#}"));
        spirv_val(&words).unwrap_or_else(|e| panic!("{what}: {e:#}"));
        println!("{what}: glslang + spirv-val {:?}", t.elapsed());
        words
    };
    naga_wgsl(WGSL).unwrap_or_else(|e| panic!("{e:#}"));
    naga_glsl(GLSL).unwrap_or_else(|e| panic!("{e:#}"));
    let glsl_spv = compile(
        "GLSL/glslang",
        GLSL,
        GlslangInput::Glsl { stage: "comp" },
        HlslOpt::Default,
    );
    let hlsl = GlslangInput::Hlsl {
        stage: "comp",
        entry: "main",
    };
    let hlsl_od = compile("HLSL/glslang -Od", HLSL, hlsl, HlslOpt::Od);
    let hlsl_default = compile("HLSL/glslang default", HLSL, hlsl, HlslOpt::Default);

    let paths = [
        ("WGSL/naga", Shader::Wgsl(WGSL)),
        ("GLSL/naga", Shader::GlslNaga(GLSL)),
        ("GLSL/glslang", Shader::SpirV(&glsl_spv)),
        ("HLSL/glslang -Od", Shader::SpirV(&hlsl_od)),
        ("HLSL/glslang default", Shader::SpirV(&hlsl_default)),
    ];
    let mut failures = Vec::new();
    for (path, shader) in paths {
        let t = Instant::now();
        let output = gpu
            .run(&shader, &input, IN_WORDS, OUT_WORDS)
            .unwrap_or_else(|e| panic!("{path}: {e:#}"));
        println!("{path}: {items} items in {:?}", t.elapsed());
        if let Err(report) = check(path, &input, &output) {
            println!("{report}");
            failures.push(report);
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));

    // One exactly-full chunk, timed on its own (pipeline creation included).
    let one_chunk = &input[..MAX_CHUNK_ITEMS * IN_WORDS];
    let t = Instant::now();
    let output = gpu
        .run(&Shader::Wgsl(WGSL), one_chunk, IN_WORDS, OUT_WORDS)
        .unwrap();
    println!("WGSL/naga: one dispatch of 2^20 items in {:?}", t.elapsed());
    check("WGSL/naga, one chunk", one_chunk, &output).unwrap();

    // Edge cases of the chunking: no items, and fewer items than one workgroup.
    assert!(
        gpu.run(&Shader::Wgsl(WGSL), &[], IN_WORDS, OUT_WORDS)
            .unwrap()
            .is_empty()
    );
    let few = &input[..5 * IN_WORDS];
    let output = gpu
        .run(&Shader::SpirV(&hlsl_od), few, IN_WORDS, OUT_WORDS)
        .unwrap();
    check("HLSL/glslang -Od, 5 items", few, &output).unwrap();
}

#[test]
fn wgsl_syntax_error_is_an_error_not_a_panic() {
    let gpu = Gpu::shared().expect("Gpu::shared()");
    let broken = WGSL.replace("let i = id.x;", "let i = id.x");
    let err = gpu
        .run(&Shader::Wgsl(&broken), &[0; 2], IN_WORDS, OUT_WORDS)
        .expect_err("a WGSL syntax error must fail");
    let msg = format!("{err:#}");
    println!("WGSL syntax error via wgpu:\n{msg}");
    assert!(msg.contains("expected `;`"), "{msg}");
    assert!(
        msg.contains("wgsl:11:5"),
        "message should locate the problem: {msg}"
    );

    let err = naga_wgsl(&broken).expect_err("naga_wgsl must reject it");
    let msg = format!("{err:#}");
    println!("WGSL syntax error via naga_wgsl:\n{msg}");
    assert!(
        msg.contains("expected `;`") && msg.contains("arrayLength"),
        "{msg}"
    );

    // A type error (validation, not parsing) also comes back as Err.
    let mistyped = WGSL.replace("floor(a)", "floor(i)");
    let err = gpu
        .run(&Shader::Wgsl(&mistyped), &[0; 2], IN_WORDS, OUT_WORDS)
        .expect_err("a WGSL type error must fail");
    println!("WGSL type error via wgpu:\n{err:#}");
    assert!(naga_wgsl(&mistyped).is_err());

    // The device still works after those errors.
    let out = gpu
        .run(
            &Shader::Wgsl(WGSL),
            &[4.0f32.to_bits(), 4.0f32.to_bits()],
            IN_WORDS,
            OUT_WORDS,
        )
        .unwrap();
    assert_eq!(out, reference(4.0, 4.0));
}

#[test]
fn glsl_errors_are_errors() {
    let gpu = Gpu::shared().expect("Gpu::shared()");
    let broken = GLSL.replace("float b =", "float b = undefined_thing +");
    let err = gpu
        .run(&Shader::GlslNaga(&broken), &[0; 2], IN_WORDS, OUT_WORDS)
        .expect_err("broken GLSL must fail in naga");
    println!("GLSL error via wgpu/naga:\n{err:#}");
    assert!(format!("{err:#}").contains("undefined_thing"));
    let err = naga_glsl(&broken).expect_err("naga_glsl must reject it");
    assert!(format!("{err:#}").contains("undefined_thing"));
    let err = glslang_spirv(
        &broken,
        GlslangInput::Glsl { stage: "comp" },
        HlslOpt::Default,
    )
    .expect_err("glslang must reject it");
    println!("GLSL error via glslang:\n{err:#}");
    assert!(format!("{err:#}").contains("undefined_thing"));
}

#[test]
fn glslang_reports_invalid_hlsl() {
    let broken = HLSL.replace("asuint(floor(a))", "asuint(floor(a)");
    let err = glslang_spirv(
        &broken,
        GlslangInput::Hlsl {
            stage: "comp",
            entry: "main",
        },
        HlslOpt::Od,
    )
    .expect_err("invalid HLSL must fail");
    let msg = format!("{err:#}");
    println!("HLSL error via glslang:\n{msg}");
    assert!(
        msg.contains("ERROR"),
        "glslang's own message should be included: {msg}"
    );
    assert!(msg.contains("glslangValidator"), "{msg}");
}

#[test]
fn spirv_val_and_passthrough_reject_garbage() {
    let err = spirv_val(&[0x0723_0203, 0, 0, 0, 0, 0xdead_beef]).expect_err("garbage SPIR-V");
    println!("spirv-val on garbage:\n{err:#}");
    let gpu = Gpu::shared().expect("Gpu::shared()");
    assert!(
        gpu.run(&Shader::SpirV(&[1, 2, 3]), &[0; 2], IN_WORDS, OUT_WORDS)
            .is_err()
    );
}

#[test]
fn glslang_check_accepts_old_versions() {
    let body = "\nfloat f(float x) { return floor(x) * 0.5; }\nvoid main() {}\n";
    for version in ["#version 330", "#version 300 es\nprecision highp float;"] {
        let src = format!("{version}\n{body}");
        unitpack::verify::tools::glslang_check(&src, "frag").unwrap_or_else(|e| panic!("{e:#}"));
    }
    let err = unitpack::verify::tools::glslang_check("#version 330\nvoid main() { x; }\n", "frag")
        .expect_err("undeclared identifier");
    println!("glslang_check error:\n{err:#}");
}

#[test]
fn many_threads_share_one_gpu() {
    let gpu = Gpu::shared().expect("Gpu::shared()");
    std::thread::scope(|s| {
        for t in 0..4u32 {
            s.spawn(move || {
                let a = (t as f32) + 0.75;
                let input: Vec<u32> = (0..1000)
                    .flat_map(|_| [a.to_bits(), 4.0f32.to_bits()])
                    .collect();
                let out = gpu
                    .run(&Shader::Wgsl(WGSL), &input, IN_WORDS, OUT_WORDS)
                    .unwrap();
                check("threads", &input, &out).unwrap();
            });
        }
    });
}

/// A selecting kernel (what `verify` compiles once per spec and path) runs the function
/// its selector names, with that function's item widths, on every shader path, over more
/// than one chunk: each function's outputs are its own, none another's; an index past the
/// last function runs none (the output stays zero).
#[test]
fn selecting_kernels_run_the_function_selected() {
    use unitpack::emit::Lang;
    use unitpack::emit::lang::Returns;
    use unitpack::model::Kind;
    use unitpack::model::trace::Ty;
    let gpu = Gpu::shared().expect("Gpu::shared()");
    let swiftshader = Gpu::shared_on(Adapter::SwiftShader).expect("SwiftShader");
    let ty = |lanes| Ty {
        kind: Kind::U32,
        lanes,
    };
    // f0: x ↦ 2x + 1 (one word to one); f1: (x, y) ↦ (y, x ^ y) (two words to two); f2:
    // (x, y) ↦ the struct s2 { a = x + y, b = (y, x) } (two words to three, a struct's
    // fields stored one after the other).
    let funcs = [
        ("f0", vec![ty(1)], Returns::one(ty(1))),
        ("f1", vec![ty(1), ty(1)], Returns::one(ty(2))),
        (
            "f2",
            vec![ty(1), ty(1)],
            Returns {
                tys: vec![ty(1), ty(2)],
                fields: vec!["a", "b"],
                name: Some("s2".into()),
            },
        ),
    ];
    let includes = [
        (
            Lang::Wgsl,
            "fn f0(x: u32) -> u32 { return 2u * x + 1u; }\n\
             fn f1(x: u32, y: u32) -> vec2<u32> { return vec2<u32>(y, x ^ y); }\n\
             struct s2 { a: u32, b: vec2<u32>, }\n\
             fn f2(x: u32, y: u32) -> s2 { return s2(x + y, vec2<u32>(y, x)); }\n",
        ),
        (
            Lang::Glsl,
            "uint f0(uint x) { return 2u * x + 1u; }\n\
             uvec2 f1(uint x, uint y) { return uvec2(y, x ^ y); }\n\
             struct s2 { uint a; uvec2 b; };\n\
             s2 f2(uint x, uint y) { return s2(x + y, uvec2(y, x)); }\n",
        ),
        (
            Lang::Hlsl,
            "uint f0(uint x) { return 2u * x + 1u; }\n\
             uint2 f1(uint x, uint y) { return uint2(y, x ^ y); }\n\
             struct s2 { uint a; uint2 b; };\n\
             s2 f2(uint x, uint y) { s2 r = { x + y, uint2(y, x) }; return r; }\n",
        ),
    ];
    let items = MAX_CHUNK_ITEMS + 77;
    let words: Vec<u32> = (0..2 * items as u32)
        .map(|k| k.wrapping_mul(2654435761))
        .collect();
    let want0: Vec<u32> = words[..items].iter().map(|x| 2 * x + 1).collect();
    let want1: Vec<u32> = words.chunks(2).flat_map(|p| [p[1], p[0] ^ p[1]]).collect();
    let want2: Vec<u32> = words
        .chunks(2)
        .flat_map(|p| [p[0].wrapping_add(p[1]), p[1], p[0]])
        .collect();
    for (lang, include) in includes {
        let kernel = lang.backend("unitpack_").kernel(include, &funcs);
        let mut shaders = Vec::new();
        let spirv = |input| {
            let words = glslang_spirv(&kernel, input, HlslOpt::Default)
                .unwrap_or_else(|e| panic!("{lang:?}: {e:#}"));
            spirv_val(&words).unwrap_or_else(|e| panic!("{lang:?}: {e:#}"));
            words
        };
        let glsl_spv;
        let hlsl_spv;
        match lang {
            Lang::Wgsl => shaders.push(("wgsl/naga", Shader::Wgsl(&kernel))),
            Lang::Glsl => {
                glsl_spv = spirv(GlslangInput::Glsl { stage: "comp" });
                shaders.push(("glsl/naga", Shader::GlslNaga(&kernel)));
                shaders.push(("glsl/glslang", Shader::SpirV(&glsl_spv)));
            }
            _ => {
                hlsl_spv = spirv(GlslangInput::Hlsl {
                    stage: "comp",
                    entry: "main",
                });
                shaders.push(("hlsl/glslang", Shader::SpirV(&hlsl_spv)));
            }
        }
        for ((path, shader), gpu) in shaders.iter().flat_map(|s| [(s, gpu), (s, swiftshader)]) {
            let path = format!("{path} on {}", gpu.adapter_name());
            if let Shader::SpirV(words) = shader {
                // The selector frozen into a constant: still a valid module, no
                // specialization constant left.
                let frozen = with_selector(words, 2).unwrap_or_else(|e| panic!("{path}: {e:#}"));
                spirv_val(&frozen).unwrap_or_else(|e| panic!("{path}, selector frozen: {e:#}"));
                let opcodes = |w: &[u32]| {
                    let (mut at, mut ops) = (5, Vec::new());
                    while at < w.len() {
                        ops.push(w[at] & 0xffff);
                        at += (w[at] >> 16).max(1) as usize;
                    }
                    ops
                };
                let count = |w: &[u32], op: u32| opcodes(w).iter().filter(|&&o| o == op).count();
                // OpSpecConstant (50) became OpConstant (43); the SpecId decoration
                // (an OpDecorate, 71) is gone.
                assert_eq!(count(words, 50), 1, "{path}: one specialization constant");
                assert_eq!(count(&frozen, 50), 0, "{path}: none once frozen");
                assert_eq!(count(&frozen, 43), count(words, 43) + 1, "{path}");
                assert_eq!(count(&frozen, 71), count(words, 71) - 1, "{path}");
            }
            let kernel = gpu
                .selecting(shader)
                .unwrap_or_else(|e| panic!("{path}: {e:#}"));
            let run = |index, input: &[u32], (iw, ow)| {
                let mut out = Vec::new();
                gpu.run_selected(&kernel, index, input, iw, ow, &mut |w| {
                    out.extend_from_slice(w)
                })
                .unwrap_or_else(|e| panic!("{path}: {e:#}"));
                out
            };
            assert!(
                run(1, &words, (2, 2)) == want1,
                "{path}: f1 over two chunks"
            );
            assert!(
                run(0, &words[..items], (1, 1)) == want0,
                "{path}: f0 over two chunks"
            );
            assert!(
                run(2, &words, (2, 3)) == want2,
                "{path}: f2 over two chunks"
            );
            assert_eq!(run(1, &words[..6], (2, 2)), want1[..6], "{path}: f1 again");
            assert_eq!(run(3, &words[..6], (2, 2)), [0; 6], "{path}: no function 3");
        }
    }
}
