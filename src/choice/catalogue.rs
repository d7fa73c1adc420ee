//! The figures a choice needs, for every spec of the catalogue, as one tool-written file
//! (`src/choice/catalogue.json`) compiled into the binary.
//!
//! Every figure here is expensive or needs tools a user may not have: the error sample
//! (2^20 vectors a spec), the ALU counts (glslang and spirv-opt), the proven decoder bounds
//! (branch and bound), the filtering sample. `list`, `choose` and `report` read them from
//! this file, so that they answer at once and agree with each other and with the
//! documentation's tables, which are computed in the same test run from the same
//! figures. `tests/figures/tables.rs` recomputes the file and fails when it is stale;
//! `UNITPACK_REFRESH=1` rewrites it.

use super::filtering::{self, Filtering};
use crate::codecs::Spec;
use crate::codecs::core::storage::{self, Format};
use crate::measure::figures::ErrorStats;
use serde::{Deserialize, Serialize};

/// The file, as compiled in.
const FILE: &str = include_str!("catalogue.json");
/// Where the file lives, relative to the repository root.
pub const PATH: &str = "src/choice/catalogue.json";

/// ALU instructions of a spec's four functions (counted as `src/verify/alu.rs` says).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Alu {
    pub encode: u32,
    pub encode_float: u32,
    pub decode: u32,
    pub decode_float: u32,
}

/// The proven bound of a decoder, in units of 2^-24 (`None`: no bound is proven).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Bounds {
    pub decode: Option<f64>,
    pub decode_float: Option<f64>,
}

/// One spec's figures.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Entry {
    /// The spec's id: the name of its include and its functions, itself a spec.
    pub spec: String,
    pub family: String,
    /// Total bits of the packed code.
    pub bits: u32,
    /// `sphere` or `hemisphere`.
    pub domain: String,
    /// Round-trip angular error of the packed code over the catalogue's sample, degrees.
    pub mean: f64,
    /// The largest error of that sample: a sample maximum, not a bound.
    pub max: f64,
    pub mse: f64,
    /// The 99th percentile of the error over a user's sample (`choose --sample`); the
    /// catalogue's own file has none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub p99: Option<f64>,
    pub alu: Alu,
    /// Whether the packed encoder gives the same code on every conformant implementation.
    pub portable: bool,
    pub bounds: Bounds,
    pub formats: Vec<Format>,
    /// The float form's filtering figures (`None`: no float form of a vector alone).
    pub filtering: Option<Filtering>,
    /// Why the float form cannot be filtered whatever its figures, when that is so.
    pub not_filterable: Option<String>,
    /// Where on the sphere the float form's parameters jump (the family's fact), if it
    /// has a float form.
    pub seam: Option<String>,
    /// The lookup tables its shader functions read.
    pub tables: Vec<TableSize>,
    /// The engine whose stored bits the spec reproduces, if it is an engine format.
    pub engine: Option<String>,
}

/// A lookup table a spec reads, by its file name and size.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct TableSize {
    pub name: String,
    pub bytes: usize,
}

/// ALU instructions of a tangent-frame spec's packed encoder and decoder.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct FrameAlu {
    pub encode: u32,
    pub decode: u32,
}

/// One tangent-frame spec's figures ([`crate::measure::figures::FrameStats`] over the
/// seeded orthonormal frames).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FrameEntry {
    pub spec: String,
    pub family: String,
    /// Total bits of the packed code.
    pub bits: u32,
    /// Angle errors in degrees, `[mean, sample max]`.
    pub normal: [f64; 2],
    pub tangent: [f64; 2],
    pub bitangent: [f64; 2],
    /// Frames whose decoded sign differs from the input's.
    pub flips: usize,
    pub alu: FrameAlu,
    /// The engine that reads these bits, if one does.
    pub engine: Option<String>,
}

impl FrameEntry {
    /// The largest sample max of the normal, the tangent and the bitangent.
    pub fn max(&self) -> f64 {
        self.normal[1].max(self.tangent[1]).max(self.bitangent[1])
    }
}

impl Entry {
    /// Whether the float form is stored in a format a texture unit filters and filters
    /// with at most `deg` degrees at the deciding separation's 99th percentile (lerp and
    /// resolve alike).
    pub fn filterable_within(&self, deg: f64) -> bool {
        self.not_filterable.is_none()
            && self.filterable_storage().is_some()
            && self
                .filtering
                .as_ref()
                .is_some_and(|f| f.deciding_p99() <= deg)
    }

    /// The float form's own format where a texture unit filters it: the one its filtering
    /// figures are measured in (a block format's are not measured).
    pub fn filterable_storage(&self) -> Option<&Format> {
        storage::float_form_storage(&self.formats).filter(|f| f.filterable)
    }

    /// The figure `--by filter` orders by (infinite when not filterable).
    pub fn filter_figure(&self) -> f64 {
        match (&self.not_filterable, &self.filtering) {
            (None, Some(f)) if self.filterable_storage().is_some() => f.deciding_p99(),
            _ => f64::INFINITY,
        }
    }
}

/// The catalogue's figures.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Catalogue {
    /// Vectors behind each spec's error figures.
    pub samples: usize,
    /// What the error figures are over where not the seeded vectors: a user's sample, in
    /// words (`choose --sample`).
    #[serde(skip)]
    pub over: Option<String>,
    /// The error sample's seed, hexadecimal.
    pub vector_seed: String,
    /// The filtering sample's seed, hexadecimal, and its size per separation.
    pub filter_seed: String,
    pub filter_pairs: usize,
    pub specs: Vec<Entry>,
    /// Frames behind each tangent-frame spec's figures.
    pub frame_samples: usize,
    /// What the frames' figures are over where not the seeded frames: a user's sample, in
    /// words (`choose --use frame --sample`).
    #[serde(skip)]
    pub frames_over: Option<String>,
    pub frames: Vec<FrameEntry>,
}

