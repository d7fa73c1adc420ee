//! Tracing: a [`Float`] implementation that records every operation into a typed SSA graph.
//!
//! Codecs are plain generic Rust; running them with [`T`] instead of `f32` yields a
//! [`Module`] of [`Func`]s that the printers in `crate::emit` turn into WGSL, GLSL and HLSL.
//! The graph keeps the model's evaluation order and never reassociates, so the printed
//! code computes the same bits as the `f32` evaluation. The recorder refuses what the
//! canonical arithmetic rules forbid and what the vocabulary cannot prevent by itself:
//! dividing by a literal (HLSL optimisers turn it into a reciprocal multiply) and
//! operations on literals only (WGSL folds those in f64).

use super::num::{Bool, Float, Kind, Lane, Uint};
pub use super::num::{Ref, Ty, Value};
use super::vec::{V2, V3, V4};
use std::cell::RefCell;
use std::marker::PhantomData;
use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Sub};

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum UnOp {
    Neg,
    Abs,
    Sqrt,
    Floor,
    Round,
    Not,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BinOp {
    Add,
    Sub,
    Mul,
    Div,
    And,
    Or,
    BitAnd,
    BitOr,
    Lt,
    Le,
    Gt,
    Ge,
    Eq,
}

impl BinOp {
    /// Arithmetic accepts a scalar operand beside a vector in every target language.
    pub fn broadcasts(self) -> bool {
        matches!(self, BinOp::Add | BinOp::Sub | BinOp::Mul | BinOp::Div)
    }
}

#[derive(Clone, Debug, PartialEq)]
pub enum Op {
    Param(usize),
    ConstF(f32),
    ConstU(u32),
    Un(UnOp),
    Bin(BinOp),
    /// Shift by a fixed amount.
    Shl(u32),
    Shr(u32),
    /// args: mask, if_true, if_false
    Select,
    /// Value conversion to the node's kind.
    Convert,
    /// Reinterpretation of the 32 bits as the node's kind (f32 ↔ u32).
    Bitcast,
    /// Builds a vector from scalars (one arg: splat).
    Construct,
    /// `args[0]` is a vector; picks the given lanes.
    Swizzle(Vec<u8>),
    Call(String),
}

#[derive(Clone, Debug)]
pub struct Node {
    pub op: Op,
    pub args: Vec<Ref>,
    pub ty: Ty,
    pub name: Option<&'static str>,
}

/// The struct a function returns its values in when it returns several (a frame
/// decoder's normal and tangent): its local name (the emitted one is prefixed like a
/// function's) and its fields' names, in order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shape {
    pub name: &'static str,
    pub fields: &'static [&'static str],
}

/// One traced function: parameters, body in evaluation order, and the returned values.
#[derive(Clone, Debug)]
pub struct Func {
    pub name: String,
    pub params: Vec<(String, Ty)>,
    pub nodes: Vec<Node>,
    /// The returned values: one, or the fields of [`Func::shape`] in order.
    pub rets: Vec<Ref>,
    pub ret_tys: Vec<Ty>,
    /// The struct the values are returned in, for a function that returns several.
    pub shape: Option<Shape>,
    /// Parameters this function multiplies by a literal (directly, or by passing them to
    /// a helper that does): a caller must not pass a literal product there.
    pub scaled_params: Vec<bool>,
    /// Whether the result is a literal product: a caller must not scale it by a literal.
    pub returns_scaled: bool,
}

impl Func {
    pub fn ty_of(&self, r: Ref) -> Ty {
        let t = self.nodes[r.node as usize].ty;
        match r.lane {
            Some(_) => Ty::scalar(t.kind),
            None => t,
        }
    }
}

/// Every function a trace produced, callees before callers.
#[derive(Clone, Debug, Default)]
pub struct Module {
    pub funcs: Vec<Func>,
}

impl Module {
    pub fn func(&self, name: &str) -> Option<&Func> {
        self.funcs.iter().find(|f| f.name == name)
    }

    /// The traces of the function `name` and of every function it calls, callees first
    /// (a module lists them in that order): everything its emitted code is made from,
    /// apart from the names' prefix.
    pub fn with_callees(&self, name: &str) -> Vec<&Func> {
        let mut wanted = std::collections::HashSet::from([name.to_string()]);
        let mut out: Vec<&Func> = self
            .funcs
            .iter()
            .rev()
            .filter(|func| {
                let keep = wanted.contains(&func.name);
                if keep {
                    wanted.extend(func.nodes.iter().filter_map(|n| match &n.op {
                        Op::Call(c) => Some(c.clone()),
                        _ => None,
                    }));
                }
                keep
            })
            .collect();
        out.reverse();
        out
    }

