//! Hemi-oct (survey Listing 6, Table 3): the +Z half of the octahedron, rotated 45° and
//! scaled so that it fills the whole square.

use crate::codecs::core::codec::{Codec, above_horizon};
use crate::codecs::core::info::Domain;
use crate::codecs::toolkit::exact::{canonical, floor_ratio_code, ratio_code_within};
use crate::codecs::toolkit::lattice::{Closeness, fixed, nearest, search_doc};
use crate::codecs::toolkit::quant::{Quant, Quants, signed_code, unsigned_code, zero_code};
use crate::codecs::octahedral::oct::fit_l1;
use crate::model::{Bool, Float, V2, V3};
use crate::codecs::core::info::{Info, Sizes, FloatForm};
use crate::codecs::core::codec_family::CodecFamily;
use crate::codecs::core::ieee;
use crate::codecs::core::texel::{self, TexelCodec, texel_variants};
use crate::codecs::core::spec::SpecError;

pub static FAMILY: CodecFamily<HemiOct> = CodecFamily::new(
    Info {
        name: "hemioct",
        title: "hemi-octahedral, snorm×2",
        sizes: Sizes::Total(&[16, 24, 32]),
        domain: Some(Domain::Hemisphere),
        source: "Cigolle et al. 2014, Listing 6 and Table 3",
        edge_policy: "input below the horizon is projected onto it (z ← max(z, +0)); zero, NaN and infinite input and -Z encode as +Z (the packed encoders also where x and y are below 2^-40 of |z|, within about 2^-39.5 rad of -Z, where encode_float already sees the horizon)",
        decode_note: "every code decodes to a unit vector with z ≥ 0",
        float_form: FloatForm::Continuous { seam: "the rim of the hemisphere, where the square's edges meet" },
        options: &[texel::OPTION, ieee::OPTION],
    },
    |bits| HemiOct { bits },
    |spec, c| ieee::functions(spec, c, texel::functions),
)
.with_validate(|spec| {
    texel::validate(spec)?;
    ieee::validate(spec, texel::layout(spec).is_some())
})
.with_variants(texel_variants!("hemioct", "hemioct16:guarantee=ieee"))
.with_helper_doc(|name| (name == "encode_codes").then(|| search_doc("the input's signs")));

