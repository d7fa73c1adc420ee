//! The numeric vocabulary every codec is written in.
//!
//! A codec is generic over [`Float`]. Instantiated with `f32` it *is* the CPU reference;
//! instantiated with [`crate::model::trace::T`] it records the expression graph that the
//! printers turn into shader code. The vocabulary holds exactly the operations that agree
//! bit for bit between Rust and the drivers (README, "Why the emitted code is bit-exact"):
//! there is no `fma`, no `sign`, no `min`/`max`, no transcendental and no pack builtin, so a
//! codec that needs one does not compile.
//! Literal division and constant expressions are refused by the tracer at record time.
//!
//! A codec cannot reach a forbidden builtin, even though `f32` itself has them:
//!
//! ```compile_fail
//! fn fused<F: unitpack::model::Float>(a: F, b: F, c: F) -> F { a.mul_add(b, c) }
//! ```
//! ```compile_fail
//! fn trig<F: unitpack::model::Float>(a: F) -> F { a.sin() }
//! ```
//! ```compile_fail
//! fn sign<F: unitpack::model::Float>(a: F) -> F { a.signum() }
//! ```
//! ```compile_fail
//! fn minimum<F: unitpack::model::Float>(a: F, b: F) -> F { a.min(b) }
//! ```
//! The same code written with the vocabulary compiles:
//! ```
//! fn fused<F: unitpack::model::Float>(a: F, b: F, c: F) -> F { a * b + c }
//! assert_eq!(fused(2.0f32, 3.0, 1.0), 7.0);
//! ```

use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Sub};

/// The scalar kinds a traced value can have.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Kind {
    F32,
    U32,
    Bool,
}

/// Everything that can sit in one lane of a vector. The two hooks are identities when
/// evaluating; the tracer uses them to turn componentwise work back into vector syntax
/// and to give intermediates readable names.
pub trait Lane: Copy + 'static + Value {
    const KIND: Kind;
    /// Called by the vector helpers on the lanes of every componentwise result.
    #[inline(always)]
    fn fuse<const L: usize>(lanes: [Self; L]) -> [Self; L] {
        lanes
    }
    /// Names the intermediate in emitted code (`let len1 = ...`).
    #[inline(always)]
    fn named(self, _name: &'static str) -> Self {
        self
    }
    /// Names the vector made of `lanes` in emitted code.
    #[inline(always)]
    fn named_lanes<const L: usize>(lanes: [Self; L], _name: &'static str) -> [Self; L] {
        lanes
    }
}

/// Boolean masks produced by comparisons.
pub trait Bool: Lane {
    fn and(self, o: Self) -> Self;
    fn or(self, o: Self) -> Self;
    fn not(self) -> Self;
}

/// 32-bit unsigned integers: the packed code and the bit fields inside it.
pub trait Uint:
    Lane + Add<Output = Self> + Sub<Output = Self> + BitAnd<Output = Self> + BitOr<Output = Self>
{
    type F: Float<U = Self, B = Self::B>;
    type B: Bool;
    fn c(v: u32) -> Self;
    fn shl(self, n: u32) -> Self;
    fn shr(self, n: u32) -> Self;
    /// Exact conversion for values below 2^24 (all the model ever converts).
    fn to_f(self) -> Self::F;
    /// The float with these bits (WGSL `bitcast<f32>`, GLSL `uintBitsToFloat`, HLSL
    /// `asfloat`): exact everywhere. The model only makes normal floats this way.
    fn as_float(self) -> Self::F;
    fn sel(m: Self::B, if_true: Self, if_false: Self) -> Self;
    /// `self + o` modulo 2^32, which is what `+` on 32-bit unsigned integers means in
    /// every shader language and in C. Integer arithmetic has no rounding, so no
    /// implementation, optimiser or regrouping can change a result built from it.
    fn wrapping_add(self, o: Self) -> Self;
    /// `self - o` modulo 2^32: a negative difference is its two's complement.
    fn wrapping_sub(self, o: Self) -> Self;
    /// `self · o` modulo 2^32 (the low word of the product).
    fn wrapping_mul(self, o: Self) -> Self;
    fn lt(self, o: Self) -> Self::B;
    /// The `b`-bit two's complement field `self` (below `2^b`, `b ≤ 24`) as a float: the
    /// unsigned value converted, less `2^b` where it is above `2^(b-1) - 1`, both exact,
    /// as the emitted code computes it. Lanes may sign-extend the integer and convert it
    /// instead, the same value in fewer instructions.
    #[inline(always)]
    fn signed_field(self, b: u32) -> Self::F {
        let c = self.to_f();
        let wrapped = c - Self::F::c((1u32 << b) as f32);
        Self::F::sel(c.gt(Self::F::c(((1u32 << (b - 1)) - 1) as f32)), wrapped, c)
    }
}

