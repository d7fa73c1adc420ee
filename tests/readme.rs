//! The README's tables are written by the tool: this test fails when they are stale, and
//! rewrites them when run with `UPDATE_README=1`.

use unitpack::doc_tables::{
    README_SAMPLES, bound_table, catalogue_table, codec_specs, error_table, replace_block,
    seed_methods_table,
};
use unitpack::quality::measure_all;

#[test]
fn readme_tables_are_generated_and_fresh() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md");
    let text = std::fs::read_to_string(&path).unwrap();
    let mut fresh = text.clone();
    let alu: Vec<[u32; 2]> =
        unitpack::verify::alu::count_all(&codec_specs(), &["encode", "decode"])
            .unwrap_or_else(|e| panic!("cannot count ALU instructions: {e:#}"))
            .into_iter()
            .map(|c| [c[0], c[1]])
            .collect();
    let stats = measure_all(&codec_specs(), README_SAMPLES);
    for (name, body) in [
        ("catalogue", catalogue_table()),
        ("errors", error_table(&stats, &alu)),
        ("seed_methods", seed_methods_table(&stats, &alu)),
        ("bounds", bound_table()),
    ] {
        fresh = replace_block(&fresh, "readme", name, &body)
            .unwrap_or_else(|| panic!("README.md lacks the markers of the {name} block"));
    }
    if std::env::var_os("UPDATE_README").is_some() {
        std::fs::write(&path, &fresh).unwrap();
        return;
    }
    assert!(
        fresh == text,
        "README.md's generated tables are stale: run `UPDATE_README=1 cargo test --release --test readme`"
    );
}
