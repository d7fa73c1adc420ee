//! The whole catalogue on lavapipe: every emitted function on every path (WGSL via naga,
//! GLSL via naga and glslang, HLSL via glslang with -Od and default optimization, C
//! and C++), and the model's own four-lane evaluation that the CPU batches run, each
//! compared as raw bits with the f32 model on every code up to 24 bits and 2^20 seeded
//! vectors plus the edge cases, plus the static checks. With no Vulkan adapter this
//! fails and names the package to install.

use unitpack::codecs::Spec;
use unitpack::emit::Lang;

#[test]
fn every_function_is_bit_exact_on_every_path() {
    let report = unitpack::verify::run(&Spec::all(), &Lang::ALL, false)
        .unwrap_or_else(|e| panic!("cannot verify: {e:#}"));
    let table = report.table();
    println!("{table}");
    assert!(
        report.rows.len() > 1000,
        "every spec × function × path is checked"
    );
    let functions: usize = Spec::all()
        .iter()
        .map(|s| s.emitted().functions.len())
        .sum();
    let lanes = report.rows.iter().filter(|r| r.path == "cpu/4 lanes");
    assert_eq!(
        lanes.filter(|r| r.tested >= 1 << 15).count(),
        functions,
        "every function on four lanes"
    );
    assert!(
        report.all_passed(),
        "mismatches or compile errors:\n{table}"
    );
}
