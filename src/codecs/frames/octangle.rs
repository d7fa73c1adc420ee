//! Octangle: the normal as an octahedral code and the tangent as its angle in the plane
//! orthogonal to the decoded normal, around Ong's basis of that normal, with the
//! bitangent's sign in one bit. 32 bits (11 + 11 + 9 + 1) and 48 bits (16 + 16 + 15 + 1);
//! the shared arithmetic and the layouts' reasons are in
//! [`crate::codecs::frames::tangent_plane`].

use crate::codecs::core::info::{Info, Sizes, FloatForm};
use crate::codecs::frames::tangent_plane::{DECODE_NOTE, EDGE_POLICY, TangentPlane, Turn};

pub static OCTANGLE: TangentPlane = TangentPlane::new(
    Info {
        name: "octangle",
        title: "octahedral normal and the tangent's angle around a basis of the decoded normal, and the sign",
        sizes: Sizes::Total(&[32, 48]),
        domain: None,
        source: "the normal: octahedral (Meyer et al. 2010, Cigolle et al. 2014); the tangent's basis: Jeremy Ong, \"Tangent spaces and diamond encoding\" (2023)",
        edge_policy: EDGE_POLICY,
        decode_note: DECODE_NOTE,
        float_form: FloatForm::Absent,
        options: &[],
    },
    Turn::Angle,
);
