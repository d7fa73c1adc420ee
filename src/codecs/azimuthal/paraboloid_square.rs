//! The dual inverted paraboloid (second seed, "Improved Normal-map Distributions"): a
//! hemisphere normal is stored as the point `p` (snorm×2 of `B/2` bits each, x in the
//! lowest bits) where its ray meets `z = (1 - x²)(1 - y²)`. Unlike
//! [`crate::codecs::azimuthal::paraboloid`]'s disk, the surface spans the whole square `[-1, 1]²`: its edges
//! are the horizon, so no code is wasted outside a disk (the seed's "~14 % of the
//! possible xy combinations"). The decoder is `normalize(p, (1 - x²)(1 - y²))`.
//!
//! The seed gives no encoder for this surface: along a ray the point is a root of a
//! quartic. With `s` the larger of `|x|, |y|` and `r ≤ 1` the ratio of the smaller to
//! it, the ray through the unit input `u` meets the surface where
//! `g(s) = (1 - s²)(1 - r²s²)·max(|u.x|, |u.y|) - u.z·s` changes sign; `g` falls
//! strictly on `[0, 1]` from `max(|u.x|, |u.y|) ≥ 0` to `-u.z ≤ 0`, so the root is unique.
//! The encoder finds it by bisection, a fixed 22 steps in fixed point (units of `2^-21`,
//! every product rounded to a unit before the next sum), from the input's fixed-point
//! direction: every step is a function of the input alone, so every implementation
//! computes the same point and the same codes.

use crate::model::num::helper;
use crate::codecs::core::codec::{Codec, above_horizon};
use crate::codecs::core::info::Domain;
use crate::codecs::toolkit::exact::{canonical_or_z, fixed_length2, fixed_ratio, fixed_root, root};
use crate::codecs::core::info::{Info, Sizes, FloatForm, seam};
use crate::codecs::core::codec_family::CodecFamily;
use crate::codecs::core::texel::{self, TexelCodec, texel_variants};
use crate::codecs::toolkit::fixed_decode::{
    BITS, ONE, fixed, fixed_mul, fixed_square, fixed_target, nearest_decoded, search_doc,
};
use crate::codecs::toolkit::quant::{Quant, Quants, signed_code};
use crate::codecs::core::spec::SpecError;
use crate::model::{Bool, Float, Uint, V2, V3};

pub static FAMILY: CodecFamily<ParaboloidSquare> = CodecFamily::new(
    Info {
        name: "paraboloid_square",
        title: "dual inverted paraboloid z = (1 - x²)(1 - y²) of the +Z hemisphere, snorm×2",
        sizes: Sizes::Total(&[16, 24, 32]),
        domain: Some(Domain::Hemisphere),
        source: "Improved Normal-map Distributions (Insomniac, after Mike Day), the dual inverted paraboloid",
        edge_policy: "input is projected onto the +Z hemisphere first (z ← max(z, +0)); zero, NaN, infinite and -Z input encode as +Z",
        decode_note: "every code decodes to a unit vector (up to rounding); the square's edges decode on the horizon",
        float_form: FloatForm::Continuous { seam: seam::NONE_IN_HEMISPHERE },
        options: &[texel::OPTION],
    },
    |bits| ParaboloidSquare { bits },
    texel::functions,
)
.with_validate(texel::validate)
.with_variants(texel_variants!("paraboloid_square"))
.with_helper_doc(|name| match name {
    "encode_codes" => Some(search_doc(BITS)),
    "square_point" => Some(
        "The point where the input's ray meets z = (1 - x²)(1 - y²), in units of 2^-21: \
         the input's fixed-point direction, then 22 bisection steps on the larger \
         coordinate; a function of the input alone."
            .into(),
    ),
    "square_step" => Some(
        "One bisection step: `s + h` where the surface at that point is still above the \
         ray (`(1 - t²)(1 - r²t²)·m ≥ u.z·t`, every product rounded to a unit of 2^-21), \
         else `s`."
            .into(),
    ),
    _ => None,
});

#[derive(Clone, Copy, Debug)]
pub struct ParaboloidSquare {
    pub bits: u32,
}

/// Bisection steps: the first tries `s = 1` (the horizon), the last adds one unit.
const STEPS: u32 = BITS + 1;

