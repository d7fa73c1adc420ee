//! The shader functions a spec emits, each with its `f32` evaluation on raw bits (what
//! the GPU output is compared against), the same generic function evaluated by the
//! adversarial [`Dev`] (what `crate::portability` measures), and the inputs it is verified on.

use super::codec::{Codec, Params, dequantize, pack, unpack};
use super::quant::Quant;
use super::spec::Spec;
use crate::model::Float;
use crate::model::avx2_lanes::{self, F8, WIDTH};
use crate::model::deviant::{Dev, DevU};
use crate::model::enclosure::{Encl, EnclU};
use crate::model::lanes::{F4, LaneIo, U4};
use crate::model::trace::{Module, Tf, define, trace_module};
use crate::model::{V2, V3, V4};
use std::sync::Arc;

/// Values that cross the verification boundary as raw 32-bit words (`W = u32`), or as
/// [`Lanes`] of four items' words at a time.
pub trait Bits<W = u32>: Sized {
    const WORDS: usize;
    fn read(w: &[W]) -> Self;
    fn write(self, w: &mut [W]);
}

/// One word of four items, for the [`F4`] evaluation.
pub type Lanes = [u32; 4];
/// One word of eight items, for the [`F8`] evaluation where the processor has AVX2 (of
/// four, never run, off x86-64).
pub type Lanes8 = [u32; WIDTH];

/// Float and integer lanes read and written through [`LaneIo`].
macro_rules! lane_bits {
    ($F:ty, $U:ty, $n:literal) => {
        impl Bits<[u32; $n]> for $F {
            const WORDS: usize = 1;
            #[inline(always)]
            fn read(w: &[[u32; $n]]) -> Self {
                <$F>::from_words(w[0])
            }
            #[inline(always)]
            fn write(self, w: &mut [[u32; $n]]) {
                w[0] = self.words();
            }
        }
        impl Bits<[u32; $n]> for $U {
            const WORDS: usize = 1;
            #[inline(always)]
            fn read(w: &[[u32; $n]]) -> Self {
                <$F>::u_from_words(w[0])
            }
            #[inline(always)]
            fn write(self, w: &mut [[u32; $n]]) {
                w[0] = <$F>::u_words(self);
            }
        }
    };
}
lane_bits!(F4, U4, 4);
#[cfg(target_arch = "x86_64")]
lane_bits!(F8, crate::model::avx2_lanes::U8, 8);
impl Bits for f32 {
    const WORDS: usize = 1;
    #[inline(always)]
    fn read(w: &[u32]) -> Self {
        f32::from_bits(w[0])
    }
    fn write(self, w: &mut [u32]) {
        w[0] = self.to_bits();
    }
}
impl Bits for u32 {
    const WORDS: usize = 1;
    #[inline(always)]
    fn read(w: &[u32]) -> Self {
        w[0]
    }
    fn write(self, w: &mut [u32]) {
        w[0] = self;
    }
}
impl Bits for Dev {
    const WORDS: usize = 1;
    #[inline(always)]
    fn read(w: &[u32]) -> Self {
        Dev::new(f32::from_bits(w[0]))
    }
    fn write(self, w: &mut [u32]) {
        w[0] = self.value().to_bits();
    }
}
impl Bits for DevU {
    const WORDS: usize = 1;
    #[inline(always)]
    fn read(w: &[u32]) -> Self {
        DevU(w[0])
    }
    fn write(self, w: &mut [u32]) {
        w[0] = self.0;
    }
}
impl<W, T: Bits<W> + crate::model::Lane> Bits<W> for V2<T> {
    const WORDS: usize = 2;
    #[inline(always)]
    fn read(w: &[W]) -> Self {
        V2::new(T::read(&w[0..]), T::read(&w[1..]))
    }
    #[inline(always)]
    fn write(self, w: &mut [W]) {
        self.x.write(&mut w[0..]);
        self.y.write(&mut w[1..]);
    }
}
/// Several arguments, one after the other.
impl<W, A: Bits<W>, B: Bits<W>> Bits<W> for (A, B) {
    const WORDS: usize = A::WORDS + B::WORDS;
    #[inline(always)]
    fn read(w: &[W]) -> Self {
        (A::read(w), B::read(&w[A::WORDS..]))
    }
    #[inline(always)]
    fn write(self, w: &mut [W]) {
        self.0.write(w);
        self.1.write(&mut w[A::WORDS..]);
    }
}
impl<W, T: Bits<W> + crate::model::Lane> Bits<W> for V3<T> {
    const WORDS: usize = 3;
    #[inline(always)]
    fn read(w: &[W]) -> Self {
        V3::new(T::read(&w[0..]), T::read(&w[1..]), T::read(&w[2..]))
    }
    #[inline(always)]
    fn write(self, w: &mut [W]) {
        self.x.write(&mut w[0..]);
        self.y.write(&mut w[1..]);
        self.z.write(&mut w[2..]);
    }
}
impl<W, T: Bits<W> + crate::model::Lane> Bits<W> for V4<T> {
    const WORDS: usize = 4;
    #[inline(always)]
    fn read(w: &[W]) -> Self {
        V4::new(
            T::read(&w[0..]),
            T::read(&w[1..]),
            T::read(&w[2..]),
            T::read(&w[3..]),
        )
    }
    #[inline(always)]
    fn write(self, w: &mut [W]) {
        self.x.write(&mut w[0..]);
        self.y.write(&mut w[1..]);
        self.z.write(&mut w[2..]);
        self.w.write(&mut w[3..]);
    }
}

