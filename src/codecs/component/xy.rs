//! X and Y stored, Z reconstructed (first seed method 1, survey XYOnly, fourth seed):
//! `z = sqrt(1 - saturate(x² + y²))`, +Z hemisphere, snorm×2.

use crate::codecs::core::codec::{Codec, above_horizon};
use crate::codecs::core::info::Domain;
use crate::codecs::toolkit::exact::{
    canonical, canonical_or_z, fixed_root, float_of, floor_ratio_code, fixed_length2, length2,
    root, sqrt_ratio_code,
};
use crate::codecs::toolkit::fixed_decode::{BITS, ONE, fixed, fixed_target, nearest_decoded, search_doc};
use crate::codecs::toolkit::quant::{Quant, Quants, signed_code, zero_code};
use crate::model::{Bool, Float, Uint, V2, V3};
use crate::codecs::core::info::{Info, Sizes, FloatForm, seam};
use crate::codecs::core::codec_family::CodecFamily;
use crate::codecs::core::ieee;
use crate::codecs::core::texel::{self, TexelCodec, texel_variants};
use crate::codecs::core::spec::SpecError;

pub static FAMILY: CodecFamily<Xy> = CodecFamily::new(
    Info {
        name: "xy",
        title: "x and y stored, z reconstructed, snorm×2",
        sizes: Sizes::Total(&[16, 24, 32]),
        domain: Some(Domain::Hemisphere),
        source: "Pranckevičius method 1; Cigolle et al. XYOnly; NVIDIA normal-map notes",
        edge_policy: "input is normalized onto the +Z hemisphere first (z ← max(z, +0)); zero, NaN and infinite input encode as +Z",
        decode_note: "z = sqrt(1 - saturate(x²+y²)); codes outside the unit disk decode to (x, y, 0), longer than 1",
        float_form: FloatForm::Continuous { seam: seam::NONE_IN_HEMISPHERE },
        options: &[texel::OPTION, ieee::OPTION],
    },
    |bits| Xy { bits },
    |spec, c| ieee::functions(spec, c, texel::functions),
)
.with_validate(|spec| {
    texel::validate(spec)?;
    ieee::validate(spec, texel::layout(spec).is_some())
})
.with_variants(texel_variants!("xy", "xy16:guarantee=ieee"))
.with_helper_doc(|name| (name == "encode_codes").then(|| search_doc(BITS)));

impl Xy {
    /// The codec with the given total bit budget; an invalid size is an error listing
    /// the allowed ones.
    pub fn new(bits: u32) -> Result<Xy, SpecError> {
        FAMILY.codec(bits)
    }
}

#[derive(Clone, Copy, Debug)]
pub struct Xy {
    pub bits: u32,
}

