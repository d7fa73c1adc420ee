//! Lambert azimuthal equal-area projection (first seed, method 6), full sphere, stored as
//! unorm×2: `enc = xy / sqrt(8z + 8) + 0.5`. The seed's encoder assumed unit input (its
//! own erratum); this one normalizes first.

use super::codec::{Codec, Domain};
use super::quant::{Quant, Quants};
use crate::model::{Float, V2, V3};

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
        let f = F::sel(f.le(F::c(4.0)), f, F::c(4.0)).named("f");
        let g = (F::c(1.0) - f * F::c(0.25)).sqrt().named("g");
        V3::from_xy(fenc * g, F::c(1.0) - f * F::c(0.5))
    }
}
