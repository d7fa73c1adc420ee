use unitpack::codecs::toolkit::exact::*;
use unitpack::codecs::toolkit::quant::Quant;
use unitpack::model::V3;

/// `rounded_root` is the exact integer root rounded to nearest, and every component
/// of `unit_on_grid` is `round(Aᵢ·2^24 / N)` (ties up) in exact integer arithmetic,
/// for seeded random directions and the axes.
#[test]
fn unit_on_grid_rounds_exactly() {
    let mut vs = unitpack::support::sampling::random_unit_vectors(3, 100_000, false);
    vs.extend([
        [1.0, 0.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.6, 0.0, 0.8],
        [1e-30, 1.0, 1e-9],
    ]);
    for v in vs {
        let (w, ok) = canonical(V3::from_array(v));
        assert!(ok, "{v:?}");
        let a = w
            .to_array()
            .map(|x| (x.abs() * FIXED_SCALE).floor() as u128);
        let parts = square_sum_parts::<f32, 3>(a.map(|a| a as u32));
        let s = joined::<f32>(parts) / (FIXED_SCALE * FIXED_SCALE);
        let big: u128 = a.iter().map(|a| a * a).sum();
        let n = u128::from(rounded_root::<f32>(s, parts));
        // Any estimate within two units reaches N: the integers decide.
        for off in [-2i64, -1, 0, 1, 2] {
            let n0 = (n as i64 + off) as u32;
            let got = u128::from(settled_root::<f32>(n0, parts));
            assert_eq!(got, n, "{v:?}: from N{off:+}");
        }
        // (N - ½)² ≤ S < (N + ½)², in integers: N² - N < S ≤ N² + N.
        assert!(
            n * n - n < big && big <= n * n + n,
            "{v:?}: N = {n} is not the rounded root of {big}"
        );
        let got = unit_on_grid(w).to_array();
        for i in 0..3 {
            let k = ((a[i] << 25) + n) / (2 * n);
            let want = k.min(1 << 24) as f32 / 16_777_216.0;
            let want = if w.to_array()[i] < 0.0 { -want } else { want };
            assert_eq!(got[i].to_bits(), want.to_bits(), "{v:?}: component {i}");
        }
    }
}

#[test]
fn canonical_scales_by_a_power_of_two_into_two_to_four() {
    for (v, s) in [
        ([1.0f32, 0.5, -0.25], 2.0f32),
        ([3.0, 0.0, 0.0], 1.0),
        ([0.0, -1e30, 5e29], 2f32.powi(-98)),
        ([2e-38, 0.0, 0.0], 2f32.powi(127)),
    ] {
        let (w, ok) = canonical(V3::new(v[0], v[1], v[2]));
        assert!(ok, "{v:?}");
        for (wi, vi) in w.to_array().iter().zip(v) {
            assert_eq!(wi.to_bits(), (vi * s).to_bits(), "{v:?}");
        }
    }
}

#[test]
fn canonical_rejects_zero_nan_infinite_and_all_denormal_input() {
    for v in [
        [0.0f32, -0.0, 0.0],
        [f32::NAN, 1.0, 0.0],
        [1.0, 0.0, f32::NAN],
        [f32::INFINITY, 0.0, 0.0],
        [1e-40, -1e-42, 0.0],
    ] {
        let (_, ok) = canonical(V3::new(v[0], v[1], v[2]));
        assert!(!ok, "{v:?}");
    }
}

#[test]
fn canonical_zeroes_denormal_and_negligible_components() {
    let (w, ok) = canonical(V3::new(1.0f32, -1e-40, -1e-13));
    assert!(ok);
    assert_eq!([w.x, w.y, w.z].map(f32::to_bits), [2f32.to_bits(), 0, 0]);
}

#[test]
fn length2_is_the_square_length_to_a_few_ulp() {
    let w = V3::new(2.703_125f32, -0.577_215_7, 1.398_437_5);
    let exact: f64 = w.to_array().iter().map(|&x| f64::from(x).powi(2)).sum();
    let got = f64::from(length2(w));
    assert!((got - exact).abs() <= 2.0 * f64::from(f32::EPSILON) * exact);
}

