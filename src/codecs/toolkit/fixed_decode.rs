//! Portable precise search for codecs whose decode divides or takes a root (`xy`,
//! `lambert`, `stereo_scaled`): the candidates are decoded in fixed point by a
//! deterministic form of the codec's own decode, the target likewise, and the nearest is
//! chosen by the exact squared distance between those integers.
//!
//! A precise search that compares decoded floats flips wherever two candidates nearly
//! tie and an implementation's division or square root lands an ULP away (or a driver
//! fuses the distance's sums). Here every quotient is decided like a code
//! ([`fixed_ratio`]), every root by comparing squares ([`crate::codecs::toolkit::exact::fixed_root`]),
//! every product feeds only a floor, a comparison or another product, and sums of
//! squares are taken in
//! integers ([`sum_of_squares`]) and rounded once: each component is an integer in
//! `[-2^21, 2^21]` (units of `2^-21`) that no allowed deviation changes, within about
//! one unit of the exact decode, so near-ties are resolved to about `2^-21` of a unit
//! vector, like a float decode's own error.

use crate::codecs::toolkit::exact::{fixed_ratio, sum_of_squares};
use crate::codecs::toolkit::lattice::{Measure, nearest};
use crate::codecs::toolkit::quant::Quant;
use crate::model::{Bool, Float, Uint, V2, V3};

/// The squared distance between two fixed-point directions, rounded once.
#[derive(Clone, Copy)]
pub struct Distance<F>(pub F);

impl<F: Float> Measure<F> for Distance<F> {
    #[inline(always)]
    fn closer(self, other: Self) -> F::B {
        self.0.lt(other.0)
    }
    #[inline(always)]
    fn sel(m: F::B, a: Self, b: Self) -> Self {
        Distance(F::sel(m, a.0, b.0).named("best_d"))
    }
}

/// The unit vector `w / l` (`l` its length from [`crate::codecs::toolkit::exact::root`]) in units of
/// `2^-bits`.
#[inline(always)]
pub fn fixed_target<F: Float>(w: V3<F>, l: F, bits: u32) -> V3<F> {
    w.map(
        #[inline(always)]
        |x| fixed_ratio(x, l, bits),
    )
    .named("aim")
}

impl<F> Distance<F> {
    /// The squared distance itself.
    #[inline(always)]
    pub fn squared(self) -> F {
        self.0
    }
}

/// `|d - u|²` of two fixed-point directions: integers whose differences are exact and
/// below `2^24` and whose squared distance is below `2^48` (always, in units of `2^-21`;
/// for a candidate next to the target, in units of `2^-23`).
#[inline(always)]
pub fn distance<F: Float>(d: V3<F>, u: V3<F>) -> Distance<F> {
    let e = (d - u)
        .named("offset")
        .map(
            #[inline(always)]
            |x| x.abs().to_u(),
        )
        .named("offset_u");
    Distance(sum_of_squares::<F, 3>([e.x, e.y, e.z]).named("dist"))
}

/// The nearest of the four codes `base`, `base + (1, 0)`, `(0, 1)` and `(1, 1)` (codes
/// past the largest of their field `q` are skipped), by the squared distance of their
/// fixed-point decodes (`decode`) to the fixed-point `target`; the first on ties.
#[inline(always)]
pub fn nearest_decoded<F: Float>(
    q: [Quant; 2],
    base: V2<F>,
    target: V3<F>,
    decode: impl Fn(V2<F>) -> V3<F>,
) -> V2<F> {
    let (hx, hy) = (F::c(q[0].max_code()), F::c(q[1].max_code()));
    nearest(
        base.x,
        base.y,
        #[inline(always)]
        |s, t| {
            let codes = V2::new(s.at_most(hx), t.at_most(hy)).named("cand");
            let valid = s.le(hx).and(t.le(hy));
            (codes, valid, distance(decode(codes), target))
        },
    )
}

/// `(tx² >> 2) + (ty² >> 2)` of odd integers `|t| < 2^16` (unorm codes `c` as
/// `t = 2c - M`), exact: `tx² + ty²` is this times 4, plus 2, and would not fit 32 bits.
#[inline(always)]
pub fn odd_square_quarter<F: Float>(t: V2<F>) -> F::U {
    let a = t.map(
        #[inline(always)]
        |x| x.abs().to_u(),
    );
    a.x.wrapping_mul(a.x).shr(2) + a.y.wrapping_mul(a.y).shr(2)
}

/// The point `p = (2c - M)/M` of unorm codes `c` (fields `q`) in the square `[-1, 1]²`,
/// in units of `2^-BITS`, each coordinate one rounded product floored, and `q = |p|²`
/// from squares each rounded to a unit, their sum exact (below `2^23`).
#[inline(always)]
pub fn fixed_square_point<F: Float>(q: [Quant; 2], c: V2<F>) -> (V2<F>, F) {
    let p = {
        #[inline(always)]
        |q: Quant, c: F| {
            let m = f64::from(q.max_code());
            fixed(c * F::c(2.0) - F::c(m as f32), ONE / m)
        }
    };
    let p = V2::new(p(q[0], c.x), p(q[1], c.y)).named("p");
    (p, fixed_length2_2d(p))
}

/// `x·y` of fixed-point values in units of `2^-BITS`, rounded to a unit: one rounded
/// product scaled by a power of two (exact), so no contraction can reach it.
#[inline(always)]
pub fn fixed_mul<F: Float>(x: F, y: F) -> F {
    (x * y * F::c((1.0 / ONE) as f32)).round()
}

/// `x²` of a fixed-point value ([`fixed_mul`]), an integer below `2^23` for `|x| ≤ √2`.
#[inline(always)]
pub fn fixed_square<F: Float>(x: F) -> F {
    fixed_mul(x, x)
}

/// `|p|²` of a fixed-point point from [`fixed_square`]s: integers, so their sum is exact.
#[inline(always)]
pub fn fixed_length2_2d<F: Float>(p: V2<F>) -> F {
    (fixed_square(p.x) + fixed_square(p.y)).named("q")
}

/// `floor(x · k)`: a fixed-point component from one product.
#[inline(always)]
pub fn fixed<F: Float>(x: F, k: f64) -> F {
    (x * F::c(k as f32)).floor()
}

/// The doc comment of the `encode_codes` helper of a search decided here, in units of
/// `2^-bits`.
pub fn search_doc(bits: u32) -> String {
    format!(
        "Precise search, decided in fixed point: among the four codes around the exact parameters, the one whose decode (computed in units of 2^-{bits} with every quotient, root and polynomial decided by comparisons or rounded to a unit) is nearest the input's by exact squared distance, the first on ties."
    )
}

/// The fixed-point unit of the decodes here is `2^-BITS`: a component in `[-1, 1]` is an
/// integer of at most `2^21`, whose estimate from a division is within one unit.
pub const BITS: u32 = 21;
/// `2^BITS`, for constants.
pub const ONE: f64 = (1u32 << BITS) as f64;
