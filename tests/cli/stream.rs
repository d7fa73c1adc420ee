//! `encode` and `decode`: the text and binary formats, line-for-line errors, and memory
//! that stays bounded whatever the input size.

use crate::common::*;
use std::collections::BTreeSet;
use std::io::Write;
use std::path::PathBuf;
use std::process::Stdio;
use unitpack::codecs::Spec;
use unitpack::codecs::core::info::OptVal;

#[test]
fn encode_prints_one_hex_code_per_line() {
    let r = run_stdin(&["encode", "oct16"], "0 0 1\n1 0 0\n");
    assert_eq!(r.code, 0, "{r:?}");
    let lines: Vec<&str> = r.stdout.lines().collect();
    assert_eq!(lines.len(), 2, "{r:?}");
    for l in &lines {
        assert!(is_hex_code(l, 8), "{l:?} is not 0x + 8 hex digits");
    }
    assert_ne!(lines[0], lines[1]);
}

/// The texel layouts' example: x in alpha (0.6·½ + ½ = 204/255), y in green, R = 1, and a
/// layout on any size but 16 bits is a clear error.
#[test]
fn encode_writes_a_dxt5nm_texel() {
    let r = run_stdin(&["encode", "xy16:layout=dxt5nm"], "0.6 0 0.8\n");
    assert_eq!(r.code, 0, "{r:?}");
    let t = u32::from_str_radix(r.stdout.trim().trim_start_matches("0x"), 16).unwrap();
    assert_eq!(t >> 24, 0xcc, "alpha of {t:#010x}");
    assert_eq!(t >> 8 & 0xff, 0x80, "green of {t:#010x}: 127.5 ties up");
    assert_eq!(
        (t & 0xff, t >> 16 & 0xff),
        (0xff, 0),
        "red and blue of {t:#010x}"
    );
    let r = run_stdin(&["encode", "xy24:layout=dxt5nm"], "0 0 1\n");
    assert_eq!(r.code, 2, "{r:?}");
    assert!(r.stderr.contains("16-bit form only"), "{r:?}");
}

#[test]
fn decode_inverts_encode() {
    let input = [
        [0.0, 0.0, 1.0],
        [1.0, 0.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.48, -0.6, 0.64],
        [-0.36, 0.48, -0.8],
    ];
    let text: String = input
        .iter()
        .map(|v| format!("{} {} {}\n", v[0], v[1], v[2]))
        .collect();
    let enc = run_stdin(&["encode", "oct16"], &text);
    assert_eq!(enc.code, 0, "{enc:?}");
    let dec = run_stdin(&["decode", "oct16"], &enc.stdout);
    assert_eq!(dec.code, 0, "{dec:?}");
    let out: Vec<[f32; 3]> = dec.stdout.lines().map(parse_vec).collect();
    assert_eq!(out.len(), input.len(), "{dec:?}");
    // Axes are exact in oct16; the documented maximum error is below 1°.
    assert_eq!(&out[..2], &[[0.0, 0.0, 1.0], [1.0, 0.0, 0.0]]);
    for (a, b) in input.iter().zip(&out) {
        assert!(angle_deg(*a, *b) < 1.0, "{a:?} → {b:?}");
        let len = b.iter().map(|x| x * x).sum::<f32>().sqrt();
        assert!(
            (len - 1.0).abs() < 1e-6,
            "oct decodes to unit vectors: {b:?}"
        );
    }
}