/// One bisection step from `s` by `h`, for the ray of the fixed-point unit input with
/// `k = (m, r², u.z)`: `m` the larger of `|u.x|, |u.y|` and `r` the smaller over it.
#[inline(always)]
fn step<F: Float>(s: F, h: F, k: V3<F>) -> F {
    let one = F::c(ONE as f32);
    let t = (s + h).named("t");
    let t2 = fixed_square(t);
    let surface = fixed_mul(one - t2, one - fixed_mul(k.y, t2)).named("surface");
    let above = fixed_mul(surface, k.x).ge(fixed_mul(k.z, t));
    F::sel(above.and(t.le(one)), t, s)
}

impl ParaboloidSquare {
    /// The codec with the given total bit budget; an invalid size is an error listing
    /// the allowed ones.
    pub fn new(bits: u32) -> Result<ParaboloidSquare, SpecError> {
        FAMILY.codec(bits)
    }

    fn field(&self) -> Quant {
        Quant::Snorm(self.bits / 2)
    }

    /// The code in the field `q` of a fixed-point parameter `x` (units of `2^-BITS`,
    /// `|x| ≤ 2^BITS`), rounded or floored. A snorm code is `x·M/2^BITS`, one product
    /// rounded or floored; a unorm one (`p·½ + ½` in a texel channel) is
    /// `(M·u + 2^BITS) >> (BITS + 1)` (rounded, ties up) or `M·u >> (BITS + 1)` of
    /// `u = x + 2^BITS`, in integers below `2^31`, so exact.
    #[inline(always)]
    fn code<F: Float>(q: Quant, x: F, rounded: bool) -> F {
        match q {
            Quant::Unorm(b) => {
                debug_assert!(b <= 9, "M·2^(BITS+1) below 2^31");
                let u = (x + F::c(ONE as f32)).to_u();
                let n = u.wrapping_mul(F::U::c(q.mask()));
                let n = if rounded { n + F::U::c(1 << BITS) } else { n };
                n.shr(BITS + 1).to_f()
            }
            _ => {
                let k = F::c((f64::from(q.max_code()) / ONE) as f32);
                if rounded { (x * k).round() } else { (x * k).floor() }
            }
        }
    }

    /// The fixed-point unit direction (units of `2^-BITS`) of the input projected onto
    /// the hemisphere. Input without a direction there (zero, NaN, infinite, -Z) becomes
    /// +Z in canonical form, whose point is the origin: no select needed afterwards.
    #[inline(always)]
    fn aim<F: Float>(v: V3<F>) -> V3<F> {
        let (w, _) = canonical_or_z(v);
        let (h, _) = canonical_or_z(above_horizon(w));
        fixed_target(h, root(fixed_length2(h)), BITS)
    }

    /// [`Self::fixed_point`] as the helper `square_point`.
    #[inline(always)]
    fn point<F: Float>(u: V3<F>) -> V2<F> {
        helper!("square_point" => Self::fixed_point(u)).named("p")
    }

