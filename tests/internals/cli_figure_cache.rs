use unitpack::cli::figure_cache::*;
use unitpack::measure::figures::Bound;
use unitpack::measure::figures::ErrorStats;

/// What is written reads back as the same figures, bit for bit.
#[test]
fn figures_round_trip() {
    let bounds = vec![
        (7, None),
        (
            u128::MAX,
            Some(Bound {
                units: 0.1 + 0.2,
                at: vec![(-3, 4), (0, 65535)],
                reached: 0.25,
            }),
        ),
    ];
    let stats = vec![
        (("oct24:layout=rgb8".to_string(), 1000), None),
        (
            ("stereo_scaled16:scale=1.7777".to_string(), 1000),
            Some(ErrorStats {
                mean: 1.0 / 3.0,
                max: f64::MIN_POSITIVE,
                mse: 1e-300,
                samples: 1000,
            }),
        ),
    ];
    let text = unitpack::cli::figure_cache::format("h", &bounds, &stats);
    let (b, s) = parse(&text, "h").expect("parses");
    assert_eq!(b, bounds);
    assert_eq!(s.len(), 2);
    assert_eq!(s[0], stats[0]);
    let (x, y) = (s[1].1.unwrap(), stats[1].1.unwrap());
    assert_eq!(
        [x.mean, x.max, x.mse].map(f64::to_bits),
        [y.mean, y.max, y.mse].map(f64::to_bits)
    );
    assert_eq!(s[1].0, stats[1].0);
}

/// On glibc `cos` comes from the shared libm, so the fingerprint covers that file.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
#[test]
fn the_math_library_is_found() {
    let libm = math_library().expect("a shared math library");
    let name = libm.file_name().unwrap().to_string_lossy().into_owned();
    assert!(name.starts_with("libm"), "{}", libm.display());
    assert!(std::fs::metadata(&libm).unwrap().is_file());
}

/// Another build's file, or a damaged one, is not read at all.
#[test]
fn another_header_or_a_bad_line_is_ignored() {
    let text = unitpack::cli::figure_cache::format("h", &[(1, None)], &[]);
    assert!(parse(&text, "h2").is_none());
    assert!(parse(&format!("{text}bound zz none\n"), "h").is_none());
    assert!(parse(&format!("{text}stats 10 oct16 1 2\n"), "h").is_none());
    assert!(parse(&format!("{text}\n"), "h").is_none());
}
