//! Lambert azimuthal equal-area projection (first seed, method 6), full sphere, stored as
//! unorm×2: `enc = xy / sqrt(8z + 8) + 0.5`. The seed's encoder assumed unit input (its
//! own erratum); this one normalizes first.

use crate::codecs::core::codec::Codec;
use crate::codecs::core::info::Domain;
use crate::codecs::toolkit::exact::{OnePlusZ, decided, fixed_root, float_of, past_root_ratio};
use crate::codecs::toolkit::fixed_decode::{
    BITS, ONE, fixed, fixed_target, nearest_decoded, odd_square_quarter, search_doc,
};
use crate::codecs::toolkit::quant::{Quant, Quants};
use crate::model::{Bool, Float, Uint, V2, V3};
use crate::codecs::core::info::{Info, Sizes, FloatForm, seam};
use crate::codecs::core::codec_family::CodecFamily;
use crate::codecs::core::ieee;
use crate::codecs::core::pipeline::codec_functions;
use crate::codecs::core::spec::SpecError;

pub static FAMILY: CodecFamily<Lambert> = CodecFamily::new(
    Info {
        name: "lambert",
        title: "Lambert azimuthal equal-area, unorm×2",
        sizes: Sizes::Total(&[16, 24, 32]),
        domain: Some(Domain::Sphere),
        source: "Pranckevičius, Compact Normal Storage, method 6",
        edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z; -Z encodes as (1, 0.5)",
        decode_note: "every code decodes to a unit vector; codes outside the disk decode as -Z",
        float_form: FloatForm::Continuous { seam: seam::RIM_IS_MINUS_Z },
        options: &[ieee::OPTION],
    },
    |bits| Lambert { bits },
    |spec, c| ieee::functions(spec, c, codec_functions),
)
.with_validate(|spec| ieee::validate(spec, false))
.with_variants(&["lambert16:guarantee=ieee"])
.with_helper_doc(|name| (name == "encode_codes").then(|| search_doc(BITS)));

impl Lambert {
    /// The codec with the given total bit budget; an invalid size is an error listing
    /// the allowed ones.
    pub fn new(bits: u32) -> Result<Lambert, SpecError> {
        FAMILY.codec(bits)
    }
}

#[derive(Clone, Copy, Debug)]
pub struct Lambert {
    pub bits: u32,
}

/// The codes of -Z, which the projection maps onto the whole rim.
#[inline(always)]
fn pole<F: Float>(m: f32) -> V2<F> {
    V2::new(F::c(m), F::c((m + 1.0) * 0.5))
}

impl Lambert {
    /// The codes of `p` (not -Z) at boundaries `c + offset`: `½` rounds to the nearest code, `1` floors.
    #[inline(always)]
    fn codes<F: Float>(&self, p: &OnePlusZ<F>, offset: f32) -> V2<F> {
        let q = self.quants()[0];
        let m = q.max_code();
        let la = (p.l * p.a).named("la");
        let g = (la / p.b).sqrt() * F::c(8f32.sqrt() / m);
        let m2 = F::c((f64::from(m) * f64::from(m) / 8.0) as f32);
        p.w.xy().map(#[inline(always)] |x| {
            let big2 = (x * x * p.b * m2).named("big2");
            let estimate = (x / g + F::c(m * 0.5)).round();
            decided(q, estimate, #[inline(always)] |c| {
                let h = c - F::c(m * 0.5 - offset);
                past_root_ratio(x, big2, h, h * h * la)
            })
        })
    }

    /// The decode of unorm codes `c` in fixed point ([`crate::codecs::toolkit::fixed_decode`]):
    /// with `t = 2c - M` and `R = M² - |t|²` (0 outside the disk), the direction is
    /// `(2t·sqrt(R), 2R - M²) / M²`, from exact integers, one root and products.
    #[inline(always)]
    fn fixed_direction<F: Float>(&self, c: V2<F>) -> V3<F> {
        let m = self.quants()[0].max_code();
        let t = (c * F::c(2.0) - F::c(m)).named("t");
        let quarter = odd_square_quarter(t);
        // M² - 2 = 4·mq + 3, so R = 4·(mq - quarter) + 3 inside the disk.
        let mq = F::U::c(((u64::from(m as u32).pow(2) - 5) / 4) as u32);
        let inside = mq.lt(quarter).not();
        // Below 2^32 (mq < 2^30); the scaling stays in integers, where no driver can
        // regroup it with the conversion's addition.
        let rest = mq.wrapping_sub(quarter).shl(2) + F::U::c(3);
        let r = float_of::<F>(F::U::sel(inside, rest, F::U::c(0))).named("r");
        let k = 2.0 * ONE / (f64::from(m) * f64::from(m));
        // `sqrt(R)·k·2^b` (below 2^21) as the fixed root of one product, so that `t`
        // meets it in one product: a chain `t·sqrt(R)·k` may be regrouped around its
        // literal; the power of two is exact wherever it goes.
        let b = (f64::from(m) * 0.5).log2().floor();
        let scale = 2f64.powf(b);
        let g = fixed_root(r * F::c((k * k * scale * scale) as f32)).named("g");
        let xy = t.map(#[inline(always)] |x| fixed(x * g, 1.0 / scale));
        V3::from_xy(xy, fixed(r, k) - F::c(ONE as f32))
    }
}

