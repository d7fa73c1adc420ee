//! The codecs, each written once against the model's vocabulary in a file of its own and
//! grouped by kind, plus the machinery they share:
//!
//! - [`core`]: what a codec and a codec family are, and the spec grammar;
//! - [`functions`]: the shader functions a spec emits, with their evaluations, verify
//!   inputs and enclosures (how they are checked and proven);
//! - [`toolkit`]: quantization and packing, exact (portable) arithmetic, the precise
//!   search, fixed-point and polynomial trigonometry — the pieces a codec is built from;
//! - one folder per kind of codec: [`octahedral`], [`component`] (per-component),
//!   [`angular`] (spherical angles and point sets), [`azimuthal`] (hemisphere-to-disk
//!   projections and their square maps), [`cube_maps`], [`table`] (table-driven) and [`engine`] (engines' own formats).
//!
//! Adding a codec is one new file in its kind's folder (its description, options,
//! variants and arithmetic, ending in a `pub static FAMILY`) and one line in
//! `registry!` below; docs/ARCHITECTURE.md has the steps.

// Machinery and the families' own modules are not API (the CPU types are, through
// [`cpu`] and `crate::api`); public for the integration tests and the binary.
#[doc(hidden)]
pub mod core;
#[doc(hidden)]
pub mod functions;
#[doc(hidden)]
pub mod toolkit;

pub use self::core::codec::Codec;
pub use self::core::info::Info;
pub use self::core::spec::Family;
pub use self::core::spec::{Spec, SpecError};

