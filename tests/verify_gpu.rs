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

/// The CPU library is the model the GPU was compared with.
#[test]
fn cpu_api_equals_the_verified_model() {
    use unitpack::api::{CpuCodec, Oct};
    use unitpack::codecs::functions::Role;
    let e: Spec = "oct24p".parse().unwrap();
    let e = e.emitted();
    let enc = e.functions.iter().find(|f| f.role == Role::Encode).unwrap();
    let api = Oct::new(24).unwrap().precise();
    for v in unitpack::quality::random_unit_vectors(7, 10_000, false) {
        let mut code = [0u32];
        (enc.eval)(&v.map(f32::to_bits), &mut code);
        assert_eq!(api.encode(v), code[0]);
    }
    assert!(Oct::new(17).is_err());
}
