//! Writes the includes this crate's renderer and asset tools use into OUT_DIR.

use unitpack::{Generator, Lang};

// An error fails the build with its message, `Error: invalid spec: oct has no 17-bit
// form; allowed sizes: 16, 20, 22, 24, 32`: `GenerateError`'s `Debug` is its `Display`.
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