/// Declares the kinds' folders and their modules (the shared ones in parentheses), lists
/// each module's families (in brackets) in [`FAMILIES`] in `list` order, and exports the
/// codecs' CPU types through [`cpu`].
macro_rules! registry {
    ($(
        $(#[doc = $doc:literal])*
        $kind:ident $(($($shared:ident),+))? {
            $($module:ident [$($family:ident),+] $(=> $($cpu:ident),+)?;)*
        }
    )*) => {
        $(
            $(#[doc = $doc])*
            #[doc(hidden)]
            pub mod $kind {
                $($(pub mod $shared;)+)?
                $(pub mod $module;)*
            }
        )*
        /// Every codec family, in the order `list` shows them.
        pub static FAMILIES: &[&dyn Family] = &[$($($(&$kind::$module::$family),+),*),*];
        /// The file that models each of [`FAMILIES`], relative to the crate's root.
        static SOURCES: &[&str] = &[$($($({
            let _ = stringify!($family);
            concat!("src/codecs/", stringify!($kind), "/", stringify!($module), ".rs")
        }),+),*),*];
        /// The codec types the CPU API offers.
        pub mod cpu {
            $($($(pub use super::$kind::$module::{$($cpu),+};)?)*)*
            pub use super::core::texel::{Layout, Texel};
        }
    };
}

registry! {
    /// Octahedral maps: the sphere onto the octahedron, unfolded onto a square.
    octahedral {
        oct [FAMILY] => Oct, Oct24Rgb8;
        hemioct [FAMILY] => HemiOct;
        eqarea_oct [FAMILY] => EqAreaOct;
    }
    /// Per-component codes: the vector's components (or two of them) quantized one by one,
    /// and the packing helpers of such fields.
    component {
        snorm3 [FAMILY] => Snorm3, OneWord, TwoWords;
        snorm11_11_10 [FAMILY];
        unorm3 [FAMILY] => Unorm3;
        float3 [FAMILY] => Float16x3, Float32x3;
        xy [FAMILY] => Xy;
        xy_signz [FAMILY] => XySignZ;
        snorm12x2 [FAMILY];
        gltf_normal [FAMILY] => GltfNormal;
    }
    /// Spherical angles (azimuth and polar angle or z), latitude rings and point sets.
    angular {
        spherical [FAMILY] => Spherical;
        spherical_z [FAMILY] => SphericalZ;
        latlong [FAMILY] => Latlong;
        latlongd [FAMILY];
        sfib [FAMILY] => Sfib;
    }
    /// Azimuthal projections of a hemisphere (or the sphere) onto a disk or plane, and the
    /// maps of the disk onto the square.
    azimuthal (disk, concentric, ellipse) {
        lambert [FAMILY] => Lambert;
        spheremap [FAMILY] => Spheremap;
        cry3 [FAMILY] => Cry3;
        stereo_scaled [FAMILY] => StereoScaled;
        stereo [FAMILY] => HemiStereo;
        eqarea [FAMILY] => HemiEqArea;
        eqdist [FAMILY] => HemiEqDist;
        disk_square [
            STEREO_CONCENTRIC, EQAREA_CONCENTRIC, EQDIST_CONCENTRIC,
            STEREO_ELLIPSE, EQAREA_ELLIPSE, EQDIST_ELLIPSE
        ] => StereoConcentric, EqAreaConcentric, EqDistConcentric,
            StereoEllipse, EqAreaEllipse, EqDistEllipse;
        xy_stereo [FAMILY] => XyStereo;
        paraboloid [FAMILY] => Paraboloid;
        paraboloid_square [FAMILY] => ParaboloidSquare;
        paraboloid_pd [FAMILY] => combine_paraboloid_pd;
    }
    /// Cube maps: a face index and two coordinates on that face.
    cube_maps (faces) {
        cube [FAMILY] => Cube;
        warpedcube [FAMILY];
        eac [FAMILY] => Eac;
    }
    /// Table-driven codecs: lookup textures and fitting tables the shader reads.
    table {
        spherical_lut [FAMILY] => SphericalLut;
        crytek_bfn [FAMILY];
    }
    /// Engine formats: the bits an engine's or a format's own encoder stores, read as its
    /// decoder reads them, in the engine's arithmetic (the lean tier is their only one).
    engine (draco_f64) {
        meshopt [MESHOPT_OCT8, MESHOPT_OCT16] => MeshoptOct;
        bevy [FAMILY] => BevyOct;
        unity [FAMILY] => UnityOct;
        draco [FAMILY] => DracoOct;
    }
    /// Tangent frames: a normal, a tangent and the bitangent's sign in one code, decoded
    /// to the struct `frame` of `n` and `t` (the sign in `t.w`).
    frames (frame, smallest_three, tangent_plane) {
        qtangent [QTANGENT];
        godot [GODOT];
        octangle [OCTANGLE];
        diamond [DIAMOND];
    }
}

/// The file that models `family`, relative to the crate's root (the emitted includes name
/// it, so that a reader of the shader code finds the model it is proven against).
pub fn source_file(family: &dyn Family) -> &'static str {
    let at = FAMILIES
        .iter()
        .position(|f| f.info().name == family.info().name)
        .expect("a registered family");
    SOURCES[at]
}

/// Doc comments of the helpers every codec may call (the precise search, the model's
/// trigonometry) and of any family's own helpers.
pub fn helper_doc(first: &dyn Family, name: &str) -> Option<String> {
    first
        .helper_doc(name)
        .or_else(|| core::codec::helper_doc(name))
        .or_else(|| toolkit::trig::helper_doc(name))
        .or_else(|| FAMILIES.iter().find_map(|f| f.helper_doc(name)))
}

/// A spec is parsed against the registry: the grammar (`core::spec`) is handed
/// [`FAMILIES`] here, so that it names no registry of its own.
impl std::str::FromStr for Spec {
    type Err = SpecError;
    fn from_str(given: &str) -> Result<Spec, SpecError> {
        Spec::parse_in(FAMILIES, given)
    }
}

impl Spec {
    /// Every spec `generate` writes: each size of each registered family with default
    /// options (fast and precise), plus each family's variants.
    pub fn all() -> Vec<Spec> {
        Spec::all_in(FAMILIES)
    }
}

/// Every spelling a user can type, for suggestions and `list`.
pub fn valid_names() -> Vec<String> {
    core::spec::valid_names_in(FAMILIES)
}
