//! snorm12×2 ↔ unorm8×3 (survey §3.3, Listings 4–5): two 12-bit parameters in the three
//! bytes of an RGB8 texel, stored biased (`u = c + 2047`, bytes `u.x>>4`,
//! `(u.x&15)<<4 | u.y>>8`, `u.y&255`). Each direction exists in an integer form and a
//! float-only form for hardware without fast integers; `tests/families/snorm12x2.rs` proves the two
//! forms bit-equal on all 2^24 inputs. The unpack ends in `(s - 2047)·(1/2047)` rather than
//! the listing's `s·(1/2047) - 1`, which misses zero by an ulp.

use crate::codecs::core::info::{Info, Sizes, FloatForm};
use crate::codecs::core::spec::{Family, Tracing};
use crate::codecs::functions::function::{Emitted, Inputs, Role};
use crate::codecs::functions::words::{declared, trace_declared};
use crate::codecs::toolkit::quant::Quant;
use crate::codecs::core::spec::Spec;
use crate::model::{Float, Uint, V2, V3};

pub static FAMILY: Pack12Family = Pack12Family;

pub struct Pack12Family;

static INFO: Info = Info {
    name: "snorm12x2",
    title: "snorm12×2 ↔ unorm8×3 packing helpers, integer and float-only forms",
    sizes: Sizes::Fixed(24),
    domain: None,
    source: "Cigolle et al. 2014 §3.3, Listings 4–5",
    edge_policy: "parameters are clamped to [-1, 1]",
    decode_note: "unpack returns values in [-1, 1]",
    float_form: FloatForm::Absent,
    options: &[],
};

/// Each packing helper once: traced into the module, evaluated as the reference and by the
/// adversarial [`Dev`].
macro_rules! helpers {
    ($(($name:literal, $role:expr, $quants:expr, $param:literal, $P:ident, $f:path)),* $(,)?) => {{
        let (module, functions) = trace_declared(vec![$(declared!(
            $name,
            $role,
            Inputs::FloatCodes($quants),
            [$param],
            <F> [] |x: $P<F>| $f(x)
        )),*]);
        Emitted { module, functions, namespace: String::new(), portable_encoder: false, cpu: Vec::new() }
    }};
}

impl Family for Pack12Family {
    fn info(&self) -> &Info {
        &INFO
    }
    fn precise(&self) -> bool {
        // A packing helper: it has no encoder.
        false
    }
    fn emitted(&self, _spec: &Spec, _: Tracing) -> Emitted {
        let s12 = || vec![Quant::Snorm(12); 2];
        let u8s = || vec![Quant::Unorm(8); 3];
        helpers!(
            ("snorm12x2_to_unorm8x3", Role::Pack, s12(), "f", V2, to_unorm8x3),
            ("snorm12x2_to_unorm8x3_int", Role::Pack, s12(), "f", V2, to_unorm8x3_int),
            ("unorm8x3_to_snorm12x2", Role::Unpack, u8s(), "u", V3, from_unorm8x3),
            ("unorm8x3_to_snorm12x2_int", Role::Unpack, u8s(), "u", V3, from_unorm8x3_int),
        )
    }
    fn helper_doc(&self, name: &str) -> Option<String> {
        let s = match name {
            "snorm12x2_to_unorm8x3" => "Float-only pack of two snorm12 values into three unorm8 values (survey Listing 5).",
            "snorm12x2_to_unorm8x3_int" => "Integer pack of two snorm12 values into three unorm8 values (survey Listing 4); equal to the float-only form on every input.",
            "unorm8x3_to_snorm12x2" => "Float-only unpack of three unorm8 values (as an RGB8 fetch returns them) into two snorm12 values in [-1, 1].",
            "unorm8x3_to_snorm12x2_int" => "Integer unpack of three unorm8 values into two snorm12 values; equal to the float-only form on every input.",
            _ => return None,
        };
        Some(format!("{s} {PORTABILITY}"))
    }
}

/// What the helpers' doc comments say of other implementations: measured, not proven
/// (the decoder bounds of [`crate::measure::decode_bound`] are for codecs).
const PORTABILITY: &str = "Other implementations: under the division, square root, contraction, denormal and sign-of-zero latitudes, unitpack verify --portable finds no change over its sample of the inputs (the float-only pack may differ in the sign of a zero); measured, not proven.";

/// The bias of the stored 12-bit integers.
pub const BIAS: f32 = 2047.0;

/// The biased 12-bit integers `round(clamp(f,-1,1)·2047 + 2047)`.
#[inline(always)]
fn biased<F: Float>(f: V2<F>) -> V2<F> {
    let c = f.map(#[inline(always)] |x| Quant::Snorm(12).clamp(x));
    (c * F::c(BIAS) + F::c(BIAS)).round().named("u")
}

/// Bytes of biased integers, with float arithmetic only (exact: every value is an integer
/// below 2^12 and every scale a power of two).
#[inline(always)]
pub fn bytes_float<F: Float>(u: V2<F>) -> V3<F> {
    let x16 = (u.x * F::c(1.0 / 16.0)).named("x16");
    let hi = x16.floor().named("hi");
    let t = (u.y * F::c(1.0 / 256.0)).floor().named("t");
    V3::new(hi, (x16 - hi) * F::c(256.0) + t, u.y - t * F::c(256.0))
}

/// Float-only pack (Listing 5): unorm8 values in [0, 1] for an RGB8 target.
#[inline(always)]
pub fn to_unorm8x3<F: Float>(f: V2<F>) -> V3<F> {
    bytes_float(biased(f)) * F::c(1.0 / 255.0)
}

/// Integer pack (Listing 4): the same values through shifts and masks.
#[inline(always)]
pub fn to_unorm8x3_int<F: Float>(f: V2<F>) -> V3<F> {
    let u = biased(f).to_u();
    let b = V3::new(
        u.x.shr(4),
        (u.x & F::U::c(15)).shl(4) | u.y.shr(8),
        u.y & F::U::c(255),
    );
    b.map(#[inline(always)] |x| x.to_f()) * F::c(1.0 / 255.0)
}

/// `(s - 2047)·(1/2047)`, clamped to [-1, 1].
#[inline(always)]
fn unbias<F: Float>(s: V2<F>) -> V2<F> {
    let f = (s - F::c(BIAS)) * F::c(1.0 / BIAS);
    f.at_most(F::c(1.0))
}

/// Float-only unpack (Listing 5) of unorm8 values as delivered by an RGB8 fetch.
#[inline(always)]
pub fn from_unorm8x3<F: Float>(u: V3<F>) -> V2<F> {
    from_bytes((u * F::c(255.0)).round().named("b"))
}

/// Float-only unpack of the three bytes, as integral floats.
#[inline(always)]
pub fn from_bytes<F: Float>(b: V3<F>) -> V2<F> {
    let y16 = (b.y * F::c(1.0 / 16.0)).named("y16");
    let hi = y16.floor().named("hi");
    let s = V2::new(b.x * F::c(16.0) + hi, (y16 - hi) * F::c(4096.0) + b.z);
    unbias(s)
}

/// Integer unpack (Listing 4).
#[inline(always)]
pub fn from_unorm8x3_int<F: Float>(u: V3<F>) -> V2<F> {
    let b = (u * F::c(255.0)).round().to_u().named("b");
    let p = V2::new(b.x.shl(4) | b.y.shr(4), (b.y & F::U::c(15)).shl(8) | b.z);
    unbias(p.to_f())
}
