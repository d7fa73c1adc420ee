//! The pieces codecs are built from, and in particular the ones a **portable packed
//! encoder** is built from (tests/portability.rs holds every family's packed encoder to
//! the same codes under every deviation the APIs allow, so a new family needs one).
//!
//! | piece | what it decides exactly |
//! |---|---|
//! | [`exact::canonical`] | the input brought to a normal-only form (denormals and negligible components `+0`, scaled by a power of two), with whether it has a direction |
//! | [`exact::snorm_ratio_within`] | the nearest snorm code of a ratio `n / d` of correctly rounded sums (`|n| ≤ d`) |
//! | [`exact::floor_ratio`] | `floor(n / d · M)`, where a precise search starts |
//! | [`exact::decided`] | any code from an estimate and a `past(c)` test "is the value past `c + ½`", built from single products |
//! | [`exact::past_root_ratio`] | that test for a ratio under a square root |
//! | [`fixed_trig::atan2_pi`] | an angle as an exact integer (fixed point), for maps that split by azimuth |
//! | `azimuthal::disk::Radius::past` | whether `r·x` passes a code boundary, `r` a projection's disk radius |
//! | `azimuthal::concentric::Concentric::codes` | the concentric map's two codes from `r` and the exact angle |
//! | [`lattice`], [`fixed_decode`] | the precise (nearest-code) search in integer or fixed-point arithmetic |
//!
//! The rest: [`quant`] (scalar quantization, survey eqs. 1–2, and bit-field packing),
//! [`half`] (binary16 fields without pack builtins), [`index`] (a point's index in two
//! fields) and [`trig`] (the model's own polynomial
//! trigonometry for decoders). Nothing here names `core`: the toolkit is the layer below it.
//!
//! # Example: `oct`'s packed encoder
//!
//! The survey's encoder rounds `x / l1 · M`, which a driver may compute a few ULP away
//! and round to the other code. `octahedral::oct::oct_codes` instead writes each
//! parameter as a ratio of correctly rounded sums and lets the toolkit decide the code:
//!
//! ```text
//! let (w, ok) = canonical(v);                          // normal-only input
//! let a = w.abs();
//! let l1 = a.x + a.y + a.z;                            // |n| <= l1 by monotone rounding
//! let folded = (V2::splat(l1) - a.xy().yx()) * sign_not_zero(w.xy());
//! let n = V2::sel_all(w.z.le(0.0), folded, w.xy());
//! let c = n.map(|x| snorm_ratio_within(q, x, l1));     // decided by products only
//! V2::sel_all(ok, c, V2::splat(0.0))                   // zero, NaN, inf: +Z
//! ```
//!
//! and declares `const EXACT_ROUNDING: bool = true` on its `Codec` impl. A map with an
//! angle (`azimuthal::concentric`, `octahedral::eqarea_oct`) takes the angle from
//! [`fixed_trig::atan2_pi`] and decides each boundary with `Radius::past`; a map with a
//! root takes [`exact::past_root_ratio`]. docs/ARCHITECTURE.md has the contributor steps.

pub mod exact;
pub mod fixed_decode;
pub mod fixed_trig;
pub mod half;
pub mod index;
pub mod lattice;
pub mod quant;
pub mod trig;
