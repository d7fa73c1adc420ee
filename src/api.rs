//! The CPU library for asset pipelines: the same `f32` model the emitted shaders are
//! verified against, so codes encoded here are the codes the shader encoder writes, and
//! the shader decoder turns them into the same vectors as [`Encoder::decode`] — exactly,
//! on implementations with correctly rounded arithmetic that keep denormals and do not
//! fuse multiply-adds (verified on lavapipe; see the README on real GPUs).
//!
//! ```
//! use unitpack::api::{CpuCodec, Oct};
//!
//! let oct = Oct::new(24).unwrap().precise();
//! let code: u32 = oct.encode([0.0, 0.6, 0.8]);
//! let v = oct.decode(code);
//! assert!((v[1] - 0.6).abs() < 1e-3 && (v[2] - 0.8).abs() < 1e-3);
//!
//! // Batches over slices, e.g. a mesh's normals into an RG16_SNORM-style buffer.
//! let normals = vec![[0.0, 0.0, 1.0]; 4];
//! let mut codes = vec![0u32; 4];
//! Oct::new(32).unwrap().fast().encode_slice(&normals, &mut codes);
//! assert!(codes.iter().all(|&c| c == codes[0]));
//! ```

use crate::codecs::core::codec::Codec;
use crate::codecs::core::pipeline::{decode_packed, encode_packed};
pub use crate::codecs::cpu::*;
pub use crate::codecs::functions::function::Width;
use crate::codecs::functions::function::{Function, Role};
use crate::codecs::toolkit::quant::Code;
use crate::codecs::{Spec, SpecError};
use crate::model::Uint;
use crate::model::V3;
use crate::model::avx2_lanes::{self, F8, WIDTH};
use crate::model::lanes::{F4, LaneIo};
use wide::bytemuck::{cast_slice, cast_slice_mut};

/// A codec with its encoder chosen (fast: nearest codes; precise: the survey's "P" search).
#[derive(Clone, Copy, Debug)]
pub struct Encoder<C> {
    pub codec: C,
    pub precise: bool,
}

/// Encoders and decoders on the CPU, for every codec.
pub trait CpuCodec: Codec + Sized {
    /// The nearest-code encoder.
    fn fast(self) -> Encoder<Self> {
        Encoder {
            codec: self,
            precise: false,
        }
    }
    /// The precise encoder: the candidate code whose decode is nearest the input.
    fn precise(self) -> Encoder<Self> {
        Encoder {
            codec: self,
            precise: true,
        }
    }
}
impl<C: Codec> CpuCodec for C {}

impl<C: Codec> Encoder<C> {
    /// The packed code of `v` (any vector; see the codec's zero/NaN policy).
    #[inline]
    pub fn encode(&self, v: [f32; 3]) -> C::C<f32> {
        encode_packed(&self.codec, self.precise, V3::from_array(v))
    }
    /// The direction a packed code stands for.
    #[inline]
    pub fn decode(&self, code: C::C<f32>) -> [f32; 3] {
        decode_packed(&self.codec, code).to_array()
    }
    /// Encodes `input` into `out` (same length), eight vectors per step on AVX2 lanes
    /// where the processor has them (compiled for AVX-512VL where it has that too), else
    /// four on SSE2 lanes ([`crate::model::lanes`]): the same bits as [`Encoder::encode`]
    /// on each.
    pub fn encode_slice(&self, input: &[[f32; 3]], out: &mut [C::C<f32>]) {
        self.encode_slice_on(Width::widest(), input, out)
    }

    /// [`Encoder::encode_slice`] on the given lanes, so that every width can be compared;
    /// [`Width::Eight`] panics without AVX2, [`Width::EightAvx512`] without AVX-512VL.
    pub fn encode_slice_on(&self, width: Width, input: &[[f32; 3]], out: &mut [C::C<f32>]) {
        assert_eq!(
            input.len(),
            out.len(),
            "encode_slice: input and output lengths differ"
        );
        match width {
            Width::Four => self.encode_lanes::<F4, 4>(input, out),
            Width::Eight => {
                assert!(avx2_lanes::available(), "eight lanes need AVX2");
                // SAFETY: the processor has AVX2 (checked just above).
                unsafe { self.encode_avx2(input, out) }
            }
            Width::EightAvx512 => {
                assert!(
                    avx2_lanes::avx512_available(),
                    "eight lanes on AVX-512VL need AVX2, AVX-512F and AVX-512VL"
                );
                // SAFETY: the processor has all three (checked just above).
                unsafe { self.encode_avx512(input, out) }
            }
        }
    }

