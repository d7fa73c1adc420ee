//! The model's own trigonometry against f64, over the whole input range.

use std::f64::consts::PI;
use unitpack::codecs::toolkit::trig::{
    ATAN2_PI_MAX_ERROR, SINCOS_PI_MAX_ERROR, atan2_pi, sincos_pi, sincos_quarter_pi,
};

#[test]
fn atan2_pi_error_is_within_the_stated_bound() {
    let mut worst = 0f64;
    let n = 2000;
    for i in 0..n {
        let a = (i as f64 / n as f64) * 2.0 * PI - PI;
        for r in [1e-20f64, 1e-3, 1.0, 3e4] {
            let (y, x) = ((a.sin() * r) as f32, (a.cos() * r) as f32);
            let want = (y as f64).atan2(x as f64) / PI;
            let got = atan2_pi(y, x) as f64;
            worst = worst.max((got - want).abs());
        }
    }
    println!("atan2_pi max error {worst:e}");
    assert!(
        worst <= ATAN2_PI_MAX_ERROR,
        "atan2_pi max error {worst:e} > {ATAN2_PI_MAX_ERROR:e}"
    );
    assert_eq!(atan2_pi(0.0f32, 0.0), 0.0);
    assert_eq!(atan2_pi(0.0f32, -1.0), 1.0);
}

#[test]
fn sincos_pi_error_is_within_the_stated_bound() {
    let mut worst = 0f64;
    for i in 0..=200_000 {
        let t = (i as f32 / 100_000.0) - 1.0;
        let sc = sincos_pi(t);
        let a = t as f64 * PI;
        worst = worst
            .max((sc.x as f64 - a.sin()).abs())
            .max((sc.y as f64 - a.cos()).abs());
    }
    println!("sincos_pi max error {worst:e}");
    assert!(
        worst <= SINCOS_PI_MAX_ERROR,
        "sincos_pi max error {worst:e} > {SINCOS_PI_MAX_ERROR:e}"
    );
}

/// The branch-free quarter-turn form over its whole domain, the ends included (a
/// diagonal of the concentric map's square is exactly ±1/4): within the same bound, and
/// the same bits as the reduced form where that takes no reduction.
#[test]
fn sincos_quarter_pi_error_is_within_the_stated_bound() {
    let mut worst = 0f64;
    for i in 0..=100_000 {
        let t = (i as f32 / 200_000.0) - 0.25;
        let sc = sincos_quarter_pi(t);
        let a = t as f64 * PI;
        worst = worst
            .max((sc.x as f64 - a.sin()).abs())
            .max((sc.y as f64 - a.cos()).abs());
        if t.abs() < 0.25 {
            let r = sincos_pi(t);
            assert_eq!(
                (sc.x.to_bits(), sc.y.to_bits()),
                (r.x.to_bits(), r.y.to_bits()),
                "t = {t}"
            );
        }
    }
    println!("sincos_quarter_pi max error {worst:e}");
    assert!(
        worst <= SINCOS_PI_MAX_ERROR,
        "sincos_quarter_pi max error {worst:e} > {SINCOS_PI_MAX_ERROR:e}"
    );
}
