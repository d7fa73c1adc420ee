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
//! vertex: each 100 instructions add the error once more to the score. `error`
//! is the round-trip sample max; where the profile filters, the worse of it and the
//! filtering error's 99th percentile at 5° apart, measured in the float form's own format
//! (a block format, used only where `--format` names it, is not measured: its figures are
//! those before compression).
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
    /// Whether the float form is stored (so `encode_float` and `decode_float` run).
    pub float_form: bool,
    /// Bits a texel, vertex or record costs.
    pub bits: u32,
    /// ALU instructions of the encoder and decoder the route runs.
    pub encode: u32,
    pub decode: u32,
    /// The instructions the score counts.
    pub cost: u32,
    /// The filtering error's 99th percentile at the deciding separation, where it filters.
    pub filter: Option<f64>,
    /// The error the score counts, degrees.
    pub error: f64,
    pub score: f64,
}

impl Route<'_> {
    /// The format's name as the use spells it (a vertex format's for a vertex attribute).
    pub fn stored_in(&self, u: Use) -> Option<&str> {
        self.format.map(|f| match (u, &f.vertex) {
            (Use::Vertex, Some(v)) => v.as_str(),
            _ => f.name(),
        })
    }
}

/// A spec's score under a profile: the module's formula.
pub fn score(error: f64, cost: u32) -> f64 {
    error * (1.0 + f64::from(cost) / ALU_WEIGHT)
}

/// A constraint on a spec and the route it takes, as typed.
type Test = (String, Box<dyn Fn(&Entry, &Route) -> bool>);

/// The constraints a user gives that apply to each route (the ALU limits to the functions
/// the route runs, `--portable` to the packed code, the only thing every GPU writes
/// alike) or to the spec (`--filterable`), in `choose`'s order.
fn route_tests(q: &Query) -> Vec<Test> {
    let mut c: Vec<Test> = Vec::new();
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
        c.push((
            "--portable".into(),
            Box::new(|e, r| e.portable && !r.float_form),
        ));
    }
    c
}

/// The best route of `e` under `u` within `query`'s budget and format that passes every
/// one of `tests`, if it has one.
fn route<'a>(u: Use, e: &'a Entry, query: &Query, tests: &[Test]) -> Option<Route<'a>> {
    // A G-buffer encodes interpolated normals, which are not unit length: an encoder that
    // takes its input as it is (glTF's quantization, `Family::keeps_length`) would store
    // their shortness as error that the catalogue's unit vectors do not show, and its
    // missing normalize would rank it ahead of the same storage with one.
    if u == Use::Gbuffer
        && crate::codecs::FAMILIES
            .iter()
            .any(|f| f.info().name == e.family && f.keeps_length())
    {
        return None;
    }
    let budget = query.bits.unwrap_or(u32::MAX);
    let named = |f: &Format| query.format.as_deref().is_none_or(|q| f.matches(q));
    // Encoder and decoder counted: a G-buffer runs both per pixel; a vertex stream and
    // a normal map are encoded offline.
    let counted = |enc: u32, dec: u32| match u {
        Use::Gbuffer => enc + dec,
        Use::Vertex | Use::NormalMap | Use::Frame => dec,
        Use::Asset => 0,
    };
    let of = |f: Option<&'a Format>, bits: u32, float_form: bool, filter: Option<f64>| {
        let (encode, decode) = if float_form {
            (e.alu.encode_float, e.alu.decode_float)
        } else {
            (e.alu.encode, e.alu.decode)
        };
        let cost = counted(encode, decode);
        let error = filter.map_or(e.max, |p| e.max.max(p));
        Route {
            format: f,
            float_form,
            bits,
            encode,
            decode,
            cost,
            filter,
            error,
            score: score(error, cost),
        }
    };
    let candidates: Vec<Route<'a>> = if u == Use::Asset {
        vec![of(None, e.bits, false, None)]
    } else if u.filters(query) {
        // The float form in the format its filtering is measured in, where a texture unit
        // filters it; a normal map also in a block format the user names, whose figures
        // are those before compression (the line under the row says so).
        let filter = e.filter_figure();
        let measured = e.filterable_storage().filter(|f| f.texture.is_some());
        let named_blocks = e
            .formats
            .iter()
            .filter(|f| u == Use::NormalMap && f.block() && query.format.is_some());
        measured
            .into_iter()
            .chain(named_blocks)
            .filter(|_| filter.is_finite())
            .map(|f| of(Some(f), f.bits, true, Some(filter)))
            .collect()
    } else {
        // Read texel by texel (a render target, so renderable) or fetched per vertex: any
        // format of the kind that stores the spec's values exactly, the code's or the
        // float form's.
        e.formats
            .iter()
            .filter(|f| match u {
                Use::Vertex => f.vertex.is_some(),
                _ => f.texture.is_some() && f.renderable(),
            })
            .filter(|f| f.exact)
            .map(|f| of(Some(f), f.bits, f.holds == Holds::FloatForm, None))
            .collect()
    };
    candidates
        .into_iter()
        .filter(|r| r.bits <= budget && r.format.is_none_or(&named))
        .filter(|r| tests.iter().all(|(_, t)| t(e, r)))
        .min_by(|a, b| a.score.total_cmp(&b.score).then(a.bits.cmp(&b.bits)))
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
        (Use::Asset, _) => format!("a code{within}"),
        (_, true) => format!("a filterable texture format{within}{named} holding the float form"),
        (Use::Vertex, _) => format!("a vertex format{within}{named} storing it exactly"),
        _ => format!("a render-target format{within}{named} storing it exactly"),
    }
}

