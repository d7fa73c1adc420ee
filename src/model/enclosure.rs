//! Enclosures: the model's vocabulary evaluated over a *set* of inputs and over *every*
//! implementation the guaranteed deviation classes allow at once, to prove how far a
//! decoder's output can move ([`crate::measure::decode_bound`]).
//!
//! An [`Encl`] holds two intervals: `[lo, hi]` contains the reference value (the `f32`
//! model, every operation correctly rounded) for every input of the set, and
//! `[elo, ehi]` contains `deviant − reference` for every input and every allowed
//! implementation: `div` (quotients within [`DIV_ULP`]), `sqrt` (roots within
//! [`SQRT_ULP`]), `fma` (any `a*b + c` rounded once), `denorm` (denormal operands and
//! results flushed) and `zero` (signs of zeros lost), all together rather than one class at
//! a time as [`crate::model::deviant`] samples them. Every step rounds outward, so the
//! enclosures only ever grow: a bound read off them is proven, not sampled.
//!
//! How each operation moves the deviation (`u` is the f32 ULP at the largest magnitude the
//! result can have):
//! - `+ - *`: correctly rounded on both sides, so identical operands give identical
//!   results (`e = 0`); otherwise the operands' deviations propagate (`a'b' − ab =
//!   a·e_b + b'·e_a`) and the two roundings add at most `u`. A product also carries
//!   `fused`, half its ULP: what a contracted `a*b + c` gains by skipping its rounding.
//! - `/`, `sqrt`: the propagated deviation (`(e_a·b − a·e_b)/(b·b')`,
//!   `e_a/(√a + √a')`), plus `DIV_ULP + ½` or `SQRT_ULP + ½` ULP: the deviant's latitude
//!   and the reference's rounding.
//! - denormals: each value carries a grid (a power of two every value is a multiple of);
//!   only where that grid is below the smallest normal can a value be denormal, and only
//!   then may flushing add up to `2^-126`.
//! - comparisons: the same outcome for reference and deviant when both operands are
//!   undeviated, or when both sides' intervals decide it; otherwise a select may take
//!   either operand, and the deviation covers the jump between them.
//! - signs of zeros do not move a real value; an operation whose result would depend on one
//!   (`1/±0`, the bits of a zero) is unbounded instead.
//!
//! Anything the enclosure cannot bound (a possible division by zero, a root of a possibly
//! negative value, an integer built from a deviated float) becomes an infinite deviation,
//! which the bound reports rather than hides.

use super::deviant::{DIV_ULP, SQRT_ULP};
use super::num::{Bool, Float, Kind, Lane, Uint};
use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Sub};

/// The smallest normal f32.
pub const MIN_NORMAL: f64 = 1.1754943508222875e-38;

/// An interval `(lo, hi)`.
type Iv = (f64, f64);

/// An f32 value over a set of inputs and implementations.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Encl {
    /// Bounds of the reference value.
    lo: f64,
    hi: f64,
    /// Bounds of every deviant value (as an interval of its own: a select or a clamp can
    /// bound it where `reference + deviation` cannot).
    dev: Iv,
    /// Bounds of `deviant − reference`.
    e: Iv,
    /// For a product: how far a contracted `a*b + c` may see it from its rounding.
    fused: f64,
    /// A power of two every value (reference and deviant) is an integer multiple of.
    grid: f64,
}

/// A `u32` over a set of inputs: `[lo, hi]`, and whether it is the same for the
/// reference and every deviant (integer arithmetic never deviates; an integer made from
/// a deviated float may).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EnclU {
    pub lo: u64,
    pub hi: u64,
    pub exact: bool,
}

/// A comparison over a set: whether the reference may be true, may be false, whether
/// every deviant agrees with the reference input by input, and, for `a < b` or `a ≤ b`
/// (after any `not`), the operands `(a, b)`: a select between them is then a minimum or a
/// maximum, which moves no further than its operands do.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EnclB {
    t: bool,
    f: bool,
    agree: bool,
    order: Option<(Encl, Encl)>,
}

