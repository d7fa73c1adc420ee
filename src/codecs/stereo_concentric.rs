//! `stereo` ([`super::hemi_stereo`]) with its disk mapped onto the square by the
//! concentric map ([`super::concentric`]): the survey's `stereo+concentric` rows.
//! This file is its entry in the registry and its CPU type.

use super::codec::Domain;
use super::concentric::Concentric;
use super::family::{Family, Info, Sizes};
use super::functions::{Emitted, codec_functions};
use super::hemi_stereo::HemiStereo;
use super::spec::{Spec, SpecError};

pub static FAMILY: StereoConcentricFamily = StereoConcentricFamily;

pub struct StereoConcentricFamily;

static INFO: Info = Info {
    name: "stereo_concentric",
    title: "stereographic hemisphere on the unit disk, concentric map to the square + hemisphere bit, unorm×2",
    sizes: Sizes::Total(&[16, 20, 22, 24, 32]),
    domain: Some(Domain::Sphere),
    precise: false,
    source: "Cigolle et al. 2014 §2 (stereo+concentric); Snyder and Mitchell 2001; Shirley and Chiu 1997",
    edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z; the equator (z = 0) is on the +Z side",
    decode_note: "every code lies on the disk, so every code decodes within its hemisphere, unit length up to rounding",
    options: &[],
};

impl Family for StereoConcentricFamily {
    fn info(&self) -> &'static Info {
        &INFO
    }
    fn emitted(&self, spec: &Spec) -> Emitted {
        codec_functions(spec, StereoConcentric::new(spec.bits()).expect("a valid size"))
    }
}

/// The `stereo_concentric` codec on the CPU.
pub type StereoConcentric = Concentric<HemiStereo>;

impl StereoConcentric {
    /// The codec with the given total bit budget; an invalid size is an error listing
    /// the allowed ones.
    #[inline(always)]
    pub fn new(bits: u32) -> Result<Self, SpecError> {
        Concentric::with(&INFO, bits)
    }
}
