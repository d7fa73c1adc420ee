//! Stereographic projection of a hemisphere onto the unit disk plus a hemisphere bit
//! (survey §2, `stereo`; Snyder and Mitchell 2001): `p = (x, y) / (1 + |z|)`, stored as
//! unorm `p·0.5 + 0.5`, and one bit for the sign of `z`, laid out as [`crate::codecs::azimuthal::disk`]
//! says (stereo16: x bits 0–7, y bits 8–14, the hemisphere bit 15).

use crate::codecs::core::codec::Codec;
use crate::codecs::core::info::Domain;
use crate::codecs::azimuthal::disk::{
    DiskProjection, Folded, Radius, disk_fields, disk_quants, fixed_disk_point,
    nearest_disk_codes, unfold,
};
use crate::codecs::toolkit::exact::{fixed_length2_xy, fixed_ratio, unorm_ratio};
use crate::codecs::core::info::{Info, Sizes, FloatForm, seam};
use crate::codecs::core::codec_family::CodecFamily;
use crate::codecs::toolkit::fixed_decode::{BITS, ONE, search_doc};
use crate::codecs::core::pipeline::codec_functions;
use crate::codecs::toolkit::quant::Quants;
use crate::codecs::core::spec::SpecError;
use crate::model::{Float, V2, V3};

pub static FAMILY: CodecFamily<HemiStereo> = CodecFamily::new(
    Info {
        name: "stereo",
        title: "stereographic hemisphere on the unit disk + hemisphere bit, unorm×2",
        sizes: Sizes::Total(&[16, 20, 22, 24, 32]),
        domain: Some(Domain::Sphere),
        source: "Cigolle et al. 2014 §2 (stereo); Snyder and Mitchell 2001",
        edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z; the equator (z = 0) is on the +Z side",
        decode_note: "every code decodes to a unit vector (up to rounding); codes outside the disk decode by the same formula (beyond the equator of their hemisphere)",
        float_form: FloatForm::Continuous { seam: seam::HEMISPHERE_BIT },
        options: &[],
    },
    |bits| HemiStereo { bits },
    codec_functions,
)
.with_helper_doc(|name| (name == "encode_codes").then(|| search_doc(BITS)));

#[derive(Clone, Copy, Debug)]
pub struct HemiStereo {
    pub bits: u32,
}

impl HemiStereo {
    /// The codec with the given total bit budget; an invalid size is an error listing
    /// the allowed ones.
    pub fn new(bits: u32) -> Result<HemiStereo, SpecError> {
        FAMILY.codec(bits)
    }

    /// The unorm codes of `w.xy / (1 + |z|)` (`w` canonical, `a = l + |w.z|` with `l`
    /// its length, a sum of positives, never 0) at the boundaries `c + offset`: the
    /// parameter is `w.x / a`, decided by [`unorm_ratio`].
    #[inline(always)]
    fn codes<F: Float>(&self, w: V3<F>, a: F, offset: f32) -> V2<F> {
        let [qx, qy] = disk_fields(self.bits);
        V2::new(
            unorm_ratio(qx, w.x, a, offset),
            unorm_ratio(qy, w.y, a, offset),
        )
    }

    /// The decode of codes `c` (and the hemisphere bit `h`) in units of `2^-BITS`: the
    /// disk point from [`fixed_disk_point`], then `2p / (1 + |p|²)` and
    /// `(1 - |p|²) / (1 + |p|²)` from products rounded to a unit (exact integers below
    /// `2^24`) and quotients decided by [`fixed_ratio`].
    #[inline(always)]
    fn fixed_direction<F: Float>(&self, c: V2<F>, h: F) -> V3<F> {
        let one = F::c(ONE as f32);
        let (p, q) = fixed_disk_point(self.bits, c);
        let d = one + q;
        let xy = p.map(#[inline(always)] |x| fixed_ratio(x + x, d, BITS));
        let z = fixed_ratio(one - q, d, BITS);
        V3::from_xy(xy, unfold(z, h))
    }
}

impl Codec for HemiStereo {
    type P<F: Float> = V3<F>;
    type C<F: Float> = F::U;
    #[inline]
    fn quants(&self) -> Quants {
        disk_quants(self.bits)
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    /// `(w.xy / (l + |w.z|)·0.5 + 0.5, z < 0)` of the canonical input and its length, as
    /// the packed encoder decides them.
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V3<F> {
        let f = Folded::of(v);
        let enc = (f.w.xy() / f.a * F::c(0.5) + F::c(0.5)).named("enc");
        V3::from_xy(enc, f.h)
    }
    /// `(2p, 1 - |p|²) / (1 + |p|²)` with `p = enc·2 - 1`, z negated where the hemisphere
    /// bit is set. Both numerators are computed, so every component divides exactly once.
    #[inline(always)]
    fn direction<F: Float>(&self, enc: V3<F>) -> V3<F> {
        let p = ((enc.xy() - F::c(0.5)) * F::c(2.0)).named("p");
        let (xy, z) = Self::lift(p);
        V3::from_xy(xy, unfold(z, enc.z))
    }
    /// The codes of [`HemiStereo::codes`] at `c + ½`, the hemisphere bit from the sign
    /// of the canonical `z` (a `-0` is already `+0` there).
    const EXACT_ROUNDING: bool = true;
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V3<F> {
        let f = Folded::of(v);
        V3::from_xy(self.codes(f.w, f.a, 0.5), f.h)
    }
    /// The nearest of the four codes around the exact parameters (floors decided like
    /// [`Codec::round_codes`]' codes, with boundaries at `c + 1`), in the input's
    /// hemisphere, by the squared distance of their fixed-point decodes.
    const EXACT_SEARCH: bool = true;
    #[inline(always)]
    fn precise_codes<F: Float>(&self, v: V3<F>) -> V3<F> {
        let f = Folded::of(v);
        let base = self.codes(f.w, f.a, 1.0).named("base");
        nearest_disk_codes(self.bits, &f, base, #[inline(always)] |c, h| self.fixed_direction(c, h))
    }
}

/// The stereographic disk radius is `ρ/(1 + |z|)`: `ρ/a` of the folded input.
impl DiskProjection for HemiStereo {
    #[inline(always)]
    fn half_radius<F: Float>(f: &Folded<F>, rho: F) -> F {
        rho / f.a * F::c(0.5)
    }
    #[inline(always)]
    fn radius<F: Float>(f: &Folded<F>) -> Radius<F> {
        Radius::Root {
            rho2: fixed_length2_xy(f.w),
            d: f.a * f.a,
        }
    }
    /// `(2p, 1 - |p|²) / (1 + |p|²)`: both numerators are computed, so every component
    /// divides exactly once.
    #[inline(always)]
    fn lift<F: Float>(p: V2<F>) -> (V2<F>, F) {
        let q = p.length_squared().named("q");
        let d = (q + F::c(1.0)).named("d");
        let z = (F::c(1.0) - q) / d;
        ((p + p) / d, z)
    }
}