/// The f32 ULP of magnitudes up to `m`: the spacing of floats in the binade of `m`.
pub fn ulp(m: f64) -> f64 {
    let m = m.abs();
    if m < MIN_NORMAL {
        return pow2(-149);
    }
    if !m.is_finite() {
        // Unbounded (or unknown) magnitudes have an unbounded spacing.
        return f64::INFINITY;
    }
    // The binade is the f64 exponent field: exact, and this runs millions of times.
    pow2(((m.to_bits() >> 52) as i32) - 1023 - 23)
}

/// `2^e`, exactly, for the exponents f32 arithmetic meets (normal f64 powers of two).
fn pow2(e: i32) -> f64 {
    debug_assert!((-1022..=1023).contains(&e));
    f64::from_bits(((e + 1023) as u64) << 52)
}

/// Whether `c` is a power of two (of either sign).
fn is_pow2(c: f64) -> bool {
    c.is_normal() && c.to_bits() & ((1u64 << 52) - 1) == 0
}

/// The largest power of two `x` is a multiple of (infinite for zero, which is a multiple
/// of everything).
fn lowest_bit(x: f32) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return if x == 0.0 { f64::INFINITY } else { 0.0 };
    }
    let b = x.to_bits();
    let exp = ((b >> 23) & 0xff) as i32;
    let mant = b & 0x7f_ffff | if exp > 0 { 0x80_0000 } else { 0 };
    pow2(exp.max(1) - 150 + mant.trailing_zeros() as i32)
}

/// The f32 nearest to `x`, as f64 (monotone in `x`).
fn f32_of(x: f64) -> f64 {
    f64::from(x as f32)
}

/// The range of a correctly rounded result whose exact value lies in `x` (f32 rounding
/// is monotone, so the ends' roundings bound it).
fn rounded(x: Iv) -> Iv {
    (f32_of(x.0), f32_of(x.1))
}

/// `s = a ∘ b` rounded in f64, and the sign of the exact result minus `s`: the f64 step
/// is only taken where f64 rounding actually lost something, so exact sums of f32
/// values (an `1 - d` that is exactly 0, say) keep their sign.
fn outward(s: f64, err: f64) -> Iv {
    if !s.is_finite() {
        return (s, s);
    }
    (
        if err < 0.0 { s.next_down() } else { s },
        if err > 0.0 { s.next_up() } else { s },
    )
}

fn add(a: f64, b: f64) -> Iv {
    let s = a + b;
    let bb = s - a;
    outward(s, (a - (s - bb)) + (b - bb))
}

fn mul(a: f64, b: f64) -> Iv {
    let p = a * b;
    // Two f32 values (24-bit significands, exponents far inside f64's range) multiply
    // exactly in f64: most products here are of f32 bounds, and this skips the fused
    // multiply-add, a library call on CPUs the build does not assume FMA for.
    if f32_of(a) == a && f32_of(b) == b {
        return (p, p);
    }
    outward(p, a.mul_add(b, -p))
}

fn hull(v: &[f64]) -> Iv {
    let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    (lo.next_down(), hi.next_up())
}

fn join(a: Iv, b: Iv) -> Iv {
    (a.0.min(b.0), a.1.max(b.1))
}

fn imul(a: Iv, b: Iv) -> Iv {
    if a == (0.0, 0.0) || b == (0.0, 0.0) {
        return (0.0, 0.0);
    }
    [mul(a.0, b.0), mul(a.0, b.1), mul(a.1, b.0), mul(a.1, b.1)]
        .into_iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), join)
}

fn iadd(a: Iv, b: Iv) -> Iv {
    (add(a.0, b.0).0, add(a.1, b.1).1)
}

fn ineg(a: Iv) -> Iv {
    (-a.1, -a.0)
}

/// `a / b` for `b` of one sign.
fn idiv(a: Iv, b: Iv) -> Iv {
    if a == (0.0, 0.0) {
        return (0.0, 0.0);
    }
    hull(&[a.0 / b.0, a.0 / b.1, a.1 / b.0, a.1 / b.1])
}

fn sym(m: f64) -> Iv {
    (-m, m)
}

fn widest(a: Iv) -> f64 {
    a.0.abs().max(a.1.abs())
}

fn one_sign(x: Iv) -> bool {
    x.0 > 0.0 || x.1 < 0.0
}

const EVERYTHING: Iv = (f64::NEG_INFINITY, f64::INFINITY);

