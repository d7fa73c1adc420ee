//! qtangent32 (smallest three) against its definition evaluated here in f64: the frame
//! made orthonormal (Gram–Schmidt), the unit quaternion of the rotation with columns
//! `(t, n × t, n)`, its largest component dropped and the other three, times √2, rounded
//! to the nearest snorm codes; the decoder restores the dropped component and returns
//! the rotation's columns. With what every frame codec promises.

use crate::frames::{self, f, frame_promises, run};
use unitpack::codecs::functions::function::{Inputs, Role};
use unitpack::codecs::functions::inputs::{codes, frames};

type D3 = [f64; 3];

/// The kept components' largest codes: snorm10, snorm10, snorm9.
const M: [f64; 3] = [511.0, 511.0, 255.0];

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

fn unit(v: D3) -> D3 {
    let l = dot(v, v).sqrt();
    v.map(|c| c / l)
}

/// The fields of a code: the three kept codes (signed), the dropped index, the sign.
fn fields(w: u32) -> ([i64; 3], usize, u32) {
    let signed = |at: u32, bits: u32| {
        let v = i64::from((w >> at) & ((1 << bits) - 1));
        if v >= 1 << (bits - 1) {
            v - (1 << bits)
        } else {
            v
        }
    };
    (
        [signed(0, 10), signed(10, 10), signed(20, 9)],
        ((w >> 29) & 3) as usize,
        w >> 31,
    )
}

/// A vector's components with denormals read as zero, and whether it has a direction
/// (finite, not all zero).
fn read(v: [f32; 3]) -> (D3, bool) {
    let d = v.map(|c| {
        if c.abs() < f32::MIN_POSITIVE {
            0.0
        } else {
            f64::from(c)
        }
    });
    let ok = d.iter().all(|c| c.is_finite()) && d.iter().any(|&c| c != 0.0);
    (d, ok)
}

/// Codes equal the definition: the sign bit is set exactly where `w < 0`; the dropped
/// index is that of the largest `q²` (either of two within `10^-5` of each other); each
/// kept field is the nearest code to `√2·q_j·M` for the quaternion whose dropped
/// component is positive, either neighbour passing within 0.01 of a code boundary (the
/// fixed-point frame is within a few `2^-22` of the exact one). A tangent without a
/// direction off the normal (below `2^-15` of its largest component) is Ong's first axis
/// of the normal; between `2^-15` and `2^-13` either may be taken, and is not checked.
#[test]
fn encoders_compute_the_definition() {
    let encode = frames::function("qtangent32", Role::Encode);
    let input = frames();
    let out = run(&encode, input);
    let (mut exact, mut near, mut canonical) = (0, 0, 0);
    for (x, &w) in input.chunks(7).zip(&out) {
        let x: Vec<f32> = x.iter().map(|&w| f(w)).collect();
        let (kept, index, sign) = fields(w);
        assert_eq!(sign, u32::from(x[6] < 0.0), "sign of {x:?}");
        let (n, ok) = read([x[0], x[1], x[2]]);
        let n = if ok { unit(n) } else { [0.0, 0.0, 1.0] };
        let (t, ok) = read([x[3], x[4], x[5]]);
        let largest = t.iter().fold(0f64, |a, c| a.max(c.abs()));
        let along = dot(t, n);
        let g = [0, 1, 2].map(|i| t[i] - along * n[i]);
        let off = g.iter().map(|c| c.abs()).sum::<f64>();
        let degenerate = |r: f64| !ok || off < r * largest;
        let g = if degenerate(2f64.powi(-15)) {
            canonical += 1;
            if n[1].abs() > n[2].abs() {
                [n[1], -n[0], 0.0]
            } else {
                [n[2], 0.0, -n[0]]
            }
        } else if degenerate(2f64.powi(-13)) {
            continue;
        } else {
            g
        };
        let t = unit(g);
        let b = cross(n, t);
        let squares = [
            1.0 + t[0] - b[1] - n[2],
            1.0 - t[0] + b[1] - n[2],
            1.0 - t[0] - b[1] + n[2],
            1.0 + t[0] + b[1] + n[2],
        ];
        let most = squares.iter().cloned().fold(f64::MIN, f64::max);
        assert!(
            squares[index] >= most - 1e-5,
            "index of {x:?}: {index} for {squares:?}"
        );
        let (xy, xz, yz) = (t[1] + b[0], t[2] + n[0], b[2] + n[1]);
        let (wx, wy, wz) = (b[2] - n[1], n[0] - t[2], t[1] - b[0]);
        let products = [[xy, xz, wx], [xy, yz, wy], [xz, yz, wz], [wx, wy, wz]][index];
        for j in 0..3 {
            let r = M[j] * products[j] / (2.0 * squares[index]).sqrt();
            let r = r.clamp(-M[j], M[j]);
            let nearest = r.round() as i64;
            if (r.abs() - r.abs().floor() - 0.5).abs() < 0.01 {
                let step = if r.abs().fract() >= 0.5 { -1 } else { 1 };
                let other = nearest + step * r.signum() as i64;
                assert!(
                    kept[j] == nearest || kept[j] == other,
                    "field {j} of {x:?}: {} for {r}",
                    kept[j]
                );
                near += 1;
            } else {
                assert_eq!(kept[j], nearest, "field {j} of {x:?}: {r}");
                exact += 1;
            }
        }
    }
    assert!(
        exact > 700_000 && canonical > 10,
        "{exact} {near} {canonical}"
    );
}

/// The decoder returns the rotation's columns `n` and `t` of the quaternion whose kept
/// components are `max(c, -M)/(M·√2)` and whose dropped one is `√max(1 - Σ kept², ¼)`,
/// with the sign: within `2^-20` of that evaluated in f64 on every sampled code, hostile
/// ones included.
#[test]
fn decoders_compute_the_definition() {
    let decode = frames::function("qtangent32", Role::Decode);
    let Inputs::Codes(q) = decode.inputs.clone() else {
        panic!("a packed decoder")
    };
    let input = codes(&q, 1);
    let out = run(&decode, &input);
    for (&w, got) in input.iter().zip(out.chunks(7)) {
        let (kept, index, sign) = fields(w);
        let v = [0, 1, 2].map(|j| (kept[j] as f64).max(-M[j]) / (M[j] * 2f64.sqrt()));
        let dropped = (1.0 - dot(v, v)).max(0.25).sqrt();
        let mut q = [0.0; 4];
        let mut rest = v.iter();
        for (i, c) in q.iter_mut().enumerate() {
            *c = if i == index {
                dropped
            } else {
                *rest.next().unwrap()
            };
        }
        let [x, y, z, qw] = q;
        let want = [
            2.0 * (x * z + y * qw),
            2.0 * (y * z - x * qw),
            1.0 - 2.0 * (x * x + y * y),
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y + z * qw),
            2.0 * (x * z - y * qw),
            if sign == 1 { -1.0 } else { 1.0 },
        ];
        for (g, w2) in got.iter().zip(want) {
            assert!(
                (f64::from(f(*g)) - w2).abs() < 2f64.powi(-20),
                "code {w:#x}: {:?} vs {want:?}",
                got.iter().map(|&g| f(g)).collect::<Vec<_>>()
            );
        }
    }
}

#[test]
fn frames_keep_their_promises() {
    frame_promises("qtangent32", 4e-6);
}
