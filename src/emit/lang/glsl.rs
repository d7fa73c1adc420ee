//! GLSL (450, 330, ES 300): `lessThan` and friends for vector comparisons, `mix` for
//! lane-wise float selects (integer ones lane by lane), `roundEven` (GLSL's `round` may
//! round halves either way), and a `PRECISE` macro in front of float declarations that
//! users define as `precise` where the language has it.

use super::{
    Backend, FileOptions, KERNEL_SELECT, KernelFn, KernelIo, Returns, kernel_io, scalar_names,
    selecting_parts,
};
use crate::emit::lang::SpecView;
use crate::model::Kind;
use crate::model::trace::{BinOp, Op, Ty, UnOp};
use askama::Template;

/// What a selecting kernel is compiled for: SPIR-V for Vulkan (glslang, naga), with the
/// function chosen by a specialization constant; or an OpenGL 4.3 driver's own GLSL
/// compiler, with a uniform (GLSL for OpenGL has no specialization constants) and the
/// include's statements `precise` or not.
pub enum Target {
    Vulkan,
    OpenGl { precise: bool },
}

pub struct Glsl {
    /// The macro in front of float declarations (`UNITPACK_PRECISE`).
    pub precise_macro: String,
}

impl Glsl {
    pub fn new(prefix: &str) -> Glsl {
        Glsl {
            precise_macro: precise_macro(prefix),
        }
    }

    /// The OpenGL form of [`Backend::kernel`]: `KERNEL_SELECT` is a uniform.
    pub fn gl_kernel(&self, include: &str, funcs: &[KernelFn], precise: bool) -> String {
        self.selecting_kernel(include, funcs, &Target::OpenGl { precise })
    }

    /// A kernel's argument reads and output stores, the words reinterpreted by GLSL's
    /// bit casts: shared by the Vulkan and the WebGL kernels.
    fn io(&self, params: &[Ty], ret: &Returns) -> KernelIo {
        kernel_io(
            self,
            params,
            ret,
            |l, _| format!("uintBitsToFloat({l})"),
            |v, _| format!("floatBitsToUint({v})"),
            |name, t, e| format!("{} {name} = {e};", self.ty(t)),
        )
    }

    /// The WebGL 2 form of a kernel, for one function: a GLSL ES 3.00 vertex shader (WebGL
    /// has no compute shaders) that reads one item's words from the integer attributes
    /// `unitpack_in_K` at location K, four words each, and writes its output words to the
    /// flat varyings `unitpack_out_K`, which transform feedback captures
    /// (`crate::verify::browser`). The include is as a user's: ES 3.00 has no `precise`.
    pub fn webgl_kernel(&self, include: &str, (func, params, ret): &KernelFn) -> String {
        let (inw, outw): (usize, usize) =
            (params.iter().map(|p| p.lanes as usize).sum(), ret.words());
        let KernelIo { args, stores } = self.io(params, ret);
        let vectors = |words: usize| words.div_ceil(4);
        let attributes: String = (0..vectors(inw))
            .map(|k| format!("layout(location = {k}) in uvec4 unitpack_in_{k};\n"))
            .collect();
        let varyings: String = (0..vectors(outw))
            .map(|k| format!("flat out uvec4 unitpack_out_{k};\n"))
            .collect();
        let loaded: Vec<String> = (0..inw)
            .map(|k| format!("unitpack_in_{}.{}", k / 4, super::LANES[k % 4]))
            .collect();
        let written: String = (0..vectors(outw))
            .map(|k| {
                let lanes: Vec<String> = (4 * k..4 * k + 4)
                    .map(|w| {
                        if w < outw {
                            format!("output_words[{w}]")
                        } else {
                            "0u".into()
                        }
                    })
                    .collect();
                format!("\n    unitpack_out_{k} = uvec4({});", lanes.join(", "))
            })
            .collect();
        format!(
            "#version 300 es
precision highp float;
precision highp int;
{attributes}{varyings}
{include}
void main() {{
    const uint i = 0u;
    uint input_words[{inw}] = uint[{inw}]({});
    uint output_words[{outw}];
    {} r = {func}({args});{stores}{written}
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}}
",
            loaded.join(", "),
            ret.ty(self)
        )
    }

