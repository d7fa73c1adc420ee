//! The library as a build script uses it: `examples/build-script` depends on unitpack with
//! `default-features = false`, generates its includes from `build.rs` through
//! [`unitpack::Generator`], and is built and run here. Its build graph stays small. What
//! such a build script reports for a bad spec is tested in `tests/generator.rs`: a crate
//! of its own would compile the library a second time (cargo keys a path dependency's
//! build by its path from the workspace root).

use std::path::Path;
use std::process::Command;

fn cargo() -> Command {
    let mut c = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()));
    c.current_dir(env!("CARGO_MANIFEST_DIR"));
    c
}

#[test]
fn a_build_script_generates_includes_with_the_light_library() {
    let target = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/build-example");
    let out = cargo()
        .args([
            "run",
            "--offline",
            "--quiet",
            "-p",
            "unitpack-build-example",
            // A user's crate builds its dependencies as cargo does by default, not with
            // this workspace's optimised dependencies (which would make this build spend
            // most of its time optimising proc-macro crates).
            "--config",
            "profile.dev.package.\"*\".opt-level=0",
            // Nor incrementally: a user's crate gets unitpack from a registry, which cargo
            // never builds incrementally (this build: 42.6 s with it, 39.9 s without, on
            // the 2-core development machine).
            "--config",
            "profile.dev.incremental=false",
        ])
        .arg("--target-dir")
        .arg(&target)
        .output()
        .expect("run cargo");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "building examples/build-script failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for (file, sig) in [
        (
            "normals.wgsl",
            "fn unitpack_oct24p_encode(v: vec3<f32>) -> u32 {",
        ),
        ("normals.glsl", "uint unitpack_oct24p_encode(vec3 v) {"),
        ("normals.hlsl", "uint unitpack_oct24p_encode(float3 v) {"),
        (
            "normals.h",
            "static inline uint32_t unitpack_oct24p_encode(const float v[3]) {",
        ),
    ] {
        let line = stdout
            .lines()
            .find(|l| l.starts_with(&format!("{file} ")))
            .unwrap_or_else(|| panic!("no line for {file}:\n{stdout}"));
        assert!(line.ends_with(sig), "{line}");
    }
}

/// `cargo tree --offline --prefix none` with `args`: one package per line.
fn tree(args: &[&str]) -> String {
    let out = cargo()
        .args(["tree", "--offline", "--prefix", "none"])
        .args(args)
        .output()
        .expect("run cargo tree");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("cargo tree prints UTF-8")
}

#[test]
fn the_library_without_default_features_builds_at_most_25_crates() {
    let text = tree(&["-p", "unitpack-build-example", "-e", "normal,build"]);
    let mut crates: Vec<&str> = text
        .lines()
        .filter_map(|l| l.split_whitespace().next())
        .collect();
    crates.sort();
    crates.dedup();
    for heavy in ["wgpu", "naga", "clap", "indicatif", "anyhow", "tempfile"] {
        assert!(
            !crates.contains(&heavy),
            "{heavy} is in the light build: {crates:?}"
        );
    }
    assert!(crates.len() <= 25, "{} crates: {crates:?}", crates.len());
}

/// `cargo build` and `cargo test` resolve the same features for every package the build
/// has (the features pinned in Cargo.toml), so that alternating them builds the library
/// once: a dependency built with other features is another build of it and of everything
/// above it, the library included.
#[test]
fn build_and_test_resolve_the_same_features() {
    let resolved = |edges: &str| -> std::collections::BTreeSet<String> {
        tree(&["-p", "unitpack", "-f", "{p} [{f}]", "-e", edges])
            .lines()
            .map(|l| l.trim_end_matches(" (*)").to_string())
            .collect()
    };
    let build = resolved("normal,build");
    let test = resolved("normal,build,dev");
    assert!(build.len() > 50, "{build:?}");
    assert!(test.len() > build.len(), "the tests add packages");
    let differ: Vec<&String> = build.difference(&test).collect();
    assert!(
        differ.is_empty(),
        "built with other features under `cargo test` than under `cargo build` (pin them in \
         Cargo.toml): {differ:?}"
    );
}
