//! The azimuth and z stored (first seed method 3, "Spherical Coordinates"):
//! `enc = ((atan2(y, x)/π, z) + 1)·0.5` as unorm×2 of `B/2` bits each, azimuth in the
//! lowest bits. Decode: `φ = enc.x·2 - 1` half turns, `z = enc.y·2 - 1`,
//! `(cos φ, sin φ)·sqrt(1 - z²)`. The trigonometry is the model's own ([`crate::codecs::toolkit::trig`]),
//! never a builtin.

use crate::model::num::helper;
use crate::codecs::core::codec::Codec;
use crate::codecs::core::info::Domain;
use crate::codecs::toolkit::exact::{canonical_or_z, fixed_length2, fixed_root, length2, root, unorm_sqrt_ratio};
use crate::codecs::core::info::{Info, Sizes, FloatForm, seam};
use crate::codecs::core::codec_family::CodecFamily;
use crate::codecs::toolkit::fixed_decode::{fixed_square, BITS, ONE, fixed, fixed_target, nearest_decoded, search_doc};
use crate::codecs::toolkit::fixed_trig;
use crate::codecs::core::pipeline::codec_functions;
use crate::codecs::toolkit::quant::{Quant, Quants};
use crate::codecs::core::spec::SpecError;
use crate::codecs::toolkit::trig::{atan2_pi, sincos_pi};
use crate::model::{Float, V2, V3};

pub static FAMILY: CodecFamily<SphericalZ> = CodecFamily::new(
    Info {
        name: "spherical_z",
        title: "azimuth and z, (atan2(y, x)/π, z)·0.5 + 0.5 as unorm×2",
        sizes: Sizes::Total(&[16, 24, 32]),
        domain: Some(Domain::Sphere),
        source: "Pranckevičius method 3",
        edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z",
        decode_note: "decodes are unit length to within the trig approximations' error (about 2.5e-7)",
        float_form: FloatForm::Continuous { seam: seam::AZIMUTH_WRAP },
        options: &[],
    },
    |bits| SphericalZ { bits },
    codec_functions,
)
.with_helper_doc(|name| (name == "encode_codes").then(|| search_doc(BITS)));

#[derive(Clone, Copy, Debug)]
pub struct SphericalZ {
    pub bits: u32,
}

impl SphericalZ {
    /// The codec with the given total bit budget; an invalid size is an error listing
    /// the allowed ones.
    pub fn new(bits: u32) -> Result<SphericalZ, SpecError> {
        FAMILY.codec(bits)
    }

    fn field(&self) -> Quant {
        Quant::Unorm(self.bits / 2)
    }

    /// The codes of a canonical `w` (`s` its [`length2`]) at the boundaries
    /// `c + offset` (`½` rounds, `1` floors). The azimuth `T = atan2(y, x)/π` in units
    /// of `2^-23` ([`fixed_trig::atan2_pi`], a function of the input alone) is coded by
    /// [`fixed_trig::angle_code`]. The height `w.z / sqrt(s)` is decided by
    /// [`unorm_sqrt_ratio`].
    #[inline(always)]
    fn codes<F: Float>(&self, w: V3<F>, s: F, offset: f32) -> V2<F> {
        let q = self.field();
        let phi = fixed_trig::angle_code(q, fixed_trig::atan2_pi(w.y, w.x), offset);
        let z = unorm_sqrt_ratio(q, w.z, s, s.sqrt(), offset);
        V2::new(phi, z)
    }

    /// The decode of codes `c` in units of `2^-BITS`: `z = (2c - M)/M` one rounded
    /// product floored, `sqrt(1 - z²)` by [`fixed_root`], the
    /// azimuth's sine and cosine from [`fixed_trig::sincos_pi`] (units of `2^-24`), each
    /// product with the root rounded to a unit.
    #[inline(always)]
    fn fixed_direction<F: Float>(&self, c: V2<F>) -> V3<F> {
        let m = f64::from(self.field().max_code());
        let one = F::c(ONE as f32);
        let centred = { #[inline(always)] |c: F| c * F::c(2.0) - F::c(m as f32) };
        let z = fixed(centred(c.y), ONE / m).named("z");
        let rest = (one - fixed_square(z)).at_least(F::c(0.0));
        let r = fixed_root(rest * one).named("r");
        let sc = fixed_trig::sincos_pi(fixed(centred(c.x), fixed_trig::FINE / m));
        let scale = F::c((1.0 / fixed_trig::FINE) as f32);
        let xy = V2::new(sc.y, sc.x).map(#[inline(always)] |a| (a * r * scale).round());
        V3::from_xy(xy, z)
    }
}

impl Codec for SphericalZ {
    type P<F: Float> = V2<F>;
    type C<F: Float> = F::U;
    #[inline]
    fn quants(&self) -> Quants {
        Quants::new(&[self.field(); 2])
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    /// `((atan2(y, x)/π, z) + 1)·0.5` of the normalized input, as the seed writes it.
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V2<F> {
        let u = self.target(v);
        let phi = helper!(atan2_pi(u.y, u.x)).named("phi");
        (V2::new(phi, u.z) + F::c(1.0)) * F::c(0.5)
    }
    /// `((cos φ, sin φ)·sqrt(1 - z²), z)` with `φ = enc.x·2 - 1` half turns and
    /// `z = enc.y·2 - 1` (`1 - z²` as `(1 - z)(1 + z)`, floored at 0).
    #[inline(always)]
    fn direction<F: Float>(&self, enc: V2<F>) -> V3<F> {
        let p = ((enc - F::c(0.5)) * F::c(2.0)).named("p");
        let sp = helper!(sincos_pi(p.x)).named("sp");
        // 1 - z² as (1 - z)(1 + z): no product for a driver to fuse into the
        // subtraction, and no cancellation near the poles.
        let rest = ((F::c(1.0) - p.y) * (F::c(1.0) + p.y)).at_least(F::c(0.0));
        let r = rest.sqrt().named("r");
        V3::new(sp.y * r, sp.x * r, p.y)
    }
    /// The codes of [`SphericalZ::codes`] at `c + ½` of the canonical input.
    const EXACT_ROUNDING: bool = true;
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V2<F> {
        let (w, _) = canonical_or_z(v);
        self.codes(w, length2(w), 0.5)
    }
    /// The nearest of the four codes around the exact parameters (floors decided like
    /// [`Codec::round_codes`]' codes) by the squared distance of their fixed-point
    /// decodes. The azimuth wraps at ±π, where the search does not look across.
    const EXACT_SEARCH: bool = true;
    #[inline(always)]
    fn precise_codes<F: Float>(&self, v: V3<F>) -> V2<F> {
        let (w, _) = canonical_or_z(v);
        let s = fixed_length2(w);
        let base = self.codes(w, s, 1.0).named("base");
        let target = fixed_target(w, root(s), BITS);
        nearest_decoded([self.field(); 2], base, target, #[inline(always)] |c| self.fixed_direction(c))
    }
}