    /// A text that two functions share exactly when their traces, and their callees',
    /// are the same: the same emitted code in every language (a precise spec's decoders
    /// are its fast spec's), so whatever runs one runs the other alike.
    pub fn identity(&self, name: &str) -> String {
        let traced = self.with_callees(name);
        assert!(!traced.is_empty(), "{name} is not in its module");
        format!("{traced:?}")
    }
}

#[derive(Default)]
struct Recorder {
    module: Module,
    stack: Vec<Vec<Node>>,
    /// For each function being traced, which of its parameters it scales by a literal.
    scaled: Vec<Vec<bool>>,
    /// Vector nodes already built from a list of lanes, so shared lanes fuse once.
    memo: std::collections::HashMap<Vec<Ref>, Ref>,
    memo_stack: Vec<std::collections::HashMap<Vec<Ref>, Ref>>,
}

thread_local! {
    static REC: RefCell<Option<Recorder>> = const { RefCell::new(None) };
    /// The functions being defined, outermost first. A definition that panics leaves its
    /// name here, so that what catches the panic can say where a rule failed
    /// ([`take_defining`]); [`trace_module`] starts it empty.
    static DEFINING: RefCell<Vec<String>> = const { RefCell::new(Vec::new()) };
}

/// The functions whose definitions were open when tracing stopped (outermost first),
/// emptied: after a panic, where it happened.
pub fn take_defining() -> Vec<String> {
    DEFINING.with(|d| std::mem::take(&mut *d.borrow_mut()))
}

fn with<R>(f: impl FnOnce(&mut Recorder) -> R) -> R {
    REC.with(|r| {
        let mut r = r.borrow_mut();
        let rec = r
            .as_mut()
            .expect("traced values exist only inside unitpack::model::trace::trace_module");
        f(rec)
    })
}

impl Recorder {
    fn nodes(&mut self) -> &mut Vec<Node> {
        self.stack.last_mut().expect("no function is being traced")
    }
    fn ty(&mut self, r: Ref) -> Ty {
        let t = self.nodes()[r.node as usize].ty;
        match r.lane {
            Some(_) => Ty::scalar(t.kind),
            None => t,
        }
    }
    fn push(&mut self, op: Op, args: Vec<Ref>, ty: Ty) -> Ref {
        let nodes = self.nodes();
        nodes.push(Node {
            op,
            args,
            ty,
            name: None,
        });
        Ref {
            node: nodes.len() as u32 - 1,
            lane: None,
        }
    }
    /// Whether `r` is a literal: a literal node, or (a lane of) a vector built from literals.
    fn is_const(&mut self, r: Ref) -> bool {
        self.literal(r).is_some()
    }

    /// The literal `r` stands for: a literal node, a lane of a vector built from literals,
    /// or a vector whose lanes are all the same literal. `Some(None)` for a literal
    /// vector with different lanes.
    fn literal(&mut self, r: Ref) -> Option<Option<f32>> {
        let n = self.nodes()[r.node as usize].clone();
        match (&n.op, r.lane) {
            (Op::ConstF(v), _) => Some(Some(*v)),
            (Op::ConstU(_), _) => Some(None),
            (Op::Construct, Some(l)) => {
                let arg = n.args[if n.args.len() == 1 { 0 } else { l as usize }];
                self.literal(arg)
            }
            (Op::Construct, None) => {
                let lanes: Option<Vec<Option<f32>>> =
                    n.args.iter().map(|a| self.literal(*a)).collect();
                let lanes = lanes?;
                Some(if lanes.iter().all(|l| l.is_some() && *l == lanes[0]) {
                    lanes[0]
                } else {
                    None
                })
            }
            _ => None,
        }
    }

    /// Whether `r` is a product with a literal that a driver could merge with another
    /// literal factor. Powers of two are exempt: `(x·a)·2^k` and `x·(a·2^k)` round alike.
    fn is_scaled(&mut self, r: Ref) -> bool {
        let n = self.nodes()[r.node as usize].clone();
        n.op == Op::Bin(BinOp::Mul)
            && n.args.iter().any(|a| match self.literal(*a) {
                Some(Some(v)) => !is_power_of_two(v),
                Some(None) => true,
                None => false,
            })
    }

    /// The parameter `r` reads, if it is one (or a lane of one).
    fn param_of(&mut self, r: Ref) -> Option<usize> {
        match self.nodes()[r.node as usize].op {
            Op::Param(i) => Some(i),
            _ => None,
        }
    }