/// What a function is verified on.
#[derive(Clone, Debug, PartialEq)]
pub enum Inputs {
    /// Seeded random unit vectors plus every edge case (3 words each).
    Vectors,
    /// Packed codes with the given fields: all of them up to 24 bits, else seeded random ones.
    Codes(Vec<Quant>),
    /// Float parameters as a texture fetch delivers them (`c/M`), for the same codes.
    FloatCodes(Vec<Quant>),
    /// [`Inputs::Vectors`], each followed by the words [`Extra`] computes from it: the
    /// model's own texture fetch for a function that takes the fetched value beside the
    /// vector.
    VectorsWith(Extra),
    /// [`Inputs::Codes`] of the fields, each code followed by every index below the
    /// bound in turn (two words an item): a function of a code and a small integer, such
    /// as the texel of a precise search's `k`-th candidate.
    CodesAndIndex(Vec<Quant>, u32),
    /// [`Inputs::Codes`] of the fields (one word each), each followed by the words
    /// [`Extra`] computes from it: the model's own fetches for a decoder stage that takes
    /// fetched table entries beside the code.
    CodesWith(Vec<Quant>, Extra),
}

/// One item's words → other words (a table lookup, the model's own fetch).
pub type WordsMap = Arc<dyn Fn(&[u32]) -> Vec<u32> + Send + Sync>;

/// What [`Inputs::VectorsWith`] appends to each vector (and [`Inputs::CodesWith`] to
/// each code).
#[derive(Clone)]
pub struct Extra {
    /// What the words are, for messages.
    pub name: &'static str,
    pub words: usize,
    /// A vector's three words (a code's one) → the extra words.
    pub of: WordsMap,
}

/// The same map, not merely the same name: two specs' fetches from different tables
/// share a name, and each `emitted()` builds its own map, so equal inputs are the same
/// `Inputs` value.
impl PartialEq for Extra {
    fn eq(&self, o: &Extra) -> bool {
        Arc::ptr_eq(&self.of, &o.of)
    }
}

impl std::fmt::Debug for Extra {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} ({} words)", self.name, self.words)
    }
}

/// What a function does, for its doc comment.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    Encode,
    Decode,
    EncodeFloat,
    DecodeFloat,
    Pack,
    Unpack,
    /// A helper that combines decoded values (the second seed's detail combine).
    Combine,
    /// The integer texel of a lookup table that an encoder or decoder reads.
    LutTexel,
}

/// A model of a function on raw words: one item in, one item out.
pub type Eval = Arc<dyn Fn(&[u32], &mut [u32]) + Send + Sync>;
/// The same on any number of items at once (`in_words` each in, `out_words` out), on SIMD
/// lanes: groups of four or eight items transposed into lanes, evaluated together and
/// transposed back, inside the function compiled for those lanes.
pub type LanesEval = Arc<dyn Fn(&[u32], &mut [u32]) + Send + Sync>;

/// Which lanes [`Function::eval_many_on`] evaluates on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Width {
    /// [`Function::eval_lanes`]: four SSE2 lanes, on every x86-64 processor.
    Four,
    /// [`Function::eval_lanes8`]: eight AVX2 lanes.
    Eight,
    /// The same eight lanes compiled for AVX-512VL too, where the processor has it:
    /// compares into mask registers, one-instruction selects and 32 registers. On an Intel
    /// Xeon, where `vblendvps` is several micro-operations, the typed oct16 decoder went
    /// from 0.87–0.93× meshoptimizer's to 1.02–1.60× with it; on AMD's Zen 4, where it is
    /// one, it runs about a seventh slower (README, "Speed"). The typed slices of [`crate::api::Encoder`] have this copy;
    /// [`Function::eval_many_on`] runs [`Width::Eight`] for it, since a second copy of
    /// every function's lanes would cost the build more than the batches gain.
    EightAvx512,
}

impl Width {
    /// The widest this processor runs: what the CPU batches use.
    pub fn widest() -> Width {
        if avx2_lanes::avx512_available() {
            Width::EightAvx512
        } else if avx2_lanes::available() {
            Width::Eight
        } else {
            Width::Four
        }
    }
}

