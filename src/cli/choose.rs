//! `choose`: the ranked table (or JSON) of the specs that meet a user's constraints.

use crate::choice::catalogue::FrameEntry;
use crate::choice::catalogue::{Catalogue, Entry};
use crate::choice::choose::{Choice, Order, choose};
use crate::choice::filtering::DECIDING_SEPARATION;
use crate::choice::profiles::{ALU_WEIGHT, rank, rank_frames};
use crate::choice::query::{Query, Use};
use serde::Serialize;
use std::path::Path;

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

/// One row under [`header`], with the packed functions' ALU counts.
pub fn row(e: &Entry) -> String {
    row_counting(e, e.alu.encode, e.alu.decode)
}

/// One row under [`header`], with the ALU counts `enc` and `dec` in its columns: under
/// `--use` those of the functions its route runs, which its score counts.
fn row_counting(e: &Entry, enc: u32, dec: u32) -> String {
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
        enc,
        dec,
        if e.portable { "yes" } else { "no" },
        fig(e.bounds.decode, 1),
        filter,
        formats.join(" ")
    )
}

/// What the columns mean, under every table.
pub fn legend(c: &Catalogue) -> String {
    legend_counting(c, "the packed encoder and decoder")
}

/// [`legend`], saying whose ALU instructions the enc and dec columns count.
fn legend_counting(c: &Catalogue, counted: &str) -> String {
    let over = match &c.over {
        Some(sample) => format!("{sample}; each row's second line adds the 99th percentile"),
        None => format!("{} seeded vectors", c.samples),
    };
    format!(
        "mean°, max°: round-trip error over {over} (max: the sample's largest, \
         not a bound). enc, dec: ALU instructions of {counted}. \
         bound: proven decode bound in units of 2^-24. filter°: 99th percentile of the \
         filtering error at {DECIDING_SEPARATION}° apart, as the float form's format stores \
         it (no: not filterable). formats: WebGPU names / bits a texel or vertex \
         (~: wider channels that round the fields, or a block format); `unitpack list \
         --json` has every API's spelling.\n"
    )
}

#[derive(Serialize)]
struct Ranked<'a> {
    rank: usize,
    why: &'a str,
    #[serde(flatten)]
    entry: &'a Entry,
}

/// A row of `choose --use`: the spec, the route it takes and its score.
#[derive(Serialize)]
struct RankedUse<'a> {
    rank: usize,
    why: &'a str,
    score: f64,
    /// The error the score counts, degrees.
    error: f64,
    /// ALU instructions the score counts.
    cost: u32,
    /// The format the profile stores it in (null: the code as it is), its bits, and
    /// the instructions of the encoder and decoder that route runs.
    stored_in: Option<&'a str>,
    stored_bits: u32,
    route_encode: u32,
    route_decode: u32,
    #[serde(flatten)]
    entry: &'a Entry,
}

/// A row of `choose --use frame`.
#[derive(Serialize)]
struct RankedFrameJson<'a> {
    rank: usize,
    why: &'a str,
    score: f64,
    error: f64,
    #[serde(flatten)]
    entry: &'a FrameEntry,
}

/// The rows a limit shows, and the line that says how many more there are.
fn shown(total: usize, limit: usize) -> (usize, String) {
    let n = if limit == 0 { total } else { limit.min(total) };
    let more = if n < total {
        format!("… and {} more (--limit 0 shows all)\n", total - n)
    } else {
        String::new()
    };
    (n, more)
}

/// JSON text of `rows`, with a final newline.
fn json_text<T: Serialize>(rows: &[T]) -> anyhow::Result<String> {
    let mut s = serde_json::to_string_pretty(rows)?;
    s.push('\n');
    Ok(s)
}

