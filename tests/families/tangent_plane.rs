//! octangle32, octangle48 and diamond32 (and their precise variants) against their
//! definition evaluated here in f64: the normal's fields are oct's codes, the sign bit is
//! the handedness, the turn is the tangent's direction around Ong's basis of the decoded
//! normal rounded to the nearest code; the decoder returns the octahedral point and the
//! stored direction normalized. With what every frame codec promises.

use crate::frames::{self, f, frame_promises, run};
use unitpack::codecs::functions::function::Role;
use unitpack::codecs::functions::inputs::{codes, frames};

/// A spec's layout: oct bits per axis, turn bits, whether the turn is the diamond, words.
struct Layout {
    spec: &'static str,
    axis: u32,
    turn: u32,
    diamond: bool,
    words: usize,
}

const LAYOUTS: [Layout; 3] = [
    Layout {
        spec: "octangle32",
        axis: 11,
        turn: 9,
        diamond: false,
        words: 1,
    },
    Layout {
        spec: "octangle48",
        axis: 16,
        turn: 15,
        diamond: false,
        words: 2,
    },
    Layout {
        spec: "diamond32",
        axis: 11,
        turn: 9,
        diamond: true,
        words: 1,
    },
];

type D3 = [f64; 3];

fn dot(a: D3, b: D3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: D3, b: D3) -> D3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The fields of a code: oct x, oct y (signed), turn, sign.
fn fields(l: &Layout, w: &[u32]) -> (i64, i64, u32, u32) {
    let hi = if l.words == 1 { 0 } else { u64::from(w[1]) };
    let bits = u64::from(w[0]) | (hi << 32);
    let (b, k) = (l.axis, l.turn);
    let field = |at: u32, n: u32| (bits >> at) & ((1u64 << n) - 1);
    let signed = |v: u64| {
        let v = v as i64;
        if v >= 1 << (b - 1) { v - (1 << b) } else { v }
    };
    let turn_at = if l.words == 1 { 2 * b } else { 32 };
    (
        signed(field(0, b)),
        signed(field(b, b)),
        field(turn_at, k) as u32,
        field(turn_at + k, 1) as u32,
    )
}

/// The octahedral point of the normal's codes (`m` the largest), the branch (`|y| > |z|`),
/// and the unit basis `(n, b1, b2)` in f64.
fn basis(x: i64, y: i64, m: i64) -> (D3, D3, D3) {
    let (x, y) = (x.max(-m), y.max(-m));
    let z = m - x.abs() - y.abs();
    let s = |v: i64| if v >= 0 { 1 } else { -1 };
    let (x, y) = if z < 0 {
        ((m - y.abs()) * s(x), (m - x.abs()) * s(y))
    } else {
        (x, y)
    };
    let p = [x as f64, y as f64, z as f64];
    let l = dot(p, p).sqrt();
    let n = p.map(|c| c / l);
    let b1 = if y.abs() > z.abs() {
        [n[1], -n[0], 0.0]
    } else {
        [n[2], 0.0, -n[0]]
    };
    let l1 = dot(b1, b1).sqrt();
    let b1 = b1.map(|c| c / l1);
    (n, b1, cross(n, b1))
}

/// The turn of the direction `(u, v)` as a real number of codes, and the number of codes
/// around the circle.
fn turn(l: &Layout, u: f64, v: f64) -> (f64, i64) {
    if l.diamond {
        let m = f64::from((1u32 << (l.turn - 2)) - 1);
        let x = u / (u.abs() + v.abs());
        let r = m * x;
        (if v >= 0.0 { 3.0 * m - r } else { m + r }, 4 * m as i64)
    } else {
        let k = 1i64 << l.turn;
        let a = v.atan2(u) / std::f64::consts::TAU * k as f64;
        (if a < 0.0 { a + k as f64 } else { a }, k)
    }
}

