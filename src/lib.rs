#![doc = include_str!("../README.md")]

pub mod api;
pub mod codecs;
pub mod generator;
pub mod quality;
pub mod sampling;

// The modules below are the tool's machinery, not API: they are public only because the
// integration tests in tests/ (which see nothing `pub(crate)`) and the binary reach them,
// so they are hidden from the documentation and may change in any release.
#[doc(hidden)]
pub mod atomic;
#[doc(hidden)]
#[cfg(feature = "cli")]
pub mod cli;
#[doc(hidden)]
pub mod decode_bound;
#[doc(hidden)]
pub mod doc_tables;
#[doc(hidden)]
pub mod emit;
mod memo;
#[doc(hidden)]
pub mod model;
#[doc(hidden)]
pub mod par;
#[doc(hidden)]
pub mod portability;
#[doc(hidden)]
#[cfg(feature = "verify")]
pub mod verify;

pub use codecs::{Spec, SpecError};
pub use emit::Lang;
pub use generator::{GenerateError, Generator, SpecInput};
