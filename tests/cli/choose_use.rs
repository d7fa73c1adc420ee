//! `choose --use`: every use at 16, 32 and 64 bits stores what it ranks in a format that
//! holds it within the bits asked, and its order is the score docs/design/choosing.md
//! states, recomputed here from `list --json` alone: per spec, the cheapest route among
//! the formats the use may store it in, error × (1 + ALU/100).

use crate::common::*;
use serde_json::Value;

const USES: [&str; 4] = ["gbuffer", "vertex", "asset", "normal-map"];

/// `list --json`, parsed.
fn list() -> Value {
    serde_json::from_str(&ok(&["list", "--json"]).stdout).expect("list --json is JSON")
}

fn num(v: &Value, key: &str) -> f64 {
    v[key].as_f64().unwrap_or_else(|| panic!("{key} of {v}"))
}

fn alu(e: &Value, f: &str) -> f64 {
    num(&e["alu"], f)
}

/// The 99th percentile of the filtering error at 5° apart, lerp and resolve alike
/// (infinite where the float form may not be filtered).
fn filter_p99(e: &Value) -> f64 {
    if !e["not_filterable"].is_null() || e["filtering"].is_null() {
        return f64::INFINITY;
    }
    ["lerp", "resolve"]
        .iter()
        .flat_map(|k| e["filtering"][k].as_array().unwrap().iter())
        .filter(|s| num(s, "separation") == 5.0)
        .map(|s| num(s, "p99"))
        .fold(0.0, f64::max)
}

/// A route as the docs define it: (score, bits, format name, error, the instructions of
/// the encoder and decoder it runs).
type Route = (f64, u64, Option<String>, f64, [f64; 2]);

/// The best route of spec `e` under `use_` within `bits`, by the documented rules.
fn route(use_: &str, filtered: bool, e: &Value, bits: u64) -> Option<Route> {
    // A G-buffer leaves out glTF's quantization, whose encoder does not normalize
    // (docs/commands.md, choose).
    if use_ == "gbuffer" && e["family"] == "gltf_normal" {
        return None;
    }
    let max = num(e, "max");
    let functions = |float_form: bool| -> [f64; 2] {
        if float_form {
            [alu(e, "encode_float"), alu(e, "decode_float")]
        } else {
            [alu(e, "encode"), alu(e, "decode")]
        }
    };
    let cost = |float_form: bool| -> f64 {
        let [enc, dec] = functions(float_form);
        match use_ {
            "gbuffer" => enc + dec,
            "asset" => 0.0,
            _ => dec,
        }
    };
    if use_ == "asset" {
        let b = e["bits"].as_u64().unwrap();
        return (b <= bits).then_some((max, b, None, max, functions(false)));
    }
    let formats = e["formats"].as_array().unwrap();
    let block = |f: &Value| {
        f["channels"]
            .as_array()
            .unwrap()
            .iter()
            .any(|c| c == "block")
    };
    // The float form's own format: the first listed that holds it and is not a block
    // format, the one its filtering is measured in.
    let measured = formats
        .iter()
        .find(|f| f["holds"] == "float_form" && !block(f));
    let mut best: Option<Route> = None;
    for f in formats {
        let fb = f["bits"].as_u64().unwrap();
        let float_form = f["holds"] == "float_form";
        if fb > bits {
            continue;
        }
        let (ok, error) = if filtered {
            let p = filter_p99(e);
            (
                measured == Some(f)
                    && f["filterable"] == true
                    && !f["texture"].is_null()
                    && p.is_finite(),
                max.max(p),
            )
        } else if use_ == "vertex" {
            (!f["vertex"].is_null() && f["exact"] == true, max)
        } else {
            (
                !f["texture"].is_null() && f["exact"] == true && !block(f),
                max,
            )
        };
        if !ok {
            continue;
        }
        let score = error * (1.0 + cost(float_form) / 100.0);
        let name = if use_ == "vertex" {
            f["vertex"].as_str()
        } else {
            f["texture"].as_str()
        }
        .map(str::to_string);
        let better = match &best {
            None => true,
            Some((s, b, ..)) => score < *s || (score == *s && fb < *b),
        };
        if better {
            best = Some((score, fb, name, error, functions(float_form)));
        }
    }
    best
}

