//! Standard output: `--out -` names it for every verb that writes a file, and every verb
//! into a closed pipe ends quietly and into a full device with a one-line error.

use crate::common::*;
use std::io::Write;
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