#[test]
fn encode_and_decode_round_trip_for_every_codec() {
    // Vectors in the +Z hemisphere, away from every codec's singular region.
    let input: Vec<[f32; 3]> = vec![
        [0.0, 0.0, 1.0],
        [0.6, 0.0, 0.8],
        [0.0, -0.6, 0.8],
        [-0.48, 0.36, 0.8],
        [0.3, 0.3, 0.9055385],
    ];
    let text: String = input
        .iter()
        .map(|v| format!("{} {} {}\n", v[0], v[1], v[2]))
        .collect();
    for spec in Spec::all().iter().filter(|s| s.info().domain.is_some()) {
        let name = spec.to_string();
        let arg = name.replace("_rgb8", ":layout=rgb8");
        let enc = run_stdin(&["encode", &arg], &text);
        assert_eq!(enc.code, 0, "{name}: {enc:?}");
        let digits = if spec.bits() > 32 {
            spec.bits().div_ceil(4) as usize
        } else {
            8
        };
        assert!(
            enc.stdout.lines().all(|l| is_hex_code(l, digits)),
            "{name}: {enc:?}"
        );
        let dec = run_stdin(&["decode", &arg], &enc.stdout);
        assert_eq!(dec.code, 0, "{name}: {dec:?}");
        let out: Vec<[f32; 3]> = dec.stdout.lines().map(parse_vec).collect();
        assert_eq!(out.len(), input.len(), "{name}: {dec:?}");
        // The seed's method 3a tables misread its own codes near the poles by several
        // degrees (README, "The first seed's method 3a"; sample max 7.2°), with either encoder.
        // meshoptimizer's words hold K-bit coordinates: its direction has 2K bits.
        let direction_bits = match spec.family().engine(spec) {
            Some("meshoptimizer") => {
                let k = spec.info().options.iter().find(|o| o.key == "bits");
                match k.and_then(|k| spec.option(k)) {
                    Some(OptVal::Number(k)) => 2 * k as u32,
                    other => panic!("{name}: K is {other:?}"),
                }
            }
            _ => spec.bits(),
        };
        let tol = match direction_bits {
            _ if spec.fast().id() == "spherical_lut16" => 8.0,
            0..=16 => 3.0,
            _ => 1.0,
        };
        for (a, b) in input.iter().zip(&out) {
            assert!(
                angle_deg(*a, *b) < tol,
                "{name}: {a:?} → {b:?} ({}°)",
                angle_deg(*a, *b)
            );
        }
    }
}

#[test]
fn encode_degenerate_input_gives_the_plus_z_code() {
    let plus_z = run_stdin(&["encode", "oct16"], "0 0 1\n");
    assert_eq!(plus_z.code, 0, "{plus_z:?}");
    let r = run_stdin(
        &["encode", "oct16"],
        "0 0 0\nnan nan nan\ninf 0 0\n-inf 1 0\n0 NaN 1\n",
    );
    assert_eq!(r.code, 0, "{r:?}");
    let lines: Vec<&str> = r.stdout.lines().collect();
    assert_eq!(lines.len(), 5, "{r:?}");
    for l in lines {
        assert!(is_hex_code(l, 8), "{l:?}");
        // oct's documented policy: zero, NaN and infinite input encode as +Z.
        assert_eq!(l, plus_z.stdout.trim());
    }
}

/// Output line N answers input line N: blank and `#` lines pass through unchanged.
#[test]
fn blank_and_comment_lines_pass_through_so_lines_correspond() {
    let plus_z = run_stdin(&["encode", "oct16"], "0 0 1\n").stdout;
    let plus_x = run_stdin(&["encode", "oct16"], "1 0 0\n").stdout;
    let r = run_stdin(
        &["encode", "oct16"],
        "\n  0 0 1  \n# a comment\n\n   # indented\n1\t0\t0",
    );
    assert_eq!(r.code, 0, "{r:?}");
    assert_eq!(
        r.stdout,
        format!("\n{plus_z}# a comment\n\n   # indented\n{plus_x}"),
        "{r:?}"
    );
    let r = run_stdin(&["decode", "oct16"], "# codes\n0x0000007f\n\n127\n");
    assert_eq!(r.code, 0, "{r:?}");
    assert_eq!(r.stdout, "# codes\n1.0 0.0 0.0\n\n1.0 0.0 0.0\n", "{r:?}");
    // Blank lines still count in error messages.
    let err = fails_after(
        &["encode", "oct16"],
        "0 0 1\n\n1 2\n",
        &format!("{plus_z}\n"),
    );
    assert!(err.contains("line 3"), "blank lines still count: {err}");
    // Empty input: no output, success.
    let r = run_stdin(&["encode", "oct16"], "");
    assert_eq!((r.code, r.stdout.as_str()), (0, ""), "{r:?}");
    // \r\n line ends are read; output lines end in \n.
    let r = run_stdin(&["encode", "oct16"], "0 0 1\r\n# c\r\n");
    assert_eq!(r.stdout, format!("{plus_z}# c\n"), "{r:?}");
}

