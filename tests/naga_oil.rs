//! WGSL modules for naga_oil (Bevy) users: an include generated with an import path
//! composes into a shader that imports its functions, and the result validates with naga.

use naga_oil::compose::{ComposableModuleDescriptor, Composer, NagaModuleDescriptor};
use unitpack::{Generator, Lang};

const SHADER: &str = "
#import unitpack::normals::{unitpack_oct16_decode, unitpack_oct24p_encode, unitpack_hemioct16_decode_float}

@group(0) @binding(0) var<storage, read_write> words: array<u32>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let n = unitpack_oct16_decode(words[id.x]);
    let h = unitpack_hemioct16_decode_float(n.xy);
    words[id.x] = unitpack_oct24p_encode(n + h);
}
";

#[test]
fn generated_wgsl_composes_with_naga_oil_and_validates() {
    let module = Generator::new()
        .specs(["oct16", "oct24p", "hemioct16"])
        .lang(Lang::Wgsl)
        .wgsl_import_path("unitpack::normals")
        .error_stats(false)
        .render(Lang::Wgsl)
        .unwrap();
    assert!(module.starts_with("#define_import_path unitpack::normals\n"));
    let mut composer = Composer::default();
    let added = composer
        .add_composable_module(ComposableModuleDescriptor {
            source: &module,
            file_path: "normals.wgsl",
            ..Default::default()
        })
        .map(drop);
    if let Err(e) = added {
        panic!("{}", e.emit_to_string(&composer));
    }
    let composed = match composer.make_naga_module(NagaModuleDescriptor {
        source: SHADER,
        file_path: "shader.wgsl",
        ..Default::default()
    }) {
        Ok(m) => m,
        Err(e) => panic!("{}", e.emit_to_string(&composer)),
    };
    // The imported functions and the helpers they call made it into the module.
    let names: Vec<String> = composed
        .functions
        .iter()
        .filter_map(|(_, f)| f.name.clone())
        .collect();
    for f in [
        "oct16_decode",
        "oct24p_encode",
        "oct24p_encode_codes",
        "hemioct16_decode_float",
    ] {
        assert!(
            names.iter().any(|n| n.contains(f)),
            "{f} missing from {names:?}"
        );
    }
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    )
    .validate(&composed)
    .expect("the composed module validates");
}

#[test]
fn import_paths_must_be_identifiers() {
    for bad in ["", "a::", "1x", "a b", "a::b-c"] {
        let e = Generator::new()
            .spec("oct16")
            .lang(Lang::Wgsl)
            .wgsl_import_path(bad)
            .render(Lang::Wgsl)
            .unwrap_err();
        assert!(
            e.to_string().contains("invalid WGSL import path"),
            "{bad}: {e}"
        );
    }
}