/// The specs of `catalogue` ranked for `u`, best first by score (ties: fewer bits,
/// lower mean, then the id), each with the route it takes and why it is there. The
/// constraints apply in order — the domain (given, or the use's), the storage, then
/// `--filterable`, the ALU limits and `--portable` on each route — so that an empty
/// answer names the one that emptied it.
pub fn rank<'a>(catalogue: &'a Catalogue, query: &Query, u: Use) -> Result<Vec<Ranked<'a>>, Empty> {
    if let Some(f) = &query.format {
        super::choose::unknown_format(catalogue, f)?;
    }
    let domain = query.domain.clone().or(u.domain().map(str::to_string));
    let specs: Vec<&Entry> = catalogue
        .specs
        .iter()
        .filter(|e| domain.as_ref().is_none_or(|d| &e.domain == d))
        .collect();
    let of_domain = domain.as_ref().map_or("".to_string(), |d| format!("{d} "));
    let tests = route_tests(query);
    let routes = |k: usize| -> Vec<(&'a Entry, Route<'a>)> {
        specs
            .iter()
            .filter_map(|e| route(u, e, query, &tests[..k]).map(|r| (*e, r)))
            .collect()
    };
    let mut left = routes(0);
    if left.is_empty() {
        return Err(Empty {
            constraint: format!("--use {}", u.name()),
            before: format!("no {of_domain}spec has {}", storage_words(u, query)),
        });
    }
    let mut met = vec![storage_words(u, query)];
    for k in 1..=tests.len() {
        let next = routes(k);
        if next.is_empty() {
            let names: Vec<&str> = left.iter().take(8).map(|(e, _)| e.spec.as_str()).collect();
            return Err(Empty {
                constraint: tests[k - 1].0.clone(),
                before: format!(
                    "{} {of_domain}specs meet --use {} with {} ({}{})",
                    left.len(),
                    u.name(),
                    met.join(", "),
                    names.join(", "),
                    if left.len() > 8 { ", …" } else { "" }
                ),
            });
        }
        met.push(tests[k - 1].0.clone());
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

/// `best by score 0.4847 = 0.3847° × (1 + 26/100)`: a row's score, spelt out.
fn scored(i: usize, error: f64, cost: u32) -> String {
    format!(
        "{} by score {:.4} = {error:.4}° × (1 + {cost}/{ALU_WEIGHT})",
        place(i),
        score(error, cost)
    )
}

/// What the next row trades: its error and bits, and its instructions where they count.
fn next_trade(
    spec: &str,
    (error, bits): (f64, u32),
    d_error: f64,
    alu: Option<(u32, i64)>,
) -> String {
    let alu = alu.map_or(String::new(), |(n, d)| format!(", {n} ALU ({d:+})"));
    format!("next, {spec}: error {error:.4}° ({d_error:+.4}°){alu}, {bits} bits")
}

/// What put `a` before `b` where their scores are equal: the sort's next key that differs.
fn tie_break(a: (&Entry, &Route), b: (&Entry, &Route)) -> &'static str {
    if a.1.bits != b.1.bits {
        "fewer bits"
    } else if a.0.mean != b.0.mean {
        "the lower mean error"
    } else {
        "the id, every figure being equal"
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
        scored(i, r.error, r.cost)
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
    let function = |f: &str| {
        if r.float_form {
            format!("{f}_float")
        } else {
            f.to_string()
        }
    };
    match u {
        Use::Gbuffer => parts.push(format!(
            "{} {} and {} {} ALU {per}",
            function("encode"),
            r.encode,
            function("decode"),
            r.decode
        )),
        Use::Vertex | Use::NormalMap => parts.push(format!(
            "{} {} ALU {per} (encoded offline: {} {})",
            function("decode"),
            r.decode,
            function("encode"),
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
        Some(f) => {
            let mut s = format!(
                "{}, {} bits{}",
                r.stored_in(u).unwrap_or(f.name()),
                f.bits,
                if r.filter.is_some() {
                    ", filterable"
                } else {
                    ""
                }
            );
            if f.block() {
                s.push_str(" (block-compressed: the figures are before compression)");
            } else if !f.exact {
                s.push_str(" (its channels round the fields: figures before storing)");
            }
            if u == Use::Gbuffer
                && let Some(n) = f.render_note()
            {
                s.push_str(&format!(" ({n})"));
            }
            s
        }
        None => format!("{} bits as stored", r.bits),
    });
    if let Some(engine) = &e.engine {
        parts.push(format!("{engine}'s decoder reads these bits"));
    }
    if let Some((n, nr)) = next {
        if nr.score == r.score {
            parts.push(format!(
                "ties {} on score: first by {}",
                n.spec,
                tie_break((e, r), (n, nr))
            ));
        } else {
            let alu = (u != Use::Asset).then(|| (nr.cost, i64::from(nr.cost) - i64::from(r.cost)));
            parts.push(next_trade(
                &n.spec,
                (nr.error, nr.bits),
                nr.error - r.error,
                alu,
            ));
        }
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
    type FrameTest = (String, Box<dyn Fn(&FrameEntry) -> bool>);
    let mut tests: Vec<FrameTest> = vec![("--use frame".into(), Box::new(|f| f.flips == 0))];
    if let Some(b) = query.bits {
        tests.push((format!("--bits {b}"), Box::new(move |f| f.bits <= b)));
    }
    if let Some(n) = query.max_encode_alu {
        tests.push((
            format!("--max-encode-alu {n}"),
            Box::new(move |f| f.alu.encode <= n),
        ));
    }
    if let Some(n) = query.max_decode_alu {
        tests.push((
            format!("--max-decode-alu {n}"),
            Box::new(move |f| f.alu.decode <= n),
        ));
    }
    let mut left: Vec<&FrameEntry> = catalogue.frames.iter().collect();
    let mut met: Vec<String> = Vec::new();
    for (typed, test) in &tests {
        let next: Vec<&FrameEntry> = left.iter().copied().filter(|f| test(f)).collect();
        if next.is_empty() {
            let smallest = left.iter().map(|f| f.bits).min().unwrap_or(0);
            let names: Vec<&str> = left.iter().map(|f| f.spec.as_str()).collect();
            return Err(Empty {
                constraint: typed.clone(),
                before: if typed.starts_with("--bits") {
                    format!(
                        "the smallest tangent-frame spec that keeps every sign has {smallest} bits"
                    )
                } else {
                    format!(
                        "{} frame specs meet {} ({})",
                        left.len(),
                        met.join(", "),
                        names.join(", ")
                    )
                },
            });
        }
        met.push(typed.clone());
        left = next;
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
            let mut parts = vec![scored(i, f.max(), f.alu.decode)];
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
            if let Some(n) = left.get(i + 1)
                && s(n) == s(f)
            {
                parts.push(format!("ties {} on score: first by fewer bits or the id", n.spec));
            }
            if let Some(n) = left.get(i + 1)
                && s(n) != s(f)
            {
                let d = i64::from(n.alu.decode) - i64::from(f.alu.decode);
                parts.push(next_trade(
                    &n.spec,
                    (n.max(), n.bits),
                    n.max() - f.max(),
                    Some((n.alu.decode, d)),
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
