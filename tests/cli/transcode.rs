//! `transcode`: codes of one spec in, another's out, equal to `decode` piped into `encode`,
//! streamed like them, with the angle each vector moved summed up on stderr.

use crate::common::*;

/// Every code of oct16, as binary records.
fn every_oct16_code() -> Vec<u8> {
    (0u32..1 << 16).flat_map(|c| c.to_le_bytes()).collect()
}

/// The round trip's figures from the summary line: records, mean, max, and the record of
/// the max.
fn summary(stderr: &str) -> (u64, f64, f64, u64) {
    let line = stderr
        .lines()
        .find(|l| l.contains(" moved from "))
        .unwrap_or_else(|| panic!("no summary in {stderr:?}"));
    let numbers: Vec<f64> = line
        .split(|c: char| !(c.is_ascii_digit() || c == '.'))
        .filter_map(|w| w.parse().ok())
        .collect();
    // "N codes moved from A to B: … by MEAN° on average, at most MAX° (code K)"; the
    // spec names carry their sizes (oct16, oct24p), which are numbers too.
    let n = numbers.len();
    (
        numbers[0] as u64,
        numbers[n - 3],
        numbers[n - 2],
        numbers[n - 1] as u64,
    )
}

/// Binary and text: the codes written are those `decode` then `encode` give, for every
/// code of the spec read; the summary counts them and its figures are the angles
/// between the two decodes, computed here from `decode`'s output.
#[test]
fn transcode_is_decode_then_encode() {
    let codes = every_oct16_code();
    let t = run_bytes(
        &[
            "transcode",
            "--from",
            "oct16",
            "--to",
            "oct24p",
            "--format",
            "binary",
        ],
        &codes,
    );
    assert_eq!(t.code, 0, "{}", t.stderr);
    let dec = run_bytes(&["decode", "oct16", "--format", "binary"], &codes);
    let enc = run_bytes(&["encode", "oct24p", "--format", "binary"], &dec.out);
    assert_eq!(enc.code, 0, "{}", enc.stderr);
    assert_eq!(t.out, enc.out, "binary codes");
    let back = run_bytes(&["decode", "oct24p", "--format", "binary"], &enc.out);
    let floats = |b: &[u8]| -> Vec<[f32; 3]> {
        b.chunks_exact(12)
            .map(|r| {
                std::array::from_fn(|i| f32::from_le_bytes(r[4 * i..][..4].try_into().unwrap()))
            })
            .collect()
    };
    let (a, b) = (floats(&dec.out), floats(&back.out));
    let angles: Vec<f64> = a.iter().zip(&b).map(|(a, b)| angle_deg(*a, *b)).collect();
    let max = angles.iter().cloned().fold(0.0, f64::max);
    let mean = angles.iter().sum::<f64>() / angles.len() as f64;
    let (n, m, x, at) = summary(&t.stderr);
    assert_eq!(n, 1 << 16);
    assert!((m - mean).abs() < 1e-6, "mean {m} against {mean}");
    assert!((x - max).abs() < 1e-6, "max {x} against {max}");
    assert_eq!(
        angles[at as usize - 1].to_bits(),
        max.to_bits(),
        "record {at}"
    );
    // oct24p holds every oct16 direction within its own error.
    assert!(max < 0.1, "{max}");

    let text: String = (0..1u32 << 16)
        .step_by(97)
        .map(|c| format!("0x{c:04x}\n"))
        .collect();
    let t = run_stdin(
        &["transcode", "--from", "oct16", "--to", "snorm16x3"],
        &text,
    );
    let dec = run_stdin(&["decode", "oct16"], &text);
    let enc = run_stdin(&["encode", "snorm16x3"], &dec.stdout);
    assert_eq!((t.code, enc.code), (0, 0), "{} {}", t.stderr, enc.stderr);
    assert_eq!(t.stdout, enc.stdout, "text codes");
}

/// Comments pass through; a bad code ends the run naming its line, after the good lines'
/// output (stdout) or with the file left as it was (`--out`).
#[test]
fn transcode_streams_like_decode() {
    let r = run_stdin(
        &["transcode", "--from", "oct16", "--to", "oct24p"],
        "# normals\n0x0000\n\n",
    );
    assert_eq!(r.code, 0, "{r:?}");
    assert_eq!(r.stdout, "# normals\n0x00000000\n\n");
    assert_eq!(summary(&r.stderr).0, 1);
    assert!(
        r.stderr.starts_with("1 code moved from oct16 to oct24p"),
        "{r:?}"
    );
    let e = fails_after(
        &["transcode", "--from", "oct16", "--to", "oct24p"],
        "0x0000\n0x1ffff\n",
        "0x00000000\n",
    );
    assert!(
        e.contains("line 2") && e.contains("oct16's width of 16 bits"),
        "{e}"
    );
    let dir = tempdir();
    let out = dir.path().join("codes.txt");
    std::fs::write(&out, "kept\n").unwrap();
    let r = run_stdin(
        &[
            "transcode",
            "--from",
            "oct16",
            "--to",
            "oct24p",
            "--out",
            out.to_str().unwrap(),
            "--force",
        ],
        "0x0000\nnope\n",
    );
    assert_ne!(r.code, 0, "{r:?}");
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "kept\n");
    let e = fails(&["transcode", "--from", "oct16", "--to", "sfib20"], "");
    assert!(e.contains("sfib has no 20-bit form"), "{e}");
}
