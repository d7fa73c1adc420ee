//! `list`: every family, size and option, as a table and as JSON.

use crate::common::*;
use std::collections::BTreeSet;
use unitpack::codecs::{FAMILIES, Spec};

#[test]
fn list_names_every_codec_with_its_bit_sizes() {
    let r = ok(&["list"]);
    assert!(r.stderr.is_empty(), "{r:?}");
    let header = r.stdout.lines().next().expect("header line");
    for col in ["family", "domain", "precise", "source"] {
        assert!(header.contains(col), "list header {header:?} lacks {col}");
    }
    for f in FAMILIES {
        let c = f.info();
        let line = r
            .stdout
            .lines()
            .find(|l| l.split_whitespace().next() == Some(c.name))
            .unwrap_or_else(|| panic!("list has no line for {}: {r:?}", c.name));
        // Every spelling a user types is listed, and each one parses.
        for (spelled, _) in c.spellings() {
            assert!(
                r.stdout.contains(&spelled),
                "list lacks the spec {spelled}: {r:?}"
            );
            spelled.parse::<Spec>().expect("listed specs parse");
        }
        assert!(
            line.contains(c.source),
            "list line for {} lacks its source: {line:?}",
            c.name
        );
        assert!(
            r.stdout.contains(c.title),
            "list lacks the title of {}",
            c.name
        );
        for o in c.options {
            assert!(
                r.stdout.contains(&format!("option {}=", o.key)) && r.stdout.contains(o.help),
                "list lacks option {} of {}",
                o.key,
                c.name
            );
        }
    }
}

/// The whole table, held to tests/cli/list.txt: a change to any family's line shows up
/// in review (`UNITPACK_REFRESH=1 cargo test --release` rewrites the file).
#[test]
fn list_snapshot() {
    let r = ok(&["list"]);
    matches_stored("list.txt", &r.stdout);
}

#[test]
fn list_json_has_every_spelling_a_user_types() {
    let r = ok(&["list", "--json"]);
    let v: serde_json::Value = serde_json::from_str(&r.stdout).expect("list --json is JSON");
    assert_eq!(v["grammar"], "NAME[BITS][p][:key=value,...]");
    let fams = v["families"].as_array().unwrap();
    assert_eq!(fams.len(), FAMILIES.len());
    let mut typed = BTreeSet::new();
    for f in fams {
        for s in f["specs"].as_array().unwrap() {
            let spec = s["spec"].as_str().unwrap();
            spec.parse::<Spec>()
                .unwrap_or_else(|e| panic!("{spec}: {e}"));
            typed.insert(spec.to_string());
            if let Some(p) = s["precise"].as_str() {
                assert!(p.parse::<Spec>().unwrap().precise(), "{p}");
            }
        }
    }
    assert!(
        typed.contains("snorm8x3") && !typed.contains("snorm3"),
        "{typed:?}"
    );
    let oct = fams.iter().find(|f| f["family"] == "oct").unwrap();
    assert_eq!(oct["options"][0]["key"], "layout");
    assert_eq!(oct["options"][0]["default"], "snorm");
    // The table shows the same spellings, and the grammar.
    let table = ok(&["list"]).stdout;
    for t in &typed {
        assert!(table.contains(t.as_str()), "{t}");
    }
    assert!(table.contains("NAME[BITS][p][:key=value,...]"));
}
