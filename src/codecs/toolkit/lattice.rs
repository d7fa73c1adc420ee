//! Portable precise search: the candidate nearest the input is chosen by integer
//! arithmetic on exact lattice directions, never by decoded floats.
//!
//! A precise encoder picks, among the codes around the exact parameters, the one whose
//! direction is nearest the input. Measured on decoded floats (divisions and square
//! roots), that choice flips on any implementation whose division or root differs by an
//! ULP; measured with float sums, it flips where a driver regroups or fuses the sums
//! (Mesa's NIR factors `a·b + a·c` on paths without `NoContraction`). Here every
//! candidate is an integer lattice direction `d` (its decode before normalization), the
//! input is fixed point `A` (exactly `floor(|w|·2^22)` of the canonical input), and the
//! closeness `sin²(A, d) = |A×d|² / (|A|²·|d|²)` is computed in wrapping 32-bit
//! integers: exact, so no optimiser can change it. Only the last step, comparing
//! `e₁·n₂ < e₂·n₁` (`e = |A×d|²·2^-29` and `n = |d|²`, both integers below 2^24), uses two
//! correctly rounded float products, as the fast encoders' comparisons do.
//!
//! Magnitudes: a candidate is within one code of the exact parameters in each
//! coordinate, so `d = P + δ` with `P ∥ A`, and `|A×d| = |A×δ| < √3·2^24·|δ|`: with
//! `|δ| < √6` for octahedral codes and `√8` for hemi-octahedral ones (whose lattice is
//! rotated and twice as fine), `|A×d| < 2^26.3`. The components of `A×d` (each a
//! difference of two products that may wrap) are therefore exact as two's complement,
//! and `e < 2^23.6` converts to f32 exactly.
//!
//! Each codec maps its codes to lattice directions in the first octant (the input's
//! magnitudes) and applies the input's signs afterwards, so every integer is
//! non-negative. [`Closeness::of_small`] measures signed candidates that are not lattice
//! directions (a lookup table's texels) against a coarser signed fixed point.

use crate::codecs::toolkit::exact::sum_of_squares;
use crate::model::{Bool, Float, Uint, V2, V3};

/// `2^22`: canonical magnitudes are below 4, so their fixed point is below `2^24`.
const FIXED: f32 = (1u32 << 22) as f32;
/// `|A×d|²` is kept as `|A×d|² >> 29`, below `2^24` for every candidate.
const CROSS_SHIFT: u32 = 29;

/// The canonical magnitudes in fixed point, `floor(|w|·2^22)`: a power-of-two scaling,
/// the floor of a normal float and the conversion of an integral value, each exact.
#[inline(always)]
pub fn fixed<F: Float>(a: V3<F>) -> V3<F::U> {
    a.map(
        #[inline(always)]
        |x| (x * F::c(FIXED)).floor().to_u(),
    )
    .named("afix")
}

/// The magnitude of a two's complement word.
#[inline(always)]
pub fn magnitude<U: Uint>(x: U) -> U {
    U::sel(x.lt(U::c(1 << 31)), x, U::c(0).wrapping_sub(x))
}

/// About `x² >> 29` for `x < 2^27`, from 16-bit halves (`x = h·2^16 + l`, so
/// `x² = h²·2^32 + 2hl·2^16 + l²`): the first two partial products, each shifted on its
/// own; `l² >> 29` (below 8) is left out. At most 9 below the exact quotient, against
/// `e` of about 2^15 to 2^18 where two candidates nearly tie. Deterministic.
#[inline(always)]
pub fn square_shifted<U: Uint>(x: U) -> U {
    let h = x.shr(16);
    let l = x & U::c(0xffff);
    h.wrapping_mul(h).shl(32 - CROSS_SHIFT) + h.wrapping_mul(l).shr(CROSS_SHIFT - 17)
}

/// How close a lattice direction is to the fixed-point input: `sin²` of their angle is
/// proportional to `e / n`.
#[derive(Clone, Copy)]
pub struct Closeness<F> {
    /// `|A×d|² >> 29`, an exact integer below 2^24 ([`Closeness::of`]), or `|a×d|²`
    /// rounded once ([`Closeness::of_small`]), as f32.
    e: F,
    /// `|d|² >> shift`, below 2^24, as f32.
    n: F,
}

impl<F: Float> Closeness<F> {
    /// `d` (non-negative integers with `|d| ≤ m`) measured against `a`, the
    /// [`fixed`] input.
    #[inline(always)]
    pub fn of(a: V3<F::U>, d: V3<F::U>, m: f32) -> Closeness<F> {
        let x = cross(a, d).map(
            #[inline(always)]
            |c| square_shifted(magnitude(c)),
        );
        let e = (x.x + x.y + x.z).to_f().named("e");
        let n2 = d.x.wrapping_mul(d.x) + d.y.wrapping_mul(d.y) + d.z.wrapping_mul(d.z);
        let shift = norm_shift(m);
        let n = if shift == 0 { n2 } else { n2.shr(shift) };
        Closeness {
            e,
            n: n.to_f().named("n"),
        }
    }

