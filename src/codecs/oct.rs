//! Octahedral encoding (survey §3.1–3.3, Meyer et al. 2010): project onto the octahedron
//! with the L1 norm, unfold the lower half over the diagonals, store snorm×2.

use super::codec::{Codec, Domain, sign_not_zero};
use super::quant::{Quant, Quants};
use crate::model::{Bool, Float, V2, V3};

#[derive(Clone, Copy, Debug)]
pub struct Oct {
    pub bits: u32,
}

/// Folds a point of the square across the diagonals: `(1 - |p.yx|) · sign_not_zero(p)`.
fn fold<F: Float>(p: V2<F>) -> V2<F> {
    (V2::splat(F::c(1.0)) - p.yx().abs()) * sign_not_zero(p)
}

/// Sphere → square. Folds on encode when `z <= 0`. Input need not be unit length: when
/// the L1 norm overflows, the input is first scaled by 1/4 (exact at that magnitude), so
/// only zero, NaN and infinite input, whose L1 norm is not a positive finite number,
/// encode as +Z. For every other input the scale is 1 and the arithmetic is the survey's.
pub fn oct_params<F: Float>(v: V3<F>) -> V2<F> {
    let w = fit_l1(v).named("w");
    let a = w.abs();
    let l1 = (a.x + a.y + a.z).named("l1");
    let ok = l1.gt(F::c(0.0)).and(l1.le(F::c(f32::MAX)));
    let p = (w.xy() / l1).named("p");
    let e = V2::sel_all(w.z.le(F::c(0.0)), fold(p), p);
    V2::sel_all(ok, e, V2::splat(F::c(0.0)))
}

/// `v`, or `v/4` when its L1 norm overflows f32 (then every component that matters is far
/// above the denormal range, so the scaling is exact where it counts).
pub fn fit_l1<F: Float>(v: V3<F>) -> V3<F> {
    let a = v.abs();
    let fits = (a.x + a.y + a.z).le(F::c(f32::MAX));
    v * F::sel(fits, F::c(1.0), F::c(0.25))
}

/// Square → unit vector. Unfolds when `z < 0`; the result is normalized as `v / sqrt(v·v)`.
pub fn oct_direction<F: Float>(e: V2<F>) -> V3<F> {
    let a = e.abs();
    let z = (F::c(1.0) - a.x - a.y).named("z");
    let xy = V2::sel_all(z.lt(F::c(0.0)), fold(e), e);
    let v = V3::from_xy(xy, z).named("v");
    v / v.length_squared().sqrt()
}

impl Codec for Oct {
    type P<F: Float> = V2<F>;
    type C<F: Float> = F::U;
    fn quants(&self) -> Quants {
        Quants::new(&[Quant::Snorm(self.bits / 2); 2])
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    fn params<F: Float>(&self, v: V3<F>) -> V2<F> {
        oct_params(v)
    }
    fn direction<F: Float>(&self, p: V2<F>) -> V3<F> {
        oct_direction(p)
    }
}
