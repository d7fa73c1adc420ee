//! godot_axis_angle against Godot: codes equal to a port of Godot's importer on every
//! frame it defines among the seeded and edge frames, decoders within a stated bound of
//! its vertex shader's decode; and what every frame codec promises: the handedness
//! survives, degenerate input gives the stated frame, decoded frames are orthonormal to a
//! stated precision.

use crate::frames::{self, f, frame_promises, run};
use crate::oracles::godot;
use unitpack::codecs::functions::function::{Function, Role};
use unitpack::codecs::functions::inputs::{codes, frames};
use unitpack::codecs::toolkit::quant::Quant;

fn function(role: Role) -> Function {
    frames::function("godot_axis_angle", role)
}

/// The three stored fields of a code's two words.
fn fields(w: &[u32]) -> [u16; 3] {
    [w[0] as u16, (w[0] >> 16) as u16, w[1] as u16]
}

/// Whether the input policy leaves the frame as Godot receives it: finite, the normal's
/// squared length within `[2^-20, 2^20]`, and Godot's own bitangent
/// `normalize(n) × normalize(t)` of squared length at least `2^-60`.
fn godot_defines(x: &[f32]) -> bool {
    let (n, t) = ([x[0], x[1], x[2]], [x[3], x[4], x[5]]);
    let l2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    let b = godot::cross(godot::normalized(n), godot::normalized(t));
    let b2 = b[0] * b[0] + b[1] * b[1] + b[2] * b[2];
    x.iter().all(|v| v.is_finite())
        && (2f32.powi(-20)..=2f32.powi(20)).contains(&l2)
        && (2f32.powi(-60)..=f32::MAX).contains(&b2)
}

#[test]
fn encoder_writes_godots_compressed_attributes() {
    let encode = function(Role::Encode);
    let input = frames();
    let out = run(&encode, input);
    let mut compared = 0;
    for (x, w) in input.chunks(7).zip(out.chunks(2)) {
        let x: Vec<f32> = x.iter().map(|&w| f(w)).collect();
        assert_eq!(
            w[1] >> 16,
            0,
            "the second word's high half is unused: {x:?}"
        );
        if !godot_defines(&x) {
            continue;
        }
        let want = godot::encode([x[0], x[1], x[2]], [x[3], x[4], x[5]], x[6]);
        assert_eq!(fields(w), want, "frame {x:?}");
        compared += 1;
    }
    assert!(compared > 250_000, "{compared} frames compared");
}

/// The model's decoders against the shader's decode evaluated exactly (f64): every
/// component within `2^-20`, the sign equal, on every code of a sampled grid.
#[test]
fn decoders_are_godots_axis_angle_to_tbn() {
    let decode = function(Role::Decode);
    let decode_float = function(Role::DecodeFloat);
    let q = [Quant::Unorm(16); 3];
    let input = codes(&q, 2);
    let out = run(&decode, &input);
    let fetched: Vec<u32> = input
        .chunks(2)
        .flat_map(|c| fields(c).map(|v| (f32::from(v) * (1.0 / 65535.0)).to_bits()))
        .collect();
    let from_floats = run(&decode_float, &fetched);
    let bound = 2f64.powi(-20);
    let mut worst = 0f64;
    for ((code, got), floats) in input
        .chunks(2)
        .zip(out.chunks(7))
        .zip(from_floats.chunks(7))
    {
        let (n, t, s) = godot::decode(fields(code));
        let want = [n[0], n[1], n[2], t[0], t[1], t[2]];
        for (g, w) in got.iter().zip(want) {
            worst = worst.max((f64::from(f(*g)) - w).abs());
        }
        assert_eq!(f64::from(f(got[6])), s, "sign of {:?}", fields(code));
        assert_eq!(got, floats, "decode and decode_float of {:?}", fields(code));
    }
    assert!(worst <= bound, "largest difference {worst:e} > 2^-20");
    assert!(input.len() / 2 > 1_000_000, "{}", input.len() / 2);
}

/// The frame codecs' promises ([`crate::frames::frame_promises`]), the decoded frame unit
/// and orthogonal within `2^-20`.
#[test]
fn handedness_survives_and_frames_are_orthonormal() {
    frame_promises("godot_axis_angle", 2f32.powi(-20));
}