    /// The surface point on the ray of the fixed-point unit `u` (`u.z ≥ 0`) in units of
    /// `2^-BITS`: `s` by bisection (see the module), the smaller coordinate `r·s`, each
    /// with its component's sign. The pole gives `s = 0` (`g` is negative past it) and
    /// the horizon `s = 1` (`g` is never negative before it), with no case of their own.
    #[inline(always)]
    fn fixed_point<F: Float>(u: V3<F>) -> V2<F> {
        let a = u.xy().abs();
        let x_major = a.x.ge(a.y);
        let (m, n) = (F::sel(x_major, a.x, a.y), F::sel(x_major, a.y, a.x));
        // `m = 0` only at the pole, where `r` is not used: any positive divisor will do.
        let r = fixed_ratio(n, m.at_least(F::c(1.0)), BITS).named("r");
        let k = V3::new(m, fixed_square(r), u.z).named("k");
        let mut s = F::c(0.0);
        for i in (0..STEPS).rev() {
            let h = F::c((1u32 << i) as f32);
            s = helper!("square_step" => step(s, h, k)).named("s");
        }
        let minor = fixed_mul(r, s);
        let p = V2::new(F::sel(x_major, s, minor), F::sel(x_major, minor, s));
        let signed = { #[inline(always)] |p: F, c: F| F::sel(c.lt(F::c(0.0)), -p, p) };
        V2::new(signed(p.x, u.x), signed(p.y, u.y))
    }

    /// The decode of codes `c` of the field `q` in units of `2^-BITS`: `p = s/M` of their
    /// signed values ([`signed_code`]) one rounded product floored, `z = (1 - x²)(1 - y²)` from squares and a product each rounded to
    /// a unit, the length `L = sqrt(x² + y² + z²)` from [`fixed_root`] (of `L²·2^19`,
    /// doubled: within two units) and no shorter than any component, then each component
    /// divided by it with [`fixed_ratio`].
    #[inline(always)]
    fn fixed_direction<F: Float>(q: Quant, c: V2<F>) -> V3<F> {
        let one = F::c(ONE as f32);
        let k = ONE / f64::from(q.max_code());
        let p = c.map(#[inline(always)] |x| fixed(signed_code(q, x), k)).named("p");
        let (x2, y2) = (fixed_square(p.x), fixed_square(p.y));
        let z = fixed_mul(one - x2, one - y2).named("z");
        // At most 3·2^21, so the root's argument is below 2^42.
        let l2 = (x2 + y2 + fixed_square(z)).named("l2");
        let l = fixed_root(l2 * F::c((ONE * 0.25) as f32)) * F::c(2.0);
        let a = p.abs();
        let l = l.at_least(a.x).at_least(a.y).at_least(z).named("l");
        V3::from_xy(p.map(#[inline(always)] |x| fixed_ratio(x, l, BITS)), fixed_ratio(z, l, BITS))
    }
}

impl Codec for ParaboloidSquare {
    type P<F: Float> = V2<F>;
    type C<F: Float> = F::U;
    #[inline]
    fn quants(&self) -> Quants {
        Quants::new(&[self.field(); 2])
    }
    fn domain(&self) -> Domain {
        Domain::Hemisphere
    }
    /// The fixed-point surface point scaled to `[-1, 1]` (exactly: a power of two).
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V2<F> {
        Self::point(Self::aim(v)) * F::c((1.0 / ONE) as f32)
    }
    /// `normalize(p, (1 - x²)(1 - y²))`: `z ≥ 0` on the whole square, zero only on its
    /// edges, where `p` itself is at least 1 long.
    #[inline(always)]
    fn direction<F: Float>(&self, p: V2<F>) -> V3<F> {
        let z = ((F::c(1.0) - p.x * p.x) * (F::c(1.0) - p.y * p.y)).named("z");
        let n = V3::from_xy(p, z).named("n");
        n / n.length_squared().sqrt()
    }
    /// The codes of the fixed-point surface point ([`Self::code`], rounded); input
    /// without a direction on the hemisphere encodes as +Z.
    const EXACT_ROUNDING: bool = true;
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V2<F> {
        self.round_in(self.field(), v)
    }
    /// The nearest of the four codes around the fixed-point surface point by the squared
    /// distance of their fixed-point decodes to the input's fixed-point direction; input
    /// without a direction on the hemisphere encodes as +Z.
    const EXACT_SEARCH: bool = true;
    #[inline(always)]
    fn precise_codes<F: Float>(&self, v: V3<F>) -> V2<F> {
        self.precise_in(self.field(), v)
    }
}

impl TexelCodec for ParaboloidSquare {
    #[inline(always)]
    fn params2<F: Float>(&self, v: V3<F>) -> V2<F> {
        self.params(v)
    }
    #[inline(always)]
    fn direction2<F: Float>(&self, p: V2<F>) -> V3<F> {
        self.direction(p)
    }
    #[inline(always)]
    fn round_in<F: Float>(&self, q: Quant, v: V3<F>) -> V2<F> {
        Self::point(Self::aim(v)).map(#[inline(always)] |x| Self::code(q, x, true))
    }
    #[inline(always)]
    fn precise_in<F: Float>(&self, q: Quant, v: V3<F>) -> V2<F> {
        let target = Self::aim(v);
        let base = Self::point(target).map(#[inline(always)] |x| Self::code(q, x, false)).named("base");
        // At the pole the origin's decode is the target itself, so +Z wins there.
        nearest_decoded([q; 2], base, target, #[inline(always)] |c| Self::fixed_direction(q, c))
    }
}
