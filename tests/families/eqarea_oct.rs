//! `eqarea_oct` is Clarberg's equal-area octahedral map: its float forms agree with the
//! map as pbrt-v4 writes it (`EqualAreaSphereToSquare`, `EqualAreaSquareToSphere`),
//! evaluated here in f64 with the exact arctangent, sine and cosine; its packed codes
//! are that map's point rounded to the nearest code; and it keeps area, which `oct` does
//! not.

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};
use unitpack::api::{CpuCodec, EqAreaOct};
use unitpack::codecs::Codec;
use unitpack::codecs::octahedral::oct::oct_params;
use unitpack::measure::figures::VECTOR_SEED;
use unitpack::model::{V2, V3};
use unitpack::support::sampling::random_unit_vectors;

/// Sphere → square `[-1, 1]²`, pbrt-v4's `EqualAreaSphereToSquare` (whose `[0, 1]²`
/// point is this one times ½ plus ½), on the direction normalized in f64.
fn sphere_to_square(v: [f32; 3]) -> [f64; 2] {
    let d = v.map(f64::from);
    let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    let (x, y, z) = ((d[0] / len).abs(), (d[1] / len).abs(), (d[2] / len).abs());
    let r = (1.0 - z).max(0.0).sqrt();
    let phi = y.atan2(x) / FRAC_PI_2;
    let (mut u, mut w) = (r - phi * r, phi * r);
    if d[2] < 0.0 {
        (u, w) = (1.0 - w, 1.0 - u);
    }
    [u.copysign(d[0]), w.copysign(d[1])]
}

/// Square `[-1, 1]²` → sphere, pbrt-v4's `EqualAreaSquareToSphere`.
fn square_to_sphere(p: [f64; 2]) -> [f64; 3] {
    let (u, v) = (p[0], p[1]);
    let (up, vp) = (u.abs(), v.abs());
    let signed_distance = 1.0 - (up + vp);
    let r = 1.0 - signed_distance.abs();
    let phi = if r == 0.0 { 1.0 } else { (vp - up) / r + 1.0 } * FRAC_PI_4;
    let z = (1.0 - r * r).copysign(signed_distance);
    let s = r * (2.0 - r * r).max(0.0).sqrt();
    [phi.cos().copysign(u) * s, phi.sin().copysign(v) * s, z]
}

#[test]
fn float_forms_are_clarbergs_map() {
    let c = EqAreaOct::new(32).unwrap();
    let mut worst = [0f64; 2];
    for v in random_unit_vectors(VECTOR_SEED, 1 << 16, false) {
        let p = c.params(V3::from_array(v));
        let want = sphere_to_square(v);
        for (got, want) in [p.x, p.y].iter().zip(want) {
            worst[0] = worst[0].max((f64::from(*got) - want).abs());
        }
        // The decoder at the model's own point, against the reference's inverse there.
        let d = c.direction(p).to_array();
        let want = square_to_sphere([f64::from(p.x), f64::from(p.y)]);
        for (got, want) in d.iter().zip(want) {
            worst[1] = worst[1].max((f64::from(*got) - want).abs());
        }
    }
    // The model's arctangent is within 2e-7 half turns (4e-7 of the quadrant's
    // fraction), its sine and cosine within 2.5e-7; the rest is f32 rounding.
    assert!(worst[0] < 1e-6, "encode_float: {:e}", worst[0]);
    assert!(worst[1] < 2e-6, "decode_float: {:e}", worst[1]);
    // The axes, the poles and the equator's diagonals land on the square's landmarks.
    for (v, want) in [
        ([0.0f32, 0.0, 1.0], [0.0f32, 0.0]),
        ([0.0, 0.0, -1.0], [1.0, 1.0]),
        ([1.0, 0.0, 0.0], [1.0, 0.0]),
        ([0.0, -1.0, 0.0], [0.0, -1.0]),
        ([-1.0, -1.0, 0.0], [-0.5, -0.5]),
    ] {
        let p = c.params(V3::from_array(v));
        assert!(
            (p.x - want[0]).abs() < 1e-6 && (p.y - want[1]).abs() < 1e-6,
            "{v:?} → {p:?}"
        );
        let d = c.direction(V2::new(want[0], want[1])).to_array();
        let len = v.iter().map(|x| x * x).sum::<f32>().sqrt();
        for (got, want) in d.iter().zip(v.map(|x| x / len)) {
            assert!((got - want).abs() < 1e-6, "{v:?} → {d:?}");
        }
    }
}

/// The packed code is the reference point rounded to the nearest snorm code, wherever
/// that point is not within the model's few units of 2^-21 of a half (the fixed-point
/// arctangent that decides the codes).
#[test]
fn packed_codes_round_the_maps_point() {
    for bits in [16, 24, 32] {
        let c = EqAreaOct::new(bits).unwrap().fast();
        let half = bits / 2;
        let m = f64::from((1u32 << (half - 1)) - 1);
        let window = 2e-6 * m + 1e-9;
        let (mut compared, mut fields) = (0, 0);
        for v in random_unit_vectors(VECTOR_SEED, 1 << 16, false) {
            let code = c.encode(v);
            let p = sphere_to_square(v);
            for (i, x) in p.iter().enumerate() {
                fields += 1;
                let scaled = x * m;
                if ((scaled - scaled.floor()) - 0.5).abs() < window {
                    continue;
                }
                compared += 1;
                let field = (code >> (i as u32 * half)) & ((1 << half) - 1);
                let want = (scaled.round() as i64 as u32) & ((1 << half) - 1);
                assert_eq!(field, want, "eqarea_oct{bits} {v:?}: field {i} of {code:x}");
            }
        }
        assert!(
            compared > fields * 4 / 5,
            "eqarea_oct{bits}: {compared} of {fields}"
        );
    }
}

/// Uniform directions fill the square uniformly (each of 8×8 cells within 20 % of its
/// share, six standard deviations), where the octahedral projection crowds them.
#[test]
fn uniform_directions_fill_the_square_evenly() {
    let c = EqAreaOct::new(32).unwrap();
    let n = 1 << 16;
    let cells = |f: &dyn Fn([f32; 3]) -> [f32; 2]| {
        let mut count = [0usize; 64];
        for v in random_unit_vectors(VECTOR_SEED, n, false) {
            let p = f(v);
            let cell = |x: f32| (((x + 1.0) * 4.0) as usize).min(7);
            count[cell(p[0]) + 8 * cell(p[1])] += 1;
        }
        let share = n / 64;
        count
            .iter()
            .map(|&k| (k as f64 / share as f64 - 1.0).abs())
            .fold(0.0, f64::max)
    };
    let eqarea = cells(&|v| {
        let p = c.params(V3::from_array(v));
        [p.x, p.y]
    });
    assert!(eqarea < 0.2, "eqarea_oct: a cell {eqarea:.3} off its share");
    let oct = cells(&|v| {
        let p = oct_params(V3::from_array(v));
        [p.x, p.y]
    });
    assert!(oct > 0.5, "oct: every cell within {oct:.3} of its share");
}