    /// Drivers inline helpers and then fold literal factors across the call: refuse a
    /// literal product passed where the helper scales by a literal, and remember that
    /// this function's parameters are scaled when it forwards them there.
    fn check_call(&mut self, callee: &str, args: &[Ref]) {
        let f = self
            .module
            .func(callee)
            .expect("helper traced before its call");
        let scaled = f.scaled_params.clone();
        for (i, a) in args.iter().enumerate() {
            if !scaled.get(i).copied().unwrap_or(false) {
                continue;
            }
            if self.is_scaled(*a) {
                panic!(
                    "a literal product passed to `{callee}`, which scales that parameter by a literal: after inlining, drivers fold (x*a)*b into x*(a*b)"
                );
            }
            if let Some(p) = self.param_of(*a) {
                self.scaled.last_mut().expect("traced function")[p] = true;
            }
        }
    }

    fn record(&mut self, op: Op, args: Vec<Ref>, kind: Kind) -> Ref {
        if !args.is_empty() && args.iter().all(|a| self.is_const(*a)) {
            if let Some(folded) = self.exact_fold(&op, &args, kind) {
                return self.push(folded, vec![], Ty::scalar(kind));
            }
            panic!(
                "constant expression {op:?} on literals only: compute the value in Rust and pass one literal (WGSL would fold it in f64)"
            );
        }
        if op == Op::Bin(BinOp::Div) && self.is_const(args[1]) {
            panic!(
                "division by a literal: multiply by the reciprocal computed in Rust (HLSL optimisers rewrite x/c as x*(1/c))"
            );
        }
        // `1/x` is exempt: what drivers compute for it, `1·rcp(x)`, is `rcp(x)`, which
        // rounds correctly wherever division does (the engine formats' `1/|v|` and `rcp`).
        if op == Op::Bin(BinOp::Div)
            && self.is_const(args[0])
            && self.literal(args[0]) != Some(Some(1.0))
        {
            panic!(
                "a literal divided by a value: drivers compute c/x as c*rcp(x); compute the numerator"
            );
        }
        // Integer products are exact: only float literal factors can be folded unsafely.
        if op == Op::Bin(BinOp::Mul) && kind == Kind::F32 {
            let lits: Vec<Option<Option<f32>>> = args.iter().map(|a| self.literal(*a)).collect();
            if let Some(k) = lits.iter().position(Option::is_some) {
                let other = args[1 - k];
                let factor = lits[k].expect("literal");
                let exempt = factor.is_some_and(is_power_of_two);
                if !exempt && self.is_scaled(other) {
                    panic!(
                        "a literal multiply of a literal multiply: drivers fold (x*a)*b into x*(a*b)"
                    );
                }
                if !exempt {
                    if let Some(p) = self.param_of(other) {
                        self.scaled.last_mut().expect("traced function")[p] = true;
                    }
                    let n = self.nodes()[other.node as usize].clone();
                    if let Op::Call(name) = &n.op {
                        let returns_scaled =
                            self.module.func(name).is_some_and(|f| f.returns_scaled);
                        if returns_scaled {
                            panic!(
                                "a literal multiply of `{name}`'s result, itself a literal product: after inlining, drivers fold (x*a)*b into x*(a*b)"
                            );
                        }
                    }
                }
            }
        }
        self.push(op, args, Ty::scalar(kind))
    }

    /// The scalar literal `r` stands for, as its node (`ConstF` or `ConstU`).
    fn scalar_literal(&mut self, r: Ref) -> Option<Op> {
        let n = self.nodes()[r.node as usize].clone();
        match (&n.op, r.lane) {
            (Op::ConstF(_) | Op::ConstU(_), _) => Some(n.op),
            (Op::Construct, Some(l)) => {
                let arg = n.args[if n.args.len() == 1 { 0 } else { l as usize }];
                self.scalar_literal(arg)
            }
            _ => None,
        }
    }

