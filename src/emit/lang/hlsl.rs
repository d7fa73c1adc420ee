//! HLSL (Shader Model 5.0+, HLSL 2018 and 2021, and Slang): every float statement is
//! `precise`; lane-wise selects go through a macro that is `select()` where the compiler
//! wants it (HLSL 2021, Slang) and `?:` elsewhere.

use super::{
    Backend, FileOptions, KERNEL_SELECT, KernelFn, KernelIo, kernel_io, scalar_names,
    selecting_parts,
};
use crate::emit::lang::SpecView;
use crate::model::Kind;
use crate::model::trace::{BinOp, Op, Ty};
use askama::Template;

pub struct Hlsl {
    /// The lane-wise select macro (`UNITPACK_SELECT`).
    pub select_macro: String,
}

impl Hlsl {
    pub fn new(prefix: &str) -> Hlsl {
        Hlsl {
            select_macro: format!("{}SELECT", crate::emit::lang::macro_prefix(prefix)),
        }
    }
}

#[derive(Template)]
#[template(path = "hlsl.txt", escape = "none")]
struct File<'a> {
    header: &'a [String],
    specs: &'a [SpecView],
    select_macro: &'a str,
}

impl Backend for Hlsl {
    fn ty(&self, t: Ty) -> String {
        let (_, _, h) = scalar_names(t.kind);
        match t.lanes {
            1 => h.to_string(),
            n => format!("{h}{n}"),
        }
    }
    /// HLSL 2021 (DXC's default) rejects `?:` on vector conditions and wants select();
    /// older HLSL has no select(). The include defines the macro.
    fn select(&self, _ty: Ty, mask_is_vector: bool, m: &str, t: &str, f: &str) -> String {
        if mask_is_vector {
            format!("{}({m}, {t}, {f})", self.select_macro)
        } else {
            format!("{m} ? {t} : {f}")
        }
    }
    fn bitcast(&self, t: Ty, a: &str) -> String {
        match t.kind {
            Kind::U32 => format!("asuint({a})"),
            _ => format!("asfloat({a})"),
        }
    }
    fn splat(&self, t: Ty, x: &str) -> String {
        let lanes = vec![x; t.lanes as usize];
        format!("{}({})", self.ty(t), lanes.join(", "))
    }
    fn precise_declarations(&self) -> bool {
        true
    }
    /// Scalar `?:` and `&&`, `||`: HLSL 2021 evaluates them lazily, as glslang does.
    fn lazy_operands(&self, op: &Op, _t: Ty, mask_is_vector: bool) -> &'static [usize] {
        match op {
            Op::Select if !mask_is_vector => &[1, 2],
            Op::Bin(BinOp::And | BinOp::Or) => &[1],
            _ => &[],
        }
    }
    fn declare(&self, name: &str, t: Ty, expr: &str) -> String {
        let q = if t.kind == Kind::F32 { "precise " } else { "" };
        format!("{q}{} {name} = {expr};", self.ty(t))
    }
    fn struct_def(&self, name: &str, fields: &[(&str, Ty)]) -> String {
        let fields: String = fields
            .iter()
            .map(|(f, t)| format!("\n    {} {f};", self.ty(*t)))
            .collect();
        format!("struct {name} {{{fields}\n}};")
    }
    /// HLSL has no struct constructor: the struct is built in a declaration.
    fn return_struct(&self, name: &str, local: &str, values: &[String]) -> Vec<String> {
        vec![
            format!("{name} {local} = {{ {} }};", values.join(", ")),
            format!("return {local};"),
        ]
    }
    fn render(&self, specs: &[SpecView], opts: &FileOptions) -> String {
        File {
            header: opts.header,
            specs,
            select_macro: &self.select_macro,
        }
        .render()
        .expect("HLSL template renders")
    }
    fn kernel(&self, include: &str, funcs: &[KernelFn]) -> String {
        let (runners, cases) = selecting_parts(
            funcs,
            |runner, (func, params, ret)| {
                let outw = ret.words();
                let KernelIo { args, stores } = kernel_io(
                    self,
                    params,
                    ret,
                    |l, _| format!("asfloat({l})"),
                    |v, _| format!("asuint({v})"),
                    |name, t, e| format!("{} {name} = {e};", self.ty(t)),
                );
                format!(
                    "
void {runner}(uint i) {{
    uint count, stride;
    output_words.GetDimensions(count, stride);
    if (i >= count / {outw}u) {{
        return;
    }}
    {} r = {func}({args});{stores}
}}
",
                    ret.ty(self)
                )
            },
            |k, runner| format!("\n    case {k}u:\n        {runner}(id.x);\n        break;"),
        );
        format!(
            "{include}
[[vk::binding(0, 0)]] StructuredBuffer<uint> input_words : register(t0);
[[vk::binding(1, 0)]] RWStructuredBuffer<uint> output_words : register(u1);
[[vk::constant_id(0)]] const uint {KERNEL_SELECT} = 0u;
{runners}
[numthreads(64, 1, 1)]
void main(uint3 id : SV_DispatchThreadID) {{
    switch ({KERNEL_SELECT}) {{{cases}
    default:
        break;
    }}
}}
"
        )
    }
}
