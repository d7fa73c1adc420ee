//! What a codec is, and the generic pipeline every codec shares: quantization, the
//! precise (integer candidate) search and bit packing are written once, here.

use crate::codecs::core::info::Domain;
use crate::codecs::toolkit::quant::{Code, Quant, Quants, field_offsets};
use crate::model::enclosure::Encl;
use crate::model::num::helper;
use crate::model::trace::Value;
use crate::model::{Bool, Float, Uint, V2, V3, V4, each};

/// The parameter vector a codec stores: `V2`, `V3` or (a texel's channels) `V4` of floats.
pub trait Params<F: Float>: Value {
    const N: usize;
    fn lane(&self, i: usize) -> F;
    /// Builds the vector from lanes, recorded as one vector operation.
    fn build(f: impl FnMut(usize) -> F) -> Self;
    /// Names the vector in emitted code.
    fn named_p(self, name: &'static str) -> Self;
}

impl<F: Float> Params<F> for V2<F> {
    const N: usize = 2;
    #[inline(always)]
    fn lane(&self, i: usize) -> F {
        self.to_array()[i]
    }
    #[inline(always)]
    fn build(mut f: impl FnMut(usize) -> F) -> Self {
        let a = [f(0), f(1)];
        V2::from_array(F::fuse(a))
    }
    #[inline(always)]
    fn named_p(self, name: &'static str) -> Self {
        self.named(name)
    }
}

impl<F: Float> Params<F> for V3<F> {
    const N: usize = 3;
    #[inline(always)]
    fn lane(&self, i: usize) -> F {
        self.to_array()[i]
    }
    #[inline(always)]
    fn build(mut f: impl FnMut(usize) -> F) -> Self {
        let a = [f(0), f(1), f(2)];
        V3::from_array(F::fuse(a))
    }
    #[inline(always)]
    fn named_p(self, name: &'static str) -> Self {
        self.named(name)
    }
}

impl<F: Float> Params<F> for V4<F> {
    const N: usize = 4;
    #[inline(always)]
    fn lane(&self, i: usize) -> F {
        self.to_array()[i]
    }
    #[inline(always)]
    fn build(mut f: impl FnMut(usize) -> F) -> Self {
        let a = [f(0), f(1), f(2), f(3)];
        V4::from_array(F::fuse(a))
    }
    #[inline(always)]
    fn named_p(self, name: &'static str) -> Self {
        self.named(name)
    }
}

/// One codec: a map from directions to parameters and back, plus how the parameters are
/// stored. Written once, generically: evaluated with `f32` it is the CPU reference,
/// traced it is the shader source.
pub trait Codec: Send + Sync {
    type P<F: Float>: Params<F>;
    type C<F: Float>: Code<F>;
    /// Storage of each parameter, in texel order. Implementations are `#[inline]`, so that
    /// the CPU slices work the fields out once per slice rather than once per group.
    fn quants(&self) -> Quants;
    fn domain(&self) -> Domain;
    /// The unit vector the encoder aims at for any input (normalized, projected onto the
    /// domain, and a fixed direction for zero, NaN or infinite input). Precise encoders
    /// measure candidates against it.
    #[inline(always)]
    fn target<F: Float>(&self, v: V3<F>) -> V3<F> {
        let u = unit_or_z(v);
        match self.domain() {
            Domain::Sphere => u,
            // Validity is judged on the raw input first (a NaN or infinite z must not be
            // projected into a real direction), then the projection is renormalized; -Z
            // projects to zero and so becomes +Z.
            Domain::Hemisphere => unit_or_z(above_horizon(u)),
        }
    }
    /// Direction → parameters in storage range, before quantization.
    fn params<F: Float>(&self, v: V3<F>) -> Self::P<F>;
    /// [`Codec::params`] in the source's plain arithmetic, for the lean tier
    /// ([`crate::codecs::core::ieee`]): without the power-of-two scalings and canonical
    /// forms that make the default tier's encoders portable, so exact only where every
    /// operation rounds correctly and denormals are kept. The default is `params` itself.
    #[inline(always)]
    fn ieee_params<F: Float>(&self, v: V3<F>) -> Self::P<F> {
        self.params(v)
    }
    /// Whether [`Codec::ieee_params`] are always within the storage range and never NaN
    /// (in the arithmetic the lean tier assumes), so that its fast encoder rounds them
    /// without clamping.
    const IEEE_IN_RANGE: bool = false;
    /// Parameters in storage range → direction.
    fn direction<F: Float>(&self, p: Self::P<F>) -> V3<F>;
    /// Integer codes (as unpacked from the texel) → direction: dequantized, then the
    /// `decode_float` helper. A codec whose parameters are themselves re-quantized by
    /// its decoder overrides this to decode the integers directly.
    #[inline(always)]
    fn decode_codes<F: Float>(&self, codes: Self::P<F>) -> V3<F> {
        let p = dequantize(&self.quants(), codes).named_p("params");
        helper!("decode_float" => self.direction(p))
    }
    /// A bit field that holds bits of more than one parameter, so that a range of it is
    /// no range of either: [`crate::measure::decode_bound`] then takes its values one at a time.
    fn whole_field(&self) -> Option<usize> {
        None
    }
    /// The parts a decoder splits a code into by integer operations alone, which no
    /// implementation can change (a combined index's face, row and column), each an
    /// inclusive range: the decoders' bound is then proven over boxes of parts
    /// ([`Codec::parts_direction`]), since boxes of a combined index's fields straddle
    /// its rows, and a split by comparisons keeps no range apart. `None`: over the fields.
    fn proof_parts(&self) -> Option<Vec<(i64, i64)>> {
        None
    }
    /// The decoder after its integer split, on enclosures of the parts
    /// ([`Codec::proof_parts`]). Where a codec names parts without it, every output is
    /// unknown, so its bound is infinite and `tests/figures/decode_bound.rs` fails.
    fn parts_direction(&self, parts: &[Encl]) -> V3<Encl> {
        let _ = parts;
        V3::new(Encl::unknown(), Encl::unknown(), Encl::unknown())
    }
    /// Fields the decoder never reads (a texel's constant channels): a bound proven over
    /// one value of each holds for all ([`crate::measure::decode_bound`]).
    fn unread_fields(&self) -> &'static [usize] {
        &[]
    }
    /// Fields every valid code holds at one value, as `(field, code)` (meshoptimizer's
    /// K-bit 1.0): [`crate::measure::decode_bound`] proves the bound for the valid codes, with the
    /// field at that value, and the decoder's doc comment says so. A code with another
    /// value there still decodes finite (tests/conventions.rs), within no stated bound.
    fn fixed_fields(&self) -> Vec<(usize, i64)> {
        Vec::new()
    }
    /// The name of a second packed encoder, if the codec has one (a texel layout that
    /// serves two block formats), which writes [`Codec::alternate_codes`] of the codes.
    fn alternate(&self) -> Option<&'static str> {
        None
    }
    /// The codes the [`Codec::alternate`] encoder writes.
    #[inline(always)]
    fn alternate_codes<F: Float>(&self, codes: Self::P<F>) -> Self::P<F> {
        codes
    }
    /// Whether [`Codec::round_codes`] decides every code with [`crate::codecs::toolkit::exact`], so
    /// that the fast packed encoder returns the same code under every deviation class the
    /// portability guarantee covers (tests/portability.rs holds each codec to its word
    /// both ways).
    const EXACT_ROUNDING: bool = false;
    /// Integer codes of the fast encoder. The default rounds the `encode_float` helper's
    /// parameters (`round(p·M)`), whose rounding boundaries move with any division or
    /// square root error an implementation is allowed. A codec that sets
    /// [`Codec::EXACT_ROUNDING`] overrides it with an exact form, which the encoder then
    /// calls as the helper `round_codes`.
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> Self::P<F> {
        let p = helper!("encode_float" => self.params(v));
        quantize(&self.quants(), p).named_p("codes")
    }
    /// Whether [`Codec::precise_codes`] decides the search in integer arithmetic
    /// ([`crate::codecs::toolkit::lattice`]), so that the precise packed encoder is portable like
    /// a fast one with [`Codec::EXACT_ROUNDING`].
    const EXACT_SEARCH: bool = false;
    /// Integer codes chosen by the precise encoder: [`precise_search`] through this
    /// codec's own `decode_float`.
    #[inline(always)]
    fn precise_codes<F: Float>(&self, v: V3<F>) -> Self::P<F> {
        precise_search(self, v, "decode_float")
    }
}

