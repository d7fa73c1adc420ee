//! `list`: every family with the specs a user types, as a table or as JSON.

use crate::choice::catalogue::{Catalogue, Entry, FrameEntry};
use crate::codecs::FAMILIES;
use crate::codecs::core::info::OptKind;
use serde::Serialize;

/// The spec grammar in one line, as every SPEC argument's help gives it.
pub const GRAMMAR: &str = "NAME[BITS][p][:key=value,...]";

/// The `list` table: each family with the specs a user types, then each of its
/// catalogue's specs with the figures a choice needs.
pub fn list_text() -> String {
    list_text_of(&Catalogue::load())
}

/// [`list_text`] from the figures of `catalogue`.
pub fn list_text_of(catalogue: &Catalogue) -> String {
    // The family column is as wide as the longest name.
    let w = FAMILIES
        .iter()
        .map(|f| f.info().name.len())
        .max()
        .unwrap_or(0);
    let mut s = format!(
        "{:<w$} {:<11} {:<8} {}\n",
        "family", "domain", "precise", "source"
    );
    for f in FAMILIES {
        let c = f.info();
        let domain = f.takes().unwrap_or("-");
        let precise = if f.precise() { "yes" } else { "no" };
        s.push_str(&format!(
            "{:<w$} {:<11} {:<8} {}\n",
            c.name, domain, precise, c.source
        ));
        s.push_str(&format!("{:<w$} {}\n", "", c.title));
        let specs: Vec<String> = c.spellings().into_iter().map(|s| s.0).collect();
        let p = if f.precise() { " (add p: precise)" } else { "" };
        s.push_str(&format!("{:<w$} specs: {}{p}\n", "", specs.join(", ")));
        for o in c.options {
            s.push_str(&format!("{:<w$} option {}\n", "", o.usage()));
        }
        // A frame spec's figures: its round trip over the seeded frames, and the
        // octahedral normal, tangent and sign at no more bits.
        for spec in crate::codecs::Spec::all()
            .iter()
            .filter(|s| std::ptr::addr_eq(s.family(), *f))
        {
            if let Some(stats) = crate::measure::quality::measure_frames(spec) {
                let ((n, t, bits), base) = crate::measure::quality::oct_frame_baseline(spec.bits());
                s.push_str(&format!(
                    "{:<w$}   {}: over {} seeded orthonormal frames, mean / sample max: {}\n{:<w$}   against {n} + {t} + sign ({bits} bits): {}\n",
                    "",
                    spec.id(),
                    stats.samples,
                    stats.summary(true),
                    "",
                    base.summary(false)
                ));
            }
        }
        let rows: Vec<&Entry> = catalogue
            .specs
            .iter()
            .filter(|e| e.family == c.name)
            .collect();
        if !rows.is_empty() {
            s.push_str(&format!("{:<w$}   {}\n", "", super::choose::header()));
            for e in rows {
                s.push_str(&format!("{:<w$}   {}\n", "", super::choose::row(e)));
            }
        }
        let missing = catalogue.missing(&crate::codecs::Spec::all_in(std::slice::from_ref(f)));
        if !missing.is_empty() {
            s.push_str(&format!(
                "{:<w$}   no figures in this build for {}: {} lacks them \
                 (`UNITPACK_REFRESH=1 cargo test --release --test figures` writes it; rebuild after)\n",
                "",
                missing.join(", "),
                crate::choice::catalogue::PATH
            ));
        }
    }
    s.push_str(&format!(
        "\nA spec is {GRAMMAR}: oct24p, snorm8x3, stereo_scaled16:scale=2, oct24:layout=rgb8.\n"
    ));
    s.push_str(&super::choose::legend(catalogue));
    s
}

#[derive(Serialize)]
struct ListJson {
    grammar: &'static str,
    families: Vec<FamilyJson>,
    /// Vectors behind each spec's error figures, and their seed.
    samples: usize,
    vector_seed: String,
    /// The filtering sample's seed and its size per separation.
    filter_seed: String,
    filter_pairs: usize,
    /// The separation whose 99th percentile `choose --filterable` reads, degrees.
    filter_deciding_separation: f64,
    /// Every spec of the catalogue (`generate` writes one include for each), by id,
    /// with its figures.
    specs: Vec<Entry>,
    /// Seeded orthonormal frames behind each tangent-frame spec's figures.
    frame_samples: usize,
    /// Every tangent-frame spec with its figures.
    frames: Vec<FrameEntry>,
}

#[derive(Serialize)]
struct FamilyJson {
    family: &'static str,
    title: &'static str,
    /// `sphere`, `hemisphere`, or null for packing helpers.
    domain: Option<&'static str>,
    precise: bool,
    source: &'static str,
    /// Every spec as typed, with its total bits (0 for fixed forms).
    specs: Vec<SpecJson>,
    options: Vec<OptionJson>,
}

#[derive(Serialize)]
struct SpecJson {
    spec: String,
    bits: u32,
    /// The precise encoder's spelling, when there is one.
    precise: Option<String>,
}

#[derive(Serialize)]
struct OptionJson {
    key: &'static str,
    default: String,
    /// The choices, for a choice option.
    choices: Option<Vec<&'static str>>,
    /// The allowed range, for a number option.
    min: Option<f32>,
    max: Option<f32>,
    help: &'static str,
}

/// `list --json`: the same content as [`list_text`], for scripts.
pub fn list_json() -> String {
    let families = FAMILIES
        .iter()
        .map(|f| {
            let c = f.info();
            FamilyJson {
                family: c.name,
                title: c.title,
                domain: f.takes(),
                precise: f.precise(),
                source: c.source,
                specs: c
                    .spellings()
                    .into_iter()
                    .map(|(spec, bits)| SpecJson {
                        precise: f.precise().then(|| format!("{spec}p")),
                        spec,
                        bits,
                    })
                    .collect(),
                options: c
                    .options
                    .iter()
                    .map(|o| {
                        let (choices, min, max) = match o.kind {
                            OptKind::Choice(names) => (Some(names.to_vec()), None, None),
                            OptKind::Number { min, max, .. } => (None, Some(min), Some(max)),
                        };
                        OptionJson {
                            key: o.key,
                            default: o.value_text(o.default_value()),
                            choices,
                            min,
                            max,
                            help: o.help,
                        }
                    })
                    .collect(),
            }
        })
        .collect();
    let c = Catalogue::load();
    let mut s = serde_json::to_string_pretty(&ListJson {
        grammar: GRAMMAR,
        families,
        samples: c.samples,
        vector_seed: c.vector_seed,
        filter_seed: c.filter_seed,
        filter_pairs: c.filter_pairs,
        filter_deciding_separation: crate::choice::filtering::DECIDING_SEPARATION,
        specs: c.specs,
        frame_samples: c.frame_samples,
        frames: c.frames,
    })
    .expect("list serializes");
    s.push('\n');
    s
}