#[test]
fn snorm_ratio_rounds_to_the_nearest_code_and_keeps_the_sign() {
    let q = Quant::Snorm(8);
    // 127 · 1/3 = 42.33 → 42; 127 · 0.5 = 63.5 → 64 (ties away from zero).
    assert_eq!(snorm_ratio(q, 1.0f32, 3.0), 42.0);
    assert_eq!(snorm_ratio(q, -1.0f32, 2.0), -64.0);
    assert_eq!(snorm_ratio(q, 1.0f32, 2.0), 64.0);
    assert_eq!(snorm_ratio(q, 2.0f32, 2.0), 127.0);
    assert_eq!(snorm_ratio(q, -0.0f32, 2.0), 0.0);
}

#[test]
fn snorm_sqrt_ratio_rounds_to_the_nearest_code() {
    let q = Quant::Snorm(8);
    // 127 · 3/5 = 76.2; 127 · 1/sqrt(2) = 89.80; 127 · 4/5 = 101.6.
    assert_eq!(snorm_sqrt_ratio(q, 3.0f32, 25.0), 76.0);
    assert_eq!(snorm_sqrt_ratio(q, -1.0f32, 2.0), -90.0);
    assert_eq!(snorm_sqrt_ratio(q, 4.0f32, 25.0), 102.0);
    assert_eq!(snorm_sqrt_ratio(q, 0.0f32, 25.0), 0.0);
    assert_eq!(snorm_sqrt_ratio(q, 5.0f32, 25.0), 127.0);
}

/// Canonical-range values from a fixed LCG: deterministic, spread over [lo, hi).
fn spread(n: usize, lo: f64, hi: f64) -> impl Iterator<Item = f64> {
    let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
    (0..n).map(move |_| {
        x = x.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
        lo + (hi - lo) * ((x >> 11) as f64 / (1u64 << 53) as f64)
    })
}

#[test]
fn root_is_the_square_root_to_two_to_minus_20_under_every_allowed_root_and_quotient() {
    use unitpack::model::deviant::Dev;
    let squares = [4.0f32, 9.0, 16.0, 49.0, 63.999_996, 4.000_001, 15.999_999];
    let sample = spread(20_000, 4.0, 64.0).map(|s| s as f32);
    for (i, s) in squares.into_iter().chain(sample).enumerate() {
        let r = root(s);
        let exact = f64::from(s).sqrt();
        assert!(
            (f64::from(r) - exact).abs() <= 1.0 / f64::from(1u32 << 20),
            "{s}: {r}"
        );
        if exact.fract() == 0.0 {
            assert_eq!(f64::from(r), exact, "{s}");
        }
        same_under_div_and_sqrt(i, r, || root(Dev::new(s)).value());
    }
}

#[test]
fn settled_sum_is_the_sum_to_two_to_minus_23_whatever_contraction_does() {
    use unitpack::model::deviant::{Class, Dev, Deviation, Mode, begin_item, with};
    assert_eq!(settled_sum(0.0f32, 0.0).to_bits(), 0);
    let factors = spread(4_000, -30.0, 30.0).map(|e| 2f64.powf(e) as f32);
    let factors: Vec<f32> = factors.collect();
    for (i, w) in factors.windows(4).enumerate() {
        let (p, q) = (w[0] * w[1], w[2] * w[3 - i % 2]);
        let s = settled_sum(p, q);
        let exact = f64::from(p) + f64::from(q);
        assert!(
            (f64::from(s) - exact).abs() <= exact / f64::from(1u32 << 23),
            "{p} + {q}: {s}"
        );
        for mode in [Mode::Lowest, Mode::Highest, Mode::Seeded(i as u64)] {
            let d = with(Some(Deviation::new(Class::Fma, mode)), || {
                begin_item(i as u64);
                let dev = |x: f32| Dev::new(x);
                settled_sum(dev(w[0]) * dev(w[1]), dev(w[2]) * dev(w[3 - i % 2])).value()
            });
            assert_eq!(d.to_bits(), s.to_bits(), "{p} + {q} under {mode:?}");
        }
    }
}

#[test]
fn bisected_counts_the_boundaries_passed() {
    for q in [Quant::Unorm(1), Quant::Unorm(7), Quant::Unorm(8)] {
        let m = q.max_code();
        let half = (m + 1.0) * 0.5;
        for k in 0..=m as u32 {
            let k = k as f32;
            let c = bisected(q, half - 1.0 < k, |c: f32| one_if(c < k));
            assert_eq!(c, k, "{q:?}");
        }
    }
}