    /// [`Encoder::encode_slice`] on eight lanes, compiled for AVX2.
    ///
    /// # Safety
    /// The processor must have AVX2.
    #[cfg_attr(target_arch = "x86_64", target_feature(enable = "avx2"))]
    unsafe fn encode_avx2(&self, input: &[[f32; 3]], out: &mut [C::C<f32>]) {
        self.encode_lanes::<F8, WIDTH>(input, out)
    }

    /// [`Encoder::encode_slice`] on eight lanes, compiled for AVX-512VL ([`Width::EightAvx512`]).
    ///
    /// # Safety
    /// The processor must have AVX2, AVX-512F and AVX-512VL.
    #[cfg_attr(
        target_arch = "x86_64",
        target_feature(enable = "avx2,avx512f,avx512vl")
    )]
    unsafe fn encode_avx512(&self, input: &[[f32; 3]], out: &mut [C::C<f32>]) {
        self.encode_lanes::<F8, WIDTH>(input, out)
    }

    /// Encodes `N` vectors per step on the lanes `L` ([`in_whole_groups`]).
    #[inline(always)]
    fn encode_lanes<L: LaneIo<N>, const N: usize>(
        &self,
        input: &[[f32; 3]],
        out: &mut [C::C<f32>],
    ) {
        in_whole_groups(input, out, {
            #[inline(always)]
            |vs: &[[f32; 3]; N], os: &mut [C::C<f32>; N]| {
                let [x, y, z] = L::u_from_items3(as_words(vs));
                let code = encode_packed(
                    &self.codec,
                    self.precise,
                    V3::new(x.as_float(), y.as_float(), z.as_float()),
                );
                let word = {
                    #[inline(always)]
                    |j: usize| {
                        if j < <C::C<L> as Code<L>>::WORDS {
                            L::u_words(code.word(j))
                        } else {
                            [0; N]
                        }
                    }
                };
                let words = [word(0), word(1), word(2)];
                for (k, o) in os.iter_mut().enumerate() {
                    *o = C::C::<f32>::from_words([words[0][k], words[1][k], words[2][k]]);
                }
            }
        });
    }

    /// Decodes `input` into `out` (same length), eight codes per step on AVX2 lanes where
    /// the processor has them (compiled for AVX-512VL where it has that too), else four on
    /// SSE2 lanes: the same bits as [`Encoder::decode`] on each.
    pub fn decode_slice(&self, input: &[C::C<f32>], out: &mut [[f32; 3]]) {
        self.decode_slice_on(Width::widest(), input, out)
    }

    /// [`Encoder::decode_slice`] on the given lanes; [`Width::Eight`] panics without AVX2,
    /// [`Width::EightAvx512`] without AVX-512VL.
    pub fn decode_slice_on(&self, width: Width, input: &[C::C<f32>], out: &mut [[f32; 3]]) {
        assert_eq!(
            input.len(),
            out.len(),
            "decode_slice: input and output lengths differ"
        );
        match width {
            Width::Four => self.decode_lanes::<F4, 4>(input, out),
            Width::Eight => {
                assert!(avx2_lanes::available(), "eight lanes need AVX2");
                // SAFETY: the processor has AVX2 (checked just above).
                unsafe { self.decode_avx2(input, out) }
            }
            Width::EightAvx512 => {
                assert!(
                    avx2_lanes::avx512_available(),
                    "eight lanes on AVX-512VL need AVX2, AVX-512F and AVX-512VL"
                );
                // SAFETY: the processor has all three (checked just above).
                unsafe { self.decode_avx512(input, out) }
            }
        }
    }

    /// [`Encoder::decode_slice`] on eight lanes, compiled for AVX2.
    ///
    /// # Safety
    /// The processor must have AVX2.
    #[cfg_attr(target_arch = "x86_64", target_feature(enable = "avx2"))]
    unsafe fn decode_avx2(&self, input: &[C::C<f32>], out: &mut [[f32; 3]]) {
        self.decode_lanes::<F8, WIDTH>(input, out)
    }

    /// [`Encoder::decode_slice`] on eight lanes, compiled for AVX-512VL ([`Width::EightAvx512`]).
    ///
    /// # Safety
    /// The processor must have AVX2, AVX-512F and AVX-512VL.
    #[cfg_attr(
        target_arch = "x86_64",
        target_feature(enable = "avx2,avx512f,avx512vl")
    )]
    unsafe fn decode_avx512(&self, input: &[C::C<f32>], out: &mut [[f32; 3]]) {
        self.decode_lanes::<F8, WIDTH>(input, out)
    }

    /// Decodes `N` codes per step on the lanes `L` ([`in_whole_groups`]).
    #[inline(always)]
    fn decode_lanes<L: LaneIo<N>, const N: usize>(
        &self,
        input: &[C::C<f32>],
        out: &mut [[f32; 3]],
    ) {
        let words = <C::C<f32> as Code<f32>>::WORDS;
        in_whole_groups(input, out, {
            #[inline(always)]
            |cs: &[C::C<f32>; N], os: &mut [[f32; 3]; N]| {
                let lane = {
                    #[inline(always)]
                    |j: usize| {
                        if j < words {
                            L::u_from_words(std::array::from_fn(|k| cs[k].word(j)))
                        } else {
                            L::U::c(0)
                        }
                    }
                };
                let code = C::C::<L>::from_words([lane(0), lane(1), lane(2)]);
                let v = decode_packed(&self.codec, code);
                L::u_to_items3(
                    [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()],
                    as_words_mut(os),
                );
            }
        });
    }
}

