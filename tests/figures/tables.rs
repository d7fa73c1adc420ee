//! The figures the repository records are the tool's: the generated tables in `docs/`
//! are written by it (the test fails when they are stale and rewrites them under
//! `UNITPACK_REFRESH=1`), and every emitted codec function's ALU count (counted as the
//! error table does, `src/verify/alu.rs`) must stay within the budget recorded for it in
//! `tests/alu_budgets.txt`, where every function has one. Lowering a count is welcome
//! (lower its budget too); raising one means editing the file and saying why in the
//! commit. `UNITPACK_REFRESH=1` rewrites that file with the current counts too, in the
//! same run, so one `UNITPACK_REFRESH=1 cargo test --release` refreshes both. The tests
//! share one count of every function: compiling each through glslang and spirv-opt is
//! the slow part of all of them.

use std::collections::BTreeMap;
use std::sync::OnceLock;
use unitpack::report::doc_tables::{
    README_SAMPLES, REFRESH_COMMAND, block, bound_table, catalogue_table, codec_specs, error_table,
    frame_error_table, portability_cost_table, refreshing, replace_block, seed_methods_table,
    tier_table,
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
            for f in &spec.emitted().functions {
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

/// The repository root.
fn root() -> &'static std::path::Path {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// `file` with each of `blocks` (name, body) replaced; written back when refreshing, else
/// the test fails if anything differs.
fn check_blocks(file: &str, blocks: &[(&str, String)]) {
    let path = root().join(file);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{file}: {e}"));
    let mut fresh = text.clone();
    for (name, body) in blocks {
        let b = block(name);
        assert_eq!(b.file, file, "the {name} block lives in {}", b.file);
        fresh = replace_block(&fresh, b.test, name, body)
            .unwrap_or_else(|| panic!("{file} lacks the markers of the {name} block"));
    }
    if refreshing() {
        if fresh != text {
            std::fs::write(&path, &fresh).unwrap();
        }
        return;
    }
    assert!(
        fresh == text,
        "{file}'s generated tables are stale: run `{REFRESH_COMMAND}` \
         (or `UNITPACK_REFRESH=1 cargo test --release --test figures` for these alone)"
    );
}

#[test]
fn generated_tables_are_fresh() {
    // Encode and decode, as the tables quote them.
    let alu: Vec<[u32; 2]> = counts().four.iter().map(|c| [c[0], c[2]]).collect();
    let stats = crate::stats(&codec_specs(), README_SAMPLES);
    check_blocks(
        "docs/codecs.md",
        &[
            ("catalogue", catalogue_table()),
            ("errors", error_table(&stats, &alu)),
            ("frame_errors", frame_error_table()),
        ],
    );
    check_blocks(
        "docs/design/families.md",
        &[("seed_methods", seed_methods_table(&stats, &alu))],
    );
    check_blocks(
        "docs/design/decoder-bounds.md",
        &[("bounds", bound_table())],
    );
    let all = &counts().all;
    let count = |spec: &unitpack::codecs::Spec, f: &str| {
        *all.get(&format!("{} {f}", spec.id()))
            .unwrap_or_else(|| panic!("{spec} {f} has an ALU count"))
    };
    check_blocks(
        "docs/design/portability.md",
        &[
            ("portability_cost", portability_cost_table(count)),
            ("tiers", tier_table(count)),
        ],
    );
}

/// The catalogue `list`, `choose` and `report` read (`src/choice/catalogue.json`, compiled
/// into the binary) holds exactly the figures measured here: the same error statistics
/// and ALU counts as the tables above, the proven bounds, the formats and the filtering
/// sample.
#[test]
fn the_choice_catalogue_is_fresh() {
    use unitpack::choice::catalogue::{self, Catalogue};
    let specs = codec_specs();
    let stats = crate::stats(&specs, README_SAMPLES);
    // The tangent-frame specs, with their packed encoder's and decoder's counts.
    let frames: Vec<unitpack::codecs::Spec> = unitpack::codecs::Spec::all()
        .into_iter()
        .filter(|s| s.family().frames())
        .collect();
    let frame_alu: Vec<[u32; 2]> = count_all(&frames, &["encode", "decode"])
        .unwrap_or_else(|e| panic!("cannot count the frames' ALU instructions: {e:#}"))
        .into_iter()
        .map(|c| [c[0], c[1]])
        .collect();
    let computed = catalogue::compute(&specs, &stats, &counts().four, &frames, &frame_alu);
    let fresh = computed.to_json();
    let path = root().join(catalogue::PATH);
    let text = std::fs::read_to_string(&path).unwrap_or_default();
    if refreshing() {
        if fresh != text {
            std::fs::write(&path, &fresh).unwrap();
        }
        // What the binary prints from the catalogue, written here from the one just
        // computed, so that one refresh writes it all: `list`'s table (which
        // tests/cli/list.rs holds the binary to, once the next build has compiled the
        // file in) and the README's recommendations (which tests/readme.rs checks
        // against the file as it is on disk).
        write_if_changed(
            &root().join("tests/cli/list.txt"),
            &unitpack::cli::list_text_of(&computed),
        );
        let readme = root().join("README.md");
        let text = std::fs::read_to_string(&readme).unwrap();
        let table = unitpack::choice::recommend::table(&computed);
        let fresh = replace_block(&text, "readme", "recommendations", &table)
            .expect("README.md has the recommendations block");
        write_if_changed(&readme, &fresh);
        return;
    }
    assert!(
        fresh == text,
        "{} is stale: run `{REFRESH_COMMAND}` (or `UNITPACK_REFRESH=1 cargo test --release \
         --test figures`)",
        catalogue::PATH
    );
    // And the binary holds the same figures, read back bit for bit.
    assert!(
        Catalogue::load() == computed,
        "the compiled-in catalogue differs from {}: rebuild",
        catalogue::PATH
    );
}

fn write_if_changed(path: &std::path::Path, text: &str) {
    if std::fs::read_to_string(path).ok().as_deref() != Some(text) {
        std::fs::write(path, text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    }
}

/// The lean tier's point: oct16's packed encoder in the instructions of its octahedral
/// core and packing (issue 44's figure, the README's counting), against the default
/// tier's, which must stay dearer (or the lean tier has nothing to offer).
#[test]
fn the_lean_oct16_encoder_takes_at_most_24_instructions() {
    let all = &counts().all;
    let lean = all["oct16_ieee encode"];
    assert!(lean <= 24, "oct16:guarantee=ieee encode counts {lean}");
    assert!(all["oct16 encode"] > lean);
}

/// docs/design/portability.md takes oct16's packed encoder apart instruction by
/// instruction; its total is the count the tool measures today.
#[test]
fn oct16_encoder_breakdown_adds_up_to_its_count() {
    let text = std::fs::read_to_string(root().join("docs/design/portability.md")).unwrap();
    let total: u32 = text
        .lines()
        .find_map(|l| l.strip_prefix("| total | | **"))
        .and_then(|rest| rest.split("**").next())
        .expect("docs/design/portability.md has the `| total | | **N** |` row")
        .parse()
        .expect("a number");
    let parts: u32 = text
        .lines()
        .skip_while(|l| !l.starts_with("| part | instructions | count |"))
        .skip(2)
        .take_while(|l| !l.starts_with("| total |"))
        .map(|l| {
            let cells: Vec<&str> = l.split(" | ").collect();
            cells[cells.len() - 2]
                .trim()
                .parse::<u32>()
                .unwrap_or_else(|_| panic!("a count in the second-to-last cell of {l:?}"))
        })
        .sum();
    assert_eq!(
        parts, total,
        "the parts of oct16's encoder add up to its total"
    );
    let now = counts().all["oct16 encode"];
    assert_eq!(
        total, now,
        "docs/design/portability.md's breakdown of oct16 encode says {total} instructions, \
         the tool counts {now}: update the breakdown"
    );
}

#[test]
fn every_function_stays_within_its_alu_budget() {
    let path = root().join("tests/alu_budgets.txt");
    let now = &counts().all;
    let text = std::fs::read_to_string(&path).unwrap_or_default();
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
    if refreshing() {
        let mut fresh = String::from(
            "# ALU budget per emitted function: spec, function, instructions (tests/figures/tables.rs).\n",
        );
        for (k, n) in now {
            fresh.push_str(&format!("{k} {n}\n"));
        }
        if fresh != text {
            std::fs::write(&path, fresh).unwrap();
        }
        // Written, not hidden: a raised budget must be explained in the commit.
        for o in &over {
            eprintln!("tests/alu_budgets.txt rewritten: {o}");
        }
        return;
    }
    assert!(
        over.is_empty(),
        "{}\nWhere a function grew on purpose, `{REFRESH_COMMAND}` records the new counts \
         in tests/alu_budgets.txt; say why in the commit.",
        over.join("\n")
    );
}
