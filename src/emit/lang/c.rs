//! C99 (also valid C++): header-only, `static inline`, vectors as small structs whose
//! lanes the printer computes one by one, and public entry points over plain arrays:
//! `uint32_t unitpack_<id>_encode(const float v[3])`, `void unitpack_<id>_decode(uint32_t
//! code, float out[3])`, `_encode_float` / `_decode_float` over `float` arrays; codes of
//! two words are `uint64_t` (first word in the low half), codes of three `uint32_t[3]`
//! arrays (`void ..._encode(const float v[3], uint32_t out[3])`). The struct forms, named with a
//! `_v` suffix, are what the functions call among themselves.
//!
//! The arithmetic is exact only when the compiler keeps it as written: no `-ffast-math`,
//! no contraction (`-ffp-contract=off`; GCC contracts by default in GNU C modes), SSE
//! rather than x87 arithmetic (x87's excess precision is not supported).

use super::{Backend, FileOptions, KernelFn, Returns, scalar_names};
use crate::emit::lang::SpecView;
use crate::model::Kind;
use crate::model::trace::{Ty, UnOp};
use askama::Template;

pub struct C {
    /// Prefix of the vector struct names (`unitpack_vec3`).
    pub prefix: String,
    /// The include guard of the struct definitions, shared by every header.
    pub types_guard: String,
}

impl C {
    pub fn new(prefix: &str) -> C {
        let prefix = if prefix.is_empty() {
            "unitpack_"
        } else {
            prefix
        };
        C {
            prefix: prefix.to_string(),
            types_guard: format!("{}C_TYPES", crate::emit::lang::macro_prefix(prefix)),
        }
    }

    fn struct_name(&self, kind: Kind, lanes: u8) -> String {
        let (_, g, _) = scalar_names(kind);
        format!("{}{g}{lanes}", self.prefix)
    }

    /// The array-based signature of a public function and the body that calls its struct
    /// form `impl_name`.
    fn array_abi(
        &self,
        name: &str,
        impl_name: &str,
        params: &[(String, Ty)],
        ret: &Returns,
    ) -> (String, Vec<String>) {
        let mut sig = Vec::new();
        let mut body = Vec::new();
        let mut args = Vec::new();
        for (p, t) in params {
            match (t.kind, t.lanes) {
                (Kind::U32, 1) => {
                    sig.push(format!("uint32_t {p}"));
                    args.push(p.clone());
                }
                (Kind::F32, 1) => {
                    sig.push(format!("float {p}"));
                    args.push(p.clone());
                }
                (Kind::U32, 2) => {
                    sig.push(format!("uint64_t {p}"));
                    body.push(format!(
                        "const {} {p}_w = {{ (uint32_t){p}, (uint32_t)({p} >> 32) }};",
                        self.ty(*t)
                    ));
                    args.push(format!("{p}_w"));
                }
                (kind @ (Kind::F32 | Kind::U32), n) if n > 1 => {
                    sig.push(format!("const {} {p}[{n}]", self.ty(Ty { kind, lanes: 1 })));
                    let lanes: Vec<String> = (0..n).map(|i| format!("{p}[{i}]")).collect();
                    body.push(format!(
                        "const {} {p}_v = {{ {} }};",
                        self.ty(*t),
                        lanes.join(", ")
                    ));
                    args.push(format!("{p}_v"));
                }
                _ => unreachable!("public functions take codes, floats or float vectors"),
            }
        }
        let call = format!("{impl_name}({})", args.join(", "));
        if let Some(strukt) = &ret.name {
            // Several values: one output array per field, named after it.
            body.push(format!("const {} r = {call};", self.impl_name(strukt)));
            for (t, value) in ret.parts("r") {
                let field = value.trim_start_matches("r.");
                sig.push(format!(
                    "{} {field}[{}]",
                    self.ty(Ty::scalar(t.kind)),
                    t.lanes
                ));
                for (i, l) in super::LANES.iter().take(t.lanes as usize).enumerate() {
                    body.push(format!("{field}[{i}] = {value}.{l};"));
                }
            }
            return (format!("void {name}({})", sig.join(", ")), body);
        }
        let ret = ret.tys[0];
        let ret_ty = match (ret.kind, ret.lanes) {
            (Kind::U32, 1) => {
                body.push(format!("return {call};"));
                "uint32_t"
            }
            (Kind::U32, 2) => {
                body.push(format!("const {} r = {call};", self.ty(ret)));
                body.push("return (uint64_t)r.x | ((uint64_t)r.y << 32);".into());
                "uint64_t"
            }
            (kind @ (Kind::F32 | Kind::U32), n) if n > 1 => {
                sig.push(format!("{} out[{n}]", self.ty(Ty { kind, lanes: 1 })));
                body.push(format!("const {} r = {call};", self.ty(ret)));
                for (i, l) in super::LANES.iter().take(n as usize).enumerate() {
                    body.push(format!("out[{i}] = r.{l};"));
                }
                "void"
            }
            _ => unreachable!("public functions return codes or float vectors"),
        };
        (format!("{ret_ty} {name}({})", sig.join(", ")), body)
    }
}

