//! Unity's octahedral normal in the three bytes of an RGB8 texel: SRP Core's
//! `PackNormalOctQuadEncode` and `PackFloat2To888` (URP's `_GBUFFER_NORMALS_OCT` writes
//! `PackFloat2To888(saturate(PackNormalOctQuadEncode(n)·½ + ½))`), read back by
//! `Unpack888ToFloat2` and `UnpackNormalOctQuadEncode`
//! (Unity-Technologies/Graphics cdc941e,
//! `Packages/com.unity.render-pipelines.core/ShaderLibrary/Packing.hlsl`).
//!
//! Two 12-bit codes `i = uint(f·4095.5)` of `f = saturate(o·½ + ½)`: a truncation, so
//! the 4096 codes split [0, 1] into equal bins and decode to `i/4095`, up to
//! `1/4095.5` from `f` where rounding would be within `1/8190` (the question "shouldn't we
//! round here?" of ScriptableRenderPipeline #883 stands). `rounding=nearest` is the same
//! format with `i = round(f·4095)`: every byte Unity's decoder reads, half the largest
//! scalar error (the mean angle drops to about 0.71 of Unity's; tests/families/engine.rs
//! asserts below 0.75). Bytes: `R = ix & 255`, `G = iy & 255`, `B = (ix >> 8) | (iy >> 8) << 4`.
//!
//! Unity's HLSL arithmetic, in its order: `rcp(max(|x| + |y| + |z|, 1e-6))` (written as
//! a division), products, `t = saturate(-z)`, the fold `x + (x ≥ 0 ? t : -t)` (so -Z is
//! `(1, 1)`), and D3D's `saturate(NaN) = 0` (a NaN input gives the codes of its NaN
//! coordinates, 0). The decoder's `x / 4095.0` is written as the product by the reciprocal
//! that HLSL compilers turn it into (a CPU port's quotient is an ulp away for some codes) and it normalizes as `n·(1/sqrt(n·n))`, where a
//! GPU's `normalize` is its own.

use crate::codecs::core::codec::Codec;
use crate::codecs::core::info::Domain;
use crate::codecs::core::codec_family::CodecFamily;
use crate::codecs::core::ieee;
use crate::codecs::core::info::{Info, OptDesc, OptKind, Sizes, FloatForm, seam};
use crate::codecs::core::pipeline::codec_functions;
use crate::codecs::core::spec::{Spec, SpecError};
use crate::codecs::engine::bevy::glam_normalize;
use crate::codecs::toolkit::quant::{Quant, Quants, round_half_away, truncated};
use crate::model::num::helper;
use crate::model::{Float, V2, V3};

/// How `PackFloat2To888` turns `f ∈ [0, 1]` into a 12-bit code.
pub const ROUNDING: OptDesc = OptDesc {
    key: "rounding",
    help: "truncate: Unity's uint(f·4095.5); nearest: round(f·4095) with halves away from zero (not Unity's), the same format and decoder with half the largest scalar error",
    kind: OptKind::Choice(&["truncate", "nearest"]),
};

pub static FAMILY: CodecFamily<UnityOct> = CodecFamily::new(
    Info {
        name: "unity_oct",
        title: "Unity SRP octahedral normal, 12|12 bits in RGB8",
        sizes: Sizes::Total(&[24]),
        domain: Some(Domain::Sphere),
        source: "Unity SRP Core (Unity-Technologies/Graphics cdc941e): ShaderLibrary/Packing.hlsl (PackNormalOctQuadEncode, PackFloat2To888, Unpack888ToFloat2, UnpackNormalOctQuadEncode), as URP's GBufferCommon.hlsl chains them",
        edge_policy: "Unity's: zero input encodes as +Z (bytes ff ff 77); -Z folds to the positive corner (ff ff ff); NaN coordinates become 0 (saturate(NaN) = 0 in D3D), so an all-NaN input gives bytes 00 00 00",
        decode_note: "UnpackNormalOctQuadEncode: a unit vector (to rounding) for every code",
        float_form: FloatForm::Continuous { seam: seam::OCTAHEDRAL_FOLD },
        options: &[ROUNDING, ieee::ENGINE_OPTION],
    },
    |_| UnityOct { nearest: false },
    codec_functions,
)
.with_options(|spec, _| UnityOct { nearest: spec.chose(&ROUNDING, "nearest") })
.with_variants(&["unity_oct24:rounding=nearest"])
.with_engine("Unity");

