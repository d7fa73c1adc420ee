//! Clarberg's equal-area octahedral map (Clarberg 2008, "Fast equal-area mapping of the
//! (hemi)sphere using SIMD"; pbrt-v4's `EqualAreaSphereToSquare` and
//! `EqualAreaSquareToSphere`), stored like `oct` ([`crate::codecs::octahedral::oct`]): two snorm fields of
//! half the bits each, x in the lowest bits.
//!
//! Where `oct` projects onto the octahedron with the L1 norm, this map keeps area: a
//! direction at polar distance `|z|` from the nearer pole lies at L1 distance
//! `r = sqrt(1 - |z|)` from the square's centre (so equal caps get equal areas), and its
//! azimuth `φ` in the quadrant, as the fraction `φ/(π/2)`, splits `r` between the two
//! coordinates: `(r·(1 - φ/(π/2)), r·φ/(π/2))`, with the input's signs. The lower
//! hemisphere unfolds over the diagonals as `oct` does, `(1 - |v|, 1 - |u|)`; the fold
//! sides are `oct`'s (encode folds at `z <= 0`, decode at `|x| + |y| > 1`). As in `oct`,
//! the square's axes and diagonals are the meridians at multiples of 45° and the
//! diamond's edges the equator; in between, equal areas of the square hold equal areas of
//! the sphere, where `oct` crowds its codes near the axes (the octahedron's vertices) and
//! thins them at the faces' centres, by up to 3·√3 ≈ 5.2 times.
//!
//! The radius is the equal-area disk codec's ([`crate::codecs::azimuthal::eqarea`]: `ρ/sqrt(1 + |z|)`
//! is `sqrt(1 - |z|)` of a unit vector), so the packed encoder decides each code as the
//! concentric map does ([`crate::codecs::azimuthal::concentric`]): each coordinate is `r` times a
//! multiplier built from [`fixed_trig::atan2_pi`] (an exact integer angle), and whether
//! `r·x` passes a code boundary is decided by [`crate::codecs::azimuthal::disk::Radius::past`], so every
//! implementation computes the same code.

use crate::model::num::helper;
use crate::codecs::core::codec::{Codec, sign_not_zero};
use crate::codecs::core::info::Domain;
use crate::codecs::azimuthal::disk::{DiskProjection, Folded};
use crate::codecs::toolkit::exact::decided;
use crate::codecs::core::info::{Info, Sizes, FloatForm, seam};
use crate::codecs::core::codec_family::CodecFamily;
use crate::codecs::toolkit::fixed_trig;
use crate::codecs::core::pipeline::codec_functions;
use crate::codecs::azimuthal::eqarea::HemiEqArea;
use crate::codecs::toolkit::quant::{Quant, Quants};
use crate::codecs::core::spec::SpecError;
use crate::codecs::toolkit::trig::{atan2_pi, sincos_quarter_pi};
use crate::model::{Float, V2, V3};

pub static FAMILY: CodecFamily<EqAreaOct> = CodecFamily::new(
    Info {
        name: "eqarea_oct",
        title: "equal-area octahedral (Clarberg), snorm×2",
        sizes: Sizes::Total(&[16, 24, 32]),
        domain: Some(Domain::Sphere),
        source: "Clarberg 2008, Fast equal-area mapping of the (hemi)sphere using SIMD (JGT 13(3)); pbrt-v4 EqualAreaSphereToSquare / EqualAreaSquareToSphere",
        edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z; folds on encode when z <= 0, as oct",
        decode_note: "every code decodes to a unit vector (up to rounding); unfolds where |x| + |y| > 1, as oct",
        float_form: FloatForm::Continuous { seam: seam::OCTAHEDRAL_FOLD },
        options: &[],
    },
    |bits| EqAreaOct { bits },
    codec_functions,
);

/// The `eqarea_oct` codec on the CPU.
#[derive(Clone, Copy, Debug)]
pub struct EqAreaOct {
    pub bits: u32,
}

impl EqAreaOct {
    /// The codec with the given total bit budget; an invalid size is an error listing
    /// the allowed ones.
    pub fn new(bits: u32) -> Result<EqAreaOct, SpecError> {
        FAMILY.codec(bits)
    }

    fn field(&self) -> Quant {
        Quant::Snorm(self.bits / 2)
    }
}

/// `(1 - |p.y|, 1 - |p.x|)`: the first quadrant's point of the square folded over its
/// diagonal (`oct`'s fold, signs left to the caller).
#[inline(always)]
fn fold<F: Float>(p: V2<F>) -> V2<F> {
    V2::splat(F::c(1.0)) - p.yx()
}

/// `(2^22 - t, t)·(M/2^22)`: what the radius multiplies to give the two codes, `t` the
/// quadrant's azimuth `φ/(π/2)` in units of `2^-22` (an exact integer from
/// [`fixed_trig::atan2_pi`], whose unit is `2^-23` half turns). `2^22 - t` is exact and
/// each product is rounded once, so both are functions of `t` alone.
#[inline(always)]
fn multipliers<F: Float>(q: Quant, t: F) -> V2<F> {
    let quarter = F::c((1u32 << 22) as f32);
    let scale = F::c((f64::from(q.max_code()) / f64::from(1u32 << 22)) as f32);
    V2::new(quarter - t, t) * scale
}

