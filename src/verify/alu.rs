//! ALU instruction counts of the emitted functions, the measure of shader cost the README
//! codec table quotes: each function called once from a GLSL 4.30 compute shader that
//! loads its argument from a storage buffer and stores its result in another
//! (`#define UNITPACK_PRECISE precise`), compiled by `glslangValidator -V`, optimised by
//! `spirv-opt -O` (which inlines the function into `main`), and counted in `main`:
//! arithmetic, bit and logic operations, comparisons, selects, conversions, bitcasts and
//! `GLSL.std.450` calls, a vector instruction counting once. Loads, stores, shuffles,
//! composites and control flow are not counted. Static counts: a select costs as much
//! as what it selects between was already computed.

use super::tools::{GlslangInput, HlslOpt, glslang_spirv, spirv_opt_dis};
use crate::codecs::Spec;
use crate::codecs::functions::function::{Emitted, Role};
use crate::emit::{DEFAULT_PREFIX, Lang, render};
use crate::model::Kind;
use crate::model::trace::Ty;
use anyhow::{Context, Result, anyhow};

/// The opcodes counted (SPIR-V names without `Op`).
const ALU: &[&str] = &[
    "FAdd",
    "FSub",
    "FMul",
    "FDiv",
    "FRem",
    "FMod",
    "FNegate",
    "IAdd",
    "ISub",
    "IMul",
    "UDiv",
    "SDiv",
    "UMod",
    "SRem",
    "SMod",
    "SNegate",
    "VectorTimesScalar",
    "Dot",
    "BitwiseAnd",
    "BitwiseOr",
    "BitwiseXor",
    "ShiftLeftLogical",
    "ShiftRightLogical",
    "ShiftRightArithmetic",
    "Not",
    "BitFieldInsert",
    "BitFieldSExtract",
    "BitFieldUExtract",
    "LogicalAnd",
    "LogicalOr",
    "LogicalNot",
    "LogicalEqual",
    "LogicalNotEqual",
    "Any",
    "All",
    "IsNan",
    "IsInf",
    "FOrdEqual",
    "FOrdNotEqual",
    "FOrdLessThan",
    "FOrdGreaterThan",
    "FOrdLessThanEqual",
    "FOrdGreaterThanEqual",
    "FUnordEqual",
    "FUnordNotEqual",
    "FUnordLessThan",
    "FUnordGreaterThan",
    "FUnordLessThanEqual",
    "FUnordGreaterThanEqual",
    "IEqual",
    "INotEqual",
    "ULessThan",
    "UGreaterThan",
    "ULessThanEqual",
    "UGreaterThanEqual",
    "SLessThan",
    "SGreaterThan",
    "SLessThanEqual",
    "SGreaterThanEqual",
    "Select",
    "ConvertFToU",
    "ConvertFToS",
    "ConvertUToF",
    "ConvertSToF",
    "Bitcast",
    "FConvert",
    "UConvert",
    "SConvert",
    "ExtInst",
];

/// The GLSL type of one traced value.
fn glsl_type(t: Ty) -> String {
    match (t.kind, t.lanes) {
        (Kind::F32, 1) => "float".into(),
        (Kind::U32, 1) => "uint".into(),
        (Kind::F32, n) => format!("vec{n}"),
        (Kind::U32, n) => format!("uvec{n}"),
        (Kind::Bool, _) => unreachable!("no function takes or returns a bool"),
    }
}

