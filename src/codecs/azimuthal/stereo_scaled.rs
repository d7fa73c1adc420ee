//! Scaled stereographic projection (first seed, method 7), stored as unorm×2:
//! `enc = xy / (z + 1) / scale · 0.5 + 0.5`. The scale (default 1.7777) maps the
//! directions a camera usually sees into the unit disk; directions more than
//! `2·atan(scale)` from +Z (121.4° at the default) fall outside it and are clamped to the
//! square's edge, so this codec is lossy there by design.

use crate::codecs::core::codec::Codec;
use crate::codecs::core::info::Domain;
use crate::codecs::toolkit::exact::{OnePlusZ, decided, fixed_ratio, float_of, one_if};
use crate::codecs::toolkit::fixed_decode::{BITS, fixed_target, nearest_decoded, odd_square_quarter, search_doc};
use crate::codecs::toolkit::quant::{Quant, Quants};
use crate::model::{Bool, Float, V2, V3};
use crate::codecs::core::info::{Info, OptDesc, OptKind, OptVal, Sizes, FloatForm};
use crate::codecs::core::codec_family::CodecFamily;
use crate::codecs::core::ieee;
use crate::codecs::core::pipeline::codec_functions;
use crate::codecs::core::spec::SpecError;

pub static FAMILY: CodecFamily<StereoScaled> = CodecFamily::new(
    Info {
        name: "stereo_scaled",
        title: "scaled stereographic, unorm×2",
        sizes: Sizes::Total(&[16, 24, 32]),
        domain: Some(Domain::Sphere),
        source: "Pranckevičius, Compact Normal Storage, method 7",
        edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z; directions beyond 2·atan(scale) from +Z clamp to the square's edge; -Z, where the projection is undefined, encodes as (0, 0), the corner nearest it",
        decode_note: "every code decodes to a unit vector (up to rounding)",
        float_form: FloatForm::Continuous {
            seam: "around -Z, beyond 2·atan(scale) from +Z, where the parameters are clamped to the square's edge",
        },
        options: &[SCALE_OPTION, ieee::OPTION],
    },
    |bits| StereoScaled { bits, scale: DEFAULT_SCALE },
    |spec, c| ieee::functions(spec, c, codec_functions),
)
.with_options(|spec, c| StereoScaled { scale: spec.number_of(&SCALE_OPTION), ..c })
.with_validate(|spec| ieee::validate(spec, false))
.with_variants(&["stereo_scaled16:guarantee=ieee"])
.with_helper_doc(|name| (name == "encode_codes").then(|| search_doc(BITS)));

/// Scales whose derived literals (`2s`, `-s`, `0.5/s`) are all normal f32 values, with
/// room to spare; the useful range is around 1 to 3.
const SCALE_OPTION: OptDesc = OptDesc {
    key: "scale",
    help: "the disk radius that maps to the square's edge; directions beyond 2·atan(scale) from +Z clamp",
    kind: OptKind::Number {
        default: DEFAULT_SCALE,
        min: 0.001,
        max: 1000.0,
    },
};

impl StereoScaled {
    /// Scaled stereographic with the seed's default scale (1.7777); see
    /// [`StereoScaled::with_scale`].
    pub fn new(bits: u32) -> Result<StereoScaled, SpecError> {
        FAMILY.codec(bits)
    }
    /// The same codec with another scale, in [0.001, 1000].
    pub fn with_scale(self, scale: f32) -> Result<StereoScaled, SpecError> {
        match SCALE_OPTION.parse_value(&scale.to_string())? {
            OptVal::Number(scale) => Ok(StereoScaled { scale, ..self }),
            OptVal::Choice(_) => unreachable!("scale is a number"),
        }
    }
}

#[derive(Clone, Copy, Debug)]
pub struct StereoScaled {
    pub bits: u32,
    pub scale: f32,
}

pub const DEFAULT_SCALE: f32 = 1.7777;

impl StereoScaled {
    /// The codes of `p` (not -Z; see [`Codec::round_codes`]) at boundaries `c + offset`: `½` rounds to the nearest code,
    /// `1` floors.
    #[inline(always)]
    fn codes<F: Float>(&self, p: &OnePlusZ<F>, offset: f32) -> V2<F> {
        let q = self.quants()[0];
        let m = q.max_code();
        let k = F::c((f64::from(m) * 0.5 / f64::from(self.scale)) as f32);
        p.w.xy().map(#[inline(always)] |x| {
            // The literal last: drivers move a literal factor outwards (NIR's
            // constant reassociation), which would regroup `x·K·b`.
            let t = (x * p.b * k).named("t");
            let estimate = (t / p.a + F::c(m * 0.5)).round();
            decided(q, estimate, #[inline(always)] |c| one_if(t.ge((c - F::c(m * 0.5 - offset)) * p.a)))
        })
    }

