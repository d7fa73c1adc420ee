//! One module per target language, as naga's `back/`: each owns its syntax (types,
//! literals, selects, statements, precise qualifiers), its file template and the compute
//! kernel (or test driver) that verification wraps around an include. The shared
//! [`super::printer`] walks a traced function once and asks the language for text.

pub mod c;
pub mod glsl;
pub mod hlsl;
pub mod wgsl;

pub mod layout;
pub mod literal;
pub mod printer;

use crate::model::Kind;
use crate::model::trace::{BinOp, Op, Ty, UnOp};
use literal::f32_literal;

/// Macros are global in GLSL, HLSL and C: without a prefix they still carry the tool's name.
pub fn macro_prefix(prefix: &str) -> String {
    if prefix.is_empty() {
        "UNITPACK_".into()
    } else {
        prefix.to_ascii_uppercase()
    }
}

/// C's public array-based entry point of a function whose struct form is [`FnView::name`].
pub struct Wrapper {
    /// The public name.
    pub name: String,
    pub signature: String,
    pub body: Vec<String>,
}

pub struct FnView {
    pub doc: Vec<String>,
    pub name: String,
    pub params: Vec<(String, String)>,
    pub ret_ty: String,
    pub body: Vec<String>,
    pub wrapper: Option<Wrapper>,
}

pub struct SpecView {
    pub guard: String,
    pub title: String,
    /// Paragraphs under the title: what the spec's functions share.
    pub doc: Vec<String>,
    /// Whether a function of the spec is marked "Portable", so that the file header says
    /// what the mark means.
    pub portable: bool,
    /// The definitions of the structs its functions return ([`Backend::struct_def`]),
    /// each once, before the functions.
    pub types: Vec<String>,
    pub functions: Vec<FnView>,
}

/// What a file template needs besides the functions.
pub struct FileOptions<'a> {
    /// Lines of the file header (without comment markers).
    pub header: &'a [String],
    pub prefix: &'a str,
    /// WGSL only: the `#define_import_path` for naga_oil / Bevy composition.
    pub import_path: Option<&'a str>,
}

/// A target language.
pub trait Backend {
    /// The type of a value.
    fn ty(&self, t: Ty) -> String;
    /// Suffix of a float literal (`1.0f` in WGSL and C).
    fn float_suffix(&self) -> &'static str {
        ""
    }
    /// The f32 constant `v` as the language writes it: [`f32_literal`] and the suffix.
    fn float_constant(&self, v: f32) -> String {
        format!("{}{}", f32_literal(v), self.float_suffix())
    }
    /// The builtin for a unary operation other than `-` and `!`.
    fn unary(&self, op: UnOp) -> &'static str {
        match op {
            UnOp::Abs => "abs",
            UnOp::Sqrt => "sqrt",
            UnOp::Floor => "floor",
            UnOp::Round => "round",
            UnOp::Neg | UnOp::Not => unreachable!("written as operators"),
        }
    }
    /// A comparison of vectors written as a function (GLSL's `lessThan`), if the language
    /// has no operator for it.
    fn vector_compare(&self, _op: BinOp) -> Option<&'static str> {
        None
    }
    /// Whether `a < b` is written `b > a`: the same comparison (false for NaN either way),
    /// without the `<` after an identifier that a template-list scanner may pair with a
    /// later `>` ([`crate::emit::lang::wgsl`]).
    fn less_than_as_greater(&self) -> bool {
        false
    }
    /// `m ? t : f`, lane-wise when `mask_is_vector`.
    fn select(&self, _ty: Ty, _mask_is_vector: bool, m: &str, t: &str, f: &str) -> String {
        format!("{m} ? {t} : {f}")
    }
    /// A value conversion to type `t`.
    fn convert(&self, t: Ty, a: &str) -> String {
        format!("{}({a})", self.ty(t))
    }
    /// A reinterpretation of the bits of `a` as type `t` (f32 ↔ u32).
    fn bitcast(&self, t: Ty, a: &str) -> String;
    /// A vector with every lane `x`.
    fn splat(&self, t: Ty, x: &str) -> String {
        format!("{}({x})", self.ty(t))
    }
    /// A vector from its lanes (or shorter vectors).
    fn construct(&self, t: Ty, args: &[String]) -> String {
        format!("{}({})", self.ty(t), self.arguments(args))
    }
    /// A call of function `name`.
    fn call(&self, name: &str, args: &[String]) -> String {
        format!("{name}({})", self.arguments(args))
    }
    /// An argument list's text.
    fn arguments(&self, args: &[String]) -> String {
        args.join(", ")
    }
    /// One statement declaring `name`.
    fn declare(&self, name: &str, t: Ty, expr: &str) -> String;
    /// Whether float declarations are `precise` (or may be made so): every float
    /// operation must then lie in a float declaration's initializer, which `precise`
    /// covers, rather than in a call's argument, a non-float declaration or a `return`.
    fn precise_declarations(&self) -> bool {
        false
    }
    /// The operands of operation `op` (of type `t`) that the language evaluates only on
    /// demand: a `?:`'s two values, `&&`'s and `||`'s right operand. glslang compiles such
    /// an operand to a branch unless it is a name or a literal, so the printer folds
    /// nothing into one (docs/design/printer.md).
    fn lazy_operands(&self, _op: &Op, _t: Ty, _mask_is_vector: bool) -> &'static [usize] {
        &[]
    }
    /// Whether the compiler may contract `a*b + c` written as one expression but not
    /// across statements (C: clang's default `-ffp-contract=on`).
    fn contracts_expressions(&self) -> bool {
        false
    }
    /// Whether vectors are values with lane-wise operators. Where they are not (C),
    /// the printer writes each lane of a vector operation as its own expression.
    fn has_vectors(&self) -> bool {
        true
    }
    /// The name a function is defined and called by: the public name, or for C the
    /// struct form behind the array-based public function.
    fn impl_name(&self, public: &str) -> String {
        public.to_string()
    }
    /// For C, the public array-based signature and body of a public function.
    fn public_abi(
        &self,
        _name: &str,
        _impl_name: &str,
        _params: &[(String, Ty)],
        _ret: &Returns,
    ) -> Option<(String, Vec<String>)> {
        None
    }
    /// The definition of the struct `name` that a function returning several values
    /// returns ([`crate::model::trace::Shape`]), with its fields in order.
    fn struct_def(&self, name: &str, fields: &[(&str, Ty)]) -> String;
    /// The statements that return `values` as the struct `name`; where the language
    /// builds it in a declaration, the declared value is called `local`.
    fn return_struct(&self, name: &str, _local: &str, values: &[String]) -> Vec<String> {
        vec![format!("return {name}({});", values.join(", "))]
    }
    /// The complete include.
    fn render(&self, specs: &[SpecView], opts: &FileOptions) -> String;
    /// A program around `include` that applies any one of `funcs` (name, parameter types
    /// whose words follow one another in an item, result type) to every item of raw
    /// 32-bit words: for the shader languages a compute shader with the binding contract
    /// of `crate::verify::gpu` whose specialization constant 0 ([`KERNEL_SELECT`]) is the
    /// index of the function it runs, for C a test driver taking the index as an argument
    /// (`c::driver`). One program per include: each front end and compiler reads the
    /// include once, not once per function.
    fn kernel(&self, include: &str, funcs: &[KernelFn]) -> String;
}

