//! unitpack: compact unit-vector codecs, defined once in Rust, emitted as WGSL, GLSL and
//! HLSL, and proven to compute the same bits as the Rust model.

pub mod api;
pub mod cli;
pub mod codecs;
pub mod emit;
pub mod model;
pub mod quality;
pub mod verify;
