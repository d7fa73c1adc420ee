//! Prints one traced function as statements of a target language, asking the language
//! ([`super::lang::Backend`]) for every piece of syntax.
//!
//! Every operation becomes one named `let`, in the model's evaluation order, so nothing is
//! reassociated or reordered; only literals, parameters, swizzles and literal vectors are
//! written inline. Values nothing returns are dropped (the tracer leaves the scalar lanes
//! it fused into vector operations behind).

use super::lang::Backend;
use crate::model::trace::{BinOp, Func, Node, Op, Ref, Ty, UnOp};
use std::collections::HashSet;

/// A function ready for a template: signature pieces and body lines.
pub struct Printed {
    pub name: String,
    pub params: Vec<(String, String)>,
    pub ret_ty: String,
    pub body: Vec<String>,
}

const LANE: [char; 4] = ['x', 'y', 'z', 'w'];

/// The shortest decimal that reads back as exactly `v`, both directly and through f64
/// (compilers that parse literals as double and then narrow must land on the same f32).
pub fn f32_literal(v: f32) -> String {
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
    s
}

fn lanes_str(l: &[u8]) -> String {
    l.iter().map(|i| LANE[*i as usize]).collect()
}

struct Ctx<'a> {
    lang: &'a dyn Backend,
    f: &'a Func,
    /// Nodes used as a whole vector: passed to a call or returned.
    whole: Vec<bool>,
    names: Vec<Option<String>>,
    fn_name: &'a dyn Fn(&str) -> String,
}

