//! `eac` against its definition evaluated in f64 with the exact arctangent and tangent:
//! the face by the major axis, each minor coordinate's `atan(a)/(π/4)` rounded to one of
//! `N` levels, the index `face·N² + t·N + s`; and back, every code's point. Its packed
//! codes are those of the definition except where the level is within the encoder's
//! arctangent error (a fixed-point series) of a rounding tie, and it beats the plain and
//! the warped cube maps of its size.

use std::f64::consts::FRAC_PI_4;
use unitpack::api::{Batch, Eac};
use unitpack::measure::figures::VECTOR_SEED;
use unitpack::support::sampling::random_unit_vectors;

/// Face, then the two coordinates' numerators in cyclic order after the major axis,
/// and the major component's magnitude: the definition's choice, ties to z, then y.
fn face_of(v: [f64; 3]) -> (u32, f64, f64, f64) {
    let a = v.map(f64::abs);
    let axis = if a[2] >= a[0] && a[2] >= a[1] {
        2
    } else if a[1] >= a[0] {
        1
    } else {
        0
    };
    let face = 2 * axis as u32 + u32::from(v[axis] < 0.0);
    (face, v[(axis + 1) % 3], v[(axis + 2) % 3], a[axis])
}

/// The level `(atan(a)/(π/4) + 1)/2·(N - 1)` before rounding.
fn level(n: u32, minor: f64, major: f64) -> f64 {
    ((minor / major).atan() / FRAC_PI_4 + 1.0) / 2.0 * f64::from(n - 1)
}

/// The unit vector of index `i` by the definition.
fn point(n: u32, i: u32) -> [f64; 3] {
    let per_face = u64::from(n) * u64::from(n);
    let i = u64::from(i).min(6 * per_face - 1);
    let (face, r) = ((i / per_face) as usize, i % per_face);
    let (t, s) = (r / u64::from(n), r % u64::from(n));
    let tan = |c: u64| ((2.0 * c as f64 / f64::from(n - 1) - 1.0) * FRAC_PI_4).tan();
    let d = [tan(s), tan(t), 1.0];
    let len = (d[0] * d[0] + d[1] * d[1] + 1.0).sqrt();
    let sign = if face % 2 == 1 { -1.0 } else { 1.0 };
    let axis = face / 2;
    let mut v = [0.0; 3];
    v[axis] = sign / len;
    v[(axis + 1) % 3] = d[0] / len;
    v[(axis + 2) % 3] = d[1] / len;
    v
}

fn encode(spec: &str, input: &[[f32; 3]]) -> Vec<u32> {
    let mut out = vec![0; input.len()];
    Batch::new(spec).unwrap().encode(input, &mut out);
    out
}

fn decode(spec: &str, codes: &[u32]) -> Vec<[f32; 3]> {
    let mut out = vec![[0.0; 3]; codes.len()];
    Batch::new(spec).unwrap().decode(codes, &mut out);
    out
}

#[test]
fn the_side_is_the_largest_that_six_faces_fit() {
    for (bits, n, points) in [
        (16, 104, 64_896),
        (24, 1672, 16_773_504),
        (32, 26_754, 4_294_659_096),
    ] {
        let c = Eac::new(bits).unwrap();
        assert_eq!((c.side(), c.points()), (n, points), "eac{bits}");
        assert!(6 * u64::from(n + 1).pow(2) > 1 << bits);
    }
    assert!(Eac::new(20).is_err());
}

#[test]
fn encoders_give_the_definitions_codes() {
    let mut input = random_unit_vectors(VECTOR_SEED, 1 << 16, false);
    // The axes, the faces' diagonals and edges, where the face and the level change.
    for x in [-1.0f32, -0.5, 0.0, 0.5, 1.0] {
        for y in [-1.0f32, 0.0, 1.0, 0.25] {
            for z in [-1.0f32, 0.0, 1.0] {
                input.push([x, y, z]);
            }
        }
    }
    for bits in [16, 24, 32] {
        let spec = format!("eac{bits}");
        let n = Eac::new(bits).unwrap().side();
        let got = encode(&spec, &input);
        let mut near_ties = 0;
        for (v, &code) in input.iter().zip(&got) {
            let d = v.map(f64::from);
            let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            let d = if len == 0.0 {
                [0.0, 0.0, 1.0]
            } else {
                d.map(|x| x / len)
            };
            let (face, s, t, major) = face_of(d);
            let levels = [level(n, s, major), level(n, t, major)];
            let index = |ls: f64, lt: f64| (face * n + lt as u32) * n + ls as u32;
            let want = index(levels[0].round_ties_even(), levels[1].round_ties_even());
            if code == want {
                continue;
            }
            // Near a tie the encoder's arctangent may round the other way: it is within
            // 2^-21 half turns of the exact one, times 4 onto `[-1, 1]`, which is
            // `2^-20·(N - 1)` levels.
            let tolerance = f64::from(n - 1) / f64::from(1 << 20);
            let choices = levels.map(|l| {
                if (l - l.floor() - 0.5).abs() <= tolerance {
                    vec![l.floor(), l.ceil()]
                } else {
                    vec![l.round_ties_even()]
                }
            });
            let allowed = choices[0]
                .iter()
                .any(|&ls| choices[1].iter().any(|&lt| index(ls, lt) == code));
            assert!(
                allowed,
                "{spec} {v:?}: {code:#010x}, the definition {want:#010x} (levels {levels:?})"
            );
            near_ties += 1;
        }
        // Each coordinate is near a tie on about a share `2·tolerance` of the inputs.
        let expected = 4.0 * f64::from(n - 1) / f64::from(1 << 20) * input.len() as f64;
        assert!(
            f64::from(near_ties) <= expected + 16.0,
            "{spec}: {near_ties} near-tie codes of {}",
            input.len()
        );
    }
}

