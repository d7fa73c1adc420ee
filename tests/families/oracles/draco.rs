//! Oracle: Draco's octahedral normal quantization (`OctahedronToolBox`).
//!
//! Source followed (C++, re-expressed here in Rust):
//!
//! * repository `google/draco`, snapshot `47238930f698250f474163e1a29d77858aa5c158`
//!   (2026-07-01). The header was last changed in
//!   `e4e34b0c63d631ec5eefa3c41bfd5dab868b82de` ("Draco v1.5.4 release").
//!   File `src/draco/compression/attributes/normal_compression_utils.h`:
//!   `OctahedronToolBox::SetQuantizationBits`,
//!   `FloatVectorToQuantizedOctahedralCoords`,
//!   `IntegerVectorToQuantizedOctahedralCoords`,
//!   `CanonicalizeOctahedralCoords`,
//!   `QuantizedOctahedralCoordsToUnitVector` and the private
//!   `OctahedralCoordsToUnitVector`.
//! * The encoder and decoder paths: `src/draco/attributes/attribute_octahedron_transform.cc`
//!   (`GeneratePortableAttribute` calls `FloatVectorToQuantizedOctahedralCoords`
//!   on each float[3] value; `InverseTransformAttribute` calls
//!   `QuantizedOctahedralCoordsToUnitVector`). Prediction schemes only change
//!   how (s, t) is entropy-coded; the decoder gets back the same (s, t).
//!
//! Parameters for q = `quantization_bits`:
//! `max_quantized_value = 2^q - 1` (odd), `max_value = max_quantized_value - 1`
//! (even), `center_value = max_value / 2`,
//! `dequantization_scale = 2.0f32 / (max_value as f32)`.
//! Valid q is **2..=30**: `SetQuantizationBits` rejects anything else. The
//! encoder's `Init` accepts any q >= 1, but setting up the transform then
//! fails for q = 1 or q > 30. The decoder reads q as a `u8` and checks the
//! same range. s and t both fall in `0..=max_value`; `max_quantized_value`
//! itself never occurs.
//!
//! Layout: Draco's octahedron is centred on **+X**, unlike the z-centred maps
//! of Bevy and Unity. The right hemisphere (x >= 0) maps into the central
//! diamond as `s = y + center`, `t = z + center` (integer units).
//!
//! Encode arithmetic, in order:
//! 1. `abs_sum = (|x| + |y|) + |z|` in **f64**;
//! 2. if `abs_sum > 1e-6`, `scaled = v * (1.0 / abs_sum)` (f64); otherwise
//!    (also when abs_sum is NaN) `scaled = (1, 0, 0)`;
//! 3. `i0 = floor(scaled.x * center + 0.5) as i32`, `i1` likewise (f64,
//!    round half up);
//! 4. `i2 = center - |i0| - |i1|`. If that is negative, it is folded into
//!    i1 (`i1 += i2` if `i1 > 0`, else `i1 -= i2`) and i2 becomes 0. Then
//!    `i2 = -i2` if `scaled.z < 0` (-0.0 does not count as negative);
//! 5. integer vector to (s, t), then canonicalization of the border and
//!    corner points.
//!
//! Decode, in f32: `y = s * scale - 1`, `z = t * scale - 1` (int converted to
//! float, then multiply, then subtract); `x = (1 - |y|) - |z|`;
//! `off = max(-x, 0)`; `y += (y < 0 ? off : -off)` and the same for z;
//! `ns = (x*x + y*y) + z*z`. If `ns < 1e-6` (compared in f64) the output is
//! (0,0,0); otherwise `d = 1 / sqrt(ns)` and the result is `(x*d, y*d, z*d)`.
//! This assumes C++ with no FMA contraction, as on x86-64 SSE. A compiler
//! that contracts (e.g. GCC on AArch64 with its default `-ffp-contract=fast`)
//! can change the last bit of the decode, and maybe rarely the rounding in
//! step 3.
//!
//! Cross-check: a scratch harness compiled the real header (g++ -O2, x86-64)
//! and found this port bit-identical. It covered 4.05M encodes (q in
//! {2,3,8,10,11,12,16,20,24,30}, random, lattice and special vectors) and
//! 1.71M decodes (every (s, t) for q <= 10, plus random samples for q = 16,
//! 24 and 30).
//!
//! Edge cases: a zero vector or a NaN input encodes as +X. An infinite
//! component gives NaN in step 3; the C++ cast is then undefined behaviour
//! (x86 yields `i32::MIN`), while this port's `as i32` yields 0.
//!
//! Sanity values for q = 10 (max_value 1022, center 511), checked with the
//! scratch program: +X -> (511, 511), -X -> (1022, 1022), +Y -> (1022, 511),
//! -Y -> (0, 511), +Z -> (511, 1022), -Z -> (511, 0). Decoding (511, 511)
//! gives exactly (1, 0, 0).

/// The quantization parameters, set up as `OctahedronToolBox::SetQuantizationBits` does.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OctahedronToolBox {
    pub quantization_bits: i32,
    pub max_quantized_value: i32,
    pub max_value: i32,
    pub dequantization_scale: f32,
    pub center_value: i32,
}

impl OctahedronToolBox {
    /// `SetQuantizationBits(q)`: returns `None` unless `2 <= q <= 30`.
    pub fn new(q: i32) -> Option<Self> {
        if !(2..=30).contains(&q) {
            return None;
        }
        // `(1u << q) - 1` assigned to int32.
        let max_quantized_value = ((1u32 << q) - 1) as i32;
        let max_value = max_quantized_value - 1;
        // `2.f / max_value_`: the int is converted to float, then an f32 division.
        let dequantization_scale = 2.0f32 / max_value as f32;
        let center_value = max_value / 2;
        Some(Self {
            quantization_bits: q,
            max_quantized_value,
            max_value,
            dequantization_scale,
            center_value,
        })
    }

