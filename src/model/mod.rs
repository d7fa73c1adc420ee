//! The model: the numeric vocabulary codecs are written in, small vectors over it, the
//! tracer that turns a codec into an expression graph, and the adversarial evaluator that
//! runs a codec the way a conformant GPU may.

#[cfg(target_arch = "x86_64")]
pub mod avx2_lanes;
/// Off x86-64 the eight-lane evaluation is compiled on the four SSE2/NEON lanes, and never
/// run: [`avx2_lanes::available`] is false.
#[cfg(not(target_arch = "x86_64"))]
pub mod avx2_lanes {
    pub(crate) use super::lanes::{F4 as F8, U4 as U8};
    /// Lanes per evaluation.
    pub(crate) const WIDTH: usize = 4;
    pub fn available() -> bool {
        false
    }
    pub fn avx512_available() -> bool {
        false
    }
    pub fn operations(_: [f32; 8], _: [f32; 8]) -> Option<Vec<(&'static str, [u32; 8])>> {
        None
    }
}
pub mod deviant;
pub mod enclosure;
pub mod lanes;
pub mod num;
pub mod trace;
pub mod vec;

pub use num::{Bool, Float, Kind, Lane, Uint};
pub use vec::{V2, V3, V4, each};