    /// An operation on literals whose result is exact, so the same in f32 and in the f64
    /// a WGSL compiler folds constants in: integer operations, conversions of integral
    /// values, and float sums and products that need no rounding (an engine format's
    /// constant words, packed like any other field). `None` for anything that rounds.
    fn exact_fold(&mut self, op: &Op, args: &[Ref], kind: Kind) -> Option<Op> {
        let lits: Option<Vec<Op>> = args.iter().map(|a| self.scalar_literal(*a)).collect();
        let lits = lits?;
        let folded = match (op, lits.as_slice(), kind) {
            (Op::Bin(b), [Op::ConstF(x), Op::ConstF(y)], Kind::F32) => {
                let (r, exact) = match b {
                    BinOp::Add => (x + y, f64::from(*x) + f64::from(*y)),
                    BinOp::Sub => (x - y, f64::from(*x) - f64::from(*y)),
                    BinOp::Mul => (x * y, f64::from(*x) * f64::from(*y)),
                    _ => return None,
                };
                (f64::from(r) == exact).then_some(Op::ConstF(r))?
            }
            (Op::Convert, [Op::ConstF(x)], Kind::U32) => {
                let integral = x.fract() == 0.0 && (0.0..4_294_967_296.0).contains(x);
                integral.then_some(Op::ConstU(*x as u32))?
            }
            (Op::Convert, [Op::ConstU(x)], Kind::F32) => {
                (*x < 1 << 24).then_some(Op::ConstF(*x as f32))?
            }
            (Op::Shl(n), [Op::ConstU(x)], Kind::U32) => Op::ConstU(x << n),
            (Op::Shr(n), [Op::ConstU(x)], Kind::U32) => Op::ConstU(x >> n),
            (Op::Bin(b), [Op::ConstU(x), Op::ConstU(y)], Kind::U32) => Op::ConstU(match b {
                BinOp::BitAnd => x & y,
                BinOp::BitOr => x | y,
                BinOp::Add => x.wrapping_add(*y),
                BinOp::Sub => x.wrapping_sub(*y),
                BinOp::Mul => x.wrapping_mul(*y),
                _ => return None,
            }),
            _ => return None,
        };
        Some(folded)
    }

    /// Turns the lanes of one operand position into a single operand.
    fn operand(&mut self, lanes: &[Ref], broadcast_ok: bool) -> Ref {
        let first = lanes[0];
        let same = |r: &mut Self, l: &Ref| {
            *l == first || {
                let a = r.nodes()[l.node as usize].op.clone();
                let b = r.nodes()[first.node as usize].op.clone();
                l.lane.is_none()
                    && match (&a, &b) {
                        (Op::ConstF(x), Op::ConstF(y)) => x.to_bits() == y.to_bits(),
                        (Op::ConstU(x), Op::ConstU(y)) => x == y,
                        _ => false,
                    }
            }
        };
        if lanes.iter().all(|l| same(self, l)) && first.lane.is_none() && self.ty(first).lanes == 1
        {
            if broadcast_ok {
                return first;
            }
            let ty = Ty {
                kind: self.ty(first).kind,
                lanes: lanes.len() as u8,
            };
            return self.push(Op::Construct, vec![first], ty);
        }
        self.vector_of(lanes)
    }

    /// Whether the lanes are distinct scalar results of one and the same operation, so
    /// that a single vector operation can compute them all.
    fn fusable(&mut self, lanes: &[Ref]) -> bool {
        if lanes.iter().any(|r| r.lane.is_some()) {
            return false;
        }
        for (i, a) in lanes.iter().enumerate() {
            if lanes[..i].contains(a) {
                return false;
            }
        }
        let n0 = self.nodes()[lanes[0].node as usize].clone();
        // Boolean logic and shifts stay scalar: vector forms of them differ across the
        // languages (GLSL has no `&&` on bvec and needs not(); WGSL shifts need a vector
        // shift amount), while scalar forms mean the same everywhere.
        let vectorizable = match n0.op {
            Op::Un(u) => u != UnOp::Not,
            Op::Bin(b) => !matches!(b, BinOp::And | BinOp::Or),
            Op::Select | Op::Convert | Op::Bitcast => true,
            _ => false,
        };
        vectorizable
            && n0.ty.lanes == 1
            && lanes.iter().all(|r| {
                let n = &self.nodes()[r.node as usize];
                n.op == n0.op && n.ty == n0.ty
            })
    }