/// On stdout, the output of every line before a bad one has been written (as the help
/// says); the error names the line and quotes it.
#[test]
fn encode_malformed_line_fails_after_the_lines_before_it() {
    let plus_z = run_stdin(&["encode", "oct16"], "0 0 1\n").stdout;
    let err = fails_after(&["encode", "oct16"], "0 0 1\n1 2\n0 1 0\n", &plus_z);
    assert!(err.contains("line 2"), "{err}");
    assert!(
        err.contains("\"1 2\""),
        "the bad line should be quoted: {err}"
    );
    for bad in ["1 2 3 4", "a b c", "1,0,0", "0x1 0 0"] {
        let err = fails(&["encode", "oct16"], &format!("{bad}\n"));
        assert!(err.contains("line 1"), "{bad:?}: {err}");
    }
}

#[test]
fn encode_names_numbers_outside_the_f32_range() {
    for bad in ["1e39 0 0", "0 -3.5e38 0", "0 0 1e400"] {
        let err = fails(&["encode", "oct16"], &format!("{bad}\n"));
        assert!(
            err.contains("line 1") && err.contains("outside the f32 range"),
            "{bad:?}: {err}"
        );
    }
    // Spelled infinities are accepted (and encode as +Z), as is f32::MAX.
    let r = run_stdin(&["encode", "oct16"], "inf 0 0\n3.4028235e38 0 0\n");
    assert_eq!(r.code, 0, "{r:?}");
}

#[test]
fn a_byte_order_mark_at_the_start_is_accepted() {
    let plain = run_stdin(&["encode", "oct16"], "0 0 1\n");
    let r = run_stdin(&["encode", "oct16"], "\u{feff}0 0 1\n");
    assert_eq!((r.code, &r.stdout), (0, &plain.stdout), "{r:?}");
    let r = run_stdin(&["decode", "oct16"], "\u{feff}0x7f\n");
    assert_eq!((r.code, r.stdout.as_str()), (0, "1.0 0.0 0.0\n"), "{r:?}");
    // Only at the start.
    let err = fails_after(
        &["encode", "oct16"],
        "0 0 1\n\u{feff}0 0 1\n",
        &plain.stdout,
    );
    assert!(err.contains("line 2"), "{err}");
}

#[test]
fn invalid_utf8_is_an_error_naming_its_line() {
    let r = run_bytes(&["encode", "oct16"], b"0 0 1\n0 1 0\n\xff\xfe 0 0\n");
    assert_eq!(r.code, 2, "{r:?}");
    assert!(
        r.stderr.contains("line 3") && r.stderr.contains("UTF-8"),
        "{r:?}"
    );
    assert_eq!(r.stdout.lines().count(), 2, "{r:?}");
    let r = run_bytes(&["decode", "oct16"], b"0x7f\n0x\xc3\n");
    assert_eq!(r.code, 2, "{r:?}");
    assert!(
        r.stderr.contains("line 2") && r.stderr.contains("UTF-8"),
        "{r:?}"
    );
}

/// A bad line is quoted cut to about 80 characters, whatever its length.
#[test]
fn errors_quote_at_most_80_characters_of_a_line() {
    for verb in ["encode", "decode"] {
        let line = format!("0 0 {}\n", "9".repeat(5000));
        let err = fails(&[verb, "oct16"], &line);
        assert!(err.contains("line 1"), "{err}");
        assert!(
            err.len() < 400,
            "{verb}: {} bytes of error: {err}",
            err.len()
        );
        assert!(err.contains("5004 bytes"), "{verb}: {err}");
    }
    // 10 MB without a line end: still a short error, and quickly.
    let huge = "x".repeat(10 << 20);
    let err = fails(&["encode", "oct16"], &huge);
    assert!(err.contains("line 1") && err.len() < 400, "{err}");
}

#[test]
fn decode_malformed_line_fails_after_the_lines_before_it() {
    let err = fails(&["decode", "oct16"], "zz\n");
    assert!(err.contains("line 1"), "{err}");
    let err = fails_after(
        &["decode", "oct16"],
        "0x00000000\n0x7f\n0xg\n",
        "0.0 0.0 1.0\n1.0 0.0 0.0\n",
    );
    assert!(err.contains("line 3"), "{err}");
    let err = fails(&["decode", "oct16"], "0x100000000\n");
    assert!(err.contains("line 1") && err.contains("16 bits"), "{err}");
    let err = fails(&["decode", "snorm16x3"], "0x10000000000000000\n");
    assert!(err.contains("line 1") && err.contains("48 bits"), "{err}");
}

