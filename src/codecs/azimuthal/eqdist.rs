//! Azimuthal equidistant projection of a hemisphere onto the unit disk plus a
//! hemisphere bit (survey §2, `eqdist`; Snyder and Mitchell 2001): the disk point keeps
//! the azimuth and puts the polar angle `θ = atan2(ρ, |z|)` at radius `θ/(π/2)`, so
//! `p = (x, y)/ρ · θ/(π/2)`, stored as unorm `p·0.5 + 0.5`, and one bit for the sign of
//! `z`, laid out as [`crate::codecs::azimuthal::disk`] says (eqdist16: x bits 0–7, y bits 8–14, the
//! hemisphere bit 15).
//!
//! The decode `(p·sin(π·r/2)/r, cos(π·r/2))` (`r = |p|`) is written as two series in
//! `r²` ([`crate::codecs::toolkit::trig::sinc_cos_quarter`]), so it needs neither a root nor a quotient.
//! The angle comes from the model's trigonometry, never a builtin.

use crate::model::num::helper;
use crate::codecs::core::codec::Codec;
use crate::codecs::core::info::Domain;
use crate::codecs::azimuthal::disk::{
    DiskProjection, Folded, Radius, disk_fields, disk_quants, fixed_disk_point,
    nearest_disk_codes, unfold,
};
use crate::codecs::toolkit::exact::{decided, fixed_length2_xy, past_root_ratio, root_of};
use crate::codecs::core::info::{Info, Sizes, FloatForm, seam};
use crate::codecs::core::codec_family::CodecFamily;
use crate::codecs::toolkit::fixed_decode::{BITS, ONE, search_doc};
use crate::codecs::toolkit::fixed_trig;
use crate::codecs::core::pipeline::codec_functions;
use crate::codecs::toolkit::quant::{Quant, Quants};
use crate::codecs::core::spec::SpecError;
use crate::codecs::toolkit::trig::{atan2_pi, sinc_cos_quarter};
use crate::model::{Float, V2, V3};

pub static FAMILY: CodecFamily<HemiEqDist> = CodecFamily::new(
    Info {
        name: "eqdist",
        title: "azimuthal equidistant hemisphere on the unit disk + hemisphere bit, unorm×2",
        sizes: Sizes::Total(&[16, 20, 22, 24, 32]),
        domain: Some(Domain::Sphere),
        source: "Cigolle et al. 2014 §2 (eqdist); Snyder and Mitchell 2001",
        edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z; the equator (z = 0) is on the +Z side",
        decode_note: "decodes are unit length to within the series' rounding (a few ULP); codes outside the disk decode by the same formula (up to 127° from their hemisphere's pole, beyond its equator)",
        float_form: FloatForm::Continuous { seam: seam::HEMISPHERE_BIT },
        options: &[],
    },
    |bits| HemiEqDist { bits },
    codec_functions,
)
.with_helper_doc(|name| (name == "encode_codes").then(|| search_doc(BITS)));

#[derive(Clone, Copy, Debug)]
pub struct HemiEqDist {
    pub bits: u32,
}

impl HemiEqDist {
    /// The codec with the given total bit budget; an invalid size is an error listing
    /// the allowed ones.
    pub fn new(bits: u32) -> Result<HemiEqDist, SpecError> {
        FAMILY.codec(bits)
    }

    /// The unorm codes of the folded input at the boundaries `c + offset` (`½` rounds to
    /// the nearest code, `1` floors).
    ///
    /// `ρ² = w.x² + w.y²` comes from [`fixed_length2_xy`] and `ρ` from [`root_of`], the
    /// angle `T = θ/π` in units of `2^-23` from [`fixed_trig::atan2_pi`]: all functions
    /// of the input alone. The parameter scaled to codes is `M/2 + M·T·2^-23·w.x/ρ`, so
    /// the boundary `c + offset` is passed where `w.x·T·(M·2^-23) ≥ k·ρ`
    /// (`k = c + offset - M/2`), which [`past_root_ratio`] decides from the square of
    /// the left side (products only, the literal last) and `k²·ρ²`. At the pole
    /// (`ρ² = 0`, where then `T = 0`) any positive stand-in for `ρ²` decides every
    /// boundary by the sign of `k`, as a parameter of exactly 0 should be.
    #[inline(always)]
    fn codes<F: Float>(&self, f: &Folded<F>, offset: f32) -> V2<F> {
        let (rho2, t) = polar_angle(f);
        let code = { #[inline(always)] |q: Quant, x: F| {
            let m = q.max_code();
            let big = (x * t * F::c((f64::from(m) / fixed_trig::ONE) as f32)).named("big");
            let estimate = (big / rho2.sqrt() + F::c(m * 0.5)).round();
            // Squared as `|big|·|big|` (the same bits): `big·big`, a product by a constant
            // squared, is what Slang's SPIR-V optimizer regroups as `(x·t)²·K²`
            // (`exact::snorm_sqrt_ratio` says more).
            let magnitude = big.abs();
            decided(q, estimate, #[inline(always)] |c| {
                let k = c - F::c(m * 0.5 - offset);
                past_root_ratio(x, magnitude * magnitude, k, k * k * rho2)
            })
        } };
        let [qx, qy] = disk_fields(self.bits);
        V2::new(code(qx, f.w.x), code(qy, f.w.y))
    }

    /// The decode of codes `c` (and the hemisphere bit `h`) in units of `2^-BITS`: the
    /// disk point and `q = |p|²` from [`fixed_disk_point`], the two series of
    /// [`fixed_trig::sinc_cos_quarter`] in the same units, then `p·sinc` rounded to a unit.
    #[inline(always)]
    fn fixed_direction<F: Float>(&self, c: V2<F>, h: F) -> V3<F> {
        let (p, q) = fixed_disk_point(self.bits, c);
        let sc = fixed_trig::sinc_cos_quarter(q, ONE);
        let xy = p.map(#[inline(always)] |x| (x * sc.x * F::c((1.0 / ONE) as f32)).round());
        V3::from_xy(xy, unfold(sc.y, h))
    }
}

