//! glTF's quantized normal (`KHR_mesh_quantization`): `NORMAL` as a normalized signed
//! `BYTE` or `SHORT` `VEC3`, each element padded to 4 bytes, written the way
//! gltf-transform's `quantize()` writes it (`@gltf-transform/functions` 4.5.1,
//! `src/quantize.ts`, `quantizeAttribute` with `quantizeNormal` 8 or 16).
//!
//! The encoder does not normalize: each component is clamped to `[-1, 1]`, its magnitude
//! times `M` (127 or 32767) rounded with halves up (`Math.round` of a product that f64
//! holds exactly), and the sign of the unclamped component applied; a NaN component is
//! stored as 0, as a JavaScript typed array stores NaN. So a non-unit input keeps its
//! length up to the clamp, as gltf-transform keeps it.
//!
//! The rounding is decided exactly in f32: with `M = 2^k - 1`, `a·M = a·2^k - a`, where
//! `a·2^k`, its floor `w` and its fraction `r` are exact, and `round(a·M) = w + d` with
//! `d = 1` where `r - ½ ≥ a`, `d = -1` where `r + ½ < a` and 0 otherwise; both sides of
//! each comparison are exact wherever it can hold (`r - ½` for `r ≥ ½`, `r + ½` on the
//! grid of `a·2^k` for `a > ½`), so no rounding of the product decides a code.
//!
//! The code is the accessor's element as it lies in the buffer: x in the lowest byte
//! (16 bits), then y, then z, the padding zero; the 16-bit form is two words, x and y in
//! the first. The decoder is the attribute fetch of glTF's rule `max(c/M, -1)` (as every
//! snorm fetch here, `c·fl(1/M)`), normalized, as a renderer normalizes an interpolated
//! normal; the all-zero code decodes as +Z.

use crate::codecs::component::snorm3::{OneWord, TwoWords, Words};
use crate::codecs::core::codec::Codec;
use crate::codecs::core::info::{Domain, FloatForm, Info, Sizes, seam};
use crate::codecs::core::pipeline::codec_functions;
use crate::codecs::core::spec::{Family, Spec, Tracing};
use crate::codecs::functions::function::Emitted;
use crate::codecs::toolkit::exact::one_if;
use crate::codecs::toolkit::quant::{Quant, Quants, not_nan};
use crate::model::{Float, V3};
use std::marker::PhantomData;

pub static FAMILY: GltfNormalFamily = GltfNormalFamily;

pub struct GltfNormalFamily;

static INFO: Info = Info {
    name: "gltf_normal",
    title: "glTF's quantized NORMAL (KHR_mesh_quantization): normalized BYTE or SHORT ×3, as gltf-transform writes it",
    sizes: Sizes::PerField {
        count: 3,
        per: &[8, 16],
    },
    domain: Some(Domain::Sphere),
    source: "KHR_mesh_quantization (glTF 2.0); gltf-transform 4.5.1, packages/functions/src/quantize.ts (quantizeAttribute)",
    edge_policy: "gltf-transform's: not normalized; each component clamped to [-1, 1], round(|x|·M) with halves up, the sign of x applied; a NaN component is stored as 0, so zero and NaN input encode as (0, 0, 0)",
    decode_note: "glTF's max(c/M, -1) per component, normalized; the all-zero code decodes as +Z",
    float_form: FloatForm::Continuous {
        seam: seam::NONE_PER_COMPONENT,
    },
    options: &[],
};

impl Family for GltfNormalFamily {
    fn info(&self) -> &Info {
        &INFO
    }
    /// No precise encoder: the format is gltf-transform's rounding, and a searched code
    /// for the same storage is `snorm8x3p`'s or `snorm16x3p`'s.
    fn precise(&self) -> bool {
        false
    }
    /// gltf-transform's policy: each component clamped, nothing normalized.
    fn keeps_length(&self) -> bool {
        true
    }
    /// The 16-bit form's three components take two words, as `SHORT VEC3` with its padding.
    fn emitted(&self, spec: &Spec, _: Tracing) -> Emitted {
        match spec.bits() {
            48 => codec_functions(spec, GltfNormal::short()),
            _ => codec_functions(spec, GltfNormal::byte()),
        }
    }
}

impl GltfNormal<OneWord> {
    /// `NORMAL` as `BYTE`: 8 bits per component in one word.
    pub fn byte() -> GltfNormal<OneWord> {
        GltfNormal::new(8)
    }
}

impl GltfNormal<TwoWords> {
    /// `NORMAL` as `SHORT`: 16 bits per component in two words.
    pub fn short() -> GltfNormal<TwoWords> {
        GltfNormal::new(16)
    }
}

impl<W> GltfNormal<W> {
    fn new(bits: u32) -> Self {
        GltfNormal {
            bits,
            words: PhantomData,
        }
    }
}

#[derive(Clone, Copy, Debug)]
pub struct GltfNormal<W> {
    /// Bits per component: 8 (`BYTE`) or 16 (`SHORT`).
    pub bits: u32,
    pub words: PhantomData<W>,
}

/// gltf-transform's code of one component for `M = 2^k - 1`, decided exactly (see the
/// module).
#[inline(always)]
fn component<F: Float>(x: F, k: u32) -> F {
    let a = x.clamped(F::c(-1.0), F::c(1.0)).abs();
    let scaled = (a * F::c((1u32 << k) as f32)).named("scaled");
    let whole = scaled.floor();
    let r = (scaled - whole).named("fraction");
    let up = (r - F::c(0.5)).ge(a);
    let down = (r + F::c(0.5)).lt(a);
    let q = whole + one_if::<F>(up) - one_if::<F>(down);
    let q = F::sel(not_nan(x), q, F::c(0.0));
    F::sel(x.lt(F::c(0.0)), -q, q)
}

impl<W: Words> Codec for GltfNormal<W> {
    type P<F: Float> = V3<F>;
    type C<F: Float> = W::C<F>;
    #[inline]
    fn quants(&self) -> Quants {
        Quants::new(&[Quant::Snorm(self.bits); 3])
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    /// The clamped components, for a snorm render target or vertex buffer to round; a
    /// NaN component is 0.
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V3<F> {
        v.map(
            #[inline(always)]
            |x| F::sel(not_nan(x), x.clamped(F::c(-1.0), F::c(1.0)), F::c(0.0)),
        )
    }
    /// The fetched components normalized; the all-zero code, the only one with no
    /// direction, decodes as +Z.
    #[inline(always)]
    fn direction<F: Float>(&self, p: V3<F>) -> V3<F> {
        p.normalize_or(V3::new(F::c(0.0), F::c(0.0), F::c(1.0)))
    }
    const EXACT_ROUNDING: bool = true;
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V3<F> {
        let k = self.bits - 1;
        v.map(
            #[inline(always)]
            |x| component(x, k),
        )
        .named("codes")
    }
}
