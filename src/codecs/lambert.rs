//! Lambert azimuthal equal-area projection (first seed, method 6), full sphere, stored as
//! unorm×2: `enc = xy / sqrt(8z + 8) + 0.5`. The seed's encoder assumed unit input (its
//! own erratum); this one normalizes first.

use super::codec::{Codec, Domain};
use super::exact::{canonical, decided, fixed_length2, one_if, one_plus_z, root};
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
    /// `w.xy / sqrt(8·l·a / b) + 0.5` from the same canonical input, length and `1 + z`
    /// as [`Codec::round_codes`] (so the float form and the packed code agree to a few
    /// ULP, and `1 + z` does not cancel near -Z). -Z, which the projection maps onto the
    /// whole rim, encodes as (1, 0.5).
    fn params<F: Float>(&self, v: V3<F>) -> V2<F> {
        let (w, ok) = canonical(v);
        let l = root(fixed_length2(w));
        let (a, b) = one_plus_z(w, l);
        let g = ((l * a / b) * F::c(8.0)).sqrt().named("g");
        let enc = w.xy() / g + F::c(0.5);
        let enc = V2::sel_all(a.gt(F::c(0.0)), enc, V2::new(F::c(1.0), F::c(0.5)));
        V2::sel_all(ok, enc, V2::splat(F::c(0.5)))
    }
    /// `x / sqrt(8(1 + z))` of the canonical input is `w.x / sqrt(8·l·a / b)`
    /// ([`one_plus_z`], `l` the length from [`root`]), so the code boundary `c + ½` is
    /// passed where `w.x·M ≥ h·sqrt(8·l·a / b)` (`h = c + ½ - M/2`, an integer): decided
    /// by the signs of `w.x` and `h` and, where they agree, by `(w.x²·b)·(M²/8)` against
    /// `h²·(l·a)`, products of exact or deterministic values meeting in a comparison
    /// ([`crate::codecs::exact`]), each literal factor last (drivers move literal factors
    /// outwards). -Z encodes as (M, (M+1)/2), as before.
    const EXACT_ROUNDING: bool = true;
    fn round_codes<F: Float>(&self, v: V3<F>) -> V2<F> {
        let q = self.quants()[0];
        let m = q.max_code();
        let (w, ok) = canonical(v);
        let l = root(fixed_length2(w));
        let (a, b) = one_plus_z(w, l);
        let la = (l * a).named("la");
        let g = (la / b).sqrt() * F::c(8f32.sqrt() / m);
        let m2 = F::c((f64::from(m) * f64::from(m) / 8.0) as f32);
        let codes = w.xy().map(|x| {
            let big2 = (x * x * b * m2).named("big2");
            let estimate = (x / g + F::c(m * 0.5)).round();
            decided(q, estimate, |c| {
                let h = c - F::c((m - 1.0) * 0.5);
                let h2la = h * h * la;
                let far = F::sel(h.gt(F::c(0.0)), one_if(big2.ge(h2la)), F::c(1.0));
                let near = F::sel(h.lt(F::c(0.0)), one_if(big2.le(h2la)), F::c(0.0));
                F::sel(x.ge(F::c(0.0)), far, near)
            })
        });
        let pole = V2::new(F::c(m), F::c((m + 1.0) * 0.5));
        let codes = V2::sel_all(a.gt(F::c(0.0)), codes, pole);
        let centre = F::c((m + 1.0) * 0.5);
        V2::sel_all(ok, codes, V2::splat(centre))
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
