//! snorm×3: the vector's components stored directly (survey; the first seed's baseline).
//! Most codes are not unit length, so decode re-normalizes.
//!
//! The precise encoder is Best Fit Normals (Kaplanyan 2010, survey §2.2): since the
//! decoder normalizes, any non-unit code stands for a direction, and the one whose
//! direction is nearest the input is searched for. With `n` scaled so that its largest
//! component is `t`, the candidate for scale `t` rounds the others. The search tries
//! scales above `M/2` only, the top [`BFN_SCALES`] of them (all of them up to snorm8): a
//! code whose largest component is below `M/2` has the same direction at twice its
//! scale, though that double is one of the integer vectors around the ray there, not
//! necessarily the rounded one. That the smaller scales add nothing is therefore a
//! measurement, not a proof: at snorm8 no integer vector around the ray at any scale
//! (`1..=127`) was nearer over the sampled inputs of `tests/families/snorm3.rs`; on snorm5's coarse
//! grid the nearest is not always a rounded one.

use crate::model::num::helper;
use crate::codecs::core::codec::{Codec, unit_or_z};
use crate::codecs::core::info::Domain;
use crate::codecs::toolkit::exact::{
    canonical, canonical_or_z, fixed_length2, fixed_ratio, length2, root, root_of,
    snorm_sqrt_ratio, sum_of_squares,
};
use crate::codecs::toolkit::fixed_decode::{BITS, ONE, distance, fixed_target};
use crate::codecs::toolkit::quant::{Code, Quant, Quants};
use crate::model::{Float, V2, V3};
use std::marker::PhantomData;
use crate::codecs::core::info::{Info, Sizes, FloatForm, seam};
use crate::codecs::core::spec::Family;
use crate::codecs::functions::function::Emitted;
use crate::codecs::core::pipeline::codec_functions;
use crate::codecs::core::spec::{Spec, SpecError, Tracing};

pub static FAMILY: Snorm3Family = Snorm3Family;

pub struct Snorm3Family;

static INFO: Info = Info {
    name: "snorm3",
    title: "components as snorm×3",
    sizes: Sizes::PerComponent {
        prefix: "snorm",
        count: 3,
        per: &[5, 8, 10, 16],
    },
    domain: Some(Domain::Sphere),
    source: "Cigolle et al. 2014 §2; Pranckevičius, baseline; precise: Best Fit Normals (Kaplanyan 2010)",
    edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z",
    decode_note: "decode re-normalizes; the all-zero code decodes as +Z",
    float_form: FloatForm::Continuous { seam: seam::NONE_PER_COMPONENT },
    options: &[],
};

impl Family for Snorm3Family {
    fn info(&self) -> &Info {
        &INFO
    }
    fn precise(&self) -> bool {
        Snorm3::<OneWord>::EXACT_SEARCH && Snorm3::<TwoWords>::EXACT_SEARCH
    }
    fn helper_doc(&self, name: &str) -> Option<String> {
        match name {
            "encode_codes" => Some(format!(
                "Best Fit Normals: among the codes whose largest component is one of at most \
                 {BFN_SCALES} of the scales above M/2, the largest first, each the input scaled \
                 to that largest component and rounded, the one whose direction (computed in units \
                 of 2^-{BITS}, every quotient and root decided by comparisons) is nearest the \
                 input's by exact squared distance, the largest scale on ties."
            )),
            "bfn_step" => Some(
                "One scale of the Best Fit Normals search: the candidate code for scale `t`, kept \
                 if its fixed-point direction is strictly nearer the input's than the best so far."
                    .into(),
            ),
            _ => None,
        }
    }
    /// Components wider than 10 bits do not fit three to a word: snorm16×3 is two words.
    fn emitted(&self, spec: &Spec, _: Tracing) -> Emitted {
        match spec.bits() / 3 {
            16 => codec_functions(spec, Snorm3::<TwoWords>::two_words()),
            b => codec_functions(spec, Snorm3::<OneWord>::new([b; 3])),
        }
    }
}

impl Snorm3<OneWord> {
    /// snorm×3 in one word, with `bits` per component (5, 8 or 10); an invalid size is
    /// an error listing the allowed ones.
    #[inline(always)]
    pub fn one_word(bits: u32) -> Result<Self, SpecError> {
        match INFO.check_bits(bits * 3)? {
            48 => Err(SpecError::Invalid(
                "snorm16x3 takes two words: use Snorm3::two_words()".into(),
            )),
            _ => Ok(Snorm3::new([bits; 3])),
        }
    }

    /// snorm11_11_10: x and y in 11 bits, z in 10, one 32-bit word.
    #[inline(always)]
    pub fn snorm11_11_10() -> Self {
        Snorm3::new([11, 11, 10])
    }
}

impl Snorm3<TwoWords> {
    /// snorm16×3 in two words (the low 48 bits of an RGBA16_SNORM texel).
    #[inline(always)]
    pub fn two_words() -> Self {
        Snorm3::new([16; 3])
    }
}

/// How many 32-bit words the packed code takes: the packed type is part of the
/// emitted signature, so it is fixed per codec type.
pub trait Words: Send + Sync + 'static {
    type C<F: Float>: Code<F>;
}
/// One `u32` (snorm8×3 in an RGBA8_SNORM texel, snorm10×3 in A2B10G10R10_SNORM).
#[derive(Clone, Copy, Debug)]
pub struct OneWord;
/// Two `u32`s (snorm16×3 in the low 48 bits of an RGBA16_SNORM texel).
#[derive(Clone, Copy, Debug)]
pub struct TwoWords;
impl Words for OneWord {
    type C<F: Float> = F::U;
}
impl Words for TwoWords {
    type C<F: Float> = V2<F::U>;
}

