//! Oracle: Unity SRP Core octahedral normal packing into 8:8:8 (12+12 bits).
//!
//! Source followed (HLSL, re-expressed here in scalar Rust):
//!
//! * repository `Unity-Technologies/Graphics`, commit
//!   `cdc941e1378729b1ca1fafb175151ac3d781ebb0`, file
//!   `Packages/com.unity.render-pipelines.core/ShaderLibrary/Packing.hlsl`:
//!   `PackNormalOctQuadEncode`, `UnpackNormalOctQuadEncode`,
//!   `PackFloat2To888UInt`, `PackFloat2To888`, `Unpack888UIntToFloat2`,
//!   `Unpack888ToFloat2`. This is the latest version held in the searchable
//!   store; the Graphics repository itself (5.9 GB) was too large to fetch,
//!   so its full history could not be checked.
//! * How the functions are chained (URP, keyword `_GBUFFER_NORMALS_OCT`):
//!   same repository, commit `433e6570eaab6277ebcbf30458ae653e9d268ef5`,
//!   `Packages/com.unity.render-pipelines.universal/ShaderLibrary/GBufferCommon.hlsl`
//!   (`PackGBufferNormal`), which does
//!   `PackFloat2To888(saturate(PackNormalOctQuadEncode(n) * 0.5 + 0.5))`.
//!   The float-precision decode is in commit
//!   `19ec161f3f752db865597374b3ad1b3eaf110097`,
//!   `Packages/com.unity.render-pipelines.universal/ShaderLibrary/DeclareNormalsTexture.hlsl`
//!   (`LoadSceneNormals`), which does
//!   `UnpackNormalOctQuadEncode(Unpack888ToFloat2(rgb) * 2.0 - 1.0)`.
//!
//! Earlier versions differ, so use care when comparing against older Unity:
//! * `Unity-Technologies/Graphics` @ `30fe655a99fe20c350f8c3c0314bb348194f3795`
//!   (`com.unity.render-pipelines.core/ShaderLibrary/Packing.hlsl`): the
//!   encode lacks the `max(.., 1e-6)` guard, and `Unpack888ToFloat2` uses
//!   `x * 255.0` where the current code uses `x * 255.5` ("+0.5 to fix
//!   precision error on iOS").
//! * `ScriptableRenderPipeline` PR #883 ("Pack normal on 1212bit in 888",
//!   2018-01-30) introduced `PackFloat2To888` as `(uint2)(f * 4095.0)`. A
//!   reviewer asked "Shouldn't we round here?"; the answer was "It is fined".
//!   The current code uses `(uint2)(f * 4095.5)`, which is still a
//!   truncation (float to uint drops the fraction) and not round-to-nearest:
//!   `i = floor(f * 4095.5)` splits [0,1] into 4096 equal bins, and the decode
//!   rebuilds `i / 4095`. The scalar error is therefore at most about
//!   `1/4095.5` (near f = 0), against `0.5/4095` for true rounding.
//!
//! Bit layout of the three bytes (R, G, B), for 12-bit codes `ix`, `iy`:
//! `R = ix & 0xFF`, `G = iy & 0xFF`, `B = (ix >> 8) | ((iy >> 8) << 4)`.
//!
//! Conversion rules assumed (this is a shader, so the hardware does them):
//! * Output merger, float to UNORM8 (D3D11 functional spec §3.2.3.6;
//!   Vulkan/Metal are equivalent for these inputs): NaN becomes 0, clamp to
//!   [0,1], then `floor(x * 255 + 0.5)`. `PackFloat2To888` always outputs
//!   `k / 255.0` for an integer k, so any sane rounding rule stores exactly
//!   k. The scratch check confirms this for all 256 k, for both `k / 255.0`
//!   and `k * (1/255.0)`.
//! * Texture fetch, UNORM8 to float: `k / 255.0`, correctly rounded.
//!   `Unpack888ToFloat2` then computes `uint(x * 255.5)`, which recovers k
//!   exactly for all 256 values (checked).
//! * `rcp` is written as `1.0 / x`, and `normalize(n)` as
//!   `n * (1.0 / sqrt((x*x + y*y) + z*z))`. On a GPU, `rcp`, `rsqrt` and
//!   the `dot` order / FMA contraction are left to the driver. The 12-bit
//!   codes sit far from bin edges in almost every case, but they are exact
//!   only when the GPU's `rcp` matches a correctly rounded division. Compare
//!   the decoded floats with a tolerance.
//! * `saturate(NaN)` is 0 (D3D semantics), and `max(NaN, c)` is `c`.
//!
//! Edge cases:
//! * zero vector: the `max(l1, 1e-6)` guard gives oct (0, 0) -> remapped
//!   (0.5, 0.5) -> code 2047 in each axis -> bytes `[255, 255, 0x77]`, the
//!   same bytes as +Z.
//! * NaN input: the `max` guard returns 1e-6 for a NaN L1 norm, and each NaN
//!   oct component becomes 0 at the `saturate` remap. An all-NaN input
//!   gives `[0, 0, 0]`; `[NaN, 0, 1]` gives `[0, 255, 112]`.
//! * -Z: `t = 1`, and `n.x >= 0` (also true for -0.0) selects `+t`, so
//!   oct = (1, 1) -> bytes `[255, 255, 0xFF]`. This folds to the **positive**
//!   corner; Bevy folds -Z to the negative one.
//! * The fold is written in a different way from the textbook version:
//!   for z < 0, `x' = x + sign(x) * |z|` (not `(1 - |y|) * sign(x)`).
//!   The two are equal in exact arithmetic but can round differently.
//!
//! Sanity values (from the scratch program): +Z -> `[255, 255, 119]`,
//! -Z -> `[255, 255, 255]`, +X -> `[255, 255, 127]`, -X -> `[0, 255, 112]`,
//! +Y -> `[255, 255, 247]`, -Y -> `[255, 0, 7]`.