/// One emitted function.
#[derive(Clone)]
pub struct Function {
    /// Local name; the emitted name is `{prefix}{namespace}_{name}`.
    pub name: &'static str,
    pub role: Role,
    pub inputs: Inputs,
    pub in_words: usize,
    pub out_words: usize,
    /// The `f32` model on raw bits: one item of `in_words` in, `out_words` out.
    pub eval: Eval,
    /// The same generic function evaluated with [`Dev`], which deviates as the
    /// thread's [`crate::model::deviant::with`] says (and equals `eval` when nothing is set).
    pub eval_dev: Eval,
    /// The same generic function evaluated on four items at once with [`F4`]: what the
    /// CPU batches run without AVX2, bit for bit `eval` on each item.
    pub eval_lanes: LanesEval,
    /// The same on eight items at once with [`F8`], compiled for AVX2: what the CPU
    /// batches run where the processor has it, bit for bit `eval` on each item.
    pub eval_lanes8: LanesEval,
    /// For a decoder: the same generic function evaluated with [`Encl`] over a box of
    /// codes, which [`crate::decode_bound`] refines into a proven deviation bound.
    pub enclose: Option<Enclose>,
    /// For a CPU-only [`Emitted::cpu`] function: the emitted functions it chains around
    /// its table fetch, whose costs add up to its own.
    pub parts: Vec<&'static str>,
}

impl Function {
    /// Runs the function on every item of `input` (`in_words` words each) into `output`
    /// (`out_words` each) on the widest lanes this processor has ([`Width::widest`]), bit
    /// for bit [`Function::eval`] on each item.
    pub fn eval_many(&self, input: &[u32], output: &mut [u32]) {
        self.eval_many_on(Width::widest(), input, output)
    }

    /// [`Function::eval_many`] on the given lanes: a block of groups per call, transposed
    /// in and out. A last partial group repeats its last item in the spare lanes and
    /// writes only the real ones. [`Width::Eight`] and [`Width::EightAvx512`] (the same
    /// AVX2 code here) panic without AVX2.
    pub fn eval_many_on(&self, width: Width, input: &[u32], output: &mut [u32]) {
        let (iw, ow) = (self.in_words, self.out_words);
        let n = input.len() / iw;
        assert_eq!(
            n * iw,
            input.len(),
            "{} input words, {iw} per item",
            input.len()
        );
        assert_eq!(
            n * ow,
            output.len(),
            "{} outputs for {n} items",
            output.len()
        );
        let eval = match width {
            Width::Four => &self.eval_lanes,
            Width::Eight | Width::EightAvx512 => &self.eval_lanes8,
        };
        // Blocks that keep a table function's intermediate items in cache.
        const BLOCK: usize = 1024;
        for (i, o) in input.chunks(BLOCK * iw).zip(output.chunks_mut(BLOCK * ow)) {
            eval(i, o)
        }
    }
}

/// The widest item a lane evaluation takes or returns, in words (a precise search's
/// vector and fetched texels).
const MAX_WORDS: usize = 32;

/// `f` on every item of `input` into `output`, `N` items per group: each group's words
/// transposed into lanes on the stack, evaluated, and transposed back. A last partial
/// group repeats its last item in the spare lanes and writes only the real ones. Inlined
/// into the function compiled for the lanes, so the transposes are too.
#[inline(always)]
fn in_groups<L: LaneIo<N>, A: Bits<[u32; N]>, R: Bits<[u32; N]>, const N: usize>(
    f: &impl Fn(A) -> R,
    input: &[u32],
    output: &mut [u32],
) {
    let (iw, ow) = (A::WORDS, R::WORDS);
    assert!(
        iw <= MAX_WORDS && ow <= MAX_WORDS,
        "items of at most {MAX_WORDS} words"
    );
    let mut lanes_in = [[0u32; N]; MAX_WORDS];
    let mut lanes_out = [[0u32; N]; MAX_WORDS];
    let (lanes_in, lanes_out) = (&mut lanes_in[..iw], &mut lanes_out[..ow]);
    let mut src = input.chunks_exact(N * iw);
    let mut dst = output.chunks_exact_mut(N * ow);
    for (s, d) in (&mut src).zip(&mut dst) {
        to_lanes::<L, N>(s, lanes_in);
        f(A::read(lanes_in)).write(lanes_out);
        from_lanes::<L, N>(lanes_out, d);
    }
    let (s, d) = (src.remainder(), dst.into_remainder());
    let items = s.len() / iw;
    if items > 0 {
        for (j, lane) in lanes_in.iter_mut().enumerate() {
            for (k, l) in lane.iter_mut().enumerate() {
                *l = s[k.min(items - 1) * iw + j];
            }
        }
        f(A::read(lanes_in)).write(lanes_out);
        for (k, item) in d.chunks_exact_mut(ow).enumerate() {
            for (o, lane) in item.iter_mut().zip(lanes_out.iter()) {
                *o = lane[k];
            }
        }
    }
}