    /// A vector whose lanes equal `lanes`. Lanes computed by the same operation become one
    /// vector operation, recursively through their operands, so code written lane by lane
    /// prints as vector code; anything else becomes a swizzle or a constructor.
    fn vector_of(&mut self, lanes: &[Ref]) -> Ref {
        let l = lanes.len() as u8;
        let first = lanes[0];
        if first.lane == Some(0)
            && lanes
                .iter()
                .enumerate()
                .all(|(i, r)| r.node == first.node && r.lane == Some(i as u8))
            && self
                .ty(Ref {
                    node: first.node,
                    lane: None,
                })
                .lanes
                == l
        {
            return Ref {
                node: first.node,
                lane: None,
            };
        }
        if let Some(v) = self.memo.get(lanes) {
            return *v;
        }
        if !self.fusable(lanes) {
            let g = self.gather(lanes);
            self.memo.insert(lanes.to_vec(), g);
            return g;
        }
        let proto = self.nodes()[first.node as usize].clone();
        let arity = proto.args.len();
        let mut args = Vec::with_capacity(arity);
        for j in 0..arity {
            let col: Vec<Ref> = lanes
                .iter()
                .map(|r| self.nodes()[r.node as usize].args[j])
                .collect();
            let broadcast_ok = match proto.op {
                Op::Bin(b) => b.broadcasts(),
                Op::Select => j == 0,
                _ => false,
            };
            args.push(self.operand(&col, broadcast_ok));
        }
        // Arithmetic on broadcast scalars only would yield a scalar: splat one side.
        if args.iter().all(|a| self.ty(*a).lanes == 1) {
            let ty = Ty {
                kind: self.ty(args[arity - 1]).kind,
                lanes: l,
            };
            args[arity - 1] = self.push(Op::Construct, vec![args[arity - 1]], ty);
        }
        let ty = Ty {
            kind: proto.ty.kind,
            lanes: l,
        };
        let v = self.push(proto.op, args, ty);
        self.memo.insert(lanes.to_vec(), v);
        v
    }

    /// A vector made of the given lanes: a swizzle of one vector, or a constructor.
    fn gather(&mut self, lanes: &[Ref]) -> Ref {
        let first = lanes[0];
        let kind = self.ty(first).kind;
        let ty = Ty {
            kind,
            lanes: lanes.len() as u8,
        };
        if first.lane.is_some()
            && lanes
                .iter()
                .all(|l| l.node == first.node && l.lane.is_some())
        {
            let src = Ref {
                node: first.node,
                lane: None,
            };
            let order: Vec<u8> = lanes.iter().map(|l| l.lane.unwrap()).collect();
            return self.push(Op::Swizzle(order), vec![src], ty);
        }
        self.push(Op::Construct, lanes.to_vec(), ty)
    }

    fn fuse(&mut self, lanes: &[Ref]) -> Vec<Ref> {
        let v = self.vector_of(lanes);
        (0..lanes.len() as u8)
            .map(|i| Ref {
                node: v.node,
                lane: Some(i),
            })
            .collect()
    }

    fn name(&mut self, r: Ref, name: &'static str) {
        self.nodes()[r.node as usize].name = Some(name);
    }
}

fn is_power_of_two(v: f32) -> bool {
    v.is_normal() && v.to_bits() & 0x007f_ffff == 0
}

/// Kind markers for [`T`].
#[derive(Clone, Copy, Debug)]
pub struct FK;
#[derive(Clone, Copy, Debug)]
pub struct UK;
#[derive(Clone, Copy, Debug)]
pub struct BK;

/// A traced value of kind `K`: a reference into the graph being recorded.
#[derive(Clone, Copy, Debug)]
pub struct T<K = FK>(Ref, PhantomData<K>);

pub type Tf = T<FK>;
pub type Tu = T<UK>;
pub type Tb = T<BK>;

impl<K> T<K> {
    fn new(r: Ref) -> Self {
        T(r, PhantomData)
    }
}

/// Records one operation. Every traced operation of every codec comes here: kept out of
/// line, a codec's traced body is a row of calls rather than this recording inlined at
/// each operation (docs/design/speed.md, "What the build spends").
#[inline(never)]
fn record(op: Op, args: &[Ref], kind: Kind) -> Ref {
    with(|r| r.record(op, args.to_vec(), kind))
}

fn rec<K>(op: Op, args: &[Ref], kind: Kind) -> T<K> {
    T::new(record(op, args, kind))
}

/// Records a literal of type `ty` ([`record`], for constants).
#[inline(never)]
fn constant(op: Op, ty: Ty) -> Ref {
    with(|r| r.push(op, vec![], ty))
}

/// [`Lane::fuse`]'s recording, out of line as [`record`] is.
#[inline(never)]
fn fuse_refs(refs: &[Ref]) -> Vec<Ref> {
    with(|r| r.fuse(refs))
}

/// [`Lane::named`]'s recording, out of line as [`record`] is.
#[inline(never)]
fn name_ref(at: Ref, name: &'static str) {
    with(|r| r.name(at, name))
}

