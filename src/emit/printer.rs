//! Prints one traced function as statements of a target language.
//!
//! Every operation becomes one named `let`, in the model's evaluation order, so nothing is
//! reassociated or reordered; only literals, parameters, swizzles and literal vectors are
//! written inline. Values nothing returns are dropped (the tracer leaves the scalar lanes
//! it fused into vector operations behind).

use super::Lang;
use crate::model::Kind;
use crate::model::trace::{BinOp, Func, Op, Ref, Ty, UnOp};
use std::collections::HashSet;

/// A function ready for a template: signature pieces and body lines.
pub struct Printed {
    pub name: String,
    pub params: Vec<(String, String)>,
    pub ret_ty: String,
    pub body: Vec<String>,
}

const LANE: [char; 4] = ['x', 'y', 'z', 'w'];

pub fn ty(lang: Lang, t: Ty) -> String {
    let (w, g, h) = match t.kind {
        Kind::F32 => ("f32", "vec", "float"),
        Kind::U32 => ("u32", "uvec", "uint"),
        Kind::Bool => ("bool", "bvec", "bool"),
    };
    match (lang, t.lanes) {
        (Lang::Wgsl, 1) => w.to_string(),
        (Lang::Wgsl, n) => format!("vec{n}<{w}>"),
        (Lang::Glsl, 1) => match t.kind {
            Kind::F32 => "float".into(),
            Kind::U32 => "uint".into(),
            Kind::Bool => "bool".into(),
        },
        (Lang::Glsl, n) => format!("{g}{n}"),
        (Lang::Hlsl, 1) => h.to_string(),
        (Lang::Hlsl, n) => format!("{h}{n}"),
    }
}

/// The shortest decimal that reads back as exactly `v`, both directly and through f64
/// (compilers that parse literals as double and then narrow must land on the same f32).
pub fn f32_literal(lang: Lang, v: f32) -> String {
    assert!(
        v.is_finite(),
        "non-finite literal {v}: compare against f32::MAX instead"
    );
    let exact = |s: &str| {
        s.parse::<f32>().map(f32::to_bits) == Ok(v.to_bits())
            && s.parse::<f64>().map(|d| (d as f32).to_bits()) == Ok(v.to_bits())
    };
    let mut s = format!("{v:?}");
    if !exact(&s) {
        s = (9..=17)
            .map(|p| format!("{:.*e}", p - 1, v))
            .find(|s| exact(s))
            .expect("f32 round trip");
    }
    if !s.contains(['.', 'e']) {
        s.push_str(".0");
    }
    match lang {
        Lang::Wgsl => format!("{s}f"),
        _ => s,
    }
}

fn lanes_str(l: &[u8]) -> String {
    l.iter().map(|i| LANE[*i as usize]).collect()
}

struct Ctx<'a> {
    lang: Lang,
    select_macro: &'a str,
    precise_macro: &'a str,
    f: &'a Func,
    names: Vec<Option<String>>,
    fn_name: &'a dyn Fn(&str) -> String,
}