/// One whole group of `N` items (`s`, `N·lanes.len()` words) into lanes. Items of three
/// words (vectors) take the lanes' own transposes ([`LaneIo::u_from_items3`]), other items
/// of 1 to 4 words (codes) go through fixed-size arrays ([`to_lanes_of`]).
#[inline(always)]
fn to_lanes<L: LaneIo<N>, const N: usize>(s: &[u32], lanes: &mut [[u32; N]]) {
    match lanes.len() {
        1 => to_lanes_of::<1, N>(s, lanes),
        2 => to_lanes_of::<2, N>(s, lanes),
        3 => {
            let items = s.as_chunks::<3>().0.try_into().expect("a whole group");
            for (lane, u) in lanes.iter_mut().zip(L::u_from_items3(items)) {
                *lane = L::u_words(u);
            }
        }
        4 => to_lanes_of::<4, N>(s, lanes),
        w => {
            for (j, lane) in lanes.iter_mut().enumerate() {
                for (k, l) in lane.iter_mut().enumerate() {
                    *l = s[k * w + j];
                }
            }
        }
    }
}

/// [`to_lanes`] for items of `W` words. A group as a fixed-size array of fixed-size items
/// is what LLVM moves with whole-register loads and shuffles; indexed through slices, the
/// eight-lane decoders' three outputs went out as six 128-bit stores and 15 % slower.
#[inline(always)]
fn to_lanes_of<const W: usize, const N: usize>(s: &[u32], lanes: &mut [[u32; N]]) {
    let items: &[[u32; W]; N] = s.as_chunks::<W>().0.try_into().expect("a whole group");
    let lanes: &mut [[u32; N]; W] = lanes.try_into().expect("W lanes");
    for k in 0..N {
        for j in 0..W {
            lanes[j][k] = items[k][j];
        }
    }
}

/// Lanes into one whole group of `N` items (`d`, `N·lanes.len()` words), as [`to_lanes`]
/// ([`LaneIo::u_to_items3`] for three words).
#[inline(always)]
fn from_lanes<L: LaneIo<N>, const N: usize>(lanes: &[[u32; N]], d: &mut [u32]) {
    match lanes.len() {
        1 => from_lanes_of::<1, N>(lanes, d),
        2 => from_lanes_of::<2, N>(lanes, d),
        3 => {
            let items = d.as_chunks_mut::<3>().0.try_into().expect("a whole group");
            let u = {
                #[inline(always)]
                |j: usize| L::u_from_words(lanes[j])
            };
            L::u_to_items3([u(0), u(1), u(2)], items);
        }
        4 => from_lanes_of::<4, N>(lanes, d),
        w => {
            for (k, item) in d.chunks_exact_mut(w).enumerate() {
                for (o, lane) in item.iter_mut().zip(lanes) {
                    *o = lane[k];
                }
            }
        }
    }
}

/// [`from_lanes`] for items of `W` words, as [`to_lanes_of`].
#[inline(always)]
fn from_lanes_of<const W: usize, const N: usize>(lanes: &[[u32; N]], d: &mut [u32]) {
    let items: &mut [[u32; W]; N] = d.as_chunks_mut::<W>().0.try_into().expect("a whole group");
    let lanes: &[[u32; N]; W] = lanes.try_into().expect("W lanes");
    for k in 0..N {
        for j in 0..W {
            items[k][j] = lanes[j][k];
        }
    }
}

/// One inclusive range per field → an enclosure per output lane.
pub type BoxEval = Arc<dyn Fn(&[(i64, i64)]) -> Vec<Encl> + Send + Sync>;

/// A decoder over boxes of codes, for [`crate::decode_bound`].
#[derive(Clone)]
pub struct Enclose {
    /// One inclusive range per field (signed codes for the float form, raw bit fields for
    /// the packed form) → an enclosure per output lane.
    pub eval: BoxEval,
    /// A field the boxes take one value of at a time ([`Codec::whole_field`]).
    pub whole_field: Option<usize>,
    /// Fields the decoder does not read ([`Codec::unread_fields`]): proven at one value.
    pub unread: &'static [usize],
}

/// A [`Function`] from its `f32`, [`Dev`], [`F4`] and [`F8`] instantiations of one
/// generic function (`generic_function!` below writes all four from one body).
#[allow(clippy::too_many_arguments)]
pub(crate) fn function<A, R, AD, RD, AL, RL, AW, RW>(
    name: &'static str,
    role: Role,
    inputs: Inputs,
    f: impl Fn(A) -> R + Send + Sync + 'static,
    f_dev: impl Fn(AD) -> RD + Send + Sync + 'static,
    f_lanes: impl Fn(AL) -> RL + Send + Sync + 'static,
    f_lanes8: impl Fn(AW) -> RW + Send + Sync + 'static,
) -> Function
where
    A: Bits + 'static,
    R: Bits + 'static,
    AD: Bits + 'static,
    RD: Bits + 'static,
    AL: Bits<Lanes> + 'static,
    RL: Bits<Lanes> + 'static,
    AW: Bits<Lanes8> + 'static,
    RW: Bits<Lanes8> + 'static,
{
    assert_eq!((A::WORDS, R::WORDS), (AD::WORDS, RD::WORDS));
    assert_eq!((A::WORDS, R::WORDS), (AL::WORDS, RL::WORDS));
    assert_eq!((A::WORDS, R::WORDS), (AW::WORDS, RW::WORDS));
    Function {
        name,
        role,
        inputs,
        in_words: A::WORDS,
        out_words: R::WORDS,
        eval: Arc::new(move |i, o| f(A::read(i)).write(o)),
        eval_dev: Arc::new(move |i, o| f_dev(AD::read(i)).write(o)),
        eval_lanes: Arc::new(move |i, o| in_groups::<F4, _, _, 4>(&f_lanes, i, o)),
        eval_lanes8: Arc::new(move |i, o| {
            assert!(
                avx2_lanes::available(),
                "{name}: the eight-lane evaluation needs a processor with AVX2"
            );
            // SAFETY: the processor has AVX2 (checked just above).
            unsafe { on_avx2(&f_lanes8, i, o) }
        }),
        enclose: None,
        parts: Vec::new(),
    }
}