/// Searches the 2^N codes around the exact parameters (floor or floor+1 per parameter)
/// and keeps the one whose decoded direction is nearest the target by squared distance,
/// the first one on ties. Candidates are integer codes and are decoded exactly as the
/// decoder will (through the helper `decode_name`), so encoder and decoder agree on
/// what "nearest" means; a cosine in f32 could not tell 32-bit candidates apart.
#[inline(always)]
pub fn precise_search<F: Float, C: Codec + ?Sized>(
    codec: &C,
    v: V3<F>,
    decode_name: &'static str,
) -> C::P<F> {
    let q = codec.quants();
    let u = codec.target(v).named("dir");
    let p = codec.params(u);
    let base = C::P::<F>::build(
        #[inline(always)]
        |i| q[i].floor_code(p.lane(i)),
    )
    .named_p("base");
    let decode = {
        #[inline(always)]
        |c: C::P<F>| {
            let params = dequantize(&q, c);
            F::call(
                decode_name,
                &["params"],
                params,
                #[inline(always)]
                |p| codec.direction(p),
            )
        }
    };
    let mut best = base;
    let mut best_d = distance2(decode(base), u).named("best_d");
    for k in 1..(1usize << C::P::<F>::N) {
        let cand = C::P::<F>::build(
            #[inline(always)]
            |i| {
                let step = if k >> i & 1 == 1 {
                    base.lane(i) + F::c(1.0)
                } else {
                    base.lane(i)
                };
                q[i].clamp_code(step)
            },
        )
        .named_p("cand");
        let d = distance2(decode(cand), u).named("d");
        let better = d.lt(best_d);
        best = C::P::<F>::build(
            #[inline(always)]
            |i| F::sel(better, cand.lane(i), best.lane(i)),
        )
        .named_p("best");
        best_d = F::sel(better, d, best_d).named("best_d");
    }
    best
}

