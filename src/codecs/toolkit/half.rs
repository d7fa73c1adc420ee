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
#[inline(always)]
pub fn half_bits<F: Float>(x: F) -> F::U {
    let u = {
        #[inline(always)]
        |v: u32| F::U::c(v)
    };
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
#[inline(always)]
pub fn half_value<F: Float>(h: F::U) -> F {
    let u = {
        #[inline(always)]
        |v: u32| F::U::c(v)
    };
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