/// [`in_groups`] of `f` on eight lanes, compiled for AVX2: `f` and everything it calls
/// inline here (the lane operations are `#[inline(always)]`), so the [`F8`] operations
/// become AVX2 instructions rather than calls.
///
/// # Safety
/// The processor must have AVX2.
#[cfg_attr(target_arch = "x86_64", target_feature(enable = "avx2"))]
unsafe fn on_avx2<A: Bits<Lanes8>, R: Bits<Lanes8>>(f: &impl Fn(A) -> R, i: &[u32], o: &mut [u32]) {
    in_groups::<F8, _, _, WIDTH>(f, i, o)
}

/// `generic_function!(name, role, inputs, <F> [captures] |x: Type<F>| body)`: a [`Function`]
/// whose `eval`, `eval_dev`, `eval_lanes` and `eval_lanes8` are the one generic `body`
/// with `F` = `f32`, [`Dev`], [`F4`] and [`F8`], so neither the adversarial nor the
/// lane evaluations can drift from the reference. Each capture is cloned into all four
/// closures.
macro_rules! generic_function {
    ($name:expr, $role:expr, $inputs:expr, <$F:ident> [$($c:ident),*] |$x:ident: $A:ty| $body:expr) => {
        $crate::codecs::functions::function(
            $name,
            $role,
            $inputs,
            {
                $(let $c = $c.clone();)*
                type $F = f32;
                move |$x: $A| $body
            },
            {
                $(let $c = $c.clone();)*
                type $F = $crate::model::deviant::Dev;
                move |$x: $A| $body
            },
            {
                $(let $c = $c.clone();)*
                type $F = $crate::model::lanes::F4;
                move |$x: $A| $body
            },
            {
                $(let $c = $c.clone();)*
                type $F = $crate::model::avx2_lanes::F8;
                #[inline(always)]
                move |$x: $A| $body
            },
        )
    };
}
pub(crate) use generic_function;

/// The traced module and the public functions of one spec.
pub struct Emitted {
    pub module: Module,
    pub functions: Vec<Function>,
    /// Prefix for every function name of the spec (its id, or empty for helpers-only specs).
    pub namespace: String,
    /// Whether the packed encoder is portable (fast with [`Codec::EXACT_ROUNDING`], or
    /// precise with [`Codec::EXACT_SEARCH`]): its
    /// doc comment says so, and tests/portability.rs holds it to that under every
    /// guaranteed deviation class.
    pub portable_encoder: bool,
    /// CPU-only functions that stand in for a role the shader splits around a texture
    /// fetch (`encode` = texel, fetch from the table in memory, `encode(v, fetched)`):
    /// what `Batch`, the CLI and the error statistics run. Never emitted; their parts are.
    pub cpu: Vec<Function>,
}

/// For each function of each of `emitted` (spec by spec, in order), the first function
/// before it (its spec's index, its index there) with the same code
/// ([`Module::identity`]) and equal inputs, if there is one. Such a function computes
/// exactly what the first one does, item by item and under any deviation: its emitted
/// text differs in the names' prefix alone, and its model is the same traced computation.
pub fn first_with_same_code(emitted: &[Emitted]) -> Vec<Vec<Option<(usize, usize)>>> {
    // Identity → the inputs met with it and where first.
    type Seen<'a> = Vec<(&'a Inputs, (usize, usize))>;
    let mut first: std::collections::HashMap<String, Seen> = Default::default();
    emitted
        .iter()
        .enumerate()
        .map(|(i, e)| {
            e.functions
                .iter()
                .enumerate()
                .map(|(j, f)| {
                    let seen = first.entry(e.module.identity(f.name)).or_default();
                    match seen.iter().find(|(inputs, _)| **inputs == f.inputs) {
                        Some(&(_, at)) => Some(at),
                        None => {
                            seen.push((&f.inputs, (i, j)));
                            None
                        }
                    }
                })
                .collect()
        })
        .collect()
}

