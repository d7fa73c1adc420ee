//! The pieces codecs are built from.
//!
//! - [`quant`]: scalar quantization (survey eqs. 1–2) and bit-field packing;
//!   [`half`]: binary16 fields without pack builtins.
//! - [`exact`]: portable quantization, codes decided by operations every implementation
//!   computes identically; [`lattice`] and [`fixed_decode`]: the portable precise search.
//! - [`trig`]: the model's own polynomial trigonometry; [`fixed_trig`]: fixed-point
//!   trigonometry for codes that must not depend on division or contraction.
//! - [`texel`]: normal-map texel layouts.
//!
//! docs/ARCHITECTURE.md ("A portable encoder") shows how a family's packed encoder is made
//! portable from these pieces.

pub mod exact;
pub mod fixed_decode;
pub mod fixed_trig;
pub mod half;
pub mod lattice;
pub mod quant;
pub mod texel;
pub mod trig;
