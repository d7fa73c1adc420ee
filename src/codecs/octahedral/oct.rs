//! Octahedral encoding (survey §3.1–3.3, Meyer et al. 2010): project onto the octahedron
//! with the L1 norm, unfold the lower half over the diagonals, store snorm×2.

use crate::model::num::helper;
use crate::codecs::core::codec::{Codec, sign_not_zero};
use crate::codecs::core::info::Domain;
use crate::codecs::toolkit::exact::{canonical, floor_ratio, snorm_ratio_within};
use crate::codecs::core::info::{Info, OptDesc, OptKind, Sizes, FloatForm, seam};
use crate::codecs::core::spec::Family;
use crate::codecs::functions::function::Emitted;
use crate::codecs::core::ieee;
use crate::codecs::core::pipeline::codec_functions;
use crate::codecs::toolkit::lattice::{Closeness, fixed, nearest, search_doc};
use crate::codecs::component::snorm12x2::{BIAS, bytes_float, from_bytes, from_unorm8x3};
use crate::codecs::toolkit::quant::{Quant, Quants};
use crate::codecs::core::spec::{Spec, SpecError, Tracing};
use crate::model::{Bool, Float, V2, V3};

pub static FAMILY: OctFamily = OctFamily;

pub struct OctFamily;

static INFO: Info = Info {
    name: "oct",
    title: "octahedral, snorm×2",
    sizes: Sizes::Total(&[16, 20, 22, 24, 32]),
    domain: Some(Domain::Sphere),
    source: "Cigolle et al. 2014 (JCGT survey) §3.1–3.3",
    edge_policy: "input need not be unit length; zero, NaN and infinite input encode as +Z",
    decode_note: "every code decodes to a unit vector (normalized as v / sqrt(v·v))",
    float_form: FloatForm::Continuous { seam: seam::OCTAHEDRAL_FOLD },
    options: &[LAYOUT, ieee::OPTION],
};

const LAYOUT: OptDesc = OptDesc {
    key: "layout",
    help: "rgb8 stores oct24 as the survey's unorm8×3 bytes (snorm12×2 split into an RGB8 texel)",
    kind: OptKind::Choice(&["snorm", "rgb8"]),
};

/// Whether the spec asks for the `rgb8` layout (oct24 in three bytes).
fn rgb8(spec: &Spec) -> bool {
    spec.chose(&LAYOUT, "rgb8")
}

impl Family for OctFamily {
    fn info(&self) -> &Info {
        &INFO
    }
    fn precise(&self) -> bool {
        Oct::EXACT_SEARCH && Oct24Rgb8::EXACT_SEARCH
    }
    fn float_form(&self, spec: &Spec) -> FloatForm {
        if rgb8(spec) {
            FloatForm::Unfilterable {
                why: "its float form splits two 12-bit fields across three bytes",
                seam: seam::OCTAHEDRAL_FOLD,
            }
        } else {
            INFO.float_form
        }
    }
    fn validate(&self, spec: &Spec) -> Result<(), SpecError> {
        if rgb8(spec) && spec.bits() != 24 {
            return Err(SpecError::BadValue {
                key: "layout".into(),
                value: "rgb8".into(),
                why: "the rgb8 layout holds oct24 only".into(),
            });
        }
        ieee::validate(spec, rgb8(spec))
    }
    fn variants(&self) -> &'static [&'static str] {
        &["oct24:layout=rgb8", "oct16:guarantee=ieee"]
    }
    fn emitted(&self, spec: &Spec, _: Tracing) -> Emitted {
        if rgb8(spec) {
            codec_functions(spec, Oct24Rgb8)
        } else {
            ieee::functions(spec, Oct { bits: spec.bits() }, codec_functions)
        }
    }
    fn helper_doc(&self, name: &str) -> Option<String> {
        match name {
            "oct24_decode_float" => {
                Some("oct24 parameters (snorm12×2 values in [-1, 1]) → unit vector.".into())
            }
            "encode_codes" => Some(search_doc("the input's signs, unfolded below the equator")),
            "bytes_to_snorm12x2" => Some(
                "The three bytes of an RGB8 texel (integral values 0–255) → two snorm12 values in [-1, 1] (survey Listing 5, float-only).".into(),
            ),
            _ => None,
        }
    }
}

impl Oct {
    /// Octahedral with the given total bit budget; an invalid size is an error listing
    /// the allowed ones.
    pub fn new(bits: u32) -> Result<Oct, SpecError> {
        Ok(Oct {
            bits: INFO.check_bits(bits)?,
        })
    }
}

#[derive(Clone, Copy, Debug)]
pub struct Oct {
    pub bits: u32,
}

