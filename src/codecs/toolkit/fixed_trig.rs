//! Trigonometry in fixed point, for codes that must not depend on an implementation's
//! division or on contraction ([`crate::codecs::toolkit::trig`]'s float polynomials have both).
//!
//! Values are integers held in floats, in units of `2^-23` (angles in half turns, as in
//! [`crate::codecs::toolkit::trig`]). A product is `mul`: one rounded product, an exact scaling and a
//! floor, so it is a function of its operands alone and nothing can be fused into it; the
//! sums that follow add integers below `2^24`, which are exact. Quotients come from
//! [`fixed_ratio`]. Each step loses at most one unit, so the results are within a few
//! units (`2^-21`) of the exact functions, as close as the float versions.

use crate::codecs::toolkit::exact::fixed_ratio;
use crate::codecs::toolkit::quant::Quant;
use crate::codecs::toolkit::trig::{atan_series, factorial, quarter_turn_series};
use crate::model::{Float, Lane, V2};
use std::f64::consts::PI;
use std::sync::OnceLock;

/// The unit of [`atan2_pi`] is `2^-BITS` half turns: 1 is the largest value it holds.
pub const BITS: u32 = 23;
/// `2^BITS`, for constants.
pub const ONE: f64 = (1u32 << BITS) as f64;
/// The unit of [`sincos_pi`]'s argument and results: `2^-24`, the finest that holds 1.
pub const FINE: f64 = (1u32 << 24) as f64;

/// `x` in units of `1/one`, rounded: a literal.
#[inline(always)]
fn units<F: Float>(x: f64, one: f64) -> F {
    F::c((x * one).round() as f32)
}

/// `a·b` of two values in units of `1/one`, rounded to a unit.
#[inline(always)]
pub(crate) fn mul<F: Float>(a: F, b: F, one: f64) -> F {
    (a * b * F::c((1.0 / one) as f32)).round()
}

/// `c[0] + z·(c[1] + z·(...))` in units of `1/one`.
#[inline(always)]
fn poly<F: Float>(z: F, coeffs: &[f64], one: f64) -> F {
    let mut acc = units::<F>(*coeffs.last().unwrap(), one);
    for &c in coeffs.iter().rev().skip(1) {
        acc = mul(acc, z, one) + units(c, one);
    }
    acc
}

/// atan2(y, x) / π in units of half turns, in `[-2^23, 2^23]`, for `y` and `x` normal or
/// `+0` (never `-0`: [`crate::codecs::toolkit::exact::canonical`] values). `atan2(0, 0) = 0`.
#[inline(always)]
pub fn atan2_pi<F: Float>(y: F, x: F) -> F {
    let one = F::c(ONE as f32);
    let (ax, ay) = (x.abs(), y.abs());
    let y_major = ay.gt(ax).named("y_major");
    let hi = F::sel(y_major, ay, ax).named("hi");
    let lo = F::sel(y_major, ax, ay).named("lo");
    let t = fixed_ratio(lo, F::sel(hi.gt(F::c(0.0)), hi, F::c(1.0)), BITS).named("t");
    // atan(t) = π/4 + atan((t-1)/(t+1)) keeps the series argument below tan(π/8).
    let far = t.gt(units((PI / 8.0).tan(), ONE)).named("far");
    let z = F::sel(far, fixed_ratio(t - one, t + one, BITS), t).named("z");
    let z2 = mul(z, z, ONE).named("z2");
    let r = mul(z, poly(z2, atan_series(), ONE), ONE).named("r");
    // Radians to half turns, then the octant's offsets (exact integers).
    let h = (r * F::c((1.0 / PI) as f32)).round().named("h");
    let h = F::sel(far, h + units(0.25, ONE), h).named("h");
    let h = F::sel(y_major, units::<F>(0.5, ONE) - h, h).named("h");
    let h = F::sel(x.lt(F::c(0.0)), one - h, h).named("h");
    F::sel(y.lt(F::c(0.0)), -h, h).named("angle")
}