/// What a function returns: one value (`fields` empty), or one value per field of a
/// struct ([`crate::model::trace::Shape`]), in order.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Returns {
    pub tys: Vec<Ty>,
    pub fields: Vec<&'static str>,
    /// The struct's emitted name, where there are fields.
    pub name: Option<String>,
}

impl Returns {
    /// One value of type `t`.
    pub fn one(t: Ty) -> Returns {
        Returns {
            tys: vec![t],
            fields: Vec::new(),
            name: None,
        }
    }

    /// The returned values of a traced function whose names carry `prefix` (the
    /// function's and its struct's: `unitpack_qtangent64_`).
    pub fn of(f: &crate::model::trace::Func, prefix: &str) -> Returns {
        Returns {
            tys: f.ret_tys.clone(),
            fields: f.shape.map_or_else(Vec::new, |s| s.fields.to_vec()),
            name: f.shape.map(|s| format!("{prefix}{}", s.name)),
        }
    }

    /// The result's type in `lang`.
    pub fn ty(&self, lang: &dyn Backend) -> String {
        match &self.name {
            Some(n) => n.clone(),
            None => lang.ty(self.tys[0]),
        }
    }

    /// The kind of every value (a function's values are all floats or all integers).
    pub fn kind(&self) -> Kind {
        let k = self.tys[0].kind;
        assert!(self.tys.iter().all(|t| t.kind == k), "mixed result kinds");
        k
    }

    /// The words every item's result takes.
    pub fn words(&self) -> usize {
        self.tys.iter().map(|t| t.lanes as usize).sum()
    }

    /// Each value's type and how it is read from the result `r`: `r` itself, or `r.field`.
    pub fn parts<'a>(&'a self, r: &'a str) -> impl Iterator<Item = (Ty, String)> + 'a {
        self.tys
            .iter()
            .enumerate()
            .map(move |(i, &t)| match self.fields.get(i) {
                Some(f) => (t, format!("{r}.{f}")),
                None => (t, r.to_string()),
            })
    }
}

/// A function a [`Backend::kernel`] can apply: its name, parameter types and results.
pub type KernelFn<'a> = (&'a str, Vec<Ty>, Returns);

/// The kernel's selector: specialization constant 0 (WGSL `@id(0) override`), whose value
/// is the index of the function a pipeline runs. A constant, so that the driver compiles
/// that function's code alone: a selector read at run time would have a CPU driver run
/// every function's code under masks.
pub const KERNEL_SELECT: &str = "unitpack_verify_select";