/// Folds a point of the square across the diagonals: `(1 - |p.yx|) · sign_not_zero(p)`.
#[inline(always)]
fn fold<F: Float>(p: V2<F>) -> V2<F> {
    ((V2::splat(F::c(1.0)) - p.yx().abs()) * sign_not_zero(p)).named("folded")
}

/// Sphere → square. Folds on encode when `z <= 0`. Input need not be unit length: when
/// the L1 norm overflows, the input is first scaled by 1/4 (exact at that magnitude), so
/// only zero, NaN and infinite input, whose L1 norm is not a positive finite number,
/// encode as +Z. For every other input the scale is 1 and the arithmetic is the survey's.
#[inline(always)]
pub fn oct_params<F: Float>(v: V3<F>) -> V2<F> {
    let w = fit_l1(v).named("w");
    let a = w.abs();
    let l1 = (a.x + a.y + a.z).named("l1");
    let ok = l1.gt(F::c(0.0)).and(l1.le(F::c(f32::MAX)));
    let p = (w.xy() / l1).named("p");
    let e = V2::sel_all(w.z.le(F::c(0.0)), fold(p), p);
    V2::sel_all(ok, e, V2::splat(F::c(0.0)))
}

/// [`oct_params`] in plain arithmetic (the lean tier): the survey's projection. A
/// quotient's magnitude is at most 1 (`|x| ≤ l1`, and rounding is monotonic), so
/// `|p.x| + l1 ≤ MAX` fails exactly where `l1` is not a finite `f32` or a quotient is NaN:
/// for zero, NaN and infinite input, and finite input whose L1 norm overflows, all of
/// which give `(0, 0)`, +Z's code, at the cost of one add and one compare.
#[inline(always)]
pub fn oct_params_ieee<F: Float>(v: V3<F>) -> V2<F> {
    let a = v.abs();
    let l1 = (a.x + a.y + a.z).named("l1");
    let p = (v.xy() / l1).named("p");
    let ap = p.abs();
    let ok = (ap.x + l1).le(F::c(f32::MAX));
    let folded = (V2::splat(F::c(1.0)) - ap.yx()) * sign_not_zero(p);
    let e = V2::sel_all(v.z.le(F::c(0.0)), folded, p);
    V2::sel_all(ok, e, V2::splat(F::c(0.0)))
}

/// `v`, or `v/4` when its L1 norm overflows f32 (then every component that matters is far
/// above the denormal range, so the scaling is exact where it counts), or `v·2^100` when
/// the norm is below `2^-100` (exact): no denormal norm then reaches the division, where an
/// implementation may flush it to zero though not in the comparisons (`0/0` is NaN).
#[inline(always)]
pub fn fit_l1<F: Float>(v: V3<F>) -> V3<F> {
    let a = v.abs();
    let l1 = (a.x + a.y + a.z).named("norm1");
    let up = crate::codecs::toolkit::exact::denormal_proof_scale(l1);
    v * F::sel(l1.le(F::c(f32::MAX)), up, F::c(0.25)).named("fit")
}

/// Square → unit vector. Unfolds when `z < 0`; the result is normalized as `v / sqrt(v·v)`.
#[inline(always)]
pub fn oct_direction<F: Float>(e: V2<F>) -> V3<F> {
    let a = e.abs();
    let z = (F::c(1.0) - a.x - a.y).named("z");
    let xy = V2::sel_all(z.lt(F::c(0.0)), fold(e), e);
    let v = V3::from_xy(xy, z).named("v");
    v / v.length_squared().sqrt()
}

