//! Writes the includes this crate's renderer and asset tools use into OUT_DIR.

use unitpack::{Generator, Lang};

fn main() -> Result<(), unitpack::GenerateError> {
    let out = std::path::PathBuf::from(std::env::var_os("OUT_DIR").expect("OUT_DIR"));
    // A WGSL module that naga_oil / Bevy shaders import as `normals::{...}`.
    Generator::new()
        .specs(["oct24p", "hemioct16"])
        .lang(Lang::Wgsl)
        .wgsl_import_path("normals")
        .write_file(out.join("normals.wgsl"))?;
    // The same codecs for GLSL and HLSL, and for a C/C++ asset pipeline.
    Generator::new()
        .specs(["oct24p", "hemioct16"])
        .langs([Lang::Glsl, Lang::Hlsl, Lang::C])
        .error_stats(false)
        .write_dir(&out, "normals")?;
    println!("cargo::rerun-if-changed=build.rs");
    Ok(())
}
