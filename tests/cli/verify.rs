//! `verify` on lavapipe, on the hardware adapter, as JSON, and `--portable`.

use crate::common::*;
use std::collections::BTreeSet;

#[test]
fn verify_oct16_wgsl_on_lavapipe() {
    // Without XDG_RUNTIME_DIR Mesa complains on stderr; that noise is not unitpack's.
    let mut cmd = unitpack();
    cmd.args(["verify", "oct16", "--lang", "wgsl"])
        .env_remove("XDG_RUNTIME_DIR");
    let r = run_cmd(cmd, b"");
    assert_eq!(r.code, 0, "{r:?}");
    assert!(!r.stderr.contains("XDG_RUNTIME_DIR"), "{r:?}");
    assert!(r.stdout.lines().any(|l| l.starts_with("adapter:")), "{r:?}");
    let rows: Vec<&str> = r
        .stdout
        .lines()
        .filter(|l| l.starts_with("oct16 "))
        .collect();
    assert!(!rows.is_empty(), "{r:?}");
    // The WGSL path, and the model's own four- and eight-lane paths, which need no language.
    assert!(
        rows.iter().all(|l| l.contains("wgsl/naga")
            || l.contains("cpu/4 lanes")
            || l.contains("cpu/8 lanes")),
        "{r:?}"
    );
    for lanes in ["cpu/4 lanes", "cpu/8 lanes"] {
        assert!(rows.iter().any(|l| l.contains(lanes)), "{lanes}: {r:?}");
    }
    for f in ["encode", "decode"] {
        assert!(
            rows.iter().any(|l| l.split_whitespace().nth(1) == Some(f)),
            "no row for {f}: {r:?}"
        );
    }
    assert!(r.stdout.contains(" 0 failed"), "{r:?}");
}

/// `--adapter gpu` runs the shader paths on the machine's own GPU, never on lavapipe: where
/// there is none (CI), it fails naming the adapters it found and what to install.
#[test]
fn verify_on_the_hardware_adapter_never_falls_back_to_lavapipe() {
    let r = run(&["verify", "oct16", "--lang", "wgsl", "--adapter", "gpu"]);
    let adapter = r.stdout.lines().find(|l| l.starts_with("adapter:"));
    match adapter {
        Some(line) => assert!(!line.contains("llvmpipe"), "{r:?}"),
        None => {
            assert_eq!(r.code, 2, "{r:?}");
            assert!(
                r.stderr
                    .contains("no hardware Vulkan adapter found (adapters: ")
                    && r.stderr.contains("llvmpipe")
                    && r.stderr.contains("libvulkan1"),
                "{r:?}"
            );
        }
    }
    let err = fails(&["verify", "oct16", "--adapter", "npu"], "");
    assert!(err.contains("invalid value 'npu'"), "{err}");
}

#[test]
fn verify_rejects_bad_specs() {
    let err = fails(&["verify", "octt16", "--lang", "wgsl"], "");
    assert!(err.contains("unknown codec 'octt16'"), "{err}");
}

#[test]
fn verify_json_reports_every_row() {
    let r = ok(&["verify", "oct16", "oct16p", "--lang", "wgsl,glsl", "--json"]);
    assert!(!r.stderr.contains("XDG_RUNTIME_DIR"), "{r:?}");
    let v: serde_json::Value = serde_json::from_str(&r.stdout).expect("verify --json is JSON");
    assert_eq!(v["passed"], true, "{r:?}");
    assert_eq!(v["failed"], 0);
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(v["checks"].as_u64().unwrap() as usize, rows.len());
    // oct16p's decoders are oct16's code: run once per path, their rows repeat oct16's;
    // the items counted are those run.
    let shared = |r: &&serde_json::Value| !r["same_code_as"].is_null();
    let items: u64 = rows
        .iter()
        .filter(|r| !shared(r))
        .map(|r| r["tested"].as_u64().unwrap())
        .sum();
    assert_eq!(v["items"].as_u64().unwrap(), items);
    let copies: Vec<_> = rows.iter().filter(shared).collect();
    assert_eq!(
        copies.len(),
        2 * 5,
        "two decoders on three shader paths and the four- and eight-lane paths"
    );
    for c in copies {
        assert_eq!(c["spec"], "oct16p");
        let owner = format!("oct16 {}", c["function"].as_str().unwrap());
        assert_eq!(c["same_code_as"].as_str(), Some(owner.as_str()));
    }
    let paths: BTreeSet<&str> = rows.iter().map(|r| r["path"].as_str().unwrap()).collect();
    for p in ["wgsl/naga", "glsl/naga", "glsl/glslang"] {
        assert!(paths.contains(p), "{paths:?}");
    }
    assert!(
        rows.iter()
            .all(|r| (r["spec"] == "oct16" || r["spec"] == "oct16p") && r["error"].is_null())
    );
}

/// `verify --portable` evaluates the model under the deviations the APIs allow. Every
/// packed encoder decides its codes portably (the spherical ones with fixed-point
/// trigonometry), so the report says so and exits 0; its float outputs still move.
#[test]
fn verify_portable_reports_codes_that_allowed_deviations_change() {
    let r = run(&["verify", "--portable", "spherical16", "--json"]);
    assert_eq!(r.code, 0, "{r:?}");
    assert!(
        r.stdout.contains("\"packed_encoders_portable\":true"),
        "{r:?}"
    );
    assert!(
        r.stdout.contains(
            "\"role\":\"DecodeFloat\",\"class\":\"fma\",\"items\":16384,\"changed\":3274"
        ),
        "{r:?}"
    );
    let r = run(&["verify", "--portable", "oct16", "--json"]);
    assert_eq!(r.code, 0, "{r:?}");
    assert!(
        r.stdout.contains("\"packed_encoders_portable\":true"),
        "{r:?}"
    );
    for class in ["div", "sqrt", "fma", "denorm", "zero", "excess"] {
        assert!(r.stdout.contains(&format!("\"{class}\"")), "{class}: {r:?}");
    }
    let r = run(&["verify", "--portable", "snorm12x2"]);
    assert_eq!(r.code, 0, "helpers have no packed encoder: {r:?}");
    assert!(r.stdout.contains("snorm12x2"), "{r:?}");
}
