//! `choose --use`: the catalogue ranked for what a renderer does with its normals.
//!
//! A profile says where the vectors are encoded and decoded, which instruction counts
//! that makes a cost, which constraints it implies, and which storage it reads the bits
//! from. Each spec is given its best *route* under the profile: the format it is stored
//! in (the packed code in an integer format, or the float form in a normalized one,
//! whose functions then are `encode_float` / `decode_float`), what that costs a texel or
//! vertex, and the error the profile counts. The score is
//!
//! ```text
//! score = error × (1 + cost / 100)
//! ```
//!
//! with `cost` the ALU instructions of the functions the profile runs per pixel or per
//! vertex: a spec twice as accurate may cost about 100 more instructions and tie. `error`
//! is the round-trip sample max; where the profile filters, the worse of it and the
//! filtering error's 99th percentile at 5° apart, measured in the route's format.
//! docs/design/choosing.md gives each profile's reasons.

use super::catalogue::{Catalogue, Entry, FrameEntry};
use super::filtering::DECIDING_SEPARATION;
use super::query::{Empty, Query, Use};
use crate::codecs::core::storage::{Format, Holds};

/// The instructions that weigh as much as the error itself.
pub const ALU_WEIGHT: f64 = 100.0;

/// Where a spec's bits live under a profile, and what they cost.
#[derive(Clone, Debug)]
pub struct Route<'a> {
    /// The format (`None`: the packed code as bytes, or a frame's words).
    pub format: Option<&'a Format>,
    /// Bits a texel, vertex or record costs.
    pub bits: u32,
    /// ALU instructions counted, of the encoder and decoder the route runs.
    pub encode: u32,
    pub decode: u32,
    pub cost: u32,
    /// The filtering error's 99th percentile at the deciding separation, where it filters.
    pub filter: Option<f64>,
    /// The error the score counts, degrees.
    pub error: f64,
    pub score: f64,
}

/// A spec's score under a profile: the module's formula.
pub fn score(error: f64, cost: u32) -> f64 {
    error * (1.0 + f64::from(cost) / ALU_WEIGHT)
}

/// The best route of `e` under `u` within `query`'s budget and format, if it has one.
fn route<'a>(u: Use, e: &'a Entry, query: &Query) -> Option<Route<'a>> {
    let budget = query.bits.unwrap_or(u32::MAX);
    let format_ok = |f: &Format| query.format.as_deref().is_none_or(|q| f.matches(q));
    // Encoder and decoder counted: a G-buffer runs both per pixel; a vertex stream and
    // a normal map are encoded offline.
    let counted = |enc: u32, dec: u32| match u {
        Use::Gbuffer => enc + dec,
        Use::Vertex | Use::NormalMap | Use::Frame => dec,
        Use::Asset => 0,
    };
    let of = |f: Option<&'a Format>, bits: u32, float_form: bool, filter: Option<f64>| {
        let (enc, dec) = if float_form {
            (e.alu.encode_float, e.alu.decode_float)
        } else {
            (e.alu.encode, e.alu.decode)
        };
        let cost = counted(enc, dec);
        let error = filter.map_or(e.max, |p| e.max.max(p));
        Route {
            format: f,
            bits,
            encode: enc,
            decode: dec,
            cost,
            filter,
            error,
            score: score(error, cost),
        }
    };
    let best = |routes: Vec<Route<'a>>| {
        routes
            .into_iter()
            .min_by(|a, b| a.score.total_cmp(&b.score).then(a.bits.cmp(&b.bits)))
    };
    if u == Use::Asset {
        return (e.bits <= budget && query.format.is_none()).then(|| of(None, e.bits, false, None));
    }
    if u.filters(query) {
        // The float form in a texture format the texture unit filters.
        let filter = e.filter_figure();
        if !filter.is_finite() {
            return None;
        }
        // A G-buffer is a render target: a shader writes it, so no block format.
        let formats = e.formats.iter().filter(|f| {
            f.holds == Holds::FloatForm
                && f.filterable
                && f.texture.is_some()
                && (u != Use::Gbuffer || f.renderable())
                && f.bits <= budget
                && format_ok(f)
        });
        return best(
            formats
                .map(|f| of(Some(f), f.bits, true, Some(filter)))
                .collect(),
        );
    }
    // Read texel by texel or fetched per vertex: any format of the kind that stores the
    // spec's values exactly, the code's or the float form's.
    let formats = e.formats.iter().filter(|f| {
        let kind = match u {
            Use::Vertex => f.vertex.is_some(),
            _ => f.texture.is_some(),
        };
        kind && f.exact && f.bits <= budget && format_ok(f)
    });
    best(
        formats
            .map(|f| of(Some(f), f.bits, f.holds == Holds::FloatForm, None))
            .collect(),
    )
}

