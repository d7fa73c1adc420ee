//! The record of figures a spec's docs quote, measured before anything is printed
//! ([`crate::measure::measured`] fills it; emission, `list`, the report and the figure
//! cache read it). Plain data: nothing here measures.

use crate::codecs::Spec;
use crate::codecs::functions::function::Emitted;
use std::collections::BTreeMap;
use std::sync::Arc;

/// Seeds are fixed so that every run, and every file generated, is identical.
pub const VECTOR_SEED: u128 = 0x756e_6974_7061_636b_5f76_6563_746f_7273;

/// Round-trip error of a spec's packed encode → decode: the angle in degrees (mean and
/// sample max), and the first seed's metric, the mean squared error of the components of
/// `n - n'` (its MSE over the `abs(n1 - n2)` difference image: three channels per
/// normal, peak 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ErrorStats {
    pub mean: f64,
    pub max: f64,
    pub mse: f64,
    pub samples: usize,
}

impl ErrorStats {
    /// `10·log10(1 / MSE)` in dB, the seed's PSNR for a peak of 1.
    pub fn psnr(&self) -> f64 {
        -10.0 * self.mse.log10()
    }
}

/// Every figure a spec's docs quote.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Figures {
    /// Round-trip error statistics of the packed encoder and decoder, where asked and
    /// the spec codes directions.
    pub errors: Option<ErrorStats>,
    /// A tangent-frame spec's frame figures, with the comparison they are set against.
    pub frames: Option<FrameFigures>,
    /// The proven bound of the packed decoder and of the float form, by the function's
    /// local name.
    pub bounds: BTreeMap<&'static str, Bound>,
}

/// A frame spec's round-trip figures and its octahedral baseline.
#[derive(Clone, Debug, PartialEq)]
pub struct FrameFigures {
    pub stats: FrameStats,
    pub baseline: FrameBaseline,
}

/// A spec ready to print: its functions, traced once, and its figures.
#[derive(Clone)]
pub struct Measured {
    pub spec: Spec,
    pub emitted: Arc<Emitted>,
    pub figures: Figures,
}

/// Round-trip errors of a tangent-frame spec over the seeded frames
/// ([`crate::codecs::functions::inputs::frames`], the edge frames left out): the angle in
/// degrees between each decoded vector and its reference, mean and sample max, for the
/// normal, the tangent and the bitangent, and how many signs flipped. The references are
/// the input's: `n` normalized, `t` made orthogonal to it (Gram–Schmidt) and normalized,
/// the sign `w < 0 ? -1 : +1`, the bitangent `cross(n, t)·sign`; the decoded bitangent is
/// `cross(n', t')·sign'` (glTF's convention), all in f64.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameStats {
    pub samples: usize,
    /// `[mean, sample max]` in degrees.
    pub normal: [f64; 2],
    pub tangent: [f64; 2],
    pub bitangent: [f64; 2],
    pub flips: usize,
}

impl FrameStats {
    /// `normal 0.00123° / 0.00456°, tangent …, bitangent …` (mean / sample max), and the
    /// flips where `flips` is asked.
    pub fn summary(&self, flips: bool) -> String {
        let pair = |[mean, max]: [f64; 2]| format!("{mean:.5}° / {max:.5}°");
        let mut s = format!(
            "normal {}, tangent {}, bitangent {}",
            pair(self.normal),
            pair(self.tangent),
            pair(self.bitangent)
        );
        if flips {
            s.push_str(&format!(", handedness flips {}", self.flips));
        }
        s
    }
}

/// The specs a frame baseline stands for and their total bits, with its figures.
pub type FrameBaseline = ((String, String, u32), FrameStats);

/// The unit bounds are stated in: the f32 ULP of values in `[0.5, 1)`.
pub const UNIT: f64 = 1.0 / 16_777_216.0;

/// A proven bound: every output component of every code is within `units · 2^-24` of
/// the reference on every implementation the guaranteed classes allow.
#[derive(Clone, Debug, PartialEq)]
pub struct Bound {
    pub units: f64,
    /// The box of codes (one inclusive range per field) whose bound is the stated one.
    pub at: Vec<(i64, i64)>,
    /// The most a single code was shown to reach, in the same units: the true bound lies
    /// in `[reached, units]`. Equal where the search closed the gap; below `units` where
    /// it spent its evaluation budget first, so that `units` is sound but may be loose:
    /// the include's doc comment and the bounds table say so ([`Bound::tight`]); the
    /// catalogue that `list`, `choose` and the report read keeps `units` alone.
    pub reached: f64,
}

impl Bound {
    /// Whether the proof closed: some single code reaches the stated bound, so no
    /// smaller bound holds.
    pub fn tight(&self) -> bool {
        self.reached >= self.units
    }
}
