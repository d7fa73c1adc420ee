//! Lambert azimuthal equal-area projection (first seed, method 6), full sphere, stored as
//! unorm×2: `enc = xy / sqrt(8z + 8) + 0.5`. The seed's encoder assumed unit input (its
//! own erratum); this one normalizes first.

use super::codec::{Codec, Domain};
use super::quant::{Quant, Quants};
use crate::model::{Float, V2, V3};
use super::family::{Family, Info, Sizes};
use super::functions::{Emitted, codec_functions};
use super::spec::{Spec, SpecError};

pub static FAMILY: LambertFamily = LambertFamily;

pub struct LambertFamily;

static INFO: Info = Info {
    name: "lambert",
    title: "Lambert azimuthal equal-area, unorm×2",
    sizes: Sizes::Total(&[16, 24, 32]),
    domain: Some(Domain::Sphere),
    precise: true,
    source: "Pranckevičius, Compact Normal Storage, method 6",
    edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z; -Z encodes as (1, 0.5)",
    decode_note: "every code decodes to a unit vector; codes outside the disk decode as -Z",
    options: &[],
};

impl Family for LambertFamily {
    fn info(&self) -> &'static Info {
        &INFO
    }
    fn emitted(&self, spec: &Spec) -> Emitted {
        codec_functions(spec, Lambert { bits: spec.bits() })
    }
}

impl Lambert {
    /// The codec with the given total bit budget; an invalid size is an error listing
    /// the allowed ones.
    pub fn new(bits: u32) -> Result<Lambert, SpecError> {
        Ok(Lambert {
            bits: INFO.check_bits(bits)?,
        })
    }
}

#[derive(Clone, Copy, Debug)]
pub struct Lambert {
    pub bits: u32,
}

impl Codec for Lambert {
    type P<F: Float> = V2<F>;
    type C<F: Float> = F::U;
    fn quants(&self) -> Quants {
        Quants::new(&[Quant::Unorm(self.bits / 2); 2])
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    /// -Z, which the projection maps onto the whole rim, encodes as (1, 0.5).
    fn params<F: Float>(&self, v: V3<F>) -> V2<F> {
        let u = self.target(v);
        let f = (u.z * F::c(8.0) + F::c(8.0)).sqrt().named("f");
        let enc = u.xy() / f + F::c(0.5);
        V2::sel_all(f.gt(F::c(0.0)), enc, V2::new(F::c(1.0), F::c(0.5)))
    }
    /// Codes outside the disk (the square's corners) decode as -Z; every decode is unit
    /// length up to rounding.
    fn direction<F: Float>(&self, enc: V2<F>) -> V3<F> {
        let fenc = (enc * F::c(4.0) - F::c(2.0)).named("fenc");
        let f = fenc.length_squared();
        let f = f.at_most(F::c(4.0)).named("f");
        let g = (F::c(1.0) - f * F::c(0.25)).sqrt().named("g");
        V3::from_xy(fenc * g, F::c(1.0) - f * F::c(0.5))
    }
}