impl UnityOct {
    /// Unity's format; `nearest` rounds the codes instead of truncating them.
    pub fn new(nearest: bool) -> Result<UnityOct, SpecError> {
        let spec: Spec = if nearest {
            "unity_oct24:rounding=nearest"
        } else {
            "unity_oct24"
        }
        .parse()?;
        Ok(FAMILY.codec_of(&spec))
    }
}

#[derive(Clone, Copy, Debug)]
pub struct UnityOct {
    pub nearest: bool,
}

/// The bytes as integers → `UnpackNormalOctQuadEncode(code/4095·2 - 1)`.
#[inline(always)]
fn from_bytes<F: Float>(b: V3<F>) -> V3<F> {
    let hi = (b.z * F::c(1.0 / 16.0)).floor();
    let lo = b.z - hi * F::c(16.0);
    let codes = V2::new(b.x + lo * F::c(256.0), b.y + hi * F::c(256.0)).named("codes");
    let q = Quant::Unorm(12);
    let o = codes.map(
        #[inline(always)]
        |c| q.dequantize(c) * F::c(2.0) - F::c(1.0),
    );
    let z = F::c(1.0) - o.x.abs() - o.y.abs();
    let t = (-z).at_least(F::c(0.0)).named("t");
    let xy = o.map(
        #[inline(always)]
        |x| x + F::sel(x.ge(F::c(0.0)), -t, t),
    );
    glam_normalize(V3::from_xy(xy, z))
}

impl Codec for UnityOct {
    type P<F: Float> = V3<F>;
    type C<F: Float> = F::U;
    #[inline]
    fn quants(&self) -> Quants {
        Quants::new(&[Quant::Unorm(8); 3])
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    /// `PackFloat2To888`'s output: the bytes as unorm8 values, which an RGB8 target
    /// stores as exactly those bytes.
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V3<F> {
        helper!(self.round_codes(v)) * F::c(1.0 / 255.0)
    }
    /// `Unpack888ToFloat2` of the fetched bytes: `uint(x·255.5)` recovers each byte.
    #[inline(always)]
    fn direction<F: Float>(&self, u: V3<F>) -> V3<F> {
        let bytes = (u * F::c(255.5)).map(
            #[inline(always)]
            |x| truncated(x),
        );
        from_bytes(bytes)
    }
    #[inline(always)]
    fn decode_codes<F: Float>(&self, b: V3<F>) -> V3<F> {
        from_bytes(b)
    }
    /// The blue byte holds the high bits of both codes.
    fn whole_field(&self) -> Option<usize> {
        Some(2)
    }
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V3<F> {
        let zero = F::c(0.0);
        let a = v.abs();
        let l1 = (a.x + a.y + a.z).at_least(F::c(1e-6));
        let p = (v * (F::c(1.0) / l1)).named("p");
        let t = (-p.z).clamped(zero, F::c(1.0)).named("t");
        let o = p.xy().map(
            #[inline(always)]
            |x| x + F::sel(x.ge(zero), t, -t),
        );
        let f = (o * F::c(0.5) + V2::splat(F::c(0.5))).map(
            #[inline(always)]
            |x| x.clamped(zero, F::c(1.0)),
        );
        let nearest = self.nearest;
        let c = f
            .map(
                #[inline(always)]
                |x| {
                    if nearest {
                        round_half_away(x * F::c(4095.0))
                    } else {
                        truncated(x * F::c(4095.5))
                    }
                },
            )
            .named("codes");
        let hi = (c * F::c(1.0 / 256.0)).floor().named("high");
        let lo = c - hi * F::c(256.0);
        V3::new(lo.x, lo.y, hi.x + hi.y * F::c(16.0)).named("bytes")
    }
}