impl Codec for Xy {
    type P<F: Float> = V2<F>;
    type C<F: Float> = F::U;
    #[inline]
    fn quants(&self) -> Quants {
        Quants::new(&[Quant::Snorm(self.bits / 2); 2])
    }
    fn domain(&self) -> Domain {
        Domain::Hemisphere
    }
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V2<F> {
        self.target(v).xy()
    }
    /// The input projected onto the hemisphere (`z ← max(z, 0)`, a NaN kept) and
    /// normalized, in plain arithmetic (the lean tier): input whose squared length is not
    /// a positive finite `f32`, an infinite `z` and `-Z` give `(0, 0)`, +Z's code.
    #[inline(always)]
    fn ieee_params<F: Float>(&self, v: V3<F>) -> V2<F> {
        let h = V3::new(v.x, v.y, F::sel(v.z.lt(F::c(0.0)), F::c(0.0), v.z));
        let len2 = h.length_squared().named("len2");
        let finite_z = v.z.ge(F::c(-f32::MAX));
        let ok = len2.gt(F::c(0.0)).and(len2.le(F::c(f32::MAX))).and(finite_z);
        let p = (h.xy() / len2.sqrt()).named("p");
        V2::sel_all(ok, p, V2::splat(F::c(0.0)))
    }
    /// Codes outside the unit disk decode to `(x, y, 0)`, which is longer than 1.
    #[inline(always)]
    fn direction<F: Float>(&self, p: V2<F>) -> V3<F> {
        let d = p.length_squared();
        let d = F::sel(d.lt(F::c(1.0)), d, F::c(1.0)).named("d");
        V3::from_xy(p, (F::c(1.0) - d).sqrt())
    }
    /// `x / |w|` and `y / |w|` of the canonical input projected onto the hemisphere
    /// (`z ← max(z, 0)`), decided portably ([`crate::codecs::toolkit::exact`]); `-Z` projects to
    /// zero and encodes as +Z, like invalid input.
    const EXACT_ROUNDING: bool = true;
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V2<F> {
        self.round_in(self.quants()[0], v)
    }
    /// The nearest of the four codes around the exact parameters (floors decided by
    /// [`floor_ratio_code`]) by the squared distance of their fixed-point decodes
    /// ([`crate::codecs::toolkit::fixed_decode`]) to the input projected onto the hemisphere
    /// (`z ← max(z, 0)`, then brought back to canonical form); `-Z` projects to zero
    /// and encodes as +Z, like invalid input.
    const EXACT_SEARCH: bool = true;
    #[inline(always)]
    fn precise_codes<F: Float>(&self, v: V3<F>) -> V2<F> {
        self.precise_in(self.quants()[0], v)
    }
}

impl TexelCodec for Xy {
    #[inline(always)]
    fn params2<F: Float>(&self, v: V3<F>) -> V2<F> {
        self.params(v)
    }
    #[inline(always)]
    fn direction2<F: Float>(&self, p: V2<F>) -> V3<F> {
        self.direction(p)
    }
    #[inline(always)]
    fn round_in<F: Float>(&self, q: Quant, v: V3<F>) -> V2<F> {
        let (w, ok) = canonical(v);
        let s = length2(above_horizon(w));
        let c = w.xy().map(#[inline(always)] |x| sqrt_ratio_code(q, x, s));
        V2::sel_all(ok.and(s.gt(F::c(0.0))), c, V2::splat(F::c(zero_code(q))))
    }
    #[inline(always)]
    fn precise_in<F: Float>(&self, q: Quant, v: V3<F>) -> V2<F> {
        let (w, ok) = canonical_or_z(v);
        let (h, up) = canonical_or_z(above_horizon(w));
        let l = root(fixed_length2(h));
        let base = h.xy().map(#[inline(always)] |x| floor_ratio_code(q, x, l)).named("base");
        let best = nearest_decoded([q; 2], base, fixed_target(h, l, BITS), #[inline(always)] |c| Self::fixed_direction(q, c));
        V2::sel_all(ok.and(up), best, V2::splat(F::c(zero_code(q))))
    }
}

impl Xy {
    /// The decode of codes of the field `q` in fixed point
    /// ([`crate::codecs::toolkit::fixed_decode`]): of their signed values `s` ([`signed_code`]),
    /// `(s, sqrt(M² - |s|²)) / M` (z = 0 outside the disk), from exact integers and one
    /// [`fixed_root`] of one product.
    #[inline(always)]
    fn fixed_direction<F: Float>(q: Quant, c: V2<F>) -> V3<F> {
        let m = q.max_code();
        let c = c.map(#[inline(always)] |x| signed_code(q, x));
        let k = ONE / f64::from(m);
        let a = c.map(#[inline(always)] |x| x.abs().to_u());
        let sq = a.x.wrapping_mul(a.x) + a.y.wrapping_mul(a.y);
        let m2 = F::U::c((m as u32) * (m as u32));
        let inside = sq.lt(m2);
        let r = float_of::<F>(F::U::sel(inside, m2.wrapping_sub(sq), F::U::c(0))).named("r");
        let z = fixed_root(r * F::c((k * k) as f32));
        V3::from_xy(c.map(#[inline(always)] |x| fixed(x, k)), z)
    }
}