/// One grammar: `0x` + hex digits, or decimal digits; nothing else.
#[test]
fn decode_reads_0x_hex_or_decimal_and_nothing_else() {
    let r = run_stdin(
        &["decode", "oct16"],
        "0x0000007f\n0X7F\n  0x7f  \n127\n\t0127\n",
    );
    assert_eq!(r.code, 0, "{r:?}");
    let lines: Vec<&str> = r.stdout.lines().collect();
    assert_eq!(lines.len(), 5, "{r:?}");
    for l in lines {
        assert_eq!(parse_vec(l), [1.0, 0.0, 0.0], "{r:?}");
    }
    // 123 is decimal 123, not 0x123.
    assert_eq!(
        run_stdin(&["decode", "oct16"], "123\n").stdout,
        run_stdin(&["decode", "oct16"], "0x7b\n").stdout
    );
    assert_ne!(
        run_stdin(&["decode", "oct16"], "123\n").stdout,
        run_stdin(&["decode", "oct16"], "0x123\n").stdout
    );
    for bad in [
        "0b101", "+ff", "0x+ff", "-1", "+1", "7f", "0x", "1_000", "0o17", "0x7f 1", "1.0",
    ] {
        let err = fails(&["decode", "oct16"], &format!("{bad}\n"));
        assert!(
            err.contains("line 1") && err.contains("0x followed by hex digits"),
            "{bad:?}: {err}"
        );
    }
}

/// A decoder ignores bits above its width, so such a code is refused rather than
/// decoded as another.
#[test]
fn decode_rejects_codes_wider_than_the_spec() {
    for (spec, ok_code, bad, bits) in [
        ("oct16", "0xffff", "0x1ffff", 16),
        ("oct16", "65535", "65536", 16),
        ("oct24", "0xffffff", "0x1000000", 24),
        ("oct24:layout=rgb8", "0xffffff", "0x1000000", 24),
        ("snorm10x3", "0x3fffffff", "0x40000000", 30),
        ("oct32", "0xffffffff", "0x100000000", 32),
        ("snorm16x3", "0xffffffffffff", "0x1000000000000", 48),
        ("snorm16x3", "281474976710655", "18446744073709551616", 48),
    ] {
        let r = run_stdin(&["decode", spec], &format!("{ok_code}\n"));
        assert_eq!(r.code, 0, "{spec} {ok_code}: {r:?}");
        let err = fails(&["decode", spec], &format!("{bad}\n"));
        assert!(
            err.contains("line 1") && err.contains(&format!("width of {bits} bits")),
            "{spec} {bad}: {err}"
        );
    }
}

/// Every code `encode` prints fits the spec's width, so `decode` accepts it.
#[test]
fn every_encoded_code_fits_the_spec_width() {
    use unitpack::codecs::functions::function::{Inputs, Role};
    let mut vs = unitpack::support::sampling::random_unit_vectors(5, 4096, false);
    vs.extend([
        [0.0, 0.0, -1.0],
        [-1.0, -1.0, -1.0],
        [0.0, 0.0, 0.0],
        [f32::NAN; 3],
    ]);
    for spec in Spec::all().iter().filter(|s| s.info().domain.is_some()) {
        let e = spec.emitted();
        // The code's width: the spec's bits, or a texel layout's whole RGBA8 texel.
        let width = if unitpack::codecs::core::texel::layout(spec).is_some() {
            32
        } else {
            spec.bits()
        };
        // Every encoder of a vector alone (a lookup-table codec's CPU encoder, not its
        // emitted `encode(v, fetched)`, which takes the fetch as well).
        let encoders = e.cpu.iter().chain(&e.functions);
        for f in encoders.filter(|f| f.role == Role::Encode && f.inputs == Inputs::Vectors) {
            let mut code = vec![0u32; f.out_words];
            for v in &vs {
                (f.eval)(&v.map(f32::to_bits), &mut code);
                let c = code
                    .iter()
                    .rev()
                    .fold(0u128, |a, w| (a << 32) | u128::from(*w));
                assert!(c >> width == 0, "{spec} {}: {v:?} → {c:#x}", f.name);
            }
        }
    }
}

