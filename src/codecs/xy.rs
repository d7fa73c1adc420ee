//! X and Y stored, Z reconstructed (first seed method 1, survey XYOnly, fourth seed):
//! `z = sqrt(1 - saturate(x² + y²))`, +Z hemisphere, snorm×2.

use super::codec::{Codec, Domain};
use super::quant::{Quant, Quants};
use crate::model::{Float, V2, V3};

#[derive(Clone, Copy, Debug)]
pub struct Xy {
    pub bits: u32,
}

impl Codec for Xy {
    type P<F: Float> = V2<F>;
    type C<F: Float> = F::U;
    fn quants(&self) -> Quants {
        Quants::new(&[Quant::Snorm(self.bits / 2); 2])
    }
    fn domain(&self) -> Domain {
        Domain::Hemisphere
    }
    fn params<F: Float>(&self, v: V3<F>) -> V2<F> {
        self.target(v).xy()
    }
    /// Codes outside the unit disk decode to `(x, y, 0)`, which is longer than 1.
    fn direction<F: Float>(&self, p: V2<F>) -> V3<F> {
        let d = p.length_squared();
        let d = F::sel(d.lt(F::c(1.0)), d, F::c(1.0)).named("d");
        V3::from_xy(p, (F::c(1.0) - d).sqrt())
    }
}
