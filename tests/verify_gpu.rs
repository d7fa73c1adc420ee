//! The whole catalogue on lavapipe: every emitted function on every path (WGSL via naga,
//! GLSL via naga and glslang, HLSL via glslang with -Od and default optimization),
//! compared as raw bits with the f32 model, plus the static checks. With no Vulkan
//! adapter this fails and names the package to install.

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
    assert!(
        report.all_passed(),
        "mismatches or compile errors:\n{table}"
    );
}