/// The ranked table, `limit` rows at most (0: all), or the JSON of every row; `--use`
/// (or `--domain frame`) ranks by its profile's score, anything else by `order`
/// (`None`: the sample max).
pub fn run(
    query: &Query,
    order: Option<Order>,
    json: bool,
    limit: usize,
    sample: Option<&Path>,
) -> anyhow::Result<String> {
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
    let frame_domain = query.domain.as_deref() == Some("frame");
    let use_case = match (query.use_case, frame_domain) {
        (None, true) | (Some(Use::Frame), _) => Some(Use::Frame),
        (Some(u), true) => anyhow::bail!(
            "--domain frame ranks tangent frames, as --use frame does; --use {} ranks vectors",
            u.name()
        ),
        (u, false) => u,
    };
    if use_case == Some(Use::Frame) {
        let vector_only = [
            ("--format", query.format.is_some()),
            ("--filterable", query.filterable.is_some()),
            ("--portable", query.portable),
            (
                "--domain sphere|hemisphere",
                query.domain.as_deref().is_some_and(|d| d != "frame"),
            ),
        ];
        if let Some((option, _)) = vector_only.iter().find(|(_, given)| *given) {
            anyhow::bail!(
                "{option} constrains vector specs; --use frame ranks tangent frames by bits and ALU only"
            );
        }
    }
    if use_case == Some(Use::Asset) && query.format.is_some() {
        anyhow::bail!(
            "--use asset stores the packed code itself; --format belongs to the uses that store a format (gbuffer, vertex, normal-map)"
        );
    }
    if query.no_filter && use_case != Some(Use::Gbuffer) {
        anyhow::bail!(
            "--no-filter belongs to --use gbuffer (the other uses either never filter or always do)"
        );
    }
    if let (Some(u), Some(_)) = (use_case, order) {
        anyhow::bail!(
            "--by ranks a plain query; --use {} ranks by its profile's score \
             (docs/design/choosing.md): drop one of them",
            u.name()
        );
    }
    let c = match sample {
        Some(path) if use_case == Some(Use::Frame) => {
            super::sample::remeasure_frames(&c, &super::sample::read_frames(path)?)
        }
        Some(path) => {
            // The specs the seeded catalogue ranks are the candidates (no constraint reads
            // an error figure); a query none meets keeps the whole catalogue, whose
            // ranking names the constraint that emptied it.
            let ranked: Option<std::collections::HashSet<String>> = match use_case {
                Some(u) => rank(&c, query, u)
                    .ok()
                    .map(|r| r.iter().map(|x| x.entry.spec.clone()).collect()),
                None => choose(&c, query, order.unwrap_or(Order::Max))
                    .ok()
                    .map(|r| r.iter().map(|x| x.entry.spec.clone()).collect()),
            };
            match ranked {
                Some(ids) => super::sample::remeasure(
                    &c,
                    |e| ids.contains(&e.spec),
                    &super::sample::read(path)?,
                ),
                None => c,
            }
        }
        None => c,
    };
    match use_case {
        Some(Use::Frame) => frames(&c, query, json, limit),
        Some(u) => by_use(&c, query, u, json, limit),
        None => plain(&c, query, order.unwrap_or(Order::Max), json, limit),
    }
}

/// `choose` without `--use`.
fn plain(
    c: &Catalogue,
    query: &Query,
    order: Order,
    json: bool,
    limit: usize,
) -> anyhow::Result<String> {
    let ranked: Vec<Choice> = choose(c, query, order)?;
    let (n, more) = shown(ranked.len(), limit);
    if json {
        let rows: Vec<Ranked> = ranked[..n]
            .iter()
            .enumerate()
            .map(|(i, ch)| Ranked {
                rank: i + 1,
                why: &ch.why,
                entry: ch.entry,
            })
            .collect();
        return json_text(&rows);
    }
    let mut s = over_line(c);
    s.push_str(&format!("{}\n", header()));
    for ch in &ranked[..n] {
        s.push_str(&format!(
            "{}\n  {}\n",
            row(ch.entry),
            with_p99(&ch.why, ch.entry)
        ));
    }
    Ok(format!("{s}{more}\n{}", legend(c)))
}

/// The line above a table whose figures are over a user's sample, naming it.
fn over_line(c: &Catalogue) -> String {
    c.over
        .as_ref()
        .map_or(String::new(), |o| format!("errors over {o}\n"))
}