    /// The decode of unorm codes `c` in fixed point ([`crate::codecs::toolkit::fixed_decode`]):
    /// with `t = 2c - M` and `K = M / scale`, the direction is `(2K·t, K² - |t|²)` over
    /// `K² + |t|²`, each quarter of them an exact integer plus a constant, each quotient
    /// decided by [`fixed_ratio`].
    #[inline(always)]
    fn fixed_direction<F: Float>(&self, c: V2<F>) -> V3<F> {
        let m = f64::from(self.quants()[0].max_code());
        let k = m / f64::from(self.scale);
        let t = (c * F::c(2.0) - F::c(m as f32)).named("t");
        // |t|² = 4·quarter + 2: the quarters of the numerators and the denominator.
        let quarter = float_of::<F>(odd_square_quarter(t)).named("quarter");
        let den = (quarter + F::c((k * k * 0.25 + 0.5) as f32)).named("den");
        let z = F::c((k * k * 0.25 - 0.5) as f32) - quarter;
        let xy = t * F::c((k * 0.5) as f32);
        V3::from_xy(xy, z).map(#[inline(always)] |n| fixed_ratio(n, den, BITS))
    }
}

impl Codec for StereoScaled {
    type P<F: Float> = V2<F>;
    type C<F: Float> = F::U;
    #[inline]
    fn quants(&self) -> Quants {
        Quants::new(&[Quant::Unorm(self.bits / 2); 2])
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    /// `w.xy·b / a · (0.5/scale) + 0.5` from the same canonical input, length and
    /// `1 + z` as [`Codec::round_codes`] (so the float form and the packed code agree to a
    /// few ULP, and `1 + z` does not cancel near -Z), clamped to the square.
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V2<F> {
        let p = OnePlusZ::of(v);
        // `/ scale * 0.5` as one literal: drivers fold literal multiply chains anyway.
        let enc = (p.w.xy() * p.b / p.a * F::c(0.5 / self.scale) + F::c(0.5)).named("enc");
        // Clamp to the square (NaN from the pole, where a = 0, goes to 0).
        let q = self.quants();
        let enc = enc.map(#[inline(always)] |x| q[0].clamp(x));
        V2::sel_all(p.ok, enc, V2::splat(F::c(0.5)))
    }
    /// The seed's `xy / (z + 1) / scale · 0.5 + 0.5` of the normalized input in plain
    /// arithmetic (the lean tier), clamped to the square (the pole's `0/0` gives 0, the
    /// corner (0, 0) like the default tier); input whose squared length is not a positive
    /// finite `f32` encodes as +Z.
    #[inline(always)]
    fn ieee_params<F: Float>(&self, v: V3<F>) -> V2<F> {
        let len2 = v.length_squared().named("len2");
        let ok = len2.gt(F::c(0.0)).and(len2.le(F::c(f32::MAX)));
        let n = (v / len2.sqrt()).named("n");
        let enc = (n.xy() / (n.z + F::c(1.0)) * F::c(0.5 / self.scale) + F::c(0.5)).named("enc");
        let q = self.quants();
        let enc = enc.map(#[inline(always)] |x| q[0].clamp(x));
        V2::sel_all(ok, enc, V2::splat(F::c(0.5)))
    }
    /// `x / (1 + z)` of the canonical input is `w.x·b / a` ([`crate::codecs::toolkit::exact::one_plus_z`], with the
    /// length from [`crate::codecs::toolkit::exact::root`]), so the code boundary `c + ½` is passed where
    /// `(w.x·b)·K ≥ (c + ½ - M/2)·a` (`K = M·0.5/scale`; `c + ½ - M/2` is an integer):
    /// two products of exact or deterministic values meeting in a comparison, decided
    /// portably ([`crate::codecs::toolkit::exact`]). -Z, the projection's pole, encodes as code
    /// (0, 0), a corner, the nearest codes to it.
    const EXACT_ROUNDING: bool = true;
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V2<F> {
        let m = self.quants()[0].max_code();
        let p = OnePlusZ::of(v);
        let codes = V2::sel_all(p.at_pole(), V2::splat(F::c(0.0)), self.codes(&p, 0.5));
        V2::sel_all(p.ok, codes, V2::splat(F::c((m + 1.0) * 0.5)))
    }
    /// The nearest of the four codes around the exact parameters (floors decided like
    /// [`Codec::round_codes`]' codes, with boundaries at `c + 1`) by the squared distance
    /// of their fixed-point decodes ([`crate::codecs::toolkit::fixed_decode`]); -Z encodes as
    /// (0, 0), like the fast encoder.
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
        let codes = V2::sel_all(p.at_pole(), V2::splat(F::c(0.0)), best);
        V2::sel_all(p.ok, codes, V2::splat(F::c((m + 1.0) * 0.5)))
    }
    /// The seed's `g = 2 / dot(nn, nn)` divides a literal, which drivers turn into a
    /// multiply by an approximate reciprocal; `(p + p) / d` and `(1 - q) / d` are the same
    /// map with both numerators computed, so every target divides exactly. `enc·2s - s` is
    /// written `(enc - 0.5)·2s`: after the packed decoder's `c·(1/M)` a second literal
    /// multiply would be folded into one by the driver.
    #[inline(always)]
    fn direction<F: Float>(&self, enc: V2<F>) -> V3<F> {
        let s = self.scale;
        let p = ((enc - F::c(0.5)) * F::c(2.0 * s)).named("p");
        let q = p.length_squared().named("q");
        let d = (q + F::c(1.0)).named("d");
        V3::from_xy((p + p) / d, (F::c(1.0) - q) / d)
    }
}
