//! Shader cost does not creep: every emitted codec function's ALU count (counted as the
//! README's codec table does, `src/verify/alu.rs`) must stay within the budget recorded
//! for it in `tests/alu_budgets.txt`, and every function has one. Lowering a count is
//! welcome (lower its budget too); raising one means editing the file and saying why in
//! the commit. `UPDATE_ALU_BUDGETS=1` rewrites the file with the current counts.

use std::collections::BTreeMap;
use unitpack::doc_tables::codec_specs;
use unitpack::verify::alu::{count, count_all};

const FUNCTIONS: [&str; 4] = ["encode", "encode_float", "decode", "decode_float"];

#[test]
fn every_function_stays_within_its_alu_budget() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/alu_budgets.txt");
    let specs = codec_specs();
    let counts = count_all(&specs, &FUNCTIONS)
        .unwrap_or_else(|e| panic!("cannot count ALU instructions: {e:#}"));
    let mut now = BTreeMap::new();
    for (spec, c) in specs.iter().zip(&counts) {
        for (f, n) in FUNCTIONS.iter().zip(c) {
            now.insert(format!("{} {f}", spec.id()), *n);
        }
        // A codec's other public functions (xra's second encoder, encode_dxt1).
        for f in spec.emitted().functions {
            if !FUNCTIONS.contains(&f.name) {
                let n = count(spec, f.name)
                    .unwrap_or_else(|e| panic!("cannot count {spec} {}: {e:#}", f.name));
                now.insert(format!("{} {}", spec.id(), f.name), n);
            }
        }
    }
    if std::env::var_os("UPDATE_ALU_BUDGETS").is_some() {
        let mut text = String::from(
            "# ALU budget per emitted function: spec, function, instructions (tests/alu_budget.rs).\n",
        );
        for (k, n) in &now {
            text.push_str(&format!("{k} {n}\n"));
        }
        std::fs::write(&path, text).unwrap();
        return;
    }
    let text = std::fs::read_to_string(&path).unwrap();
    let mut budgets = BTreeMap::new();
    for line in text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
    {
        let (key, n) = line.rsplit_once(' ').expect("`spec function budget`");
        budgets.insert(key.to_string(), n.parse::<u32>().expect("a number"));
    }
    let mut over = Vec::new();
    for (k, n) in &now {
        match budgets.get(k) {
            None => over.push(format!("{k}: {n} instructions, no budget recorded")),
            Some(b) if n > b => over.push(format!("{k}: {n} instructions, budget {b}")),
            _ => {}
        }
    }
    for k in budgets.keys().filter(|k| !now.contains_key(*k)) {
        over.push(format!(
            "{k}: a budget for a function that no longer exists"
        ));
    }
    assert!(over.is_empty(), "{}", over.join("\n"));
}