#[test]
fn snorm16x3_codes_have_12_hex_digits() {
    let enc = run_stdin(&["encode", "snorm16x3"], "0 0 1\n");
    assert_eq!(enc.code, 0, "{enc:?}");
    assert_eq!(enc.stdout, "0x7fff00000000\n");
    let dec = run_stdin(&["decode", "snorm16x3"], "0x7fff00000000\n0x123456789abc\n");
    assert_eq!(dec.code, 0, "{dec:?}");
    let out: Vec<[f32; 3]> = dec.stdout.lines().map(parse_vec).collect();
    assert_eq!(out.len(), 2);
    assert_eq!(out[0], [0.0, 0.0, 1.0]);
    let len = out[1].iter().map(|x| x * x).sum::<f32>().sqrt();
    assert!(
        (len - 1.0).abs() < 1e-5,
        "snorm3 decode re-normalizes: {:?}",
        out[1]
    );
}

/// float32x3 codes are three words: 24 hex digits (z's word highest) in text, 12 bytes
/// (x's word first) in binary, and back.
#[test]
fn float32x3_codes_are_three_words() {
    let enc = run_stdin(&["encode", "float32x3"], "0 -2 0\n");
    assert_eq!(enc.code, 0, "{enc:?}");
    assert_eq!(enc.stdout, "0x00000000bf80000000000000\n");
    let dec = run_stdin(&["decode", "float32x3"], "0x3f800000000000003f000000\n");
    assert_eq!(dec.code, 0, "{dec:?}");
    assert_eq!(dec.stdout, "0.5 0.0 1.0\n");
    let err = fails(&["decode", "float32x3"], "0x1000000000000000000000000\n");
    assert!(err.contains("96 bits"), "{err}");
    let bin = run_stdin(
        &["encode", "float32x3", "--output-format", "binary"],
        "0 0 -1\n",
    );
    assert_eq!(bin.code, 0, "{bin:?}");
    let words: Vec<u8> = [0u32, 0, 0xbf80_0000]
        .iter()
        .flat_map(|w| w.to_le_bytes())
        .collect();
    assert_eq!(bin.out, words);
    let back = run_bytes(&["decode", "float32x3", "--input-format", "binary"], &words);
    assert_eq!(back.code, 0, "{back:?}");
    assert_eq!(back.stdout, "0.0 0.0 -1.0\n");
    let short = run_bytes(
        &["decode", "float32x3", "--input-format", "binary"],
        &words[..8],
    );
    assert_ne!(short.code, 0);
    assert!(
        short.stderr.contains("a code is 12 bytes, 3×u32"),
        "{short:?}"
    );
}

