//! WGSL: `let` statements, `select(f, t, m)`, `1.0f` literals; no preprocessor, so names
//! carry a prefix and naga_oil users may add `#define_import_path`.

use super::{
    Backend, FileOptions, KERNEL_SELECT, KernelFn, KernelIo, kernel_io, scalar_names,
    selecting_parts,
};
use crate::emit::lang::SpecView;
use crate::emit::lang::literal::f32_literal;
use crate::emit::lang::printer::top_level_tokens;
use crate::model::Kind;
use crate::model::trace::Ty;
use askama::Template;

pub struct Wgsl;

#[derive(Template)]
#[template(path = "wgsl.txt", escape = "none")]
struct File<'a> {
    header: &'a [String],
    import_path: Option<&'a str>,
    specs: &'a [SpecView],
}

impl Backend for Wgsl {
    fn ty(&self, t: Ty) -> String {
        let (w, _, _) = scalar_names(t.kind);
        match t.lanes {
            1 => w.to_string(),
            n => format!("vec{n}<{w}>"),
        }
    }
    fn float_suffix(&self) -> &'static str {
        "f"
    }
    /// ±FLT_MAX as the bitcast of its bits, every other value as a literal. WESL linkers
    /// parse a module's literals and print them again: the `wesl` crate prints an f32
    /// through Rust's shortest round trip, `340282350000000000000000000000000000000f` for
    /// FLT_MAX, a decimal above it, which Tint rejects as out of range. A bitcast of an
    /// integer means FLT_MAX to every compiler and survives any reprinting.
    fn float_constant(&self, v: f32) -> String {
        if v.abs() == f32::MAX {
            format!("bitcast<f32>({:#010x}u)", v.to_bits())
        } else {
            format!("{}f", f32_literal(v))
        }
    }
    /// `select` on integer or boolean vectors is lane by lane: naga writes a vector
    /// `select` as GLSL's `mix`, which takes such vectors only from GLSL 4.50 and ES 3.10,
    /// so the include would not compile as GLSL 4.30 on wgpu's OpenGL backend.
    fn select(&self, ty: Ty, mask_is_vector: bool, m: &str, t: &str, f: &str) -> String {
        let select = |[m, t, f]: [&str; 3]| {
            format!(
                "select({})",
                self.arguments(&[f.to_string(), t.to_string(), m.to_string()])
            )
        };
        if mask_is_vector && ty.kind != Kind::F32 {
            super::select_by_lane(&self.ty(ty), ty.lanes, [m, t, f], select)
        } else {
            select([m, t, f])
        }
    }
    /// The WESL linker of npm's `wesl` (0.7.31) ends its template-list discovery at `;`,
    /// `{`, `:`, `==`, `!=`, `&&` or `||` but not at a closing bracket, as WGSL §3.9 does:
    /// `select(select(x, y, t < u), z, t >= u)` fails to link there, `t <` read as a
    /// template whose `>` is the later `>=`. Written `u > t`, no comparison opens one.
    fn less_than_as_greater(&self) -> bool {
        true
    }
    /// WGSL's template-list discovery reads `f(a < b, c > d)` as `f(a<b, c>d)`, a template
    /// list (WGSL §3.9): an argument with a `<` at its top level is bracketed unless it is
    /// the last, whose `<` the closing `)` ends.
    fn arguments(&self, args: &[String]) -> String {
        let last = args.len().saturating_sub(1);
        args.iter()
            .enumerate()
            .map(|(i, a)| {
                if i < last && top_level_tokens(a).iter().any(|(_, t)| *t == "<") {
                    format!("({a})")
                } else {
                    a.clone()
                }
            })
            .collect::<Vec<_>>()
            .join(", ")
    }
    fn declare(&self, name: &str, _t: Ty, expr: &str) -> String {
        format!("let {name} = {expr};")
    }
    fn bitcast(&self, t: Ty, a: &str) -> String {
        format!("bitcast<{}>({a})", self.ty(t))
    }
    fn struct_def(&self, name: &str, fields: &[(&str, Ty)]) -> String {
        let fields: String = fields
            .iter()
            .map(|(f, t)| format!("\n    {f}: {},", self.ty(*t)))
            .collect();
        format!("struct {name} {{{fields}\n}}")
    }
    fn render(&self, specs: &[SpecView], opts: &FileOptions) -> String {
        File {
            header: opts.header,
            import_path: opts.import_path,
            specs,
        }
        .render()
        .expect("WGSL template renders")
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
                    |l, param| self.bitcast(param, l),
                    |v, t| {
                        self.bitcast(
                            Ty {
                                kind: Kind::U32,
                                lanes: t.lanes,
                            },
                            v,
                        )
                    },
                    |name, t, e| self.declare(name, t, e),
                );
                format!(
                    "
fn {runner}(i: u32) {{
    if (i >= arrayLength(&output_words) / {outw}u) {{
        return;
    }}
    let r = {func}({args});{stores}
}}
"
                )
            },
            |k, runner| format!("\n        case {k}u: {{ {runner}(id.x); }}"),
        );
        format!(
            "{include}
@group(0) @binding(0) var<storage, read> input_words: array<u32>;
@group(0) @binding(1) var<storage, read_write> output_words: array<u32>;
@id(0) override {KERNEL_SELECT}: u32 = 0u;
{runners}
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {{
    switch {KERNEL_SELECT} {{{cases}
        default: {{}}
    }}
}}
"
        )
    }
}
