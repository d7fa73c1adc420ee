//! Hemi-oct (survey Listing 6, Table 3): the +Z half of the octahedron, rotated 45° and
//! scaled so that it fills the whole square.

use super::codec::{Codec, Domain, above_horizon};
use super::exact::{canonical, snorm_ratio};
use super::quant::{Quant, Quants};
use crate::model::{Bool, Float, V2, V3};
use super::family::{Family, Info, Sizes};
use super::functions::{Emitted, codec_functions};
use super::spec::{Spec, SpecError};

pub static FAMILY: HemiOctFamily = HemiOctFamily;

pub struct HemiOctFamily;

static INFO: Info = Info {
    name: "hemioct",
    title: "hemi-octahedral, snorm×2",
    sizes: Sizes::Total(&[16, 24, 32]),
    domain: Some(Domain::Hemisphere),
    precise: true,
    source: "Cigolle et al. 2014, Listing 6 and Table 3",
    edge_policy: "input below the horizon is projected onto it (z ← max(z, +0)); zero, NaN and infinite input encode as +Z",
    decode_note: "every code decodes to a unit vector with z ≥ 0",
    options: &[],
};

impl Family for HemiOctFamily {
    fn info(&self) -> &'static Info {
        &INFO
    }
    fn emitted(&self, spec: &Spec) -> Emitted {
        codec_functions(spec, HemiOct { bits: spec.bits() })
    }
}

impl HemiOct {
    /// The codec with the given total bit budget; an invalid size is an error listing
    /// the allowed ones.
    pub fn new(bits: u32) -> Result<HemiOct, SpecError> {
        Ok(HemiOct {
            bits: INFO.check_bits(bits)?,
        })
    }
}

#[derive(Clone, Copy, Debug)]
pub struct HemiOct {
    pub bits: u32,
}

/// Listing 6's parameters as ratios `n / l1` of correctly rounded sums of the canonical
/// input ([`canonical`]), projected onto the hemisphere: `n = (x + y, x - y)` and
/// `l1 = |x| + |y| + max(z, 0)`. The L1 projection does not depend on length, so no
/// normalization is needed. `ok` is false for zero, NaN and infinite input and for `-Z`,
/// which projects to zero; all of them encode as +Z.
fn hemi_ratios<F: Float>(v: V3<F>) -> (V2<F>, F, F::B) {
    let (w, ok) = canonical(v);
    let a = above_horizon(w).abs();
    let l1 = (a.x + a.y + a.z).named("l1");
    let n = V2::new(w.x + w.y, w.x - w.y).named("n");
    (n, l1, ok.and(l1.gt(F::c(0.0))))
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
    /// The survey's Listing 6 on the input projected onto the +Z hemisphere: `(x ± y) /
    /// (|x| + |y| + z)` with `z ← max(z, 0)`, as [`hemi_ratios`] gives them.
    fn params<F: Float>(&self, v: V3<F>) -> V2<F> {
        let (n, l1, ok) = hemi_ratios(v);
        V2::sel_all(ok, n / l1, V2::splat(F::c(0.0)))
    }
    fn direction<F: Float>(&self, e: V2<F>) -> V3<F> {
        let t = (V2::new(e.x + e.y, e.x - e.y) * F::c(0.5)).named("t");
        let a = t.abs();
        let v = V3::from_xy(t, F::c(1.0) - a.x - a.y).named("v");
        v / v.length_squared().sqrt()
    }
    /// Listing 6 decided portably ([`crate::codecs::exact`]) from the same ratios.
    const EXACT_ROUNDING: bool = true;
    fn round_codes<F: Float>(&self, v: V3<F>) -> V2<F> {
        let q = self.quants()[0];
        let (n, l1, ok) = hemi_ratios(v);
        let c = n.map(|x| snorm_ratio(q, x, l1));
        V2::sel_all(ok, c, V2::splat(F::c(0.0)))
    }
}
