//! Cube-map projection (survey §2, `cube`; `warpedcube` in [`crate::codecs::cube_maps::warpedcube`]): the
//! direction divided by its largest-magnitude component lands on one of six cube faces;
//! the code stores the face and two coordinates on it.
//!
//! Layout of a `B`-bit code: `s` in the lowest `⌈(B-3)/2⌉` bits, `t` in the next
//! `⌊(B-3)/2⌋`, the face in the top 3 (cube16: s bits 0–6, t bits 7–12, face 13–15).
//! The survey's version leaves one bit unused for alignment; this one gives it to `s`.
//! Faces are numbered like a cube map's layers, `2·axis + (major < 0)`: +X, -X, +Y, -Y,
//! +Z, -Z = 0–5; 6 and 7 are never written and decode as +Z and -Z. On the face of axis
//! `a` the coordinates are the next two components in cyclic order divided by the major
//! one's magnitude (+X: `(y, z)/|x|`, +Y: `(z, x)/|y|`, +Z: `(x, y)/|z|`), stored as unorm
//! `·0.5 + 0.5`. Ties between components go to z, then y.
//!
//! The warped variant stores `atan(s)/(π/4)` instead of `s` (the equi-angular warp, one
//! reading of the survey's "warp the parameter space to more evenly distribute the
//! representable points"): equal code steps are equal angles along the face's axes, which
//! evens the point density between a face's centre and its corners.

use crate::model::num::helper;
use crate::codecs::core::codec::Codec;
use crate::codecs::cube_maps::faces::{Face, placed};
use crate::codecs::core::info::Domain;
use crate::codecs::toolkit::exact::{canonical_or_z, fixed_length2, fixed_ratio, fixed_root, root, unorm_ratio};
use crate::codecs::core::info::{Info, Sizes, FloatForm, seam};
use crate::codecs::core::codec_family::CodecFamily;
use crate::codecs::toolkit::fixed_decode::{fixed_length2_2d, BITS, ONE, fixed, fixed_square_point, fixed_target, nearest_decoded, search_doc};
use crate::codecs::toolkit::fixed_trig;
use crate::codecs::core::pipeline::codec_functions;
use crate::codecs::toolkit::quant::{Quant, Quants};
use crate::codecs::core::spec::SpecError;
use crate::codecs::toolkit::trig::{atan2_pi, sincos_pi};
use crate::model::{Float, V2, V3};

pub static FAMILY: CodecFamily<Cube> = CodecFamily::new(
    Info {
        name: "cube",
        title: "cube-map face (3 bits) + unorm×2 coordinates on it",
        sizes: Sizes::Total(&[16, 24, 32]),
        domain: Some(Domain::Sphere),
        source: "Cigolle et al. 2014 §2 (cube)",
        edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z; ties between components go to z, then y",
        decode_note: "every code decodes to a unit vector (up to rounding); faces 6 and 7 are never written and decode as +Z and -Z",
        float_form: FloatForm::Continuous { seam: seam::CUBE_FACES },
        options: &[],
    },
    |bits| Cube::of(bits, false),
    codec_functions,
)
.with_helper_doc(|name| (name == "encode_codes").then(|| search_doc(BITS)));

/// A cube-map codec; `warped` selects the equi-angular coordinates.
#[derive(Clone, Copy, Debug)]
pub struct Cube {
    pub bits: u32,
    pub warped: bool,
}

/// The largest face number, as a unorm field's `M`.
const FACES: f32 = 7.0;

impl Cube {
    /// The plain cube codec with the given total bit budget; an invalid size is an error
    /// listing the allowed ones.
    pub fn new(bits: u32) -> Result<Cube, SpecError> {
        FAMILY.codec(bits)
    }
    /// The warped (equi-angular) cube codec.
    pub fn warped(bits: u32) -> Result<Cube, SpecError> {
        FAMILY.codec(bits).map(|c| Cube::of(c.bits, true))
    }
    pub(super) fn of(bits: u32, warped: bool) -> Cube {
        Cube { bits, warped }
    }

    fn fields(&self) -> [Quant; 2] {
        let rest = self.bits - 3;
        [Quant::Unorm(rest.div_ceil(2)), Quant::Unorm(rest / 2)]
    }