/// A row's reason, with the 99th percentile of its error where measured over a sample.
fn with_p99(why: &str, e: &Entry) -> String {
    match e.p99 {
        Some(p) => format!("{why}; round-trip p99 {p:.5}° over the sample"),
        None => why.to_string(),
    }
}

/// How a profile ranks, for the line above its table.
fn score_words(u: Use) -> String {
    match u {
        Use::Asset => "ranked by sample max".into(),
        _ => format!("ranked by score = error × (1 + ALU / {ALU_WEIGHT})"),
    }
}

/// `choose --use` for vectors.
fn by_use(
    c: &Catalogue,
    query: &Query,
    u: Use,
    json: bool,
    limit: usize,
) -> anyhow::Result<String> {
    let ranked = rank(c, query, u)?;
    let (n, more) = shown(ranked.len(), limit);
    if json {
        let rows: Vec<RankedUse> = ranked[..n]
            .iter()
            .enumerate()
            .map(|(i, r)| RankedUse {
                rank: i + 1,
                why: &r.why,
                score: r.route.score,
                error: r.route.error,
                cost: r.route.cost,
                stored_in: r.route.stored_in(u),
                stored_bits: r.route.bits,
                route_encode: r.route.encode,
                route_decode: r.route.decode,
                entry: r.entry,
            })
            .collect();
        return json_text(&rows);
    }
    let mut s = over_line(c);
    s += &format!(
        "{}; {}\n{}\n",
        u.what(u.filters(query)),
        score_words(u),
        header()
    );
    for r in &ranked[..n] {
        let line = row_counting(r.entry, r.route.encode, r.route.decode);
        s.push_str(&format!("{line}\n  {}\n", with_p99(&r.why, r.entry)));
    }
    let counted = "the encoder and decoder this use runs (the float form's where the \
                   route's format holds the float form; the line above the table says which \
                   the score counts)";
    Ok(format!("{s}{more}\n{}", legend_counting(c, counted)))
}

/// `choose --use frame`.
fn frames(c: &Catalogue, query: &Query, json: bool, limit: usize) -> anyhow::Result<String> {
    let ranked = rank_frames(c, query)?;
    let (n, more) = shown(ranked.len(), limit);
    if json {
        let rows: Vec<RankedFrameJson> = ranked[..n]
            .iter()
            .enumerate()
            .map(|(i, r)| RankedFrameJson {
                rank: i + 1,
                why: &r.why,
                score: r.score,
                error: r.error,
                entry: r.entry,
            })
            .collect();
        return json_text(&rows);
    }
    let over = c.frames_over.as_ref();
    let mut s = over.map_or(String::new(), |o| format!("errors over {o}\n"));
    s += &format!(
        "{}; {}\n{:<20} {:>4} {:>19} {:>19} {:>19} {:>5} {:>5} {:>5}  engine\n",
        Use::Frame.what(false),
        score_words(Use::Frame),
        "spec",
        "bits",
        "normal°",
        "tangent°",
        "bitangent°",
        "flips",
        "enc",
        "dec"
    );
    let pair = |[mean, max]: [f64; 2]| format!("{mean:.5} / {max:.5}");
    for r in &ranked[..n] {
        let e = r.entry;
        s.push_str(&format!(
            "{:<20} {:>4} {:>19} {:>19} {:>19} {:>5} {:>5} {:>5}  {}\n  {}\n",
            e.spec,
            e.bits,
            pair(e.normal),
            pair(e.tangent),
            pair(e.bitangent),
            e.flips,
            e.alu.encode,
            e.alu.decode,
            e.engine.as_deref().unwrap_or("-"),
            r.why
        ));
    }
    Ok(format!(
        "{s}{more}\nnormal°, tangent°, bitangent°: mean / sample max of the angle error over {} (not a bound). flips: frames whose handedness changed. enc, dec: ALU instructions of the packed encoder and decoder. engine: the engine that reads these bits.\n",
        over.cloned()
            .unwrap_or_else(|| format!("{} seeded orthonormal frames", c.frame_samples))
    ))
}