    fn selecting_kernel(&self, include: &str, funcs: &[KernelFn], target: &Target) -> String {
        let (runners, cases) = selecting_parts(
            funcs,
            |runner, (func, params, ret)| {
                let outw = ret.words();
                let KernelIo { args, stores } = self.io(params, ret);
                format!(
                    "
void {runner}(uint i) {{
    if (i >= uint(output_words.length()) / {outw}u) {{
        return;
    }}
    {} r = {func}({args});{stores}
}}
",
                    ret.ty(self)
                )
            },
            |k, runner| {
                format!(
                    "\n    case {k}u:\n        {runner}(gl_GlobalInvocationID.x);\n        break;"
                )
            },
        );
        let (head, set, select) = match target {
            Target::Vulkan => (
                "#version 450\n".to_string(),
                "set = 0, ",
                format!("layout(constant_id = 0) const uint {KERNEL_SELECT} = 0u;"),
            ),
            Target::OpenGl { precise } => (
                format!(
                    "#version 430\n{}",
                    if *precise {
                        format!("#define {} precise\n", self.precise_macro)
                    } else {
                        String::new()
                    }
                ),
                "",
                format!("uniform uint {KERNEL_SELECT};"),
            ),
        };
        format!(
            "{head}layout(local_size_x = 64) in;
layout(std430, {set}binding = 0) readonly buffer InputWords {{ uint input_words[]; }};
layout(std430, {set}binding = 1) buffer OutputWords {{ uint output_words[]; }};
{select}

{include}{runners}
void main() {{
    switch ({KERNEL_SELECT}) {{{cases}
    default:
        break;
    }}
}}
"
        )
    }
}

/// The GLSL macro in front of float declarations: empty by default (GLSL 330 and ES 300
/// have no `precise`), `precise` where the user defines it so.
pub fn precise_macro(prefix: &str) -> String {
    format!("{}PRECISE", crate::emit::lang::macro_prefix(prefix))
}

#[derive(Template)]
#[template(path = "glsl.txt", escape = "none")]
struct File<'a> {
    header: &'a [String],
    specs: &'a [SpecView],
    precise_macro: &'a str,
}

impl Backend for Glsl {
    fn ty(&self, t: Ty) -> String {
        let (_, g, h) = scalar_names(t.kind);
        match t.lanes {
            1 => h.to_string(),
            n => format!("{g}{n}"),
        }
    }
    fn unary(&self, op: UnOp) -> &'static str {
        match op {
            UnOp::Round => "roundEven",
            UnOp::Abs => "abs",
            UnOp::Sqrt => "sqrt",
            UnOp::Floor => "floor",
            UnOp::Neg | UnOp::Not => unreachable!("written as operators"),
        }
    }
    fn vector_compare(&self, op: BinOp) -> Option<&'static str> {
        match op {
            BinOp::Lt => Some("lessThan"),
            BinOp::Le => Some("lessThanEqual"),
            BinOp::Gt => Some("greaterThan"),
            BinOp::Ge => Some("greaterThanEqual"),
            BinOp::Eq => Some("equal"),
            _ => None,
        }
    }
    /// `mix` with a boolean vector selects floats everywhere, but integers only from GLSL
    /// 4.50 (or with `GL_EXT_shader_integer_mix`): integer vectors select lane by lane.
    fn select(&self, ty: Ty, mask_is_vector: bool, m: &str, t: &str, f: &str) -> String {
        if !mask_is_vector {
            return format!("{m} ? {t} : {f}");
        }
        if ty.kind == Kind::F32 {
            return format!("mix({f}, {t}, {m})");
        }
        super::select_by_lane(&self.ty(ty), ty.lanes, [m, t, f], |[m, t, f]| {
            format!("{m} ? {t} : {f}")
        })
    }
    fn bitcast(&self, t: Ty, a: &str) -> String {
        match t.kind {
            Kind::U32 => format!("floatBitsToUint({a})"),
            _ => format!("uintBitsToFloat({a})"),
        }
    }
    fn struct_def(&self, name: &str, fields: &[(&str, Ty)]) -> String {
        let fields: String = fields
            .iter()
            .map(|(f, t)| format!("\n    {} {f};", self.ty(*t)))
            .collect();
        format!("struct {name} {{{fields}\n}};")
    }
    /// Float results carry the precise macro, so drivers that contract `a*b + c` into an
    /// fma must not do so here where the user defines it as `precise`.
    fn declare(&self, name: &str, t: Ty, expr: &str) -> String {
        let q = if t.kind == Kind::F32 {
            format!("{} ", self.precise_macro)
        } else {
            String::new()
        };
        format!("{q}{} {name} = {expr};", self.ty(t))
    }
    fn precise_declarations(&self) -> bool {
        true
    }
    /// `?:` (scalar selects, integer lanes) and `&&`, `||`: GLSL evaluates them lazily.
    fn lazy_operands(&self, op: &Op, t: Ty, mask_is_vector: bool) -> &'static [usize] {
        match op {
            Op::Select if !mask_is_vector || t.kind != Kind::F32 => &[1, 2],
            Op::Bin(BinOp::And | BinOp::Or) => &[1],
            _ => &[],
        }
    }
    fn render(&self, specs: &[SpecView], opts: &FileOptions) -> String {
        File {
            header: opts.header,
            specs,
            precise_macro: &self.precise_macro,
        }
        .render()
        .expect("GLSL template renders")
    }
    /// A `#version 450` compute shader; the include goes after the version line.
    fn kernel(&self, include: &str, funcs: &[KernelFn]) -> String {
        self.selecting_kernel(include, funcs, &Target::Vulkan)
    }
}
