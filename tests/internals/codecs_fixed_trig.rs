use std::f64::consts::PI;
use unitpack::codecs::toolkit::fixed_trig::*;

#[test]
fn atan2_pi_is_within_one_and_a_half_units() {
    // 1.1 units measured over 2·10⁶ angles; the float `trig::atan2_pi` it stands in
    // for is within 2·10⁻⁷ half turns, 1.7 units.
    for i in 0..20000 {
        let a = (i as f64 / 20000.0 - 0.5) * 2.0 * PI;
        for r in [1.0f64, 3.5] {
            let (y, x) = ((a.sin() * r) as f32, (a.cos() * r) as f32);
            let got = f64::from(atan2_pi(y, x)) / ONE;
            let exact = f64::from(y).atan2(f64::from(x)) / PI;
            assert!((got - exact).abs() <= 1.5 / ONE, "{a}: {got} vs {exact}");
        }
    }
    assert_eq!(atan2_pi(0.0f32, 0.0), 0.0);
    assert_eq!(atan2_pi(0.0f32, -2.0), ONE as f32);
}

#[test]
fn sinc_cos_quarter_is_within_four_units_for_every_q() {
    let one = f64::from(1u32 << 21);
    let mut worst = [0f64; 2];
    for q in 0..=(1u32 << 22) {
        let q = f64::from(q);
        let v = sinc_cos_quarter(q as f32, one);
        let r = (q / one).sqrt();
        let a = r * PI / 2.0;
        let sinc = if r == 0.0 { PI / 2.0 } else { a.sin() / r };
        worst[0] = worst[0].max((f64::from(v.x) - sinc * one).abs());
        worst[1] = worst[1].max((f64::from(v.y) - a.cos() * one).abs());
    }
    assert!(worst[0] <= 4.0 && worst[1] <= 4.0, "{worst:?}");
}

#[test]
fn sincos_pi_is_within_four_units() {
    for i in -1000..=1000 {
        let t = (f64::from(i) / 1000.0 * FINE).floor();
        let v = sincos_pi(t as f32);
        let a = t / FINE * PI;
        assert!((f64::from(v.x) / FINE - a.sin()).abs() <= 4.0 / FINE, "{t}");
        assert!((f64::from(v.y) / FINE - a.cos()).abs() <= 4.0 / FINE, "{t}");
    }
}
