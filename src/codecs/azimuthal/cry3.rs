//! CryEngine 3's normal encoding (first seed, method 5, after Mittring 2009):
//! `enc = normalize(n.xy) · sqrt(½ - ½z) · ½ + ½`, stored as unorm×2, with the seed's two
//! decoders (`decoder=plain`, `decoder=optimized`).
//!
//! For unit input the radius `sqrt((1 - z)/2) · ½` is `|n.xy| / sqrt(8z + 8)`, so this is
//! [`crate::codecs::azimuthal::lambert`]'s mapping (the seed's erratum), with the seed's Unity orientation
//! (+Z at the centre, as printed). The encoders are Lambert's, which also define the poles
//! (`normalize(n.xy)` has no direction there); the decoders are the seed's.
//! `tests/families/lambert.rs` checks the seed's encoder formulas against each other and the
//! shared codes.

use crate::codecs::core::info::Domain;
use crate::codecs::core::info::{Info, Sizes, FloatForm, seam};
use crate::codecs::core::codec_family::CodecFamily;
use crate::codecs::toolkit::fixed_decode::{BITS, search_doc};
use crate::codecs::core::pipeline::codec_functions;
use crate::codecs::azimuthal::lambert::{Lambert, LambertDecoder, WithDecoder};
use crate::codecs::core::spec::SpecError;
use crate::codecs::azimuthal::spheremap::DECODER_OPTION;
use crate::model::{Float, V2, V3};

pub static FAMILY: CodecFamily<Cry3> = CodecFamily::new(
    Info {
        name: "cry3",
        title: "CryEngine 3, unorm×2 (Lambert's codes, the seed's decoders)",
        sizes: Sizes::Total(&[16, 24, 32]),
        domain: Some(Domain::Sphere),
        source: "Pranckevičius, Compact Normal Storage, method 5 (Mittring 2009)",
        edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z; -Z encodes as (1, 0.5)",
        decode_note: "every code decodes to a unit vector up to rounding; codes outside the disk decode as -Z",
        float_form: FloatForm::Continuous { seam: seam::RIM_IS_MINUS_Z },
        options: &[DECODER_OPTION],
    },
    |bits| WithDecoder {
        lambert: Lambert { bits },
        decoder: Cry3Decoder { optimized: false },
    },
    codec_functions,
)
.with_options(|spec, c| if spec.chose(&DECODER_OPTION, "optimized") { c.optimized() } else { c })
.with_variants(&[
    "cry3_16:decoder=optimized",
    "cry3_24:decoder=optimized",
    "cry3_32:decoder=optimized",
])
.with_helper_doc(|name| (name == "encode_codes").then(|| search_doc(BITS)));

/// The seed's decoders of Lambert's mapping.
#[derive(Clone, Copy, Debug)]
pub struct Cry3Decoder {
    /// The seed's optimized decoder rather than its plain one.
    pub optimized: bool,
}

/// Lambert's codes with the seed's decoders.
pub type Cry3 = WithDecoder<Cry3Decoder>;

impl Cry3 {
    /// The codec with the given total bit budget and the plain decoder; an invalid size
    /// is an error listing the allowed ones.
    pub fn new(bits: u32) -> Result<Cry3, SpecError> {
        FAMILY.codec(bits)
    }
    /// The same codes, decoded by the seed's optimized decoder.
    pub fn optimized(self) -> Cry3 {
        WithDecoder {
            decoder: Cry3Decoder { optimized: true },
            ..self
        }
    }
}

impl LambertDecoder for Cry3Decoder {
    /// With `f = 2enc - 1` and `d = f·f` limited to the disk (so the square's corners
    /// decode as -Z): plain, `z = -(2d - 1)` and `xy = normalize(f)·sqrt(|1 - z²|)` (the
    /// centre, where `normalize` has no direction, decodes as +Z); optimized,
    /// `l = 1 - d`, `xy = 2f·sqrt(l)` and `z = 2l - 1`.
    #[inline(always)]
    fn direction<F: Float>(&self, enc: V2<F>) -> V3<F> {
        let f = (enc * F::c(2.0) - F::c(1.0)).named("fenc");
        let d = f.length_squared().named("d");
        if self.optimized {
            let l = (F::c(1.0) - d).at_least(F::c(0.0)).named("l");
            let xy = f * l.sqrt();
            V3::from_xy(xy * F::c(2.0), l * F::c(2.0) - F::c(1.0))
        } else {
            let z = (-(d.at_most(F::c(1.0)) * F::c(2.0) - F::c(1.0))).named("z");
            let dir = f.normalize_or(V2::splat(F::c(0.0)));
            // 1 - z² is never negative (|z| ≤ 1), so its absolute value changes no
            // output; it lets the proven bound see that the root's argument is not
            // negative, which a limit at 0 could not promise where a comparison flushes
            // a denormal the select then passes on.
            let r2 = (F::c(1.0) - z * z).abs();
            V3::from_xy(dir * r2.sqrt(), z)
        }
    }
}