/// A tangent-frame spec streams frames, seven numbers `nx ny nz tx ty tz w` per line or
/// 28-byte records: its codes are the CPU API's `FrameBatch` codes (the generated
/// functions' bits), its decoded frames `FrameBatch`'s, in text and binary alike; a line
/// of three numbers is an error naming the seven; `Batch` and `FrameBatch` each refuse the
/// other kind of spec.
#[test]
fn frame_specs_stream_frames() {
    use unitpack::api::Frame;
    let n = [[0.0f32, 0.0, 1.0], [0.6, 0.0, 0.8], [0.0, -0.28, 0.96]];
    let t = [
        [1.0f32, 0.0, 0.0, 1.0],
        [0.0, 1.0, 0.0, -1.0],
        [0.8, 0.5, 0.1, 1.0],
    ];
    let text: String = n
        .iter()
        .zip(&t)
        .map(|(n, t)| {
            format!(
                "{} {} {} {} {} {} {}\n",
                n[0], n[1], n[2], t[0], t[1], t[2], t[3]
            )
        })
        .collect();
    let records: Vec<u8> = n
        .iter()
        .zip(&t)
        .flat_map(|(n, t)| n.iter().chain(t).flat_map(|x| x.to_le_bytes()))
        .collect();
    for (spec, digits) in [
        ("qtangent64", 16),
        ("qtangent32", 8),
        ("godot_axis_angle", 12),
        ("octangle32", 8),
        ("octangle48", 12),
    ] {
        let batch = unitpack::api::FrameBatch::new(spec).unwrap();
        let frames: Vec<Frame> = n.iter().zip(&t).map(|(&n, &t)| Frame { n, t }).collect();
        let mut codes = vec![0u32; n.len() * batch.words()];
        batch.encode(&frames, &mut codes);
        let want: String = codes
            .chunks(batch.words())
            .map(|c| {
                let hi = c.get(1).map_or(0, |&w| u64::from(w));
                format!("0x{:0digits$x}\n", hi << 32 | u64::from(c[0]))
            })
            .collect();
        let enc = run_stdin(&["encode", spec], &text);
        assert_eq!((enc.code, &enc.stdout), (0, &want), "{spec}: {enc:?}");
        let bytes: Vec<u8> = codes.iter().flat_map(|w| w.to_le_bytes()).collect();
        let r = run_bytes(&["encode", spec, "--format", "binary"], &records);
        assert_eq!((r.code, &r.out), (0, &bytes), "{spec}: {r:?}");
        // Decoded: seven floats per frame, n then t with the sign in w.
        let mut back = vec![Frame::default(); n.len()];
        batch.decode(&codes, &mut back);
        let want: String = back
            .iter()
            .map(|f| {
                let v: Vec<String> = f.n.iter().chain(&f.t).map(|x| format!("{x:?}")).collect();
                v.join(" ") + "\n"
            })
            .collect();
        let dec = run_stdin(&["decode", spec], &enc.stdout);
        assert_eq!((dec.code, &dec.stdout), (0, &want), "{spec}: {dec:?}");
        let r = run_bytes(&["decode", spec, "--format", "binary"], &bytes);
        let floats: Vec<u8> = back
            .iter()
            .flat_map(|f| f.n.iter().chain(&f.t).flat_map(|x| x.to_le_bytes()))
            .collect();
        assert_eq!((r.code, &r.out), (0, &floats), "{spec}: {r:?}");
        assert_eq!(
            back.iter().map(|f| f.t[3]).collect::<Vec<_>>(),
            [1.0, -1.0, 1.0]
        );
        // A vector line is not a frame; a partial record names the frame's size.
        let err = fails(&["encode", spec], "0 0 1\n");
        assert!(
            err.contains("expected seven numbers `nx ny nz tx ty tz w`, found 3"),
            "{spec}: {err}"
        );
        let r = run_bytes(
            &["encode", spec, "--input-format", "binary"],
            &records[..40],
        );
        assert!(
            r.stderr.contains("a frame is 28 bytes, 7×f32"),
            "{spec}: {r:?}"
        );
    }
    let batch = unitpack::api::Batch::new("qtangent64");
    assert!(batch.is_err_and(|e| e.to_string().contains("use FrameBatch")));
    let frames = unitpack::api::FrameBatch::new("oct16");
    assert!(frames.is_err_and(|e| e.to_string().contains("use Batch")));
}

#[test]
fn helpers_have_no_encode_or_decode() {
    for verb in ["encode", "decode"] {
        for helper in ["snorm12x2", "paraboloid_pd"] {
            let err = fails(&[verb, helper], "0 0 1\n");
            assert!(
                err.contains(&format!("{helper} is a helper, not a codec")),
                "{verb}: {err}"
            );
        }
    }
}

#[test]
fn encode_and_decode_reject_bad_specs() {
    for verb in ["encode", "decode"] {
        let err = fails(&[verb, "octt16"], "0 0 1\n");
        assert!(err.contains("unknown codec 'octt16'"), "{verb}: {err}");
        let err = fails(&[verb, "oct16:layout=rgb8"], "0 0 1\n");
        assert!(err.contains("oct24"), "{verb}: {err}");
    }
}