/// One ranked spec under a profile.
#[derive(Clone, Debug)]
pub struct Ranked<'a> {
    pub entry: &'a Entry,
    pub route: Route<'a>,
    pub why: String,
}

/// One ranked tangent-frame spec.
#[derive(Clone, Debug)]
pub struct RankedFrame<'a> {
    pub entry: &'a FrameEntry,
    pub error: f64,
    pub score: f64,
    pub why: String,
}

/// A constraint on a spec and its route, as typed.
type Test = (String, Box<dyn Fn(&Entry, &Route) -> bool>);

/// The explicit constraints that still apply under a profile (and the domain it implies
/// where none is given), in `choose`'s order.
fn explicit(q: &Query, u: Use) -> Vec<Test> {
    let mut c: Vec<Test> = Vec::new();
    if let Some(d) = q.domain.clone().or(u.domain().map(str::to_string)) {
        let typed = if q.domain.is_some() {
            format!("--domain {d}")
        } else {
            format!("--use {} (a {d})", u.name())
        };
        c.push((typed, Box::new(move |e, _| e.domain == d)));
    }
    if let Some(deg) = q.filterable {
        c.push((
            format!("--filterable={deg}"),
            Box::new(move |e, _| e.filterable_within(deg)),
        ));
    }
    if let Some(n) = q.max_encode_alu {
        c.push((
            format!("--max-encode-alu {n}"),
            Box::new(move |_, r| r.encode <= n),
        ));
    }
    if let Some(n) = q.max_decode_alu {
        c.push((
            format!("--max-decode-alu {n}"),
            Box::new(move |_, r| r.decode <= n),
        ));
    }
    if q.portable {
        c.push(("--portable".into(), Box::new(|e, _| e.portable)));
    }
    c
}

/// The storage a profile needs, in words, for the error that finds none.
fn storage_words(u: Use, q: &Query) -> String {
    let within = q
        .bits
        .map_or(String::new(), |b| format!(" of at most {b} bits"));
    let named = q
        .format
        .as_ref()
        .map_or(String::new(), |f| format!(" spelled {f}"));
    match (u, u.filters(q)) {
        (Use::Asset, _) => format!("a code{within}{named}"),
        (_, true) => format!("a filterable texture format{within}{named} holding the float form"),
        (Use::Vertex, _) => format!("a vertex format{within}{named} storing it exactly"),
        _ => format!("a texture format{within}{named} storing it exactly"),
    }
}