/// 32-bit IEEE floats with round-to-nearest-even arithmetic.
pub trait Float:
    Lane
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    type U: Uint<F = Self, B = Self::B>;
    type B: Bool;
    /// A literal. Compute constants in Rust (`F::c(1.0 / 2047.0)`) so the shader
    /// receives the exact f32 the model uses.
    fn c(v: f32) -> Self;
    fn abs(self) -> Self;
    fn sqrt(self) -> Self;
    fn floor(self) -> Self;
    /// Round half to even, which is what `round` compiles to on every target.
    fn round(self) -> Self;
    fn lt(self, o: Self) -> Self::B;
    fn le(self, o: Self) -> Self::B;
    fn gt(self, o: Self) -> Self::B;
    fn ge(self, o: Self) -> Self::B;
    fn eq(self, o: Self) -> Self::B;
    /// `m ? if_true : if_false` without branching and without any ±0/NaN surprise.
    fn sel(m: Self::B, if_true: Self, if_false: Self) -> Self;
    /// Exact conversion of a non-negative integral value below 2^32.
    fn to_u(self) -> Self::U;
    /// The IEEE bits (WGSL `bitcast<u32>`, GLSL `floatBitsToUint`, HLSL `asuint`): no
    /// arithmetic, so no implementation can change them.
    fn to_bits(self) -> Self::U;
    /// The bits of `|self|` (exponent and mantissa, the sign cleared): what NaN,
    /// infinity, zero and the binade are decided on. A compiler may fold a float
    /// comparison with NaN or infinity where `precise` is absent (Mesa's OpenGL GLSL
    /// compiler folds `|x| <= MAX` to true); an integer comparison of a bitcast means
    /// the same everywhere.
    #[inline(always)]
    fn magnitude_bits(self) -> Self::U {
        self.to_bits() & Self::U::c(0x7fff_ffff)
    }
    /// `self ≥ lo ? self : lo`, a select rather than a `max` builtin, whose ±0 and NaN
    /// results differ between drivers. A NaN `self` gives `lo`; when the two compare
    /// equal (`-0` and `+0`) `self` is kept.
    #[inline(always)]
    fn at_least(self, lo: Self) -> Self {
        Self::sel(self.ge(lo), self, lo)
    }
    /// [`Float::at_least`] of a bound `lo` that is neither zero nor NaN: there it is
    /// `max(self, lo)` with a NaN `self` giving `lo`, since only a zero bound tells `-0`
    /// from `+0`. The emitted code keeps the select; lanes may take their `max`
    /// instruction, which returns its second operand for a NaN.
    #[inline(always)]
    fn at_least_nonzero(self, lo: f32) -> Self {
        self.at_least(Self::c(lo))
    }
    /// `self ≤ hi ? self : hi`: a NaN `self` gives `hi`; on equality `self` is kept.
    #[inline(always)]
    fn at_most(self, hi: Self) -> Self {
        Self::sel(self.le(hi), self, hi)
    }
    /// `self` with its sign flipped where `m` holds, as a product with `-1` or `1`: the
    /// same bits as `m ? -self : self` for every number, zeros included. A decoder's
    /// hemisphere flip is written this way because a SPIR-V optimizer (spirv-opt, which
    /// SwiftShader and so the browsers run) rewrites the negation of a difference with a
    /// constant, `-(1 - q)`, as `q - 1`: `+0` where the model's negation gives `-0`. A
    /// product with a selected sign is not rewritten.
    #[inline(always)]
    fn negated_where(self, m: Self::B) -> Self {
        self * Self::sel(m, Self::c(-1.0), Self::c(1.0))
    }
    /// `self` limited to `[lo, hi]` (`lo ≤ hi`): [`Float::at_least`] then
    /// [`Float::at_most`], so a NaN `self` gives `lo`.
    #[inline(always)]
    fn clamped(self, lo: Self, hi: Self) -> Self {
        self.at_least(lo).at_most(hi)
    }
    /// Calls a helper function. Evaluating, that is just `f(a)`; tracing, the helper is
    /// traced once into its own shader function, its parameters named `params` (where an
    /// argument's text is no identifier, after its type), and the call site prints a call.
    /// [`helper!`] writes the common call, a model function of up to four arguments
    /// named after itself.
    #[inline(always)]
    fn call<A: Value, R: Value>(
        _name: &'static str,
        _params: &[&'static str],
        a: A,
        f: impl FnOnce(A) -> R,
    ) -> R {
        f(a)
    }
}

