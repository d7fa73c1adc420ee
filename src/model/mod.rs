//! The model: the numeric vocabulary codecs are written in, small vectors over it, the
//! tracer that turns a codec into an expression graph, and the adversarial evaluator that
//! runs a codec the way a conformant GPU may.

pub mod deviant;
pub mod enclosure;
pub mod lanes;
pub mod num;
pub mod trace;
pub mod vec;

pub use num::{Bool, Float, Kind, Lane, Uint};
pub use vec::{V2, V3, V4};
