//! The codecs, each written once against the model's vocabulary in a file of its own,
//! plus the machinery they share: quantization and packing, the precise search, the
//! registry and the spec grammar, and the list of shader functions each spec emits.
//!
//! Adding a codec is one new file (its description, options, variants and arithmetic,
//! ending in a `pub static FAMILY`) and one line in `registry!` below.

pub mod codec;
pub mod concentric;
pub mod disk;
pub mod ellipse;
pub mod exact;
pub mod family;
pub mod fixed_decode;
pub mod fixed_trig;
pub mod functions;
pub mod half;
pub mod inputs;
pub mod lattice;
pub mod quant;
pub mod spec;
pub mod texel;
pub mod trig;

pub use codec::Codec;
pub use family::{Family, Info};
pub use spec::{Spec, SpecError};

/// Declares each codec's module, lists its family in [`FAMILIES`] (in `list` order) and
/// exports its CPU types through [`cpu`].
macro_rules! registry {
    ($($module:ident $(=> $($cpu:ident),+)?;)*) => {
        $(pub mod $module;)*
        /// Every codec family, in the order `list` shows them.
        pub static FAMILIES: &[&dyn Family] = &[$(&$module::FAMILY),*];
        /// The codec types the CPU API offers.
        pub mod cpu {
            $($(pub use super::$module::{$($cpu),+};)?)*
            pub use super::texel::{Layout, Texel};
        }
    };
}

registry! {
    oct => Oct, Oct24Rgb8;
    hemioct => HemiOct;
    eqarea_oct => EqAreaOct;
    snorm3 => Snorm3, OneWord, TwoWords;
    snorm11_11_10;
    unorm3 => Unorm3;
    float3 => Float16x3, Float32x3;
    spherical => Spherical;
    lambert => Lambert;
    spheremap => Spheremap;
    cry3 => Cry3;
    stereo => StereoScaled;
    hemi_stereo => HemiStereo;
    hemi_eqarea => HemiEqArea;
    hemi_eqdist => HemiEqDist;
    stereo_concentric => StereoConcentric;
    eqarea_concentric => EqAreaConcentric;
    eqdist_concentric => EqDistConcentric;
    stereo_ellipse => StereoEllipse;
    eqarea_ellipse => EqAreaEllipse;
    eqdist_ellipse => EqDistEllipse;
    cube => Cube;
    warpedcube;
    xy => Xy;
    xy_signz => XySignZ;
    xy_stereo => XyStereo;
    paraboloid => Paraboloid;
    paraboloid_square => ParaboloidSquare;
    paraboloid_pd => combine_paraboloid_pd;
    spherical_z => SphericalZ;
    spherical_lut => SphericalLut;
    sfib => Sfib;
    latlong => Latlong;
    latlongd;
    crytek_bfn;
    pack12;
}

/// Doc comments of the helpers every codec may call (the precise search, the model's
/// trigonometry) and of any family's own helpers.
pub fn helper_doc(first: &dyn Family, name: &str) -> Option<String> {
    first
        .helper_doc(name)
        .or_else(|| codec::helper_doc(name))
        .or_else(|| trig::helper_doc(name))
        .or_else(|| FAMILIES.iter().find_map(|f| f.helper_doc(name)))
}