/// Calls a function of the model as a helper function of the emitted code
/// ([`Float::call`]), named after it, with its arguments packed as the helper's one
/// argument and unpacked again:
///
/// - `helper!(atan2_pi(y, x))` is
///   `F::call("atan2_pi", &["y", "x"], (y, x), |(y, x)| atan2_pi(y, x))`;
/// - `helper!(self.fixed_point(i))` calls a method, named after the method;
/// - `helper!("fixed_sincos_pi" => fixed_trig::sincos_pi(t))` names the helper where
///   the function's name is taken or is a path.
///
/// `F` is the caller's float type parameter, which every model function calls `F`; one
/// to four arguments.
macro_rules! helper {
    ($name:literal => $recv:ident . $m:ident ($($a:expr),+ $(,)?)) => {
        $crate::model::num::helper!(@call $name, [$recv.$m], $($a),+)
    };
    ($name:literal => $($f:ident)::+ ($($a:expr),+ $(,)?)) => {
        $crate::model::num::helper!(@call $name, [$($f)::+], $($a),+)
    };
    ($recv:ident . $m:ident ($($a:expr),+ $(,)?)) => {
        $crate::model::num::helper!(@call stringify!($m), [$recv.$m], $($a),+)
    };
    ($f:ident ($($a:expr),+ $(,)?)) => {
        $crate::model::num::helper!(@call stringify!($f), [$f], $($a),+)
    };
    (@call $name:expr, [$($f:tt)+], $a:expr) => {
        F::call($name, &[stringify!($a)], $a, #[inline(always)] |a| $($f)+(a))
    };
    (@call $name:expr, [$($f:tt)+], $a:expr, $b:expr) => {
        F::call(
            $name,
            &[stringify!($a), stringify!($b)],
            ($a, $b),
            #[inline(always)]
            |(a, b)| $($f)+(a, b),
        )
    };
    (@call $name:expr, [$($f:tt)+], $a:expr, $b:expr, $c:expr) => {
        F::call(
            $name,
            &[stringify!($a), stringify!($b), stringify!($c)],
            ($a, ($b, $c)),
            #[inline(always)]
            |(a, (b, c))| $($f)+(a, b, c),
        )
    };
    (@call $name:expr, [$($f:tt)+], $a:expr, $b:expr, $c:expr, $d:expr) => {
        F::call(
            $name,
            &[stringify!($a), stringify!($b), stringify!($c), stringify!($d)],
            ($a, ($b, ($c, $d))),
            #[inline(always)]
            |(a, (b, (c, d)))| $($f)+(a, b, c, d),
        )
    };
}
pub(crate) use helper;

impl Lane for f32 {
    const KIND: Kind = Kind::F32;
}
impl Lane for u32 {
    const KIND: Kind = Kind::U32;
}
impl Lane for bool {
    const KIND: Kind = Kind::Bool;
}

impl Bool for bool {
    #[inline(always)]
    fn and(self, o: Self) -> Self {
        self & o
    }
    #[inline(always)]
    fn or(self, o: Self) -> Self {
        self | o
    }
    #[inline(always)]
    fn not(self) -> Self {
        !self
    }
}

impl Uint for u32 {
    type F = f32;
    type B = bool;
    #[inline(always)]
    fn c(v: u32) -> Self {
        v
    }
    #[inline(always)]
    fn shl(self, n: u32) -> Self {
        self << n
    }
    #[inline(always)]
    fn shr(self, n: u32) -> Self {
        self >> n
    }
    #[inline(always)]
    fn to_f(self) -> f32 {
        self as f32
    }
    #[inline(always)]
    fn as_float(self) -> f32 {
        f32::from_bits(self)
    }
    #[inline(always)]
    fn sel(m: bool, t: Self, f: Self) -> Self {
        if m { t } else { f }
    }
    #[inline(always)]
    fn wrapping_add(self, o: Self) -> Self {
        u32::wrapping_add(self, o)
    }
    #[inline(always)]
    fn wrapping_sub(self, o: Self) -> Self {
        u32::wrapping_sub(self, o)
    }
    #[inline(always)]
    fn wrapping_mul(self, o: Self) -> Self {
        u32::wrapping_mul(self, o)
    }
    #[inline(always)]
    fn lt(self, o: Self) -> bool {
        self < o
    }
}

/// `f32::round_ties_even`, inline: on the baseline x86-64 target (no SSE4.1 `roundss`)
/// the library call dominated the models' evaluation. Adding and removing 2^23 rounds to
/// an integer, half to even, for every magnitude below 2^23; larger values, infinities
/// and NaN already are what rounding returns.
#[inline(always)]
fn round_even(x: f32) -> f32 {
    const TWO_23: f32 = 8_388_608.0;
    if x.abs() < TWO_23 {
        ((x.abs() + TWO_23) - TWO_23).copysign(x)
    } else {
        x
    }
}

impl Float for f32 {
    type U = u32;
    type B = bool;
    #[inline(always)]
    fn c(v: f32) -> Self {
        v
    }
    #[inline(always)]
    fn abs(self) -> Self {
        f32::abs(self)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f32::sqrt(self)
    }
    #[inline(always)]
    fn floor(self) -> Self {
        let r = round_even(self);
        if r > self { r - 1.0 } else { r }
    }
    #[inline(always)]
    fn round(self) -> Self {
        round_even(self)
    }
    #[inline(always)]
    fn lt(self, o: Self) -> bool {
        self < o
    }
    #[inline(always)]
    fn le(self, o: Self) -> bool {
        self <= o
    }
    #[inline(always)]
    fn gt(self, o: Self) -> bool {
        self > o
    }
    #[inline(always)]
    fn ge(self, o: Self) -> bool {
        self >= o
    }
    #[inline(always)]
    fn eq(self, o: Self) -> bool {
        self == o
    }
    #[inline(always)]
    fn sel(m: bool, t: Self, f: Self) -> Self {
        if m { t } else { f }
    }
    #[inline(always)]
    fn to_u(self) -> u32 {
        self as u32
    }
    #[inline(always)]
    fn to_bits(self) -> u32 {
        f32::to_bits(self)
    }
}

/// The type of a graph value: a scalar kind and 1 to 4 lanes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Ty {
    pub kind: Kind,
    pub lanes: u8,
}

