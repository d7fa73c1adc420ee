//! The README's recommendations for common cases: each case is a `choose` query, and the
//! table shows what `choose` ranks first for it. `tests/readme.rs` holds the README's
//! block to [`table`] of the compiled-in catalogue, and `tests/cli/choose.rs` runs each
//! case's command through the binary.

use super::catalogue::{Catalogue, Entry};
use super::choose::{Order, Query, choose};

/// One common case.
pub struct Case {
    pub what: &'static str,
    pub query: Query,
    pub order: Order,
}

impl Case {
    /// The `choose` arguments of the case, as a user types them.
    pub fn args(&self) -> Vec<String> {
        let q = &self.query;
        let mut a: Vec<String> = Vec::new();
        if let Some(b) = q.bits {
            a.extend(["--bits".into(), b.to_string()]);
        }
        if let Some(f) = &q.format {
            a.extend(["--format".into(), f.clone()]);
        }
        if let Some(d) = &q.domain {
            a.extend(["--domain".into(), d.clone()]);
        }
        if let Some(deg) = q.filterable {
            a.push(format!("--filterable={deg}"));
        }
        if let Some(n) = q.max_encode_alu {
            a.extend(["--max-encode-alu".into(), n.to_string()]);
        }
        if let Some(n) = q.max_decode_alu {
            a.extend(["--max-decode-alu".into(), n.to_string()]);
        }
        if q.portable {
            a.push("--portable".into());
        }
        let by = match self.order {
            Order::Mean => "mean",
            Order::Max => "max",
            Order::DecodeAlu => "decode-alu",
            Order::EncodeAlu => "encode-alu",
            Order::Filter => "filter",
        };
        a.extend(["--by".into(), by.into()]);
        a
    }
}

/// The cases, in the README's order. A G-buffer is decoded per pixel, so its cases hold
/// the decoder to 40 instructions; vertex and texture cases name their format.
pub fn cases() -> Vec<Case> {
    let gbuffer = |bits| Query {
        bits: Some(bits),
        domain: Some("sphere".into()),
        max_decode_alu: Some(40),
        portable: true,
        ..Query::default()
    };
    let format = |f: &str, domain: &str| Query {
        format: Some(f.into()),
        domain: Some(domain.into()),
        ..Query::default()
    };
    let case = |what, query, order| Case { what, query, order };
    vec![
        case("G-buffer normals in 16 bits", gbuffer(16), Order::Max),
        case("G-buffer normals in 24 bits", gbuffer(24), Order::Max),
        case("G-buffer normals in 32 bits", gbuffer(32), Order::Max),
        case(
            "a G-buffer that is filtered or MSAA-resolved, 32 bits a texel",
            Query {
                filterable: Some(1.0),
                ..gbuffer(32)
            },
            Order::Max,
        ),
        case(
            "the lowest error in 16 bits, encoded offline",
            Query {
                bits: Some(16),
                domain: Some("sphere".into()),
                ..Query::default()
            },
            Order::Max,
        ),
        case(
            "vertex normals as snorm16x2",
            format("snorm16x2", "sphere"),
            Order::Max,
        ),
        case(
            "vertex normals as unorm8x4",
            format("unorm8x4", "sphere"),
            Order::Max,
        ),
        case(
            "tangent-space normal maps in BC5",
            format("bc5-rg-unorm", "hemisphere"),
            Order::Max,
        ),
        case(
            "tangent-space normal maps in RG8",
            format("rg8snorm", "hemisphere"),
            Order::Max,
        ),
    ]
}

/// Where the case stores the first choice: the filterable texel where it filters, the
/// format it names, else the code's format.
fn stored_as(case: &Case, e: &Entry) -> String {
    let q = &case.query;
    let f = if q.filterable.is_some() {
        e.filterable_storage()
    } else if let Some(name) = &q.format {
        e.formats.iter().find(|f| f.matches(name))
    } else {
        e.formats.first()
    };
    f.map_or_else(String::new, |f| format!("{}, {} bits", f.name(), f.bits))
}

/// The README's table: each case, its command and what `choose` ranks first.
pub fn table(c: &Catalogue) -> String {
    let mut s = String::from(
        "| for | `unitpack choose …` | first choice | stored as | mean | sample max | encode / decode ALU |\n\
         |---|---|---|---|---|---|---|\n",
    );
    for case in cases() {
        let first = choose(c, &case.query, case.order)
            .ok()
            .and_then(|r| r.into_iter().next());
        match first {
            Some(ch) => {
                let e = ch.entry;
                s.push_str(&format!(
                    "| {} | `{}` | `{}` | {} | {:.4}° | {:.4}° | {} / {} |\n",
                    case.what,
                    case.args().join(" "),
                    e.spec,
                    stored_as(&case, e),
                    e.mean,
                    e.max,
                    e.alu.encode,
                    e.alu.decode
                ));
            }
            None => s.push_str(&format!(
                "| {} | `{}` | none | | | | |\n",
                case.what,
                case.args().join(" ")
            )),
        }
    }
    s
}