/// The specs of `catalogue` ranked for `u`, best first by score (ties: fewer bits,
/// lower mean, then the id), each with the route it takes and why it is there.
pub fn rank<'a>(catalogue: &'a Catalogue, query: &Query, u: Use) -> Result<Vec<Ranked<'a>>, Empty> {
    let mut left: Vec<(&Entry, Route)> = Vec::new();
    for e in &catalogue.specs {
        if let Some(r) = route(u, e, query) {
            left.push((e, r));
        }
    }
    if left.is_empty() {
        return Err(Empty {
            constraint: format!("--use {}", u.name()),
            before: format!("no spec has {}", storage_words(u, query)),
        });
    }
    let mut met = vec![storage_words(u, query)];
    for (typed, test) in explicit(query, u) {
        let next: Vec<(&Entry, Route)> = left.iter().filter(|(e, r)| test(e, r)).cloned().collect();
        if next.is_empty() {
            let names: Vec<&str> = left.iter().take(8).map(|(e, _)| e.spec.as_str()).collect();
            return Err(Empty {
                constraint: typed,
                before: format!(
                    "{} specs meet --use {} with {} ({}{})",
                    left.len(),
                    u.name(),
                    met.join(", "),
                    names.join(", "),
                    if left.len() > 8 { ", …" } else { "" }
                ),
            });
        }
        met.push(typed);
        left = next;
    }
    left.sort_by(|(a, ra), (b, rb)| {
        ra.score
            .total_cmp(&rb.score)
            .then(ra.bits.cmp(&rb.bits))
            .then(a.mean.total_cmp(&b.mean))
            .then(a.spec.cmp(&b.spec))
    });
    let why: Vec<String> = (0..left.len())
        .map(|i| why(u, &left[i], left.get(i + 1), i))
        .collect();
    Ok(left
        .into_iter()
        .zip(why)
        .map(|((entry, route), why)| Ranked { entry, route, why })
        .collect())
}

/// `best`, `#2`, …
fn place(i: usize) -> String {
    if i == 0 {
        "best".into()
    } else {
        format!("#{}", i + 1)
    }
}

/// The line under a row: its score, what decided it, and what the next row trades.
fn why(u: Use, (e, r): &(&Entry, Route), next: Option<&(&Entry, Route)>, i: usize) -> String {
    let per = match u {
        Use::Gbuffer | Use::NormalMap => "a pixel",
        _ => "a vertex",
    };
    let mut parts = vec![if u == Use::Asset {
        format!("{} by sample max {:.4}°", place(i), r.error)
    } else {
        format!(
            "{} by score {:.4} = {:.4}° × (1 + {}/{ALU_WEIGHT})",
            place(i),
            r.score,
            r.error,
            r.cost
        )
    }];
    parts.push(match r.filter {
        Some(p) if p > e.max => format!(
            "error: filtering p99 {p:.4}° at {DECIDING_SEPARATION}° apart (sample max {:.4}°)",
            e.max
        ),
        Some(p) => {
            format!("error: sample max (filtering p99 {p:.4}° at {DECIDING_SEPARATION}° apart)")
        }
        None if u == Use::Asset => "only the error counts".into(),
        None => "error: sample max".into(),
    });
    let functions = |f: &str| {
        if r.format.is_some_and(|f| f.holds == Holds::FloatForm) {
            format!("{f}_float")
        } else {
            f.to_string()
        }
    };
    match u {
        Use::Gbuffer => parts.push(format!(
            "{} {} and {} {} ALU {per}",
            functions("encode"),
            r.encode,
            functions("decode"),
            r.decode
        )),
        Use::Vertex | Use::NormalMap => parts.push(format!(
            "{} {} ALU {per} (encoded offline: {} {})",
            functions("decode"),
            r.decode,
            functions("encode"),
            r.encode
        )),
        Use::Asset | Use::Frame => {}
    }
    if let Some(s) = &e.seam
        && r.filter.is_some()
    {
        parts.push(format!("seam: {s}"));
    }
    parts.push(if e.tables.is_empty() {
        "no table".into()
    } else {
        let t: Vec<String> = e
            .tables
            .iter()
            .map(|t| format!("{} ({} bytes)", t.name, t.bytes))
            .collect();
        format!("reads table {}", t.join(", "))
    });
    parts.push(match r.format {
        Some(f) => format!(
            "{}, {} bits{}{}",
            f.name(),
            f.bits,
            if r.filter.is_some() {
                ", filterable"
            } else {
                ""
            },
            if f.exact {
                ""
            } else {
                " (its channels round the fields: figures before storing)"
            }
        ),
        None => format!("{} bits as stored", r.bits),
    });
    if let Some(engine) = &e.engine {
        parts.push(format!("the bits {engine} stores"));
    }
    if let Some((n, nr)) = next {
        let alu = if u == Use::Asset {
            String::new()
        } else {
            format!(
                ", {} ALU ({:+})",
                nr.cost,
                i64::from(nr.cost) - i64::from(r.cost)
            )
        };
        parts.push(format!(
            "next, {}: error {:.4}° ({:+.4}°){alu}, {} bits",
            n.spec,
            nr.error,
            nr.error - r.error,
            nr.bits
        ));
    }
    parts.join("; ")
}