impl Emitted {
    /// The CPU function of `role`: a [`Emitted::cpu`] stand-in, else the emitted one.
    pub fn cpu_function(&self, role: Role) -> Option<&Function> {
        self.cpu
            .iter()
            .chain(&self.functions)
            .find(|f| f.role == role)
    }
}

/// The four functions of a codec spec (`decode_float`, `decode`, `encode_float`,
/// `encode`), traced once and evaluated by the same generic code.
pub(crate) fn codec_functions<C: Codec + Clone + 'static>(spec: &Spec, c: C) -> Emitted
where
    C::P<f32>: Bits,
    C::C<f32>: Bits,
    C::P<Dev>: Bits,
    C::C<Dev>: Bits,
    C::P<F4>: Bits<Lanes>,
    C::C<F4>: Bits<Lanes>,
    C::P<F8>: Bits<Lanes8>,
    C::C<F8>: Bits<Lanes8>,
{
    let precise = spec.precise();
    let module = trace_module(
        #[inline(always)]
        || trace_codec(&c, precise),
    );
    let mut functions = codec_decoders(&c);
    functions.extend([
        generic_function!(
            "encode_float",
            Role::EncodeFloat,
            Inputs::Vectors,
            <F> [c] |v: V3<F>| encode_float(&c, precise, v)
        ),
        generic_function!(
            "encode",
            Role::Encode,
            Inputs::Vectors,
            <F> [c] |v: V3<F>| encode_packed(&c, precise, v)
        ),
    ]);
    if let Some(name) = c.alternate() {
        functions.push(generic_function!(
            name,
            Role::Encode,
            Inputs::Vectors,
            <F> [c] |v: V3<F>| encode_alternate(&c, precise, v)
        ));
    }
    Emitted {
        module,
        functions,
        namespace: spec.id(),
        portable_encoder: if precise {
            C::EXACT_SEARCH
        } else {
            C::EXACT_ROUNDING
        },
        cpu: Vec::new(),
    }
}

/// A codec's `decode_float` and `decode`, with the enclosures their bounds are proven
/// by: what a spec whose encoders are its own (a table codec) shares with the codec
/// whose texels it writes. Traced by [`trace_decoders`].
pub(crate) fn codec_decoders<C: Codec + Clone + 'static>(c: &C) -> Vec<Function>
where
    C::P<f32>: Bits,
    C::C<f32>: Bits,
    C::P<Dev>: Bits,
    C::C<Dev>: Bits,
    C::P<F4>: Bits<Lanes>,
    C::C<F4>: Bits<Lanes>,
    C::P<F8>: Bits<Lanes8>,
    C::C<F8>: Bits<Lanes8>,
{
    let q = c.quants();
    let fetch_box = {
        let c = c.clone();
        move |r: &[(i64, i64)]| {
            let p = C::P::<Encl>::build(
                #[inline(always)]
                |i| fetched_range(q[i], r[i]),
            );
            c.direction(p).to_array().to_vec()
        }
    };
    let field_box = {
        let c = c.clone();
        move |r: &[(i64, i64)]| {
            let codes = C::P::<Encl>::build(
                #[inline(always)]
                |i| field_codes(q[i], r[i]),
            );
            c.decode_codes(codes).to_array().to_vec()
        }
    };
    let c = c.clone();
    let mut functions = vec![
        generic_function!(
            "decode_float",
            Role::DecodeFloat,
            Inputs::FloatCodes(q.to_vec()),
            <F> [c] |p: C::P<F>| c.direction(p)
        ),
        generic_function!(
            "decode",
            Role::Decode,
            Inputs::Codes(q.to_vec()),
            <F> [c] |code: C::C<F>| decode_packed(&c, code)
        ),
    ];
    let whole_field = c.whole_field();
    let unread = c.unread_fields();
    functions[0].enclose = Some(Enclose {
        eval: Arc::new(fetch_box),
        whole_field,
        unread,
    });
    functions[1].enclose = Some(Enclose {
        eval: Arc::new(field_box),
        whole_field,
        unread,
    });
    functions
}

/// How [`through_table`] chains two lane evaluations around a lookup.
struct Chain {
    iw: usize,
    mid: usize,
    second_in: usize,
    keep_input: bool,
    lookup: WordsMap,
}

impl Chain {
    /// `a` on the items, the lookup item by item, then `b`: each part on its lanes.
    fn chain(&self, a: &LanesEval, b: &LanesEval) -> LanesEval {
        let (a, b, lookup) = (a.clone(), b.clone(), self.lookup.clone());
        let Chain {
            iw,
            mid,
            second_in,
            keep_input,
            ..
        } = *self;
        Arc::new(move |i: &[u32], o: &mut [u32]| {
            let n = i.len() / iw;
            let mut t = vec![0u32; n * mid];
            a(i, &mut t);
            let mut arg = Vec::with_capacity(n * second_in);
            for (item, t) in i.chunks_exact(iw).zip(t.chunks_exact(mid)) {
                if keep_input {
                    arg.extend_from_slice(item);
                }
                arg.extend(lookup(t));
            }
            assert_eq!(arg.len(), n * second_in, "the lookup's words");
            b(&arg, o)
        })
    }
}

