//! snorm×3: the vector's components stored directly (survey; the first seed's baseline).
//! Most codes are not unit length, so decode re-normalizes.

use super::codec::{Codec, Domain, unit_or_z};
use super::exact::{canonical, length2, snorm_sqrt_ratio};
use super::quant::{Code, Quant, Quants};
use crate::model::{Float, V2, V3};
use std::marker::PhantomData;
use super::family::{Family, Info, Sizes};
use super::functions::{Emitted, codec_functions};
use super::spec::{Spec, SpecError};

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
    precise: false,
    source: "Cigolle et al. 2014 §2; Pranckevičius, baseline",
    edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z",
    decode_note: "decode re-normalizes; the all-zero code decodes as +Z",
    options: &[],
};

impl Family for Snorm3Family {
    fn info(&self) -> &'static Info {
        &INFO
    }
    /// Components wider than 10 bits do not fit three to a word: snorm16×3 is two words.
    fn emitted(&self, spec: &Spec) -> Emitted {
        match spec.bits() / 3 {
            16 => codec_functions(spec, Snorm3::<TwoWords>::two_words()),
            b => codec_functions(spec, Snorm3::<OneWord>::new([b; 3])),
        }
    }
}

impl Snorm3<OneWord> {
    /// snorm×3 in one word, with `bits` per component (5, 8 or 10); an invalid size is
    /// an error listing the allowed ones.
    pub fn one_word(bits: u32) -> Result<Self, SpecError> {
        match INFO.check_bits(bits * 3)? {
            48 => Err(SpecError::Invalid(
                "snorm16x3 takes two words: use Snorm3::two_words()".into(),
            )),
            _ => Ok(Snorm3::new([bits; 3])),
        }
    }

    /// snorm11_11_10: x and y in 11 bits, z in 10, one 32-bit word.
    pub fn snorm11_11_10() -> Self {
        Snorm3::new([11, 11, 10])
    }
}

impl Snorm3<TwoWords> {
    /// snorm16×3 in two words (the low 48 bits of an RGBA16_SNORM texel).
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
    fn params<F: Float>(&self, v: V3<F>) -> V3<F> {
        unit_or_z(v)
    }
    /// The all-zero code, the only one with no direction, decodes as +Z.
    fn direction<F: Float>(&self, p: V3<F>) -> V3<F> {
        p.normalize_or(V3::new(F::c(0.0), F::c(0.0), F::c(1.0)))
    }
    /// Each component `x / |w|` of the canonical input decided portably
    /// ([`crate::codecs::exact`]) against its exactly computed square length.
    const EXACT_ROUNDING: bool = true;
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
}