/// Runs `args` over `input` with stdout discarded; returns (exit status, peak RSS in KiB).
/// The peak is the child's VmHWM, sampled every few milliseconds until it exits (a lower
/// bound of the true peak, which a program holding its whole input keeps for seconds).
/// Neither wait4's ru_maxrss nor /proc before exec will do: both count the parent's
/// memory, which the child shares until it runs `unitpack`.
#[cfg(target_os = "linux")]
fn peak_rss_kib(args: &[&str], input: Vec<u8>) -> (i32, u64) {
    let mut child = unitpack()
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let mut si = child.stdin.take().unwrap();
    let w = std::thread::spawn(move || {
        let _ = si.write_all(&input);
    });
    let status_file = format!("/proc/{}/status", child.id());
    let mut peak = 0;
    let status = loop {
        if let Ok(s) = std::fs::read_to_string(&status_file) {
            let ours = s
                .lines()
                .any(|l| l.split_whitespace().eq(["Name:", "unitpack"]));
            let hwm = s.lines().find_map(|l| l.strip_prefix("VmHWM:"));
            if let (true, Some(v)) = (ours, hwm) {
                let kib: u64 = v.trim().trim_end_matches("kB").trim().parse().unwrap();
                peak = peak.max(kib);
            }
        }
        if let Some(st) = child.try_wait().unwrap() {
            break st;
        }
        std::thread::sleep(std::time::Duration::from_millis(3));
    };
    w.join().unwrap();
    assert!(peak > 0, "no sample of the child's memory");
    (status.code().expect("not killed"), peak)
}

/// 48 MB of input in, peak memory far below it: nothing holds the whole input.
#[cfg(target_os = "linux")]
#[test]
fn encode_and_decode_stream_in_bounded_memory() {
    let vectors = "0.48 -0.6 0.64\n".repeat(3_200_000).into_bytes();
    let (code, kib) = peak_rss_kib(&["encode", "oct16"], vectors);
    assert_eq!(code, 0);
    assert!(
        kib < 32 * 1024,
        "encode peaked at {kib} KiB on 48 MB of input"
    );
    let codes = "0x00001234\n".repeat(4_400_000).into_bytes();
    let (code, kib) = peak_rss_kib(&["decode", "oct16"], codes);
    assert_eq!(code, 0);
    assert!(
        kib < 32 * 1024,
        "decode peaked at {kib} KiB on 48 MB of input"
    );
}

#[test]
fn encode_out_file_is_written_only_when_every_line_is_good() {
    let dir = tempdir();
    let p = dir.path().join("codes.txt");
    std::fs::write(&p, "previous\n").unwrap();
    let err = fails(
        &["encode", "oct16", "--out", p.to_str().unwrap()],
        "0 0 1\n1 0 0\nbad\n",
    );
    assert!(err.contains("line 3"), "{err}");
    assert_eq!(std::fs::read_to_string(&p).unwrap(), "previous\n");
    assert_eq!(
        tree(dir.path()),
        BTreeSet::from([PathBuf::from("codes.txt")])
    );
    let r = run_stdin(
        &["encode", "oct16", "--out", p.to_str().unwrap()],
        "0 0 1\n1 0 0\n",
    );
    assert_eq!((r.code, r.stdout.as_str()), (0, ""), "{r:?}");
    assert_eq!(
        std::fs::read_to_string(&p).unwrap(),
        run_stdin(&["encode", "oct16"], "0 0 1\n1 0 0\n").stdout
    );
    assert_eq!(
        tree(dir.path()),
        BTreeSet::from([PathBuf::from("codes.txt")])
    );
}

fn f32s_le(v: &[[f32; 3]]) -> Vec<u8> {
    v.iter().flatten().flat_map(|x| x.to_le_bytes()).collect()
}