impl Ty {
    pub const fn scalar(kind: Kind) -> Ty {
        Ty { kind, lanes: 1 }
    }
}

/// A reference to a node's value, or to one lane of a vector node.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Ref {
    pub node: u32,
    pub lane: Option<u8>,
}

/// Values that can be function parameters and results: traced scalars, vectors of them,
/// and tuples of those (parameters only).
pub trait Value: Copy {
    fn tys() -> Vec<Ty>;
    fn refs(self) -> Vec<Ref>;
    fn from_refs(r: &mut dyn Iterator<Item = Ref>) -> Self;
}

/// [`Value`] for number types that are evaluated, never traced (`f32`, the adversarial
/// and the enclosure evaluators).
macro_rules! value_eval {
    ($($t:ty),*) => {$(
        /// Evaluated values never cross a traced call boundary; `call` runs the closure.
        impl $crate::model::num::Value for $t {
            fn tys() -> Vec<$crate::model::num::Ty> {
                vec![$crate::model::num::Ty::scalar(<$t as $crate::model::Lane>::KIND)]
            }
            fn refs(self) -> Vec<$crate::model::num::Ref> {
                unreachable!("evaluated values are not traced")
            }
            fn from_refs(_: &mut dyn Iterator<Item = $crate::model::num::Ref>) -> Self {
                unreachable!("evaluated values are not traced")
            }
        }
    )*};
}
pub(crate) use value_eval;
value_eval!(f32, u32, bool);

impl<A: Value, B: Value, C: Value> Value for (A, B, C) {
    fn tys() -> Vec<Ty> {
        let mut t = <(A, B)>::tys();
        t.extend(C::tys());
        t
    }
    fn refs(self) -> Vec<Ref> {
        let mut r = (self.0, self.1).refs();
        r.extend(self.2.refs());
        r
    }
    fn from_refs(r: &mut dyn Iterator<Item = Ref>) -> Self {
        let (a, b) = <(A, B)>::from_refs(r);
        (a, b, C::from_refs(r))
    }
}

impl<A: Value, B: Value> Value for (A, B) {
    fn tys() -> Vec<Ty> {
        let mut t = A::tys();
        t.extend(B::tys());
        t
    }
    fn refs(self) -> Vec<Ref> {
        let mut r = self.0.refs();
        r.extend(self.1.refs());
        r
    }
    fn from_refs(r: &mut dyn Iterator<Item = Ref>) -> Self {
        let a = A::from_refs(r);
        (a, B::from_refs(r))
    }
}