    /// The codes of the coordinates `n / major` at the boundaries `c + offset` (`½`
    /// rounds, `1` floors). Plain: [`unorm_ratio`]. Warped: the angle `T = atan2(n, major)/π`
    /// in units of `2^-23` from [`fixed_trig::atan2_pi`] (`|T| ≤ 2^21`, a function of the
    /// input alone), times 4 (the face's quarter turn onto `[-1, 1]`), coded by
    /// [`fixed_trig::angle_code`].
    #[inline(always)]
    fn codes<F: Float>(&self, f: &Face<F>, offset: f32) -> V2<F> {
        let code = { #[inline(always)] |q: Quant, n: F| {
            if !self.warped {
                return unorm_ratio(q, n, f.major, offset);
            }
            let t = fixed_trig::atan2_pi(n, f.major);
            fixed_trig::angle_code(q, t * F::c(4.0), offset)
        } };
        let [qs, qt] = self.fields();
        V2::new(code(qs, f.s), code(qt, f.t)).named("st")
    }

    /// The decode of codes `c` on face `face` in units of `2^-BITS`: the face point
    /// (plain: [`fixed_square_point`]; warped: `tan` of the angles as
    /// [`fixed_trig::sincos_pi`]'s sine over cosine by [`fixed_ratio`]), its length
    /// `sqrt(1 + |p|²)` by [`fixed_root`], then each component over it by [`fixed_ratio`].
    #[inline(always)]
    fn fixed_direction<F: Float>(&self, c: V2<F>, face: F) -> V3<F> {
        let one = F::c(ONE as f32);
        let (p, q) = if self.warped {
            let [qs, qt] = self.fields();
            let tan = { #[inline(always)] |q: Quant, c: F| {
                let m = f64::from(q.max_code());
                // The angle in units of 2^-24 half turns: (2c - M)/M · 1/4.
                let a = fixed(c * F::c(2.0) - F::c(m as f32), fixed_trig::FINE / (4.0 * m));
                let sc = fixed_trig::sincos_pi(a);
                fixed_ratio(sc.x, sc.y, BITS)
            } };
            let p = V2::new(tan(qs, c.x), tan(qt, c.y)).named("p");
            (p, fixed_length2_2d(p))
        } else {
            fixed_square_point(self.fields(), c)
        };
        // |(p, 1)|² and |(p, 1)| (the root of at most 3·2^40 in units of 2^-20, then
        // doubled), both in units of 2^-21; the major component 1/len is len/len².
        let len2 = (one + q).named("len2");
        let len = (fixed_root(len2 * F::c((1u32 << 19) as f32)) * F::c(2.0)).named("len");
        let r = { #[inline(always)] |x: F| fixed_ratio(x, len, BITS) };
        placed(face, 1.0, fixed_ratio(len, len2, BITS), r(p.x), r(p.y))
    }
}

impl Codec for Cube {
    type P<F: Float> = V3<F>;
    type C<F: Float> = F::U;
    #[inline]
    fn quants(&self) -> Quants {
        let [qs, qt] = self.fields();
        Quants::new(&[qs, qt, Quant::Unorm(3)])
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    /// `(s·0.5 + 0.5, t·0.5 + 0.5, face/7)` of the canonical input, the coordinates
    /// `n / major` (warped: `atan2(n, major)/(π/4)`).
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V3<F> {
        let (w, _) = canonical_or_z(v);
        let f = Face::of(w);
        let st = V2::new(f.s, f.t);
        let enc = if self.warped {
            let a = { #[inline(always)] |n: F| {
                helper!(atan2_pi(n, f.major)) * F::c(2.0)
            } };
            V2::new(a(st.x), a(st.y)) + F::c(0.5)
        } else {
            st / f.major * F::c(0.5) + F::c(0.5)
        };
        V3::from_xy(enc.named("enc"), f.number * F::c(1.0 / FACES))
    }
    /// The face point `p = enc·2 - 1` (warped: `tan(p·π/4)`, as `sin/cos` of
    /// [`sincos_pi`] with both scaled by the cosines so no quotient is needed) and the
    /// unit vector `d / sqrt(d·d)` of `d = (p, 1)` placed on face `enc.z·7`.
    #[inline(always)]
    fn direction<F: Float>(&self, enc: V3<F>) -> V3<F> {
        let p = ((enc.xy() - F::c(0.5)) * F::c(2.0)).named("p");
        let u = if self.warped {
            let cs = helper!(sincos_pi(p.x * F::c(0.25))).named("cs");
            let ct = helper!(sincos_pi(p.y * F::c(0.25))).named("ct");
            // (tan a, tan b, 1)·cos a·cos b.
            let d = V3::new(cs.x * ct.y, ct.x * cs.y, cs.y * ct.y).named("d");
            d / d.length_squared().sqrt()
        } else {
            // The major coordinate is max(1, |s|, |t|): 1 for every code, and still
            // the largest for parameters past the face's edge. A literal 1 would make
            // the squared length a sum with a constant, which a compiler may regroup.
            let m = p.x.abs().at_least(p.y.abs()).at_least(F::c(1.0));
            let d = V3::from_xy(p, m).named("d");
            d / d.length_squared().sqrt()
        };
        let u = u.named("u");
        placed(enc.z, 1.0 / f64::from(FACES), u.z, u.x, u.y)
    }
    /// The codes of [`Cube::codes`] at `c + ½` on the canonical input's face.
    const EXACT_ROUNDING: bool = true;
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V3<F> {
        let f = Face::of(canonical_or_z(v).0);
        V3::from_xy(self.codes(&f, 0.5), f.number)
    }
    /// The nearest of the four codes around the exact parameters (floors decided like
    /// [`Codec::round_codes`]' codes), on the input's face, by the squared distance of
    /// their fixed-point decodes.
    const EXACT_SEARCH: bool = true;
    #[inline(always)]
    fn precise_codes<F: Float>(&self, v: V3<F>) -> V3<F> {
        let (w, _) = canonical_or_z(v);
        let f = Face::of(w);
        let base = self.codes(&f, 1.0).named("base");
        let target = fixed_target(w, root(fixed_length2(w)), BITS);
        let best = nearest_decoded(self.fields(), base, target, #[inline(always)] |c| {
            self.fixed_direction(c, f.number)
        });
        V3::from_xy(best, f.number)
    }
}
