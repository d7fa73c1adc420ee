//! Compute kernels that wrap an emitted include: read one item's words from the input
//! buffer, bit-cast them to the function's parameter, call it, write the result's bits.
//! Inputs come from a storage buffer, never literals, so the driver's constant folder is
//! not what gets tested.

use crate::emit::Lang;
use crate::emit::printer::ty;
use crate::model::Kind;
use crate::model::trace::Ty;

const LANES: [&str; 3] = ["x", "y", "z"];

/// Loads `ty` from `input_words[i*n + k]` as an expression.
fn load(lang: Lang, t: Ty, stride: usize) -> String {
    let words: Vec<String> = (0..t.lanes as usize)
        .map(|k| match lang {
            Lang::Wgsl => format!("input_words[i * {stride}u + {k}u]"),
            _ => format!("input_words[i * {stride}u + {k}u]"),
        })
        .collect();
    let u = if t.lanes == 1 {
        words[0].clone()
    } else {
        format!(
            "{}({})",
            ty(
                lang,
                Ty {
                    kind: Kind::U32,
                    lanes: t.lanes
                }
            ),
            words.join(", ")
        )
    };
    match (t.kind, lang) {
        (Kind::U32, _) => u,
        (Kind::F32, Lang::Wgsl) => format!("bitcast<{}>({u})", ty(lang, t)),
        (Kind::F32, Lang::Glsl) => format!("uintBitsToFloat({u})"),
        (Kind::F32, Lang::Hlsl) => format!("asfloat({u})"),
        (Kind::Bool, _) => unreachable!("no function takes booleans"),
    }
}

/// Statements storing `r` (of type `t`) at `output_words[i*n + k]`.
fn store(lang: Lang, t: Ty, stride: usize) -> Vec<String> {
    let bits = match (t.kind, lang) {
        (Kind::U32, _) => "r".to_string(),
        (Kind::F32, Lang::Wgsl) => format!(
            "bitcast<{}>(r)",
            ty(
                lang,
                Ty {
                    kind: Kind::U32,
                    lanes: t.lanes
                }
            )
        ),
        (Kind::F32, Lang::Glsl) => "floatBitsToUint(r)".to_string(),
        (Kind::F32, Lang::Hlsl) => "asuint(r)".to_string(),
        (Kind::Bool, _) => unreachable!(),
    };
    let decl = match lang {
        Lang::Wgsl => format!("let rb = {bits};"),
        _ => format!(
            "{} rb = {bits};",
            ty(
                lang,
                Ty {
                    kind: Kind::U32,
                    lanes: t.lanes
                }
            )
        ),
    };
    let mut out = vec![decl];
    for (k, l) in LANES.iter().enumerate().take(t.lanes as usize) {
        let lane = if t.lanes == 1 {
            String::new()
        } else {
            format!(".{l}")
        };
        out.push(format!("output_words[i * {stride}u + {k}u] = rb{lane};"));
    }
    out
}

/// A compute shader around `include` that calls `func` (parameter type `param`, result
/// type `ret`) on every item. GLSL is a `#version 450` compute shader; HLSL and WGSL are
/// the include plus an entry point.
pub fn wrap(lang: Lang, include: &str, func: &str, param: Ty, ret: Ty) -> String {
    let (inw, outw) = (param.lanes as usize, ret.lanes as usize);
    let call = match lang {
        Lang::Wgsl => format!("let r = {func}({});", load(lang, param, inw)),
        _ => format!("{} r = {func}({});", ty(lang, ret), load(lang, param, inw)),
    };
    let body = std::iter::once(call)
        .chain(store(lang, ret, outw))
        .collect::<Vec<_>>()
        .join("\n    ");
    match lang {
        Lang::Wgsl => format!(
            "{include}
@group(0) @binding(0) var<storage, read> input_words: array<u32>;
@group(0) @binding(1) var<storage, read_write> output_words: array<u32>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {{
    let i = id.x;
    if (i >= arrayLength(&output_words) / {outw}u) {{
        return;
    }}
    {body}
}}
"
        ),
        Lang::Glsl => format!(
            "#version 450
layout(local_size_x = 64) in;
layout(std430, set = 0, binding = 0) readonly buffer InputWords {{ uint input_words[]; }};
layout(std430, set = 0, binding = 1) buffer OutputWords {{ uint output_words[]; }};

{include}
void main() {{
    uint i = gl_GlobalInvocationID.x;
    if (i >= uint(output_words.length()) / {outw}u) {{
        return;
    }}
    {body}
}}
"
        ),
        Lang::Hlsl => format!(
            "{include}
[[vk::binding(0, 0)]] StructuredBuffer<uint> input_words : register(t0);
[[vk::binding(1, 0)]] RWStructuredBuffer<uint> output_words : register(u1);

[numthreads(64, 1, 1)]
void main(uint3 id : SV_DispatchThreadID) {{
    uint i = id.x;
    uint count, stride;
    output_words.GetDimensions(count, stride);
    if (i >= count / {outw}u) {{
        return;
    }}
    {body}
}}
"
        ),
    }
}
