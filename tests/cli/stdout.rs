//! Standard output: `--out -` names it for every verb that writes a file, and every verb
//! into a closed pipe ends quietly and into a full device with a one-line error.

use crate::common::*;
use std::collections::BTreeSet;
use std::io::Write;
use std::path::PathBuf;
use std::process::Stdio;

fn closed_pipe() -> Stdio {
    let (reader, writer) = std::io::pipe().expect("pipe");
    drop(reader);
    Stdio::from(writer)
}

fn dev_full() -> Stdio {
    Stdio::from(
        std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .expect("/dev/full"),
    )
}

/// Runs `args` with stdout going to `out`; returns (exit status, stderr).
fn run_into(args: &[&str], stdin: &[u8], out: Stdio) -> (i32, String) {
    let mut child = unitpack()
        .args(args)
        .stdin(Stdio::piped())
        .stdout(out)
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn");
    let mut si = child.stdin.take().unwrap();
    let input = stdin.to_vec();
    let w = std::thread::spawn(move || {
        let _ = si.write_all(&input);
    });
    let o = child.wait_with_output().unwrap();
    w.join().unwrap();
    (
        o.status.code().expect("not killed by a signal"),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// Every verb into a closed pipe (ends quietly) and into a full device (one-line error).
#[test]
fn every_verb_into_a_closed_pipe_and_a_full_device() {
    let gen_dir = tempdir();
    generated_copy(gen_dir.path());
    let g = gen_dir.path().to_str().unwrap().to_string();
    let vectors = "0.48 -0.6 0.64\n".repeat(20_000);
    let codes = "0x00001234\n".repeat(20_000);
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["list"], ""),
        (vec!["list", "--json"], ""),
        (vec!["gen", "oct24p", "--lang", "wgsl"], ""),
        (vec!["generate", "--out", &g], ""),
        (vec!["generate", "--out", &g, "--check"], ""),
        (vec!["encode", "oct16"], &vectors),
        (vec!["encode", "oct16", "--format", "binary"], ""),
        (
            vec!["encode", "oct16", "--output-format", "binary"],
            &vectors,
        ),
        (vec!["decode", "oct16"], &codes),
        (vec!["verify", "oct16", "--lang", "wgsl"], ""),
        (vec!["verify", "oct16", "--lang", "wgsl", "--json"], ""),
        (vec!["--help"], ""),
        (vec!["--version"], ""),
        (vec!["gen", "--help"], ""),
    ];
    for (args, stdin) in &cases {
        let (code, err) = run_into(args, stdin.as_bytes(), closed_pipe());
        assert_eq!(code, 0, "{args:?} into a closed pipe: {err}");
        assert!(err.is_empty(), "{args:?} into a closed pipe printed: {err}");
    }
    for (args, stdin) in &cases {
        // `encode --format binary` with no input writes nothing, so nothing can fail.
        if stdin.is_empty() && args.contains(&"encode") {
            continue;
        }
        let (code, err) = run_into(args, stdin.as_bytes(), dev_full());
        assert_eq!(code, 2, "{args:?} into /dev/full: {err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(
            err.starts_with("error: ") && err.contains("No space left on device"),
            "{args:?}: {err}"
        );
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
}

/// `--out -` is standard output for `gen`, `encode` and `decode`, and OUT `-` for
/// `convert-normal-map`: the same bytes as without it, and no file named `-`. `generate`
/// writes a folder, which stdout cannot hold: refused. Before, each of them wrote (or
/// made a folder) named `-` in the working directory and printed nothing.
#[test]
fn out_dash_is_standard_output_for_every_verb() {
    let dir = tempdir();
    let d = Some(dir.path());
    let gen_args = ["gen", "oct16", "--lang", "wgsl"];
    let r = run_in(d, &[&gen_args[..], &["--out", "-"]].concat(), "");
    assert_eq!(r.code, 0, "{r:?}");
    assert_eq!(r.stdout, ok(&gen_args).stdout);
    let vectors = "0 0 1\n0.6 0 0.8\n";
    let codes = run_stdin(&["encode", "oct16"], vectors).stdout;
    let r = run_in(d, &["encode", "oct16", "--out", "-"], vectors);
    assert_eq!((r.code, &r.stdout), (0, &codes), "{r:?}");
    let r = run_in(d, &["decode", "oct16", "--out", "-"], &codes);
    assert_eq!(
        (r.code, &r.stdout),
        (0, &run_stdin(&["decode", "oct16"], &codes).stdout),
        "{r:?}"
    );
    // A map: 2×1 texels, straight up and tilted, written as an RGB8 PNG.
    let map = dir.path().join("map.png");
    let mut png = Vec::new();
    let mut e = png::Encoder::new(&mut png, 2, 1);
    e.set_color(png::ColorType::Rgb);
    let mut w = e.write_header().unwrap();
    w.write_image_data(&[128, 128, 255, 200, 128, 220]).unwrap();
    w.finish().unwrap();
    std::fs::write(&map, &png).unwrap();
    let convert = ["convert-normal-map", "map.png", "--to", "xy16_rg"];
    let r = run_in(d, &[&convert[..2], &["-"], &convert[2..]].concat(), "");
    assert_eq!(r.code, 0, "{r:?}");
    run_in(d, &[&convert[..2], &["rg.png"], &convert[2..]].concat(), "");
    let file = dir.path().join("rg.png");
    assert_eq!(r.out, std::fs::read(&file).unwrap(), "the PNG, on stdout");
    std::fs::remove_file(file).unwrap();
    let r = run_in(d, &["generate", "--out", "-"], "");
    assert_eq!(r.code, 2, "{r:?}");
    assert!(r.stderr.contains("--out -") && r.stdout.is_empty(), "{r:?}");
    assert_eq!(
        tree(dir.path()),
        BTreeSet::from([PathBuf::from("map.png")]),
        "nothing but the map"
    );
}