impl Encl {
    /// A set of reference values in `[lo, hi]`, multiples of `grid`, undeviated.
    pub fn range(lo: f64, hi: f64, grid: f64) -> Encl {
        Encl {
            lo,
            hi,
            dev: (lo, hi),
            e: (0.0, 0.0),
            fused: 0.0,
            grid,
        }
    }
    /// A result: a value that may be denormal may also be flushed to zero, which widens
    /// both the deviant range and the deviation.
    fn result(r: Iv, dev: Iv, e: Iv, grid: f64) -> Encl {
        let mut x = Encl {
            lo: r.0,
            hi: r.1,
            dev,
            e,
            fused: 0.0,
            grid,
        };
        let (a, b) = join(r, dev);
        if grid < MIN_NORMAL && a < MIN_NORMAL && b > -MIN_NORMAL {
            x.dev = join(x.dev, (0.0, 0.0));
            x.e = iadd(x.e, sym(MIN_NORMAL));
        }
        let sum = iadd(r, x.e);
        x.dev = (x.dev.0.max(sum.0), x.dev.1.min(sum.1));
        x
    }
    /// Nothing can be said.
    pub fn unknown() -> Encl {
        Encl {
            lo: f64::NEG_INFINITY,
            hi: f64::INFINITY,
            dev: EVERYTHING,
            e: EVERYTHING,
            fused: 0.0,
            grid: 0.0,
        }
    }
    /// The largest `|deviant − reference|` (infinite where unbounded).
    pub fn deviation(self) -> f64 {
        let w = widest(self.e);
        if w.is_nan() || self.lo.is_nan() || self.hi.is_nan() {
            f64::INFINITY
        } else {
            w
        }
    }
    /// The bounds of the reference value.
    pub fn reference(self) -> (f64, f64) {
        (self.lo, self.hi)
    }
    /// The bounds of every deviant value.
    pub fn deviants(self) -> (f64, f64) {
        self.dev
    }
    fn v(self) -> Iv {
        (self.lo, self.hi)
    }
    fn undeviated(self) -> bool {
        self.e == (0.0, 0.0)
    }
    /// The largest magnitude of the reference or a deviant.
    fn mag(r: Iv, dev: Iv) -> f64 {
        widest(r).max(widest(dev))
    }
    /// Whether the value is the constant `c` on every input and implementation.
    fn constant(self) -> Option<f64> {
        (self.lo == self.hi && self.undeviated()).then_some(self.lo)
    }
    /// The deviant range and deviation as an add sees them (a product possibly unrounded).
    fn addend(self) -> (Iv, Iv) {
        (
            iadd(self.dev, sym(self.fused)),
            iadd(self.e, sym(self.fused)),
        )
    }
    /// `a ± b` (`b` negated when `sub`).
    fn sum(self, o: Encl, sub: bool) -> Encl {
        let o = if sub { -o } else { o };
        let r = rounded(iadd(self.v(), o.v()));
        let grid = self.grid.min(o.grid);
        if self.undeviated() && o.undeviated() && self.fused == 0.0 && o.fused == 0.0 {
            return Encl::result(r, r, (0.0, 0.0), grid);
        }
        let (da, ea) = self.addend();
        let (db, eb) = o.addend();
        let dev = rounded(iadd(da, db));
        let e = iadd(iadd(ea, eb), sym(ulp(Encl::mag(r, dev))));
        Encl::result(r, dev, e, grid)
    }
    /// `floor` or `round`: `op` applied to the bounds (both are monotone); a deviation
    /// that may cross an integer step moves the result by whole steps.
    fn integral(self, op: fn(f64) -> f64) -> Encl {
        let r = (op(self.lo), op(self.hi));
        let dev = (op(self.dev.0), op(self.dev.1));
        let all = join(self.v(), self.dev);
        let e = if self.undeviated() || op(all.0) == op(all.1) {
            (0.0, 0.0)
        } else {
            (self.e.0.floor().min(-1.0), self.e.1.ceil().max(1.0))
        };
        Encl::result(r, dev, e, 1.0)
    }
    /// A comparison given `decided(a, b)` = `(always, never)` over intervals.
    fn compare(self, o: Encl, decided: fn(Iv, Iv) -> (bool, bool)) -> EnclB {
        let (always, never) = decided(self.v(), o.v());
        let (dev_always, dev_never) = decided(self.dev, o.dev);
        EnclB {
            t: !never,
            f: !always,
            agree: self.undeviated() && o.undeviated()
                || always && dev_always
                || never && dev_never,
            order: None,
        }
    }
    /// `min(a, b)` (or the maximum): monotone in both operands and moving no more than
    /// they do.
    fn extreme(a: Encl, b: Encl, max: bool) -> Encl {
        // One operand always the smaller (or larger), for the reference and every deviant:
        // the result is that operand.
        let below = |x: Encl, y: Encl| x.hi <= y.lo && x.dev.1 <= y.dev.0;
        match (below(a, b), below(b, a), max) {
            (true, _, false) | (_, true, true) => return a,
            (_, true, false) | (true, _, true) => return b,
            _ => {}
        }
        let pick = |x: f64, y: f64| if max { x.max(y) } else { x.min(y) };
        // A comparison may see a denormal operand flushed where the select returns it
        // unflushed: then the result misses the extreme by less than a normal.
        let grid = a.grid.min(b.grid);
        let slack = if grid < MIN_NORMAL { MIN_NORMAL } else { 0.0 };
        Encl::result(
            (pick(a.lo, b.lo), pick(a.hi, b.hi)),
            iadd((pick(a.dev.0, b.dev.0), pick(a.dev.1, b.dev.1)), sym(slack)),
            iadd(join(a.e, b.e), sym(slack)),
            grid,
        )
    }
}

