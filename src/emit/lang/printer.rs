//! Prints one traced function as statements of a target language, asking the language
//! ([`super::Backend`]) for every piece of syntax.
//!
//! Every traced operation is printed once, with the operands it was traced with, so nothing
//! is reassociated, reordered within an operation, duplicated or dropped (values nothing
//! returns are dropped: the tracer leaves the scalar lanes it fused into vector operations
//! behind). What changes between operations is only how they are written down:
//! - a value the model names (`Float::named`) is declared under its name;
//! - an unnamed value used once is folded into the expression that uses it, with the
//!   parentheses the languages' precedence needs, when it holds few operations
//!   ([`FOLD_OPERATIONS`]);
//! - an unnamed value used more than once is declared as a temporary `t1`, `t2`, …;
//! - literals, parameters, swizzles and literal vectors are written where they are used.
//!
//! Folding keeps two guarantees the one-operation-per-statement form had:
//! - Where float declarations are `precise` (GLSL with `UNITPACK_PRECISE`, HLSL), every
//!   float operation must lie in the initializer of a float declaration, because `precise`
//!   covers the operations that compute the declared value (GLSL 4.60 §4.7.1; glslang marks
//!   each with `NoContraction`). So a float operation is never folded into a call's
//!   argument, a non-float declaration or a `return`: it is declared instead.
//! - C compilers may contract `a*b + c` written as one expression (clang's default
//!   `-ffp-contract=on`), never across statements: in C a product is not folded into a sum,
//!   difference or negation.
//!
//! `tests/internals/emit_folding.rs` proves that folding changed no operation: naga reads
//! the folded and the one-operation-per-statement text of every function, in WGSL and in
//! GLSL, into the same expression graph.

use super::Backend;
use crate::model::Kind;
use crate::model::trace::{BinOp, Func, Node, Op, Ref, Ty, UnOp};
use std::collections::HashSet;

/// A function ready for a template: signature pieces and body lines.
pub struct Printed {
    pub name: String,
    pub params: Vec<(String, String)>,
    pub ret_ty: String,
    pub body: Vec<String>,
}

/// The most operations a value folded into another may hold: a larger one is declared, so
/// that a statement reads as one line and a reader can name its parts. Counted in
/// operations rather than characters, so that a name prefix changes no folding.
pub const FOLD_OPERATIONS: usize = 6;

const LANE: [char; 4] = ['x', 'y', 'z', 'w'];

fn lanes_str(l: &[u8]) -> String {
    l.iter().map(|i| LANE[*i as usize]).collect()
}

/// Operator precedence levels, tightest first, as C, GLSL, HLSL and WGSL share them.
pub mod prec {
    pub const PRIMARY: u8 = 0;
    pub const UNARY: u8 = 1;
    pub const MUL: u8 = 2;
    pub const ADD: u8 = 3;
    pub const SHIFT: u8 = 4;
    pub const COMPARE: u8 = 5;
    pub const BITAND: u8 = 7;
    pub const BITOR: u8 = 8;
    pub const AND: u8 = 9;
    pub const OR: u8 = 10;
    pub const TERNARY: u8 = 11;
}

/// The level of a binary operator token as the printer writes it (between spaces).
pub(crate) fn op_level(tok: &str) -> Option<u8> {
    Some(match tok {
        "*" | "/" => prec::MUL,
        "+" | "-" => prec::ADD,
        "<<" | ">>" => prec::SHIFT,
        "<" | "<=" | ">" | ">=" | "==" | "!=" => prec::COMPARE,
        "&" => prec::BITAND,
        "|" => prec::BITOR,
        "&&" => prec::AND,
        "||" => prec::OR,
        "?" | ":" => prec::TERNARY,
        _ => return None,
    })
}

/// The tokens of `text` outside brackets, split at spaces: the printer writes every binary
/// operator between spaces and nothing else at the top level with one.
pub fn top_level_tokens(text: &str) -> Vec<(usize, &str)> {
    let mut out = Vec::new();
    let mut depth = 0i32;
    let mut start = 0;
    for (i, c) in text.char_indices() {
        match c {
            '(' | '[' | '{' => depth += 1,
            ')' | ']' | '}' => depth -= 1,
            ' ' if depth == 0 => {
                out.push((start, &text[start..i]));
                start = i + 1;
            }
            _ => {}
        }
    }
    out.push((start, &text[start..]));
    out
}