impl HemiOct {
    /// The codec with the given total bit budget; an invalid size is an error listing
    /// the allowed ones.
    pub fn new(bits: u32) -> Result<HemiOct, SpecError> {
        FAMILY.codec(bits)
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
#[inline(always)]
fn hemi_ratios<F: Float>(v: V3<F>) -> (V2<F>, F, F::B) {
    let (w, ok) = canonical(v);
    let a = above_horizon(w).abs();
    let l1 = (a.x + a.y + a.z).named("l1");
    let n = V2::new(w.x + w.y, w.x - w.y).named("n");
    (n, l1, ok.and(l1.gt(F::c(0.0))))
}

/// The hemi-octahedral codes nearest the input, decided portably
/// ([`crate::codecs::toolkit::lattice`]). In the first octant (`a = |x|`, `b = |y|`,
/// `c = max(z, 0)`) codes `(S, T)` decode to the lattice direction
/// `(S + T, S - T, 2M - 2S)`; the candidates are the four codes around
/// `floor(M·(a + b, a - b) / l1)`, each reflected into the first octant (`(-T, -S)` where
/// `S + T < 0`, `(T, S)` where `S < T`: the reflection is nearer, and is itself a
/// candidate) and dropped past the equator (`S > M`). The nearest (the first on ties)
/// then takes the input's signs: a negative `x` maps `(S, T)` to `(-T, -S)`, a negative
/// `y` to `(T, S)`. Zero, NaN, infinite input and `-Z` give `(0, 0)`. In a unorm field
/// (a texel channel) the same holds of the codes' signed values `2c - M`
/// ([`signed_code`]), and invalid input gives `(M + 1)/2` ([`zero_code`]).
#[inline(always)]
fn hemioct_nearest_codes<F: Float>(q: Quant, v: V3<F>) -> V2<F> {
    let m = q.max_code();
    let mf = F::c(m);
    let (w, ok) = canonical(v);
    let a = above_horizon(w).abs();
    let sum = (a.x + a.y + a.z).named("sum");
    let good = ok.and(sum.gt(F::c(0.0)));
    // Invalid input searches around +Z instead, so that every conversion to an integer
    // below stays in range (a NaN or negative float has no defined u32 in C).
    let a = V3::sel_all(good, a, V3::new(F::c(0.0), F::c(0.0), F::c(2.0))).named("a");
    let l1 = F::sel(good, sum, F::c(2.0)).named("l1");
    let s0 = floor_ratio_code(q, a.x + a.y, l1).named("s0");
    let t0 = floor_ratio_code(q, a.x - a.y, l1).named("t0");
    let afix = fixed(a);
    let best = nearest(s0, t0, #[inline(always)] |s, t| {
        let (s, t) = (signed_code(q, s), signed_code(q, t));
        let r = V2::sel_all((s + t).lt(F::c(0.0)), V2::new(-t, -s), V2::new(s, t));
        let r = V2::sel_all(r.x.lt(r.y), r.yx(), r).named("cand");
        let z = (F::c(2.0 * m) - r.x - r.x).at_least(F::c(0.0));
        let d = V3::new((r.x + r.y).to_u(), (r.x - r.y).to_u(), z.to_u());
        let c = Closeness::of(afix, d, 2.0 * m);
        (r, r.x.le(mf), c)
    });
    let zero = F::c(0.0);
    let st = V2::sel_all(w.x.lt(zero), -best.yx(), best);
    let st = V2::sel_all(w.y.lt(zero), st.yx(), st).map(#[inline(always)] |x| unsigned_code(q, x));
    V2::sel_all(good, st, V2::splat(F::c(zero_code(q))))
}

impl Codec for HemiOct {
    type P<F: Float> = V2<F>;
    type C<F: Float> = F::U;
    #[inline]
    fn quants(&self) -> Quants {
        Quants::new(&[Quant::Snorm(self.bits / 2); 2])
    }
    fn domain(&self) -> Domain {
        Domain::Hemisphere
    }
    /// The survey's Listing 6 on the input projected onto the +Z hemisphere: `(x ± y) /
    /// (|x| + |y| + z)` with a negative `z` replaced by 0 (a NaN kept, so that it fails
    /// the check below). The L1 projection needs no unit length, so the projected input is
    /// only brought into range by oct's power-of-two [`fit_l1`] (exact), not normalized,
    /// in 20 instructions instead of the 32 of `hemi_ratios`' canonical form; fitting the
    /// projection, not the input, keeps a denormal hemisphere L1 norm (`(1e-45, 1e-45,
    /// -1)`) from reaching the division. `x/l1 ± y/l1` rather than `(x ± y)/l1`: a driver
    /// may factor the scale out of `x·¼ + y·¼`, and `x + y` overflows for huge input;
    /// each quotient is at most 1. Zero, NaN and infinite input and `-Z` fail
    /// `0 < l1 ≤ MAX` or `z ≥ -MAX` and give `(0, 0)`.
    ///
    /// Within about `2^-39.5` rad of `-Z` this form and the packed encoders part: `(1e-13,
    /// 0, -1)` projects onto the horizon at `+X` here, while the packed encoders' canonical
    /// form zeroes components below `2^-40` of the largest, sees `-Z` and writes `+Z`'s code.
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V2<F> {
        let h = V3::new(v.x, v.y, F::sel(v.z.lt(F::c(0.0)), F::c(0.0), v.z));
        let w = fit_l1(h).named("w");
        let a = w.abs();
        let l1 = (a.x + a.y + a.z).named("l1");
        let p = (w.xy() / l1).named("p");
        let finite_z = v.z.ge(F::c(-f32::MAX));
        let ok = l1.gt(F::c(0.0)).and(l1.le(F::c(f32::MAX))).and(finite_z);
        V2::sel_all(ok, V2::new(p.x + p.y, p.x - p.y), V2::splat(F::c(0.0)))
    }
    /// Listing 6 in plain arithmetic (the lean tier): the same projection onto the
    /// hemisphere and checks, without [`fit_l1`]'s scaling.
    #[inline(always)]
    fn ieee_params<F: Float>(&self, v: V3<F>) -> V2<F> {
        let h = V3::new(v.x, v.y, F::sel(v.z.lt(F::c(0.0)), F::c(0.0), v.z));
        let a = h.abs();
        let l1 = (a.x + a.y + a.z).named("l1");
        let p = (h.xy() / l1).named("p");
        let finite_z = v.z.ge(F::c(-f32::MAX));
        let ok = l1.gt(F::c(0.0)).and(l1.le(F::c(f32::MAX))).and(finite_z);
        V2::sel_all(ok, V2::new(p.x + p.y, p.x - p.y), V2::splat(F::c(0.0)))
    }
    #[inline(always)]
    fn direction<F: Float>(&self, e: V2<F>) -> V3<F> {
        let t = (V2::new(e.x + e.y, e.x - e.y) * F::c(0.5)).named("t");
        let a = t.abs();
        let v = V3::from_xy(t, F::c(1.0) - a.x - a.y).named("v");
        v / v.length_squared().sqrt()
    }
    /// Listing 6 decided portably ([`crate::codecs::toolkit::exact`]) from [`hemi_ratios`]' exact
    /// sums of the canonical input, not from `params`' quotients.
    const EXACT_ROUNDING: bool = true;
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V2<F> {
        self.round_in(self.quants()[0], v)
    }
    const EXACT_SEARCH: bool = true;
    #[inline(always)]
    fn precise_codes<F: Float>(&self, v: V3<F>) -> V2<F> {
        self.precise_in(self.quants()[0], v)
    }
}

impl TexelCodec for HemiOct {
    #[inline(always)]
    fn params2<F: Float>(&self, v: V3<F>) -> V2<F> {
        self.params(v)
    }
    #[inline(always)]
    fn direction2<F: Float>(&self, p: V2<F>) -> V3<F> {
        self.direction(p)
    }
    #[inline(always)]
    fn round_in<F: Float>(&self, q: Quant, v: V3<F>) -> V2<F> {
        let (n, l1, ok) = hemi_ratios(v);
        let c = n.map(#[inline(always)] |x| ratio_code_within(q, x, l1));
        V2::sel_all(ok, c, V2::splat(F::c(zero_code(q))))
    }
    #[inline(always)]
    fn precise_in<F: Float>(&self, q: Quant, v: V3<F>) -> V2<F> {
        hemioct_nearest_codes(q, v)
    }
}