impl Codec for Lambert {
    type P<F: Float> = V2<F>;
    type C<F: Float> = F::U;
    #[inline]
    fn quants(&self) -> Quants {
        Quants::new(&[Quant::Unorm(self.bits / 2); 2])
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    /// `w.xy / sqrt(8·l·a / b) + 0.5` from the same canonical input, length and `1 + z`
    /// as [`Codec::round_codes`] (so the float form and the packed code agree to a few
    /// ULP, and `1 + z` does not cancel near -Z). -Z, which the projection maps onto the
    /// whole rim, encodes as (1, 0.5).
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V2<F> {
        let p = OnePlusZ::of(v);
        let g = ((p.l * p.a / p.b) * F::c(8.0)).sqrt().named("g");
        let enc = p.w.xy() / g + F::c(0.5);
        let enc = V2::sel_all(p.at_pole(), V2::new(F::c(1.0), F::c(0.5)), enc);
        V2::sel_all(p.ok, enc, V2::splat(F::c(0.5)))
    }
    /// The seed's `xy / sqrt(8z + 8) + 0.5` of the normalized input in plain arithmetic
    /// (the lean tier); -Z encodes as (1, 0.5) and input whose squared length is not a
    /// positive finite `f32` as +Z, like the default tier.
    #[inline(always)]
    fn ieee_params<F: Float>(&self, v: V3<F>) -> V2<F> {
        let len2 = v.length_squared().named("len2");
        let ok = len2.gt(F::c(0.0)).and(len2.le(F::c(f32::MAX)));
        let n = (v / len2.sqrt()).named("n");
        let f = (n.z * F::c(8.0) + F::c(8.0)).sqrt().named("f");
        let enc = n.xy() / f + F::c(0.5);
        let enc = V2::sel_all(f.gt(F::c(0.0)), enc, V2::new(F::c(1.0), F::c(0.5)));
        V2::sel_all(ok, enc, V2::splat(F::c(0.5)))
    }
    /// `x / sqrt(8(1 + z))` of the canonical input is `w.x / sqrt(8·l·a / b)`
    /// ([`crate::codecs::toolkit::exact::one_plus_z`], `l` the length from [`crate::codecs::toolkit::exact::root`]), so the code boundary `c + ½` is
    /// passed where `w.x·M ≥ h·sqrt(8·l·a / b)` (`h = c + ½ - M/2`, an integer): decided
    /// by the signs of `w.x` and `h` and, where they agree, by `(w.x²·b)·(M²/8)` against
    /// `h²·(l·a)`, products of exact or deterministic values meeting in a comparison
    /// ([`crate::codecs::toolkit::exact`]), each literal factor last (drivers move literal factors
    /// outwards). -Z encodes as (M, (M+1)/2), as before.
    const EXACT_ROUNDING: bool = true;
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V2<F> {
        let m = self.quants()[0].max_code();
        let p = OnePlusZ::of(v);
        let codes = V2::sel_all(p.at_pole(), pole(m), self.codes(&p, 0.5));
        V2::sel_all(p.ok, codes, V2::splat(F::c((m + 1.0) * 0.5)))
    }
    /// The nearest of the four codes around the exact parameters (floors decided like
    /// [`Codec::round_codes`]' codes, with boundaries at `c + 1`) by the squared distance
    /// of their fixed-point decodes ([`crate::codecs::toolkit::fixed_decode`]); -Z encodes as
    /// (M, (M+1)/2), like the fast encoder.
    const EXACT_SEARCH: bool = true;
    #[inline(always)]
    fn precise_codes<F: Float>(&self, v: V3<F>) -> V2<F> {
        let q = self.quants()[0];
        let m = q.max_code();
        let p = OnePlusZ::of(v);
        // -Z has no parameters to search around; it searches around +Z, then is replaced.
        let s = p.off_pole();
        let base = self.codes(&s, 1.0).named("base");
        let target = fixed_target(s.w, s.l, BITS);
        let best = nearest_decoded([q; 2], base, target, #[inline(always)] |c| self.fixed_direction(c));
        let codes = V2::sel_all(p.at_pole(), pole(m), best);
        V2::sel_all(p.ok, codes, V2::splat(F::c((m + 1.0) * 0.5)))
    }
    /// Codes outside the disk (the square's corners) decode as -Z; every decode is unit
    /// length up to rounding.
    #[inline(always)]
    fn direction<F: Float>(&self, enc: V2<F>) -> V3<F> {
        let fenc = (enc * F::c(4.0) - F::c(2.0)).named("fenc");
        let f = fenc.length_squared();
        let f = f.at_most(F::c(4.0)).named("f");
        let g = (F::c(1.0) - f * F::c(0.25)).sqrt().named("g");
        V3::from_xy(fenc * g, F::c(1.0) - f * F::c(0.5))
    }
}

/// A decoder of Lambert's mapping written another way: the first seed's spheremap
/// ([`crate::codecs::azimuthal::spheremap`]) and CryEngine 3 ([`crate::codecs::azimuthal::cry3`]) decoders.
pub trait LambertDecoder: Copy + Send + Sync {
    /// Parameters in storage range (Lambert's) → direction.
    fn direction<F: Float>(&self, enc: V2<F>) -> V3<F>;
}

/// Lambert's codes, encoders and all, decoded by `decoder`: for unit input the seed's
/// methods 4, 5 and 6 are one mapping (its erratum), so only the decoders differ.
#[derive(Clone, Copy, Debug)]
pub struct WithDecoder<D> {
    pub lambert: Lambert,
    pub decoder: D,
}

impl<D: LambertDecoder> Codec for WithDecoder<D> {
    type P<F: Float> = V2<F>;
    type C<F: Float> = F::U;
    #[inline]
    fn quants(&self) -> Quants {
        self.lambert.quants()
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    /// [`Lambert`]'s parameters.
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V2<F> {
        self.lambert.params(v)
    }
    #[inline(always)]
    fn direction<F: Float>(&self, enc: V2<F>) -> V3<F> {
        self.decoder.direction(enc)
    }
    const EXACT_ROUNDING: bool = true;
    /// [`Lambert`]'s codes, decided exactly.
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V2<F> {
        self.lambert.round_codes(v)
    }
    const EXACT_SEARCH: bool = true;
    /// [`Lambert`]'s search: candidates are compared by their exact directions, which
    /// every decoder of the mapping computes.
    #[inline(always)]
    fn precise_codes<F: Float>(&self, v: V3<F>) -> V2<F> {
        self.lambert.precise_codes(v)
    }
}