/// The use's domain where none is given: a sphere, except normal maps (either).
fn domain_ok(use_: &str, e: &Value) -> bool {
    use_ == "normal-map" || e["domain"] == "sphere"
}

/// Each use at 16, 32 and 64 bits (a G-buffer also unfiltered): the order is the
/// recomputed score's, every row's score and format are the recomputed route's, and
/// the format named is one the spec lists, of the kind the use needs, within the bits.
#[test]
fn each_use_ranks_by_the_score_recomputed_from_list_json() {
    let listed = list();
    let specs = listed["specs"].as_array().unwrap();
    let mut cases: Vec<(&str, bool)> = USES.iter().map(|u| (*u, false)).collect();
    cases.push(("gbuffer", true));
    for (use_, no_filter) in cases {
        let filtered = !no_filter && matches!(use_, "gbuffer" | "normal-map");
        for bits in [16u64, 32, 64] {
            let b = bits.to_string();
            let mut args = vec!["--use", use_, "--bits", &b];
            if no_filter {
                args.push("--no-filter");
            }
            let got = chosen(&args);
            assert!(!got.is_empty(), "{args:?} ranks nothing");
            let mut want: Vec<(Route, f64, String)> = specs
                .iter()
                .filter(|e| domain_ok(use_, e))
                .filter_map(|e| {
                    route(use_, filtered, e, bits)
                        .map(|r| (r, num(e, "mean"), e["spec"].as_str().unwrap().to_string()))
                })
                .collect();
            want.sort_by(|(a, am, an), (b, bm, bn)| {
                a.0.total_cmp(&b.0)
                    .then(a.1.cmp(&b.1))
                    .then(am.total_cmp(bm))
                    .then(an.cmp(bn))
            });
            let got_ids: Vec<&str> = got.iter().map(|r| r["spec"].as_str().unwrap()).collect();
            let want_ids: Vec<&str> = want.iter().map(|w| w.2.as_str()).collect();
            assert_eq!(
                got_ids, want_ids,
                "{args:?}: the order of the recomputed scores"
            );
            for (row, (r, ..)) in got.iter().zip(&want) {
                let (score, rbits, name, error, [enc, dec]) = r;
                assert_eq!(num(row, "route_encode"), *enc, "{args:?} {}", row["spec"]);
                assert_eq!(num(row, "route_decode"), *dec, "{args:?} {}", row["spec"]);
                let cost = match use_ {
                    "gbuffer" => enc + dec,
                    "asset" => 0.0,
                    _ => *dec,
                };
                assert_eq!(num(row, "cost"), cost, "{args:?} {}", row["spec"]);
                let id = &row["spec"];
                assert!(
                    (num(row, "score") - score).abs() <= 1e-12 * score.max(1.0),
                    "{args:?} {id}: score {} against {score}",
                    row["score"]
                );
                assert_eq!(row["stored_bits"].as_u64(), Some(*rbits), "{args:?} {id}");
                assert!(*rbits <= bits, "{args:?} {id}: {rbits} bits");
                assert_eq!(row["stored_in"].as_str(), name.as_deref(), "{args:?} {id}");
                assert_eq!(num(row, "error"), *error, "{args:?} {id}");
                if filtered {
                    let p = filter_p99(row);
                    assert!(p.is_finite() && *error >= p, "{args:?} {id}: filters");
                }
            }
        }
    }
}

