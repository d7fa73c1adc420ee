//! qtangent64 against Filament: codes equal to a port of Filament's encoder on every
//! frame it defines among the seeded and edge frames, decoders equal to its shader
//! decode; and what every frame codec promises: the handedness survives, degenerate input
//! gives the stated frame, decoded frames are orthonormal to a stated precision.

use crate::frames::{self, f, frame_promises, run};
use crate::oracles::filament;
use unitpack::codecs::functions::function::{Function, Role};
use unitpack::codecs::functions::inputs::{codes, frames};
use unitpack::codecs::toolkit::quant::Quant;

fn function(role: Role) -> Function {
    frames::function("qtangent64", role)
}

/// The four stored components of a code's two words.
fn components(w: &[u32]) -> [i16; 4] {
    [
        w[0] as i16,
        (w[0] >> 16) as i16,
        w[1] as i16,
        (w[1] >> 16) as i16,
    ]
}

/// Whether the input policy leaves the frame as Filament receives it: finite, `w` neither
/// 0 nor NaN, the normal's squared length within `[2^-20, 2^20]`, and Filament's own
/// orthogonalised tangent of squared length at least `2^-60`.
fn filament_defines(x: &[f32]) -> bool {
    let (n, t, w) = ([x[0], x[1], x[2]], [x[3], x[4], x[5]], x[6]);
    let l2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    let c = |u: [f32; 3], v: [f32; 3]| {
        [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ]
    };
    let b = if w > 0.0 { c(t, n) } else { c(n, t) };
    let tp = if w > 0.0 { c(n, b) } else { c(b, n) };
    let tl2 = tp[0] * tp[0] + tp[1] * tp[1] + tp[2] * tp[2];
    x.iter().all(|v| v.is_finite())
        && w != 0.0
        && (2f32.powi(-20)..=2f32.powi(20)).contains(&l2)
        && (2f32.powi(-60)..=f32::MAX).contains(&tl2)
}

#[test]
fn encoder_writes_filaments_short4() {
    let encode = function(Role::Encode);
    let input = frames();
    let out = run(&encode, input);
    let mut compared = 0;
    for (x, w) in input.chunks(7).zip(out.chunks(2)) {
        let x: Vec<f32> = x.iter().map(|&w| f(w)).collect();
        if !filament_defines(&x) {
            continue;
        }
        let want = filament::encode([x[0], x[1], x[2]], [x[3], x[4], x[5]], x[6]);
        assert_eq!(components(w), want, "frame {x:?}");
        compared += 1;
    }
    assert!(compared > 250_000, "{compared} frames compared");
}

#[test]
fn decoders_are_filaments_to_tangent_frame() {
    let decode = function(Role::Decode);
    let decode_float = function(Role::DecodeFloat);
    let q = [Quant::Snorm(16); 4];
    let input = codes(&q, 2);
    let out = run(&decode, &input);
    let mut compared = 0;
    for (code, got) in input.chunks(2).zip(out.chunks(7)) {
        let c = components(code);
        // Filament's fetch is `c·(1/32767)` unclamped; a -32768 (which packSnorm16 never
        // writes) is read as -1 by a snorm fetch and by the model.
        if c.contains(&i16::MIN) {
            continue;
        }
        let (n, t, s) = filament::to_tangent_frame(c.map(filament::fetch));
        let want = [n[0], n[1], n[2], t[0], t[1], t[2], s];
        // Filament adds literal zeros, which the model leaves out: only a zero's sign may
        // differ.
        for (g, w) in got.iter().zip(want) {
            assert!(
                f(*g) == w,
                "code {c:?}: {:?} against {want:?}",
                got.iter().map(|&g| f(g)).collect::<Vec<_>>()
            );
        }
        compared += 1;
    }
    assert!(compared > 1_000_000, "{compared}");
    // The float form on the fetched values, likewise.
    let fetched: Vec<u32> = [[0i16, 0, 0, 1], [12345, -32767, 77, -3], [-1, 2, -30000, 9]]
        .iter()
        .flat_map(|c| c.map(|v| filament::fetch(v).to_bits()))
        .collect();
    let got = run(&decode_float, &fetched);
    for (q, g) in fetched.chunks(4).zip(got.chunks(7)) {
        let (n, t, s) = filament::to_tangent_frame([f(q[0]), f(q[1]), f(q[2]), f(q[3])]);
        let want = [n[0], n[1], n[2], t[0], t[1], t[2], s];
        assert!(g.iter().zip(want).all(|(g, w)| f(*g) == w), "{q:?}");
    }
}

/// The frame codecs' promises ([`crate::frames::frame_promises`]), the decoded frame unit
/// and orthogonal within `4·2^-15`.
#[test]
fn handedness_survives_and_frames_are_orthonormal() {
    frame_promises("qtangent64", 4.0 / 32768.0);
}
