//! Stereographic projection of the +Z hemisphere (fourth seed, "alternative
//! projections"): `p = (x, y) / (1 + z)` stored as snorm×2 of `B/2` bits each, x in the
//! lowest bits; decode by the inverse, `(2p, 1 - |p|²) / (1 + |p|²)`. The hemisphere
//! maps onto the unit disk, so the square's corners are wasted, but unlike
//! [`crate::codecs::component::xy`] the points stay dense at the horizon. The projection is conformal (a
//! code's cell is locally a scaled square on the sphere), so the precise encoder rarely
//! finds a nearer code than rounding does.

use crate::codecs::core::codec::{Codec, above_horizon};
use crate::codecs::core::info::Domain;
use crate::codecs::toolkit::exact::{canonical_or_z, fixed_length2, fixed_ratio, floor_ratio_code, ratio_code, root};
use crate::codecs::core::info::{Info, Sizes, FloatForm, seam};
use crate::codecs::core::codec_family::CodecFamily;
use crate::codecs::core::texel::{self, TexelCodec, texel_variants};
use crate::codecs::toolkit::fixed_decode::{fixed_length2_2d, BITS, ONE, fixed, fixed_target, nearest_decoded, search_doc};
use crate::codecs::toolkit::quant::{Quant, Quants, signed_code, zero_code};
use crate::codecs::core::spec::SpecError;
use crate::model::{Bool, Float, V2, V3};

pub static FAMILY: CodecFamily<XyStereo> = CodecFamily::new(
    Info {
        name: "xy_stereo",
        title: "stereographic projection of the +Z hemisphere, (x, y)/(1 + z) as snorm×2",
        sizes: Sizes::Total(&[16, 24, 32]),
        domain: Some(Domain::Hemisphere),
        source: "NVIDIA normal-map notes (alternative projections); Snyder and Mitchell 2001",
        edge_policy: "input is normalized onto the +Z hemisphere first (z ← max(z, +0)); zero, NaN, infinite and -Z input encode as +Z",
        decode_note: "every code decodes to a unit vector (up to rounding); codes outside the unit disk decode below the horizon",
        float_form: FloatForm::Continuous { seam: seam::NONE_IN_HEMISPHERE },
        options: &[texel::OPTION],
    },
    |bits| XyStereo { bits },
    texel::functions,
)
.with_validate(texel::validate)
.with_variants(texel_variants!("xy_stereo"))
.with_helper_doc(|name| (name == "encode_codes").then(|| search_doc(BITS)));

#[derive(Clone, Copy, Debug)]
pub struct XyStereo {
    pub bits: u32,
}

/// The input projected onto the hemisphere in canonical form, its length `l` and
/// `a = l + z` (a sum of non-negatives, at least `l`), and whether it has a direction
/// there (-Z projects to zero).
struct Upper<F: Float> {
    h: V3<F>,
    l: F,
    a: F,
    ok: F::B,
}

impl<F: Float> Upper<F> {
    #[inline(always)]
    fn of(v: V3<F>) -> Self {
        let (w, ok) = canonical_or_z(v);
        let (h, up) = canonical_or_z(above_horizon(w));
        let l = root(fixed_length2(h));
        Upper {
            h,
            l,
            a: (l + h.z).named("a"),
            ok: ok.and(up),
        }
    }
}

impl XyStereo {
    /// The codec with the given total bit budget; an invalid size is an error listing
    /// the allowed ones.
    pub fn new(bits: u32) -> Result<XyStereo, SpecError> {
        FAMILY.codec(bits)
    }

    fn field(&self) -> Quant {
        Quant::Snorm(self.bits / 2)
    }

    /// The decode of codes `c` of the field `q` in units of `2^-BITS`: `p = s/M` of
    /// their signed values ([`signed_code`]) one rounded product floored, `q = |p|²` from
    /// squares rounded to a unit (an exact sum), then `2p / (1 + q)` and
    /// `(1 - q) / (1 + q)` by [`fixed_ratio`].
    #[inline(always)]
    fn fixed_direction<F: Float>(q: Quant, c: V2<F>) -> V3<F> {
        let one = F::c(ONE as f32);
        let k = ONE / f64::from(q.max_code());
        let p = c.map(#[inline(always)] |x| fixed(signed_code(q, x), k)).named("p");
        let q = fixed_length2_2d(p);
        let d = one + q;
        V3::from_xy(
            p.map(#[inline(always)] |x| fixed_ratio(x + x, d, BITS)),
            fixed_ratio(one - q, d, BITS),
        )
    }
}

impl Codec for XyStereo {
    type P<F: Float> = V2<F>;
    type C<F: Float> = F::U;
    #[inline]
    fn quants(&self) -> Quants {
        Quants::new(&[self.field(); 2])
    }
    fn domain(&self) -> Domain {
        Domain::Hemisphere
    }
    /// `w.xy / (l + w.z)` of the canonical input projected onto the hemisphere.
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V2<F> {
        let u = Upper::of(v);
        u.h.xy() / u.a
    }
    /// `(2p, 1 - |p|²) / (1 + |p|²)`: both numerators are computed, so each component
    /// divides exactly once.
    #[inline(always)]
    fn direction<F: Float>(&self, p: V2<F>) -> V3<F> {
        let q = p.length_squared().named("q");
        let d = (q + F::c(1.0)).named("d");
        V3::from_xy((p + p) / d, (F::c(1.0) - q) / d)
    }
    /// The codes of `w.x / a` and `w.y / a` ([`ratio_code`]); input without a
    /// direction on the hemisphere encodes as +Z.
    const EXACT_ROUNDING: bool = true;
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V2<F> {
        self.round_in(self.field(), v)
    }
    /// The nearest of the four codes around the exact parameters (floors decided by
    /// [`floor_ratio_code`]) by the squared distance of their fixed-point decodes to the input
    /// projected onto the hemisphere; input without a direction there encodes as +Z.
    const EXACT_SEARCH: bool = true;
    #[inline(always)]
    fn precise_codes<F: Float>(&self, v: V3<F>) -> V2<F> {
        self.precise_in(self.field(), v)
    }
}

impl TexelCodec for XyStereo {
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
        let u = Upper::of(v);
        let c = u.h.xy().map(#[inline(always)] |x| ratio_code(q, x, u.a));
        V2::sel_all(u.ok, c, V2::splat(F::c(zero_code(q))))
    }
    #[inline(always)]
    fn precise_in<F: Float>(&self, q: Quant, v: V3<F>) -> V2<F> {
        let u = Upper::of(v);
        let base = u.h.xy().map(#[inline(always)] |x| floor_ratio_code(q, x, u.a)).named("base");
        let target = fixed_target(u.h, u.l, BITS);
        let best = nearest_decoded([q; 2], base, target, #[inline(always)] |c| Self::fixed_direction(q, c));
        V2::sel_all(u.ok, best, V2::splat(F::c(zero_code(q))))
    }
}
