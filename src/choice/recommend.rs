//! The README's recommendations: each row is a `choose --use` query at a size, and the
//! table shows what `choose` ranks first for it. `tests/readme.rs` holds the README's
//! block to [`table`] of the compiled-in catalogue, and `tests/cli/choose.rs` runs each
//! case's command through the binary.

use super::catalogue::Catalogue;
use super::profiles::{rank, rank_frames};
use super::query::{Query, Use};

/// One common case.
pub struct Case {
    pub query: Query,
}

impl Case {
    /// The `choose` arguments of the case, as a user types them.
    pub fn args(&self) -> Vec<String> {
        let q = &self.query;
        let mut a: Vec<String> = Vec::new();
        if let Some(u) = q.use_case {
            a.extend(["--use".into(), u.name().into()]);
        }
        if q.no_filter {
            a.push("--no-filter".into());
        }
        if let Some(b) = q.bits {
            a.extend(["--bits".into(), b.to_string()]);
        }
        if let Some(f) = &q.format {
            a.extend(["--format".into(), f.clone()]);
        }
        a
    }

    /// What the case is for, in words.
    pub fn what(&self) -> String {
        let q = &self.query;
        let u = q.use_case.expect("every case names a use");
        let size = match (&q.format, q.bits) {
            (Some(f), _) => format!("in {f}"),
            (None, Some(b)) => format!("{b} bits"),
            (None, None) => String::new(),
        };
        format!("{}, {size}", u.label(u.filters(q)))
    }
}

/// The cases, in the README's order: every profile at the sizes engines store.
pub fn cases() -> Vec<Case> {
    let at = |u: Use, bits: u32| Case {
        query: Query {
            use_case: Some(u),
            bits: Some(bits),
            ..Query::default()
        },
    };
    let mut v = vec![
        at(Use::Gbuffer, 16),
        at(Use::Gbuffer, 32),
        at(Use::Gbuffer, 64),
    ];
    for bits in [16, 32] {
        let mut c = at(Use::Gbuffer, bits);
        c.query.no_filter = true;
        v.push(c);
    }
    v.extend([
        at(Use::Vertex, 16),
        at(Use::Vertex, 32),
        at(Use::Asset, 16),
        at(Use::Asset, 32),
        at(Use::NormalMap, 16),
        at(Use::NormalMap, 32),
        Case {
            query: Query {
                use_case: Some(Use::NormalMap),
                format: Some("bc5-rg-unorm".into()),
                ..Query::default()
            },
        },
        at(Use::Frame, 32),
        at(Use::Frame, 64),
    ]);
    v
}

/// What `choose` ranks first for a case.
pub struct Winner {
    pub spec: String,
    pub family: String,
    /// The format and bits it is stored in, in words.
    pub stored: String,
    /// The error its score counts, degrees.
    pub error: f64,
    /// The instructions of the encoder and decoder its storage runs.
    pub encode: u32,
    pub decode: u32,
    /// The engine that stores or reads the same bits, if one does.
    pub engine: Option<String>,
    /// The line `choose` prints under it.
    pub why: String,
}

/// Each case with what `choose` ranks first for it (`None`: nothing meets it).
pub fn winners(c: &Catalogue) -> Vec<(Case, Option<Winner>)> {
    cases()
        .into_iter()
        .map(|case| {
            let u = case.query.use_case.expect("every case names a use");
            let w = if u == Use::Frame {
                rank_frames(c, &case.query).ok().and_then(|r| {
                    r.into_iter().next().map(|f| Winner {
                        spec: f.entry.spec.clone(),
                        family: f.entry.family.clone(),
                        stored: format!("{} bits", f.entry.bits),
                        error: f.error,
                        encode: f.entry.alu.encode,
                        decode: f.entry.alu.decode,
                        engine: f.entry.engine.clone(),
                        why: f.why,
                    })
                })
            } else {
                rank(c, &case.query, u).ok().and_then(|r| {
                    r.into_iter().next().map(|ch| Winner {
                        spec: ch.entry.spec.clone(),
                        family: ch.entry.family.clone(),
                        stored: match ch.route.stored_in(u) {
                            Some(name) => format!("{name}, {} bits", ch.route.bits),
                            None => format!("{} bits", ch.route.bits),
                        },
                        error: ch.route.error,
                        encode: ch.route.encode,
                        decode: ch.route.decode,
                        engine: ch.entry.engine.clone(),
                        why: ch.why,
                    })
                })
            };
            (case, w)
        })
        .collect()
}

/// The README's table: each case, its command and what `choose` ranks first.
pub fn table(c: &Catalogue) -> String {
    let mut s = String::from(
        "| for | `unitpack choose …` | first choice | stored as | error | encode / decode ALU |\n\
         |---|---|---|---|---|---|\n",
    );
    for (case, w) in winners(c) {
        let row = w.map_or_else(
            || "none | | |".to_string(),
            |w| {
                // An engine is named where it reads a whole frame; a vector format's
                // engine is in its id.
                let by = match (&w.engine, case.query.use_case) {
                    (Some(n), Some(Use::Frame)) => format!(" ({n})"),
                    _ => String::new(),
                };
                format!(
                    "`{}`{by} | {} | {:.4}° | {} / {}",
                    w.spec, w.stored, w.error, w.encode, w.decode
                )
            },
        );
        s.push_str(&format!(
            "| {} | `{}` | {row} |\n",
            case.what(),
            case.args().join(" ")
        ));
    }
    s
}
