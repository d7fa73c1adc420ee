//! Each family's own tests, in a module named after the family (or the families) it
//! checks; what holds for every spec (conventions, verify, portability, figures) is in
//! the suite's other binaries. One binary, so that the suite links the library once for
//! all of them.

mod crytek_bfn;
mod eac;
mod engine;
mod eqarea_oct;
mod frames;
mod gltf;
mod godot;
mod ieee;
mod lambert;
mod latlongd;
mod oct;
mod oracles;
mod qtangent;
mod sfib;
mod smallest_three;
mod snorm12x2;
mod snorm3;
mod spherical_lut;
mod tangent_plane;
mod texel_layouts;