impl Codec for EqAreaOct {
    type P<F: Float> = V2<F>;
    type C<F: Float> = F::U;
    #[inline]
    fn quants(&self) -> Quants {
        Quants::new(&[self.field(); 2])
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    /// The square point of the canonical input (Clarberg's map in floats): the radius
    /// `r = ρ/sqrt(l·(l + |z|))` (`sqrt(1 - |z|)` of the direction), the quadrant's
    /// azimuth `φ/(π/2) = 2·atan2_pi(|y|, |x|)` from the model's [`atan2_pi`], then
    /// `(r - r·φ/(π/2), r·φ/(π/2))`, folded where `z <= 0`, with the input's signs.
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V2<F> {
        let f = Folded::of(v);
        let a = f.w.xy().abs();
        let rho = f.w.xy().length_squared().sqrt().named("rho");
        let r = (rho / (f.l * f.a).sqrt()).named("r");
        let t = helper!(atan2_pi(a.y, a.x))
        .named("t");
        let along_y = (r * (t * F::c(2.0))).named("v");
        let p = V2::new(r - along_y, along_y).named("p");
        let e = V2::sel_all(f.w.z.le(F::c(0.0)), fold(p), p);
        (e * sign_not_zero(f.w.xy())).named("enc")
    }
    /// The square point `e` back on the sphere (Clarberg's inverse): folded into the
    /// first quadrant's upper triangle `b` (unfolded where `1 - |x| - |y| < 0`), the
    /// radius is `r = b.x + b.y` and the azimuth `φ = (π/2)·b.y/r`; the direction is
    /// `(cos φ, sin φ)·r·sqrt(2 - r²)` with the code's signs, and `z = ±(1 - r²)`: unit
    /// length for every code.
    ///
    /// As in the concentric decoder, the sine and cosine take no range reduction: where
    /// `b.y ≤ b.x` they are of `φ/π = b.y/r·½ ≤ ¼`, elsewhere of `(π/2 - φ)/π = b.x/r·½`
    /// with the two swapped. Both are computed and one chosen last, so that codes on
    /// either side of the diagonal are smooth functions up to the choice (which keeps the
    /// decoder's bound provable in reasonable time), and no rounding of a quotient picks
    /// a formula.
    #[inline(always)]
    fn direction<F: Float>(&self, e: V2<F>) -> V3<F> {
        let a = e.abs();
        let south = (F::c(1.0) - a.x - a.y).lt(F::c(0.0));
        let b = V2::sel_all(south, fold(a), a).named("b");
        let r = (b.x + b.y).named("r");
        let div = F::sel(r.gt(F::c(0.0)), r, F::c(1.0));
        let angle = (b / div * F::c(0.5)).named("angle");
        // (sin φ, cos φ) where φ ≤ π/4, (cos φ, sin φ) where φ ≥ π/4.
        let low = helper!(sincos_quarter_pi(angle.y))
        .named("low");
        let high = helper!(sincos_quarter_pi(angle.x))
        .named("high");
        let x_major = b.x.ge(b.y);
        let cs = V2::new(
            F::sel(x_major, low.y, high.x),
            F::sel(x_major, low.x, high.y),
        )
        .named("cs");
        let r2 = (r * r).named("r2");
        let k = (r * (F::c(2.0) - r2).sqrt()).named("k");
        let xy = cs * k * sign_not_zero(e);
        let z = F::c(1.0) - r2;
        V3::from_xy(xy, z.negated_where(south))
    }
    /// The nearest snorm codes of the first quadrant's point, `round(r·(1 - φ/(π/2))·M)`
    /// and `round(r·φ/(π/2)·M)` (ties up), each decided by
    /// [`crate::codecs::azimuthal::disk::Radius::past`] from the multipliers of [`multipliers`]; then
    /// folded as integers, `(M - c.y, M - c.x)`, where the canonical `z <= 0` (the same
    /// codes as rounding the folded point, but for exact ties), and the input's signs.
    /// Zero, NaN and infinite input is canonical +Z, whose codes are `(0, 0)`.
    const EXACT_ROUNDING: bool = true;
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V2<F> {
        let q = self.field();
        let m = F::c(q.max_code());
        let f = Folded::of(v);
        let radius = <HemiEqArea as DiskProjection>::radius(&f);
        let estimate = radius.estimate().named("r");
        let a = f.w.xy().abs();
        let t = fixed_trig::atan2_pi(a.y, a.x).named("t");
        let mult = multipliers(q, t).named("mult");
        let code = {
            #[inline(always)]
            |x: F| {
                decided(
                    q,
                    (estimate * x).round(),
                    #[inline(always)]
                    |c| radius.past(x, c + F::c(0.5)),
                )
            }
        };
        let c = V2::new(code(mult.x), code(mult.y)).named("c");
        let folded = (V2::splat(m) - c.yx()).named("folded");
        let s = V2::sel_all(f.w.z.le(F::c(0.0)), folded, c);
        V2::sel(f.w.xy().lt(V2::splat(F::c(0.0))), -s, s)
    }
}
