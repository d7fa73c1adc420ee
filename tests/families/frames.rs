//! What every tangent-frame codec promises, checked for each (`qtangent`, `godot`, `octangle`, `diamond`): the
//! handedness survives exactly, decoded frames are unit and orthogonal to the spec's
//! stated precision, and degenerate input decodes to the stated frame. With the helpers
//! the frame families' tests share.

use unitpack::codecs::Spec;
use unitpack::codecs::functions::function::{Function, Role};
use unitpack::codecs::functions::inputs::frames;

/// The `role` function of `spec`.
pub fn function(spec: &str, role: Role) -> Function {
    let spec: Spec = spec.parse().unwrap();
    spec.emitted()
        .functions
        .iter()
        .find(|f| f.role == role)
        .cloned()
        .unwrap()
}

/// `f` over every item of `input`.
pub fn run(f: &Function, input: &[u32]) -> Vec<u32> {
    let mut out = vec![0u32; input.len() / f.in_words * f.out_words];
    (f.eval)(input, &mut out);
    out
}

pub fn f(w: u32) -> f32 {
    f32::from_bits(w)
}

/// The decoded sign is the input's handedness (-1 for `w < 0`, else +1) on every seeded
/// and edge frame; the decoded frame is unit and orthogonal within `tol`; zero, NaN and
/// denormal normals decode to +Z, and a zero, NaN or parallel tangent to the canonical
/// tangent, +X for +Z (Duff et al.: (1 + s·x²·a, s·x·y·a, -s·x)); `decode_tbn` returns
/// the same decode's columns `t`, `cross(n, t)·sign` and `n`.
pub fn frame_promises(spec: &str, tol: f32) {
    let encode = function(spec, Role::Encode);
    let decode = function(spec, Role::Decode);
    let input = frames();
    let decoded = run(&decode, &run(&encode, input));
    for (x, d) in input.chunks(7).zip(decoded.chunks(7)) {
        let d: Vec<f32> = d.iter().map(|&w| f(w)).collect();
        let w = f(x[6]);
        let want = if w < 0.0 { -1.0 } else { 1.0 };
        assert_eq!(
            d[6],
            want,
            "{spec}: handedness of {:?}",
            x.iter().map(|&w| f(w)).collect::<Vec<_>>()
        );
        let (n, t) = ([d[0], d[1], d[2]], [d[3], d[4], d[5]]);
        let dot = |a: [f32; 3], b: [f32; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        assert!((dot(n, n).sqrt() - 1.0).abs() < tol, "{spec}: |n| of {d:?}");
        assert!((dot(t, t).sqrt() - 1.0).abs() < tol, "{spec}: |t| of {d:?}");
        assert!(dot(n, t).abs() < tol, "{spec}: n·t of {d:?}");
    }
    // The TBN decoder: the columns t, cross(n, t)·sign and n of the same decode, bit for
    // bit (the cross product as the model writes it, lane by lane, in f32).
    let tbn = spec
        .parse::<Spec>()
        .unwrap()
        .emitted()
        .functions
        .iter()
        .find(|f| f.name == "decode_tbn")
        .cloned()
        .unwrap_or_else(|| panic!("{spec}: a decode_tbn"));
    let codes = run(&encode, input);
    let (frames, columns) = (run(&decode, &codes), run(&tbn, &codes));
    for (d, c) in frames.chunks(7).zip(columns.chunks(9)) {
        let d: Vec<f32> = d.iter().map(|&w| f(w)).collect();
        let (n, t, w) = ([d[0], d[1], d[2]], [d[3], d[4], d[5]], d[6]);
        let b = [
            (n[1] * t[2] - n[2] * t[1]) * w,
            (n[2] * t[0] - n[0] * t[2]) * w,
            (n[0] * t[1] - n[1] * t[0]) * w,
        ];
        let want: Vec<u32> = t.iter().chain(&b).chain(&n).map(|v| v.to_bits()).collect();
        assert_eq!(c, &want[..], "{spec}: decode_tbn of {d:?}");
    }
    let degenerate: [[f32; 7]; 4] = [
        [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [f32::NAN, 0.0, 1.0, f32::NAN, 1.0, 0.0, f32::NAN],
        [1e-45, 0.0, 0.0, 0.0, 0.0, 5.0, 1.0],
        [0.0, 0.0, 2.0, 0.0, 0.0, -1.0, -0.0],
    ];
    let input: Vec<u32> = degenerate.iter().flatten().map(|v| v.to_bits()).collect();
    let decoded = run(&decode, &run(&encode, &input));
    for d in decoded.chunks(7) {
        let d: Vec<f32> = d.iter().map(|&w| f(w)).collect();
        let want = [0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0];
        assert!(
            d.iter().zip(want).all(|(d, w)| (d - w).abs() < 1e-4),
            "{spec}: {d:?}"
        );
    }
}