#[test]
fn decoders_give_the_definitions_points() {
    for bits in [16, 24, 32] {
        let spec = format!("eac{bits}");
        let c = Eac::new(bits).unwrap();
        let n = c.side();
        let per_face = n * n;
        // Every code at 16 bits; elsewhere the faces' and rows' first and last codes,
        // the unused codes and a seeded sample.
        let mut codes: Vec<u32> = if bits == 16 {
            (0..1 << 16).collect()
        } else {
            let mut codes = vec![u32::MAX, (c.points() - 1) as u32];
            for face in 0..6 {
                for row in [0, 1, n / 2, n - 1] {
                    let first = face * per_face + row * n;
                    codes.extend([first, first + 1, first + n - 1]);
                }
            }
            if bits < 32 {
                codes.push(1 << bits);
                codes.push((1 << bits) - 1);
            }
            let mut x = 0x9e37_79b9u32;
            codes.extend((0..1 << 16).map(|_| {
                x ^= x << 13;
                x ^= x >> 17;
                x ^= x << 5;
                if bits == 32 { x } else { x >> (32 - bits) }
            }));
            codes
        };
        codes.sort_unstable();
        let got = decode(&spec, &codes);
        for (&code, g) in codes.iter().zip(&got) {
            // The decoder reads the code's low `bits` bits, as every spec does.
            let want = point(n, (u64::from(code) & ((1u64 << bits) - 1)) as u32);
            let worst = (0..3)
                .map(|k| (f64::from(g[k]) - want[k]).abs())
                .fold(0.0, f64::max);
            assert!(
                worst < 1e-6,
                "{spec} {code:#010x}: {g:?}, the definition {want:?} ({worst:e} apart)"
            );
        }
    }
}

#[test]
fn a_points_code_is_its_own_inside_the_faces() {
    // At level 0 or N - 1 a point lies on a cube edge, which the tie rule may give to the
    // neighbouring face; every other point encodes to its own index.
    for bits in [16, 24] {
        let spec = format!("eac{bits}");
        let n = Eac::new(bits).unwrap().side();
        let step = if bits == 16 { 1 } else { 97 };
        let codes: Vec<u32> = (0..6 * n * n)
            .step_by(step)
            .filter(|i| {
                let r = i % (n * n);
                let (t, s) = (r / n, r % n);
                s != 0 && t != 0 && s != n - 1 && t != n - 1
            })
            .collect();
        let back = encode(&spec, &decode(&spec, &codes));
        for (code, again) in codes.iter().zip(&back) {
            assert_eq!(
                code, again,
                "{spec}: {code:#010x} encodes back as {again:#010x}"
            );
        }
    }
}

#[test]
fn at_16_bits_it_beats_both_cube_maps() {
    let input = random_unit_vectors(VECTOR_SEED, 1 << 16, false);
    let errors = |spec: &str| {
        let out = decode(spec, &encode(spec, &input));
        let angles: Vec<f64> = input
            .iter()
            .zip(&out)
            .map(|(a, b)| {
                let dot: f64 = (0..3).map(|k| f64::from(a[k]) * f64::from(b[k])).sum();
                dot.clamp(-1.0, 1.0).acos().to_degrees()
            })
            .collect();
        let mean = angles.iter().sum::<f64>() / angles.len() as f64;
        (mean, angles.iter().cloned().fold(0.0, f64::max))
    };
    let eac = errors("eac16");
    for other in ["cube16", "warpedcube16"] {
        let (mean, max) = errors(other);
        assert!(
            eac.0 < 0.85 * mean && eac.1 < 0.85 * max,
            "eac16 {eac:?} against {other} ({mean}, {max})"
        );
    }
}