/// A CPU-only function through a table in memory: `first`, then `lookup` of its
/// output words (one item's), then `second` on the lookup's words, after the item's own
/// input words where `keep_input`. Each evaluation (`f32`, [`Dev`], four lanes) chains
/// the parts' own, so it is bit for bit the emitted functions around a fetch that
/// returns what `lookup` does.
pub fn through_table(
    name: &'static str,
    role: Role,
    inputs: Inputs,
    first: &Function,
    lookup: WordsMap,
    second: &Function,
    keep_input: bool,
) -> Function {
    let (iw, mid) = (first.in_words, first.out_words);
    let kept = if keep_input { iw } else { 0 };
    assert!(
        second.in_words > kept,
        "{name}: {} takes {} words, fewer than the kept input and a lookup",
        second.name,
        second.in_words
    );
    let want = second.in_words;
    let chain = |a: &Eval, b: &Eval| -> Eval {
        let (a, b, lookup) = (a.clone(), b.clone(), lookup.clone());
        Arc::new(move |i: &[u32], o: &mut [u32]| {
            let mut t = vec![0u32; mid];
            a(i, &mut t);
            // A caller's item may sit in a longer buffer: keep its own words only.
            let mut arg = if keep_input {
                i[..iw].to_vec()
            } else {
                Vec::new()
            };
            arg.extend(lookup(&t));
            assert_eq!(arg.len(), want, "the lookup's words and the kept input");
            b(&arg, o)
        })
    };
    let lanes = Chain {
        iw,
        mid,
        second_in: second.in_words,
        keep_input,
        lookup: lookup.clone(),
    };
    Function {
        name,
        role,
        inputs,
        in_words: iw,
        out_words: second.out_words,
        eval: chain(&first.eval, &second.eval),
        eval_dev: chain(&first.eval_dev, &second.eval_dev),
        eval_lanes: lanes.chain(&first.eval_lanes, &second.eval_lanes),
        eval_lanes8: lanes.chain(&first.eval_lanes8, &second.eval_lanes8),
        enclose: None,
        parts: vec![first.name, second.name],
    }
}

/// The values a texture fetch returns for the codes `c0..=c1` (`c/M` correctly rounded,
/// snorm at least -1; for a float field, its finite values in order, see
/// [`float_code_range`]): monotone in `c`, so the bounds are the ends'. Every nonzero
/// one is at least `1/M`, so all are multiples of the f32 spacing at `1/M` (of `2^-24`,
/// the least f16, for halves; of `2^-149`, the least denormal, for f32 fields).
pub(crate) fn fetched_range(q: Quant, (c0, c1): (i64, i64)) -> Encl {
    let (at, grid): (fn(Quant, i64) -> f32, f64) = match q {
        Quant::Half | Quant::Single => (float_of_ordinal, float_grid(q)),
        _ => (
            |q, c| crate::codecs::inputs::fetched(q, c as f32),
            crate::model::enclosure::ulp(f64::from(1.0 / q.max_code())),
        ),
    };
    Encl::range(f64::from(at(q, c0)), f64::from(at(q, c1)), grid)
}

/// The spacing every value of a float field is a multiple of: the least f16 (`2^-24`),
/// or for an f32 field the least denormal (`2^-149`).
fn float_grid(q: Quant) -> f64 {
    match q {
        Quant::Half => 1.0 / f64::from(1u32 << 24),
        _ => f64::from(f32::from_bits(1)),
    }
}

/// The codes in the raw fields `lo..=hi`: [`Quant::from_field`] evaluated over the range.
/// A float field's conversion ([`crate::codecs::half::half_value`], or the f32 bits
/// themselves) is integer operations and at most one exact product with a normal result,
/// so no deviation class can move it; its bit manipulation has no useful interval form,
/// so its enclosure is taken directly as the exact values of the range: monotone within a
/// sign, finite or not. Infinities and NaNs stand as infinities, which every decoder only
/// compares (`|x| ≤ MAX` is false for both) before replacing them.
fn field_codes(q: Quant, (lo, hi): (i64, i64)) -> Encl {
    if !q.is_float() {
        return q.from_field(EnclU::range(lo as u64, hi as u64));
    }
    let (lo, hi) = (lo as u32, hi as u32);
    let b = q.bits();
    let magnitude = q.mask() >> 1;
    let inf = match q {
        Quant::Half => 0x7c00,
        _ => 0x7f80_0000,
    };
    let negative = lo >> (b - 1) == 1;
    let special = |h: u32| h & magnitude >= inf;
    if lo >> (b - 1) != hi >> (b - 1) || special(lo) != special(hi) {
        return Encl::unknown();
    }
    if special(lo) {
        let inf = if negative {
            f64::NEG_INFINITY
        } else {
            f64::INFINITY
        };
        return Encl::range(inf, inf, 0.0);
    }
    let (a, c) = (
        f64::from(q.from_field::<f32>(lo)),
        f64::from(q.from_field::<f32>(hi)),
    );
    Encl::range(a.min(c), a.max(c), float_grid(q))
}