/// (sin(π·t), cos(π·t)) for `t` in units of `2^-24` half turns, `|t| ≤ 2^24`, in units
/// of `2^-24`.
#[inline(always)]
pub fn sincos_pi<F: Float>(t: F) -> V2<F> {
    let a = t.abs();
    let back = a.gt(units(0.5, FINE)).named("back");
    let b = F::sel(back, F::c(FINE as f32) - a, a).named("b");
    let swap = b.gt(units(0.25, FINE)).named("swap");
    let c = F::sel(swap, units::<F>(0.5, FINE) - b, b);
    // In radians, at most π/4.
    let u = (c * F::c(PI as f32)).round().named("u");
    let u2 = mul(u, u, FINE).named("u2");
    static SIN: OnceLock<Vec<f64>> = OnceLock::new();
    static COS: OnceLock<Vec<f64>> = OnceLock::new();
    let sin_coeffs = SIN.get_or_init(
        #[inline(always)]
        || {
            (0..6)
                .map(
                    #[inline(always)]
                    |k| (-1f64).powi(k) / factorial(2 * k + 1),
                )
                .collect()
        },
    );
    let cos_coeffs = COS.get_or_init(
        #[inline(always)]
        || {
            (0..7)
                .map(
                    #[inline(always)]
                    |k| (-1f64).powi(k) / factorial(2 * k),
                )
                .collect()
        },
    );
    let s = mul(u, poly(u2, sin_coeffs, FINE), FINE).named("s");
    let co = poly(u2, cos_coeffs, FINE).named("co");
    let sb = F::sel(swap, co, s);
    let cb = F::sel(swap, s, co);
    let cos = F::sel(back, -cb, cb);
    let sin = F::sel(t.lt(F::c(0.0)), -sb, sb);
    V2::new(sin, cos)
}

/// The unorm code (fields `q`) of an angle `a` in units of `2^-23` half turns,
/// `|a| ≤ 2^23`, with `[-1, 1]` half turns mapped onto the codes: `(a + 2^23)·M/2^24`,
/// an exact integer times one literal, rounded once, then rounded to a code (ties to
/// even) where `offset` is `½` or floored where it is `1`. No sum follows the product,
/// so nothing can be fused into it: a function of `a` alone.
#[inline(always)]
pub fn angle_code<F: Float>(q: Quant, a: F, offset: f32) -> F {
    angle_level(q.max_code(), a, offset)
}

/// [`angle_code`] onto the levels `0..=m` of any count (`m < 2^24`), not only a field's
/// `2^b - 1`: a cube face's side in a combined index.
#[inline(always)]
pub fn angle_level<F: Float>(m: f32, a: F, offset: f32) -> F {
    let scaled = (a + F::c(ONE as f32)) * F::c((f64::from(m) / (2.0 * ONE)) as f32);
    let c = if offset < 1.0 {
        scaled.round()
    } else {
        scaled.floor()
    };
    c.clamped(F::c(0.0), F::c(m))
}

/// `(sin(π·r/2)/r, cos(π·r/2))` of `r = sqrt(q)` for `0 ≤ q ≤ 2`, with `q` and the
/// results in units of `1/one` (`one` at most `2^21`): [`crate::codecs::toolkit::trig::quarter_turn_series`]
/// by Horner's rule in `q/2`, every product rounded to a unit. In `q/2 ≤ 1` (the
/// coefficients times `2^k`) a unit lost in one step is never amplified by the next, and
/// every partial sum stays below `cosh(π/√2) < 5`, so below `2^24` units.
#[inline(always)]
pub fn sinc_cos_quarter<F: Float>(q: F, one: f64) -> V2<F> {
    static SIN: OnceLock<Vec<f64>> = OnceLock::new();
    static COS: OnceLock<Vec<f64>> = OnceLock::new();
    let series = {
        #[inline(always)]
        |sine: bool| {
            let c = (if sine { &SIN } else { &COS }).get_or_init(
                #[inline(always)]
                || {
                    quarter_turn_series(sine)
                        .iter()
                        .enumerate()
                        .map(
                            #[inline(always)]
                            |(k, c)| c * 2f64.powi(k as i32),
                        )
                        .collect()
                },
            );
            let mut acc = units::<F>(*c.last().unwrap(), one);
            for &c in c.iter().rev().skip(1) {
                acc = mul(acc, q, 2.0 * one) + units(c, one);
            }
            acc
        }
    };
    V2::new(series(true).named("sinc"), series(false).named("cosq"))
}
