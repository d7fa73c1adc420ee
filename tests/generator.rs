//! The build-script library: typed errors, atomic writes, one file per language.

use unitpack::{GenerateError, Generator, Lang, Spec};

fn tempdir() -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!(
        "unitpack-generator-{}-{:?}",
        std::process::id(),
        std::thread::current().id()
    ));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn errors_are_typed() {
    let g = Generator::new().lang(Lang::Wgsl);
    assert!(matches!(g.render(Lang::Wgsl), Err(GenerateError::NoSpecs)));
    let e = g.clone().spec("octt16").render(Lang::Wgsl).unwrap_err();
    assert!(matches!(e, GenerateError::Spec(_)), "{e}");
    assert!(e.to_string().contains("did you mean oct"), "{e}");
    let e = g
        .clone()
        .spec("oct16")
        .prefix("9x")
        .render(Lang::Wgsl)
        .unwrap_err();
    assert!(matches!(e, GenerateError::Prefix(_)), "{e}");
    let e = Generator::new()
        .spec("oct16")
        .langs([Lang::Wgsl, Lang::C])
        .write_file("/nonexistent/x")
        .unwrap_err();
    assert!(
        matches!(e, GenerateError::Languages { count: 2, .. }),
        "{e}"
    );
}

#[test]
fn writes_are_atomic_create_parents_and_match_render() {
    let dir = tempdir();
    let g = Generator::new()
        .spec("oct16")
        .spec("oct16".parse::<Spec>().unwrap())
        .error_stats(false);
    let path = dir.join("a/b/normals.glsl");
    g.clone().lang(Lang::Glsl).write_file(&path).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert_eq!(text, g.render(Lang::Glsl).unwrap());
    assert_eq!(
        text.matches("uint unitpack_oct16_encode(").count(),
        1,
        "duplicates dropped"
    );
    let written = g.langs(Lang::ALL).write_dir(&dir, "n").unwrap();
    let names: Vec<String> = written
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names, ["n.wgsl", "n.glsl", "n.hlsl", "n.h"]);
    // Nothing but the outputs is left behind (no temporary files).
    let mut left: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    left.sort();
    assert_eq!(left, ["a", "n.glsl", "n.h", "n.hlsl", "n.wgsl"]);
    // A file in place of the directory: an error naming the path, nothing written.
    let blocker = dir.join("blocker");
    std::fs::write(&blocker, "keep").unwrap();
    let e = Generator::new()
        .spec("oct16")
        .lang(Lang::C)
        .write_file(blocker.join("x.h"))
        .unwrap_err();
    assert!(matches!(e, GenerateError::Io { .. }), "{e}");
    assert!(e.to_string().contains("blocker"), "{e}");
    assert_eq!(std::fs::read_to_string(&blocker).unwrap(), "keep");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A build script written as `examples/build-script/build.rs` is (`fn main() -> Result<(),
/// GenerateError>`) that asks for a spec that does not exist fails with the error's
/// message, which says what to fix: `main` reports an error as `Error: {err:?}`, so the
/// `Debug` form must be the message. Before, it printed `Error: Spec(InvalidBits { codec:
/// "oct", bits: "17", .. })`. Nothing is written.
#[test]
fn a_failing_build_script_says_what_to_fix() {
    let dir = tempdir();
    let out = dir.join("normals.wgsl");
    let e = Generator::new()
        .specs(["oct24p", "oct17"])
        .lang(Lang::Wgsl)
        .wgsl_import_path("normals")
        .write_file(&out)
        .unwrap_err();
    let reported = format!("Error: {e:?}");
    assert_eq!(
        reported,
        "Error: invalid spec: oct has no 17-bit form; allowed sizes: 16, 20, 22, 24, 32"
    );
    assert!(matches!(e, GenerateError::Spec(_)), "{e}");
    assert!(!out.exists(), "a failed build wrote {}", out.display());
    std::fs::remove_dir_all(dir).unwrap();
}
