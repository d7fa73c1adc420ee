//! The disk codecs' disk mapped onto the whole square by the elliptical grid map (survey
//! §2, `stereo+ellipse`, `eqarea+ellipse`, `eqdist+ellipse`), so that no code is spent
//! outside the disk.
//!
//! The survey's own elliptical map is in its supplement, which we do not have; this is
//! the elliptical grid map (Nowell's "mapping a square to a circle"; Fong 2014): the
//! square point `(u, v)` goes to the disk point `(u·sqrt(1 - v²/2), v·sqrt(1 - u²/2))`.
//! A vertical grid line `u = t` becomes the half ellipse `x²/t² + y²/(2 - t²) = 1`, and a
//! horizontal one the same with the axes swapped, hence the name; the square's edges
//! become the circle and its corners the points at 45°. It reproduces Table 1's ellipse
//! rows (`tests/figures/accuracy.rs`). The layout is [`crate::codecs::azimuthal::disk`]'s: `(u, v)` stored as unorm
//! `(u, v)·0.5 + 0.5`, x lowest, then y, then the hemisphere bit.
//!
//! The inverse, `u = (√a - √b)/2` with `a, b = 2 + x² - y² ± 2√2·x`, cancels badly near
//! `x = 0` (the survey reports float32 artifacts in these rows); the float form computes
//! it as `2√2·x/(√a + √b)` with `a` and `b` as products of sums, which does not. The
//! codes are decided exactly instead: code `c`'s upper boundary `t = T/M`
//! (`T = 2c + 1 - M`) is passed where the disk point lies on or outside that ellipse, a
//! quadric in the point's squared coordinates, `(x²·G + y²·H)·M² ≥ H·G` with
//! `H = T²` and `G = 2M² - T²` (for `T < 0`: on or inside, where `x < 0`). With the disk
//! point `r·w.xy/ρ`, the left side is `(r²/ρ²)·(w.x²·G + w.y²·H)`: the sum is a
//! [`settled_sum`] of two products and [`Radius::square_sides`] brings in the radius, so
//! every boundary is decided by products meeting in comparisons, the same on every
//! implementation. The codes are found by bisection ([`bisected`]): near the square's
//! corners the inverse is too ill-conditioned for a float estimate to land within one
//! code. The decoder is the map itself, then the projection's lift.

use crate::codecs::core::codec::Codec;
use crate::codecs::core::info::Domain;
use crate::codecs::azimuthal::disk::{DiskProjection, Folded, Radius, disk_fields, disk_quants, unfold};
use crate::codecs::toolkit::exact::{bisected, one_if, settled_sum};
use crate::codecs::core::info::Info;
use crate::codecs::toolkit::quant::{Quant, Quants};
use crate::codecs::core::spec::SpecError;
use crate::model::{Float, V2, V3};
use std::marker::PhantomData;

/// A hemisphere-to-disk projection `P` composed with the elliptical grid map. `P` is
/// only a type: its arithmetic is in associated functions.
#[derive(Clone, Copy, Debug)]
pub struct Ellipse<P> {
    pub bits: u32,
    projection: PhantomData<P>,
}

/// `√2`, where the inverse map needs it.
const SQRT2: f32 = std::f32::consts::SQRT_2;

impl<P: DiskProjection> Ellipse<P> {
    /// The codec with the given total bit budget, for the family `info`; an invalid size
    /// is an error listing the allowed ones.
    #[inline(always)]
    pub fn with(info: &'static Info, bits: u32) -> Result<Self, SpecError> {
        Ok(Ellipse {
            bits: info.check_bits(bits)?,
            projection: PhantomData,
        })
    }

    /// The square point of the folded input's disk point over `2√2`, in floats: the
    /// disk point `w.xy·(r/ρ)` (the pole, `ρ = 0`, is the centre), then [`inverse`].
    #[inline(always)]
    fn square_point<F: Float>(f: &Folded<F>) -> V2<F> {
        let rho = f.w.xy().length_squared().sqrt().named("rho");
        let half = P::half_radius(f, rho).named("half_r");
        let div = F::sel(rho.gt(F::c(0.0)), rho, F::c(1.0));
        let p = (f.w.xy() * (half / div * F::c(2.0))).named("disk");
        V2::new(inverse(p.x, p.y), inverse(p.y, p.x)).named("square")
    }

