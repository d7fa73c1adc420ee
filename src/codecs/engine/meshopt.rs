//! meshoptimizer's octahedral vertex filter, as glTF's `EXT_meshopt_compression` stores it
//! (filter 1, `OCTAHEDRAL`): four 8-bit (`meshopt_oct8`, a 4-byte stride) or 16-bit
//! (`meshopt_oct16`, an 8-byte stride) two's complement words per vector. x and y are
//! octahedral coordinates as K-bit snorm integers (`bits=K`, 4 ≤ K ≤ 8 or 16, sign-extended
//! into the word), the third word is 1.0 as a K-bit snorm (`2^(K-1) - 1`), so a decoder
//! finds K per vector, and the fourth is passed through (0 here: a normal has no w).
//!
//! The encoder is `meshopt_encodeFilterOct` (meshoptimizer 1.3, `src/vertexfilter.cpp`)
//! step by step: `1/(|x| + |y| + |z|)` (0 for the zero vector), products, the fold on the
//! unscaled `z ≥ 0`, and `meshopt_quantizeSnorm`'s `int(clamp(u)·M + (u ≥ 0 ? ½ : -½))`
//! (truncation; a NaN coordinate becomes `-M`). The decoder is the extension's reference
//! pseudo-code (Appendix B): `x/one`, `y/one`, `z = 1 - |x| - |y|`, the `copysign` fix-up,
//! division by the length, and `round(·INTN_MAX)` half away from zero; it returns those
//! output words as the snorm vertex fetch reads them (`max(c·fl(1/INTN_MAX), -1)`, as every
//! decoder here reads a snorm field). The extension allows a decoder one unit in the last place of the
//! output word, which meshoptimizer's own SIMD decoders use (a reciprocal square root,
//! not the divisions); this decoder is the reference, not those.

use crate::codecs::component::snorm3::{OneWord, TwoWords, Words};
use crate::codecs::core::codec::Codec;
use crate::codecs::core::info::Domain;
use crate::codecs::core::codec_family::CodecFamily;
use crate::codecs::core::ieee;
use crate::codecs::core::info::{Info, OptDesc, OptKind, Sizes, FloatForm, seam};
use crate::codecs::core::pipeline::codec_functions;
use crate::codecs::core::spec::{Spec, SpecError};
use crate::codecs::toolkit::quant::{Quant, Quants, round_half_away, truncated};
use crate::model::num::helper;
use crate::model::{Float, V3, V4};
use std::marker::PhantomData;

const SOURCE: &str = "meshoptimizer 1.3 (src/vertexfilter.cpp, meshopt_encodeFilterOct; meshopt crate 0.7.0) and glTF EXT_meshopt_compression, Appendix B, filter 1 (the reference decoder)";
const EDGE: &str = "meshoptimizer's: zero input encodes as +Z (0, 0); NaN coordinates become -M (a NaN fails both clamps' comparisons); infinite input gives NaN coordinates, so (-M, -M)";
const DECODE: &str = "the extension's reference decoder, read as the snorm vertex fetch reads its output words: a unit vector to the output's rounding; a third word below 1 (invalid, unspecified by the extension) is read as its magnitude, at least 1";

const fn bits_option(word: u32) -> OptDesc {
    OptDesc {
        key: "bits",
        help: "K, the bits of each octahedral coordinate (meshopt_encodeFilterOct's bits): an integer from 4 to the word size",
        kind: OptKind::Number {
            default: word as f32,
            min: 4.0,
            max: word as f32,
        },
    }
}

const BITS8: OptDesc = bits_option(8);
const BITS16: OptDesc = bits_option(16);

pub static MESHOPT_OCT8: CodecFamily<MeshoptOct<OneWord>> = CodecFamily::new(
    Info {
        name: "meshopt_oct8",
        title: "meshoptimizer / EXT_meshopt_compression octahedral filter, 8-bit words",
        sizes: Sizes::Fixed(32),
        domain: Some(Domain::Sphere),
        source: SOURCE,
        edge_policy: EDGE,
        decode_note: DECODE,
        float_form: FloatForm::Continuous { seam: seam::OCTAHEDRAL_FOLD },
        options: &[BITS8, ieee::ENGINE_OPTION],
    },
    // Four words a vector: 32 bits of 8-bit words, 64 of 16-bit ones.
    |bits| MeshoptOct::new_unchecked(bits / 4),
    codec_functions,
)
.with_options(|spec, c| c.with_k(spec.number_of(&BITS8)))
.with_validate(validate)
.with_variants(&["meshopt_oct8:bits=6"])
.with_engine("meshoptimizer");

