//! `choose`: the catalogue filtered by a user's constraints and ranked by one figure.
//!
//! Constraints are applied in a fixed order (bits, format, domain, filterable, encode
//! ALU, decode ALU, portable), so that when nothing is left the answer can name the
//! constraint that emptied the list and say what was left before it.

use super::catalogue::{Catalogue, Entry};
use super::filtering::DECIDING_SEPARATION;
use super::query::{Empty, Query};

/// What the ranking orders by, best first.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Order {
    /// Mean round-trip error.
    Mean,
    /// Sample maximum of the round-trip error.
    Max,
    /// ALU instructions of the packed decoder.
    DecodeAlu,
    /// ALU instructions of the packed encoder.
    EncodeAlu,
    /// 99th percentile of the filtering error at the deciding separation.
    Filter,
}

impl Order {
    fn key(self, e: &Entry) -> f64 {
        match self {
            Order::Mean => e.mean,
            Order::Max => e.max,
            Order::DecodeAlu => f64::from(e.alu.decode),
            Order::EncodeAlu => f64::from(e.alu.encode),
            Order::Filter => e.filter_figure(),
        }
    }

    /// The figure a row is ranked by, in words.
    fn describe(self, e: &Entry) -> String {
        match self {
            Order::Mean => format!("mean error {:.4}°", e.mean),
            Order::Max => format!("sample max {:.4}°", e.max),
            Order::DecodeAlu => format!("decode {} ALU", e.alu.decode),
            Order::EncodeAlu => format!("encode {} ALU", e.alu.encode),
            Order::Filter => match e.filter_figure() {
                f if f.is_finite() => {
                    format!("filtering p99 {f:.4}° at {DECIDING_SEPARATION}°")
                }
                _ => "not filterable".to_string(),
            },
        }
    }
}

/// Refuses a `--format` that is no spelling of any format in the catalogue (a typo such as
/// `rg8snrom` would otherwise read as "no spec meets it"), naming the nearest spellings.
pub(super) fn unknown_format(catalogue: &Catalogue, typed: &str) -> Result<(), Empty> {
    let formats = || catalogue.specs.iter().flat_map(|e| &e.formats);
    if formats().any(|x| x.matches(typed)) {
        return Ok(());
    }
    let typed_lower = typed.trim().to_ascii_lowercase();
    let mut spellings: Vec<String> = formats()
        .flat_map(|x| x.spellings())
        .map(str::to_ascii_lowercase)
        .collect();
    spellings.sort();
    spellings.dedup();
    let distance = |s: &String| strsim::levenshtein(&typed_lower, s);
    let best = spellings.iter().map(distance).min().unwrap_or(usize::MAX);
    let nearest: Vec<&str> = spellings
        .iter()
        .filter(|s| distance(s) == best)
        .map(String::as_str)
        .collect();
    Err(Empty {
        constraint: format!("--format {typed}"),
        before: format!(
            "no format the catalogue's specs are written to is spelled so; did you mean {}? \
             (`unitpack list` names each spec's formats)",
            nearest.join(" or ")
        ),
    })
}

/// One ranked spec and why it is there.
#[derive(Clone, Debug)]
pub struct Choice<'a> {
    pub entry: &'a Entry,
    pub why: String,
}

type Test = Box<dyn Fn(&Entry) -> bool>;