#[test]
fn binary_formats_are_raw_little_endian_records() {
    let vs = [[0.0f32, 0.0, 1.0], [0.48, -0.6, 0.64], [-0.36, 0.48, -0.8]];
    let text: String = vs
        .iter()
        .map(|v| format!("{} {} {}\n", v[0], v[1], v[2]))
        .collect();
    for (spec, width) in [("oct16", 4), ("oct24p", 4), ("snorm16x3", 8)] {
        let hex = run_stdin(&["encode", spec], &text);
        let want: Vec<u8> = hex
            .stdout
            .lines()
            .flat_map(|l| {
                let v = u64::from_str_radix(&l[2..], 16).unwrap();
                v.to_le_bytes()[..width].to_vec()
            })
            .collect();
        // text → binary, binary → binary
        let r = run_stdin(&["encode", spec, "--output-format", "binary"], &text);
        assert_eq!((r.code, &r.out), (0, &want), "{spec}: {r:?}");
        let r = run_bytes(&["encode", spec, "--format", "binary"], &f32s_le(&vs));
        assert_eq!((r.code, &r.out), (0, &want), "{spec}: {r:?}");
        // binary codes → text vectors equals text → text
        let r = run_bytes(&["decode", spec, "--input-format", "binary"], &want);
        assert_eq!(r.code, 0, "{r:?}");
        assert_eq!(r.stdout, run_stdin(&["decode", spec], &hex.stdout).stdout);
        // binary → binary: 12 bytes per vector, the same floats
        let r = run_bytes(&["decode", spec, "--format", "binary"], &want);
        assert_eq!(r.out.len(), 12 * vs.len(), "{spec}");
        let floats: Vec<[f32; 3]> = r
            .out
            .chunks_exact(12)
            .map(|c| [0, 4, 8].map(|i| f32::from_le_bytes(c[i..i + 4].try_into().unwrap())))
            .collect();
        let text_floats: Vec<[f32; 3]> = run_stdin(&["decode", spec], &hex.stdout)
            .stdout
            .lines()
            .map(parse_vec)
            .collect();
        assert_eq!(floats, text_floats, "{spec}");
    }
    // A partial record is an error naming the record; so is a code above the width.
    let r = run_bytes(
        &["encode", "oct16", "--format", "binary"],
        &[0u8; 12 * 2 + 5],
    );
    assert_eq!(r.code, 2, "{r:?}");
    assert!(
        r.stderr.contains("record 3") && r.stderr.contains("12 bytes"),
        "{r:?}"
    );
    // The two whole records before the partial one are written (to stdout).
    assert_eq!(r.out.len(), 2 * 4, "{r:?}");
    assert!(!r.stderr.contains("looks like text"), "{r:?}");
    // Text given as binary input (`--format binary` meant for the output) is said to be
    // text, with the options meant: when it ends mid-record, and when it happens to fill
    // whole records, which then encode as the nonsense they are.
    let r = run_bytes(&["encode", "oct16", "--format", "binary"], b"0 0 1\n");
    assert_eq!(r.code, 2, "{r:?}");
    assert!(
        r.stderr.contains("record 1")
            && r.stderr.contains("looks like text")
            && r.stderr
                .contains("--input-format text --output-format binary"),
        "{r:?}"
    );
    let r = run_bytes(
        &["encode", "oct16", "--format", "binary"],
        b"0 0 1\n1 0 0\n",
    );
    assert_eq!(r.code, 0, "{r:?}");
    assert!(
        r.stderr.starts_with("warning: the input looks like text"),
        "{r:?}"
    );
    let r = run_bytes(
        &[
            "encode",
            "oct16",
            "--input-format",
            "text",
            "--output-format",
            "binary",
        ],
        b"0 0 1\n",
    );
    assert_eq!((r.code, r.out.len()), (0, 4), "{r:?}");
    // A bad code in the second block of 8192 records: every record before it is
    // written, each the code's decode, and the error names record 8193.
    let mut codes: Vec<u8> = (0..8192u32)
        .flat_map(|i| ((i * 7) & 0xffff).to_le_bytes())
        .collect();
    codes.extend(0x1_0000u32.to_le_bytes());
    codes.extend(5u32.to_le_bytes());
    let r = run_bytes(&["decode", "oct16", "--format", "binary"], &codes);
    assert_eq!(r.code, 2, "{r:?}");
    assert!(r.stderr.contains("record 8193"), "{}", r.stderr);
    assert_eq!(r.out.len(), 8192 * 12, "{}", r.stderr);
    let whole = run_bytes(
        &["decode", "oct16", "--format", "binary"],
        &codes[..8192 * 4],
    );
    assert_eq!(whole.code, 0, "{}", whole.stderr);
    assert_eq!(r.out, whole.out);
    let r = run_bytes(
        &["decode", "oct16", "--format", "binary"],
        &0x1_0000u32.to_le_bytes(),
    );
    assert_eq!(r.code, 2, "{r:?}");
    assert!(
        r.stderr.contains("record 1") && r.stderr.contains("16 bits"),
        "{r:?}"
    );
    // Blank and comment lines of text input produce no record.
    let r = run_stdin(
        &["encode", "oct16", "--output-format", "binary"],
        "# c\n\n0 0 1\n",
    );
    assert_eq!(r.out.len(), 4, "{r:?}");
}
