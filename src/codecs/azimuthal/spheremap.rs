//! The spheremap transform (first seed, method 4): the sphere-environment-map coordinates
//! of the normal, `enc = n.xy / sqrt(2z + 2) · ½ + ½`, stored as unorm×2, with the seed's
//! two decoders (`decoder=plain`, `decoder=optimized`).
//!
//! For unit input `n.xy / sqrt(2z + 2) · ½` is `n.xy / sqrt(8z + 8)`: the seed's erratum
//! notes that methods 4, 5 and 6 are one mapping. So the encoders are
//! [`crate::codecs::azimuthal::lambert`]'s (which normalize first, decide every code exactly and keep -Z
//! defined), and what this codec adds is the seed's decoders, which compute the same
//! direction in other orders of operations. `tests/families/lambert.rs` checks the seed's
//! encoder formulas against each other and the shared codes.

use crate::codecs::core::info::Domain;
use crate::codecs::core::info::{Info, OptDesc, OptKind, Sizes, FloatForm, seam};
use crate::codecs::core::codec_family::CodecFamily;
use crate::codecs::toolkit::fixed_decode::{BITS, search_doc};
use crate::codecs::core::pipeline::codec_functions;
use crate::codecs::azimuthal::lambert::{Lambert, LambertDecoder, WithDecoder};
use crate::codecs::core::spec::SpecError;
use crate::model::{Float, V2, V3};

/// The `decoder` option shared with [`crate::codecs::azimuthal::cry3`]: the seed gives each method a plain
/// decoder and an "optimized" one with fewer instructions.
pub const DECODER_OPTION: OptDesc = OptDesc {
    key: "decoder",
    help: "the seed's decoder: plain, or its optimized rewrite (the same mapping, fewer instructions)",
    kind: OptKind::Choice(&["plain", "optimized"]),
};

pub static FAMILY: CodecFamily<Spheremap> = CodecFamily::new(
    Info {
        name: "spheremap",
        title: "spheremap transform, unorm×2 (Lambert's codes, the seed's decoders)",
        sizes: Sizes::Total(&[16, 24, 32]),
        domain: Some(Domain::Sphere),
        source: "Pranckevičius, Compact Normal Storage, method 4",
        edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z; -Z encodes as (1, 0.5)",
        decode_note: "every code decodes to a unit vector up to rounding; codes outside the disk decode as -Z",
        float_form: FloatForm::Continuous { seam: seam::RIM_IS_MINUS_Z },
        options: &[DECODER_OPTION],
    },
    |bits| WithDecoder {
        lambert: Lambert { bits },
        decoder: SpheremapDecoder { optimized: false },
    },
    codec_functions,
)
.with_options(|spec, c| if spec.chose(&DECODER_OPTION, "optimized") { c.optimized() } else { c })
.with_variants(&["spheremap16:decoder=optimized", "spheremap24:decoder=optimized", "spheremap32:decoder=optimized"])
.with_helper_doc(|name| (name == "encode_codes").then(|| search_doc(BITS)));

/// The seed's decoders of Lambert's mapping.
#[derive(Clone, Copy, Debug)]
pub struct SpheremapDecoder {
    /// The seed's optimized decoder rather than its plain one.
    pub optimized: bool,
}

/// Lambert's codes with the seed's decoders.
pub type Spheremap = WithDecoder<SpheremapDecoder>;

impl Spheremap {
    /// The codec with the given total bit budget and the plain decoder; an invalid size
    /// is an error listing the allowed ones.
    pub fn new(bits: u32) -> Result<Spheremap, SpecError> {
        FAMILY.codec(bits)
    }
    /// The same codes, decoded by the seed's optimized decoder.
    pub fn optimized(self) -> Spheremap {
        WithDecoder {
            decoder: SpheremapDecoder { optimized: true },
            ..self
        }
    }
}

impl LambertDecoder for SpheremapDecoder {
    /// Plain: `t = enc·(1 - enc)` (the seed's `enc - enc²`), `f = t.x + t.y`, `xy = (4enc - 2)·sqrt(4f - 1)`,
    /// `z = 8f - 3`. Optimized: `f = (t.x - ¼) + t.y` (the seed's `dot(n, (1, 1, ¼))`
    /// with `n = (t, -1)`, its literal term first so that no driver regroups the sum),
    /// `xy = (8enc - 4)·sqrt(f)`, `z = 8f - 1`. `f` is limited to the disk (`4f - 1 ≥ 0`), so the square's corners
    /// decode as -Z.
    #[inline(always)]
    fn direction<F: Float>(&self, enc: V2<F>) -> V3<F> {
        // The seed's `-enc·enc + enc`, factored as the naga paths' drivers factor it.
        let t = (enc * (V2::splat(F::c(1.0)) - enc)).named("t");
        if self.optimized {
            let f = ((t.x - F::c(0.25)) + t.y).at_least(F::c(0.0)).named("f");
            let xy = (enc * F::c(8.0) - F::c(4.0)) * f.sqrt();
            V3::from_xy(xy, f * F::c(8.0) - F::c(1.0))
        } else {
            let f = (t.x + t.y).at_least(F::c(0.25)).named("f");
            let m = (f * F::c(4.0) - F::c(1.0)).sqrt().named("m");
            let xy = (enc * F::c(4.0) - F::c(2.0)) * m;
            V3::from_xy(xy, f * F::c(8.0) - F::c(3.0))
        }
    }
}