impl Ctx<'_> {
    /// Values written where they are used rather than named: literals, parameters,
    /// swizzles and literal vectors. Without vector values (C) a swizzle or literal vector
    /// is written lane by lane where it is used, and named only where it is passed or
    /// returned whole.
    fn inline(&self, id: usize) -> bool {
        let n = &self.f.nodes[id];
        match &n.op {
            Op::ConstF(_) | Op::ConstU(_) | Op::Param(_) => true,
            Op::Swizzle(_) => self.lang.has_vectors() || !self.whole[id],
            Op::Construct => {
                (self.lang.has_vectors() || !self.whole[id])
                    && n.args.iter().all(|a| {
                        matches!(
                            self.f.nodes[a.node as usize].op,
                            Op::ConstF(_) | Op::ConstU(_)
                        )
                    })
            }
            _ => false,
        }
    }

    /// An operand as text: a name, a literal, or a lane of a vector.
    fn r(&self, r: Ref) -> String {
        let id = r.node as usize;
        let n = &self.f.nodes[id];
        // Without vector values, a lane of an unnamed constructor or swizzle is the lane's
        // own expression (C has no `{ a, b }.x`).
        if let Some(l) = r.lane
            && !self.lang.has_vectors()
            && self.names[id].is_none()
            && matches!(n.op, Op::Construct | Op::Swizzle(_))
        {
            return self.lane_expr(n, l);
        }
        let base = self.value(id);
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

    /// Lane `l` of operand `r`, for languages without vector values: a scalar operand is
    /// used as it is (broadcast), a vector one through its lane.
    fn lane(&self, r: Ref, l: u8) -> String {
        if r.lane.is_some() || self.f.ty_of(r).lanes == 1 {
            return self.r(r);
        }
        let id = r.node as usize;
        let n = &self.f.nodes[id];
        if self.names[id].is_none() && matches!(n.op, Op::Construct | Op::Swizzle(_)) {
            return self.lane_expr(n, l);
        }
        format!("{}.{}", self.value(id), LANE[l as usize])
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
        let n = &self.f.nodes[id];
        if !self.lang.has_vectors() && n.ty.lanes > 1 && !matches!(n.op, Op::Param(_) | Op::Call(_))
        {
            let lanes: Vec<String> = (0..n.ty.lanes).map(|l| self.lane_expr(n, l)).collect();
            return self.lang.construct(n.ty, &lanes);
        }
        let arg_vec = |i: usize| self.f.ty_of(n.args[i]).lanes > 1;
        let vector = n.ty.lanes > 1;
        match &n.op {
            Op::Construct => {
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
                if (n.args.len() == 1 || same_literal) && vector {
                    self.lang.splat(n.ty, &self.r(n.args[0]))
                } else {
                    self.lang.construct(n.ty, &self.construct_args(&n.args))
                }
            }
            Op::Swizzle(l) => format!("{}.{}", self.value(n.args[0].node as usize), lanes_str(l)),
            _ => self.op_text(n, n.ty, &|i| self.r(n.args[i]), &arg_vec),
        }
    }

    /// Lane `l` of a vector operation, as a scalar expression.
    fn lane_expr(&self, n: &Node, l: u8) -> String {
        match &n.op {
            Op::Construct => self.r(n.args[if n.args.len() == 1 { 0 } else { l as usize }]),
            Op::Swizzle(order) => self.lane(n.args[0], order[l as usize]),
            _ => self.op_text(
                n,
                Ty::scalar(n.ty.kind),
                &|i| self.lane(n.args[i], l),
                &|_| false,
            ),
        }
    }

    /// One operation with its operands already written.
    fn op_text(
        &self,
        n: &Node,
        ty: Ty,
        a: &dyn Fn(usize) -> String,
        arg_vec: &dyn Fn(usize) -> bool,
    ) -> String {
        let lang = self.lang;
        match &n.op {
            Op::Param(i) => self.f.params[*i].0.clone(),
            Op::ConstF(v) => format!("{}{}", f32_literal(*v), lang.float_suffix()),
            Op::ConstU(v) => format!("{v}u"),
            Op::Un(UnOp::Neg) => format!("-{}", a(0)),
            Op::Un(UnOp::Not) => format!("!{}", a(0)),
            Op::Un(u) => format!("{}({})", lang.unary(*u), a(0)),
            Op::Bin(b) => {
                if let Some(f) = lang.vector_compare(*b).filter(|_| arg_vec(0)) {
                    return format!("{f}({}, {})", a(0), a(1));
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
            Op::Select => lang.select(ty, arg_vec(0), &a(0), &a(1), &a(2)),
            Op::Convert => lang.convert(ty, &a(0)),
            Op::Bitcast => lang.bitcast(ty, &a(0)),
            Op::Call(name) => {
                let args: Vec<String> = n.args.iter().map(|r| self.r(*r)).collect();
                format!("{}({})", (self.fn_name)(name), args.join(", "))
            }
            Op::Construct | Op::Swizzle(_) => unreachable!("written by expr"),
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

/// Words reserved in one of the languages that a value's name could plausibly be (WGSL
/// reserves many ordinary words, e.g. `target`, `filter`, `sample`); a value named one of
/// them is printed with a number appended, like a repeated name. HLSL's `half1`–`half4`
/// are types, so a value named `half` must not become `half1`.
const RESERVED: &[&str] = &[
    "active",
    "attribute",
    "buffer",
    "centroid",
    "common",
    "const",
    "filter",
    "fixed",
    "flat",
    "half",
    "half1",
    "half2",
    "half3",
    "half4",
    "in",
    "inout",
    "input",
    "layout",
    "line",
    "linear",
    "matrix",
    "noperspective",
    "out",
    "output",
    "patch",
    "point",
    "precise",
    "precision",
    "register",
    "sample",
    "sampler",
    "shared",
    "signed",
    "smooth",
    "static",
    "string",
    "target",
    "texture",
    "uniform",
    "unsigned",
    "vector",
    "volatile",
];

/// Prints `f` in `lang`; `fn_name` maps a traced function's local name to the name it is
/// defined and called by.
pub fn print(lang: &dyn Backend, f: &Func, fn_name: &dyn Fn(&str) -> String) -> Printed {
    let live = live(f);
    let mut whole = vec![false; f.nodes.len()];
    whole[f.ret.node as usize] = f.ret.lane.is_none();
    for n in &f.nodes {
        if matches!(n.op, Op::Call(_)) {
            for a in n.args.iter().filter(|a| a.lane.is_none()) {
                whole[a.node as usize] = true;
            }
        }
    }
    let mut ctx = Ctx {
        lang,
        f,
        whole,
        names: vec![None; f.nodes.len()],
        fn_name,
    };
    let mut used: HashSet<String> = f.params.iter().map(|p| p.0.clone()).collect();
    used.extend(RESERVED.iter().map(|w| w.to_string()));
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
        body.push(lang.declare(&name, node.ty, &e));
        ctx.names[id] = Some(name);
    }
    body.push(format!("return {};", ctx.r(f.ret)));
    Printed {
        name: fn_name(&f.name),
        params: f
            .params
            .iter()
            .map(|(n, t)| (n.clone(), lang.ty(*t)))
            .collect(),
        ret_ty: lang.ty(f.ret_ty),
        body,
    }
}
