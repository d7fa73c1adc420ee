//! The model's own trigonometry. Shader `atan2`, `sin`, `cos` and `acos` differ between
//! drivers, and from Rust by up to thousands of ULP even on lavapipe, so codecs that need
//! angles use these polynomial versions, built only from exact operations: both sides then
//! compute the same bits. Angles are in units of π (half turns), which keeps the range
//! reductions exact. `tests/internals/codecs_trig.rs` measures the error against f64 over the whole range:
//! [`atan2_pi`] within [`ATAN2_PI_MAX_ERROR`], [`sincos_pi`] within [`SINCOS_PI_MAX_ERROR`].

use crate::model::{Float, Lane, V2};
use std::f64::consts::PI;
use std::sync::OnceLock;

/// Largest absolute error of [`atan2_pi`] in half turns, as tested (about 0.05°·10⁻³).
pub const ATAN2_PI_MAX_ERROR: f64 = 2.0e-7;
/// Largest absolute error of each lane of [`sincos_pi`], as tested.
pub const SINCOS_PI_MAX_ERROR: f64 = 2.5e-7;

/// `c[0] + z·(c[1] + z·(...))`, evaluated as written.
#[inline(always)]
fn horner<F: Float>(z: F, coeffs: &[f64]) -> F {
    let mut acc = F::c(*coeffs.last().unwrap() as f32);
    for c in coeffs.iter().rev().skip(1) {
        acc = acc * z + F::c(*c as f32);
    }
    acc
}

/// `n!`, for the series' coefficients.
pub fn factorial(n: i32) -> f64 {
    (1..=n).map(f64::from).product()
}

/// The coefficients of atan(z)/z in z², through z^19: for |z| ≤ tan(π/8) the series'
/// truncation is below 3·10⁻⁹. Shared with [`crate::codecs::toolkit::fixed_trig`]. Each series here is
/// computed once per process: the f32 model evaluates its polynomial for every item, and
/// the powers and factorials would cost more than the polynomial.
pub fn atan_series() -> &'static [f64] {
    static C: OnceLock<Vec<f64>> = OnceLock::new();
    C.get_or_init(|| {
        (0..10)
            .map(|k| if k % 2 == 0 { 1.0 } else { -1.0 } / (2 * k + 1) as f64)
            .collect()
    })
}

/// atan(z) for |z| ≤ tan(π/8), by [`atan_series`].
#[inline(always)]
fn atan_small<F: Float>(z: F) -> F {
    let z2 = (z * z).named("z2");
    z * horner(z2, atan_series())
}

/// atan2(y, x) / π in [-1, 1]. Signed zeros count as positive (`atan2_pi(+0, -0) = 0`,
/// `atan2_pi(-0, -1) = 1`); `atan2_pi(0, 0) = 0`. Tiny operands are scaled up before
/// the division, so no input gives NaN, even on an implementation that flushes denormals
/// (which may then read denormal operands as zeros).
#[inline(always)]
pub fn atan2_pi<F: Float>(y: F, x: F) -> F {
    let ax = x.abs();
    let ay = y.abs();
    let y_major = ay.gt(ax).named("y_major");
    let hi = F::sel(y_major, ay, ax).named("hi");
    let lo = F::sel(y_major, ax, ay);
    let up = crate::codecs::toolkit::exact::denormal_proof_scale(hi).named("up");
    let (hi, lo) = ((hi * up).named("hi"), lo * up);
    let t = (lo / F::sel(hi.gt(F::c(0.0)), hi, F::c(1.0))).named("t");
    // atan(t) = π/4 + atan((t-1)/(t+1)) keeps the series argument below tan(π/8).
    let far = t.gt(F::c((PI / 8.0).tan() as f32)).named("far");
    let z = F::sel(far, (t - F::c(1.0)) / (t + F::c(1.0)), t).named("z");
    let r = atan_small(z).named("r");
    let r = F::sel(far, r + F::c((PI / 4.0) as f32), r).named("r");
    let r = F::sel(y_major, F::c((PI / 2.0) as f32) - r, r).named("r");
    let r = F::sel(x.lt(F::c(0.0)), F::c(PI as f32) - r, r).named("r");
    let r = F::sel(y.lt(F::c(0.0)), -r, r);
    r * F::c((1.0 / PI) as f32)
}