impl Neg for Encl {
    type Output = Encl;
    fn neg(self) -> Encl {
        Encl {
            lo: -self.hi,
            hi: -self.lo,
            dev: ineg(self.dev),
            e: ineg(self.e),
            ..self
        }
    }
}

impl Add for Encl {
    type Output = Encl;
    fn add(self, o: Encl) -> Encl {
        self.sum(o, false)
    }
}

impl Sub for Encl {
    type Output = Encl;
    fn sub(self, o: Encl) -> Encl {
        self.sum(o, true)
    }
}

impl Mul for Encl {
    type Output = Encl;
    fn mul(self, o: Encl) -> Encl {
        let r = rounded(imul(self.v(), o.v()));
        let grid = self.grid * o.grid;
        // A product by zero, or by a power of two that cannot underflow, is exact: there
        // is no rounding for a contraction to skip.
        let pow2 = |c: Option<f64>| c.is_some_and(|c| c == 0.0 || is_pow2(c));
        let exact = pow2(self.constant()) && (grid >= MIN_NORMAL || self.constant() == Some(0.0))
            || pow2(o.constant()) && (grid >= MIN_NORMAL || o.constant() == Some(0.0));
        let mut x = if self.undeviated() && o.undeviated() {
            Encl::result(r, r, (0.0, 0.0), grid)
        } else {
            let dev = rounded(imul(self.dev, o.dev));
            // a'b' − ab = a·e_b + b'·e_a
            let e = iadd(imul(self.v(), o.e), imul(o.dev, self.e));
            let e = iadd(e, sym(ulp(Encl::mag(r, dev))));
            Encl::result(r, dev, e, grid)
        };
        if !exact && r != (0.0, 0.0) {
            x.fused = 0.5 * ulp(Encl::mag(x.v(), x.dev));
        }
        x
    }
}

impl Div for Encl {
    type Output = Encl;
    fn div(self, o: Encl) -> Encl {
        let (b, bd) = (o.v(), o.dev);
        if !one_sign(b) || !one_sign(bd) {
            return Encl::unknown();
        }
        let r = rounded(idiv(self.v(), b));
        let exact = idiv(self.dev, bd);
        let dev = iadd(exact, sym(DIV_ULP * ulp(widest(exact))));
        // A nonzero quotient is at least the numerator's grid over the largest divisor;
        // the deviant's within a few ULP of it.
        let smallest = self.grid / widest(b).max(widest(bd));
        // a'/b' − a/b = (e_a·b − a·e_b) / (b·b')
        let num = iadd(imul(self.e, b), ineg(imul(self.v(), o.e)));
        let e = idiv(num, imul(b, bd));
        let e = iadd(e, sym((DIV_ULP + 0.5) * ulp(Encl::mag(r, dev))));
        Encl::result(r, dev, e, ulp(smallest * 0.5))
    }
}

