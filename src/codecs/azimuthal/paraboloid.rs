//! The inverted paraboloid (second seed, "Improved Normal-map Distributions"): a
//! hemisphere normal is stored as the point `p` (snorm×2 of `B/2` bits each, x in the
//! lowest bits) where its ray meets `z = 1 - (x² + y²)`; the decoder is the seed's,
//! `normalize(p, 1 - saturate(p·p))`, with no square root of its own. Near the horizon
//! the texels cover far less solid angle than [`crate::codecs::component::xy`]'s.
//!
//! The encoder solves the seed's quadratic `a·t² + z·t - 1 = 0` (`a = x² + y²`), whose
//! positive root is `t = 2 / (z + sqrt(z² + 4a))`; for any length of the input,
//! `p = (x, y)·t = (x, y) / (z/2 + sqrt(x² + y² + (z/2)²))` — the stereographic point
//! ([`crate::codecs::azimuthal::xy_stereo`]) of `(x, y, z/2)`, a quotient the codes are decided from exactly.

use crate::codecs::core::codec::{Codec, above_horizon};
use crate::codecs::core::info::Domain;
use crate::codecs::toolkit::exact::{
    canonical_or_z, fixed_length2, fixed_ratio, fixed_root, floor_ratio_code, ratio_code, root,
    root_of,
};
use crate::codecs::core::info::{Info, Sizes, FloatForm, seam};
use crate::codecs::core::codec_family::CodecFamily;
use crate::codecs::core::texel::{self, TexelCodec, texel_variants};
use crate::codecs::toolkit::fixed_decode::{
    BITS, ONE, fixed, fixed_length2_2d, fixed_square, fixed_target, nearest_decoded, search_doc,
};
use crate::codecs::toolkit::quant::{Quant, Quants, signed_code, zero_code};
use crate::codecs::core::spec::SpecError;
use crate::model::{Bool, Float, V2, V3};

pub static FAMILY: CodecFamily<Paraboloid> = CodecFamily::new(
    Info {
        name: "paraboloid",
        title: "inverted paraboloid z = 1 - (x² + y²) of the +Z hemisphere, snorm×2",
        sizes: Sizes::Total(&[16, 24, 32]),
        domain: Some(Domain::Hemisphere),
        source: "Improved Normal-map Distributions (Insomniac, after Mike Day), the inverted paraboloid",
        edge_policy: "input is projected onto the +Z hemisphere first (z ← max(z, +0)); zero, NaN, infinite and -Z input encode as +Z",
        decode_note: "every code decodes to a unit vector (up to rounding); codes outside the unit disk decode on the horizon",
        float_form: FloatForm::Continuous { seam: seam::NONE_IN_HEMISPHERE },
        options: &[texel::OPTION],
    },
    |bits| Paraboloid { bits },
    texel::functions,
)
.with_validate(texel::validate)
.with_variants(texel_variants!("paraboloid"))
.with_helper_doc(|name| (name == "encode_codes").then(|| search_doc(BITS)));

#[derive(Clone, Copy, Debug)]
pub struct Paraboloid {
    pub bits: u32,
}

/// The input projected onto the hemisphere in canonical form `h`, the denominator
/// `a = z/2 + |(x, y, z/2)|` of its paraboloid point (a sum of non-negatives, at least
/// `|x|` and `|y|`), and whether it has a direction there (-Z projects to zero).
struct Upper<F: Float> {
    h: V3<F>,
    a: F,
    ok: F::B,
}

impl<F: Float> Upper<F> {
    #[inline(always)]
    fn of(v: V3<F>) -> Self {
        let (w, ok) = canonical_or_z(v);
        let (h, up) = canonical_or_z(above_horizon(w));
        // Halving is exact (a canonical component is 0 or at least 2^-39); the largest
        // component stays at least 1, so the root's argument is at least 1.
        let halved = V3::from_xy(h.xy(), h.z * F::c(0.5)).named("halved");
        let l = root_of(fixed_length2(halved));
        Upper {
            h,
            a: (l + halved.z).named("a"),
            ok: ok.and(up),
        }
    }
}

impl Paraboloid {
    /// The codec with the given total bit budget; an invalid size is an error listing
    /// the allowed ones.
    pub fn new(bits: u32) -> Result<Paraboloid, SpecError> {
        FAMILY.codec(bits)
    }

    fn field(&self) -> Quant {
        Quant::Snorm(self.bits / 2)
    }

    /// The decode of codes `c` of the field `q` in units of `2^-BITS`: `p = s/M` of their
    /// signed values ([`signed_code`]) one rounded product floored, `q = |p|²` and `z = 1 - min(q, 1)` exact integers, the length
    /// `L = sqrt(q + z²)` from [`fixed_root`] (of `L²·2^19`, doubled: within two units)
    /// and no shorter than any component, then each component divided by it with
    /// [`fixed_ratio`].
    #[inline(always)]
    fn fixed_direction<F: Float>(q: Quant, c: V2<F>) -> V3<F> {
        let one = F::c(ONE as f32);
        let k = ONE / f64::from(q.max_code());
        let p = c.map(#[inline(always)] |x| fixed(signed_code(q, x), k)).named("p");
        let q = fixed_length2_2d(p);
        let z = (one - q.at_most(one)).named("z");
        // Below 2^22 (q ≤ 2, and z = 0 there), so the root's argument is below 2^41.
        let l2 = (q + fixed_square(z)).named("l2");
        let l = fixed_root(l2 * F::c((ONE * 0.25) as f32)) * F::c(2.0);
        let a = p.abs();
        let l = l.at_least(a.x).at_least(a.y).at_least(z).named("l");
        V3::from_xy(p.map(#[inline(always)] |x| fixed_ratio(x, l, BITS)), fixed_ratio(z, l, BITS))
    }
}

impl Codec for Paraboloid {
    type P<F: Float> = V2<F>;
    type C<F: Float> = F::U;
    #[inline]
    fn quants(&self) -> Quants {
        Quants::new(&[self.field(); 2])
    }
    fn domain(&self) -> Domain {
        Domain::Hemisphere
    }
    /// `h.xy / a` of the canonical input projected onto the hemisphere (see [`Upper`]):
    /// the seed's `(x, y)·t`.
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V2<F> {
        let u = Upper::of(v);
        u.h.xy() / u.a
    }
    /// The seed's `normalize(p, 1 - saturate(p·p))`: inside the disk the point on the
    /// paraboloid, outside it a direction on the horizon.
    #[inline(always)]
    fn direction<F: Float>(&self, p: V2<F>) -> V3<F> {
        let q = p.length_squared().named("q");
        let n = V3::from_xy(p, F::c(1.0) - q.at_most(F::c(1.0))).named("n");
        n / n.length_squared().sqrt()
    }
    /// The codes of `h.x / a` and `h.y / a` ([`ratio_code`]); input without a
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

impl TexelCodec for Paraboloid {
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
        let target = fixed_target(u.h, root(fixed_length2(u.h)), BITS);
        let best = nearest_decoded([q; 2], base, target, #[inline(always)] |c| Self::fixed_direction(q, c));
        V2::sel_all(u.ok, best, V2::splat(F::c(zero_code(q))))
    }
}
