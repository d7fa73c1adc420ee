//! The codecs, each written once against the model's vocabulary, plus the machinery they
//! share: quantization and packing, the precise search, the catalogue and spec syntax,
//! and the list of shader functions each spec emits.

pub mod catalogue;
pub mod codec;
pub mod functions;
pub mod hemioct;
pub mod lambert;
pub mod oct;
pub mod pack12;
pub mod quant;
pub mod snorm3;
pub mod spherical;
pub mod stereo;
pub mod trig;
pub mod xy;

pub use catalogue::{CATALOGUE, Spec, SpecError};
pub use codec::Codec;