/// HLSL `saturate` with D3D semantics: NaN gives 0.
pub fn saturate(x: f32) -> f32 {
    if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) }
}

/// `PackNormalOctQuadEncode(float3 n)`: returns octahedral coordinates in [-1, 1].
pub fn pack_normal_oct_quad_encode(n: [f32; 3]) -> [f32; 2] {
    // `dot(abs(n), 1.0)`: the multiplications by 1 are exact, so fusing makes
    // no difference. The sum is (|x| + |y|) + |z|.
    let l1 = (n[0].abs() + n[1].abs()) + n[2].abs();
    // `rcp(max(l1, 1e-6))`. HLSL `max` returns the non-NaN operand, as Rust does.
    let r = 1.0 / l1.max(1e-6);
    let p = [n[0] * r, n[1] * r, n[2] * r];
    let t = saturate(-p[2]);
    // `n.xy + float2(n.x >= 0.0 ? t : -t, n.y >= 0.0 ? t : -t)`
    [
        p[0] + if p[0] >= 0.0 { t } else { -t },
        p[1] + if p[1] >= 0.0 { t } else { -t },
    ]
}

/// `PackFloat2To888UInt(float2 f)`: two 12-bit codes `floor(f * 4095.5)`
/// (truncating float to uint; f is expected in [0,1]), packed into 8:8:(4|4).
pub fn pack_float2_to_888_uint(f: [f32; 2]) -> [u32; 3] {
    // `(uint2)(f * 4095.5)`. Rust `as u32` truncates toward zero and
    // saturates, which matches D3D `ftou` for values in range.
    let ix = (f[0] * 4095.5) as u32;
    let iy = (f[1] * 4095.5) as u32;
    let (hx, hy) = (ix >> 8, iy >> 8);
    let (lx, ly) = (ix & 255, iy & 255);
    [lx, ly, hx | (hy << 4)]
}

/// `PackFloat2To888(float2 f)`: `PackFloat2To888UInt(f) / 255.0`, the float
/// that the shader writes to an RGB8 UNORM target.
pub fn pack_float2_to_888(f: [f32; 2]) -> [f32; 3] {
    let c = pack_float2_to_888_uint(f);
    [
        c[0] as f32 / 255.0,
        c[1] as f32 / 255.0,
        c[2] as f32 / 255.0,
    ]
}

/// The output merger's float -> UNORM8 conversion (D3D11 §3.2.3.6): NaN -> 0,
/// clamp to [0,1], `floor(x * 255 + 0.5)`.
pub fn f32_to_unorm8(x: f32) -> u8 {
    let c = saturate(x);
    (c * 255.0 + 0.5).floor() as u8
}

/// UNORM8 texel to float on fetch: `k / 255`.
pub fn unorm8_to_f32(k: u8) -> f32 {
    k as f32 / 255.0
}

