//! Spherical coordinates (survey §2): θ ∈ [0, π] and φ ∈ [-π, π] stored as snorm×2,
//! `(θ/π·2 - 1, φ/π)`. Trigonometry comes from [`crate::codecs::toolkit::trig`].
//! θ is computed as `atan2(|xy|, z)` rather than `acos(z)`: same angle, but well
//! conditioned near the poles, where acos loses half its digits.

use crate::model::num::helper;
use crate::codecs::core::codec::Codec;
use crate::codecs::core::info::Domain;
use crate::codecs::toolkit::exact::{canonical_or_z, fixed_length2, fixed_length2_xy, root, root_of};
use crate::codecs::toolkit::fixed_decode::{fixed_target, nearest_decoded, search_doc};
use crate::codecs::toolkit::fixed_trig::{self, FINE, ONE};
use crate::codecs::toolkit::quant::{Quant, Quants};
use crate::codecs::toolkit::trig::{atan2_pi, sincos_pi};
use crate::model::{Float, V2, V3};
use crate::codecs::core::info::{Info, Sizes, FloatForm, seam};
use crate::codecs::core::codec_family::CodecFamily;
use crate::codecs::core::pipeline::codec_functions;
use crate::codecs::core::spec::SpecError;

pub static FAMILY: CodecFamily<Spherical> = CodecFamily::new(
    Info {
        name: "spherical",
        title: "spherical coordinates (θ, φ), snorm×2",
        sizes: Sizes::Total(&[16, 20, 22, 24, 32]),
        domain: Some(Domain::Sphere),
        source: "Cigolle et al. 2014 §2",
        edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z",
        decode_note: "decodes are unit length to within the trig approximations' error (about 2.5e-7)",
        float_form: FloatForm::Continuous { seam: seam::AZIMUTH_WRAP },
        options: &[],
    },
    |bits| Spherical { bits },
    codec_functions,
)
.with_helper_doc(|name| (name == "encode_codes").then(|| search_doc(fixed_trig::BITS)));

impl Spherical {
    /// The codec with the given total bit budget; an invalid size is an error listing
    /// the allowed ones.
    pub fn new(bits: u32) -> Result<Spherical, SpecError> {
        FAMILY.codec(bits)
    }
}

#[derive(Clone, Copy, Debug)]
pub struct Spherical {
    pub bits: u32,
}

impl Codec for Spherical {
    type P<F: Float> = V2<F>;
    type C<F: Float> = F::U;
    #[inline]
    fn quants(&self) -> Quants {
        Quants::new(&[Quant::Snorm(self.bits / 2); 2])
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V2<F> {
        let (theta, phi) = float_angles(self.target(v));
        V2::new(theta * F::c(2.0) - F::c(1.0), phi)
    }
    #[inline(always)]
    fn direction<F: Float>(&self, p: V2<F>) -> V3<F> {
        let theta = ((p.x + F::c(1.0)) * F::c(0.5)).named("theta");
        let st = helper!(sincos_pi(theta)).named("st");
        let sp = helper!(sincos_pi(p.y)).named("sp");
        V3::new(sp.y * st.x, sp.x * st.x, st.y)
    }
    /// `θ` and `φ` from [`fixed_trig::atan2_pi`] of the canonical input (and its `ρ`
    /// from [`root_of`]), in units of `2^-23` half turns: functions of the input alone,
    /// each code then one product rounded. Zero, NaN and infinite input give +Z's codes.
    const EXACT_ROUNDING: bool = true;
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V2<F> {
        let (theta, phi) = fixed_angles(canonical_or_z(v).0);
        let k = F::c((f64::from(self.quants()[0].max_code()) / ONE) as f32);
        V2::new(theta, phi).map(#[inline(always)] |a| (a * k).round())
    }
    /// The nearest of the four codes around the exact parameters by the squared distance
    /// of their fixed-point decodes ([`crate::codecs::toolkit::fixed_decode`], with
    /// [`fixed_trig::sincos_pi`]), on the trigonometry's grid of `2^-23`: candidates next
    /// to the target are far closer than `2^24` units, so their squared distances stay
    /// exact.
    const EXACT_SEARCH: bool = true;
    #[inline(always)]
    fn precise_codes<F: Float>(&self, v: V3<F>) -> V2<F> {
        let q = self.quants()[0];
        let m = q.max_code();
        let (w, _) = canonical_or_z(v);
        let (theta, phi) = fixed_angles(w);
        let k = F::c((f64::from(m) / ONE) as f32);
        let base = V2::new(theta, phi).map(#[inline(always)] |a| (a * k).floor()).named("base");
        let target = fixed_target(w, root(fixed_length2(w)), fixed_trig::BITS);
        nearest_decoded([q; 2], base, target, #[inline(always)] |c| {
            let theta = (c.x + F::c(m)) * F::c((FINE * 0.5 / f64::from(m)) as f32);
            let phi = c.y * F::c((FINE / f64::from(m)) as f32);
            let st = fixed_trig::sincos_pi(theta.round());
            let sp = fixed_trig::sincos_pi(phi.round());
            // From units of 2^-24 to the target's 2^-23.
            let scale = F::c((0.5 / FINE) as f32);
            V3::new(
                (sp.y * st.x * scale).round(),
                (sp.x * st.x * scale).round(),
                (st.y * F::c(0.5)).round(),
            )
        })
    }
}

/// The polar angle `θ = atan2(|xy|, z)` and the azimuth `φ = atan2(y, x)` of a unit
/// `u`, in half turns, from the model's float trigonometry: the float forms' angles.
#[inline(always)]
pub(crate) fn float_angles<F: Float>(u: V3<F>) -> (F, F) {
    let rho = u.xy().length_squared().sqrt().named("rho");
    let theta = helper!(atan2_pi(rho, u.z)).named("theta");
    let phi = helper!(atan2_pi(u.y, u.x)).named("phi");
    (theta, phi)
}

/// `(2θ - 1, φ)` of a canonical `w` in units of `2^-23` half turns, decided in fixed
/// point.
#[inline(always)]
pub(crate) fn fixed_angles<F: Float>(w: V3<F>) -> (F, F) {
    let rho2 = fixed_length2_xy(w);
    let has_rho = rho2.gt(F::c(0.0));
    // Any positive stand-in for zero: its root is discarded.
    let rho = F::sel(has_rho, root_of(F::sel(has_rho, rho2, F::c(1.0))), F::c(0.0));
    let theta = fixed_trig::atan2_pi(rho.named("rho"), w.z);
    let phi = fixed_trig::atan2_pi(w.y, w.x);
    let theta = (theta * F::c(2.0) - F::c(ONE as f32)).named("theta");
    (theta, phi.named("phi"))
}