/// The nearest snorm codes of [`oct_params`], decided portably ([`crate::codecs::toolkit::exact`]):
/// each parameter is a ratio `n / l1` of correctly rounded sums of the canonical input's
/// magnitudes, `x / l1` above the equator and `(l1 - |y|)·sign(x) / l1` folded below it.
#[inline(always)]
pub fn oct_codes<F: Float>(q: Quant, v: V3<F>) -> V2<F> {
    let (w, ok) = canonical(v);
    let a = w.abs();
    let l1 = (a.x + a.y + a.z).named("l1");
    let folded = (V2::splat(l1) - a.xy().yx()) * sign_not_zero(w.xy());
    let n = V2::sel_all(w.z.le(F::c(0.0)), folded, w.xy()).named("n");
    let c = n.map(#[inline(always)] |x| snorm_ratio_within(q, x, l1));
    V2::sel_all(ok, c, V2::splat(F::c(0.0)))
}

/// The octahedral codes nearest the input, decided portably: the first octant's lattice
/// point `(s, t, M - s - t)` nearest `(|x|, |y|, |z|)` in angle among the four around
/// `floor(M·(|x|, |y|) / l1)` (the first on ties), then the input's signs, unfolded
/// below the equator: `(±s, ±t)` above, `(±(M - t), ±(M - s))` below, whose decode has
/// the same magnitudes with a negative `z`. Zero, NaN and infinite input give `(0, 0)`.
#[inline(always)]
pub fn oct_nearest_codes<F: Float>(q: Quant, v: V3<F>) -> V2<F> {
    let m = q.max_code();
    let mf = F::c(m);
    let (w, ok) = canonical(v);
    // Invalid input searches around +Z instead, so that every conversion to an integer
    // below stays in range (a NaN or negative float has no defined u32 in C).
    let a = V3::sel_all(ok, w.abs(), V3::new(F::c(0.0), F::c(0.0), F::c(2.0))).named("a");
    let l1 = (a.x + a.y + a.z).named("l1");
    let s0 = floor_ratio(q, a.x, l1).named("s0");
    // Rounded comparisons could put the floors one past the equator together.
    let t0 = floor_ratio(q, a.y, l1).at_most(mf - s0).named("t0");
    let fixed = fixed(a);
    let best = nearest(s0, t0, #[inline(always)] |s, t| {
        let u = (mf - s - t).at_least(F::c(0.0));
        let c = Closeness::of(fixed, V3::new(s.to_u(), t.to_u(), u.to_u()), m);
        (V2::new(s, t), (s + t).le(mf), c)
    });
    let below = w.z.lt(F::c(0.0));
    let st = V2::sel_all(below, (V2::splat(mf) - best.yx()).named("folded"), best);
    let signed = V2::sel(w.xy().lt(V2::splat(F::c(0.0))), -st, st);
    V2::sel_all(ok, signed, V2::splat(F::c(0.0)))
}

impl Codec for Oct {
    type P<F: Float> = V2<F>;
    type C<F: Float> = F::U;
    #[inline]
    fn quants(&self) -> Quants {
        Quants::new(&[Quant::Snorm(self.bits / 2); 2])
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V2<F> {
        oct_params(v)
    }
    #[inline(always)]
    fn ieee_params<F: Float>(&self, v: V3<F>) -> V2<F> {
        oct_params_ieee(v)
    }
    /// [`oct_params_ieee`]'s parameters are in `[-1, 1]` and never NaN.
    const IEEE_IN_RANGE: bool = true;
    #[inline(always)]
    fn direction<F: Float>(&self, p: V2<F>) -> V3<F> {
        oct_direction(p)
    }
    const EXACT_ROUNDING: bool = true;
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V2<F> {
        oct_codes(self.quants()[0], v)
    }
    const EXACT_SEARCH: bool = true;
    #[inline(always)]
    fn precise_codes<F: Float>(&self, v: V3<F>) -> V2<F> {
        oct_nearest_codes(self.quants()[0], v)
    }
}

/// oct24 in the three bytes of an RGB8 texel (survey §3.3). The float form is the
/// three unorm8 values; the packed form is the RGB8 texel (R in the lowest byte).
#[derive(Clone, Copy, Debug)]
pub struct Oct24Rgb8;

impl Codec for Oct24Rgb8 {
    type P<F: Float> = V3<F>;
    type C<F: Float> = F::U;
    #[inline]
    fn quants(&self) -> Quants {
        Quants::new(&[Quant::Unorm(8); 3])
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    /// The bytes of the portable oct24 codes as unorm8 values: already quantized, so a
    /// render target stores exactly the packed code's bytes.
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V3<F> {
        helper!(self.round_codes(v)) * F::c(1.0 / 255.0)
    }
    #[inline(always)]
    fn direction<F: Float>(&self, u: V3<F>) -> V3<F> {
        let e = helper!("unorm8x3_to_snorm12x2" => from_unorm8x3(u)).named("e");
        helper!("oct24_decode_float" => oct_direction(e))
    }
    /// The middle byte holds the low bits of one parameter and the high bits of the other.
    fn whole_field(&self) -> Option<usize> {
        Some(1)
    }
    /// The bytes are already integers: unpacking them with the float-only form directly
    /// skips a `c·(1/255)·255` round trip (which drivers would fold across the call).
    #[inline(always)]
    fn decode_codes<F: Float>(&self, b: V3<F>) -> V3<F> {
        let e = helper!("bytes_to_snorm12x2" => from_bytes(b)).named("e");
        helper!("oct24_decode_float" => oct_direction(e))
    }
    const EXACT_ROUNDING: bool = true;
    /// The portable oct24 codes, split into bytes.
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V3<F> {
        bytes_float(oct_codes(Quant::Snorm(12), v) + F::c(BIAS))
    }
    const EXACT_SEARCH: bool = true;
    /// The oct24 precise search, then its 12-bit codes split into bytes.
    #[inline(always)]
    fn precise_codes<F: Float>(&self, v: V3<F>) -> V3<F> {
        bytes_float(oct_nearest_codes(Quant::Snorm(12), v) + F::c(BIAS))
    }
}