/// `f` (the same computation on the deviant type) returns `reference`'s bits under
/// every allowed quotient and root, at both ends and seeded.
fn same_under_div_and_sqrt(i: usize, reference: f32, f: impl Fn() -> f32) {
    use unitpack::model::deviant::{Class, Deviation, Mode, begin_item, with};
    for class in [Class::Sqrt, Class::Div] {
        for mode in [Mode::Lowest, Mode::Highest, Mode::Seeded(i as u64)] {
            let d = with(Some(Deviation::new(class, mode)), || {
                begin_item(i as u64);
                f()
            });
            assert_eq!(
                d.to_bits(),
                reference.to_bits(),
                "item {i} under {} {mode:?}",
                class.name()
            );
        }
    }
}

#[test]
fn fixed_ratio_is_the_floor_to_one_unit_under_every_allowed_quotient() {
    use unitpack::model::deviant::Dev;
    let pairs = spread(20_000, -1.0, 1.0).zip(spread(20_001, 0.5, 14.0).skip(1));
    for (i, (f, d)) in pairs.enumerate() {
        let (d, n) = (d as f32, (f * d) as f32);
        let n = n.clamp(-d, d);
        for bits in [21, 23] {
            let r = fixed_ratio(n, d, bits);
            let exact = (f64::from(n) / f64::from(d) * f64::from(1u32 << bits)).floor();
            assert!(
                (f64::from(r) - exact).abs() <= 1.0,
                "{n}/{d} at {bits}: {r}"
            );
            same_under_div_and_sqrt(i, r, || fixed_ratio(Dev::new(n), Dev::new(d), bits).value());
        }
    }
}

#[test]
fn fixed_root_and_root_of_are_roots_under_every_allowed_root() {
    use unitpack::model::deviant::Dev;
    let squares = [0.0f32, 1.0, 4.0, 2.0f32.powi(42), 1e-30, 3.0e12];
    let sample = spread(20_000, 0.0, 42.0).map(|e| 2f64.powf(e) as f32);
    for (i, s) in squares.into_iter().chain(sample).enumerate() {
        let exact = f64::from(s).sqrt();
        let r = fixed_root(s);
        assert!((f64::from(r) - exact.floor()).abs() <= 1.0, "{s}: {r}");
        same_under_div_and_sqrt(i, r, || fixed_root(Dev::new(s)).value());
        if s > 0.0 {
            let r = root_of(s);
            assert!(
                (f64::from(r) - exact).abs() <= exact / f64::from(1u32 << 21),
                "{s}: {r}"
            );
            same_under_div_and_sqrt(i, r, || root_of(Dev::new(s)).value());
        }
    }
}

#[test]
fn float_of_rounds_every_u32_to_nearest() {
    for x in [
        0u32,
        1,
        0xff_ffff,
        0x100_0001,
        0x100_0003,
        0x7fff_ffff,
        u32::MAX,
    ] {
        let got: f32 = float_of(x);
        // Nearest (to even on ties), as Rust's conversion does.
        assert_eq!(got.to_bits(), (x as f32).to_bits(), "{x}");
    }
}

#[test]
fn fixed_length2_is_the_square_length_to_two_to_minus_20() {
    let c = |x: f64| x as f32;
    let v: Vec<f64> = spread(30_000, -4.0, 4.0).collect();
    for t in v.chunks(3) {
        // Canonical: the largest component in [2, 4).
        let w = V3::new(c(t[0].abs().max(2.0)), c(t[1]), c(t[2]));
        let exact: f64 = w.to_array().iter().map(|&x| f64::from(x).powi(2)).sum();
        let got = f64::from(fixed_length2(w));
        assert!(
            (got - exact).abs() <= exact / f64::from(1u32 << 20),
            "{w:?}"
        );
        let xy = f64::from(w.x).powi(2) + f64::from(w.y).powi(2);
        assert!((f64::from(fixed_length2_xy(w)) - xy).abs() <= xy / f64::from(1u32 << 20));
    }
    // Exact where the components are on the fixed-point grid.
    assert_eq!(fixed_length2(V3::new(3.0f32, -2.0, 0.5)), 13.25);
}
