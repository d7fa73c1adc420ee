//! Compact unit-vector ("normal") codecs, each written once as a Rust model from which
//! WGSL, GLSL, HLSL and C functions are emitted that compute the model's bits.
//!
//! The library has three faces:
//!
//! - [`Generator`] renders or writes includes for chosen specs ([`Spec`], parsed from
//!   strings such as `"oct24p"` or `"xy16:layout=dxt5nm"`) and languages ([`Lang`]), for
//!   a build script. Errors are a typed [`GenerateError`]; files are written atomically.
//! - [`api`] is the CPU side of the same model: typed encoders ([`api::Oct`],
//!   [`api::HemiOct`], … with [`api::CpuCodec::fast`] / [`api::CpuCodec::precise`]) over
//!   single vectors and slices, and [`api::Batch`], the same behind a spec string.
//! - [`codecs`] holds the models and their registry ([`codecs::FAMILIES`]); [`emit`]
//!   prints traced functions; with the default `verify` feature, `verify` runs them
//!   on Vulkan (lavapipe) and through the system C compiler against the model.
//!
//! ```
//! use unitpack::api::{CpuCodec, Oct};
//! use unitpack::{Generator, Lang};
//!
//! // The CPU encoder writes the code the shader encoder writes.
//! let oct = Oct::new(24).unwrap().precise();
//! let code: u32 = oct.encode([0.0, 0.6, 0.8]);
//! let v = oct.decode(code);
//! assert!((v[1] - 0.6).abs() < 1e-3);
//!
//! // The shader side: an include with the same spec's functions.
//! let wgsl = Generator::new().spec("oct24p").error_stats(false).render(Lang::Wgsl);
//! assert!(wgsl.unwrap().contains("fn unitpack_oct24p_decode("));
//! ```
//!
//! Without default features (`default-features = false`) the crate is the model, the
//! codecs, emission and the CPU API only: what a build script needs. The user guide is the
//! repository's `README.md`; contributors start at `docs/ARCHITECTURE.md`.

// The README's Rust examples run as doctests; kept out of the library's own build so that
// editing the README does not rebuild it.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;

pub mod api;
pub mod codecs;
pub mod generator;
pub mod measure;
pub mod support;

// The modules below are the tool's machinery, not API: they are public only because the
// integration tests in tests/ (which see nothing `pub(crate)`) and the binary reach them,
// so they are hidden from the documentation and may change in any release.
#[doc(hidden)]
#[cfg(feature = "cli")]
pub mod choice;
#[doc(hidden)]
#[cfg(feature = "cli")]
pub mod cli;
#[doc(hidden)]
pub mod emit;
#[doc(hidden)]
pub mod model;
#[doc(hidden)]
#[cfg(feature = "cli")]
pub mod report;
#[doc(hidden)]
#[cfg(feature = "verify")]
pub mod verify;

pub use codecs::{Spec, SpecError};
pub use emit::Lang;
pub use generator::{GenerateError, Generator, SpecInput};