/// The compute shader that calls `function` of `spec` once. Several float arguments
/// (`encode(v, fetched)`) arrive as one vector, split by swizzles.
fn shader(spec: &Spec, e: &Emitted, function: &str) -> Result<String> {
    let f = e
        .functions
        .iter()
        .find(|f| f.name == function)
        .ok_or_else(|| anyhow!("{spec} has no function `{function}`"))?;
    if matches!(f.role, Role::Pack | Role::Unpack | Role::Combine) {
        return Err(anyhow!("{spec}: only codec functions are counted"));
    }
    let traced = e.module.func(function).expect("every function is traced");
    let params: Vec<Ty> = traced.params.iter().map(|p| p.1).collect();
    let lanes: u8 = params.iter().map(|t| t.lanes).sum();
    // The input buffer's element type, the call's arguments, and a declaration the
    // element type needs.
    let (tin, args, decl) = match params.as_slice() {
        [one] => (glsl_type(*one), "inp[i]".to_string(), String::new()),
        many if many.iter().all(|t| t.kind == Kind::F32) && lanes <= 4 => {
            let mut at = 0;
            let args: Vec<String> = many
                .iter()
                .map(|t| {
                    let sw: String = "xyzw"[at as usize..(at + t.lanes) as usize].into();
                    at += t.lanes;
                    format!("inp[i].{sw}")
                })
                .collect();
            (
                glsl_type(Ty {
                    kind: Kind::F32,
                    lanes,
                }),
                args.join(", "),
                String::new(),
            )
        }
        // Mixed or many arguments (a precise search's code and fetched texels): one
        // struct member each, loaded as they are (a load is no ALU instruction).
        many => {
            let members: String = many
                .iter()
                .enumerate()
                .map(|(k, t)| format!(" {} a{k};", glsl_type(*t)))
                .collect();
            let args: Vec<String> = (0..many.len()).map(|k| format!("inp[i].a{k}")).collect();
            let decl = format!("struct Args {{{members} }};\n");
            ("Args".to_string(), args.join(", "), decl)
        }
    };
    let include = render(
        &[crate::measure::measured(spec, None)],
        Lang::Glsl,
        DEFAULT_PREFIX,
        "",
    );
    let prefix = if e.namespace.is_empty() {
        DEFAULT_PREFIX.to_string()
    } else {
        format!("{DEFAULT_PREFIX}{}_", e.namespace)
    };
    let name = format!("{prefix}{function}");
    // Several results arrive as the struct they are returned in, one per item.
    let tout = match traced.shape {
        Some(shape) => format!("{prefix}{}", shape.name),
        None => glsl_type(traced.ret_tys[0]),
    };
    Ok(format!(
        "#version 430\n#define UNITPACK_PRECISE precise\n{include}\n\
         layout(local_size_x = 64) in;\n{decl}\
         layout(std430, set = 0, binding = 0) readonly buffer In {{ {tin} inp[]; }};\n\
         layout(std430, set = 0, binding = 1) writeonly buffer Out {{ {tout} outp[]; }};\n\
         void main() {{\n    uint i = gl_GlobalInvocationID.x;\n    outp[i] = {name}({args});\n}}\n",
    ))
}

/// ALU instructions in the function `main` of a disassembled module.
pub fn count_main(dis: &str) -> Result<u32> {
    let main_id = dis
        .lines()
        .find_map(|l| {
            let l = l.trim();
            let rest = l.strip_prefix("OpEntryPoint GLCompute ")?;
            rest.split_whitespace().next().map(str::to_string)
        })
        .ok_or_else(|| anyhow!("no compute entry point in the optimised module"))?;
    let mut inside = false;
    let mut n = 0;
    for l in dis.lines() {
        let l = l.trim();
        let op = match l.split_once("= Op") {
            Some((_, rest)) => rest,
            None => l.strip_prefix("Op").unwrap_or(""),
        };
        let op = op.split_whitespace().next().unwrap_or("");
        if op == "Function" && l.starts_with(&format!("{main_id} ")) {
            inside = true;
        } else if op == "FunctionEnd" {
            inside = false;
        } else if inside && ALU.contains(&op) {
            n += 1;
        }
    }
    Ok(n)
}

/// The ALU count of one function of one spec. A function the shader splits around a
/// table fetch (`spherical_lut16`'s `encode` = `atan_texel`, fetch, `encode(v, fetched)`)
/// counts as the sum of its emitted parts.
pub fn count(spec: &Spec, function: &str) -> Result<u32> {
    let parts = spec
        .emitted()
        .cpu
        .iter()
        .find(|f| f.name == function)
        .map(|f| f.parts.clone());
    match parts {
        Some(parts) => parts.iter().map(|p| count_emitted(spec, p)).sum(),
        None => count_emitted(spec, function),
    }
}

/// The ALU count of one emitted function, compiled once per process for each distinct
/// code: functions with the same [`Module::identity`](crate::model::trace::Module::identity)
/// (a precise spec's decoders are its fast spec's) differ only in their names, which no
/// instruction counts.
fn count_emitted(spec: &Spec, function: &str) -> Result<u32> {
    static MEMO: crate::support::memo::Memo<String, u32> = crate::support::memo::Memo::new();
    let e = spec.emitted();
    let src = shader(spec, &e, function)?;
    let code = e.module.identity(function);
    if let Some(n) = MEMO.get(&code) {
        return Ok(n);
    }
    let words = glslang_spirv(&src, GlslangInput::Glsl { stage: "comp" }, HlslOpt::Default)
        .with_context(|| format!("compiling {spec}'s {function} for counting"))?;
    let n = count_main(&spirv_opt_dis(&words)?)?;
    MEMO.extend([(code, n)]);
    Ok(n)
}

/// [`count`] of each of `functions` for every spec, on all cores: `out[i][j]` is spec `i`,
/// function `j`.
pub fn count_all(specs: &[Spec], functions: &[&str]) -> Result<Vec<Vec<u32>>> {
    // Each thread takes the next spec: one precise search costs as much as dozens of others.
    crate::support::par::map(specs, |spec| {
        functions.iter().map(|f| count(spec, f)).collect()
    })
    .into_iter()
    .collect()
}
