//! `eqarea` ([`super::hemi_eqarea`]) with its disk mapped onto the square by the
//! elliptical grid map ([`super::ellipse`]): the survey's `eqarea+ellipse` rows.
//! This file is its entry in the registry and its CPU type.

use super::codec::Domain;
use super::ellipse::Ellipse;
use super::family::{Family, Info, Sizes};
use super::functions::{Emitted, codec_functions};
use super::hemi_eqarea::HemiEqArea;
use super::spec::{Spec, SpecError};

pub static FAMILY: EqAreaEllipseFamily = EqAreaEllipseFamily;

pub struct EqAreaEllipseFamily;

static INFO: Info = Info {
    name: "eqarea_ellipse",
    title: "Lambert equal-area hemisphere on the unit disk, elliptical grid map to the square + hemisphere bit, unorm×2",
    sizes: Sizes::Total(&[16, 20, 22, 24, 32]),
    domain: Some(Domain::Sphere),
    precise: false,
    source: "Cigolle et al. 2014 §2 (eqarea+ellipse); Snyder and Mitchell 2001; the elliptical grid map (Nowell 2005, Fong 2014)",
    edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z; the equator (z = 0) is on the +Z side",
    decode_note: "every code lies on the disk, so every code decodes within its hemisphere, unit length up to rounding",
    options: &[],
};

impl Family for EqAreaEllipseFamily {
    fn info(&self) -> &'static Info {
        &INFO
    }
    fn emitted(&self, spec: &Spec) -> Emitted {
        codec_functions(spec, EqAreaEllipse::new(spec.bits()).expect("a valid size"))
    }
}

/// The `eqarea_ellipse` codec on the CPU.
pub type EqAreaEllipse = Ellipse<HemiEqArea>;

impl EqAreaEllipse {
    /// The codec with the given total bit budget; an invalid size is an error listing
    /// the allowed ones.
    #[inline(always)]
    pub fn new(bits: u32) -> Result<Self, SpecError> {
        Ellipse::with(&INFO, bits)
    }
}