/// (sin(π·t), cos(π·t)) for t in [-1, 1], by range reduction to [0, 1/4] and Taylor
/// polynomials in t (through t^9 for sine, t^10 for cosine).
#[inline(always)]
pub fn sincos_pi<F: Float>(t: F) -> V2<F> {
    let a = t.abs();
    // cos(π(1-a)) = -cos(πa), sin(π(1-a)) = sin(πa)
    let back = a.gt(F::c(0.5)).named("back");
    let b = F::sel(back, F::c(1.0) - a, a).named("b");
    // sin(π(1/2-b)) = cos(πb)
    let swap = b.gt(F::c(0.25)).named("swap");
    let c = F::sel(swap, F::c(0.5) - b, b).named("c");
    let V2 { x: s, y: co } = series_quarter(c);
    let sb = F::sel(swap, co, s);
    let cb = F::sel(swap, s, co);
    let cos = F::sel(back, -cb, cb);
    let sin = F::sel(t.lt(F::c(0.0)), -sb, sb);
    V2::new(sin, cos)
}

/// `(sin(π·c), cos(π·c))` for `|c| ≤ 1/4` by the Taylor polynomials in `c` (through
/// `c^9` for sine, `c^10` for cosine), with no branch.
#[inline(always)]
fn series_quarter<F: Float>(c: F) -> V2<F> {
    let c2 = (c * c).named("c2");
    static SIN: OnceLock<Vec<f64>> = OnceLock::new();
    static COS: OnceLock<Vec<f64>> = OnceLock::new();
    let sin_coeffs = SIN.get_or_init(
        #[inline(always)]
        || {
            (0..5)
                .map(
                    #[inline(always)]
                    |k| (-1f64).powi(k) * PI.powi(2 * k + 1) / factorial(2 * k + 1),
                )
                .collect()
        },
    );
    let cos_coeffs = COS.get_or_init(
        #[inline(always)]
        || {
            (0..6)
                .map(
                    #[inline(always)]
                    |k| (-1f64).powi(k) * PI.powi(2 * k) / factorial(2 * k),
                )
                .collect()
        },
    );
    let s = (c * horner(c2, sin_coeffs)).named("s");
    let co = horner(c2, cos_coeffs).named("co");
    V2::new(s, co)
}

/// `(sin(π·t), cos(π·t))` for `|t| ≤ 1/4` (at most an eighth of a turn), with no range
/// reduction: [`sincos_pi`]'s polynomials on their own. Without a branch there is no
/// point where an argument's rounding can pick another formula, which is what a
/// decoder whose angle may land exactly on `±1/4` needs ([`crate::codecs::azimuthal::concentric`]).
#[inline(always)]
pub fn sincos_quarter_pi<F: Float>(t: F) -> V2<F> {
    series_quarter(t)
}

/// The coefficients of `sin(π·r/2)/r` (`sine`) or `cos(π·r/2)` as series in `q = r²`,
/// through `q^8`: both are even in `r`, so neither needs the root or a quotient. For
/// `q ≤ 2` (a unit square's corners) the truncation is below `3·10⁻¹⁰`. Shared with
/// [`crate::codecs::toolkit::fixed_trig`].
pub fn quarter_turn_series(sine: bool) -> &'static [f64] {
    static SIN: OnceLock<Vec<f64>> = OnceLock::new();
    static COS: OnceLock<Vec<f64>> = OnceLock::new();
    let h = PI / 2.0;
    (if sine { &SIN } else { &COS }).get_or_init(|| {
        (0..9)
            .map(|k| {
                let n = 2 * k + i32::from(sine);
                (-1f64).powi(k) * h.powi(n) / factorial(n)
            })
            .collect()
    })
}

/// `(sin(π·r/2)/r, cos(π·r/2))` of `r = sqrt(q)` for `0 ≤ q ≤ 2`, by
/// [`quarter_turn_series`]: the decode of an azimuthal equidistant disk point `p` is
/// `(p·s, c)` with `q = |p|²`, division-free and exact at the centre.
#[inline(always)]
pub fn sinc_cos_quarter<F: Float>(q: F) -> V2<F> {
    let s = horner(q, quarter_turn_series(true)).named("sinc");
    let c = horner(q, quarter_turn_series(false)).named("cosq");
    V2::new(s, c)
}

/// Doc comments of the helpers defined here.
pub fn helper_doc(name: &str) -> Option<String> {
    match name {
        "atan2_pi" => Some(format!(
            "atan2(y, x) / π in [-1, 1] from exact operations only (|error| ≤ {ATAN2_PI_MAX_ERROR:e}); signed zeros count as positive."
        )),
        "sincos_pi" => Some(format!(
            "(sin(π·t), cos(π·t)) for t in [-1, 1] from exact operations only (|error| ≤ {SINCOS_PI_MAX_ERROR:e})."
        )),
        "sincos_quarter_pi" => Some(format!(
            "(sin(π·t), cos(π·t)) for t in [-1/4, 1/4] from exact operations only, with no branch (|error| ≤ {SINCOS_PI_MAX_ERROR:e})."
        )),
        _ => None,
    }
}
