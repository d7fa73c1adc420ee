//! Hemi-oct (survey Listing 6, Table 3): the +Z half of the octahedron, rotated 45° and
//! scaled so that it fills the whole square.

use super::codec::{Codec, Domain};
use super::quant::{Quant, Quants};
use crate::model::{Bool, Float, V2, V3};

#[derive(Clone, Copy, Debug)]
pub struct HemiOct {
    pub bits: u32,
}

impl Codec for HemiOct {
    type P<F: Float> = V2<F>;
    type C<F: Float> = F::U;
    fn quants(&self) -> Quants {
        Quants::new(&[Quant::Snorm(self.bits / 2); 2])
    }
    fn domain(&self) -> Domain {
        Domain::Hemisphere
    }
    /// Input below the horizon is projected onto it (`z ← max(z, +0)`); zero, NaN or
    /// infinite input encodes as +Z.
    fn params<F: Float>(&self, v: V3<F>) -> V2<F> {
        let z = F::sel(v.z.gt(F::c(0.0)), v.z, F::c(0.0));
        let l1 = (v.x.abs() + v.y.abs() + z).named("l1");
        let ok = l1.gt(F::c(0.0)).and(l1.le(F::c(f32::MAX)));
        let p = (v.xy() / l1).named("p");
        let e = V2::new(p.x + p.y, p.x - p.y);
        V2::sel_all(ok, e, V2::splat(F::c(0.0)))
    }
    fn direction<F: Float>(&self, e: V2<F>) -> V3<F> {
        let t = (V2::new(e.x + e.y, e.x - e.y) * F::c(0.5)).named("t");
        let a = t.abs();
        let v = V3::from_xy(t, F::c(1.0) - a.x - a.y).named("v");
        v / v.length_squared().sqrt()
    }
}
