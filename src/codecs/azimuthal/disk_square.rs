//! The three hemisphere-to-disk projections ([`super::stereo`], [`super::eqarea`],
//! [`super::eqdist`]) with their disk mapped onto the whole square by the concentric map
//! ([`super::concentric`]) or the elliptical grid map ([`super::ellipse`]): the survey's
//! `stereo+concentric` … `eqdist+ellipse` rows. A combination adds no arithmetic of its
//! own, so all six are one generic family, [`DiskSquare`], with one line each below.

use super::concentric::Concentric;
use super::ellipse::Ellipse;
use super::eqarea::HemiEqArea;
use super::eqdist::HemiEqDist;
use super::stereo::HemiStereo;
use crate::codecs::core::codec::Codec;
use crate::codecs::core::info::Domain;
use crate::codecs::core::info::{Info, Sizes, FloatForm, seam};
use crate::codecs::core::spec::Family;
use crate::codecs::functions::function::Emitted;
use crate::codecs::core::pipeline::codec_functions;
use crate::codecs::core::spec::{Spec, SpecError, Tracing};

/// A projection composed with a square map: the family's description and its functions,
/// traced from the combination's codec type.
pub struct DiskSquare {
    info: &'static Info,
    precise: bool,
    emitted: fn(&Spec) -> Emitted,
}

impl Family for DiskSquare {
    fn info(&self) -> &Info {
        self.info
    }
    fn precise(&self) -> bool {
        self.precise
    }
    fn emitted(&self, spec: &Spec, _: Tracing) -> Emitted {
        (self.emitted)(spec)
    }
}

/// Each combination: its family static, its CPU type, its name and survey row, and the
/// words its description takes from the projection and the map.
macro_rules! disk_square {
    ($(
        $family:ident: $cpu:ident = $map:ident<$projection:ident>, $name:literal, $row:literal,
        $projection_title:literal, $map_title:literal, $map_source:literal;
    )*) => {$(
        #[doc = concat!("The `", $name, "` family.")]
        pub static $family: DiskSquare = DiskSquare {
            info: &Info {
                name: $name,
                title: concat!(
                    $projection_title,
                    " hemisphere on the unit disk, ",
                    $map_title,
                    " to the square + hemisphere bit, unorm×2"
                ),
                sizes: Sizes::Total(&[16, 20, 22, 24, 32]),
                domain: Some(Domain::Sphere),
                source: concat!(
                    "Cigolle et al. 2014 §2 (",
                    $row,
                    "); Snyder and Mitchell 2001; ",
                    $map_source
                ),
                edge_policy: "input is normalized first; zero, NaN and infinite input encode \
                              as +Z; the equator (z = 0) is on the +Z side",
                decode_note: "every code lies on the disk, so every code decodes within its \
                              hemisphere, unit length up to rounding",
                float_form: FloatForm::Continuous { seam: seam::HEMISPHERE_BIT },
                options: &[],
            },
            precise: <$cpu as Codec>::EXACT_SEARCH,
            emitted: |spec| codec_functions(spec, $cpu::new(spec.bits()).expect("a valid size")),
        };

        #[doc = concat!("The `", $name, "` codec on the CPU.")]
        pub type $cpu = $map<$projection>;

        impl $cpu {
            /// The codec with the given total bit budget; an invalid size is an error
            /// listing the allowed ones.
            #[inline(always)]
            pub fn new(bits: u32) -> Result<Self, SpecError> {
                $map::with($family.info, bits)
            }
        }
    )*};
}

disk_square! {
    STEREO_CONCENTRIC: StereoConcentric = Concentric<HemiStereo>,
        "stereo_concentric", "stereo+concentric",
        "stereographic", "concentric map", "Shirley and Chiu 1997";
    EQAREA_CONCENTRIC: EqAreaConcentric = Concentric<HemiEqArea>,
        "eqarea_concentric", "eqarea+concentric",
        "Lambert equal-area", "concentric map", "Shirley and Chiu 1997";
    EQDIST_CONCENTRIC: EqDistConcentric = Concentric<HemiEqDist>,
        "eqdist_concentric", "eqdist+concentric",
        "azimuthal equidistant", "concentric map", "Shirley and Chiu 1997";
    STEREO_ELLIPSE: StereoEllipse = Ellipse<HemiStereo>,
        "stereo_ellipse", "stereo+ellipse",
        "stereographic", "elliptical grid map", "the elliptical grid map (Nowell 2005, Fong 2014)";
    EQAREA_ELLIPSE: EqAreaEllipse = Ellipse<HemiEqArea>,
        "eqarea_ellipse", "eqarea+ellipse",
        "Lambert equal-area", "elliptical grid map", "the elliptical grid map (Nowell 2005, Fong 2014)";
    EQDIST_ELLIPSE: EqDistEllipse = Ellipse<HemiEqDist>,
        "eqdist_ellipse", "eqdist+ellipse",
        "azimuthal equidistant", "elliptical grid map", "the elliptical grid map (Nowell 2005, Fong 2014)";
}