/// A group of vectors as their components' bits ([`LaneIo::u_from_items3`]'s items).
#[inline(always)]
fn as_words<const N: usize>(vs: &[[f32; 3]; N]) -> &[[u32; 3]; N] {
    cast_slice(vs).try_into().expect("N vectors")
}

/// [`as_words`] for writing.
#[inline(always)]
fn as_words_mut<const N: usize>(vs: &mut [[f32; 3]; N]) -> &mut [[u32; 3]; N] {
    cast_slice_mut(vs).try_into().expect("N vectors")
}

/// `group` on each whole group of `N` items of `input` and `out` (of equal lengths), then
/// on the last partial group padded with copies of its last item, of which only the real
/// items' outputs are kept. A whole group's length is known at compile time, so its loads
/// and stores need no per-item checks: with the partial group handled in the same loop,
/// those checks cost the eight-lane oct16 decoder more instructions than its arithmetic.
#[inline(always)]
fn in_whole_groups<I: Copy, O: Copy, const N: usize>(
    input: &[I],
    out: &mut [O],
    group: impl Fn(&[I; N], &mut [O; N]),
) {
    let mut ins = input.chunks_exact(N);
    let mut outs = out.chunks_exact_mut(N);
    for (i, o) in (&mut ins).zip(&mut outs) {
        group(
            i.try_into().expect("a whole group"),
            o.try_into().expect("a whole group"),
        );
    }
    let (i, o) = (ins.remainder(), outs.into_remainder());
    if let (Some(&last), Some(&first_out)) = (i.last(), o.first()) {
        let padded: [I; N] = std::array::from_fn(|k| *i.get(k).unwrap_or(&last));
        let mut full = [first_out; N];
        group(&padded, &mut full);
        o.copy_from_slice(&full[..o.len()]);
    }
}

/// A spec's packed encoder and decoder over slices, chosen at run time and compiled inside
/// unitpack: nothing here is generic, so none of it is instantiated in the calling crate.
///
/// [`Encoder`]'s methods are generic, so they are compiled with the caller's profile: in a
/// dependent crate's debug build, unoptimized (about 20× slower than release). `Batch`'s
/// code is unitpack's own, and with
///
/// ```toml
/// [profile.dev.package.unitpack]
/// opt-level = 3
/// ```
///
/// in the dependent crate's `Cargo.toml` it runs optimized in that debug build. It computes
/// the same bits as [`Encoder`] (the same model, evaluated eight vectors at a time on AVX2
/// lanes where the processor has them, else four on SSE2 lanes; `tests/api.rs` compares
/// them).
///
/// ```
/// use unitpack::api::Batch;
///
/// let oct = Batch::new("oct24p").unwrap();
/// let normals = [[0.0, 0.6, 0.8], [0.0, 0.0, -1.0]];
/// let mut codes = vec![0u32; normals.len() * oct.words()];
/// oct.encode(&normals, &mut codes);
/// let mut back = [[0f32; 3]; 2];
/// oct.decode(&codes, &mut back);
/// assert!((back[0][1] - 0.6).abs() < 1e-3);
/// ```
pub struct Batch {
    encode: Function,
    decode: Function,
}

impl Batch {
    /// The batch codec of a spec as the CLI takes it (`oct24p`, `oct24:layout=rgb8`).
    /// A packing helper (no encoder or decoder) is an error, and so is a tangent-frame
    /// spec, whose encoders take a frame rather than a vector (use [`FrameBatch`]).
    pub fn new(spec: &str) -> Result<Batch, SpecError> {
        let (encode, decode) = coders(
            spec,
            false,
            "codes tangent frames: a Batch encodes unit vectors (use FrameBatch)",
        )?;
        Ok(Batch { encode, decode })
    }

