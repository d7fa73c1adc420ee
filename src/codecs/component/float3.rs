//! float×3 (survey §2 and Table 1): the unit vector's components stored as floats.
//! - float16×3: IEEE binary16, the layout of the first three channels of an RGBA16_FLOAT
//!   texel: x in bits 0–15 and y in bits 16–31 of word 0, z in bits 0–15 of word 1.
//!   Packing and unpacking are [`crate::codecs::toolkit::half`]'s integer forms, never a pack builtin.
//! - float32×3: IEEE binary32, one word per component (x in word 0, y in word 1, z in
//!   word 2: an RGB32_FLOAT texel, or a `vec3` in a storage buffer), each component a
//!   multiple of `2^-24` (f32's spacing in `[½, 1)`) decided from integers, so that every
//!   implementation writes the same bits; the survey's baseline.

use crate::codecs::core::codec::{Codec, unit_or_z};
use crate::codecs::core::info::Domain;
use crate::codecs::toolkit::exact::{canonical, canonical_or_z, half_sqrt_ratio, length2, unit_on_grid};
use crate::codecs::core::info::{Info, Sizes, FloatForm, seam};
use crate::codecs::core::spec::{Family, Tracing};
use crate::codecs::functions::function::Emitted;
use crate::codecs::core::pipeline::codec_functions;
use crate::codecs::toolkit::quant::{Quant, Quants};
use crate::codecs::core::spec::Spec;
use crate::model::{Bool, Float, Uint, V2, V3};

pub static FAMILY: Float3Family = Float3Family;

pub struct Float3Family;

static INFO: Info = Info {
    name: "float3",
    title: "components as IEEE floats (float16: RGBA16_FLOAT's first three channels; float32: RGB32_FLOAT)",
    sizes: Sizes::PerComponent {
        prefix: "float",
        count: 3,
        per: &[16, 32],
    },
    domain: Some(Domain::Sphere),
    source: "Cigolle et al. 2014 §2 and Table 1 (float×3)",
    edge_policy: "input is normalized first, then each component is rounded to the nearest f16 (float32x3: to the 2^-24 grid, from the input on a 2^-21 grid of its largest component's binade); a component that rounds to zero is +0; zero, NaN and infinite input encode as +Z",
    decode_note: "the three stored floats, exactly, without normalizing (unit length to within 2^-11 for float16 codes the encoder writes, 2^-21 for float32); a code with an infinite or NaN component, or with every component zero, decodes as +Z; a denormal float32 component is read as +0",
    float_form: FloatForm::Continuous { seam: seam::NONE_PER_COMPONENT },
    options: &[],
};

impl Family for Float3Family {
    fn info(&self) -> &Info {
        &INFO
    }
    fn precise(&self) -> bool {
        Float16x3::EXACT_SEARCH && Float32x3::EXACT_SEARCH
    }
    fn emitted(&self, spec: &Spec, _: Tracing) -> Emitted {
        match spec.bits() {
            48 => codec_functions(spec, Float16x3),
            _ => codec_functions(spec, Float32x3),
        }
    }
}

/// float16×3 in two words (the low 48 bits of an RGBA16_FLOAT texel).
#[derive(Clone, Copy, Debug, Default)]
pub struct Float16x3;

impl Codec for Float16x3 {
    type P<F: Float> = V3<F>;
    type C<F: Float> = V2<F::U>;
    #[inline]
    fn quants(&self) -> Quants {
        Quants::new(&[Quant::Half; 3])
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    /// The unit vector, for an RGBA16_FLOAT render target to round.
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V3<F> {
        unit_or_z(v)
    }
    /// The fetched halves themselves: a half is exact in f32, and normalizing would move
    /// the vector the encoder chose. Only codes no encoder writes need a stand-in.
    #[inline(always)]
    fn direction<F: Float>(&self, p: V3<F>) -> V3<F> {
        stored_or_z(p, 1, false)
    }
    /// Each component of the canonical input rounded to the f16 grid by
    /// [`half_sqrt_ratio`]: decided by comparing correctly rounded products.
    const EXACT_ROUNDING: bool = true;
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V3<F> {
        let (w, ok) = canonical(v);
        let s = length2(w);
        let c = w.map(#[inline(always)] |x| half_sqrt_ratio(x, s));
        V3::sel_all(ok, c, V3::new(F::c(0.0), F::c(0.0), F::c(1.0)))
    }
}

/// The stored floats themselves, with each component whose magnitude's bits are below
/// `least` read as +0 (when `flush`), or +Z for a vector with an infinite or NaN component
/// or without a component of at least `least`. Everything is decided on the bits
/// ([`Float::magnitude_bits`]): a compiler may fold a float comparison with NaN where
/// `precise` is absent, and Mesa's OpenGL GLSL compiler does (`|x| <= MAX` becomes true).
#[inline(always)]
fn stored_or_z<F: Float>(p: V3<F>, least: u32, flush: bool) -> V3<F> {
    let m = p.map(#[inline(always)] |x| x.magnitude_bits());
    let finite = m.map(#[inline(always)] |m| m.lt(F::U::c(F32_INF)));
    let counts = m.map(#[inline(always)] |m| F::U::c(least - 1).lt(m));
    let ok = finite.x.and(finite.y).and(finite.z);
    let some = counts.x.or(counts.y).or(counts.z);
    let kept = if flush {
        p.zip(counts, #[inline(always)] |x, c| F::sel(c, x, F::c(0.0)))
    } else {
        p
    };
    V3::sel_all(ok.and(some), kept, V3::new(F::c(0.0), F::c(0.0), F::c(1.0)))
}

/// The bits of the f32 infinity, the least magnitude that is not finite.
const F32_INF: u32 = 0x7f80_0000;

/// The bits of the smallest normal f32.
const F32_MIN_NORMAL: u32 = 0x0080_0000;

/// float32×3 in three words (an RGB32_FLOAT texel).
#[derive(Clone, Copy, Debug, Default)]
pub struct Float32x3;

impl Codec for Float32x3 {
    type P<F: Float> = V3<F>;
    type C<F: Float> = V3<F::U>;
    #[inline]
    fn quants(&self) -> Quants {
        Quants::new(&[Quant::Single; 3])
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    /// The unit vector, as an RGB32_FLOAT render target stores it.
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V3<F> {
        unit_or_z(v)
    }
    /// The fetched floats themselves, with a denormal (which an implementation may
    /// flush) read as +0 and only codes no encoder writes replaced. Decided on the
    /// fetched bits before any arithmetic, so no flush can reach the decision.
    #[inline(always)]
    fn direction<F: Float>(&self, p: V3<F>) -> V3<F> {
        stored_or_z(p, F32_MIN_NORMAL, true)
    }
    /// Each component on the `2^-24` grid by [`unit_on_grid`]: integers decide every digit.
    const EXACT_ROUNDING: bool = true;
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V3<F> {
        let (w, ok) = canonical_or_z(v);
        V3::sel_all(ok, unit_on_grid(w), V3::new(F::c(0.0), F::c(0.0), F::c(1.0)))
    }
}
