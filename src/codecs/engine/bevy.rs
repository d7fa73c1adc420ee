//! Bevy's compressed-mesh normal (`Mesh::compressed_mesh` with `COMPRESS_NORMAL`,
//! bevyengine/bevy #21926): octahedral coordinates as `Snorm16x2`, encoded on the CPU in
//! `crates/bevy_mesh/src/vertex.rs` and decoded by `octahedral_decode_signed` in
//! `crates/bevy_render/src/utils.wgsl` (commit 7517c61, unchanged at 4805ca7, where the
//! file is `utils.wesl`). The vertex format is Snorm16x2, not the Unorm16x2 the pull
//! request's text names: the encoder writes `[i16; 2]` holding coordinates in [-1, 1].
//!
//! Every step is Bevy's own arithmetic, in its order: glam's `normalize`
//! (`v·(1/sqrt((x² + y²) + z²))`), division by the L1 norm, the fold with a `> 0` sign
//! test (a zero coordinate folds to the negative side, so -Z is `(-1, -1)`), and
//! `round(clamp(c, -1, 1)·32767)` with halves away from zero (NaN gives 0, so zero and
//! NaN input encode as +Z, `(0, 0)`). `decode_float` is Bevy's WGSL function on the
//! fetched coordinates, its `normalize` written as glam's; `decode` fetches the codes as
//! every decoder here does, `max(c·fl(1/32767), -1)`, which is the Snorm16 fetch's
//! quotient `c/32767` or an ulp from it.

use crate::codecs::core::codec::Codec;
use crate::codecs::core::info::Domain;
use crate::codecs::core::codec_family::CodecFamily;
use crate::codecs::core::ieee;
use crate::codecs::core::info::{Info, Sizes, FloatForm, seam};
use crate::codecs::core::pipeline::codec_functions;
use crate::codecs::core::spec::SpecError;
use crate::codecs::toolkit::quant::{Quant, Quants, not_nan, round_half_away};
use crate::model::num::helper;
use crate::model::{Float, V2, V3};

pub static FAMILY: CodecFamily<BevyOct> = CodecFamily::new(
    Info {
        name: "bevy_oct",
        title: "Bevy's compressed-mesh octahedral normal, Snorm16x2",
        sizes: Sizes::Total(&[32]),
        domain: Some(Domain::Sphere),
        source: "Bevy main at bevyengine/bevy 7517c61 (#21926, merged 2026-06-02; unchanged at 4805ca7): crates/bevy_mesh/src/vertex.rs (octahedral_encode_signed, arr_f32_to_snorm16) and crates/bevy_render/src/utils.wgsl (octahedral_decode_signed)",
        edge_policy: "Bevy's: zero and NaN input encode as +Z (0, 0); infinite input too (its normalize gives NaN); -Z encodes as (-32767, -32767)",
        decode_note: "Bevy's octahedral_decode_signed: a unit vector (to rounding) for every code",
        float_form: FloatForm::Continuous { seam: seam::OCTAHEDRAL_FOLD },
        options: &[ieee::ENGINE_OPTION],
    },
    |_| BevyOct,
    codec_functions,
)
.with_engine("Bevy");

impl BevyOct {
    /// The codec (it has one size, 32 bits).
    pub fn new() -> Result<BevyOct, SpecError> {
        FAMILY.codec(32)
    }
}

#[derive(Clone, Copy, Debug)]
pub struct BevyOct;

/// glam's `Vec3::normalize`: `v·(1/sqrt((x² + y²) + z²))`; zero gives NaN lanes.
#[inline(always)]
pub fn glam_normalize<F: Float>(v: V3<F>) -> V3<F> {
    let r = F::c(1.0) / v.length_squared().sqrt();
    v * r
}

impl Codec for BevyOct {
    type P<F: Float> = V2<F>;
    type C<F: Float> = F::U;
    #[inline]
    fn quants(&self) -> Quants {
        Quants::new(&[Quant::Snorm(16); 2])
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    /// `octahedral_encode_signed(normalize(v))`: `p = n / ((|x| + |y|) + |z|)`, then `p.xy`
    /// where `p.z ≥ 0`, else `(1 - |p.yx|)·(p.xy > 0 ? 1 : -1)`. Where Bevy's coordinates
    /// are NaN (zero, NaN and infinite input) they are 0 here, the value its
    /// `arr_f32_to_snorm16` stores for them.
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V2<F> {
        let n = glam_normalize(v).named("n");
        let a = n.abs();
        let p = (n / (a.x + a.y + a.z)).named("p");
        let sign = p.xy().map(
            #[inline(always)]
            |x| F::sel(x.gt(F::c(0.0)), F::c(1.0), F::c(-1.0)),
        );
        let wrap = (V2::splat(F::c(1.0)) - p.xy().yx().abs()) * sign;
        V2::sel_all(p.z.ge(F::c(0.0)), p.xy(), wrap)
            .map(
                #[inline(always)]
                |x| F::sel(not_nan(x), x, F::c(0.0)),
            )
    }
    /// `octahedral_decode_signed`: `n = (x, y, (1 - |x|) - |y|)`, `t = saturate(-n.z)`,
    /// `n.xy += n.xy ≥ 0 ? -t : t`, then glam's normalize.
    #[inline(always)]
    fn direction<F: Float>(&self, f: V2<F>) -> V3<F> {
        let z = F::c(1.0) - f.x.abs() - f.y.abs();
        let t = (-z).clamped(F::c(0.0), F::c(1.0)).named("t");
        let xy = f.map(
            #[inline(always)]
            |x| x + F::sel(x.ge(F::c(0.0)), -t, t),
        );
        glam_normalize(V3::from_xy(xy, z))
    }
    /// `arr_f32_to_snorm16`: `round(clamp(c, -1, 1)·32767)`, halves away from zero.
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V2<F> {
        let p = helper!("encode_float" => self.params(v));
        p.map(
            #[inline(always)]
            |x| round_half_away(x.clamped(F::c(-1.0), F::c(1.0)) * F::c(32767.0)),
        )
        .named("codes")
    }
}