macro_rules! lane_impl {
    ($K:ty, $kind:expr) => {
        impl Lane for T<$K> {
            const KIND: Kind = $kind;
            fn fuse<const L: usize>(lanes: [Self; L]) -> [Self; L] {
                let out = fuse_refs(&lanes.map(|t| t.0));
                std::array::from_fn(|i| T::new(out[i]))
            }
            fn named(self, name: &'static str) -> Self {
                // A lane of a vector has no statement of its own to name.
                if self.0.lane.is_none() {
                    name_ref(self.0, name);
                }
                self
            }
            fn named_lanes<const L: usize>(lanes: [Self; L], name: &'static str) -> [Self; L] {
                let v = Self::fuse(lanes);
                name_ref(
                    Ref {
                        node: v[0].0.node,
                        lane: None,
                    },
                    name,
                );
                v
            }
        }
        impl Value for T<$K> {
            fn tys() -> Vec<Ty> {
                vec![Ty::scalar($kind)]
            }
            fn refs(self) -> Vec<Ref> {
                vec![self.0]
            }
            fn from_refs(r: &mut dyn Iterator<Item = Ref>) -> Self {
                T::new(r.next().unwrap())
            }
        }
    };
}
lane_impl!(FK, Kind::F32);
lane_impl!(UK, Kind::U32);
lane_impl!(BK, Kind::Bool);

macro_rules! bin_impl {
    ($K:ty, $kind:expr, $Tr:ident, $m:ident, $op:expr) => {
        impl $Tr for T<$K> {
            type Output = Self;
            fn $m(self, o: Self) -> Self {
                rec(Op::Bin($op), &[self.0, o.0], $kind)
            }
        }
    };
}
bin_impl!(FK, Kind::F32, Add, add, BinOp::Add);
bin_impl!(FK, Kind::F32, Sub, sub, BinOp::Sub);
bin_impl!(FK, Kind::F32, Mul, mul, BinOp::Mul);
bin_impl!(FK, Kind::F32, Div, div, BinOp::Div);
bin_impl!(UK, Kind::U32, Add, add, BinOp::Add);
bin_impl!(UK, Kind::U32, Sub, sub, BinOp::Sub);
bin_impl!(UK, Kind::U32, BitAnd, bitand, BinOp::BitAnd);
bin_impl!(UK, Kind::U32, BitOr, bitor, BinOp::BitOr);

impl Neg for Tf {
    type Output = Self;
    fn neg(self) -> Self {
        rec(Op::Un(UnOp::Neg), &[self.0], Kind::F32)
    }
}

impl Bool for Tb {
    fn and(self, o: Self) -> Self {
        rec(Op::Bin(BinOp::And), &[self.0, o.0], Kind::Bool)
    }
    fn or(self, o: Self) -> Self {
        rec(Op::Bin(BinOp::Or), &[self.0, o.0], Kind::Bool)
    }
    fn not(self) -> Self {
        rec(Op::Un(UnOp::Not), &[self.0], Kind::Bool)
    }
}

impl Uint for Tu {
    type F = Tf;
    type B = Tb;
    fn c(v: u32) -> Self {
        T::new(constant(Op::ConstU(v), Ty::scalar(Kind::U32)))
    }
    fn shl(self, n: u32) -> Self {
        rec(Op::Shl(n), &[self.0], Kind::U32)
    }
    fn shr(self, n: u32) -> Self {
        rec(Op::Shr(n), &[self.0], Kind::U32)
    }
    fn to_f(self) -> Tf {
        rec(Op::Convert, &[self.0], Kind::F32)
    }
    fn as_float(self) -> Tf {
        rec(Op::Bitcast, &[self.0], Kind::F32)
    }
    fn sel(m: Tb, t: Self, f: Self) -> Self {
        rec(Op::Select, &[m.0, t.0, f.0], Kind::U32)
    }
    fn wrapping_add(self, o: Self) -> Self {
        self + o
    }
    fn wrapping_sub(self, o: Self) -> Self {
        self - o
    }
    fn wrapping_mul(self, o: Self) -> Self {
        rec(Op::Bin(BinOp::Mul), &[self.0, o.0], Kind::U32)
    }
    fn lt(self, o: Self) -> Tb {
        rec(Op::Bin(BinOp::Lt), &[self.0, o.0], Kind::Bool)
    }
}

