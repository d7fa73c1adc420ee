//! How a spec's functions are evaluated and checked, apart from what a codec is
//! (`core`), in dependency order (no module names one after it):
//!
//! - [`function`]: the shader functions a spec emits as the registry holds them, and
//!   [`words`]: their evaluations on raw words and SIMD lanes;
//! - [`inputs`]: what every function is verified on; [`decode_boxes`]: enclosures over
//!   boxes of codes for the proven decoder bounds.
//!
//! This layer names the toolkit and the model, never `core`.

pub mod decode_boxes;
pub mod function;
pub mod inputs;
pub mod words;
