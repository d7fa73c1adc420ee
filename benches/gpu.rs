//! GPU time per function on lavapipe, measured as the survey's Table 2: each invocation
//! encodes (or decodes) its item many times with a small bias per iteration and sums the
//! results, so that no compiler can drop the work; a kernel that only fetches and sums is
//! the baseline, subtracted. Each kernel also runs on a handful of items, whose time
//! (pipeline compilation, buffer transfers) is subtracted too. Figures are ns per vector
//! on this machine's lavapipe and, beside them, the ratio to oct at the same size in the
//! same run: lavapipe is a CPU rasterizer, so only the ratios carry over to GPUs, loosely.
//!
//! `cargo bench --bench gpu` (needs lavapipe, `mesa-vulkan-drivers`).

use std::time::Instant;
use unitpack::Spec;
use unitpack::codecs::functions::function::Role;
use unitpack::emit::{DEFAULT_PREFIX, Lang, render};
use unitpack::measure::measured;
use unitpack::verify::gpu::{Gpu, Shader};

/// Items per timed dispatch and iterations per item (more for decoders, which are short).
const ITEMS: usize = 1 << 18;
const ENCODE_ITER: u32 = 256;
const DECODE_ITER: u32 = 1024;
/// Items of the run whose time (compilation, transfers) is subtracted.
const FEW: usize = 64;

/// The kernel around one loop body; `v` (the input vector) and `code` (the input code)
/// are in scope, `acc` collects the results.
fn kernel(include: &str, iter: u32, body: &str) -> String {
    format!(
        "{include}
@group(0) @binding(0) var<storage, read> input_words: array<u32>;
@group(0) @binding(1) var<storage, read_write> output_words: array<u32>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {{
    let i = id.x;
    if (i >= arrayLength(&output_words)) {{
        return;
    }}
    let v = vec3<f32>(bitcast<f32>(input_words[3u * i]), bitcast<f32>(input_words[3u * i + 1u]), bitcast<f32>(input_words[3u * i + 2u]));
    let code = input_words[3u * i];
    var acc = 0u;
    for (var k = 0u; k < {iter}u; k++) {{
        let b = f32(k) * 0.0001;
        {body}
    }}
    output_words[i] = acc;
}}
"
    )
}

/// Seconds for `ITEMS` items of `source`, less the seconds for `FEW` items (the best of
/// five runs each).
fn seconds(gpu: &Gpu, source: &str, input: &[u32]) -> f64 {
    let time = |items: usize| {
        (0..5)
            .map(|_| {
                let t = Instant::now();
                gpu.run(&Shader::Wgsl(source), &input[..items * 3], 3, 1)
                    .expect("kernel runs");
                t.elapsed().as_secs_f64()
            })
            .fold(f64::INFINITY, f64::min)
    };
    time(ITEMS) - time(FEW)
}

/// ns per vector of one function call, the baseline's time subtracted.
fn per_vector(gpu: &Gpu, source: &str, iter: u32, base: f64, input: &[u32]) -> f64 {
    (seconds(gpu, source, input) - base) * 1e9 / (ITEMS as f64 * f64::from(iter))
}

fn main() {
    let gpu = Gpu::shared().expect("lavapipe (install mesa-vulkan-drivers)");
    let vs = unitpack::support::sampling::random_unit_vectors(1, ITEMS, false);
    let input: Vec<u32> = vs.iter().flatten().map(|x| x.to_bits()).collect();
    let base_encode = seconds(
        gpu,
        &kernel("", ENCODE_ITER, "acc += bitcast<u32>(v.x + v.y + v.z + b);"),
        &input,
    );
    let base_decode = seconds(
        gpu,
        &kernel(
            "",
            DECODE_ITER,
            "let d = vec3<f32>(f32(code + k)); acc += bitcast<u32>(d.x + d.y + d.z);",
        ),
        &input,
    );
    println!(
        "lavapipe on {} ({}), {ITEMS} vectors × {ENCODE_ITER} encodes or {DECODE_ITER} decodes; baselines (fetch and sum) {:.1} / {:.1} ms",
        gpu.adapter_name(),
        gpu.driver(),
        base_encode * 1e3,
        base_decode * 1e3
    );
    for bits in [16, 24, 32] {
        let mut oct = (0.0, 0.0);
        for id in [
            "oct",
            "oct_p",
            "spherical",
            "eqarea_ellipse",
            "hemioct",
            "lambert",
        ] {
            let id = match id.strip_suffix("_p") {
                Some(family) => format!("{family}{bits}p"),
                None => format!("{id}{bits}"),
            };
            let spec: Spec = id.parse().expect("spec");
            let words = |role| {
                let e = spec.emitted();
                let f = e.functions.iter().find(|f| f.role == role).cloned();
                f.map(|f| (f.in_words, f.out_words))
            };
            if words(Role::Encode) != Some((3, 1)) || words(Role::Decode) != Some((1, 3)) {
                continue;
            }
            let include = render(
                &[measured(&spec, None)],
                Lang::Wgsl,
                DEFAULT_PREFIX,
                "bench",
            );
            let name = |f: &str| format!("{DEFAULT_PREFIX}{}_{f}", spec.id());
            let enc = kernel(
                &include,
                ENCODE_ITER,
                &format!("acc += {}(v + vec3<f32>(b));", name("encode")),
            );
            let dec = kernel(
                &include,
                DECODE_ITER,
                &format!(
                    "let d = {}(code + k); acc += bitcast<u32>(d.x + d.y + d.z);",
                    name("decode")
                ),
            );
            let e = per_vector(gpu, &enc, ENCODE_ITER, base_encode, &input);
            let d = per_vector(gpu, &dec, DECODE_ITER, base_decode, &input);
            if id == format!("oct{bits}") {
                oct = (e, d);
            }
            println!(
                "{id:<18} encode {e:>7.3} ns/vector ({:>5.2}× oct{bits})   decode {d:>7.3} ns/vector ({:>5.2}× oct{bits})",
                e / oct.0,
                d / oct.1
            );
        }
    }
}
