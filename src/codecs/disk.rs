//! What the hemisphere-to-disk codecs (`stereo`, `eqarea`; survey §2) share: the layout
//! of a hemisphere bit beside two unorm parameters, and the folded canonical input.
//!
//! Layout: a total of `B` bits is one hemisphere bit and two parameters of `⌈(B-1)/2⌉`
//! and `⌊(B-1)/2⌋` bits (16 = 1 + 8 + 7), x in the lowest bits, then y, then the
//! hemisphere bit (1 for `z < 0`) at bit `B - 1`. Parameters are the disk point `p`
//! stored as unorm `p·0.5 + 0.5`. This is the split that reproduces the survey's Table 1
//! rows (1 + 7 + 7, a wasted bit, makes every mean about 30 % worse; snorm parameters are
//! within 1 % of unorm ones, unorm matches best at 16 bits).

use super::exact::{canonical_or_z, fixed_length2, one_if, root};
use super::fixed_decode::{BITS, fixed_square_point, fixed_target, nearest_decoded};
use super::quant::{Quant, Quants};
use crate::model::{Float, V2, V3};

/// The two parameters' fields of a `bits`-bit code.
pub fn disk_fields(bits: u32) -> [Quant; 2] {
    let rest = bits - 1;
    [Quant::Unorm(rest.div_ceil(2)), Quant::Unorm(rest / 2)]
}

/// The parameters' fields and the hemisphere bit.
pub fn disk_quants(bits: u32) -> Quants {
    let [qx, qy] = disk_fields(bits);
    Quants::new(&[qx, qy, Quant::Unorm(1)])
}

/// The input folded onto the +Z hemisphere, as the portable encoders see it.
#[derive(Clone, Copy)]
pub struct Folded<F: Float> {
    /// The canonical input ([`canonical_or_z`]: invalid input is canonical +Z).
    pub w: V3<F>,
    /// Its length ([`root`]).
    pub l: F,
    /// `l + |w.z|`: `l·(1 + |z|)` of the unit direction, a sum of positives, never 0.
    pub a: F,
    /// The hemisphere bit: 1 where the canonical `z < 0` (a `-0` is already `+0` there,
    /// so the equator is on the +Z side).
    pub h: F,
}

impl<F: Float> Folded<F> {
    pub fn of(v: V3<F>) -> Self {
        let (w, _) = canonical_or_z(v);
        let l = root(fixed_length2(w));
        Folded {
            w,
            l,
            a: l + w.z.abs(),
            h: one_if(w.z.lt(F::c(0.0))),
        }
    }
}

/// `z` on the hemisphere the bit `h` (0 or 1) names.
pub fn unfold<F: Float>(z: F, h: F) -> F {
    F::sel(h.gt(F::c(0.5)), -z, z)
}

/// The disk point of codes `c` in units of `2^-21` ([`super::fixed_decode`]), for the
/// precise searches, and `q = |p|²`: [`fixed_square_point`] of the parameters' fields.
pub fn fixed_disk_point<F: Float>(bits: u32, c: V2<F>) -> (V2<F>, F) {
    fixed_square_point(disk_fields(bits), c)
}

/// A disk codec's precise codes: of the four codes around `base` (the floors), in the
/// input's hemisphere, the one whose fixed-point decode (`decode(codes, h)`) is nearest
/// the input's by exact squared distance ([`nearest_decoded`]), with the hemisphere bit.
pub fn nearest_disk_codes<F: Float>(
    bits: u32,
    f: &Folded<F>,
    base: V2<F>,
    decode: impl Fn(V2<F>, F) -> V3<F>,
) -> V3<F> {
    let target = fixed_target(f.w, f.l, BITS);
    let best = nearest_decoded(disk_fields(bits), base, target, |c| decode(c, f.h));
    V3::from_xy(best, f.h)
}