#[derive(Clone, Copy, Debug)]
pub struct Snorm3<W> {
    /// Bits of x, y and z, first field lowest: 5, 8, 10 or 16 each, or 11, 11, 10.
    pub bits: [u32; 3],
    pub words: PhantomData<W>,
}

impl<W> Snorm3<W> {
    #[inline(always)]
    fn new(bits: [u32; 3]) -> Self {
        Snorm3 {
            bits,
            words: PhantomData,
        }
    }
}

impl<W: Words> Codec for Snorm3<W> {
    type P<F: Float> = V3<F>;
    type C<F: Float> = W::C<F>;
    #[inline]
    fn quants(&self) -> Quants {
        Quants::new(&self.bits.map(Quant::Snorm))
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V3<F> {
        unit_or_z(v)
    }
    /// The all-zero code, the only one with no direction, decodes as +Z.
    #[inline(always)]
    fn direction<F: Float>(&self, p: V3<F>) -> V3<F> {
        p.normalize_or(V3::new(F::c(0.0), F::c(0.0), F::c(1.0)))
    }
    /// Each component `x / |w|` of the canonical input decided portably
    /// ([`crate::codecs::toolkit::exact`]) against its exactly computed square length.
    const EXACT_ROUNDING: bool = true;
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V3<F> {
        let q = self.quants();
        let (w, ok) = canonical(v);
        let s = length2(w);
        let c = V3::new(
            snorm_sqrt_ratio(q[0], w.x, s),
            snorm_sqrt_ratio(q[1], w.y, s),
            snorm_sqrt_ratio(q[2], w.z, s),
        );
        V3::sel_all(ok, c, V3::new(F::c(0.0), F::c(0.0), F::c(q[2].max_code())))
    }
    /// Best Fit Normals (see the module): the top scales tried one by one, the largest
    /// first, each candidate's direction measured in fixed point. Zero, NaN and infinite
    /// input aim at +Z, whose candidates all point there: the first, `(0, 0, M)`, wins.
    const EXACT_SEARCH: bool = true;
    #[inline(always)]
    fn precise_codes<F: Float>(&self, v: V3<F>) -> V3<F> {
        let (w, _) = canonical_or_z(v);
        let aim = fixed_target(w, root(fixed_length2(w)), BITS);
        let a = aim.abs();
        let m = a.x.at_least(a.y).at_least(a.z);
        // Each component over the largest in units of 2^-BITS (the largest exactly ONE).
        let r = a.map(#[inline(always)] |x| fixed_ratio(x, m, BITS)).named("r");
        let top = self.bits.iter().copied().min().map_or(0, #[inline(always)] |b| (1u32 << (b - 1)) - 1);
        // The best scale so far and its squared distance.
        let mut best = V2::new(F::c(0.0), F::c(BFN_FAR));
        for t in (top + 1 - bfn_scales(top)..=top).rev() {
            let t = F::c(t as f32);
            best = helper!(bfn_step(best, t, r, aim))
            .named("best");
        }
        let c = candidate(r, best.x);
        let signed = { #[inline(always)] |c: F, x: F| F::sel(x.lt(F::c(0.0)), -c, c) };
        V3::new(signed(c.x, aim.x), signed(c.y, aim.y), signed(c.z, aim.z))
    }
}

/// Scales the Best Fit Normals search tries at most (all those above `M/2` up to snorm8,
/// the top ones above): each costs about 150 ALU instructions.
pub const BFN_SCALES: u32 = 64;

/// The scales tried below the largest code `top`.
fn bfn_scales(top: u32) -> u32 {
    (top - top / 2).min(BFN_SCALES)
}

/// A squared distance no candidate reaches (fixed-point unit vectors are at most 2 apart:
/// `(2·2^21)²`).
const BFN_FAR: f32 = 1.0e30;

/// The candidate code magnitudes for scale `t` (`r` the input's magnitudes over its
/// largest, in units of `2^-BITS`): each component one product rounded, so the largest
/// is `t` exactly. The same value as [`crate::codecs::toolkit::fixed_decode::fixed_mul`]`(r, t)`, but
/// scaled first: `r·2^-BITS` is then the same in every step, and compilers compute it
/// once instead of once per scale (64 instructions fewer).
#[inline(always)]
fn candidate<F: Float>(r: V3<F>, t: F) -> V3<F> {
    r.map(#[inline(always)] |x| (x * F::c((1.0 / ONE) as f32) * t).round())
        .named("c")
}

/// One scale of the search from `best = (scale, squared distance)`: the candidate's
/// direction `c / |c|` in units of `2^-BITS` from the root of its exact square sum, then
/// its squared distance to `aim`'s magnitudes; `t` replaces the best only if strictly
/// nearer.
#[inline(always)]
fn bfn_step<F: Float>(best: V2<F>, t: F, r: V3<F>, aim: V3<F>) -> V2<F> {
    let c = candidate(r, t);
    let a = c.map(#[inline(always)] |x| x.to_u());
    let l = root_of(sum_of_squares::<F, 3>([a.x, a.y, a.z])).at_least(t).named("l");
    let d = c.map(#[inline(always)] |x| fixed_ratio(x, l, BITS)).named("d");
    let dist = distance(d, aim.abs()).squared().named("dist");
    let nearer = dist.lt(best.y);
    V2::sel_all(nearer, V2::new(t, dist), best)
}
