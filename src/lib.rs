#![doc = include_str!("../README.md")]

pub mod api;
pub mod atomic;
#[cfg(feature = "cli")]
pub mod cli;
pub mod codecs;
pub mod decode_bound;
pub mod doc_tables;
pub mod emit;
pub mod generator;
mod memo;
pub mod model;
pub mod par;
pub mod portability;
pub mod quality;
pub mod sampling;
#[cfg(feature = "verify")]
pub mod verify;

pub use codecs::{Spec, SpecError};
pub use emit::Lang;
pub use generator::{GenerateError, Generator, SpecInput};