/// The tangent-frame specs ranked for `--use frame` within `query`'s budget: no
/// handedness flip, the error the largest sample max of normal, tangent and bitangent,
/// the cost the decoder's instructions a vertex.
pub fn rank_frames<'a>(
    catalogue: &'a Catalogue,
    query: &Query,
) -> Result<Vec<RankedFrame<'a>>, Empty> {
    let budget = query.bits.unwrap_or(u32::MAX);
    let mut left: Vec<&FrameEntry> = catalogue
        .frames
        .iter()
        .filter(|f| f.flips == 0 && f.bits <= budget)
        .collect();
    if let Some(n) = query.max_decode_alu {
        left.retain(|f| f.alu.decode <= n);
    }
    if let Some(n) = query.max_encode_alu {
        left.retain(|f| f.alu.encode <= n);
    }
    if left.is_empty() {
        let smallest = catalogue.frames.iter().map(|f| f.bits).min().unwrap_or(0);
        return Err(Empty {
            constraint: "--use frame".into(),
            before: format!(
                "no tangent-frame spec keeps every sign within {}{} (the smallest has {smallest} bits)",
                query
                    .bits
                    .map_or("any size".into(), |b| format!("{b} bits")),
                match (query.max_encode_alu, query.max_decode_alu) {
                    (None, None) => String::new(),
                    _ => " and the ALU limits".into(),
                }
            ),
        });
    }
    let s = |f: &FrameEntry| score(f.max(), f.alu.decode);
    left.sort_by(|a, b| {
        s(a).total_cmp(&s(b))
            .then(a.bits.cmp(&b.bits))
            .then(a.spec.cmp(&b.spec))
    });
    Ok(left
        .iter()
        .enumerate()
        .map(|(i, f)| {
            let mut parts = vec![format!(
                "{} by score {:.4} = {:.4}° × (1 + {}/{ALU_WEIGHT})",
                place(i),
                s(f),
                f.max(),
                f.alu.decode
            )];
            parts.push(format!(
                "error: the largest sample max of normal {:.4}°, tangent {:.4}°, bitangent {:.4}°; no handedness flip",
                f.normal[1], f.tangent[1], f.bitangent[1]
            ));
            parts.push(format!(
                "decode {} ALU a vertex (encoded offline: encode {})",
                f.alu.decode, f.alu.encode
            ));
            parts.push(match &f.engine {
                Some(e) => format!("{e} reads these bits"),
                None => "no engine reads these bits: decode them in your shader".into(),
            });
            if let Some(n) = left.get(i + 1) {
                parts.push(format!(
                    "next, {}: error {:.4}° ({:+.4}°), {} ALU ({:+}), {} bits",
                    n.spec,
                    n.max(),
                    n.max() - f.max(),
                    n.alu.decode,
                    i64::from(n.alu.decode) - i64::from(f.alu.decode),
                    n.bits
                ));
            }
            RankedFrame {
                entry: f,
                error: f.max(),
                score: s(f),
                why: parts.join("; "),
            }
        })
        .collect())
}
