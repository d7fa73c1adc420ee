//! Oracle: the reference decoder of glTF's `EXT_meshopt_compression` octahedral filter
//! (filter 1), re-expressed in scalar Rust from the pseudo-code of the extension's
//! Appendix B (KhronosGroup/glTF, `extensions/2.0/Vendor/EXT_meshopt_compression/
//! README.md`, commit 0dc2f8e299a26f3544d26d8aefbc893b08fc5037). The encoder's oracle is
//! meshoptimizer itself, through the `meshopt` crate (0.7.0, meshoptimizer 1.3).
//!
//! ```text
//! one = input[2]; x = input[0] / one; y = input[1] / one; z = 1.0 - abs(x) - abs(y);
//! t = min(z, 0.0); x -= copysign(t, x); y -= copysign(t, y);
//! len = sqrt(x * x + y * y + z * z); x /= len; y /= len; z /= len;
//! output[i] = round(v * INTN_MAX); output[3] = input[3];
//! ```
//! `round` is C's (halves away from zero); every operation is f32.

/// The filter's output words for input words `c` (x, y, one), `max` = `INTN_MAX`.
pub fn decode(c: [i32; 3], max: f32) -> [i32; 3] {
    let one = c[2] as f32;
    let mut x = c[0] as f32 / one;
    let mut y = c[1] as f32 / one;
    let z = 1.0 - x.abs() - y.abs();
    let t = z.min(0.0);
    x -= t.copysign(x);
    y -= t.copysign(y);
    let len = (x * x + y * y + z * z).sqrt();
    [x / len, y / len, z / len].map(|v| (v * max).round() as i32)
}