/// `--use frame` ranks the tangent-frame specs of `list --json`'s `frames` by the
/// largest sample max of normal, tangent and bitangent × (1 + decode ALU/100), none that
/// flips a sign, each within the bits; below the smallest frame it says how small that is.
#[test]
fn frames_rank_by_their_own_figures() {
    let listed = list();
    let frames = listed["frames"].as_array().expect("list --json has frames");
    assert!(frames.len() >= 6, "{frames:?}");
    for bits in [32u64, 48, 64] {
        let b = bits.to_string();
        let got = chosen(&["--use", "frame", "--bits", &b]);
        let score = |f: &Value| {
            let worst = ["normal", "tangent", "bitangent"]
                .iter()
                .map(|k| f[k][1].as_f64().unwrap())
                .fold(0.0, f64::max);
            (worst * (1.0 + alu(f, "decode") / 100.0), worst)
        };
        let mut want: Vec<&Value> = frames
            .iter()
            .filter(|f| f["bits"].as_u64().unwrap() <= bits && f["flips"] == 0)
            .collect();
        want.sort_by(|a, b| {
            score(a)
                .0
                .total_cmp(&score(b).0)
                .then(a["bits"].as_u64().cmp(&b["bits"].as_u64()))
                .then(a["spec"].as_str().cmp(&b["spec"].as_str()))
        });
        let ids = |v: &[&Value]| -> Vec<String> {
            v.iter()
                .map(|f| f["spec"].as_str().unwrap().to_string())
                .collect()
        };
        assert!(!got.is_empty(), "--use frame --bits {bits}");
        assert_eq!(
            ids(&got.iter().collect::<Vec<_>>()),
            ids(&want),
            "--bits {bits}"
        );
        for (row, f) in got.iter().zip(&want) {
            assert_eq!(num(row, "score"), score(f).0, "{}", f["spec"]);
            assert_eq!(num(row, "error"), score(f).1, "{}", f["spec"]);
        }
    }
    let top = chosen(&["--use", "frame", "--bits", "64"]);
    assert_eq!(top[0]["spec"], "qtangent64");
    assert!(
        top[0]["why"]
            .as_str()
            .unwrap()
            .contains("Filament reads these bits")
    );
    // `--domain frame` is the same ranking.
    assert_eq!(chosen(&["--domain", "frame", "--bits", "64"]), top);
    let e = fails(&["choose", "--use", "frame", "--bits", "16"], "");
    assert!(e.contains("spec that keeps every sign has 32 bits"), "{e}");
}

/// The line under a row names what decided it (its ALU per pixel, its seam where it
/// filters, its table, its format and bits) and what the next row trades.
#[test]
fn the_line_under_a_row_says_what_decided_it() {
    let g = chosen(&["--use", "gbuffer", "--bits", "32"]);
    let why = g[0]["why"].as_str().unwrap();
    for part in [
        "best by score",
        "encode_float",
        "ALU a pixel",
        "seam: ",
        "no table",
        ", 32 bits, filterable",
        "next, ",
    ] {
        assert!(why.contains(part), "{part:?} in {why}");
    }
    let a = chosen(&["--use", "asset", "--bits", "16"]);
    let with_table = a
        .iter()
        .find(|r| r["tables"].as_array().is_some_and(|t| !t.is_empty()))
        .expect("a table codec among the 16-bit assets");
    let why = with_table["why"].as_str().unwrap();
    assert!(why.contains("reads table latlongd16_rings ("), "{why}");
    // The last row trades with nothing.
    let last = g.last().unwrap()["why"].as_str().unwrap();
    assert!(!last.contains("next, "), "{last}");
    // Block formats are written offline: never a G-buffer's render target.
    for r in &g {
        let s = r["stored_in"].as_str().unwrap();
        assert!(!s.starts_with("bc"), "{} in {s}", r["spec"]);
    }
}

/// Under `--use` the table's enc and dec columns are the counts of the route the score
/// counts (a G-buffer's float-form encoder, not the packed one), as the JSON has them,
/// and the legend says so.
#[test]
fn the_table_counts_the_route_it_ranks() {
    let args = ["choose", "--use", "gbuffer", "--bits", "32", "--limit", "0"];
    let table = ok(&args).stdout;
    let rows = chosen(&args[1..5]);
    let mut differ = 0;
    for r in &rows {
        let spec = r["spec"].as_str().unwrap();
        let line = table
            .lines()
            .find(|l| l.split_whitespace().next() == Some(spec))
            .unwrap_or_else(|| panic!("{spec} in the table:\n{table}"));
        // spec, bits, domain, mean°, max°, enc, dec, …
        let cols: Vec<&str> = line.split_whitespace().collect();
        let (enc, dec) = (
            r["route_encode"].as_u64().unwrap(),
            r["route_decode"].as_u64().unwrap(),
        );
        assert_eq!(cols[5], enc.to_string(), "{spec} enc in {line}");
        assert_eq!(cols[6], dec.to_string(), "{spec} dec in {line}");
        differ += usize::from(r["alu"]["encode"].as_u64() != Some(enc));
    }
    assert!(
        differ > 0,
        "some route runs other functions than the packed ones"
    );
    assert!(
        table.contains("enc, dec: ALU instructions of the encoder and decoder this use runs"),
        "{table}"
    );
}