    /// `CanonicalizeOctahedralCoords(s, t)`, its condition written as Draco writes it.
    #[allow(clippy::nonminimal_bool)]
    pub fn canonicalize_octahedral_coords(&self, s: i32, t: i32) -> (i32, i32) {
        let (mv, c) = (self.max_value, self.center_value);
        let (mut s, mut t) = (s, t);
        if (s == 0 && t == 0) || (s == 0 && t == mv) || (s == mv && t == 0) {
            s = mv;
            t = mv;
        } else if s == 0 && t > c {
            t = c - (t - c);
        } else if s == mv && t < c {
            t = c + (c - t);
        } else if t == mv && s < c {
            s = c + (c - s);
        } else if t == 0 && s > c {
            s = c - (s - c);
        }
        (s, t)
    }

    /// `IntegerVectorToQuantizedOctahedralCoords(int_vec)`. Precondition
    /// (a DCHECK in Draco): `|v0| + |v1| + |v2| == center_value`.
    pub fn integer_vector_to_quantized_octahedral_coords(&self, v: [i32; 3]) -> (i32, i32) {
        let (mv, c) = (self.max_value, self.center_value);
        let (s, t);
        if v[0] >= 0 {
            // Right hemisphere.
            s = v[1] + c;
            t = v[2] + c;
        } else {
            // Left hemisphere.
            s = if v[1] < 0 {
                v[2].abs()
            } else {
                mv - v[2].abs()
            };
            t = if v[2] < 0 {
                v[1].abs()
            } else {
                mv - v[1].abs()
            };
        }
        self.canonicalize_octahedral_coords(s, t)
    }

    /// `FloatVectorToQuantizedOctahedralCoords<float>(vector)`.
    pub fn float_vector_to_quantized_octahedral_coords(&self, v: [f32; 3]) -> (i32, i32) {
        let c = self.center_value;
        let abs_sum = ((v[0] as f64).abs() + (v[1] as f64).abs()) + (v[2] as f64).abs();
        let scaled: [f64; 3] = if abs_sum > 1e-6 {
            let scale = 1.0f64 / abs_sum;
            [
                v[0] as f64 * scale,
                v[1] as f64 * scale,
                v[2] as f64 * scale,
            ]
        } else {
            [1.0, 0.0, 0.0]
        };
        let mut iv = [0i32; 3];
        iv[0] = (scaled[0] * c as f64 + 0.5).floor() as i32;
        iv[1] = (scaled[1] * c as f64 + 0.5).floor() as i32;
        iv[2] = c - iv[0].abs() - iv[1].abs();
        if iv[2] < 0 {
            if iv[1] > 0 {
                iv[1] += iv[2];
            } else {
                iv[1] -= iv[2];
            }
            iv[2] = 0;
        }
        if scaled[2] < 0.0 {
            iv[2] *= -1;
        }
        self.integer_vector_to_quantized_octahedral_coords(iv)
    }

    /// `QuantizedOctahedralCoordsToUnitVector(s, t)`.
    pub fn quantized_octahedral_coords_to_unit_vector(&self, s: i32, t: i32) -> [f32; 3] {
        let sc = self.dequantization_scale;
        octahedral_coords_to_unit_vector(s as f32 * sc - 1.0, t as f32 * sc - 1.0)
    }
}

/// The private `OctahedralCoordsToUnitVector(in_s_scaled, in_t_scaled)`;
/// inputs are in [-1, 1].
pub fn octahedral_coords_to_unit_vector(in_s_scaled: f32, in_t_scaled: f32) -> [f32; 3] {
    let mut y = in_s_scaled;
    let mut z = in_t_scaled;
    let x = (1.0f32 - y.abs()) - z.abs();
    let mut x_offset = -x;
    x_offset = if x_offset < 0.0 { 0.0 } else { x_offset };
    y += if y < 0.0 { x_offset } else { -x_offset };
    z += if z < 0.0 { x_offset } else { -x_offset };
    let norm_squared = (x * x + y * y) + z * z;
    // `norm_squared < 1e-6`: a float promoted to double, compared with the
    // double literal.
    if (norm_squared as f64) < 1e-6 {
        [0.0, 0.0, 0.0]
    } else {
        let d = 1.0f32 / norm_squared.sqrt();
        [x * d, y * d, z * d]
    }
}

fn toolbox(quantization_bits: u32) -> OctahedronToolBox {
    let q = i32::try_from(quantization_bits).unwrap_or(-1);
    OctahedronToolBox::new(q).unwrap_or_else(|| {
        panic!("draco: quantization_bits must be in 2..=30, got {quantization_bits}")
    })
}

/// Draco's encoder: a float[3] normal (used as given; Draco divides by the
/// L1 norm itself) becomes the quantized octahedral coordinates (s, t).
/// Panics if `quantization_bits` is outside 2..=30.
pub fn encode(n: [f32; 3], quantization_bits: u32) -> [i32; 2] {
    let (s, t) = toolbox(quantization_bits).float_vector_to_quantized_octahedral_coords(n);
    [s, t]
}

/// Draco's decoder (`AttributeOctahedronTransform::InverseTransformAttribute`):
/// (s, t) becomes a unit vector (or (0,0,0) when the norm is tiny). Panics if
/// `quantization_bits` is outside 2..=30.
pub fn decode(s: i32, t: i32, quantization_bits: u32) -> [f32; 3] {
    toolbox(quantization_bits).quantized_octahedral_coords_to_unit_vector(s, t)
}
