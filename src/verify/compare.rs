//! The model's expected output words, on all cores and on SIMD lanes, and the streaming
//! comparison of a driver's output words with them as raw bits ([`Comparison`]).

use super::*;
use crate::codecs::functions::function::{Function, Width};
use crate::model::Kind;
use crate::model::trace::Ty;
use anyhow::Result;

/// Expected outputs of the model, computed on all cores.
pub fn expected(f: &Function, input: &[u32]) -> Vec<u32> {
    let mut out = Vec::new();
    expected_into(f, input, &mut out);
    out
}

/// [`expected`] into `out`, whose allocation a worker keeps from one function to the
/// next: a fresh one for each (up to 200 MB) had the kernel map and zero new pages.
pub(super) fn expected_into(f: &Function, input: &[u32], out: &mut Vec<u32>) {
    out.clear();
    out.resize(input.len() / f.in_words * f.out_words, 0);
    on_all_cores(input, out, f.in_words, f.out_words, |i, o| (f.eval)(i, o));
}

/// The outputs of [`Function::eval_many_on`] the given lanes for `input`, on all cores,
/// into `out`.
pub(super) fn lanes(f: &Function, width: Width, input: &[u32], out: &mut [u32]) {
    on_all_cores(input, out, f.in_words, f.out_words, |i, o| {
        f.eval_many_on(width, i, o)
    });
}

/// Items a CPU path (the lanes, the C driver) computes at a time before the comparison
/// takes them: a whole function's outputs at once (up to 200 MB for a 24-bit decoder) had
/// the kernel map and zero fresh pages for every function and path. A multiple of 256, so
/// that the lanes meet the same neighbours as in one call.
pub(super) const CPU_CHUNK: usize = 1 << 18;

/// Runs `fill` over `input` a [`CPU_CHUNK`] at a time, into one reused buffer, and hands
/// each chunk's outputs to the comparison.
pub(super) fn in_chunks(
    f: &Function,
    input: &[u32],
    cmp: &mut Comparison,
    mut fill: impl FnMut(&[u32], &mut [u32]) -> Result<()>,
) -> Result<()> {
    let mut out = vec![0u32; CPU_CHUNK.min(input.len() / f.in_words) * f.out_words];
    for items in input.chunks(CPU_CHUNK * f.in_words) {
        let out = &mut out[..items.len() / f.in_words * f.out_words];
        fill(items, out)?;
        cmp.take(out);
    }
    Ok(())
}

/// Runs `run` over `input` (items of `in_words`) split into one contiguous share per
/// core, each writing its items' `out_words` to the same share of `output`. While one
/// spec's shader runs on the adapter or its C driver compiles, the other cores would
/// otherwise idle on a single-threaded path.
pub(crate) fn on_all_cores(
    input: &[u32],
    output: &mut [u32],
    in_words: usize,
    out_words: usize,
    run: impl Fn(&[u32], &mut [u32]) + Sync,
) {
    let n = input.len() / in_words;
    let threads = std::thread::available_parallelism().map_or(1, |t| t.get());
    // Whole blocks of the four-lane batches, so that each item meets the same lane
    // neighbours as in one call over everything.
    let per = n.div_ceil(threads).max(1).next_multiple_of(256);
    let run = &run;
    std::thread::scope(|s| {
        for (o, i) in output
            .chunks_mut(per * out_words)
            .zip(input.chunks(per * in_words))
        {
            s.spawn(move || run(i, o));
        }
    });
}

/// A function's outputs on one path compared with the model's as they arrive, chunk by
/// chunk: the mismatch count and the first few mismatches, with their inputs.
pub struct Comparison<'a> {
    f: &'a Function,
    /// The parameters' types and the kind of the result's words.
    types: (&'a [Ty], Kind),
    input: &'a [u32],
    want: &'a [u32],
    /// Output words received so far.
    words: usize,
    count: usize,
    first: Vec<Mismatch>,
    /// How many mismatches `first` lists.
    keep: usize,
    largest: Option<Largest>,
}

/// What a [`Comparison`] found.
#[derive(Debug)]
pub struct Outcome {
    pub count: usize,
    /// The first few mismatches, in input order.
    pub first: Vec<Mismatch>,
    /// For float outputs, the mismatch farthest from the model.
    pub largest: Option<Largest>,
}

impl<'a> Comparison<'a> {
    pub fn new(
        f: &'a Function,
        types: (&'a [Ty], Kind),
        input: &'a [u32],
        want: &'a [u32],
    ) -> Self {
        Comparison {
            f,
            types,
            input,
            want,
            words: 0,
            count: 0,
            first: Vec::new(),
            keep: FIRST,
            largest: None,
        }
    }

    /// Lists up to `keep` mismatches (at least [`FIRST`]).
    pub fn keeping(mut self, keep: usize) -> Self {
        self.keep = keep.max(FIRST);
        self
    }

    /// The next `got` words of output, continuing from the words already received.
    pub fn take(&mut self, got: &[u32]) {
        let at = self.words;
        self.words += got.len();
        let Some(want) = self.want.get(at..self.words) else {
            return; // More words than expected: `finish` says so.
        };
        // Nearly every check matches: one comparison of the whole chunk settles it.
        if want == got {
            return;
        }
        let (f, first_item) = (self.f, at / self.f.out_words);
        for (k, (w, g)) in want
            .chunks(f.out_words)
            .zip(got.chunks(f.out_words))
            .enumerate()
        {
            if w != g {
                self.count += 1;
                let item = first_item + k;
                let mismatch = || Mismatch {
                    input: self.input[item * f.in_words..(item + 1) * f.in_words].to_vec(),
                    expected: w.to_vec(),
                    actual: g.to_vec(),
                    input_float: self.types.0.iter().all(|t| t.kind == Kind::F32),
                    output_float: self.types.1 == Kind::F32,
                };
                if self.types.1 == Kind::F32 {
                    let d = w
                        .iter()
                        .zip(g)
                        .map(|(&w, &g)| difference(w, g))
                        .fold(0.0, f64::max);
                    if self.largest.as_ref().is_none_or(|l| d > l.difference) {
                        self.largest = Some(Largest {
                            difference: d,
                            at: mismatch(),
                        });
                    }
                }
                if self.first.len() < self.keep {
                    self.first.push(mismatch());
                }
            }
        }
    }

    /// What was found, or an error if the path returned another number of words than
    /// the model.
    pub fn finish(self) -> std::result::Result<Outcome, String> {
        if self.words != self.want.len() {
            return Err(format!(
                "returned {} words for {} expected",
                self.words,
                self.want.len()
            ));
        }
        Ok(Outcome {
            count: self.count,
            first: self.first,
            largest: self.largest,
        })
    }
}