/// `Unpack888UIntToFloat2(uint3 x)`: rebuilds the two 12-bit codes and
/// returns `code / 4095.0`.
pub fn unpack_888_uint_to_float2(x: [u32; 3]) -> [f32; 2] {
    let hi = x[2] >> 4;
    let lo = x[2] & 15;
    let cx = x[0] | (lo << 8);
    let cy = x[1] | (hi << 8);
    [cx as f32 / 4095.0, cy as f32 / 4095.0]
}

/// `Unpack888ToFloat2(float3 x)`: `uint3(x * 255.5)` (truncating), then
/// `Unpack888UIntToFloat2`.
pub fn unpack_888_to_float2(x: [f32; 3]) -> [f32; 2] {
    let i = [
        (x[0] * 255.5) as u32,
        (x[1] * 255.5) as u32,
        (x[2] * 255.5) as u32,
    ];
    unpack_888_uint_to_float2(i)
}

/// `UnpackNormalOctQuadEncode(float2 f)`: f holds octahedral coordinates in [-1, 1].
pub fn unpack_normal_oct_quad_encode(f: [f32; 2]) -> [f32; 3] {
    // `1.0 - (f.x < 0 ? -f.x : f.x) - (f.y < 0 ? -f.y : f.y)`: written
    // without abs() in the source because of a compiler bug; same value.
    let ax = if f[0] < 0.0 { -f[0] } else { f[0] };
    let ay = if f[1] < 0.0 { -f[1] } else { f[1] };
    let z = (1.0 - ax) - ay;
    let t = (-z).max(0.0);
    // `n.xy += float2(n.x >= 0.0 ? -t : t, n.y >= 0.0 ? -t : t)`
    let x = f[0] + if f[0] >= 0.0 { -t } else { t };
    let y = f[1] + if f[1] >= 0.0 { -t } else { t };
    normalize3([x, y, z])
}

/// HLSL `normalize`, modelled as `n * (1 / sqrt(dot(n, n)))` with
/// `dot = (x*x + y*y) + z*z`. A GPU uses its own `rsqrt`.
pub fn normalize3(n: [f32; 3]) -> [f32; 3] {
    let d = (n[0] * n[0] + n[1] * n[1]) + n[2] * n[2];
    let r = 1.0 / d.sqrt();
    [n[0] * r, n[1] * r, n[2] * r]
}

/// The float3 that a URP `_GBUFFER_NORMALS_OCT` pass writes to the normals
/// target: `PackFloat2To888(saturate(PackNormalOctQuadEncode(n) * 0.5 + 0.5))`.
/// `x * 0.5 + 0.5` comes out the same whether or not it is fused, because
/// `* 0.5` is exact.
pub fn encode_float(n: [f32; 3]) -> [f32; 3] {
    let o = pack_normal_oct_quad_encode(n);
    let r = [saturate(o[0] * 0.5 + 0.5), saturate(o[1] * 0.5 + 0.5)];
    pack_float2_to_888(r)
}

/// The three bytes stored in the RGB8 UNORM target. `encode_float`'s output
/// goes through the output merger's float -> UNORM8 conversion
/// (`f32_to_unorm8`, round-to-nearest of `x * 255`). This always equals
/// `pack_float2_to_888_uint` of the remapped coordinates.
pub fn encode(n: [f32; 3]) -> [u8; 3] {
    let f = encode_float(n);
    [
        f32_to_unorm8(f[0]),
        f32_to_unorm8(f[1]),
        f32_to_unorm8(f[2]),
    ]
}

/// The decode as in `DeclareNormalsTexture.hlsl` (all fp32): fetch the UNORM8
/// texels (`k/255`), `Unpack888ToFloat2`, `* 2.0 - 1.0`, then
/// `UnpackNormalOctQuadEncode`. The GBuffer path (`UnpackGBufferNormal`) does
/// the `* 2 - 1` in `half`; on platforms where half is real fp16 that loses
/// bits, and it is not modelled here.
pub fn decode(bytes: [u8; 3]) -> [f32; 3] {
    let x = [
        unorm8_to_f32(bytes[0]),
        unorm8_to_f32(bytes[1]),
        unorm8_to_f32(bytes[2]),
    ];
    let r = unpack_888_to_float2(x);
    let o = [r[0] * 2.0 - 1.0, r[1] * 2.0 - 1.0];
    unpack_normal_oct_quad_encode(o)
}
