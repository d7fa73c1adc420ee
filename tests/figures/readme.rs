//! The figures the repository records are the tool's: the README's tables are written by
//! it (the test fails when they are stale and rewrites them with `UPDATE_README=1`), and
//! every emitted codec function's ALU count (counted as the README's codec table does,
//! `src/verify/alu.rs`) must stay within the budget recorded for it in
//! `tests/alu_budgets.txt`, where every function has one. Lowering a count is welcome
//! (lower its budget too); raising one means editing the file and saying why in the
//! commit. `UPDATE_ALU_BUDGETS=1` rewrites that file with the current counts. The two
//! tests share one count of every function: compiling each through glslang and spirv-opt
//! is the slow part of both.

use std::collections::BTreeMap;
use std::sync::OnceLock;
use unitpack::doc_tables::{
    README_SAMPLES, bound_table, catalogue_table, codec_specs, error_table, replace_block,
    seed_methods_table,
};
use unitpack::verify::alu::{count, count_all};

const FUNCTIONS: [&str; 4] = ["encode", "encode_float", "decode", "decode_float"];

/// The ALU counts both tests read, counted once.
struct Counts {
    /// Each codec spec's count of each of [`FUNCTIONS`], in [`codec_specs`] order.
    four: Vec<[u32; 4]>,
    /// Every public function's count (also xra's second encoder and `encode_dxt1`),
    /// keyed `spec function`.
    all: BTreeMap<String, u32>,
}

fn counts() -> &'static Counts {
    static COUNTS: OnceLock<Counts> = OnceLock::new();
    COUNTS.get_or_init(|| {
        let specs = codec_specs();
        let four: Vec<[u32; 4]> = count_all(&specs, &FUNCTIONS)
            .unwrap_or_else(|e| panic!("cannot count ALU instructions: {e:#}"))
            .into_iter()
            .map(|c| c.try_into().expect("one count per function"))
            .collect();
        let mut all = BTreeMap::new();
        for (spec, c) in specs.iter().zip(&four) {
            for (f, n) in FUNCTIONS.iter().zip(c) {
                all.insert(format!("{} {f}", spec.id()), *n);
            }
            for f in spec.emitted().functions {
                if !FUNCTIONS.contains(&f.name) {
                    let n = count(spec, f.name)
                        .unwrap_or_else(|e| panic!("cannot count {spec} {}: {e:#}", f.name));
                    all.insert(format!("{} {}", spec.id(), f.name), n);
                }
            }
        }
        Counts { four, all }
    })
}

#[test]
fn readme_tables_are_generated_and_fresh() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md");
    let text = std::fs::read_to_string(&path).unwrap();
    let mut fresh = text.clone();
    // Encode and decode, as the tables quote them.
    let alu: Vec<[u32; 2]> = counts().four.iter().map(|c| [c[0], c[2]]).collect();
    let stats = crate::stats(&codec_specs(), README_SAMPLES);
    for (name, body) in [
        ("catalogue", catalogue_table()),
        ("errors", error_table(&stats, &alu)),
        ("seed_methods", seed_methods_table(&stats, &alu)),
        ("bounds", bound_table()),
    ] {
        fresh = replace_block(&fresh, "figures/readme", name, &body)
            .unwrap_or_else(|| panic!("README.md lacks the markers of the {name} block"));
    }
    if std::env::var_os("UPDATE_README").is_some() {
        std::fs::write(&path, &fresh).unwrap();
        return;
    }
    assert!(
        fresh == text,
        "README.md's generated tables are stale: run `UPDATE_README=1 cargo test --release --test figures`"
    );
}

#[test]
fn every_function_stays_within_its_alu_budget() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/alu_budgets.txt");
    let now = &counts().all;
    if std::env::var_os("UPDATE_ALU_BUDGETS").is_some() {
        let mut text = String::from(
            "# ALU budget per emitted function: spec, function, instructions (tests/figures/readme.rs).\n",
        );
        for (k, n) in now {
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
    for (k, n) in now {
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