    /// 32-bit words per code: 1, 2 (`snorm16x3`, `float16x3`) or 3 (`float32x3`), first
    /// word first.
    pub fn words(&self) -> usize {
        self.encode.out_words
    }

    /// Encodes `input` into `out`, `words()` words per vector.
    pub fn encode(&self, input: &[[f32; 3]], out: &mut [u32]) {
        let w = self.words();
        assert_eq!(
            input.len() * w,
            out.len(),
            "Batch::encode: out must hold words() = {w} words per input vector"
        );
        self.encode.eval_many(cast_slice(input), out);
    }

    /// Decodes `codes` (`words()` words each) into `out`.
    pub fn decode(&self, codes: &[u32], out: &mut [[f32; 3]]) {
        let w = self.words();
        assert_eq!(
            codes.len(),
            out.len() * w,
            "Batch::decode: codes must hold words() = {w} words per output vector"
        );
        self.decode.eval_many(codes, cast_slice_mut(out));
    }
}

/// The CPU encoder and decoder of `spec` for [`Batch`] (`frames` false) or [`FrameBatch`]
/// (`frames` true): a spec of the other kind is an error saying `other` after its id, and
/// so is a packing helper (no encoder or decoder).
fn coders(spec: &str, frames: bool, other: &str) -> Result<(Function, Function), SpecError> {
    let spec: Spec = spec.parse()?;
    if spec.family().frames() != frames {
        return Err(SpecError::Invalid(format!("{} {other}", spec.id())));
    }
    let e = spec.emitted();
    let take = |role| e.cpu_function(role).cloned();
    match (take(Role::Encode), take(Role::Decode)) {
        (Some(encode), Some(decode)) => Ok((encode, decode)),
        _ => Err(SpecError::Invalid(format!(
            "{} is a helper, not a codec: it has no encode/decode",
            spec.id()
        ))),
    }
}

/// A tangent frame as a vertex holds it: the normal `n`, and the tangent `t` whose `w` is
/// the bitangent's sign (glTF's convention: bitangent = `cross(n, t.xyz)·t.w`). 28 bytes,
/// `n` then `t`: the layout of the frame streams' binary records and of the generated
/// functions' inputs and outputs, so that [`FrameBatch`] reads and writes slices of it in
/// place.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Frame {
    pub n: [f32; 3],
    pub t: [f32; 4],
}

// SAFETY: `Frame` is `repr(C)` and holds seven `f32` and nothing else: no padding (28
// bytes, alignment 4), every bit pattern a valid value, all zeros the zero frame.
unsafe impl wide::bytemuck::Zeroable for Frame {}
// SAFETY: as above; it is `Copy` and `'static`.
unsafe impl wide::bytemuck::Pod for Frame {}

/// A tangent-frame spec's packed encoder and decoder over slices of [`Frame`]
/// (`qtangent64`, `octangle32`, …), as [`Batch`] is a vector spec's: compiled inside
/// unitpack, eight frames per step on AVX2 lanes where the processor has them, else four
/// on SSE2 lanes, the same bits as the generated functions. Each spec's input policy (its
/// `unitpack list` entry) says what degenerate frames encode to.
///
/// ```
/// use unitpack::api::{Frame, FrameBatch};
///
/// let q = FrameBatch::new("qtangent64").unwrap();
/// let frames = [Frame { n: [0.0, 0.0, 1.0], t: [1.0, 0.0, 0.0, -1.0] }];
/// let mut codes = vec![0u32; frames.len() * q.words()];
/// q.encode(&frames, &mut codes);
/// let mut back = [Frame::default()];
/// q.decode(&codes, &mut back);
/// assert!((back[0].n[2] - 1.0).abs() < 1e-4 && (back[0].t[0] - 1.0).abs() < 1e-4);
/// assert_eq!(back[0].t[3], -1.0);
/// ```
pub struct FrameBatch {
    encode: Function,
    decode: Function,
}

impl FrameBatch {
    /// The batch codec of a tangent-frame spec. A vector spec is an error (use [`Batch`]).
    pub fn new(spec: &str) -> Result<FrameBatch, SpecError> {
        let (encode, decode) = coders(
            spec,
            true,
            "codes unit vectors: a FrameBatch encodes tangent frames (use Batch)",
        )?;
        Ok(FrameBatch { encode, decode })
    }