/// The level of the loosest operator at the top level of an expression's text.
pub fn precedence(text: &str) -> u8 {
    let level = top_level_tokens(text)
        .iter()
        .filter_map(|(_, t)| op_level(t))
        .max();
    if let Some(l) = level {
        return l;
    }
    if text.starts_with(['-', '!']) {
        return prec::UNARY;
    }
    // `(float)x`, a C cast: an opening bracket closed before the end.
    if text.starts_with('(') {
        let mut depth = 0;
        for (i, c) in text.char_indices() {
            match c {
                '(' => depth += 1,
                ')' => {
                    depth -= 1;
                    if depth == 0 {
                        return if i + 1 == text.len() {
                            prec::PRIMARY
                        } else {
                            prec::UNARY
                        };
                    }
                }
                _ => {}
            }
        }
    }
    prec::PRIMARY
}

/// `text` as an operand where nothing looser than `max` may stand unbracketed.
pub fn operand(text: String, max: u8) -> String {
    if precedence(&text) > max {
        format!("({text})")
    } else {
        text
    }
}

/// Whether the printer folds single-use values into their users, or writes every operation
/// as a statement of its own (the form `tests/internals/emit_folding.rs` compares the
/// folded one with).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Style {
    Folded,
    OneOperationPerStatement,
}

/// Who uses a value: the value declared by the statement it appears in, or `return`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum User {
    Node(usize),
    Return,
}

/// How often a value's text appears in the function, written one operation per statement.
#[derive(Clone, Default)]
struct Uses {
    /// Appearances whole (or through a swizzle of several lanes).
    whole: usize,
    /// Appearances through one lane, per lane.
    lanes: [usize; 4],
    users: Vec<User>,
}

impl Uses {
    fn total(&self) -> usize {
        self.whole + self.lanes.iter().sum::<usize>()
    }
}

/// The text that stands for node `id` while uses are counted.
fn marker(id: usize) -> String {
    format!("\u{1}{id}\u{2}")
}

/// Records the markers in `text` as uses by `user`.
fn count_markers(text: &str, user: User, uses: &mut [Uses]) {
    let mut rest = text;
    while let Some(p) = rest.find('\u{1}') {
        let q = p + rest[p..].find('\u{2}').expect("marker ends");
        let id: usize = rest[p + 1..q].parse().expect("marker id");
        let after = &rest[q + '\u{2}'.len_utf8()..];
        let swizzle: String = after
            .strip_prefix('.')
            .map(|s| s.chars().take_while(|c| LANE.contains(c)).collect())
            .unwrap_or_default();
        let u = &mut uses[id];
        match swizzle.as_bytes() {
            [l] => u.lanes[LANE.iter().position(|c| *c as u8 == *l).expect("lane")] += 1,
            _ => u.whole += 1,
        }
        u.users.push(user);
        rest = after;
    }
}