/// Codes equal the definition: the normal's fields are the oct spec's codes at the same
/// size (the precise one for a `p` spec), the sign bit is set exactly where `w < 0`, and
/// the turn is the nearest code to the tangent's direction around the basis of the
/// decoded normal, or the basis's first axis (the canonical code) for a tangent without
/// a usable direction. Near a code boundary (0.02 of a code for octangle48's angle, whose
/// fixed-point arithmetic is within a few `2^-24` turns; 10^-3 otherwise) either
/// neighbour passes; every other turn must be exact.
#[test]
fn encoders_compute_the_definition() {
    for l in &LAYOUTS {
        let encode = frames::function(l.spec, Role::Encode);
        let precise = l.spec.ends_with('p');
        let oct = frames::function(
            &format!("oct{}{}", 2 * l.axis, if precise { "p" } else { "" }),
            Role::Encode,
        );
        let input = frames();
        let out = run(&encode, input);
        let normals: Vec<u32> = input.chunks(7).flat_map(|x| [x[0], x[1], x[2]]).collect();
        let oct_codes = run(&oct, &normals);
        let m = (1i64 << (l.axis - 1)) - 1;
        // The fixed-point angle is within a few 2^-24 turns of the exact one.
        let window = (0.02 * 2f64.powi(l.turn as i32 - 15)).max(1e-3);
        let (mut exact, mut near, mut canonical) = (0, 0, 0);
        for ((x, w), o) in input.chunks(7).zip(out.chunks(l.words)).zip(&oct_codes) {
            let x: Vec<f32> = x.iter().map(|&w| f(w)).collect();
            let (cx, cy, a, s) = fields(l, w);
            let mask = (1u32 << l.axis) - 1;
            let want = (*o & mask, (*o >> l.axis) & mask);
            assert_eq!(
                ((cx as u32) & mask, (cy as u32) & mask),
                want,
                "{}: normal of {x:?}",
                l.spec
            );
            assert_eq!(s, u32::from(x[6] < 0.0), "{}: sign of {x:?}", l.spec);
            let (_, b1, b2) = basis(cx, cy, m);
            let t = [x[3], x[4], x[5]].map(f64::from);
            let (u, v) = (dot(t, b1), dot(t, b2));
            let largest = t.iter().fold(0f64, |a, c| a.max(c.abs()));
            // Denormal components read as zero; an all-denormal tangent has no direction.
            let invalid =
                t.iter().any(|c| !c.is_finite()) || largest < f64::from(f32::MIN_POSITIVE);
            let degenerate = |r: f64| invalid || u.abs() + v.abs() < r * largest;
            let (r, codes) = turn(l, u, v);
            let canonical_code = if l.diamond { codes as u32 / 2 } else { 0 };
            // The threshold is 2^-13 of the largest component scaled into [2, 4):
            // between 2^-15 and 2^-14 of it unscaled.
            if degenerate(2f64.powi(-15)) {
                assert_eq!(a, canonical_code, "{}: degenerate {x:?}", l.spec);
                canonical += 1;
                continue;
            }
            if degenerate(2f64.powi(-13)) {
                continue;
            }
            let nearest = (r.round() as i64).rem_euclid(codes) as u32;
            if (r - r.floor() - 0.5).abs() < window {
                let other = ((r.round() as i64 + if r.fract() >= 0.5 { -1 } else { 1 })
                    .rem_euclid(codes)) as u32;
                assert!(a == nearest || a == other, "{}: {x:?}: {a} for {r}", l.spec);
                near += 1;
            } else {
                assert_eq!(a, nearest, "{}: turn of {x:?} ({r})", l.spec);
                exact += 1;
            }
        }
        assert!(
            exact > 250_000 && canonical > 10,
            "{}: {exact} {near} {canonical}",
            l.spec
        );
    }
}

/// The decoders return the octahedral point normalized and the stored direction around
/// its basis normalized, with the sign: within `2^-20` of that evaluated in f64 on every
/// sampled code, hostile ones included.
#[test]
fn decoders_compute_the_definition() {
    for l in LAYOUTS.iter().filter(|l| !l.spec.ends_with('p')) {
        let decode = frames::function(l.spec, Role::Decode);
        let q = decode.inputs.clone();
        let unitpack::codecs::functions::function::Inputs::Codes(q) = q else {
            panic!("{}: a packed decoder", l.spec)
        };
        let input = codes(&q, l.words);
        let out = run(&decode, &input);
        let m = (1i64 << (l.axis - 1)) - 1;
        for (w, got) in input.chunks(l.words).zip(out.chunks(7)) {
            let (cx, cy, a, s) = fields(l, w);
            let (n, b1, b2) = basis(cx, cy, m);
            let (c, sn) = if l.diamond {
                let m = f64::from((1u32 << (l.turn - 2)) - 1);
                let a = f64::from(a).min(4.0 * m);
                let x = if a >= 2.0 * m {
                    (3.0 * m - a) / m
                } else {
                    (a - m) / m
                };
                let y = (1.0 - x.abs()) * if a >= 2.0 * m { 1.0 } else { -1.0 };
                let l = (x * x + y * y).sqrt();
                (x / l, y / l)
            } else {
                let theta = f64::from(a) / f64::from(1u32 << l.turn) * std::f64::consts::TAU;
                (theta.cos(), theta.sin())
            };
            let t: Vec<f64> = (0..3).map(|i| c * b1[i] + sn * b2[i]).collect();
            let want = [
                n[0],
                n[1],
                n[2],
                t[0],
                t[1],
                t[2],
                if s == 1 { -1.0 } else { 1.0 },
            ];
            for (g, w2) in got.iter().zip(want) {
                assert!(
                    (f64::from(f(*g)) - w2).abs() < 2f64.powi(-20),
                    "{}: code {w:x?}: {:?} vs {want:?}",
                    l.spec,
                    got.iter().map(|&g| f(g)).collect::<Vec<_>>()
                );
            }
        }
    }
}

#[test]
fn frames_keep_their_promises() {
    for l in &LAYOUTS {
        frame_promises(l.spec, 4e-6);
    }
}