    /// The unorm codes of the folded input (rounded, ties up), each decided by
    /// [`passed`] and found by [`bisected`]: near the square's corners the inverse map is
    /// ill-conditioned (a disk point `δ` inside the circle is `~√δ` from the corner), so
    /// a float estimate can be dozens of codes from the decided one at 32 bits.
    #[inline(always)]
    fn codes<F: Float>(&self, f: &Folded<F>) -> V2<F> {
        let r = P::radius(f);
        let [qx, qy] = disk_fields(self.bits);
        // The middle boundary, `T = 0`, is `u = 0`: passed where `x ≥ 0`.
        let middle = {
            #[inline(always)]
            |along: F| along.ge(F::c(0.0))
        };
        V2::new(
            bisected(
                qx,
                middle(f.w.x),
                #[inline(always)]
                |c| passed(qx, &r, f.w.x, f.w.y, c),
            ),
            bisected(
                qy,
                middle(f.w.y),
                #[inline(always)]
                |c| passed(qy, &r, f.w.y, f.w.x, c),
            ),
        )
    }
}

/// The inverse map's first coordinate of the disk point `(x, y)` over `2√2` (the
/// caller's literal factor takes it in): `x/(√a + √b)` with `a = (√2 + x)² - y²` and
/// `b = (√2 - x)² - y²`, each written as a product of two sums that are non-negative on
/// the disk (clamped at 0 against rounding just outside it); `a` and `b` vanish together
/// only off the disk.
#[inline(always)]
fn inverse<F: Float>(x: F, y: F) -> F {
    let ay = y.abs();
    let side = {
        #[inline(always)]
        |x: F| {
            let near = ((x + F::c(SQRT2)) - ay).at_least(F::c(0.0));
            let far = (x + F::c(SQRT2)) + ay;
            (near * far).sqrt()
        }
    };
    x / (side(x) + side(-x))
}

/// `1` where the square coordinate `u` of the disk point `r·(along, across)/ρ` is at or
/// past code `c`'s upper boundary `t = T/M` (`T = 2c + 1 - M`, so the boundary is
/// `c + ½`), else `0`. On the side of `t`'s sign the point is past where it lies on or
/// outside the ellipse `x²/t² + y²/(2 - t²) = 1`; `T = 0` is decided by the sign of `x`
/// alone (`x = 0` is past: ties go up).
#[inline(always)]
fn passed<F: Float>(q: Quant, r: &Radius<F>, along: F, across: F, c: F) -> F {
    let m = f64::from(q.max_code());
    let big_t = ((c - F::c(((m - 1.0) * 0.5) as f32)) * F::c(2.0)).named("ell_t");
    // T² through a floor (the identity on an integer), so no contraction reaches it.
    let h = (big_t * big_t).floor().named("ell_h");
    let g = (F::c((2.0 * m * m) as f32) - h).named("ell_g");
    let s = settled_sum(
        (along * along * g).named("ell_p"),
        (across * across * h).named("ell_q"),
    )
    .named("ell_s");
    let (lhs, rhs) = r.square_sides(s, h * g, m * m);
    let (lhs, rhs) = (lhs.named("lhs"), rhs.named("rhs"));
    let up = big_t.gt(F::c(0.0));
    let outside = F::sel(along.gt(F::c(0.0)), one_if(lhs.ge(rhs)), F::c(0.0)).named("outside");
    let inside = F::sel(along.ge(F::c(0.0)), F::c(1.0), one_if(lhs.le(rhs))).named("inside");
    F::sel(up, outside, inside)
}

impl<P: DiskProjection> Codec for Ellipse<P> {
    type P<F: Float> = V3<F>;
    type C<F: Float> = F::U;
    #[inline]
    fn quants(&self) -> Quants {
        disk_quants(self.bits)
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    /// `(u, v)·0.5 + 0.5` of the folded canonical input's square point, and `z < 0`.
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V3<F> {
        let f = Folded::of(v);
        let enc = (Self::square_point(&f) * F::c(SQRT2) + F::c(0.5)).named("enc");
        V3::from_xy(enc, f.h)
    }
    /// The square point `s = enc·2 - 1` on the disk,
    /// `(s.x·sqrt(1 - s.y²/2), s.y·sqrt(1 - s.x²/2))` (each root of a value in
    /// `[½, 1]`); the projection lifts it, and z is negated where the hemisphere bit is
    /// set. Every code lies on the disk, so every code decodes within its hemisphere.
    #[inline(always)]
    fn direction<F: Float>(&self, enc: V3<F>) -> V3<F> {
        let s = (enc.xy() * F::c(2.0) - F::c(1.0)).named("s");
        let stretch = {
            #[inline(always)]
            |a: F| (F::c(1.0) - a * a * F::c(0.5)).sqrt()
        };
        let p = V2::new(s.x * stretch(s.y), s.y * stretch(s.x)).named("disk");
        let (xy, z) = P::lift(p);
        V3::from_xy(xy, unfold(z, enc.z))
    }
    /// The codes of [`Ellipse::codes`], the hemisphere bit from the sign of the
    /// canonical `z`.
    const EXACT_ROUNDING: bool = true;
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V3<F> {
        let f = Folded::of(v);
        V3::from_xy(self.codes(&f), f.h)
    }
}
