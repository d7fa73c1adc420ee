//! Lambert equal-area projection of a hemisphere onto the unit disk plus a hemisphere bit
//! (survey §2, `eqarea`; Snyder and Mitchell 2001): `p = (x, y) / sqrt(1 + |z|)`, stored
//! as unorm `p·0.5 + 0.5`, and one bit for the sign of `z`, laid out as [`crate::codecs::azimuthal::disk`]
//! says (eqarea16: x bits 0–7, y bits 8–14, the hemisphere bit 15).

use crate::codecs::core::codec::Codec;
use crate::codecs::core::info::Domain;
use crate::codecs::azimuthal::disk::{
    DiskProjection, Folded, Radius, disk_fields, disk_quants, fixed_disk_point,
    nearest_disk_codes, unfold,
};
use crate::codecs::toolkit::exact::{fixed_length2_xy, fixed_root, unorm_sqrt_ratio};
use crate::codecs::core::info::{Info, Sizes, FloatForm, seam};
use crate::codecs::core::codec_family::CodecFamily;
use crate::codecs::toolkit::fixed_decode::{BITS, ONE, fixed, search_doc};
use crate::codecs::core::pipeline::codec_functions;
use crate::codecs::toolkit::quant::{Quant, Quants};
use crate::codecs::core::spec::SpecError;
use crate::model::{Float, V2, V3};

pub static FAMILY: CodecFamily<HemiEqArea> = CodecFamily::new(
    Info {
        name: "eqarea",
        title: "Lambert equal-area hemisphere on the unit disk + hemisphere bit, unorm×2",
        sizes: Sizes::Total(&[16, 20, 22, 24, 32]),
        domain: Some(Domain::Sphere),
        source: "Cigolle et al. 2014 §2 (eqarea); Snyder and Mitchell 2001",
        edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z; the equator (z = 0) is on the +Z side",
        decode_note: "every code decodes to a unit vector (up to rounding); codes outside the disk decode by the same formula (beyond the equator of their hemisphere, the square's corners at its opposite pole)",
        float_form: FloatForm::Continuous { seam: seam::HEMISPHERE_BIT },
        options: &[],
    },
    |bits| HemiEqArea { bits },
    codec_functions,
)
.with_helper_doc(|name| (name == "encode_codes").then(|| search_doc(BITS)));

#[derive(Clone, Copy, Debug)]
pub struct HemiEqArea {
    pub bits: u32,
}

impl HemiEqArea {
    /// The codec with the given total bit budget; an invalid size is an error listing
    /// the allowed ones.
    pub fn new(bits: u32) -> Result<HemiEqArea, SpecError> {
        FAMILY.codec(bits)
    }

    /// The unorm codes of the folded input at the boundaries `c + offset` (`½` rounds to
    /// the nearest code, `1` floors): the parameter is `w.x / sqrt(l·a)`, decided by
    /// [`unorm_sqrt_ratio`].
    #[inline(always)]
    fn codes<F: Float>(&self, f: &Folded<F>, offset: f32) -> V2<F> {
        let la = (f.l * f.a).named("la");
        let root_la = la.sqrt();
        let code = { #[inline(always)] |q: Quant, x: F| unorm_sqrt_ratio(q, x, la, root_la, offset) };
        let [qx, qy] = disk_fields(self.bits);
        V2::new(code(qx, f.w.x), code(qy, f.w.y))
    }

    /// The decode of codes `c` (and the hemisphere bit `h`) in units of `2^-BITS`: the
    /// disk point and `q = |p|²` from [`fixed_disk_point`], `sqrt(2 - q)` in units of `2^-20` by
    /// [`fixed_root`] (of at most `2^41`), then `p·sqrt(2 - q)` and `1 - q`.
    #[inline(always)]
    fn fixed_direction<F: Float>(&self, c: V2<F>, h: F) -> V3<F> {
        let one = F::c(ONE as f32);
        let (p, q) = fixed_disk_point(self.bits, c);
        let rest = (F::c((2.0 * ONE) as f32) - q).at_least(F::c(0.0));
        let g = fixed_root(rest * F::c((1u32 << 19) as f32)).named("g");
        let xy = p.map(#[inline(always)] |x| fixed(x * g, 1.0 / f64::from(1u32 << 20)));
        V3::from_xy(xy, unfold(one - q, h))
    }
}

impl Codec for HemiEqArea {
    type P<F: Float> = V3<F>;
    type C<F: Float> = F::U;
    #[inline]
    fn quants(&self) -> Quants {
        disk_quants(self.bits)
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    /// `(w.xy / sqrt(l·a)·0.5 + 0.5, z < 0)` of the folded canonical input, as the
    /// packed encoder decides them.
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V3<F> {
        let f = Folded::of(v);
        let enc = (f.w.xy() / (f.l * f.a).sqrt() * F::c(0.5) + F::c(0.5)).named("enc");
        V3::from_xy(enc, f.h)
    }
    /// `(p·sqrt(2 - q), 1 - q)` with `p = enc·2 - 1`, `q = |p|²` (at most 2, the
    /// square's corners), z negated where the hemisphere bit is set: unit length for
    /// every code.
    #[inline(always)]
    fn direction<F: Float>(&self, enc: V3<F>) -> V3<F> {
        let p = ((enc.xy() - F::c(0.5)) * F::c(2.0)).named("p");
        let (xy, z) = Self::lift(p);
        V3::from_xy(xy, unfold(z, enc.z))
    }
    /// The codes of [`HemiEqArea::codes`] at `c + ½`, the hemisphere bit from the sign
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

/// The equal-area disk radius is `ρ/sqrt(1 + |z|)`: `ρ/sqrt(l·a)` of the folded input.
impl DiskProjection for HemiEqArea {
    #[inline(always)]
    fn half_radius<F: Float>(f: &Folded<F>, rho: F) -> F {
        rho / (f.l * f.a).sqrt() * F::c(0.5)
    }
    #[inline(always)]
    fn radius<F: Float>(f: &Folded<F>) -> Radius<F> {
        Radius::Root {
            rho2: fixed_length2_xy(f.w),
            d: f.l * f.a,
        }
    }
    /// `(p·sqrt(2 - q), 1 - q)` with `q = |p|²` (at most 2, a square's corners).
    #[inline(always)]
    fn lift<F: Float>(p: V2<F>) -> (V2<F>, F) {
        let q = p.length_squared().at_most(F::c(2.0)).named("q");
        let g = (F::c(2.0) - q).sqrt().named("g");
        (p * g, F::c(1.0) - q)
    }
}
