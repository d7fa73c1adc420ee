//! What a codec and a codec family are, and no codec's arithmetic, in dependency order
//! (no module names one after it). How their functions are evaluated and checked is the
//! layer below ([`crate::codecs::functions`]); the toolkit is below both.
//!
//! - [`error`]: what is wrong with a spec; [`info`]: what a family says about itself;
//! - [`spec`]: the spec grammar and the [`spec::Family`] trait every family implements;
//! - [`codec`]: what a codec is, and [`pipeline`]: the encode/decode pipeline every codec
//!   shares and the four functions of a codec spec;
//! - [`codec_family`]: the family of one codec type, which most families are;
//! - [`texel`]: normal-map texel layouts, a projection's functions in an RGBA8 texel;
//! - [`storage`]: the real formats a spec's code and float form are stored in, and what
//!   each costs and stores;
//! - [`ieee`]: the lean tier (`guarantee=ieee`), a codec's encoders without the exact
//!   decisions that make them portable.

pub mod codec;
pub mod codec_family;
pub mod error;
pub mod ieee;
pub mod info;
pub mod pipeline;
pub mod spec;
pub mod storage;
pub mod texel;