#[inline(always)]
fn distance2<F: Float>(a: V3<F>, b: V3<F>) -> F {
    (a - b).length_squared()
}

/// `v` projected onto the +Z hemisphere: `z ← max(z, +0)` as a select (a NaN `z` becomes
/// `+0`, so validity must be judged before).
#[inline(always)]
pub fn above_horizon<F: Float>(v: V3<F>) -> V3<F> {
    V3::new(v.x, v.y, F::sel(v.z.gt(F::c(0.0)), v.z, F::c(0.0)))
}

/// `x ≥ 0 ? 1 : -1`: −0 counts as positive (never `sign()`, which is 0 at 0).
#[inline(always)]
pub fn sign_not_zero<F: Float>(v: V2<F>) -> V2<F> {
    v.map(
        #[inline(always)]
        |x| F::sel(x.ge(F::c(0.0)), F::c(1.0), F::c(-1.0)),
    )
}

/// Normalizes `v`; zero, NaN and infinite input become +Z. Scaling by the largest
/// component first keeps huge and denormal inputs from overflowing or vanishing; after
/// it the squared length is at least 1 for every valid input and NaN or below 1 for
/// every invalid one (a NaN lane can hide from the select-based maximum, not from it).
#[inline(always)]
pub fn unit_or_z<F: Float>(v: V3<F>) -> V3<F> {
    let a = v.abs();
    let m = a.x.at_least(a.y).at_least(a.z).named("largest");
    let ok = m.gt(F::c(0.0)).and(m.le(F::c(f32::MAX)));
    let w = (v / F::sel(ok, m, F::c(1.0))).named("scaled");
    let len2 = w.length_squared().named("len2");
    let good = ok.and(len2.ge(F::c(1.0)));
    let unit = w / len2.sqrt();
    V3::sel_all(good, unit, V3::new(F::c(0.0), F::c(0.0), F::c(1.0)))
}

#[inline(always)]
pub fn quantize<F: Float, P: Params<F>>(q: &[Quant], p: P) -> P {
    P::build(
        #[inline(always)]
        |i| q[i].quantize(p.lane(i)),
    )
}

#[inline(always)]
pub fn dequantize<F: Float, P: Params<F>>(q: &[Quant], c: P) -> P {
    P::build(
        #[inline(always)]
        |i| q[i].dequantize(c.lane(i)),
    )
}

/// Packs integer codes into the texel's bits: first field lowest, little-endian.
#[inline(always)]
pub fn pack<F: Float, P: Params<F>, C: Code<F>>(q: &[Quant], c: P) -> C {
    let offs = field_offsets(q);
    let mut words: [Option<F::U>; 3] = [None; 3];
    for (i, quant) in q.iter().enumerate() {
        let (w, sh) = ((offs[i] / 32) as usize, offs[i] % 32);
        let f = quant.field_at(c.lane(i), sh);
        words[w] = Some(match words[w] {
            None => f,
            Some(acc) => acc | f,
        });
    }
    C::from_words(each(
        words,
        #[inline(always)]
        |w| {
            w.unwrap_or_else(
                #[inline(always)]
                || F::U::c(0),
            )
        },
    ))
}

/// Unpacks integer codes; bits outside the fields are ignored.
#[inline(always)]
pub fn unpack<F: Float, P: Params<F>, C: Code<F>>(q: &[Quant], code: C) -> P {
    let offs = field_offsets(q);
    P::build(
        #[inline(always)]
        |i| {
            let (w, sh) = ((offs[i] / 32) as usize, offs[i] % 32);
            let word = code.word(w);
            let shifted = if sh == 0 { word } else { word.shr(sh) };
            let field = if sh + q[i].bits() == 32 {
                shifted
            } else {
                shifted & F::U::c(q[i].mask())
            };
            q[i].from_field(field)
        },
    )
}

/// Doc comments of the helpers defined here.
pub fn helper_doc(name: &str) -> Option<String> {
    match name {
        "encode_codes" => Some("Precise search: the integer codes (as floats) around the exact parameters whose decode is nearest the input by squared distance.".to_string()),
        "round_codes" => Some("The nearest integer codes (as floats; bytes of them for the rgb8 layout), each decided by comparing correctly rounded products, never a quotient or a root, so division and square root error, contraction, denormal flushing and lost signs of zero cannot change them.".to_string()),
        _ => None,
    }
}