/// Options that belong to another kind of ranking are refused, naming why.
#[test]
fn options_of_another_ranking_are_refused() {
    let e = fails(&["choose", "--use", "vertex", "--no-filter"], "");
    assert!(e.contains("--no-filter belongs to --use gbuffer"), "{e}");
    let e = fails(&["choose", "--use", "asset", "--by", "mean"], "");
    assert!(e.contains("drop one of them"), "{e}");
    let e = fails(&["choose", "--use", "vertex", "--domain", "frame"], "");
    assert!(e.contains("--domain frame ranks tangent frames"), "{e}");
    // Explicit constraints still apply under a use.
    let limited = chosen(&["--use", "vertex", "--bits", "32", "--max-decode-alu", "16"]);
    assert!(!limited.is_empty());
    for r in &limited {
        let d = r["route_decode"].as_u64().unwrap();
        assert!(d <= 16, "{}: decode {d}", r["spec"]);
    }
}

/// Constraints given with a use apply to the route it takes: an ALU limit keeps a spec
/// whose other route is within it, `--portable` keeps only the packed code (the one thing
/// every GPU writes alike), a block format is used only where named (its figures are
/// before compression, and the line says so), and a typo in `--format` is named.
#[test]
fn constraints_apply_to_the_route() {
    let limited = chosen(&[
        "--use",
        "gbuffer",
        "--no-filter",
        "--bits",
        "32",
        "--max-encode-alu",
        "360",
    ]);
    let ld = limited
        .iter()
        .find(|r| r["spec"] == "latlongd32")
        .expect("latlongd32's code route encodes in 358");
    assert!(ld["route_encode"].as_u64().unwrap() <= 360, "{ld}");
    for r in &limited {
        assert!(r["route_encode"].as_u64().unwrap() <= 360, "{}", r["spec"]);
    }
    let e = fails(&["choose", "--use", "gbuffer", "--portable"], "");
    assert!(e.contains("no spec meets --portable"), "{e}");
    for r in chosen(&["--use", "gbuffer", "--no-filter", "--portable"]) {
        let stored = r["stored_in"].as_str().unwrap();
        assert!(stored.contains("uint"), "{}: {stored}", r["spec"]);
    }
    for r in chosen(&["--use", "normal-map", "--bits", "16"]) {
        let stored = r["stored_in"].as_str().unwrap();
        assert!(!stored.starts_with("bc"), "{}: {stored}", r["spec"]);
    }
    let bc5 = chosen(&["--use", "normal-map", "--format", "bc5-rg-unorm"]);
    assert!(!bc5.is_empty());
    for r in &bc5 {
        assert_eq!(r["stored_in"], "bc5-rg-unorm");
        let why = r["why"].as_str().unwrap();
        assert!(
            why.contains("block-compressed: the figures are before compression"),
            "{why}"
        );
    }
    let e = fails(&["choose", "--use", "vertex", "--format", "snorm16x3"], "");
    assert!(e.contains("did you mean"), "{e}");
    // A vertex attribute is named by its vertex format.
    let v = chosen(&["--use", "vertex", "--bits", "16"]);
    assert_eq!(v[0]["stored_in"], "snorm8x2", "{}", v[0]);
}

/// Options a use does not take are refused, naming why; a frame ranking that the bits
/// empty says how small the smallest frame is, and one the ALU limits empty names them.
#[test]
fn options_a_use_does_not_take_are_refused() {
    for opt in [
        &["--format", "rg8snorm"][..],
        &["--filterable"],
        &["--portable"],
        &["--domain", "sphere"],
    ] {
        let e = fails(&[&["choose", "--use", "frame"][..], opt].concat(), "");
        assert!(
            e.contains("--use frame ranks tangent frames"),
            "{opt:?}: {e}"
        );
    }
    let e = fails(&["choose", "--use", "asset", "--format", "rg8snorm"], "");
    assert!(e.contains("stores the packed code itself"), "{e}");
    let e = fails(&["choose", "--use", "frame", "--max-decode-alu", "10"], "");
    assert!(e.contains("no spec meets --max-decode-alu 10"), "{e}");
    assert!(!e.contains("smallest"), "{e}");
}