#[derive(Template)]
#[template(path = "c.txt", escape = "none")]
struct File<'a> {
    header: &'a [String],
    specs: &'a [SpecView],
    types_guard: &'a str,
    prefix: &'a str,
    types: Vec<String>,
    types4: Vec<String>,
}

impl Backend for C {
    fn ty(&self, t: Ty) -> String {
        match (t.kind, t.lanes) {
            (Kind::F32, 1) => "float".into(),
            (Kind::U32, 1) => "uint32_t".into(),
            (Kind::Bool, 1) => "bool".into(),
            (k, n) => self.struct_name(k, n),
        }
    }
    fn float_suffix(&self) -> &'static str {
        "f"
    }
    fn unary(&self, op: UnOp) -> &'static str {
        match op {
            UnOp::Abs => "fabsf",
            UnOp::Sqrt => "sqrtf",
            UnOp::Floor => "floorf",
            // Ties to even in the default rounding mode, without raising inexact.
            UnOp::Round => "nearbyintf",
            UnOp::Neg | UnOp::Not => unreachable!("written as operators"),
        }
    }
    fn convert(&self, t: Ty, a: &str) -> String {
        let a = crate::emit::lang::printer::operand(
            a.to_string(),
            crate::emit::lang::printer::prec::UNARY,
        );
        format!("({}){a}", self.ty(t))
    }
    /// Through the header's memcpy helpers: the only bitcast valid in both C and C++.
    fn bitcast(&self, t: Ty, a: &str) -> String {
        match t.kind {
            Kind::U32 => format!("{}bits_of({a})", self.prefix),
            _ => format!("{}float_of({a})", self.prefix),
        }
    }
    fn splat(&self, t: Ty, x: &str) -> String {
        self.construct(t, &vec![x.to_string(); t.lanes as usize])
    }
    /// A brace initializer: valid in a declaration in both C99 and C++.
    fn construct(&self, _t: Ty, args: &[String]) -> String {
        format!("{{ {} }}", args.join(", "))
    }
    fn declare(&self, name: &str, t: Ty, expr: &str) -> String {
        format!("const {} {name} = {expr};", self.ty(t))
    }
    fn has_vectors(&self) -> bool {
        false
    }
    fn contracts_expressions(&self) -> bool {
        true
    }
    fn impl_name(&self, public: &str) -> String {
        format!("{public}_v")
    }
    fn public_abi(
        &self,
        name: &str,
        impl_name: &str,
        params: &[(String, Ty)],
        ret: &Returns,
    ) -> Option<(String, Vec<String>)> {
        Some(self.array_abi(name, impl_name, params, ret))
    }
    fn struct_def(&self, name: &str, fields: &[(&str, Ty)]) -> String {
        let fields: String = fields
            .iter()
            .map(|(f, t)| format!("\n    {} {f};", self.ty(*t)))
            .collect();
        format!("typedef struct {{{fields}\n}} {name};")
    }
    /// A brace initializer, valid in a declaration in both C99 and C++.
    fn return_struct(&self, name: &str, local: &str, values: &[String]) -> Vec<String> {
        vec![
            format!("const {name} {local} = {{ {} }};", values.join(", ")),
            format!("return {local};"),
        ]
    }
    fn render(&self, specs: &[SpecView], opts: &FileOptions) -> String {
        let typedefs = |sizes: &[u8]| -> Vec<String> {
            let mut out = Vec::new();
            for kind in [Kind::F32, Kind::U32, Kind::Bool] {
                for &n in sizes {
                    let lanes = ["x", "y", "z", "w"][..n as usize].join(", ");
                    out.push(format!(
                        "typedef struct {{ {} {lanes}; }} {};",
                        self.ty(Ty::scalar(kind)),
                        self.struct_name(kind, n)
                    ));
                }
            }
            out
        };
        let types = typedefs(&[2, 3]);
        // Four-lane structs (a texel layout's channels) under a guard of their own, in
        // the files that use them: a header from before they existed, included first,
        // has already defined the common guard.
        let four = [Kind::F32, Kind::U32, Kind::Bool].map(|k| self.struct_name(k, 4));
        let uses_four = specs.iter().flat_map(|s| &s.functions).any(|f| {
            let text = |t: &str| four.iter().any(|n| t.contains(n.as_str()));
            text(&f.ret_ty) || f.params.iter().any(|p| text(&p.1)) || f.body.iter().any(|l| text(l))
        }) || specs
            .iter()
            .flat_map(|s| &s.types)
            .any(|t| four.iter().any(|n| t.contains(n.as_str())));
        File {
            header: opts.header,
            specs,
            types_guard: &self.types_guard,
            prefix: &self.prefix,
            types,
            types4: if uses_four {
                typedefs(&[4])
            } else {
                Vec::new()
            },
        }
        .render()
        .expect("C template renders")
    }
    /// The test driver: see [`driver`].
    fn kernel(&self, include: &str, funcs: &[KernelFn]) -> String {
        driver(include, funcs)
    }
}