struct Ctx<'a> {
    lang: &'a dyn Backend,
    f: &'a Func,
    /// Nodes used as a whole vector: passed to a call or returned.
    whole: Vec<bool>,
    names: Vec<Option<String>>,
    /// Values written inside the expression that uses them.
    folded: Vec<bool>,
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

    /// Without vector values (C), whether a lane of this node, unnamed, is written as the
    /// lane's own expression (C has no `{ a, b }.x`).
    fn by_lane(&self, id: usize) -> bool {
        !self.lang.has_vectors()
            && self.names[id].is_none()
            && !matches!(
                self.f.nodes[id].op,
                Op::Call(_) | Op::Param(_) | Op::ConstF(_) | Op::ConstU(_)
            )
    }

    /// `value.suffix`, with the value bracketed unless it is primary.
    fn postfix(&self, id: usize, suffix: &str) -> String {
        format!("{}.{suffix}", operand(self.value(id), prec::PRIMARY))
    }

    /// An operand as text: a name, a literal, a folded expression, or a lane of one.
    fn r(&self, r: Ref) -> String {
        let id = r.node as usize;
        match r.lane {
            Some(l) if self.by_lane(id) => self.lane_expr(&self.f.nodes[id], l),
            Some(l) => self.postfix(id, &LANE[l as usize].to_string()),
            None => self.value(id),
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
        if self.by_lane(id) {
            return self.lane_expr(&self.f.nodes[id], l);
        }
        self.postfix(id, &LANE[l as usize].to_string())
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
                    let id = a.node as usize;
                    let lanes: Vec<u8> = (l0..l0 + (j - i) as u8).collect();
                    let whole = l0 == 0 && self.f.nodes[id].ty.lanes as usize == j - i;
                    out.push(if whole {
                        self.value(id)
                    } else {
                        self.postfix(id, &lanes_str(&lanes))
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
            Op::Swizzle(l) => self.postfix(n.args[0].node as usize, &lanes_str(l)),
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
        // `-x` of a negative operand would read `--x`.
        let unary = |s: String| {
            if s.starts_with('-') {
                format!("({s})")
            } else {
                operand(s, prec::UNARY)
            }
        };
        match &n.op {
            Op::Param(i) => self.f.params[*i].0.clone(),
            Op::ConstF(v) => lang.float_constant(*v),
            Op::ConstU(v) => super::literal::u32_literal(*v),
            Op::Un(UnOp::Neg) => format!("-{}", unary(a(0))),
            Op::Un(UnOp::Not) => format!("!{}", unary(a(0))),
            Op::Un(u) => format!("{}({})", lang.unary(*u), a(0)),
            Op::Bin(b) => {
                if let Some(f) = lang.vector_compare(*b).filter(|_| arg_vec(0)) {
                    return format!("{f}({}, {})", a(0), a(1));
                }
                let swapped = *b == BinOp::Lt && lang.less_than_as_greater();
                let (a0, a1) = if swapped { (a(1), a(0)) } else { (a(0), a(1)) };
                let (op, level) = match b {
                    BinOp::Lt if swapped => (">", prec::COMPARE),
                    BinOp::Add => ("+", prec::ADD),
                    BinOp::Sub => ("-", prec::ADD),
                    BinOp::Mul => ("*", prec::MUL),
                    BinOp::Div => ("/", prec::MUL),
                    BinOp::And => ("&&", prec::AND),
                    BinOp::Or => ("||", prec::OR),
                    BinOp::BitAnd => ("&", prec::BITAND),
                    BinOp::BitOr => ("|", prec::BITOR),
                    BinOp::Lt => ("<", prec::COMPARE),
                    BinOp::Le => ("<=", prec::COMPARE),
                    BinOp::Gt => (">", prec::COMPARE),
                    BinOp::Ge => (">=", prec::COMPARE),
                    BinOp::Eq => ("==", prec::COMPARE),
                };
                // The tighter operands WGSL's grammar allows (its bitwise operators and
                // comparisons mix with nothing unbracketed), which also keep C compilers'
                // -Wparentheses quiet. The left operand may continue a chain of the same
                // associative-to-the-left operator; the right one may not.
                let (right_max, chains) = match level {
                    prec::MUL => (prec::UNARY, true),
                    prec::ADD => (prec::MUL, true),
                    prec::COMPARE => (prec::ADD, false),
                    prec::BITAND | prec::BITOR => (prec::UNARY, true),
                    _ => (prec::COMPARE, true),
                };
                let left = a0;
                let left = if chains && precedence(&left) == level {
                    left
                } else {
                    operand(left, right_max)
                };
                // `x - -1.0` reads badly: a negative right operand is bracketed.
                let right = a1;
                let right = if right.starts_with('-') {
                    format!("({right})")
                } else {
                    operand(right, right_max)
                };
                format!("{left} {op} {right}")
            }
            Op::Shl(s) => format!("{} << {s}u", operand(a(0), prec::UNARY)),
            Op::Shr(s) => format!("{} >> {s}u", operand(a(0), prec::UNARY)),
            // Bracketed so that a `?:` select's operands need nothing more.
            Op::Select => lang.select(
                ty,
                arg_vec(0),
                &operand(a(0), prec::OR),
                &operand(a(1), prec::OR),
                &operand(a(2), prec::OR),
            ),
            Op::Convert => lang.convert(ty, &a(0)),
            Op::Bitcast => lang.bitcast(ty, &a(0)),
            Op::Call(name) => {
                let args: Vec<String> = n.args.iter().map(|r| self.r(*r)).collect();
                lang.call(&(self.fn_name)(name), &args)
            }
            Op::Construct | Op::Swizzle(_) => unreachable!("written by expr"),
        }
    }

    /// The operations the value's text, as folded now, holds: its own and its folded
    /// operands'.
    fn operations(&self, id: usize) -> usize {
        let n = &self.f.nodes[id];
        let own = usize::from(!self.inline(id));
        own + n
            .args
            .iter()
            .map(|a| a.node as usize)
            .filter(|&a| self.names[a].is_none())
            .map(|a| self.operations(a))
            .sum::<usize>()
    }

    /// Whether the value's text, as folded now, holds a float operation that a `precise`
    /// declaration must cover.
    fn carries_float_op(&self, id: usize) -> bool {
        let n = &self.f.nodes[id];
        (n.ty.kind == Kind::F32 && matches!(n.op, Op::Bin(_) | Op::Un(_)))
            || n.args.iter().any(|a| {
                let a = a.node as usize;
                self.names[a].is_none() && self.carries_float_op(a)
            })
    }
}

/// Nodes used as a whole vector: passed to a call or returned.
fn whole_uses(f: &Func) -> Vec<bool> {
    let mut whole = vec![false; f.nodes.len()];
    for r in &f.rets {
        whole[r.node as usize] |= r.lane.is_none();
    }
    for n in &f.nodes {
        if matches!(n.op, Op::Call(_)) {
            for a in n.args.iter().filter(|a| a.lane.is_none()) {
                whole[a.node as usize] = true;
            }
        }
    }
    whole
}

/// Node ids the return value depends on.
fn live(f: &Func) -> Vec<bool> {
    let mut live = vec![false; f.nodes.len()];
    let mut stack: Vec<usize> = f.rets.iter().map(|r| r.node as usize).collect();
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

/// Builtin functions of the languages (and of C's `<math.h>`) that a value's name could
/// plausibly be: a local of that name hides the function for the rest of its scope in
/// GLSL and WGSL, and reads as a call to a programmer in any language.
const BUILTINS: &[&str] = &[
    "abs",
    "acos",
    "all",
    "any",
    "asin",
    "atan",
    "atan2",
    "bitcast",
    "ceil",
    "clamp",
    "cos",
    "cross",
    "degrees",
    "determinant",
    "distance",
    "dot",
    "exp",
    "exp2",
    "faceforward",
    "floor",
    "fma",
    "fmod",
    "fract",
    "frexp",
    "inverse",
    "ldexp",
    "length",
    "lerp",
    "log",
    "log2",
    "mad",
    "max",
    "min",
    "mix",
    "modf",
    "normalize",
    "pow",
    "radians",
    "rcp",
    "reflect",
    "refract",
    "round",
    "rsqrt",
    "saturate",
    "select",
    "sign",
    "sin",
    "smoothstep",
    "sqrt",
    "step",
    "tan",
    "transpose",
    "trunc",
];

/// Statements being written: the body so far and the names taken.
struct Body {
    lines: Vec<String>,
    used: HashSet<String>,
    temps: usize,
}

impl Ctx<'_> {
    /// The name a value takes from what computes it, where the model gives it none: a
    /// helper's result takes the helper's name (`round_codes`, `abs_normal` for
    /// `abs(normal)`), a named value squared its name and `_sq`, negated `neg_` and its
    /// name, converted its name and `_u` or `_f`.
    fn derived_name(&self, id: usize) -> Option<String> {
        let n = &self.f.nodes[id];
        let named = |r: Ref| -> Option<String> {
            let a = r.node as usize;
            let base = match &self.f.nodes[a].op {
                Op::Param(i) => self.f.params[*i].0.clone(),
                _ => self.names[a].clone()?,
            };
            Some(match r.lane {
                Some(l) => format!("{base}_{}", LANE[l as usize]),
                None => base,
            })
        };
        match &n.op {
            Op::Call(callee) => Some(callee.clone()),
            Op::Un(u @ (UnOp::Abs | UnOp::Floor | UnOp::Round | UnOp::Sqrt)) => {
                let op = match u {
                    UnOp::Abs => "abs",
                    UnOp::Floor => "floor",
                    UnOp::Round => "round",
                    _ => "sqrt",
                };
                Some(format!("{op}_{}", named(n.args[0])?))
            }
            Op::Bin(BinOp::Mul) if n.args[0] == n.args[1] => {
                Some(format!("{}_sq", named(n.args[0])?))
            }
            Op::Un(UnOp::Neg) => Some(format!("neg_{}", named(n.args[0])?)),
            Op::Convert => {
                let to = match n.ty.kind {
                    Kind::F32 => "f",
                    Kind::U32 => "u",
                    Kind::Bool => "b",
                };
                Some(format!("{}_{to}", named(n.args[0])?))
            }
            _ => None,
        }
    }

    /// Declares node `id` under its model name, `hint`, a name derived from what computes
    /// it, or the next temporary's name. A name taken already gets a number, after an
    /// underscore where it ends in a digit.
    fn declare(&mut self, id: usize, hint: Option<&str>, body: &mut Body) {
        let node = &self.f.nodes[id];
        let base = match node.name.map(str::to_string).or(hint.map(str::to_string)) {
            Some(n) => n,
            None => match self.derived_name(id) {
                Some(n) => n,
                None => loop {
                    body.temps += 1;
                    let t = format!("t{}", body.temps);
                    if !body.used.contains(&t) {
                        break t;
                    }
                },
            },
        };
        let mut name = base.clone();
        let mut k = 1;
        let sep = if base.ends_with(|c: char| c.is_ascii_digit()) {
            "_"
        } else {
            ""
        };
        while !body.used.insert(name.clone()) {
            k += 1;
            name = format!("{base}{sep}{k}");
        }
        self.folded[id] = false;
        let e = self.expr(id);
        body.lines.push(self.lang.declare(&name, node.ty, &e));
        self.names[id] = Some(name);
    }

    /// Where float declarations are `precise`: declares the float values folded into `refs`
    /// that no float declaration would otherwise cover (below a call, a non-float
    /// declaration or `return`), looking through folded non-float values.
    fn declare_uncovered(&mut self, refs: &[Ref], hint: Option<&str>, body: &mut Body) {
        for r in refs {
            let id = r.node as usize;
            if self.names[id].is_some() {
                continue;
            }
            let n = &self.f.nodes[id];
            let folded = self.folded[id] || self.inline(id);
            if self.folded[id] && n.ty.kind == Kind::F32 && self.carries_float_op(id) {
                self.declare(id, hint, body);
            } else if folded {
                let args = n.args.clone();
                self.declare_uncovered(&args, None, body);
            }
        }
    }
}

/// How often each value's text appears when every operation has a statement of its own,
/// and where.
fn uses(
    lang: &dyn Backend,
    f: &Func,
    live: &[bool],
    fn_name: &dyn Fn(&str) -> String,
) -> Vec<Uses> {
    let mut ctx = Ctx {
        lang,
        f,
        whole: whole_uses(f),
        names: vec![None; f.nodes.len()],
        folded: vec![false; f.nodes.len()],
        fn_name,
    };
    let declared: Vec<usize> = (0..f.nodes.len())
        .filter(|&id| live[id] && !ctx.inline(id))
        .collect();
    for &id in &declared {
        ctx.names[id] = Some(marker(id));
    }
    let mut uses = vec![Uses::default(); f.nodes.len()];
    for &id in &declared {
        count_markers(&ctx.expr(id), User::Node(id), &mut uses);
    }
    for &r in &f.rets {
        count_markers(&ctx.r(r), User::Return, &mut uses);
    }
    uses
}

/// Prints `f` in `lang`; `fn_name` maps a traced function's local name to the name it is
/// defined and called by.
pub fn print(lang: &dyn Backend, f: &Func, fn_name: &dyn Fn(&str) -> String) -> Printed {
    print_as(lang, f, fn_name, Style::Folded)
}

/// [`print`] in the given [`Style`].
pub fn print_as(
    lang: &dyn Backend,
    f: &Func,
    fn_name: &dyn Fn(&str) -> String,
    style: Style,
) -> Printed {
    let live = live(f);
    let uses = uses(lang, f, &live, fn_name);
    let mut ctx = Ctx {
        lang,
        f,
        whole: whole_uses(f),
        names: vec![None; f.nodes.len()],
        folded: vec![false; f.nodes.len()],
        fn_name,
    };
    let mut body = Body {
        lines: Vec::new(),
        used: f.params.iter().map(|p| p.0.clone()).collect(),
        temps: 0,
    };
    body.used
        .extend(RESERVED.iter().chain(BUILTINS).map(|w| w.to_string()));
    body.used.extend(f.shape.map(|s| s.name.to_string()));
    // A value named like a function it calls would hide that function.
    body.used.extend(f.nodes.iter().filter_map(|n| match &n.op {
        Op::Call(c) => Some(fn_name(c)),
        _ => None,
    }));
    let precise = lang.precise_declarations();
    for (id, node) in f.nodes.iter().enumerate() {
        if !live[id] || ctx.inline(id) {
            continue;
        }
        if precise && matches!(node.op, Op::Call(_)) {
            ctx.declare_uncovered(&node.args, None, &mut body);
        }
        if style == Style::Folded && may_fold(&ctx, id, &uses[id]) {
            ctx.folded[id] = true;
            // `return x;` is no longer than `let t = x;`.
            if uses[id].users == [User::Return] || ctx.operations(id) <= FOLD_OPERATIONS {
                continue;
            }
        }
        if precise && node.ty.kind != Kind::F32 {
            ctx.folded[id] = false;
            ctx.declare_uncovered(&node.args, None, &mut body);
        }
        ctx.declare(id, None, &mut body);
    }
    match f.shape {
        None => {
            if precise {
                ctx.declare_uncovered(&f.rets, Some("result"), &mut body);
            }
            body.lines.push(format!("return {};", ctx.r(f.rets[0])));
        }
        Some(shape) => {
            let mut values = Vec::new();
            for (&r, field) in f.rets.iter().zip(shape.fields) {
                if precise {
                    ctx.declare_uncovered(&[r], Some(field), &mut body);
                }
                values.push(ctx.r(r));
            }
            // Where the language builds the struct in a declaration, that declaration
            // takes the shape's own name, which no value has taken (see `used` above).
            body.lines
                .extend(lang.return_struct(&fn_name(shape.name), shape.name, &values));
        }
    }
    Printed {
        name: fn_name(&f.name),
        params: f
            .params
            .iter()
            .map(|(n, t)| (n.clone(), lang.ty(*t)))
            .collect(),
        ret_ty: match f.shape {
            Some(shape) => fn_name(shape.name),
            None => lang.ty(f.ret_tys[0]),
        },
        body: body.lines,
    }
}

/// Whether node `id` may be written inside the expression that uses it.
fn may_fold(ctx: &Ctx, id: usize, uses: &Uses) -> bool {
    let n = &ctx.f.nodes[id];
    let vectors = ctx.lang.has_vectors();
    if n.name.is_some() || uses.users.is_empty() {
        return false;
    }
    // Once, or without vector values once per lane (each lane is its own expression).
    let once = uses.total() == 1
        || (!vectors
            && !matches!(n.op, Op::Call(_))
            && uses.whole == 0
            && uses.lanes.iter().all(|&k| k <= 1));
    // A brace initializer is no expression: a vector passed or returned whole is declared.
    let braced = !vectors && n.ty.lanes > 1 && uses.whole > 0;
    let contracted = ctx.lang.contracts_expressions()
        && n.ty.kind == Kind::F32
        && n.op == Op::Bin(BinOp::Mul)
        && uses.users.iter().any(|u| match u {
            User::Node(c) => matches!(
                ctx.f.nodes[*c].op,
                Op::Bin(BinOp::Add | BinOp::Sub) | Op::Un(UnOp::Neg)
            ),
            User::Return => false,
        });
    // Through an inline swizzle or literal vector, an operand is still this value.
    let refers = |r: &Ref| {
        let a = r.node as usize;
        a == id || (ctx.inline(a) && ctx.f.nodes[a].args.iter().any(|b| b.node as usize == id))
    };
    let lazy = uses.users.iter().any(|u| match u {
        User::Node(c) => {
            let c = &ctx.f.nodes[*c];
            let mask_is_vector = c.args.first().is_some_and(|m| ctx.f.ty_of(*m).lanes > 1);
            ctx.lang
                .lazy_operands(&c.op, c.ty, mask_is_vector)
                .iter()
                .any(|&i| refers(&c.args[i]))
        }
        User::Return => false,
    });
    once && !braced && !contracted && !lazy
}
