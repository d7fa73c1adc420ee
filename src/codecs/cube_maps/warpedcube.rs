//! The warped cube-map codec (survey §2, `warpedcube`; ISO/IEC 2005): [`crate::codecs::cube_maps::cube`]'s
//! layout with equi-angular coordinates on each face. Its arithmetic is
//! [`crate::codecs::cube_maps::cube::Cube`] with `warped` set; this file is its entry in the registry.

use crate::codecs::core::info::Domain;
use crate::codecs::cube_maps::cube::Cube;
use crate::codecs::core::info::{Info, Sizes, FloatForm, seam};
use crate::codecs::core::codec_family::CodecFamily;
use crate::codecs::toolkit::fixed_decode::{BITS, search_doc};
use crate::codecs::core::pipeline::codec_functions;

pub static FAMILY: CodecFamily<Cube> = CodecFamily::new(
    Info {
        name: "warpedcube",
        title: "cube-map face (3 bits) + equi-angular unorm×2 coordinates, atan(s)/(π/4)",
        sizes: Sizes::Total(&[16, 24, 32]),
        domain: Some(Domain::Sphere),
        source: "Cigolle et al. 2014 §2 (warpedcube; ISO/IEC 2005); the equi-angular warp",
        edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z; ties between components go to z, then y",
        decode_note: "decodes are unit length to within the trig approximations' error (about 2.5e-7); faces 6 and 7 are never written and decode as +Z and -Z",
        float_form: FloatForm::Continuous { seam: seam::CUBE_FACES },
        options: &[],
    },
    |bits| Cube::of(bits, true),
    codec_functions,
)
.with_helper_doc(|name| (name == "encode_codes").then(|| search_doc(BITS)));