impl Ctx<'_> {
    fn inline(&self, id: usize) -> bool {
        let n = &self.f.nodes[id];
        match &n.op {
            Op::ConstF(_) | Op::ConstU(_) | Op::Param(_) | Op::Swizzle(_) => true,
            Op::Construct => n.args.iter().all(|a| {
                matches!(
                    self.f.nodes[a.node as usize].op,
                    Op::ConstF(_) | Op::ConstU(_)
                )
            }),
            _ => false,
        }
    }

    /// An operand as text: a name, a literal, or a lane of a vector.
    fn r(&self, r: Ref) -> String {
        let base = self.value(r.node as usize);
        match r.lane {
            Some(l) => format!("{}.{}", base, LANE[l as usize]),
            None => base,
        }
    }

    fn value(&self, id: usize) -> String {
        if let Some(n) = &self.names[id] {
            return n.clone();
        }
        self.expr(id)
    }

    /// Construct arguments, with runs of consecutive lanes of one vector written as that
    /// vector or a swizzle of it (`vec3(xy, z)` rather than `vec3(xy.x, xy.y, z)`).
    fn construct_args(&self, args: &[Ref]) -> Vec<String> {
        let mut out = Vec::new();
        let mut i = 0;
        while i < args.len() {
            let a = args[i];
            if let Some(l0) = a.lane {
                let mut j = i + 1;
                while j < args.len()
                    && args[j].node == a.node
                    && args[j].lane == Some(l0 + (j - i) as u8)
                {
                    j += 1;
                }
                if j - i > 1 {
                    let src = self.value(a.node as usize);
                    let lanes: Vec<u8> = (l0..l0 + (j - i) as u8).collect();
                    let whole = l0 == 0 && self.f.nodes[a.node as usize].ty.lanes as usize == j - i;
                    out.push(if whole {
                        src
                    } else {
                        format!("{src}.{}", lanes_str(&lanes))
                    });
                    i = j;
                    continue;
                }
            }
            out.push(self.r(a));
            i += 1;
        }
        out
    }

    fn expr(&self, id: usize) -> String {
        let lang = self.lang;
        let n = &self.f.nodes[id];
        let a = |i: usize| self.r(n.args[i]);
        let is_vec = n.ty.lanes > 1;
        match &n.op {
            Op::Param(i) => self.f.params[*i].0.clone(),
            Op::ConstF(v) => f32_literal(lang, *v),
            Op::ConstU(v) => format!("{v}u"),
            Op::Un(u) => {
                let f = match u {
                    UnOp::Neg => return format!("-{}", a(0)),
                    UnOp::Not => return format!("!{}", a(0)),
                    UnOp::Abs => "abs",
                    UnOp::Sqrt => "sqrt",
                    UnOp::Floor => "floor",
                    // GLSL's round() may round halves either way; roundEven is exact.
                    UnOp::Round if lang == Lang::Glsl => "roundEven",
                    UnOp::Round => "round",
                };
                format!("{f}({})", a(0))
            }
            Op::Bin(b) => {
                let arg_vec = self.f.ty_of(n.args[0]).lanes > 1;
                if lang == Lang::Glsl && arg_vec {
                    let f = match b {
                        BinOp::Lt => Some("lessThan"),
                        BinOp::Le => Some("lessThanEqual"),
                        BinOp::Gt => Some("greaterThan"),
                        BinOp::Ge => Some("greaterThanEqual"),
                        BinOp::Eq => Some("equal"),
                        _ => None,
                    };
                    if let Some(f) = f {
                        return format!("{f}({}, {})", a(0), a(1));
                    }
                }
                let op = match b {
                    BinOp::Add => "+",
                    BinOp::Sub => "-",
                    BinOp::Mul => "*",
                    BinOp::Div => "/",
                    BinOp::And => "&&",
                    BinOp::Or => "||",
                    BinOp::BitAnd => "&",
                    BinOp::BitOr => "|",
                    BinOp::Lt => "<",
                    BinOp::Le => "<=",
                    BinOp::Gt => ">",
                    BinOp::Ge => ">=",
                    BinOp::Eq => "==",
                };
                // `x - -1.0` reads badly and `x--1` does not parse: parenthesize.
                let paren = |s: String| {
                    if s.starts_with('-') {
                        format!("({s})")
                    } else {
                        s
                    }
                };
                format!("{} {op} {}", paren(a(0)), paren(a(1)))
            }
            Op::Shl(s) => format!("{} << {s}u", a(0)),
            Op::Shr(s) => format!("{} >> {s}u", a(0)),
            Op::Select => {
                let mask_vec = self.f.ty_of(n.args[0]).lanes > 1;
                match lang {
                    Lang::Wgsl => format!("select({}, {}, {})", a(2), a(1), a(0)),
                    Lang::Glsl if mask_vec => format!("mix({}, {}, {})", a(2), a(1), a(0)),
                    // HLSL 2021 (DXC's default) rejects `?:` on vector conditions and wants
                    // select(); older HLSL has no select(). The include defines this macro.
                    Lang::Hlsl if mask_vec => {
                        format!("{}({}, {}, {})", self.select_macro, a(0), a(1), a(2))
                    }
                    _ => format!("{} ? {} : {}", a(0), a(1), a(2)),
                }
            }
            Op::Convert => format!("{}({})", ty(lang, n.ty), a(0)),
            Op::Construct => {
                let t = ty(lang, n.ty);
                let same_literal = n.args.len() > 1
                    && n.args.iter().all(|r| {
                        r.lane.is_none()
                            && matches!(
                                self.f.nodes[r.node as usize].op,
                                Op::ConstF(_) | Op::ConstU(_)
                            )
                            && self.f.nodes[r.node as usize].op
                                == self.f.nodes[n.args[0].node as usize].op
                    });
                if (n.args.len() == 1 || same_literal) && is_vec {
                    let x = a(0);
                    match lang {
                        Lang::Hlsl => format!("{t}({})", vec![x; n.ty.lanes as usize].join(", ")),
                        _ => format!("{t}({x})"),
                    }
                } else {
                    format!("{t}({})", self.construct_args(&n.args).join(", "))
                }
            }
            Op::Swizzle(l) => format!("{}.{}", self.value(n.args[0].node as usize), lanes_str(l)),
            Op::Call(name) => {
                let args: Vec<String> = n.args.iter().map(|r| self.r(*r)).collect();
                format!("{}({})", (self.fn_name)(name), args.join(", "))
            }
        }
    }
}