impl Float for Tf {
    type U = Tu;
    type B = Tb;
    fn c(v: f32) -> Self {
        T::new(constant(Op::ConstF(v), Ty::scalar(Kind::F32)))
    }
    fn abs(self) -> Self {
        rec(Op::Un(UnOp::Abs), &[self.0], Kind::F32)
    }
    fn sqrt(self) -> Self {
        rec(Op::Un(UnOp::Sqrt), &[self.0], Kind::F32)
    }
    fn floor(self) -> Self {
        rec(Op::Un(UnOp::Floor), &[self.0], Kind::F32)
    }
    fn round(self) -> Self {
        rec(Op::Un(UnOp::Round), &[self.0], Kind::F32)
    }
    fn lt(self, o: Self) -> Tb {
        rec(Op::Bin(BinOp::Lt), &[self.0, o.0], Kind::Bool)
    }
    fn le(self, o: Self) -> Tb {
        rec(Op::Bin(BinOp::Le), &[self.0, o.0], Kind::Bool)
    }
    fn gt(self, o: Self) -> Tb {
        rec(Op::Bin(BinOp::Gt), &[self.0, o.0], Kind::Bool)
    }
    fn ge(self, o: Self) -> Tb {
        rec(Op::Bin(BinOp::Ge), &[self.0, o.0], Kind::Bool)
    }
    fn eq(self, o: Self) -> Tb {
        rec(Op::Bin(BinOp::Eq), &[self.0, o.0], Kind::Bool)
    }
    fn sel(m: Tb, t: Self, f: Self) -> Self {
        rec(Op::Select, &[m.0, t.0, f.0], Kind::F32)
    }
    fn to_u(self) -> Tu {
        rec(Op::Convert, &[self.0], Kind::U32)
    }
    fn to_bits(self) -> Tu {
        rec(Op::Bitcast, &[self.0], Kind::U32)
    }
    fn call<A: Value, R: Value>(
        name: &'static str,
        params: &[&'static str],
        a: A,
        f: impl FnOnce(A) -> R,
    ) -> R {
        define(name, &helper_params(params), f);
        let r = record_call(name, a.refs(), R::tys());
        R::from_refs(&mut std::iter::once(r))
    }
}

/// A helper's parameter names from its arguments' text: an identifier is kept (`v` for
/// `helper!(round_codes(v))`), an expression (`x * 2.0`, `self.k`) leaves the name to
/// [`define`]'s default (empty here).
fn helper_params(args: &[&'static str]) -> Vec<&'static str> {
    let identifier = |s: &str| {
        s.starts_with(|c: char| c.is_ascii_alphabetic())
            && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
    };
    args.iter()
        .map(|&a| if identifier(a) { a } else { "" })
        .collect()
}

/// Records a call of the helper `name` on `args`, returning a value of type `rty`:
/// [`Float::call`]'s recording, compiled once rather than per helper.
#[inline(never)]
fn record_call(name: &'static str, args: Vec<Ref>, rty: Vec<Ty>) -> Ref {
    assert_eq!(rty.len(), 1, "helpers return one value");
    with(|r| {
        r.check_call(name, &args);
        r.push(Op::Call(name.to_string()), args, rty[0])
    })
}

macro_rules! value_vec {
    ($V:ident, $n:literal) => {
        impl<X: Lane + Value> Value for $V<X> {
            fn tys() -> Vec<Ty> {
                vec![Ty {
                    kind: X::KIND,
                    lanes: $n,
                }]
            }
            fn refs(self) -> Vec<Ref> {
                let lanes = X::fuse(self.to_array());
                let r = lanes[0].refs()[0];
                vec![Ref {
                    node: r.node,
                    lane: None,
                }]
            }
            fn from_refs(r: &mut dyn Iterator<Item = Ref>) -> Self {
                let v = r.next().unwrap();
                $V::from_array(std::array::from_fn(|i| {
                    X::from_refs(&mut std::iter::once(Ref {
                        node: v.node,
                        lane: Some(i as u8),
                    }))
                }))
            }
        }
    };
}
value_vec!(V2, 2);
value_vec!(V3, 3);
value_vec!(V4, 4);

/// Traces `f` into a function called `name` (once per module; later calls are no-ops).
/// `param_names` name the parameters in order; a missing or empty name is the type's
/// (`x`, `v`, `word`, `words`, `mask`), numbered where two share it.
///
/// Only the conversions between values and references are generic: every codec function
/// and helper instantiates this once per closure, and the recording around it
/// ([`begin_define`], [`end_define`]) is compiled once for all of them.
pub fn define<A: Value, R: Value>(name: &str, param_names: &[&str], f: impl FnOnce(A) -> R) {
    let tys = A::tys();
    let Some(param_refs) = begin_define(name, &tys) else {
        return;
    };
    let out = f(A::from_refs(&mut param_refs.into_iter()));
    end_define(name, param_names, tys, out.refs(), None);
}

/// [`define`] for a public function that returns several values (a tuple), as the
/// fields of the struct `shape`, one field per value. Helpers return one value: only
/// the emitted entry points have a struct, which each language writes its own way.
pub fn define_fields<A: Value, R: Value>(
    name: &str,
    param_names: &[&str],
    shape: Shape,
    f: impl FnOnce(A) -> R,
) {
    let tys = A::tys();
    let Some(param_refs) = begin_define(name, &tys) else {
        return;
    };
    let out = f(A::from_refs(&mut param_refs.into_iter()));
    end_define(name, param_names, tys, out.refs(), Some(shape));
}

/// Opens the function `name` with parameters of types `tys`, returning their references;
/// `None` when the module already has it (with the same parameter types).
#[inline(never)]
fn begin_define(name: &str, tys: &[Ty]) -> Option<Vec<Ref>> {
    let existing = with(|r| {
        r.module
            .func(name)
            .map(|f| f.params.iter().map(|p| p.1).collect::<Vec<_>>())
    });
    if let Some(params) = existing {
        // Helpers are keyed by name: a second, different helper under the same name would
        // silently be replaced by the first.
        assert_eq!(
            params, tys,
            "two different helpers are both called `{name}`"
        );
        return None;
    }
    DEFINING.with(|d| d.borrow_mut().push(name.to_string()));
    Some(with(|r| {
        r.stack.push(Vec::new());
        r.scaled.push(vec![false; tys.len()]);
        r.memo_stack.push(std::mem::take(&mut r.memo));
        tys.iter()
            .enumerate()
            .map(|(i, t)| r.push(Op::Param(i), vec![], *t))
            .collect()
    }))
}

/// Closes the function [`begin_define`] opened, with parameters of types `tys`,
/// returning `ret` (the fields of `shape`, where it has one).
#[inline(never)]
fn end_define(name: &str, param_names: &[&str], tys: Vec<Ty>, ret: Vec<Ref>, shape: Option<Shape>) {
    DEFINING.with(|d| d.borrow_mut().pop());
    match shape {
        Some(s) => assert_eq!(ret.len(), s.fields.len(), "{name}: one value per field"),
        None => assert_eq!(
            ret.len(),
            1,
            "{name}: a function without a shape returns one value"
        ),
    }
    let mut params: Vec<(String, Ty)> = Vec::new();
    for (i, t) in tys.into_iter().enumerate() {
        let given = param_names.get(i).filter(|s| !s.is_empty());
        let name = match given {
            Some(s) => s.to_string(),
            // Named after the type, numbered where two share it.
            None => {
                let base = match (t.kind, t.lanes) {
                    (Kind::F32, 1) => "x",
                    (Kind::F32, _) => "v",
                    (Kind::U32, 1) => "word",
                    (Kind::U32, _) => "words",
                    (Kind::Bool, _) => "mask",
                };
                let taken =
                    |n: &str| params.iter().any(|(p, _)| p == n) || param_names.contains(&n);
                let mut name = base.to_string();
                let mut k = 1;
                while taken(&name) {
                    name = format!("{base}{k}");
                    k += 1;
                }
                name
            }
        };
        params.push((name, t));
    }
    with(|r| {
        let ret_tys = ret.iter().map(|&v| r.ty(v)).collect();
        let returns_scaled = ret.iter().any(|&v| r.is_scaled(v));
        let scaled_params = r.scaled.pop().unwrap();
        let nodes = r.stack.pop().unwrap();
        r.memo = r.memo_stack.pop().unwrap();
        r.module.funcs.push(Func {
            name: name.to_string(),
            params,
            nodes,
            rets: ret,
            ret_tys,
            shape,
            scaled_params,
            returns_scaled,
        });
    });
}

/// Runs `build` with a fresh recorder and returns every function it defined.
pub fn trace_module(build: impl FnOnce()) -> Module {
    REC.with(|r| {
        let prev = r.borrow_mut().replace(Recorder::default());
        assert!(prev.is_none(), "trace_module does not nest");
    });
    take_defining();
    struct Reset;
    impl Drop for Reset {
        fn drop(&mut self) {
            REC.with(|r| r.borrow_mut().take());
        }
    }
    let _reset = Reset;
    build();
    REC.with(|r| {
        r.borrow_mut()
            .as_mut()
            .map(|rec| std::mem::take(&mut rec.module))
    })
    .unwrap_or_default()
}
