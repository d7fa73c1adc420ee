//! Portable quantization: codes decided only by operations that every implementation
//! rounding `+ - *` to nearest and keeping the order of operations computes identically.
//!
//! A GPU may return a quotient or a square root a few ULP away from the correctly rounded
//! one, contract `a*b + c` into one rounding, flush denormals and lose the sign of a zero
//! (`crate::model::deviant` lists what each API allows). A code computed as
//! `round(x / d * M)` therefore changes wherever `x / d * M` lies within a few ULP of a
//! half-integer. The functions here still *estimate* the code that way, then correct the
//! estimate by ±1 with comparisons between single products, `|n|·M` against
//! `(c ± ½)·d`: a product is correctly rounded everywhere, and a product that feeds a
//! comparison (not an addition) cannot be contracted. Whatever the estimate was, the
//! corrected code is the one integer `c` with `(c - ½)·d ≤ |n|·M < (c + ½)·d` (each side
//! rounded once), a function of the input alone.
//!
//! Every value these comparisons see must be normal, so the input is first brought to a
//! canonical form by [`canonical`]: scaled by a power of two (exact), with denormal and
//! negligible components set to zero, which makes flushing and sign-of-zero loss
//! irrelevant.
//!
//! What this cannot absorb: sums and products rounded in another direction (D3D11 lets
//! hardware truncate, Vulkan's default rounding mode may be toward zero, WGSL names none)
//! or regrouped (WGSL and SPIR-V without `NoContraction` may reassociate). Both move the
//! correctly rounded values the comparisons rely on; only exact (integer) arithmetic would
//! survive them.

use super::quant::Quant;
use crate::model::{Bool, Float, Uint, V3};

/// The smallest normal f32, `2^-126`.
const MIN_NORMAL: f32 = f32::MIN_POSITIVE;
/// After [`canonical`] scaling, components below this are set to zero. The largest
/// component is at least 2, so a zeroed component is below `2^-40` of it: far below the
/// resolution of any code (a direction moves by less than `2^-40` rad), while every
/// product of what remains, down to the low half of a split square, stays normal.
const NEGLIGIBLE: f32 = 1.0 / (1u64 << 39) as f32;
/// The exponent field of an f32.
const EXPONENT: u32 = 0x7f80_0000;

/// The input in canonical form, and whether it has a direction.
///
/// Denormal components become `+0` (an implementation may flush them, so none may
/// matter); the vector is scaled by the power of two `2^(128 - E)`, `E` the biased
/// exponent of its largest component, which puts that component in `[2, 4)` exactly;
/// components then below `2^-39` become `+0`. The result has no denormal, and no
/// component whose sign could be lost. `ok` is false for zero, NaN, infinite and
/// all-denormal input: the scale is then infinite or zero and the scaled sum of magnitudes
/// NaN or outside `[2, 12)`.
pub fn canonical<F: Float>(v: V3<F>) -> (V3<F>, F::B) {
    // `x < least` is false for NaN, so NaN survives to spoil the sum below.
    let keep = |x: F, least: f32| F::sel(x.abs().lt(F::c(least)), F::c(0.0), x);
    let v = v.map(|x| keep(x, MIN_NORMAL)).named("normal");
    let a = v.abs();
    let m = a.x.at_least(a.y).at_least(a.z).named("largest");
    let scale = (F::U::c(EXPONENT) - (m.to_bits() & F::U::c(EXPONENT)))
        .as_float()
        .named("scale");
    let w = (v * scale).named("scaled");
    let b = w.abs();
    let sum = (b.x + b.y + b.z).named("sum");
    let ok = sum.ge(F::c(2.0)).and(sum.lt(F::c(16.0)));
    (w.map(|x| keep(x, NEGLIGIBLE)).named("w"), ok)
}

/// `x·x` as the sum of three products that are exact in f32, so that no contraction of
/// the additions that follow can change them: `x = h + l` with `h` the top 12 significant
/// bits (a mask of the bits, no arithmetic) and `l = x - h` (exact) the other 12.
/// Returns `(h·h, 2h·l, l·l)`. `x` is a canonical component: zero or above `2^-39`,
/// so every product is zero or normal.
fn split_square<F: Float>(x: F) -> [F; 3] {
    let h = (x.to_bits() & F::U::c(0xffff_f000)).as_float();
    let l = x - h;
    [h * h, (h + h) * l, l * l]
}

/// `w·w` of a canonical vector, computed from exact products only (so contraction cannot
/// change it) in a fixed order: large terms first, then the cross terms, then the small
/// ones. Deterministic, within a few ULP of the exact square length.
pub fn length2<F: Float>(w: V3<F>) -> F {
    let [x, y, z] = [w.x, w.y, w.z].map(split_square);
    let big = x[0] + y[0] + z[0];
    let cross = x[1] + y[1] + z[1];
    let small = x[2] + y[2] + z[2];
    (big + cross + small).named("len2")
}

/// The snorm code of `n / d` (`d > 0`, `|n| ≤ d`, both normal or `n` zero, both computed
/// with correctly rounded additions only): the integer `c ≤ M` with
/// `(c - ½)·d ≤ |n|·M < (c + ½)·d`, with the sign of `n` (`-0` counts as positive). Ties
/// (`|n|·M` equal to a product) round away from zero.
pub fn snorm_ratio<F: Float>(q: Quant, n: F, d: F) -> F {
    let a = n.abs();
    let m = F::c(q.max_code());
    let estimate = (a / d * m).round();
    let big = a * m;
    let up = big.ge((estimate + F::c(0.5)) * d);
    let down = big.lt((estimate - F::c(0.5)) * d);
    signed(n, corrected(q, estimate, up, down))
}

