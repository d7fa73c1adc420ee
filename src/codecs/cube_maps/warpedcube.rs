//! The warped cube-map codec (survey §2, `warpedcube`; ISO/IEC 2005): [`crate::codecs::cube_maps::cube`]'s
//! layout with equi-angular coordinates on each face. Its arithmetic is
//! [`crate::codecs::cube_maps::cube::Cube`] with `warped` set; this file is its entry in the registry.

use crate::codecs::core::codec::Domain;
use crate::codecs::cube_maps::cube::Cube;
use crate::codecs::core::codec::Codec;
use crate::codecs::core::info::{Info, Sizes};
use crate::codecs::core::spec::Family;
use crate::codecs::toolkit::fixed_decode::{BITS, search_doc};
use crate::codecs::core::function::Emitted;
use crate::codecs::core::pipeline::codec_functions;
use crate::codecs::core::spec::Spec;

pub static FAMILY: WarpedCubeFamily = WarpedCubeFamily;

pub struct WarpedCubeFamily;

static INFO: Info = Info {
    name: "warpedcube",
    title: "cube-map face (3 bits) + equi-angular unorm×2 coordinates, atan(s)/(π/4)",
    sizes: Sizes::Total(&[16, 24, 32]),
    domain: Some(Domain::Sphere),
    source: "Cigolle et al. 2014 §2 (warpedcube; ISO/IEC 2005); the equi-angular warp",
    edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z; ties between components go to z, then y",
    decode_note: "decodes are unit length to within the trig approximations' error (about 2.5e-7); faces 6 and 7 are never written and decode as +Z and -Z",
    options: &[],
};

impl Family for WarpedCubeFamily {
    fn info(&self) -> &'static Info {
        &INFO
    }
    fn precise(&self) -> bool {
        Cube::EXACT_SEARCH
    }
    fn helper_doc(&self, name: &str) -> Option<String> {
        (name == "encode_codes").then(|| search_doc(BITS))
    }
    fn emitted(&self, spec: &Spec) -> Emitted {
        codec_functions(spec, Cube::of(spec.bits(), true))
    }
}