crate::model::num::value_eval!(Encl, EnclU, EnclB);

impl Lane for Encl {
    const KIND: Kind = Kind::F32;
}
impl Lane for EnclU {
    const KIND: Kind = Kind::U32;
}
impl Lane for EnclB {
    const KIND: Kind = Kind::Bool;
}

impl Bool for EnclB {
    fn and(self, o: Self) -> Self {
        let never = |b: EnclB| !b.t && b.agree;
        if never(self) || never(o) {
            return EnclB {
                t: false,
                f: true,
                agree: true,
                order: None,
            };
        }
        EnclB {
            t: self.t && o.t,
            f: self.f || o.f,
            agree: self.agree && o.agree,
            order: None,
        }
    }
    fn or(self, o: Self) -> Self {
        self.not().and(o.not()).not()
    }
    fn not(self) -> Self {
        // not (a < b) is b ≤ a.
        EnclB {
            t: self.f,
            f: self.t,
            agree: self.agree,
            order: self.order.map(|(a, b)| (b, a)),
        }
    }
}

impl EnclU {
    pub fn range(lo: u64, hi: u64) -> EnclU {
        EnclU {
            lo,
            hi,
            exact: true,
        }
    }
    fn constant(self) -> Option<u64> {
        (self.lo == self.hi && self.exact).then_some(self.lo)
    }
    /// `op` on the bounds when it is monotone and stays in 32 bits; else every `u32`.
    fn monotone(self, o: EnclU, op: fn(u64, u64) -> u64) -> EnclU {
        let (lo, hi) = (op(self.lo, o.lo), op(self.hi, o.hi));
        EnclU {
            lo: if hi <= u64::from(u32::MAX) { lo } else { 0 },
            hi: hi.min(u64::from(u32::MAX)),
            // A wrapped result is anywhere in the word, but still the same for the
            // reference and every deviant: integer arithmetic does not deviate.
            exact: self.exact && o.exact,
        }
    }
}

impl Add for EnclU {
    type Output = EnclU;
    fn add(self, o: EnclU) -> EnclU {
        self.monotone(o, |a, b| a + b)
    }
}
impl Sub for EnclU {
    type Output = EnclU;
    fn sub(self, o: EnclU) -> EnclU {
        self.wrapping_sub(o)
    }
}
impl BitAnd for EnclU {
    type Output = EnclU;
    fn bitand(self, o: EnclU) -> EnclU {
        let exact = self.exact && o.exact;
        if let (Some(a), Some(b)) = (self.constant(), o.constant()) {
            return EnclU::range(a & b, a & b);
        }
        // A low mask over a range that does not cross a multiple of its period is
        // monotone; otherwise the result is at most the smaller operand.
        let masked = |x: EnclU, m: u64| {
            ((m + 1).is_power_of_two() && x.lo >> m.count_ones() == x.hi >> m.count_ones())
                .then_some(EnclU {
                    lo: x.lo & m,
                    hi: x.hi & m,
                    exact,
                })
        };
        o.constant()
            .and_then(|m| masked(self, m))
            .or_else(|| self.constant().and_then(|m| masked(o, m)))
            .unwrap_or(EnclU {
                lo: 0,
                hi: self.hi.min(o.hi),
                exact,
            })
    }
}
impl BitOr for EnclU {
    type Output = EnclU;
    fn bitor(self, o: EnclU) -> EnclU {
        let top = (self.hi.max(o.hi) + 1).next_power_of_two() - 1;
        EnclU {
            lo: self.lo.max(o.lo),
            hi: top.min(u64::from(u32::MAX)),
            exact: self.exact && o.exact,
        }
    }
}

