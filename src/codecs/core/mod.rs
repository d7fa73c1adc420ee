//! What every codec shares and no codec's arithmetic, in dependency order (no module
//! names one after it):
//!
//! - [`error`]: what is wrong with a spec; [`info`]: what a family says about itself;
//! - [`function`]: the shader functions a spec emits as the registry holds them, and
//!   [`words`]: their evaluations on raw words and SIMD lanes;
//! - [`inputs`]: what every function is verified on; [`decode_boxes`]: enclosures over
//!   boxes of codes for the proven decoder bounds;
//! - [`spec`]: the spec grammar and the [`spec::Family`] trait every family implements;
//! - [`codec`]: what a codec is, and [`pipeline`]: the encode/decode pipeline every codec
//!   shares and the four functions of a codec spec;
//! - [`codec_family`]: the family of one codec type, which most families are;
//! - [`ieee`]: the lean tier (`guarantee=ieee`), a codec's encoders without the exact
//!   decisions that make them portable.

pub mod codec;
pub mod codec_family;
pub mod decode_boxes;
pub mod error;
pub mod function;
pub mod ieee;
pub mod info;
pub mod inputs;
pub mod pipeline;
pub mod spec;
pub mod words;