    /// `d` measured against `a`, both signed (two's complement words) and small:
    /// Euclidean `|a|·|d| < 2^24` and `|d| < 2^12`. Then `|a×d| < 2^24`, so every
    /// component of `a×d` is exact and below 2^24 and their squares sum below 2^48: `e` is
    /// `|a×d|²` summed exactly in integers and rounded once ([`sum_of_squares`]), `n` the
    /// exact `|d|²`. For candidates that are not lattice directions (a table's texels) at
    /// a coarser fixed point than [`fixed`]'s.
    #[inline(always)]
    pub fn of_small(a: V3<F::U>, d: V3<F::U>) -> Closeness<F> {
        let x = cross(a, d).map(magnitude);
        let n2 = d.x.wrapping_mul(d.x) + d.y.wrapping_mul(d.y) + d.z.wrapping_mul(d.z);
        Closeness {
            e: sum_of_squares::<F, 3>([x.x, x.y, x.z]).named("e"),
            n: n2.to_f().named("n"),
        }
    }
}

/// `a×d` in wrapping 32-bit arithmetic: exact as two's complement while each component's
/// magnitude is below 2^31.
#[inline(always)]
fn cross<U: Uint>(a: V3<U>, d: V3<U>) -> V3<U> {
    V3::new(
        a.y.wrapping_mul(d.z).wrapping_sub(a.z.wrapping_mul(d.y)),
        a.z.wrapping_mul(d.x).wrapping_sub(a.x.wrapping_mul(d.z)),
        a.x.wrapping_mul(d.y).wrapping_sub(a.y.wrapping_mul(d.x)),
    )
    .named("axd")
}

/// A deterministic measure of how near a candidate is, for [`nearest`].
pub trait Measure<F: Float>: Copy {
    /// Whether `self` is strictly nearer than `other`.
    fn closer(self, other: Self) -> F::B;
    fn sel(m: F::B, a: Self, b: Self) -> Self;
}

impl<F: Float> Measure<F> for Closeness<F> {
    /// `e/n` compared by cross multiplication, two correctly rounded products feeding a
    /// comparison.
    #[inline(always)]
    fn closer(self, other: Closeness<F>) -> F::B {
        (self.e * other.n).lt(other.e * self.n)
    }

    #[inline(always)]
    fn sel(m: F::B, a: Self, b: Self) -> Self {
        Closeness {
            e: F::sel(m, a.e, b.e).named("best_e"),
            n: F::sel(m, a.n, b.n).named("best_n"),
        }
    }
}

/// The nearest of four candidate codes: `(s0, t0)` and the codes one step up in either
/// or both parameters, the first on ties. `candidate` maps a pair of codes to the codes
/// it stands for (a codec may reflect them), whether those are valid (the first always
/// is) and how near they are (a [`Closeness`] or another [`Measure`]).
#[inline(always)]
pub fn nearest<F: Float, M: Measure<F>>(
    s0: F,
    t0: F,
    candidate: impl Fn(F, F) -> (V2<F>, F::B, M),
) -> V2<F> {
    let (mut best, _, mut best_c) = candidate(s0, t0);
    // The steps up are shared by the candidates that take them.
    let (s1, t1) = (
        (s0 + F::c(1.0)).named("s_up"),
        (t0 + F::c(1.0)).named("t_up"),
    );
    for (up_s, up_t) in [(true, false), (false, true), (true, true)] {
        let s = if up_s { s1 } else { s0 };
        let t = if up_t { t1 } else { t0 };
        let (codes, valid, c) = candidate(s, t);
        let better = valid.and(c.closer(best_c));
        best = V2::sel_all(better, codes, best).named("best");
        best_c = M::sel(better, c, best_c);
    }
    best
}

/// The doc comment of a lattice search's `encode_codes` helper; `signs` says how the
/// input's signs are applied.
pub fn search_doc(signs: &str) -> String {
    format!(
        "Precise search, decided in integer arithmetic: among the four codes around the exact parameters, the one whose lattice direction (its decode before normalization) is nearest the input in angle, measured against the input's fixed-point magnitudes (the first on ties); then {signs}."
    )
}

/// The right shift that brings `|d|² ≤ m²` below `2^24`.
pub fn norm_shift(m: f32) -> u32 {
    let bits = 64 - ((m as u64) * (m as u64)).leading_zeros();
    bits.saturating_sub(24)
}