/// `ρ² = w.x² + w.y²` of the folded input from [`fixed_length2_xy`], with any positive
/// stand-in at the pole (`ρ² = 0`), and the polar angle `θ/π = atan2(ρ, |z|)/π` in
/// units of `2^-23` half turns from [`fixed_trig::atan2_pi`] (`ρ` from [`root_of`], 0 at
/// the pole): functions of the input alone.
#[inline(always)]
pub fn polar_angle<F: Float>(f: &Folded<F>) -> (F, F) {
    let rho2 = fixed_length2_xy(f.w);
    let has_rho = rho2.gt(F::c(0.0));
    let rho2 = F::sel(has_rho, rho2, F::c(1.0)).named("rho2");
    let rho = F::sel(has_rho, root_of(rho2), F::c(0.0)).named("rho");
    (rho2, fixed_trig::atan2_pi(rho, f.w.z.abs()).named("t"))
}

impl Codec for HemiEqDist {
    type P<F: Float> = V3<F>;
    type C<F: Float> = F::U;
    #[inline]
    fn quants(&self) -> Quants {
        disk_quants(self.bits)
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    /// `(w.xy·(θ/π)/ρ + 0.5, z < 0)` of the folded canonical input (`p·0.5 + 0.5` with
    /// `p = w.xy/ρ · θ/(π/2)`); the pole, where `ρ = 0`, is the disk's centre.
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V3<F> {
        let f = Folded::of(v);
        let rho = f.w.xy().length_squared().sqrt().named("rho");
        let t = helper!(atan2_pi(rho, f.w.z.abs())).named("t");
        let s = (t / F::sel(rho.gt(F::c(0.0)), rho, F::c(1.0))).named("s");
        let enc = (f.w.xy() * s + F::c(0.5)).named("enc");
        V3::from_xy(enc, f.h)
    }
    /// `(p·sin(π·r/2)/r, cos(π·r/2))` with `p = enc·2 - 1` and `r = |p|` (the two
    /// series in `r²` of [`sinc_cos_quarter`]), z negated where the hemisphere bit is
    /// set: unit length for every code, the square's corners (`r = √2`) 127° from their
    /// hemisphere's pole.
    #[inline(always)]
    fn direction<F: Float>(&self, enc: V3<F>) -> V3<F> {
        let p = ((enc.xy() - F::c(0.5)) * F::c(2.0)).named("p");
        let (xy, z) = Self::lift(p);
        V3::from_xy(xy, unfold(z, enc.z))
    }
    /// The codes of [`HemiEqDist::codes`] at `c + ½`, the hemisphere bit from the sign
    /// of the canonical `z`.
    const EXACT_ROUNDING: bool = true;
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V3<F> {
        let f = Folded::of(v);
        V3::from_xy(self.codes(&f, 0.5), f.h)
    }
    /// The nearest of the four codes around the exact parameters (floors decided like
    /// [`Codec::round_codes`]' codes, with boundaries at `c + 1`), in the input's
    /// hemisphere, by the squared distance of their fixed-point decodes.
    const EXACT_SEARCH: bool = true;
    #[inline(always)]
    fn precise_codes<F: Float>(&self, v: V3<F>) -> V3<F> {
        let f = Folded::of(v);
        let base = self.codes(&f, 1.0).named("base");
        nearest_disk_codes(self.bits, &f, base, #[inline(always)] |c, h| self.fixed_direction(c, h))
    }
}

/// The equidistant disk radius is `θ/(π/2)`, `θ = atan2(ρ, |z|)` the polar angle.
impl DiskProjection for HemiEqDist {
    #[inline(always)]
    fn half_radius<F: Float>(f: &Folded<F>, rho: F) -> F {
        helper!(atan2_pi(rho, f.w.z.abs()))
    }
    #[inline(always)]
    fn radius<F: Float>(f: &Folded<F>) -> Radius<F> {
        let (rho2, t) = polar_angle(f);
        Radius::Angle { t, rho2 }
    }
    /// `(p·sin(π·r/2)/r, cos(π·r/2))` with `r = |p|`: the two series in `r²` of
    /// [`sinc_cos_quarter`].
    #[inline(always)]
    fn lift<F: Float>(p: V2<F>) -> (V2<F>, F) {
        let q = p.length_squared().named("q");
        let sc = sinc_cos_quarter(q);
        (p * sc.x, sc.y)
    }
}