/// Node ids the return value depends on.
fn live(f: &Func) -> Vec<bool> {
    let mut live = vec![false; f.nodes.len()];
    let mut stack = vec![f.ret.node as usize];
    while let Some(i) = stack.pop() {
        if std::mem::replace(&mut live[i], true) {
            continue;
        }
        stack.extend(f.nodes[i].args.iter().map(|a| a.node as usize));
    }
    live
}

/// The HLSL lane-wise select macro the templates define, named after the prefix.
pub fn select_macro(prefix: &str) -> String {
    format!("{}SELECT", macro_prefix(prefix))
}

/// Macros are global in GLSL and HLSL: without a prefix they still carry the tool's name.
fn macro_prefix(prefix: &str) -> String {
    if prefix.is_empty() {
        "UNITPACK_".into()
    } else {
        prefix.to_ascii_uppercase()
    }
}

/// The GLSL macro in front of float declarations: empty by default (GLSL 330 and ES 300
/// have no `precise`), `precise` where the user defines it so.
pub fn precise_macro(prefix: &str) -> String {
    format!("{}PRECISE", macro_prefix(prefix))
}

pub fn print(lang: Lang, f: &Func, prefix: &str, fn_name: &dyn Fn(&str) -> String) -> Printed {
    let live = live(f);
    let select_macro = select_macro(prefix);
    let precise_macro = precise_macro(prefix);
    let mut ctx = Ctx {
        lang,
        select_macro: &select_macro,
        precise_macro: &precise_macro,
        f,
        names: vec![None; f.nodes.len()],
        fn_name,
    };
    let mut used: HashSet<String> = f.params.iter().map(|p| p.0.clone()).collect();
    let mut body = Vec::new();
    let mut temp = 0;
    for (id, node) in f.nodes.iter().enumerate() {
        if !live[id] || ctx.inline(id) {
            continue;
        }
        let base = match node.name {
            Some(n) => n.to_string(),
            None => {
                temp += 1;
                format!("t{temp}")
            }
        };
        let mut name = base.clone();
        let mut k = 1;
        while !used.insert(name.clone()) {
            k += 1;
            name = format!("{base}{k}");
        }
        let e = ctx.expr(id);
        // Float results are `precise` where the language allows it, so drivers that
        // contract `a*b + c` into an fma must not do so here (lavapipe never does).
        let qualifier = match (lang, node.ty.kind) {
            (Lang::Hlsl, Kind::F32) => "precise ".to_string(),
            (Lang::Glsl, Kind::F32) => format!("{} ", ctx.precise_macro),
            _ => String::new(),
        };
        body.push(match lang {
            Lang::Wgsl => format!("let {name} = {e};"),
            _ => format!("{qualifier}{} {name} = {e};", ty(lang, node.ty)),
        });
        ctx.names[id] = Some(name);
    }
    body.push(format!("return {};", ctx.r(f.ret)));
    Printed {
        name: fn_name(&f.name),
        params: f
            .params
            .iter()
            .map(|(n, t)| (n.clone(), ty(lang, *t)))
            .collect(),
        ret_ty: ty(lang, f.ret_ty),
        body,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every literal reads back as the same f32, directly and through f64, in every language.
    #[test]
    fn literals_round_trip_exactly() {
        let mut x: u32 = 0x1234_5678;
        for i in 0..200_000u32 {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            let v = f32::from_bits(if i < 1000 { i } else { x });
            if !v.is_finite() {
                continue;
            }
            for lang in [Lang::Wgsl, Lang::Glsl, Lang::Hlsl] {
                let s = f32_literal(lang, v);
                let t = s.trim_end_matches('f');
                assert!(t.contains(['.', 'e']), "{s} is not a float literal");
                assert_eq!(t.parse::<f32>().unwrap().to_bits(), v.to_bits(), "{s}");
                assert_eq!(
                    (t.parse::<f64>().unwrap() as f32).to_bits(),
                    v.to_bits(),
                    "{s} via f64"
                );
            }
        }
    }
}