impl Query {
    /// The constraints in the order they apply: as typed, what each keeps, and the test.
    fn constraints(&self) -> Vec<(String, String, Test)> {
        let mut c: Vec<(String, String, Test)> = Vec::new();
        if let Some(b) = self.bits {
            // A filtered G-buffer or texture costs its float form's texel, which may be
            // wider than the code: with `--filterable`, N counts the texel's bits.
            if self.filterable.is_some() {
                c.push((
                    format!("--bits {b}"),
                    format!("a filterable texel of {b} bits"),
                    Box::new(move |e: &Entry| e.filterable_storage().is_some_and(|f| f.bits == b)),
                ));
            } else {
                c.push((
                    format!("--bits {b}"),
                    format!("{b} bits"),
                    Box::new(move |e: &Entry| e.bits == b),
                ));
            }
        }
        if let Some(f) = self.format.clone() {
            let g = f.clone();
            c.push((
                format!("--format {f}"),
                format!("written to {f}"),
                Box::new(move |e: &Entry| e.formats.iter().any(|x| x.matches(&g))),
            ));
        }
        if let Some(d) = self.domain.clone() {
            let g = d.clone();
            c.push((
                format!("--domain {d}"),
                d,
                Box::new(move |e: &Entry| e.domain == g),
            ));
        }
        if let Some(deg) = self.filterable {
            c.push((
                format!("--filterable={deg}"),
                format!("filters within {deg}°"),
                Box::new(move |e: &Entry| e.filterable_within(deg)),
            ));
        }
        if let Some(n) = self.max_encode_alu {
            c.push((
                format!("--max-encode-alu {n}"),
                format!("encode ≤ {n} ALU"),
                Box::new(move |e: &Entry| e.alu.encode <= n),
            ));
        }
        if let Some(n) = self.max_decode_alu {
            c.push((
                format!("--max-decode-alu {n}"),
                format!("decode ≤ {n} ALU"),
                Box::new(move |e: &Entry| e.alu.decode <= n),
            ));
        }
        if self.portable {
            c.push((
                "--portable".to_string(),
                "portable encoder".to_string(),
                Box::new(|e: &Entry| e.portable),
            ));
        }
        c
    }
}

/// The specs of `catalogue` that meet `query`, best first by `order` (ties: fewer bits,
/// lower mean, lower sample max, fewer decode then encode instructions, then the id).
pub fn choose<'a>(
    catalogue: &'a Catalogue,
    query: &Query,
    order: Order,
) -> Result<Vec<Choice<'a>>, Empty> {
    if let Some(f) = &query.format {
        unknown_format(catalogue, f)?;
    }
    let mut left: Vec<&Entry> = catalogue.specs.iter().collect();
    let constraints = query.constraints();
    let mut met: Vec<String> = Vec::new();
    for (typed, kept, test) in &constraints {
        let next: Vec<&Entry> = left.iter().copied().filter(|e| test(e)).collect();
        if next.is_empty() {
            let before = if met.is_empty() {
                format!("the catalogue has {} specs", left.len())
            } else {
                let names: Vec<&str> = left.iter().take(8).map(|e| e.spec.as_str()).collect();
                let more = if left.len() > 8 { ", …" } else { "" };
                format!(
                    "{} specs meet {} ({}{more})",
                    left.len(),
                    met.join(", "),
                    names.join(", ")
                )
            };
            return Err(Empty {
                constraint: typed.clone(),
                before,
            });
        }
        met.push(kept.clone());
        left = next;
    }
    left.sort_by(|a, b| {
        order
            .key(a)
            .total_cmp(&order.key(b))
            .then(a.bits.cmp(&b.bits))
            .then(a.mean.total_cmp(&b.mean))
            .then(a.max.total_cmp(&b.max))
            .then(a.alu.decode.cmp(&b.alu.decode))
            .then(a.alu.encode.cmp(&b.alu.encode))
            .then(a.spec.cmp(&b.spec))
    });
    let meets = if met.is_empty() {
        String::new()
    } else {
        format!("; {}", met.join(", "))
    };
    Ok(left
        .into_iter()
        .enumerate()
        .map(|(i, e)| {
            let place = if i == 0 {
                "best".to_string()
            } else {
                format!("#{}", i + 1)
            };
            let stored = match (query.filterable, e.filterable_storage()) {
                (Some(_), Some(f)) if f.bits > e.bits => format!(
                    "; filtered in {}, {} bits a texel (no format of the code's {} bits holds its float form)",
                    f.name(),
                    f.bits,
                    e.bits
                ),
                (Some(_), Some(f)) => format!("; filtered in {}, {} bits a texel", f.name(), f.bits),
                _ => String::new(),
            };
            Choice {
                entry: e,
                why: format!("{place} by {}{meets}{stored}", order.describe(e)),
            }
        })
        .collect())
}