pub static MESHOPT_OCT16: CodecFamily<MeshoptOct<TwoWords>> = CodecFamily::new(
    Info {
        name: "meshopt_oct16",
        title: "meshoptimizer / EXT_meshopt_compression octahedral filter, 16-bit words",
        sizes: Sizes::Fixed(64),
        domain: Some(Domain::Sphere),
        source: SOURCE,
        edge_policy: EDGE,
        decode_note: DECODE,
        float_form: FloatForm::Continuous { seam: seam::OCTAHEDRAL_FOLD },
        options: &[BITS16, ieee::ENGINE_OPTION],
    },
    |bits| MeshoptOct::new_unchecked(bits / 4),
    codec_functions,
)
.with_options(|spec, c| c.with_k(spec.number_of(&BITS16)))
.with_validate(validate)
.with_variants(&["meshopt_oct16:bits=12"])
.with_engine("meshoptimizer");

fn validate(spec: &Spec) -> Result<(), SpecError> {
    // Both sizes' option is keyed `bits`.
    let k = spec.number_of(&BITS8);
    if k.fract() == 0.0 {
        Ok(())
    } else {
        Err(SpecError::BadValue {
            key: "bits".into(),
            value: k.to_string(),
            why: "K is a whole number of bits".into(),
        })
    }
}

/// The filter's words with K-bit coordinates: `W` is the word size's packed type (one
/// `u32` for 8-bit words, two for 16-bit ones).
#[derive(Clone, Copy, Debug)]
pub struct MeshoptOct<W> {
    /// The word size, 8 or 16.
    pub word: u32,
    /// K, the coordinates' bits, 4 ≤ K ≤ word.
    pub k: u32,
    words: PhantomData<W>,
}

impl<W> MeshoptOct<W> {
    const fn new_unchecked(word: u32) -> Self {
        MeshoptOct {
            word,
            k: word,
            words: PhantomData,
        }
    }
    /// The same word size with K-bit coordinates (the spec's `bits`, validated whole).
    fn with_k(self, k: f32) -> Self {
        MeshoptOct { k: k as u32, ..self }
    }
}

impl MeshoptOct<OneWord> {
    /// `meshopt_oct8` with K-bit coordinates (4 ≤ K ≤ 8).
    pub fn new(k: u32) -> Result<Self, SpecError> {
        let spec: Spec = format!("meshopt_oct8:bits={k}").parse()?;
        Ok(MESHOPT_OCT8.codec_of(&spec))
    }
}

impl MeshoptOct<TwoWords> {
    /// `meshopt_oct16` with K-bit coordinates (4 ≤ K ≤ 16).
    pub fn new(k: u32) -> Result<Self, SpecError> {
        let spec: Spec = format!("meshopt_oct16:bits={k}").parse()?;
        Ok(MESHOPT_OCT16.codec_of(&spec))
    }
}

impl<W> MeshoptOct<W> {
    /// `M = 2^(K-1) - 1`, the K-bit snorm's 1.0 (the third word).
    fn one(&self) -> f32 {
        ((1u32 << (self.k - 1)) - 1) as f32
    }
    /// The word's snorm: the output words' `INTN_MAX` and the vertex fetch's field.
    fn field(&self) -> Quant {
        Quant::Snorm(self.word)
    }
}

