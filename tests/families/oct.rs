//! The integer-decided precise searches (oct, hemioct) pick the nearest code: checked
//! against a brute force in f64 over every code within two steps of the chosen one,
//! decoded with the survey's formulas in f64 (an independent decoder, not the model's).

use unitpack::api::{CpuCodec, HemiOct, Oct};
use unitpack::support::sampling::random_unit_vectors;

/// The two snorm fields of a 2×`half`-bit code, first field lowest.
fn fields(code: u32, half: u32) -> [i64; 2] {
    let mask = (1u64 << half) - 1;
    [0, half].map(|sh| {
        let f = (u64::from(code) >> sh) & mask;
        if f >= 1 << (half - 1) {
            f as i64 - (1i64 << half)
        } else {
            f as i64
        }
    })
}

fn oct_f64(s: i64, t: i64, m: i64) -> [f64; 3] {
    let (x, y) = (s as f64 / m as f64, t as f64 / m as f64);
    let z = 1.0 - x.abs() - y.abs();
    let sg = |v: f64| if v >= 0.0 { 1.0 } else { -1.0 };
    let (x, y) = if z < 0.0 {
        ((1.0 - y.abs()) * sg(x), (1.0 - x.abs()) * sg(y))
    } else {
        (x, y)
    };
    [x, y, z]
}

fn hemioct_f64(s: i64, t: i64, m: i64) -> [f64; 3] {
    let (x, y) = (
        (s + t) as f64 / (2 * m) as f64,
        (s - t) as f64 / (2 * m) as f64,
    );
    [x, y, 1.0 - x.abs() - y.abs()]
}

fn angle(v: [f32; 3], d: [f64; 3]) -> f64 {
    let v = v.map(f64::from);
    let dot: f64 = (0..3).map(|i| v[i] * d[i]).sum();
    let cross = [
        v[1] * d[2] - v[2] * d[1],
        v[2] * d[0] - v[0] * d[2],
        v[0] * d[1] - v[1] * d[0],
    ];
    cross.iter().map(|c| c * c).sum::<f64>().sqrt().atan2(dot)
}

/// Every chosen code is within a hair of the nearest code around it: `2^-13` relative
/// (the integer comparison keeps about 15 bits where candidates nearly tie) plus the
/// input's fixed-point resolution, `2^-22` of its largest component.
fn misses(
    name: &str,
    half: u32,
    hemisphere: bool,
    encode: impl Fn([f32; 3]) -> u32,
    decode: fn(i64, i64, i64) -> [f64; 3],
) -> Vec<String> {
    let m = (1i64 << (half - 1)) - 1;
    let mut out = Vec::new();
    for v in random_unit_vectors(7, 1 << 15, hemisphere) {
        let [s, t] = fields(encode(v), half);
        let chosen = angle(v, decode(s, t, m));
        let mut best = f64::INFINITY;
        for ds in -2..=2 {
            for dt in -2..=2 {
                let (s2, t2) = (s + ds, t + dt);
                if s2.abs() > m || t2.abs() > m {
                    continue;
                }
                let d = decode(s2, t2, m);
                if hemisphere && d[2] < 0.0 {
                    continue;
                }
                best = best.min(angle(v, d));
            }
        }
        let slack = best * 2f64.powi(-13) + 2f64.powi(-21);
        if chosen > best + slack {
            out.push(format!(
                "{name}: {v:?} got ({s}, {t}) at {chosen:e} rad, a code within two steps is at {best:e}"
            ));
        }
    }
    out
}

fn check(
    name: &str,
    half: u32,
    hemisphere: bool,
    encode: impl Fn([f32; 3]) -> u32,
    decode: fn(i64, i64, i64) -> [f64; 3],
) {
    let m = misses(name, half, hemisphere, encode, decode);
    assert!(m.is_empty(), "{} misses, first: {}", m.len(), m[0]);
}

/// The check can fail: the fast encoders, which round each parameter on its own, miss
/// the nearest code often.
#[test]
fn fast_encoders_are_caught_missing_the_nearest_code() {
    let oct = Oct::new(16).unwrap().fast();
    assert!(misses("oct16", 8, false, |v| oct.encode(v), oct_f64).len() > 1000);
    let h = HemiOct::new(16).unwrap().fast();
    assert!(misses("hemioct16", 8, true, |v| h.encode(v), hemioct_f64).len() > 1000);
}

#[test]
fn precise_oct_picks_the_nearest_code() {
    for bits in [16, 24, 32] {
        let oct = Oct::new(bits).unwrap().precise();
        check(
            &format!("oct{bits}p"),
            bits / 2,
            false,
            |v| oct.encode(v),
            oct_f64,
        );
    }
}

#[test]
fn precise_hemioct_picks_the_nearest_code() {
    for bits in [16, 24, 32] {
        let h = HemiOct::new(bits).unwrap().precise();
        check(
            &format!("hemioct{bits}p"),
            bits / 2,
            true,
            |v| h.encode(v),
            hemioct_f64,
        );
    }
}
