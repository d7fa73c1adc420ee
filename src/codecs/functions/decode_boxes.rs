//! Enclosures of what a decoder's inputs can be over a box of codes, for the proven
//! decoder bounds (`crate::measure::decode_bound`): the values a texture fetch returns for a range
//! of codes, and the codes of a float field in order.

use crate::codecs::toolkit::quant::Quant;
use crate::model::enclosure::{Encl, EnclU};

/// The values a texture fetch returns for the codes `c0..=c1` (`c/M` correctly rounded,
/// snorm at least -1; for a float field, its finite values in order, see
/// [`float_code_range`]): monotone in `c`, so the bounds are the ends'. Every nonzero
/// one is at least `1/M`, so all are multiples of the f32 spacing at `1/M` (of `2^-24`,
/// the least f16, for halves; of `2^-149`, the least denormal, for f32 fields).
pub(crate) fn fetched_range(q: Quant, (c0, c1): (i64, i64)) -> Encl {
    let (at, grid): (fn(Quant, i64) -> f32, f64) = match q {
        Quant::Half | Quant::Single => (float_of_ordinal, float_grid(q)),
        _ => (
            |q, c| crate::codecs::functions::inputs::fetched(q, c as f32),
            crate::model::enclosure::ulp(f64::from(1.0 / q.max_code())),
        ),
    };
    Encl::range(f64::from(at(q, c0)), f64::from(at(q, c1)), grid)
}

/// The spacing every value of a float field is a multiple of: the least f16 (`2^-24`),
/// or for an f32 field the least denormal (`2^-149`).
fn float_grid(q: Quant) -> f64 {
    match q {
        Quant::Half => 1.0 / f64::from(1u32 << 24),
        _ => f64::from(f32::from_bits(1)),
    }
}

/// The codes in the raw fields `lo..=hi`: [`Quant::from_field`] evaluated over the range.
/// A float field's conversion ([`crate::codecs::toolkit::half::half_value`], or the f32 bits
/// themselves) is integer operations and at most one exact product with a normal result,
/// so no deviation class can move it; its bit manipulation has no useful interval form,
/// so its enclosure is taken directly as the exact values of the range: monotone within a
/// sign, finite or not. Infinities and NaNs stand as infinities, which every decoder only
/// compares (`|x| ≤ MAX` is false for both) before replacing them.
pub(crate) fn field_codes(q: Quant, (lo, hi): (i64, i64)) -> Encl {
    if !q.is_float() {
        return q.from_field(EnclU::range(lo as u64, hi as u64));
    }
    let (lo, hi) = (lo as u32, hi as u32);
    let b = q.bits();
    let magnitude = q.mask() >> 1;
    let inf = match q {
        Quant::Half => 0x7c00,
        _ => 0x7f80_0000,
    };
    let negative = lo >> (b - 1) == 1;
    let special = |h: u32| h & magnitude >= inf;
    if lo >> (b - 1) != hi >> (b - 1) || special(lo) != special(hi) {
        return Encl::unknown();
    }
    if special(lo) {
        let inf = if negative {
            f64::NEG_INFINITY
        } else {
            f64::INFINITY
        };
        return Encl::range(inf, inf, 0.0);
    }
    let (a, c) = (
        f64::from(q.from_field::<f32>(lo)),
        f64::from(q.from_field::<f32>(hi)),
    );
    Encl::range(a.min(c), a.max(c), float_grid(q))
}

/// The codes a float-form decoder is proven over, as ordered integers: `min..=max` of
/// the integer codes, or for a float field its finite values numbered in order of value
/// (`k ≥ 0` the `k`-th non-negative one, `-k` its negative): `-0x7bff..=0x7bff` for halves
/// (`k` is the half's bits); for f32, zero and the normal values (`k` is the bits less the
/// `2^23 - 1` denormal patterns). f32 denormals are left out because the f32 decoder reads
/// them as `+0` before any arithmetic (an implementation may flush them); numbered in,
/// they would make the all-zero stand-in a cube of `2^24` values a side whose surface no
/// refinement of boxes resolves.
pub fn float_code_range(q: Quant) -> (i64, i64) {
    match q {
        Quant::Half => (-0x7bff, 0x7bff),
        Quant::Single => (-SINGLE_ORDINALS, SINGLE_ORDINALS),
        _ => (q.min_code() as i64, q.max_code() as i64),
    }
}

/// The largest f32 ordinal of [`float_code_range`]: `f32::MAX`'s bits less the denormals.
const SINGLE_ORDINALS: i64 = 0x7f7f_ffff - DENORMALS;
const DENORMALS: i64 = 0x7f_ffff;

/// The finite value of a float field numbered `k` by [`float_code_range`].
fn float_of_ordinal(q: Quant, k: i64) -> f32 {
    let n = k.unsigned_abs();
    let v = match q {
        Quant::Half => crate::codecs::toolkit::half::half_value::<f32>(n as u32),
        _ if n == 0 => 0.0,
        _ => f32::from_bits((n + DENORMALS as u64) as u32),
    };
    if k < 0 { -v } else { v }
}