impl Uint for EnclU {
    type F = Encl;
    type B = EnclB;
    fn c(v: u32) -> Self {
        EnclU::range(u64::from(v), u64::from(v))
    }
    fn shl(self, n: u32) -> Self {
        let (lo, hi) = (self.lo << n, self.hi << n);
        let fits = hi <= u64::from(u32::MAX);
        EnclU {
            lo: if fits { lo } else { 0 },
            hi: hi.min(u64::from(u32::MAX)),
            exact: self.exact,
        }
    }
    fn shr(self, n: u32) -> Self {
        EnclU {
            lo: self.lo >> n,
            hi: self.hi >> n,
            exact: self.exact,
        }
    }
    /// Exact below `2^24`; a larger value converts with an implementation-defined
    /// rounding direction, so the enclosure is only claimed for the exact range.
    fn to_f(self) -> Encl {
        let r = Encl::range(f32_of(self.lo as f64), f32_of(self.hi as f64), 1.0);
        if self.exact && self.hi < 1 << 24 {
            r
        } else {
            Encl::unknown()
        }
    }
    fn as_float(self) -> Encl {
        let r = Encl::range(
            f64::from(f32::from_bits(self.lo as u32)),
            f64::from(f32::from_bits(self.hi as u32)),
            0.0,
        );
        let positive_normal = self.lo >= 0x0080_0000 && self.hi < 0x7f80_0000;
        match self.constant() {
            Some(_) if positive_normal => Encl {
                grid: ulp(r.lo),
                ..r
            },
            _ if positive_normal && self.exact => Encl {
                grid: ulp(r.lo),
                ..r
            },
            _ => Encl::unknown(),
        }
    }
    fn sel(m: EnclB, t: Self, f: Self) -> Self {
        match (m.agree, m.t, m.f) {
            (true, true, false) => t,
            (true, false, true) => f,
            _ => EnclU {
                lo: t.lo.min(f.lo),
                hi: t.hi.max(f.hi),
                exact: m.agree && t.exact && f.exact || t.constant().is_some() && t == f,
            },
        }
    }
    fn wrapping_add(self, o: Self) -> Self {
        self + o
    }
    fn wrapping_sub(self, o: Self) -> Self {
        if self.lo >= o.hi {
            EnclU {
                lo: self.lo - o.hi,
                hi: self.hi - o.lo,
                exact: self.exact && o.exact,
            }
        } else {
            EnclU {
                lo: 0,
                hi: u64::from(u32::MAX),
                exact: self.exact && o.exact,
            }
        }
    }
    fn wrapping_mul(self, o: Self) -> Self {
        self.monotone(o, |a, b| a * b)
    }
    fn lt(self, o: Self) -> EnclB {
        EnclB {
            t: self.lo < o.hi,
            f: self.hi >= o.lo,
            agree: self.exact && o.exact,
            order: None,
        }
    }
}

