//! The first seed's baseline, "store X&Y&Z": the three components scaled and biased,
//! `n·0.5 + 0.5`, as unorm8×3 in one word (x in bits 0–7, y 8–15, z 16–23; bits 24–31
//! clear), the layout of an RGB8 texel; decode re-normalizes `enc·2 - 1`. No code
//! decodes to zero: each component `(2c - 255)/255` has an odd numerator.

use crate::codecs::core::codec::Codec;
use crate::codecs::core::info::Domain;
use crate::codecs::toolkit::exact::{canonical_or_z, length2, unorm_sqrt_ratio};
use crate::codecs::core::info::{Info, Sizes, FloatForm, seam};
use crate::codecs::core::codec_family::CodecFamily;
use crate::codecs::core::pipeline::codec_functions;
use crate::codecs::toolkit::quant::{Quant, Quants};
use crate::model::{Float, V3};

pub static FAMILY: CodecFamily<Unorm3> = CodecFamily::new(
    Info {
        name: "unorm3",
        title: "components scaled and biased, n·0.5 + 0.5, as unorm8×3 (an RGB8 texel)",
        sizes: Sizes::Fixed(24),
        domain: Some(Domain::Sphere),
        source: "Pranckevičius, Compact Normal Storage, baseline (store X&Y&Z)",
        edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z",
        decode_note: "decode re-normalizes (v / sqrt(v·v)); every code decodes to a unit vector",
        float_form: FloatForm::Continuous { seam: seam::NONE_PER_COMPONENT },
        options: &[],
    },
    |_| Unorm3,
    codec_functions,
);

/// The baseline codec; it has one size.
#[derive(Clone, Copy, Debug)]
pub struct Unorm3;

impl Codec for Unorm3 {
    type P<F: Float> = V3<F>;
    type C<F: Float> = F::U;
    #[inline]
    fn quants(&self) -> Quants {
        Quants::new(&[Quant::Unorm(8); 3])
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    /// `n·0.5 + 0.5` of the normalized input.
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V3<F> {
        self.target(v) * F::c(0.5) + F::c(0.5)
    }
    /// `p / sqrt(p·p)` of `p = enc·2 - 1`.
    #[inline(always)]
    fn direction<F: Float>(&self, enc: V3<F>) -> V3<F> {
        let p = ((enc - F::c(0.5)) * F::c(2.0)).named("p");
        p / p.length_squared().sqrt()
    }
    /// Each component `w / |w|` of the canonical input decided by [`unorm_sqrt_ratio`].
    const EXACT_ROUNDING: bool = true;
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V3<F> {
        let (w, _) = canonical_or_z(v);
        let s = length2(w);
        let root = s.sqrt();
        w.map(#[inline(always)] |x| unorm_sqrt_ratio(Quant::Unorm(8), x, s, root, 0.5))
    }
}
