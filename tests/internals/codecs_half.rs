use unitpack::codecs::toolkit::half::*;

/// Every f16 value, from the definition: `(-1)^s · 2^(e-15) · (1 + m/1024)`, or
/// `m · 2^-24` for `e = 0`.
fn value_of(h: u16) -> f64 {
    let s = if h & 0x8000 != 0 { -1.0 } else { 1.0 };
    let e = i32::from((h >> 10) & 31);
    let m = f64::from(h & 1023);
    match e {
        0 => s * m * 2f64.powi(-24),
        31 if m == 0.0 => s * f64::INFINITY,
        31 => f64::NAN,
        _ => s * (1.0 + m / 1024.0) * 2f64.powi(e - 15),
    }
}

#[test]
fn every_half_converts_exactly() {
    for h in 0..=u16::MAX {
        let got = half_value::<f32>(u32::from(h));
        let want = value_of(h);
        if want.is_nan() {
            assert!(got.is_nan(), "{h:#06x}: {got}");
            assert_eq!(got.to_bits() >> 31, u32::from(h >> 15), "{h:#06x}: sign");
            assert_eq!(got.to_bits() & 0x007f_ffff, u32::from(h & 1023) << 13);
        } else {
            assert_eq!(f64::from(got), want, "{h:#06x}");
            assert_eq!(got.is_sign_negative(), h & 0x8000 != 0, "{h:#06x}: sign");
        }
    }
}

/// The nearest f16 by search over the sorted finite values, ties to the even
/// pattern, overflow from 65520 (IEEE 754 §4.3.1, §7.4).
fn nearest(x: f32) -> u32 {
    let v = f64::from(x);
    if v.is_nan() {
        return if x.is_sign_negative() { 0xfe00 } else { 0x7e00 };
    }
    let sign = if x.is_sign_negative() { 0x8000 } else { 0 };
    let a = v.abs();
    if a >= 65520.0 {
        return sign | 0x7c00;
    }
    let mut best = 0u16;
    for h in 0..0x7c00u16 {
        let (d, db) = ((value_of(h) - a).abs(), (value_of(best) - a).abs());
        if d < db || (d == db && h & 1 == 0) {
            best = h;
        }
    }
    sign | u32::from(best)
}

#[test]
fn floats_round_to_the_nearest_half_ties_to_even() {
    let mut xs: Vec<f32> = vec![
        0.0,
        -0.0,
        1e-45,
        -1e-45,
        f32::MIN_POSITIVE,
        2f32.powi(-25),
        2f32.powi(-25) * 1.000_001,
        2f32.powi(-24) * 1.5,
        2f32.powi(-24) * 2.5,
        65504.0,
        65519.99,
        65520.0,
        -65520.0,
        f32::MAX,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
        -f32::NAN,
        1.0,
        1.0 + 2f32.powi(-11),
        1.0 + 3.0 * 2f32.powi(-11),
        0.1,
        -0.7,
    ];
    // Every midpoint between neighbouring finite halves, and a float either side.
    for h in (0..0x7bffu32).step_by(61) {
        let mid = ((value_of(h as u16) + value_of(h as u16 + 1)) / 2.0) as f32;
        xs.extend([
            mid,
            f32::from_bits(mid.to_bits() - 1),
            f32::from_bits(mid.to_bits() + 1),
        ]);
    }
    for x in xs {
        assert_eq!(half_bits(x), nearest(x), "{x:e} ({:#010x})", x.to_bits());
    }
}