/// The snorm code of `n / sqrt(s)` (`s > 0`, `n² ≤ s` up to rounding, both exact or
/// correctly rounded functions of the input, `s` from [`length2`]): the integer `c ≤ M`
/// with `(c - ½)²·s ≤ (|n|·M)² < (c + ½)²·s` (each product rounded once), with the sign
/// of `n`.
pub fn snorm_sqrt_ratio<F: Float>(q: Quant, n: F, s: F) -> F {
    let a = n.abs();
    let m = F::c(q.max_code());
    let estimate = (a / s.sqrt() * m).round();
    let big = a * m;
    let big2 = big * big;
    let hi = estimate + F::c(0.5);
    let lo = estimate - F::c(0.5);
    let up = big2.ge(hi * hi * s);
    // At code 0 the lower boundary is 0 itself (`lo² > 0` would wrongly step down).
    let down = estimate.gt(F::c(0.0)).and(big2.lt(lo * lo * s));
    signed(n, corrected(q, estimate, up, down))
}

/// `floor(n / d · M)` for `|n| ≤ d` (`d > 0`, as for [`snorm_ratio`]): the integer `c`
/// in `[-M, M]` with `c·d ≤ n·M < (c + 1)·d` (each side rounded once), where a precise
/// search starts.
pub fn floor_ratio<F: Float>(q: Quant, n: F, d: F) -> F {
    let m = F::c(q.max_code());
    let estimate = (n / d * m).floor();
    let big = n * m;
    let up = big.ge((estimate + F::c(1.0)) * d);
    let down = big.lt(estimate * d);
    stepped(estimate, up, down).clamped(F::c(q.min_code()), m)
}

/// The estimate stepped by one where a comparison says so, within `[0, M]`.
fn corrected<F: Float>(q: Quant, estimate: F, up: F::B, down: F::B) -> F {
    stepped(estimate, up, down).clamped(F::c(0.0), F::c(q.max_code()))
}

/// The estimate stepped by one where a comparison says so.
fn stepped<F: Float>(estimate: F, up: F::B, down: F::B) -> F {
    estimate + F::sel(up, F::c(1.0), F::sel(down, F::c(-1.0), F::c(0.0)))
}

/// `c` with the sign of `n`; a zero `n` gives `c` (which is then 0).
fn signed<F: Float>(n: F, c: F) -> F {
    F::sel(n.lt(F::c(0.0)), -c, c)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn canonical_scales_by_a_power_of_two_into_two_to_four() {
        for (v, s) in [
            ([1.0f32, 0.5, -0.25], 2.0f32),
            ([3.0, 0.0, 0.0], 1.0),
            ([0.0, -1e30, 5e29], 2f32.powi(-98)),
            ([2e-38, 0.0, 0.0], 2f32.powi(127)),
        ] {
            let (w, ok) = canonical(V3::new(v[0], v[1], v[2]));
            assert!(ok, "{v:?}");
            for (wi, vi) in w.to_array().iter().zip(v) {
                assert_eq!(wi.to_bits(), (vi * s).to_bits(), "{v:?}");
            }
        }
    }

    #[test]
    fn canonical_rejects_zero_nan_infinite_and_all_denormal_input() {
        for v in [
            [0.0f32, -0.0, 0.0],
            [f32::NAN, 1.0, 0.0],
            [1.0, 0.0, f32::NAN],
            [f32::INFINITY, 0.0, 0.0],
            [1e-40, -1e-42, 0.0],
        ] {
            let (_, ok) = canonical(V3::new(v[0], v[1], v[2]));
            assert!(!ok, "{v:?}");
        }
    }

    #[test]
    fn canonical_zeroes_denormal_and_negligible_components() {
        let (w, ok) = canonical(V3::new(1.0f32, -1e-40, -1e-13));
        assert!(ok);
        assert_eq!([w.x, w.y, w.z].map(f32::to_bits), [2f32.to_bits(), 0, 0]);
    }

    #[test]
    fn length2_is_the_square_length_to_a_few_ulp() {
        let w = V3::new(2.703_125f32, -0.577_215_7, 1.398_437_5);
        let exact: f64 = w.to_array().iter().map(|&x| f64::from(x).powi(2)).sum();
        let got = f64::from(length2(w));
        assert!((got - exact).abs() <= 2.0 * f64::from(f32::EPSILON) * exact);
    }

    #[test]
    fn snorm_ratio_rounds_to_the_nearest_code_and_keeps_the_sign() {
        let q = Quant::Snorm(8);
        // 127 · 1/3 = 42.33 → 42; 127 · 0.5 = 63.5 → 64 (ties away from zero).
        assert_eq!(snorm_ratio(q, 1.0f32, 3.0), 42.0);
        assert_eq!(snorm_ratio(q, -1.0f32, 2.0), -64.0);
        assert_eq!(snorm_ratio(q, 1.0f32, 2.0), 64.0);
        assert_eq!(snorm_ratio(q, 2.0f32, 2.0), 127.0);
        assert_eq!(snorm_ratio(q, -0.0f32, 2.0), 0.0);
    }

    #[test]
    fn snorm_sqrt_ratio_rounds_to_the_nearest_code() {
        let q = Quant::Snorm(8);
        // 127 · 3/5 = 76.2; 127 · 1/sqrt(2) = 89.80; 127 · 4/5 = 101.6.
        assert_eq!(snorm_sqrt_ratio(q, 3.0f32, 25.0), 76.0);
        assert_eq!(snorm_sqrt_ratio(q, -1.0f32, 2.0), -90.0);
        assert_eq!(snorm_sqrt_ratio(q, 4.0f32, 25.0), 102.0);
        assert_eq!(snorm_sqrt_ratio(q, 0.0f32, 25.0), 0.0);
        assert_eq!(snorm_sqrt_ratio(q, 5.0f32, 25.0), 127.0);
    }
}
