//! Spherical coordinates (survey §2): θ ∈ [0, π] and φ ∈ [-π, π] stored as snorm×2,
//! `(θ/π·2 - 1, φ/π)`. Trigonometry comes from [`super::trig`].
//! θ is computed as `atan2(|xy|, z)` rather than `acos(z)`: same angle, but well
//! conditioned near the poles, where acos loses half its digits.

use super::codec::{Codec, Domain};
use super::quant::{Quant, Quants};
use super::trig::{atan2_pi, sincos_pi};
use crate::model::{Float, V2, V3};
use super::family::{Family, Info, Sizes};
use super::functions::{Emitted, codec_functions};
use super::spec::{Spec, SpecError};

pub static FAMILY: SphericalFamily = SphericalFamily;

pub struct SphericalFamily;

static INFO: Info = Info {
    name: "spherical",
    title: "spherical coordinates (θ, φ), snorm×2",
    sizes: Sizes::Total(&[16, 24, 32]),
    domain: Some(Domain::Sphere),
    precise: true,
    source: "Cigolle et al. 2014 §2",
    edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z",
    decode_note: "decodes are unit length to within the trig approximations' error (about 2.5e-7)",
    options: &[],
};

impl Family for SphericalFamily {
    fn info(&self) -> &'static Info {
        &INFO
    }
    fn emitted(&self, spec: &Spec) -> Emitted {
        codec_functions(spec, Spherical { bits: spec.bits() })
    }
}

impl Spherical {
    /// The codec with the given total bit budget; an invalid size is an error listing
    /// the allowed ones.
    pub fn new(bits: u32) -> Result<Spherical, SpecError> {
        Ok(Spherical {
            bits: INFO.check_bits(bits)?,
        })
    }
}

#[derive(Clone, Copy, Debug)]
pub struct Spherical {
    pub bits: u32,
}

impl Codec for Spherical {
    type P<F: Float> = V2<F>;
    type C<F: Float> = F::U;
    fn quants(&self) -> Quants {
        Quants::new(&[Quant::Snorm(self.bits / 2); 2])
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    fn params<F: Float>(&self, v: V3<F>) -> V2<F> {
        let u = self.target(v);
        let rho = u.xy().length_squared().sqrt().named("rho");
        let theta = F::call("atan2_pi", (rho, u.z), |(y, x)| atan2_pi(y, x)).named("theta");
        let phi = F::call("atan2_pi", (u.y, u.x), |(y, x)| atan2_pi(y, x)).named("phi");
        V2::new(theta * F::c(2.0) - F::c(1.0), phi)
    }
    fn direction<F: Float>(&self, p: V2<F>) -> V3<F> {
        let theta = ((p.x + F::c(1.0)) * F::c(0.5)).named("theta");
        let st = F::call("sincos_pi", theta, sincos_pi).named("st");
        let sp = F::call("sincos_pi", p.y, sincos_pi).named("sp");
        V3::new(sp.y * st.x, sp.x * st.x, st.y)
    }
}