impl Float for Encl {
    type U = EnclU;
    type B = EnclB;
    fn c(v: f32) -> Self {
        Encl::range(f64::from(v), f64::from(v), lowest_bit(v))
    }
    fn abs(self) -> Self {
        let all = join(self.v(), self.dev);
        if all.0 >= 0.0 {
            return Encl { fused: 0.0, ..self };
        }
        if all.1 <= 0.0 {
            return Encl {
                fused: 0.0,
                ..-self
            };
        }
        let abs = |x: Iv| {
            if x.0 < 0.0 && x.1 > 0.0 {
                (0.0, widest(x))
            } else {
                (x.0.abs().min(x.1.abs()), widest(x))
            }
        };
        // ||a'| − |a|| ≤ |a' − a|
        let e = if self.undeviated() {
            (0.0, 0.0)
        } else {
            sym(widest(self.e))
        };
        Encl::result(abs(self.v()), abs(self.dev), e, self.grid)
    }
    fn sqrt(self) -> Self {
        if self.lo < 0.0 || self.dev.0 < 0.0 {
            return Encl::unknown();
        }
        let r = rounded((
            self.lo.sqrt().next_down().max(0.0),
            self.hi.sqrt().next_up(),
        ));
        let exact = (
            self.dev.0.sqrt().next_down().max(0.0),
            self.dev.1.sqrt().next_up(),
        );
        let dev = iadd(exact, sym(SQRT_ULP * ulp(widest(exact))));
        // |√a' − √a| = |e| / (√a + √a') ≤ √|e|
        let em = widest(self.e);
        // Rounded down, so the quotient below is not.
        let denom = (self.lo.sqrt().next_down().max(0.0) + self.dev.0.sqrt().next_down().max(0.0))
            .next_down()
            .max(0.0);
        let prop = if denom > 0.0 {
            (em / denom).min(em.sqrt())
        } else {
            em.sqrt()
        };
        let e = iadd(
            sym(prop.next_up()),
            sym((SQRT_ULP + 0.5) * ulp(Encl::mag(r, dev))),
        );
        Encl::result(r, dev, e, ulp(self.grid.sqrt() * 0.5))
    }
    fn floor(self) -> Self {
        self.integral(f64::floor)
    }
    fn round(self) -> Self {
        self.integral(|x| x.round_ties_even())
    }
    fn lt(self, o: Self) -> EnclB {
        EnclB {
            order: Some((self, o)),
            ..self.compare(o, |a, b| (a.1 < b.0, a.0 >= b.1))
        }
    }
    fn le(self, o: Self) -> EnclB {
        EnclB {
            order: Some((self, o)),
            ..self.compare(o, |a, b| (a.1 <= b.0, a.0 > b.1))
        }
    }
    fn gt(self, o: Self) -> EnclB {
        o.lt(self)
    }
    fn ge(self, o: Self) -> EnclB {
        o.le(self)
    }
    fn eq(self, o: Self) -> EnclB {
        self.compare(o, |a, b| {
            (
                a.0 == a.1 && b.0 == b.1 && a.0 == b.0,
                a.1 < b.0 || b.1 < a.0,
            )
        })
    }
    fn sel(m: EnclB, t: Self, f: Self) -> Self {
        let (t, f) = (Encl { fused: 0.0, ..t }, Encl { fused: 0.0, ..f });
        if m.agree && !m.f {
            return t;
        }
        if m.agree && !m.t {
            return f;
        }
        if let Some((a, b)) = m.order {
            let (a, b) = (Encl { fused: 0.0, ..a }, Encl { fused: 0.0, ..b });
            if (t, f) == (a, b) {
                return Encl::extreme(a, b, false);
            }
            if (t, f) == (b, a) {
                return Encl::extreme(a, b, true);
            }
        }
        let grid = t.grid.min(f.grid);
        let refs: Vec<Encl> = [(m.t, t), (m.f, f)]
            .into_iter()
            .filter_map(|(may, x)| may.then_some(x))
            .collect();
        let r = refs
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |h, x| join(h, x.v()));
        let mut dev = refs
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |h, x| join(h, x.dev));
        let mut e = refs
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |h, x| join(h, x.e));
        if !m.agree {
            // The deviant may take the other operand.
            dev = join(t.dev, f.dev);
            for x in &refs {
                let other = if *x == t { f } else { t };
                e = join(e, iadd(other.dev, ineg(x.v())));
            }
        }
        Encl::result(r, dev, e, grid)
    }
    fn to_u(self) -> EnclU {
        let ok = self.lo >= 0.0 && self.hi <= f64::from(u32::MAX);
        EnclU {
            lo: if ok { self.lo as u64 } else { 0 },
            hi: if ok {
                self.hi as u64
            } else {
                u64::from(u32::MAX)
            },
            exact: ok && self.undeviated(),
        }
    }
    /// Monotone in `|x|` and blind to the sign of a zero, so as exact as the value.
    fn magnitude_bits(self) -> EnclU {
        let (lo, hi) = if self.lo >= 0.0 {
            (self.lo, self.hi)
        } else if self.hi <= 0.0 {
            (-self.hi, -self.lo)
        } else {
            (0.0, (-self.lo).max(self.hi))
        };
        if lo.is_nan() || hi.is_nan() || hi == f64::INFINITY && lo == 0.0 {
            return EnclU {
                lo: 0,
                hi: 0x7fff_ffff,
                exact: false,
            };
        }
        let bits = |m: f64| u64::from((m as f32).to_bits());
        EnclU {
            lo: bits(lo),
            hi: bits(hi),
            exact: self.undeviated(),
        }
    }
    fn to_bits(self) -> EnclU {
        // Monotone on positive floats; a zero's bits depend on its sign.
        let ok = self.lo > 0.0;
        EnclU {
            lo: if ok {
                u64::from((self.lo as f32).to_bits())
            } else {
                0
            },
            hi: if ok {
                u64::from((self.hi as f32).to_bits())
            } else {
                u64::from(u32::MAX)
            },
            exact: ok && self.undeviated(),
        }
    }
}
