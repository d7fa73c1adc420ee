//! The shader functions a spec emits, as the registry holds them: each [`Function`] with
//! its `f32` evaluation on raw bits (what the GPU output is compared against), the same
//! generic function evaluated by the adversarial `Dev` (what `crate::measure::portability`
//! measures) and on SIMD lanes (the CPU API), and the inputs it is verified on; and
//! [`Emitted`], a spec's traced module with its functions.

use crate::codecs::toolkit::quant::Quant;
use crate::model::avx2_lanes;
use crate::model::enclosure::Encl;
use crate::model::trace::Module;
use std::sync::Arc;

/// What a function is verified on.
#[derive(Clone, Debug, PartialEq)]
pub enum Inputs {
    /// Seeded random unit vectors plus every edge case (3 words each).
    Vectors,
    /// Tangent frames: a normal and a tangent with its handedness in `w` (7 words each),
    /// seeded and edge cases ([`crate::codecs::functions::inputs::frames`]).
    Frames,
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

/// A model of a function on raw words: any number of whole items at once (`in_words`
/// each in, `out_words` out), one after the other. One call over a slice runs the body in
/// a loop compiled around it, which costs a cheap function (a decoder) a fraction of a
/// call per item (docs/design/speed.md).
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
    /// The `f32` model on raw bits: items of `in_words` in, `out_words` out ([`Eval`]).
    pub eval: Eval,
    /// The same generic function evaluated with [`Dev`], which deviates as the
    /// thread's [`crate::model::deviant::with`] says (and equals `eval` when nothing is set).
    /// Its seeded modes reseed per item at [`crate::model::deviant::begin_item`], so a
    /// caller that deviates passes one item per call.
    pub eval_dev: Eval,
    /// The same generic function evaluated on four items at once with [`F4`]: what the
    /// CPU batches run without AVX2, bit for bit `eval` on each item.
    pub eval_lanes: LanesEval,
    /// The same on eight items at once with [`F8`], compiled for AVX2: what the CPU
    /// batches run where the processor has it, bit for bit `eval` on each item.
    pub eval_lanes8: LanesEval,
    /// For a decoder: the same generic function evaluated with [`Encl`] over a box of
    /// codes, which [`crate::measure::decode_bound`] refines into a proven deviation bound.
    pub enclose: Option<Enclose>,
    /// For a CPU-only [`Emitted::cpu`] function: the emitted functions it chains around
    /// its table fetch, whose costs add up to its own.
    pub parts: Vec<&'static str>,
    /// For a function made of two steps ([`crate::codecs::functions::words::chained`]): the
    /// steps' `f32` models, so that `verify` runs a first step several functions of a
    /// spec share (a precise encoder's search, a frame's decoder) once for all of them.
    pub stages: Option<Stages>,
}

/// The two steps of a chained [`Function`]'s `f32` model: `eval` is `then` over the
/// outputs of `first`, bit for bit, since the words between carry the values unchanged.
/// Two functions begin with the same step exactly when their `first` is the same [`Arc`].
#[derive(Clone)]
pub struct Stages {
    pub first: Eval,
    /// Words per item between the steps.
    pub mid_words: usize,
    pub then: Eval,
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

pub type BoxEval = Arc<dyn Fn(&[(i64, i64)]) -> Vec<Encl> + Send + Sync>;

/// A decoder over boxes of codes, for [`crate::measure::decode_bound`].
#[derive(Clone)]
pub struct Enclose {
    /// One inclusive range per field (signed codes for the float form, raw bit fields for
    /// the packed form) → an enclosure per output lane.
    pub eval: BoxEval,
    /// A field the boxes take one value of at a time ([`Codec::whole_field`]).
    pub whole_field: Option<usize>,
    /// Fields the decoder does not read ([`Codec::unread_fields`]): proven at one value.
    pub unread: &'static [usize],
    /// Fields every valid code holds at one value ([`Codec::fixed_fields`]): proven there.
    pub fixed: Vec<(usize, i64)>,
    /// Box evaluations allowed before the bound is stated as it stands, where not
    /// [`crate::measure::decode_bound::BUDGET`]: a decoder whose enclosures over boxes stay wider
    /// than a single code's never stops earlier, so it spends whatever it is given.
    pub budget: Option<usize>,
    /// The ranges the boxes are drawn from where they are not the code's fields: the
    /// parts a decoder splits its code into by integer operations alone
    /// ([`crate::codecs::Codec::proof_parts`]), which `eval` then takes.
    pub parts: Option<Vec<(i64, i64)>>,
}

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
pub fn first_with_same_code(emitted: &[Arc<Emitted>]) -> Vec<Vec<Option<(usize, usize)>>> {
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
