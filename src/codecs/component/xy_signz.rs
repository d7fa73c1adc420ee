//! X and Y stored with the sign of Z, Z reconstructed (first seed method 2, "store
//! X&Y&sign of Z"): method 1 ([`crate::codecs::component::xy`]) made whole-sphere by one bit,
//! `z = ±sqrt(1 - saturate(x² + y²))`.
//!
//! Layout of a `B`-bit code: x as snorm in the lowest `⌈(B-1)/2⌉` bits, y as snorm in
//! the next `⌊(B-1)/2⌋`, the sign bit of z (1 for `z < 0`) at bit `B - 1` (xy_signz16:
//! x bits 0–7, y bits 8–14, the sign bit 15). The equator and `-0` are on the +Z side.

use crate::codecs::core::codec::Codec;
use crate::codecs::core::info::Domain;
use crate::codecs::azimuthal::disk::unfold;
use crate::codecs::toolkit::exact::{
    canonical_or_z, fixed_length2, fixed_root, floor_ratio, length2, one_if, root,
    snorm_sqrt_ratio,
};
use crate::codecs::core::info::{Info, Sizes, FloatForm, seam};
use crate::codecs::core::codec_family::CodecFamily;
use crate::codecs::toolkit::fixed_decode::{fixed_length2_2d, BITS, ONE, fixed, fixed_target, nearest_decoded, search_doc};
use crate::codecs::core::pipeline::codec_functions;
use crate::codecs::toolkit::quant::{Quant, Quants};
use crate::codecs::core::spec::SpecError;
use crate::model::{Float, V2, V3};

pub static FAMILY: CodecFamily<XySignZ> = CodecFamily::new(
    Info {
        name: "xy_signz",
        title: "x and y stored with the sign of z, z reconstructed, snorm×2 + 1 bit",
        sizes: Sizes::Total(&[16, 24, 32]),
        domain: Some(Domain::Sphere),
        source: "Pranckevičius method 2",
        edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z; the equator (z = 0) and -0 are on the +Z side",
        decode_note: "z = ±sqrt(1 - saturate(x²+y²)); codes outside the unit disk decode to (x, y, ±0), longer than 1",
        float_form: FloatForm::Continuous { seam: seam::HEMISPHERE_BIT },
        options: &[],
    },
    |bits| XySignZ { bits },
    codec_functions,
)
.with_helper_doc(|name| (name == "encode_codes").then(|| search_doc(BITS)));

#[derive(Clone, Copy, Debug)]
pub struct XySignZ {
    pub bits: u32,
}

impl XySignZ {
    /// The codec with the given total bit budget; an invalid size is an error listing
    /// the allowed ones.
    pub fn new(bits: u32) -> Result<XySignZ, SpecError> {
        FAMILY.codec(bits)
    }

    fn fields(&self) -> [Quant; 2] {
        let rest = self.bits - 1;
        [Quant::Snorm(rest.div_ceil(2)), Quant::Snorm(rest / 2)]
    }

    /// The decode of snorm codes `c` with the sign bit `h` in units of `2^-BITS`: each
    /// component `c/M` one rounded product floored, `q = x² + y²` from squares rounded
    /// to a unit (an exact sum), `z = sqrt(1 - q)` by [`fixed_root`] of one product
    /// (0 outside the disk).
    #[inline(always)]
    fn fixed_direction<F: Float>(&self, c: V2<F>, h: F) -> V3<F> {
        let [qx, qy] = self.fields();
        let one = F::c(ONE as f32);
        let k = { #[inline(always)] |q: Quant| ONE / f64::from(q.max_code()) };
        let p = V2::new(fixed(c.x, k(qx)), fixed(c.y, k(qy))).named("p");
        let rest = (one - fixed_length2_2d(p)).at_least(F::c(0.0)).named("rest");
        let z = fixed_root(rest * one);
        V3::from_xy(p, unfold(z, h))
    }
}

impl Codec for XySignZ {
    type P<F: Float> = V3<F>;
    type C<F: Float> = F::U;
    #[inline]
    fn quants(&self) -> Quants {
        let [qx, qy] = self.fields();
        Quants::new(&[qx, qy, Quant::Unorm(1)])
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    /// `(x, y, z < 0)` of the normalized input.
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V3<F> {
        let u = self.target(v);
        V3::from_xy(u.xy(), one_if(u.z.lt(F::c(0.0))))
    }
    /// `(x, y, ±sqrt(1 - min(x² + y², 1)))`, z negated where the sign bit is set.
    #[inline(always)]
    fn direction<F: Float>(&self, p: V3<F>) -> V3<F> {
        let xy = p.xy();
        let d = xy.length_squared();
        let d = F::sel(d.lt(F::c(1.0)), d, F::c(1.0)).named("d");
        V3::from_xy(xy, unfold((F::c(1.0) - d).sqrt(), p.z))
    }
    /// `x / |w|` and `y / |w|` of the canonical input, decided portably
    /// ([`snorm_sqrt_ratio`]), and the sign bit of its `z` (a `-0` is already `+0`).
    const EXACT_ROUNDING: bool = true;
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V3<F> {
        let [qx, qy] = self.fields();
        let (w, _) = canonical_or_z(v);
        let s = length2(w);
        let c = V2::new(snorm_sqrt_ratio(qx, w.x, s), snorm_sqrt_ratio(qy, w.y, s));
        V3::from_xy(c, one_if(w.z.lt(F::c(0.0))))
    }
    /// The nearest of the four codes around the exact parameters (floors decided by
    /// [`floor_ratio`]), with the input's sign bit, by the squared distance of their
    /// fixed-point decodes.
    const EXACT_SEARCH: bool = true;
    #[inline(always)]
    fn precise_codes<F: Float>(&self, v: V3<F>) -> V3<F> {
        let [qx, qy] = self.fields();
        let (w, _) = canonical_or_z(v);
        let l = root(fixed_length2(w));
        let h = one_if(w.z.lt(F::c(0.0)));
        let base = V2::new(floor_ratio(qx, w.x, l), floor_ratio(qy, w.y, l)).named("base");
        let target = fixed_target(w, l, BITS);
        let best = nearest_decoded([qx, qy], base, target, #[inline(always)] |c| self.fixed_direction(c, h));
        V3::from_xy(best, h)
    }
}
