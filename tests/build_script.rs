//! The library as a build script uses it: `examples/build-script` depends on unitpack with
//! `default-features = false`, generates its includes from `build.rs` through
//! [`unitpack::Generator`], and is built and run here. Its build graph stays small.

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

#[test]
fn the_library_without_default_features_builds_at_most_25_crates() {
    let out = cargo()
        .args([
            "tree",
            "--offline",
            "-p",
            "unitpack-build-example",
            "-e",
            "normal,build",
            "--prefix",
            "none",
        ])
        .output()
        .expect("run cargo tree");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
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

/// A build script written as the example's (`fn main() -> Result<(), GenerateError>`)
/// that asks for a spec that does not exist fails with the error's message, which says
/// what to fix. Before, the error printed as `Error: Spec(InvalidBits { codec: "oct",
/// bits: "17", .. })`: `main` reports an error through `Debug`, which was derived. The
/// crate built here is the example with one spec changed, in its own workspace; it
/// shares the example's target folder, where the light library is already built.
#[test]
fn a_failing_build_script_says_what_to_fix() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let example = root.join("examples/build-script");
    let tmp = tempfile::tempdir().expect("temporary directory");
    let krate = tmp.path();
    let build = std::fs::read_to_string(example.join("build.rs")).unwrap();
    assert!(build.contains("\"hemioct16\""), "{build}");
    std::fs::write(
        krate.join("build.rs"),
        build.replace("\"hemioct16\"", "\"oct17\""),
    )
    .unwrap();
    std::fs::create_dir(krate.join("src")).unwrap();
    std::fs::write(krate.join("src/main.rs"), "fn main() {}\n").unwrap();
    std::fs::write(
        krate.join("Cargo.toml"),
        format!(
            "[package]\nname = \"unitpack-failing-build\"\nversion = \"0.0.0\"\nedition = \"2024\"\n\
             publish = false\n\n[build-dependencies]\nunitpack = {{ path = {:?}, default-features = false }}\n\n\
             [workspace]\n",
            root.to_str().unwrap()
        ),
    )
    .unwrap();
    // The same versions as this workspace, without a registry.
    std::fs::copy(root.join("Cargo.lock"), krate.join("Cargo.lock")).unwrap();
    let out = cargo()
        .current_dir(krate)
        .args([
            "build",
            "--offline",
            "--config",
            "profile.dev.package.\"*\".opt-level=0",
        ])
        .arg("--target-dir")
        .arg(root.join("target/build-example"))
        .output()
        .expect("run cargo");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "the build should fail:\n{stderr}");
    assert!(
        stderr.contains(
            "Error: invalid spec: oct has no 17-bit form; allowed sizes: 16, 20, 22, 24, 32"
        ),
        "{stderr}"
    );
    assert!(!stderr.contains("InvalidBits"), "{stderr}");
}