    /// 32-bit words per code, first word first: 1 (`octangle32`, `diamond32`) or 2.
    pub fn words(&self) -> usize {
        self.encode.out_words
    }

    /// Encodes `frames` into `out`, `words()` words per frame.
    pub fn encode(&self, frames: &[Frame], out: &mut [u32]) {
        let w = self.words();
        assert_eq!(
            frames.len() * w,
            out.len(),
            "FrameBatch::encode: out must hold words() = {w} words per frame"
        );
        self.encode.eval_many(cast_slice(frames), out);
    }

    /// Decodes `codes` (`words()` words each) into `out` (the sign, ±1, in `t[3]`).
    pub fn decode(&self, codes: &[u32], out: &mut [Frame]) {
        let w = self.words();
        assert_eq!(
            codes.len(),
            out.len() * w,
            "FrameBatch::decode: codes must hold words() = {w} words per output frame"
        );
        self.decode.eval_many(codes, cast_slice_mut(out));
    }
}

/// Codes moved from one spec to another: decoded by `from`'s decoder and encoded by `to`'s
/// encoder, as an asset pipeline moves normals between engines or formats. Each new code is
/// decoded again to measure how far it lands from the vector the old one stood for (the
/// error the move adds; the old code's own error is not known without the original
/// vectors).
///
/// ```
/// use unitpack::api::Transcoder;
///
/// let t = Transcoder::new("oct16", "oct24p").unwrap();
/// let mut new = vec![0u32; 2 * t.to_words()];
/// let error = t.transcode(&[0x0000, 0x7f7f], &mut new);
/// assert_eq!(error.records, 2);
/// assert!(error.max < 0.1);
/// ```
pub struct Transcoder {
    from: Batch,
    to: Batch,
}

impl Transcoder {
    /// The move from spec `from` to spec `to`, both as the CLI takes them.
    pub fn new(from: &str, to: &str) -> Result<Transcoder, SpecError> {
        Ok(Transcoder {
            from: Batch::new(from)?,
            to: Batch::new(to)?,
        })
    }

    /// 32-bit words per code read.
    pub fn from_words(&self) -> usize {
        self.from.words()
    }

    /// 32-bit words per code written.
    pub fn to_words(&self) -> usize {
        self.to.words()
    }

    /// Writes the new code of each of `codes` (`from_words()` words each) to `out`
    /// (`to_words()` each), and returns the angle between each old code's vector and its
    /// new code's, records numbered from 1. Bits above the `from` spec's width are
    /// ignored, as its decoder ignores them (the CLI refuses such codes).
    ///
    /// # Panics
    /// If `codes` is not whole codes or `out` has not room for exactly one new code each.
    pub fn transcode(&self, codes: &[u32], out: &mut [u32]) -> RoundTrip {
        let n = codes.len() / self.from_words();
        let mut vectors = vec![[0f32; 3]; n];
        self.from.decode(codes, &mut vectors);
        self.to.encode(&vectors, out);
        let mut back = vec![[0f32; 3]; n];
        self.to.decode(out, &mut back);
        vectors
            .iter()
            .zip(&back)
            .fold(RoundTrip::default(), |r, (a, b)| r.with(*a, *b))
    }
}

/// The angles between vectors and their round trips through another code, in degrees:
/// their count, sum and largest, and the record (from 1) where the largest is. A vector of
/// zero length, whose angle is undefined, counts as 180°.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RoundTrip {
    pub records: u64,
    pub sum: f64,
    pub max: f64,
    pub max_at: u64,
}

impl RoundTrip {
    /// The mean angle (0 for no records).
    pub fn mean(&self) -> f64 {
        if self.records == 0 {
            0.0
        } else {
            self.sum / self.records as f64
        }
    }

    /// One more record: the vector `a` and its round trip `b`.
    pub fn with(self, a: [f32; 3], b: [f32; 3]) -> RoundTrip {
        let angle = crate::measure::quality::angle_deg(a, b);
        let angle = if angle.is_nan() { 180.0 } else { angle };
        self.then(RoundTrip {
            records: 1,
            sum: angle,
            max: angle,
            max_at: 1,
        })
    }

    /// `self`'s records followed by `later`'s, renumbered after them; the first of equal
    /// largest angles keeps its place.
    pub fn then(self, later: RoundTrip) -> RoundTrip {
        let later_max = later.records > 0 && (self.records == 0 || later.max > self.max);
        RoundTrip {
            records: self.records + later.records,
            sum: self.sum + later.sum,
            max: if later_max { later.max } else { self.max },
            max_at: if later_max {
                self.records + later.max_at
            } else {
                self.max_at
            },
        }
    }
}
