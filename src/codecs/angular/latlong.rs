//! The survey's fast `latlong` (Smith et al. 2012's patches numbered by ring, with the
//! fast decoder): a latitude–longitude grid whose every ring holds the same number of
//! patches, so that the ring and the patch within it are two bit fields and decoding
//! needs no table.
//!
//! Neither the survey's text nor Smith et al.'s paper fixes the fast variant's grid (its
//! supplement, which would, is not available to us). We infer it from Table 1: the
//! latlong rows sit on the plain lat-long grid's error (mean/max ratio 0.45, where
//! `latlongd`'s equal-area rings give 0.54), and the grid that reproduces them is `2^h` rings
//! from pole to pole by `2^h - 1` azimuths, `h = B/2`. `tests/figures/accuracy.rs` holds all
//! three sizes to the table.
//!
//! Layout, first field lowest: the azimuth `k` (unorm, `h` bits), then the ring `j`
//! (unorm, `h` bits), so the packed word is `j·2^h + k`, the patches numbered ring by
//! ring from +Z. Ring `j` is at the polar angle `θ = π·j/M` and patch `k` at the
//! azimuth `φ = π·(2k/M - 1)` (`M = 2^h - 1`): `k = 0` and `k = M` are the same
//! meridian, and each pole is one point stored `2^h` times, which is the fast decoder's
//! price against `latlongd`'s tables.
//!
//! The angles come from the model's fixed-point trigonometry ([`crate::codecs::toolkit::fixed_trig`]),
//! each code one rounded product of an exact integer, so the packed code is a function of
//! the input alone on every path; the decoder uses [`crate::codecs::toolkit::trig`], never a builtin.

use crate::model::num::helper;
use crate::codecs::core::codec::Codec;
use crate::codecs::core::info::Domain;
use crate::codecs::toolkit::exact::canonical_or_z;
use crate::codecs::core::info::{Info, Sizes, FloatForm, seam};
use crate::codecs::core::codec_family::CodecFamily;
use crate::codecs::toolkit::fixed_trig;
use crate::codecs::core::pipeline::codec_functions;
use crate::codecs::toolkit::quant::{Quant, Quants};
use crate::codecs::core::spec::SpecError;
use crate::codecs::angular::spherical::{fixed_angles, float_angles};
use crate::codecs::toolkit::trig::sincos_pi;
use crate::model::{Float, V2, V3};

pub static FAMILY: CodecFamily<Latlong> = CodecFamily::new(
    Info {
        name: "latlong",
        title: "latitude–longitude patches numbered by ring, 2^h rings × (2^h - 1) azimuths",
        sizes: Sizes::Total(&[16, 24, 32]),
        domain: Some(Domain::Sphere),
        source: "Cigolle et al. 2014 §2 (Smith et al. 2012), fast decoder",
        edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z (ring 0)",
        decode_note: "decodes are unit length to within the trig approximations' error (about 2.5e-7)",
        float_form: FloatForm::Unfilterable {
            why: FloatForm::INDEX_SPLIT,
            seam: seam::AZIMUTH_WRAP,
        },
        options: &[],
    },
    |bits| Latlong { bits },
    codec_functions,
);

#[derive(Clone, Copy, Debug)]
pub struct Latlong {
    pub bits: u32,
}

impl Latlong {
    /// The codec with the given total bit budget; an invalid size is an error listing
    /// the allowed ones.
    pub fn new(bits: u32) -> Result<Latlong, SpecError> {
        FAMILY.codec(bits)
    }

    fn field(&self) -> Quant {
        Quant::Unorm(self.bits / 2)
    }
}

impl Codec for Latlong {
    type P<F: Float> = V2<F>;
    type C<F: Float> = F::U;
    #[inline]
    fn quants(&self) -> Quants {
        Quants::new(&[self.field(); 2])
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    /// `(φ/π·½ + ½, θ/π)`: the azimuth and the polar angle as fractions of their ranges.
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V2<F> {
        let (theta, phi) = float_angles(self.target(v));
        V2::new(phi * F::c(0.5) + F::c(0.5), theta)
    }
    #[inline(always)]
    fn direction<F: Float>(&self, p: V2<F>) -> V3<F> {
        grid_direction(p)
    }
    /// Both angles of the canonical input from [`fixed_angles`] (units of `2^-23` half
    /// turns, functions of the input alone), each coded by [`fixed_trig::angle_code`]:
    /// one exact sum, one product with a literal, rounded once.
    const EXACT_ROUNDING: bool = true;
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V2<F> {
        let (theta, phi) = fixed_angles(canonical_or_z(v).0);
        let q = self.field();
        V2::new(
            fixed_trig::angle_code(q, phi, 0.5),
            fixed_trig::angle_code(q, theta, 0.5),
        )
    }
}

/// The direction of parameters `p` in `[0, 1]²`: azimuth `p.x·2 - 1` and polar angle
/// `p.y`, in half turns (`latlongd`'s decoder ends the same way).
#[inline(always)]
pub fn grid_direction<F: Float>(p: V2<F>) -> V3<F> {
    let phi = (p.x * F::c(2.0) - F::c(1.0)).named("phi");
    let st = helper!(sincos_pi(p.y)).named("st");
    let sp = helper!(sincos_pi(phi)).named("sp");
    V3::new(sp.y * st.x, sp.x * st.x, st.y)
}