/// The reference decoder on the integer words `c` (as floats): the direction as the
/// output words' snorm fetch reads them. A third word below 1 (invalid) is read as its
/// magnitude, at least 1, so that every code decodes finite within a proven bound.
#[inline(always)]
fn reference_decode<F: Float>(out: Quant, c: V4<F>) -> V3<F> {
    let zero = F::c(0.0);
    let one = c.z.abs().at_least(F::c(1.0)).named("one");
    let x = c.x / one;
    let y = c.y / one;
    let z = F::c(1.0) - x.abs() - y.abs();
    let t = F::sel(z.lt(zero), z, zero).named("t");
    // x -= copysign(t, x), t ≤ 0: toward zero by |t|. The sign is read from the integer
    // word, whose quotient by `one ≥ 1` has its sign (a zero word of either sign, like its
    // quotient, reads ≥ 0; where `one` is infinite, t is 0 and the side does not
    // matter): the pseudo-code's selection on every code, and one no implementation can
    // change. The quotient's can: `0/one` may be a denormal of either sign within
    // division's 2.5 ULP, and on a code no encoder writes (a zero coordinate, the other
    // beyond the third word) that sign flips an output component.
    let fix = {
        #[inline(always)]
        |a: F, word: F| a - F::sel(word.ge(zero), -t, t)
    };
    let v = V3::new(fix(x, c.x), fix(y, c.y), z).named("v");
    let len = v.length_squared().sqrt();
    let m = F::c(out.max_code());
    (v / len).map(
        #[inline(always)]
        |a| {
            let o = round_half_away(a * m);
            // The output word 0 is fetched as +0.
            out.dequantize(F::sel(o.eq(zero), zero, o))
        },
    )
}

impl<W: Words> Codec for MeshoptOct<W> {
    type P<F: Float> = V4<F>;
    type C<F: Float> = W::C<F>;
    #[inline]
    fn quants(&self) -> Quants {
        Quants::new(&[self.field(); 4])
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    /// The float form: the encoder's words as the snorm fetch reads them, already
    /// quantized, so a render target or a CPU conversion of the matching format stores
    /// exactly the packed code's words.
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V4<F> {
        let q = self.field();
        let c = helper!(self.round_codes(v));
        let one = self.one() / q.max_code();
        V4::new(
            q.dequantize(c.x),
            q.dequantize(c.y),
            F::c(one),
            F::c(0.0),
        )
    }
    /// The fetched words back to integers, then the reference decoder.
    #[inline(always)]
    fn direction<F: Float>(&self, p: V4<F>) -> V3<F> {
        let m = F::c(self.field().max_code());
        let words = p.map(
            #[inline(always)]
            |x| (x * m).round(),
        );
        reference_decode(self.field(), words)
    }
    #[inline(always)]
    fn decode_codes<F: Float>(&self, codes: V4<F>) -> V3<F> {
        reference_decode(self.field(), codes)
    }
    /// The fourth word is passed through: no decode reads it.
    fn unread_fields(&self) -> &'static [usize] {
        &[3]
    }
    /// Every valid code's third word is the K-bit 1.0.
    fn fixed_fields(&self) -> Vec<(usize, i64)> {
        vec![(2, self.one() as i64)]
    }
    /// `meshopt_encodeFilterOct` for `(x, y, z, 0)`.
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V4<F> {
        let zero = F::c(0.0);
        let a = v.abs();
        let nl = (a.x + a.y + a.z).named("nl");
        let is_zero = nl.eq(zero);
        let ns = F::sel(is_zero, zero, F::c(1.0) / F::sel(is_zero, F::c(1.0), nl)).named("ns");
        let nx = (v.x * ns).named("nx");
        let ny = (v.y * ns).named("ny");
        let sign = {
            #[inline(always)]
            |a: F| F::sel(a.ge(zero), F::c(1.0), F::c(-1.0))
        };
        let upper = v.z.ge(zero);
        let u = F::sel(upper, nx, (F::c(1.0) - ny.abs()) * sign(nx));
        let w = F::sel(upper, ny, (F::c(1.0) - nx.abs()) * sign(ny));
        let m = F::c(self.one());
        let quantize = {
            #[inline(always)]
            |x: F| {
                let half = F::sel(x.ge(zero), F::c(0.5), F::c(-0.5));
                truncated(x.clamped(F::c(-1.0), F::c(1.0)) * m + half)
            }
        };
        V4::new(quantize(u), quantize(w), m, zero).named("codes")
    }
}