/// The codes a float-form decoder is proven over, as ordered integers: `min..=max` of
/// the integer codes, or for a float field its finite values numbered in order of value
/// (`k ≥ 0` the `k`-th non-negative one, `-k` its negative): `-0x7bff..=0x7bff` for halves
/// (`k` is the half's bits); for f32, zero and the normal values (`k` is the bits less the
/// `2^23 - 1` denormal patterns). f32 denormals are left out because the f32 decoder reads
/// them as `+0` before any arithmetic (an implementation may flush them); numbered in,
/// they would make the all-zero stand-in a cube of `2^24` values a side whose surface no
/// refinement of boxes resolves.
pub fn float_code_range(q: Quant) -> (i64, i64) {
    match q {
        Quant::Half => (-0x7bff, 0x7bff),
        Quant::Single => (-SINGLE_ORDINALS, SINGLE_ORDINALS),
        _ => (q.min_code() as i64, q.max_code() as i64),
    }
}

/// The largest f32 ordinal of [`float_code_range`]: `f32::MAX`'s bits less the denormals.
const SINGLE_ORDINALS: i64 = 0x7f7f_ffff - DENORMALS;
const DENORMALS: i64 = 0x7f_ffff;

/// The finite value of a float field numbered `k` by [`float_code_range`].
fn float_of_ordinal(q: Quant, k: i64) -> f32 {
    let n = k.unsigned_abs();
    let v = match q {
        Quant::Half => crate::codecs::half::half_value::<f32>(n as u32),
        _ if n == 0 => 0.0,
        _ => f32::from_bits((n + DENORMALS as u64) as u32),
    };
    if k < 0 { -v } else { v }
}

/// The packed decoder: unpack, then [`Codec::decode_codes`].
#[inline(always)]
pub fn decode_packed<F: Float, C: Codec>(c: &C, code: C::C<F>) -> V3<F> {
    c.decode_codes(unpack(&c.quants(), code))
}

/// Integer codes of an encoder: the precise search (through the `encode_codes` helper),
/// or the nearest codes of the `encode_float` helper's parameters.
#[inline(always)]
fn codes_of<F: Float, C: Codec>(c: &C, precise: bool, v: V3<F>) -> C::P<F> {
    if precise {
        F::call(
            "encode_codes",
            v,
            #[inline(always)]
            |v| c.precise_codes(v),
        )
    } else if C::EXACT_ROUNDING {
        F::call(
            "round_codes",
            v,
            #[inline(always)]
            |v| c.round_codes(v),
        )
    } else {
        c.round_codes(v)
    }
}

/// The packed encoder.
#[inline(always)]
pub fn encode_packed<F: Float, C: Codec>(c: &C, precise: bool, v: V3<F>) -> C::C<F> {
    pack(&c.quants(), codes_of(c, precise, v))
}

/// The packed [`Codec::alternate`] encoder.
#[inline(always)]
pub fn encode_alternate<F: Float, C: Codec>(c: &C, precise: bool, v: V3<F>) -> C::C<F> {
    pack(&c.quants(), c.alternate_codes(codes_of(c, precise, v)))
}

/// Float-form encoder output: the exact parameters for the hardware to round (fast), or
/// the chosen codes' values (precise), which the hardware's rounding keeps.
#[inline(always)]
pub fn encode_float<F: Float, C: Codec>(c: &C, precise: bool, v: V3<F>) -> C::P<F> {
    if precise {
        dequantize(
            &c.quants(),
            F::call(
                "encode_codes",
                v,
                #[inline(always)]
                |v| c.precise_codes(v),
            ),
        )
    } else {
        c.params(v)
    }
}

/// Defines [`codec_decoders`]' functions in the module being traced.
pub fn trace_decoders<C: Codec>(c: &C) {
    define("decode_float", &["params"], |p: C::P<Tf>| c.direction(p));
    define("decode", &["code"], |code: C::C<Tf>| decode_packed(c, code));
}

/// Traces the public functions, decoders first so that encoders calling them find them
/// with their parameter names. Each is the same generic function the `f32` reference runs.
fn trace_codec<C: Codec>(c: &C, precise: bool) {
    trace_decoders(c);
    if precise {
        define("encode_codes", &["v"], |v: V3<Tf>| c.precise_codes(v));
    }
    define("encode_float", &["v"], |v: V3<Tf>| {
        encode_float(c, precise, v)
    });
    define("encode", &["v"], |v: V3<Tf>| encode_packed(c, precise, v));
    if let Some(name) = c.alternate() {
        define(name, &["v"], |v: V3<Tf>| encode_alternate(c, precise, v));
    }
}
