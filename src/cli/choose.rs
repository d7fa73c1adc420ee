//! `choose`: the ranked table (or JSON) of the specs that meet a user's constraints.

use crate::choice::catalogue::{Catalogue, Entry};
use crate::choice::choose::{Choice, Order, Query, choose};
use crate::choice::filtering::DECIDING_SEPARATION;
use serde::Serialize;

/// A figure with a fixed number of decimals, or `-`.
fn fig(v: Option<f64>, digits: usize) -> String {
    match v {
        Some(v) if v.is_finite() => format!("{v:.digits$}"),
        _ => "-".to_string(),
    }
}

/// The figures of a spec as `list` and `choose` print them: a header line and one row.
pub fn header() -> String {
    format!(
        "{:<28} {:>4} {:<10} {:>9} {:>9} {:>5} {:>5} {:<8} {:>7} {:>9}  formats",
        "spec", "bits", "domain", "mean°", "max°", "enc", "dec", "portable", "bound", "filter°"
    )
}

/// One row under [`header`].
pub fn row(e: &Entry) -> String {
    let formats: Vec<String> = e
        .formats
        .iter()
        .map(|f| format!("{}/{}{}", f.name(), f.bits, if f.exact { "" } else { "~" }))
        .collect();
    let filter = if e.filter_figure().is_finite() {
        fig(Some(e.filter_figure()), 4)
    } else {
        "no".to_string()
    };
    format!(
        "{:<28} {:>4} {:<10} {:>9} {:>9} {:>5} {:>5} {:<8} {:>7} {:>9}  {}",
        e.spec,
        e.bits,
        e.domain,
        fig(Some(e.mean), 5),
        fig(Some(e.max), 5),
        e.alu.encode,
        e.alu.decode,
        if e.portable { "yes" } else { "no" },
        fig(e.bounds.decode, 1),
        filter,
        formats.join(" ")
    )
}

/// What the columns mean, under every table.
pub fn legend(c: &Catalogue) -> String {
    format!(
        "mean°, max°: round-trip error over {} seeded vectors (max: the sample's largest, \
         not a bound). enc, dec: ALU instructions of the packed encoder and decoder. \
         bound: proven decode bound in units of 2^-24. filter°: 99th percentile of the \
         filtering error at {DECIDING_SEPARATION}° apart, as the float form's format stores \
         it (no: not filterable). formats: WebGPU names / bits a texel or vertex \
         (~: wider channels that round the fields, or a block format); `unitpack list \
         --json` has every API's spelling.\n",
        c.samples
    )
}

#[derive(Serialize)]
struct Ranked<'a> {
    rank: usize,
    why: &'a str,
    #[serde(flatten)]
    entry: &'a Entry,
}

/// The ranked table, `limit` rows at most (0: all), or the JSON of every row.
pub fn run(query: &Query, order: Order, json: bool, limit: usize) -> anyhow::Result<String> {
    let c = Catalogue::load();
    // A spec without figures cannot be ranked: said on stderr, where a script's parse of
    // the table or the JSON is not disturbed.
    let missing = c.missing(&crate::codecs::Spec::all());
    if !missing.is_empty() {
        eprintln!(
            "warning: not ranked, no figures in this build for {}: {} lacks them",
            missing.join(", "),
            crate::choice::catalogue::PATH
        );
    }
    let ranked: Vec<Choice> = choose(&c, query, order)?;
    let shown = if limit == 0 {
        ranked.len()
    } else {
        limit.min(ranked.len())
    };
    if json {
        let rows: Vec<Ranked> = ranked[..shown]
            .iter()
            .enumerate()
            .map(|(i, ch)| Ranked {
                rank: i + 1,
                why: &ch.why,
                entry: ch.entry,
            })
            .collect();
        let mut s = serde_json::to_string_pretty(&rows)?;
        s.push('\n');
        return Ok(s);
    }
    let mut s = format!("{}\n", header());
    for ch in &ranked[..shown] {
        s.push_str(&row(ch.entry));
        s.push('\n');
        s.push_str(&format!("  {}\n", ch.why));
    }
    if shown < ranked.len() {
        s.push_str(&format!(
            "… and {} more (--limit 0 shows all)\n",
            ranked.len() - shown
        ));
    }
    s.push('\n');
    s.push_str(&legend(&c));
    Ok(s)
}
