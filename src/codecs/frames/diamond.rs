//! Diamond: the normal as an octahedral code and the tangent's direction in the plane
//! orthogonal to the decoded normal as Jeremy Ong's diamond code (a ratio on the unit
//! diamond, no trigonometry), around his basis of that normal, with the bitangent's sign
//! in one bit: 32 bits, 11 + 11 + 9 + 1. The shared arithmetic is in
//! [`crate::codecs::frames::tangent_plane`].

use crate::codecs::core::info::{Info, Sizes, FloatForm};
use crate::codecs::frames::tangent_plane::{DECODE_NOTE, EDGE_POLICY, TangentPlane, Turn};

pub static DIAMOND: TangentPlane = TangentPlane::new(
    Info {
        name: "diamond",
        title: "octahedral normal and the tangent's diamond-encoded direction around a basis of the decoded normal, and the sign",
        sizes: Sizes::Total(&[32]),
        domain: None,
        source: "Jeremy Ong, \"Tangent spaces and diamond encoding\" (2023): the basis and the diamond; the normal: octahedral (Meyer et al. 2010)",
        edge_policy: EDGE_POLICY,
        decode_note: DECODE_NOTE,
        float_form: FloatForm::Absent,
        options: &[],
    },
    Turn::Diamond,
);
