//! `choose`: each constraint keeps what it says, each order ranks by its figure, an
//! impossible request names the constraint that emptied the list, and the README's
//! recommendations are what the binary answers.

use crate::common::*;
use serde_json::Value;
use std::collections::BTreeSet;

/// `list --json`'s per-spec figures.
fn listed() -> Vec<Value> {
    let r = ok(&["list", "--json"]);
    let v: Value = serde_json::from_str(&r.stdout).expect("list --json is JSON");
    v["specs"]
        .as_array()
        .expect("list --json has specs")
        .clone()
}

fn ids(v: &[Value]) -> BTreeSet<String> {
    v.iter()
        .map(|e| e["spec"].as_str().expect("a spec id").to_string())
        .collect()
}

fn f(e: &Value, key: &str) -> f64 {
    e[key].as_f64().unwrap_or_else(|| panic!("{key} of {e}"))
}

#[test]
fn the_16_bit_sphere_spec_with_the_lowest_sample_max_comes_first() {
    let r = ok(&[
        "choose", "--bits", "16", "--domain", "sphere", "--by", "max", "--json",
    ]);
    let ranked: Value = serde_json::from_str(&r.stdout).unwrap();
    let first = &ranked[0];
    let candidates: Vec<Value> = listed()
        .into_iter()
        .filter(|e| e["bits"] == 16 && e["domain"] == "sphere")
        .collect();
    let lowest = candidates
        .iter()
        .map(|e| f(e, "max"))
        .fold(f64::INFINITY, f64::min);
    assert_eq!(f(first, "max"), lowest, "{first}");
    let best: Vec<&str> = candidates
        .iter()
        .filter(|e| f(e, "max") == lowest)
        .map(|e| e["spec"].as_str().unwrap())
        .collect();
    assert!(best.contains(&first["spec"].as_str().unwrap()), "{best:?}");
    assert_eq!(first["rank"], 1);
    assert!(
        first["why"].as_str().unwrap().contains("sample max"),
        "{first}"
    );
}