/// A select of integer or boolean vectors as a vector of `T` built from one scalar select
/// per lane: `T(sel(m.x, t.x, f.x), …)`, for GLSL before 4.50 and WGSL that naga writes as
/// such GLSL, where a vector select takes float vectors alone. Each operand appears once per
/// lane, so the printer names any that is not a name or a literal already.
pub(crate) fn select_by_lane(
    ty: &str,
    lanes: u8,
    operands: [&str; 3],
    scalar: impl Fn([&str; 3]) -> String,
) -> String {
    let lane = |e: &str, i: usize| {
        let c = ["x", "y", "z", "w"][i];
        if e.chars().all(|ch| ch.is_ascii_alphanumeric() || ch == '_') {
            format!("{e}.{c}")
        } else {
            format!("({e}).{c}")
        }
    };
    let lanes: Vec<String> = (0..usize::from(lanes))
        .map(|i| {
            let [m, t, f] = operands.map(|e| lane(e, i));
            scalar([&m, &t, &f])
        })
        .collect();
    format!("{ty}({})", lanes.join(", "))
}

/// A selecting kernel's runners and the cases of its switch on [`KERNEL_SELECT`], one of
/// each per function in order: `runner(name, function)` writes the runner `name`, which
/// applies `function` to item `i`; `case(k, name)` the case that calls it.
pub(crate) fn selecting_parts(
    funcs: &[KernelFn],
    runner: impl Fn(&str, &KernelFn) -> String,
    case: impl Fn(usize, &str) -> String,
) -> (String, String) {
    let (mut runners, mut cases) = (String::new(), String::new());
    for (k, f) in funcs.iter().enumerate() {
        let name = format!("unitpack_verify_{k}");
        runners.push_str(&runner(&name, f));
        cases.push_str(&case(k, &name));
    }
    (runners, cases)
}

/// `vec3<f32>`-style names for WGSL, `vec3`/`uvec3`/`bvec3` for GLSL, `float3` for HLSL.
pub(crate) fn scalar_names(kind: Kind) -> (&'static str, &'static str, &'static str) {
    match kind {
        Kind::F32 => ("f32", "vec", "float"),
        Kind::U32 => ("u32", "uvec", "uint"),
        Kind::Bool => ("bool", "bvec", "bool"),
    }
}

/// The word-level view of a value crossing the kernel boundary: `lanes` words.
pub(crate) const LANES: [&str; 4] = ["x", "y", "z", "w"];

/// The pieces every compute kernel shares: the arguments loaded one after the other from
/// `input_words` (each bit-cast by `as_float` where it is float), and the statements
/// storing the words of each value of the result `r` to `output_words`, each bit-cast by
/// `as_bits` (value, its type) and declared by `declare_bits` (name, type, expression).
pub(crate) struct KernelIo {
    pub args: String,
    pub stores: String,
}

pub(crate) fn kernel_io(
    lang: &dyn Backend,
    params: &[Ty],
    ret: &Returns,
    as_float: impl Fn(&str, Ty) -> String,
    as_bits: impl Fn(&str, Ty) -> String,
    declare_bits: impl Fn(&str, Ty, &str) -> String,
) -> KernelIo {
    let inw: usize = params.iter().map(|p| p.lanes as usize).sum();
    let outw = ret.words();
    let mut first = 0;
    let args: Vec<String> = params
        .iter()
        .map(|&param| {
            let words: Vec<String> = (first..first + param.lanes as usize)
                .map(|k| format!("input_words[i * {inw}u + {k}u]"))
                .collect();
            first += words.len();
            let loaded = if words.len() == 1 {
                words[0].clone()
            } else {
                let u = lang.ty(Ty {
                    kind: Kind::U32,
                    lanes: param.lanes,
                });
                format!("{u}({})", words.join(", "))
            };
            match param.kind {
                Kind::F32 => as_float(&loaded, param),
                _ => loaded,
            }
        })
        .collect();
    let mut stores = String::new();
    let mut word = 0;
    let single = ret.tys.len() == 1;
    for (j, (t, value)) in ret.parts("r").enumerate() {
        let rb = if single {
            "rb".to_string()
        } else {
            format!("rb{j}")
        };
        let u = Ty {
            kind: Kind::U32,
            lanes: t.lanes,
        };
        let bits = match t.kind {
            Kind::F32 => as_bits(&value, t),
            _ => value,
        };
        stores.push_str(&format!("\n    {}", declare_bits(&rb, u, &bits)));
        for (k, l) in LANES.iter().take(t.lanes as usize).enumerate() {
            let lane = if t.lanes == 1 {
                String::new()
            } else {
                format!(".{l}")
            };
            stores.push_str(&format!(
                "\n    output_words[i * {outw}u + {}u] = {rb}{lane};",
                word + k
            ));
        }
        word += t.lanes as usize;
    }
    KernelIo {
        args: args.join(", "),
        stores,
    }
}
