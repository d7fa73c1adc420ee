//! IEEE binary16 ("half") fields without pack builtins: GLSL's `packHalf2x16` leaves
//! the rounding to the implementation, WGSL's `pack2x16float` is only specified for
//! values it can represent, and HLSL's `f32tof16` rounds as the hardware does. These
//! are written in integer operations on the bits (plus one exact float product), so every
//! implementation computes the same bits.

use crate::model::{Float, Uint};

/// `2^24`: f16 subnormals are multiples of `2^-24`.
const SUBNORMAL_SCALE: f32 = (1u32 << 24) as f32;
/// The bits of `2^-14`, the smallest normal f16, as an f32.
const HALF_MIN_NORMAL: u32 = 0x3880_0000;
/// The bits of 65520, halfway between the largest finite f16 (65504) and 65536: from
/// here on round-to-nearest-even gives infinity.
const HALF_OVERFLOW: u32 = 0x477f_f000;
/// Rebiasing an exponent from f32 (127) to f16 (15), in f32 bit positions.
const REBIAS: u32 = (127 - 15) << 23;
const F32_INF: u32 = 0x7f80_0000;
/// The f16 exponent field all ones: infinities and NaNs.
const HALF_INF: u32 = 0x7c00;
/// The quiet NaN every f32 NaN becomes (sign kept, payload dropped).
const HALF_NAN: u32 = 0x7e00;

/// The f16 bits of any f32, rounded to nearest, ties to even, as IEEE 754 converts:
/// values from 65520 up become infinity, values at most `2^-25` become zero (`2^-25`
/// itself is a tie, which goes to the even zero), f16 subnormals are exact multiples of
/// `2^-24`, the sign is kept (also of zeros, infinities and NaNs), and every NaN becomes
/// the quiet NaN `0x7e00` with its sign. f32 denormals become signed zeros, decided on
/// the bits, so flushing them changes nothing.
pub fn half_bits<F: Float>(x: F) -> F::U {
    let u = |v: u32| F::U::c(v);
    let b = x.to_bits();
    let sign = b.shr(16) & u(0x8000);
    let a = b & u(0x7fff_ffff);
    // Normal halves: rebias, then add just under half a unit of the 13 dropped bits plus
    // the kept lowest bit (ties to even); a carry rounds into the exponent.
    let lowest = a.shr(13) & u(1);
    let normal = a
        .wrapping_sub(u(REBIAS))
        .wrapping_add(u(0x0fff))
        .wrapping_add(lowest)
        .shr(13);
    // Subnormal halves: |x|·2^24 (exact), rounded half to even. Larger magnitudes are
    // replaced by 0 first so that no NaN or infinity reaches the conversion to integer.
    let small = a.lt(u(HALF_MIN_NORMAL));
    let t = F::U::sel(small, a, u(0)).as_float();
    let subnormal = (t * F::c(SUBNORMAL_SCALE)).round().to_u();
    let special = F::U::sel(u(F32_INF).lt(a), u(HALF_NAN), u(HALF_INF));
    let finite = F::U::sel(a.lt(u(HALF_OVERFLOW)), normal, special);
    F::U::sel(small, subnormal, finite) | sign
}

/// The f32 of f16 bits (the low 16 bits of `h`; the rest must be zero): exact for every
/// pattern, infinities and NaNs (payload kept) included.
pub fn half_value<F: Float>(h: F::U) -> F {
    let u = |v: u32| F::U::c(v);
    let sign = (h & u(0x8000)).shl(16);
    let m = h & u(0x7fff);
    let wide = m.shl(13);
    let normal = wide.wrapping_add(u(REBIAS));
    let special = wide | u(F32_INF);
    // Subnormals: the 10-bit mantissa times 2^-24, an exact product whose result is a
    // normal f32; 0 gives +0.
    let subnormal = (m.to_f() * F::c(1.0 / SUBNORMAL_SCALE)).to_bits();
    let finite = F::U::sel(m.lt(u(0x0400)), subnormal, normal);
    let mag = F::U::sel(m.lt(u(HALF_INF)), finite, special);
    (mag | sign).as_float()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every f16 value, from the definition: `(-1)^s · 2^(e-15) · (1 + m/1024)`, or
    /// `m · 2^-24` for `e = 0`.
    fn value_of(h: u16) -> f64 {
        let s = if h & 0x8000 != 0 { -1.0 } else { 1.0 };
        let e = i32::from((h >> 10) & 31);
        let m = f64::from(h & 1023);
        match e {
            0 => s * m * 2f64.powi(-24),
            31 if m == 0.0 => s * f64::INFINITY,
            31 => f64::NAN,
            _ => s * (1.0 + m / 1024.0) * 2f64.powi(e - 15),
        }
    }

    #[test]
    fn every_half_converts_exactly() {
        for h in 0..=u16::MAX {
            let got = half_value::<f32>(u32::from(h));
            let want = value_of(h);
            if want.is_nan() {
                assert!(got.is_nan(), "{h:#06x}: {got}");
                assert_eq!(got.to_bits() >> 31, u32::from(h >> 15), "{h:#06x}: sign");
                assert_eq!(got.to_bits() & 0x007f_ffff, u32::from(h & 1023) << 13);
            } else {
                assert_eq!(f64::from(got), want, "{h:#06x}");
                assert_eq!(got.is_sign_negative(), h & 0x8000 != 0, "{h:#06x}: sign");
            }
        }
    }

    /// The nearest f16 by search over the sorted finite values, ties to the even
    /// pattern, overflow from 65520 (IEEE 754 §4.3.1, §7.4).
    fn nearest(x: f32) -> u32 {
        let v = f64::from(x);
        if v.is_nan() {
            return if x.is_sign_negative() { 0xfe00 } else { 0x7e00 };
        }
        let sign = if x.is_sign_negative() { 0x8000 } else { 0 };
        let a = v.abs();
        if a >= 65520.0 {
            return sign | 0x7c00;
        }
        let mut best = 0u16;
        for h in 0..0x7c00u16 {
            let (d, db) = ((value_of(h) - a).abs(), (value_of(best) - a).abs());
            if d < db || (d == db && h & 1 == 0) {
                best = h;
            }
        }
        sign | u32::from(best)
    }

    #[test]
    fn floats_round_to_the_nearest_half_ties_to_even() {
        let mut xs: Vec<f32> = vec![
            0.0,
            -0.0,
            1e-45,
            -1e-45,
            f32::MIN_POSITIVE,
            2f32.powi(-25),
            2f32.powi(-25) * 1.000_001,
            2f32.powi(-24) * 1.5,
            2f32.powi(-24) * 2.5,
            65504.0,
            65519.99,
            65520.0,
            -65520.0,
            f32::MAX,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            -f32::NAN,
            1.0,
            1.0 + 2f32.powi(-11),
            1.0 + 3.0 * 2f32.powi(-11),
            0.1,
            -0.7,
        ];
        // Every midpoint between neighbouring finite halves, and a float either side.
        for h in (0..0x7bffu32).step_by(61) {
            let mid = ((value_of(h as u16) + value_of(h as u16 + 1)) / 2.0) as f32;
            xs.extend([
                mid,
                f32::from_bits(mid.to_bits() - 1),
                f32::from_bits(mid.to_bits() + 1),
            ]);
        }
        for x in xs {
            assert_eq!(half_bits(x), nearest(x), "{x:e} ({:#010x})", x.to_bits());
        }
    }
}