/// The one symbol a [`driver`] exports.
pub const DRIVER_ENTRY: &str = "unitpack_verify_run";

/// A test driver for several functions of one include, compiled once as a shared library
/// that the verifier loads: its one exported function, [`DRIVER_ENTRY`]
/// `(index, in_words, out_words, in, out, n)`, applies function number `index` through
/// its public array signature to `n` items of raw words (each function's arguments one
/// after the other) and writes the result words to `out`. In the verifying process, so
/// that no item crosses a pipe. Returns 0; 2 for an index out of range, 3 when the item
/// widths are not the function's, touching nothing in either case.
pub fn driver(include: &str, funcs: &[KernelFn]) -> String {
    let mut runners = String::new();
    for (k, (func, params, ret)) in funcs.iter().enumerate() {
        let inw: usize = params.iter().map(|p| p.lanes as usize).sum();
        let outw = ret.words();
        let mut body = vec![];
        let mut args = vec![];
        let mut first = 0;
        for (j, param) in params.iter().enumerate() {
            let n = param.lanes as usize;
            args.push(match (param.kind, param.lanes) {
                (Kind::U32, 1) => format!("w[{first}]"),
                (Kind::U32, 2) => {
                    format!("(uint64_t)w[{first}] | ((uint64_t)w[{}] << 32)", first + 1)
                }
                (Kind::U32, _) => format!("&w[{first}]"),
                (_, 1) => {
                    body.push(format!("float a{j};"));
                    body.push(format!("memcpy(&a{j}, &w[{first}], sizeof a{j});"));
                    format!("a{j}")
                }
                _ => {
                    body.push(format!("float a{j}[{n}];"));
                    body.push(format!("memcpy(a{j}, &w[{first}], sizeof a{j});"));
                    format!("a{j}")
                }
            });
            first += n;
        }
        let arg = args.join(", ");
        if ret.name.is_some() {
            // One output array per field, of the field's element type as the public
            // signature declares it, copied out one after the other.
            let mut outs = Vec::new();
            let mut word = 0;
            for (j, t) in ret.tys.iter().enumerate() {
                let element = if t.kind == Kind::U32 {
                    "uint32_t"
                } else {
                    "float"
                };
                body.push(format!("{element} o{j}[{}];", t.lanes));
                outs.push(format!("o{j}"));
            }
            body.push(format!("{func}({arg}, {});", outs.join(", ")));
            for (j, t) in ret.tys.iter().enumerate() {
                body.push(format!("memcpy(&r[{word}], o{j}, sizeof o{j});"));
                word += t.lanes as usize;
            }
        } else {
            let ret = ret.tys[0];
            match (ret.kind, ret.lanes) {
                (Kind::U32, 1) => body.push(format!("r[0] = {func}({arg});")),
                (Kind::U32, 2) => {
                    body.push(format!("const uint64_t c = {func}({arg});"));
                    body.push("r[0] = (uint32_t)c;".into());
                    body.push("r[1] = (uint32_t)(c >> 32);".into());
                }
                (Kind::U32, _) => body.push(format!("{func}({arg}, r);")),
                _ => {
                    body.push(format!("float o[{outw}];"));
                    body.push(format!("{func}({arg}, o);"));
                    body.push("memcpy(r, o, sizeof o);".into());
                }
            }
        }
        let body = body.join("\n        ");
        runners.push_str(&format!(
            "
static void run{k}(const uint32_t *in, uint32_t *out, size_t n) {{
    for (size_t i = 0; i < n; i++) {{
        const uint32_t *w = &in[i * {inw}];
        uint32_t *r = &out[i * {outw}];
        {body}
    }}
}}
"
        ));
    }
    // A caller's item widths that are not the function's would make it read or write
    // past the buffers: refused (3) before any item is touched.
    let cases: String = funcs
        .iter()
        .enumerate()
        .map(|(k, (_, params, ret))| {
            let inw: usize = params.iter().map(|p| p.lanes as usize).sum();
            format!(
                "\n    case {k}:\n        if (in_words != {inw} || out_words != {}) return 3;\n        run{k}(in, out, n);\n        return 0;",
                ret.words()
            )
        })
        .collect();
    format!(
        "#include <stddef.h>
#include <string.h>
{include}
{runners}
#ifdef __cplusplus
extern \"C\"
#endif
int {DRIVER_ENTRY}(unsigned index, unsigned in_words, unsigned out_words,
    const uint32_t *in, uint32_t *out, size_t n);

int {DRIVER_ENTRY}(unsigned index, unsigned in_words, unsigned out_words,
    const uint32_t *in, uint32_t *out, size_t n) {{
    switch (index) {{{cases}
    default:
        return 2;
    }}
}}
"
    )
}
