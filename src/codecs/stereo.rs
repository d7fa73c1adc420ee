//! Scaled stereographic projection (first seed, method 7), stored as unorm×2:
//! `enc = xy / (z + 1) / scale · 0.5 + 0.5`. The scale (default 1.7777) maps the
//! directions a camera usually sees into the unit disk; directions more than
//! `2·atan(scale)` from +Z (121.4° at the default) fall outside it and are clamped to the
//! square's edge, so this codec is lossy there by design.

use super::codec::{Codec, Domain};
use super::quant::Quant;
use crate::model::{Float, V2, V3};

#[derive(Clone, Copy, Debug)]
pub struct StereoScaled {
    pub bits: u32,
    pub scale: f32,
}

pub const DEFAULT_SCALE: f32 = 1.7777;

impl Codec for StereoScaled {
    type P<F: Float> = V2<F>;
    type C<F: Float> = F::U;
    fn quants(&self) -> Vec<Quant> {
        vec![Quant::Unorm(self.bits / 2); 2]
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    fn to_params<F: Float>(&self, v: V3<F>) -> V2<F> {
        let u = self.target(v);
        let d = (u.z + F::c(1.0)).named("d");
        let enc = (u.xy() / d * F::c(1.0 / self.scale)).named("proj");
        let enc = enc * F::c(0.5) + F::c(0.5);
        // Clamp to the square (NaN from the pole, where d = 0, goes to 0).
        let enc = V2::sel(enc.ge(V2::splat(F::c(0.0))), enc, V2::splat(F::c(0.0)));
        V2::sel(enc.le(V2::splat(F::c(1.0))), enc, V2::splat(F::c(1.0)))
    }
    fn from_params<F: Float>(&self, enc: V2<F>) -> V3<F> {
        let s = self.scale;
        let nn = V3::from_xy(enc * F::c(2.0 * s) + F::c(-s), F::c(1.0)).named("nn");
        let g = (F::c(2.0) / nn.length_squared()).named("g");
        V3::from_xy(nn.xy() * g, g - F::c(1.0))
    }
}