/// Each constraint alone keeps exactly the specs of `list --json` its definition keeps.
#[test]
fn each_constraint_filters_as_stated() {
    let all = listed();
    let keep = |test: &dyn Fn(&Value) -> bool| -> BTreeSet<String> {
        ids(&all.iter().filter(|e| test(e)).cloned().collect::<Vec<_>>())
    };
    let p99_at_5 = |e: &Value| -> f64 {
        if !e["not_filterable"].is_null()
            || e["filtering"].is_null()
            || filterable_texels(e).is_empty()
        {
            return f64::INFINITY;
        }
        ["lerp", "resolve"]
            .iter()
            .map(|k| {
                let s = e["filtering"][k]
                    .as_array()
                    .unwrap()
                    .iter()
                    .find(|s| s["separation"] == 5.0)
                    .expect("a 5° row");
                f(s, "p99")
            })
            .fold(0.0, f64::max)
    };
    let cases: Vec<(Vec<&str>, BTreeSet<String>)> = vec![
        (vec!["--bits", "24"], keep(&|e| e["bits"] == 24)),
        (
            vec!["--domain", "hemisphere"],
            keep(&|e| e["domain"] == "hemisphere"),
        ),
        (
            vec!["--format", "RG8SNORM"],
            keep(&|e| {
                e["formats"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .any(|x| x["texture"] == "rg8snorm")
            }),
        ),
        (
            // Vulkan's spelling names the same format.
            vec!["--format", "VK_FORMAT_R8G8_SNORM"],
            keep(&|e| {
                e["formats"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .any(|x| x["vulkan"] == "VK_FORMAT_R8G8_SNORM")
            }),
        ),
        (vec!["--filterable"], keep(&|e| p99_at_5(e) <= 1.0)),
        (vec!["--filterable=0.1"], keep(&|e| p99_at_5(e) <= 0.1)),
        // The bound may follow as its own argument too.
        (vec!["--filterable", "0.1"], keep(&|e| p99_at_5(e) <= 0.1)),
        (
            vec!["--max-encode-alu", "40"],
            keep(&|e| e["alu"]["encode"].as_u64().unwrap() <= 40),
        ),
        (
            vec!["--max-decode-alu", "20"],
            keep(&|e| e["alu"]["decode"].as_u64().unwrap() <= 20),
        ),
        (vec!["--portable"], keep(&|e| e["portable"] == true)),
    ];
    for (args, want) in cases {
        assert!(!want.is_empty(), "{args:?} keeps something");
        assert!(want.len() < all.len(), "{args:?} removes something");
        assert_eq!(ids(&chosen(&args)), want, "choose {args:?}");
    }
    // Together: the intersection.
    let both = chosen(&["--bits", "32", "--portable", "--domain", "sphere"]);
    let want = keep(&|e| e["bits"] == 32 && e["portable"] == true && e["domain"] == "sphere");
    assert_eq!(ids(&both), want);
}

/// The bits a texel of each filterable format of the spec's float form costs.
fn filterable_texels(e: &Value) -> Vec<u64> {
    e["formats"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|x| x["holds"] == "float_form" && x["filterable"] == true)
        .map(|x| x["bits"].as_u64().unwrap())
        .collect()
}

/// A filtered G-buffer costs its float form's texel: with `--filterable`, `--bits N`
/// keeps the specs with a filterable format of N bits a texel, never one whose only
/// filterable storage is wider (eqdist16's float form, unorm8, unorm7 and unorm1, exists
/// only as rgba8unorm at 32 bits, and r16uint is not filtered).
#[test]
fn with_filterable_the_bits_are_the_texels() {
    let all = listed();
    for bits in [16u64, 32, 64] {
        let b = bits.to_string();
        // Any filtering error: which specs remain is decided by their texels alone.
        let got = chosen(&["--bits", &b, "--filterable=180", "--domain", "sphere"]);
        assert!(
            !got.is_empty(),
            "--bits {bits} --filterable finds something"
        );
        for e in &got {
            assert!(
                filterable_texels(e).contains(&bits),
                "--bits {bits}: {} has no filterable {bits}-bit texel: {}",
                e["spec"],
                e["formats"]
            );
        }
        let why = got[0]["why"].as_str().unwrap();
        assert!(why.contains(&format!("{bits} bits a texel")), "{why}");
        if bits == 64 {
            continue;
        }
        let any_wider = all.iter().any(|e| {
            e["domain"] == "sphere"
                && e["bits"] == bits
                && !filterable_texels(e).is_empty()
                && filterable_texels(e).iter().all(|&t| t > bits)
        });
        assert!(
            any_wider,
            "a {bits}-bit code whose float form needs more exists"
        );
    }
    let sixteen = ids(&chosen(&[
        "--bits",
        "16",
        "--filterable=180",
        "--domain",
        "sphere",
    ]));
    for wide in ["eqdist16p", "eqdist_ellipse16", "eqarea_ellipse16"] {
        assert!(!sixteen.contains(wide), "{wide} in {sixteen:?}");
    }
    assert!(sixteen.contains("oct16"), "{sixteen:?}");
    let listed_eqdist = all.iter().find(|e| e["spec"] == "eqdist16").unwrap();
    assert_eq!(filterable_texels(listed_eqdist), [32], "{listed_eqdist}");
}

#[test]
fn each_order_ranks_by_its_figure() {
    let key = |e: &Value, by: &str| -> f64 {
        match by {
            "mean" => f(e, "mean"),
            "max" => f(e, "max"),
            "decode-alu" => f(&e["alu"], "decode"),
            "encode-alu" => f(&e["alu"], "encode"),
            _ => unreachable!(),
        }
    };
    for by in ["mean", "max", "decode-alu", "encode-alu"] {
        let r = chosen(&["--bits", "32", "--by", by]);
        assert!(r.len() > 3);
        for w in r.windows(2) {
            assert!(
                key(&w[0], by) <= key(&w[1], by),
                "--by {by}: {} before {}",
                w[0]["spec"],
                w[1]["spec"]
            );
        }
    }
    // --by filter puts every filterable spec before every unfilterable one.
    let r = chosen(&["--bits", "24", "--by", "filter"]);
    let filterable: Vec<bool> = r
        .iter()
        .map(|e| e["not_filterable"].is_null() && !filterable_texels(e).is_empty())
        .collect();
    assert!(filterable[0]);
    assert!(
        filterable.windows(2).all(|w| w[0] || !w[1]),
        "{filterable:?}"
    );
}

#[test]
fn an_impossible_request_names_the_constraint_that_empties_the_list() {
    let err = fails(&["choose", "--bits", "17"], "");
    assert!(
        err.contains("--bits 17") && err.contains("catalogue has"),
        "{err}"
    );
    let err = fails(
        &[
            "choose",
            "--bits",
            "16",
            "--domain",
            "sphere",
            "--max-decode-alu",
            "1",
        ],
        "",
    );
    assert!(err.contains("no spec meets --max-decode-alu 1"), "{err}");
    assert!(err.contains("16 bits, sphere"), "says what was left: {err}");
    let err = fails(&["choose", "--format", "no-such-format"], "");
    assert!(err.contains("--format no-such-format"), "{err}");
    // A misspelt format is named as one, with the spelling meant.
    let err = fails(&["choose", "--format", "rg8snrom"], "");
    assert!(
        err.contains("is spelled so") && err.contains("did you mean rg8snorm?"),
        "{err}"
    );
    // A real format no spec of the other constraints is written to is not a misspelling.
    let err = fails(&["choose", "--bits", "32", "--format", "rg8snorm"], "");
    assert!(!err.contains("spelled so"), "{err}");
    ok(&["choose", "--format", "VK_FORMAT_R8G8_SNORM"]);
    // A filter bound must be a positive number of degrees.
    for bad in ["--filterable=0", "--filterable=-1", "--filterable=nan"] {
        let err = fails(&["choose", bad], "");
        assert!(err.contains("positive number of degrees"), "{bad}: {err}");
    }
}

#[test]
fn the_table_says_why_each_spec_is_there() {
    let r = ok(&[
        "choose",
        "--bits",
        "16",
        "--domain",
        "hemisphere",
        "--limit",
        "3",
    ]);
    let lines: Vec<&str> = r.stdout.lines().collect();
    assert!(
        lines[0].starts_with("spec") && lines[0].contains("formats"),
        "{}",
        r.stdout
    );
    assert!(
        lines[2].trim_start().starts_with("best by sample max"),
        "{}",
        r.stdout
    );
    assert!(lines[4].trim_start().starts_with("#2 by"), "{}", r.stdout);
    assert!(lines[2].contains("16 bits, hemisphere"), "{}", r.stdout);
    assert!(
        r.stdout.contains("more (--limit 0 shows all)"),
        "{}",
        r.stdout
    );
}

/// The README's recommendations: each command, run, ranks first what the table says.
#[test]
fn the_readme_recommendations_are_what_choose_answers() {
    let readme = std::fs::read_to_string(manifest_dir().join("README.md")).unwrap();
    let rows: Vec<&str> = readme
        .lines()
        .filter(|l| l.starts_with("| ") && l.contains("| `--"))
        .collect();
    assert!(rows.len() >= 5, "the README's recommendation table");
    for row in rows {
        let cells: Vec<&str> = row.split(" | ").collect();
        let args: Vec<&str> = cells[1].trim_matches('`').split(' ').collect();
        let first = cells[2]
            .split('`')
            .nth(1)
            .expect("the first choice in backticks");
        let r = ok(&[&["choose"][..], &args, &["--json", "--limit", "1"]].concat());
        let v: Value = serde_json::from_str(&r.stdout).unwrap();
        assert_eq!(v[0]["spec"], first, "choose {args:?}");
    }
}