impl Catalogue {
    /// The compiled-in catalogue.
    pub fn load() -> Catalogue {
        Catalogue::parse(FILE).expect("src/choice/catalogue.json is the tool's own file")
    }

    /// A catalogue from the file's text: the tests read [`PATH`] as it is on disk, so that
    /// what they write from a catalogue just computed needs no rebuild first.
    pub fn parse(text: &str) -> Result<Catalogue, serde_json::Error> {
        serde_json::from_str(text)
    }

    /// The file's text.
    pub fn to_json(&self) -> String {
        let mut s = serde_json::to_string_pretty(self).expect("the catalogue serializes");
        s.push('\n');
        s
    }

    /// The entry of the spec with this id.
    pub fn get(&self, id: &str) -> Option<&Entry> {
        self.specs.iter().find(|e| e.spec == id)
    }

    /// The ids of the codec specs among `specs` (those with a domain) that have no entry:
    /// a family added since [`PATH`] was last written, which `list` and `choose` would
    /// otherwise leave out without a word.
    pub fn missing(&self, specs: &[Spec]) -> Vec<String> {
        specs
            .iter()
            .filter(|s| s.info().domain.is_some() && self.get(&s.id()).is_none())
            .map(Spec::id)
            .collect()
    }
}

/// Computes the catalogue for `specs` (the codecs, in catalogue order) from their error
/// statistics and ALU counts (`[encode, encode_float, decode, decode_float]`), and for
/// `frames` (the tangent-frame specs) from their ALU counts (`[encode, decode]`),
/// proving the decoder bounds and measuring the filtering and the frames here.
pub fn compute(
    specs: &[Spec],
    stats: &[Option<ErrorStats>],
    alu: &[[u32; 4]],
    frames: &[Spec],
    frame_alu: &[[u32; 2]],
) -> Catalogue {
    assert_eq!(specs.len(), stats.len());
    assert_eq!(specs.len(), alu.len());
    assert_eq!(frames.len(), frame_alu.len());
    crate::measure::decode_bound::prove_all(specs);
    let rows = crate::support::par::map(specs, |spec| {
        let e = spec.emitted();
        let domain = spec.info().domain.expect("a codec spec has a domain");
        let bound = |name: &str| {
            e.functions
                .iter()
                .find(|f| f.name == name)
                .and_then(|f| crate::measure::decode_bound::cached(&e.module, f))
                .map(|b| b.units)
        };
        (
            e.portable_encoder,
            Bounds {
                decode: bound("decode"),
                decode_float: bound("decode_float"),
            },
            {
                let formats = storage::formats(spec, &e);
                let filtering = storage::float_form_storage(&formats)
                    .and_then(|f| filtering::measure(&e, f, domain));
                (formats, filtering)
            },
        )
    });
    let frame_rows = frame_entries(frames, frame_alu);
    let samples = stats
        .iter()
        .flatten()
        .next()
        .map_or(0, |s: &ErrorStats| s.samples);
    let specs = specs
        .iter()
        .zip(stats)
        .zip(alu)
        .zip(rows)
        .map(
            |(((spec, st), a), (portable, bounds, (formats, filtering)))| {
                let st = st.expect("a codec spec has error statistics");
                Entry {
                    spec: spec.id(),
                    family: spec.info().name.to_string(),
                    bits: spec.bits(),
                    domain: spec.info().domain.map_or("", |d| d.name()).to_string(),
                    mean: st.mean,
                    max: st.max,
                    mse: st.mse,
                    p99: None,
                    alu: Alu {
                        encode: a[0],
                        encode_float: a[1],
                        decode: a[2],
                        decode_float: a[3],
                    },
                    portable,
                    bounds,
                    formats,
                    not_filterable: spec
                        .family()
                        .float_form(spec)
                        .unfilterable()
                        .map(str::to_string),
                    filtering,
                    seam: spec.family().float_form(spec).seam().map(str::to_string),
                    tables: spec
                        .family()
                        .tables(spec)
                        .into_iter()
                        .map(|t| TableSize {
                            name: t.stem,
                            bytes: t.bytes.len(),
                        })
                        .collect(),
                    engine: spec.family().engine(spec).map(str::to_string),
                }
            },
        )
        .collect();
    Catalogue {
        samples,
        over: None,
        vector_seed: format!("{:#x}", crate::measure::figures::VECTOR_SEED),
        filter_seed: format!("{:#x}", filtering::SEED),
        filter_pairs: filtering::PAIRS,
        specs,
        frame_samples: frame_rows.first().map_or(0, |r| r.0),
        frames_over: None,
        frames: frame_rows.into_iter().map(|r| r.1).collect(),
    }
}

/// The catalogue rows of the tangent-frame specs, each with its sample size.
fn frame_entries(frames: &[Spec], alu: &[[u32; 2]]) -> Vec<(usize, FrameEntry)> {
    crate::support::par::map(frames, |spec| {
        crate::measure::quality::measure_frames(spec).expect("a tangent-frame spec")
    })
    .into_iter()
    .zip(frames.iter().zip(alu))
    .map(|(st, (spec, a))| {
        (
            st.samples,
            FrameEntry {
                spec: spec.id(),
                family: spec.info().name.to_string(),
                bits: spec.bits(),
                normal: st.normal,
                tangent: st.tangent,
                bitangent: st.bitangent,
                flips: st.flips,
                alu: FrameAlu {
                    encode: a[0],
                    decode: a[1],
                },
                engine: spec.family().engine(spec).map(str::to_string),
            },
        )
    })
    .collect()
}
