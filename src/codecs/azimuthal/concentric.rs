//! The disk codecs' disk mapped onto the whole square by Shirley and Chiu's concentric
//! map (survey §2, `stereo+concentric`, `eqarea+concentric`, `eqdist+concentric`), so
//! that no code is spent outside the disk.
//!
//! A disk point of radius `r` and azimuth `φ` goes to the square point `(a, b)`: where
//! the azimuth is nearer the x axis (`|x| ≥ |y|`), `a = ±r` (the sign of `x`) and
//! `b = r·atan(y/|x|)/(π/4)`; elsewhere the roles of the axes swap. Both coordinates are
//! linear in `r`, and the angle depends on the input's `x` and `y` alone, so each code is
//! `r` times a multiplier: `±1`, or the angle from [`fixed_trig::atan2_pi`] (an exact
//! integer). The projection decides `r·x ≥ k` exactly ([`Radius::past`]), so every code is
//! decided on every implementation alike. The layout is [`crate::codecs::azimuthal::disk`]'s: the square
//! point stored as unorm `(a, b)·0.5 + 0.5`, x lowest, then y, then the hemisphere bit.
//!
//! The decoder inverts the map: `r = |a|` and `φ = (π/4)·(b/|a|)` where `|a| ≥ |b|`
//! (one quotient, then the model's sine and cosine), and the projection lifts the disk
//! point.

use crate::model::num::helper;
use crate::codecs::core::codec::Codec;
use crate::codecs::core::info::Domain;
use crate::codecs::azimuthal::disk::{DiskProjection, Folded, disk_fields, disk_quants, unfold};
use crate::codecs::toolkit::exact::decided;
use crate::codecs::core::info::Info;
use crate::codecs::toolkit::fixed_trig;
use crate::codecs::toolkit::quant::{Quant, Quants};
use crate::codecs::core::spec::SpecError;
use crate::codecs::toolkit::trig::{atan2_pi, sincos_quarter_pi};
use crate::model::{Float, V2, V3};
use std::marker::PhantomData;

/// A hemisphere-to-disk projection `P` composed with the concentric map. `P` is only a
/// type: its arithmetic is in associated functions, so the codec holds no value of it.
#[derive(Clone, Copy, Debug)]
pub struct Concentric<P> {
    pub bits: u32,
    projection: PhantomData<P>,
}

impl<P: DiskProjection> Concentric<P> {
    /// The codec with the given total bit budget, for the family `info`; an invalid size
    /// is an error listing the allowed ones.
    #[inline(always)]
    pub fn with(info: &'static Info, bits: u32) -> Result<Self, SpecError> {
        Ok(Concentric {
            bits: info.check_bits(bits)?,
            projection: PhantomData,
        })
    }

    /// The unorm codes of the folded input at the boundaries `c + offset` (`½` rounds to
    /// the nearest code, ties up). The major axis is the one with the larger input
    /// component (`x` on a tie); its code is `r·(±M/2) + M/2`, the other's
    /// `r·T·(M/2)·2^-21 + M/2`, `T` the angle from the major axis in units of `2^-23`
    /// half turns (so `T·2^-21` is the angle over `π/4`, in `[-1, 1]`). Each boundary is
    /// decided by [`crate::codecs::azimuthal::disk::Radius::past`] from the multiplier, a select of two
    /// literals or one product with the literal last.
    #[inline(always)]
    pub fn codes<F: Float>(&self, f: &Folded<F>, offset: f32) -> V2<F> {
        let r = P::radius(f);
        let estimate = r.estimate().named("r");
        let x_major = f.w.x.abs().ge(f.w.y.abs());
        let major = F::sel(x_major, f.w.x, f.w.y).named("major");
        let minor = F::sel(x_major, f.w.y, f.w.x).named("minor");
        let t = fixed_trig::atan2_pi(minor, major.abs()).named("t");
        let neg = major.lt(F::c(0.0));
        let code = {
            #[inline(always)]
            |q: Quant, x_field: bool| {
                let m = q.max_code();
                let along = F::sel(neg, F::c(-m * 0.5), F::c(m * 0.5));
                let across = t * F::c((f64::from(m) / f64::from(1u32 << 22)) as f32);
                let (a, b) = if x_field {
                    (along, across)
                } else {
                    (across, along)
                };
                let x = F::sel(x_major, a, b).named("x");
                let first = (estimate * x + F::c(m * 0.5)).round();
                decided(
                    q,
                    first,
                    #[inline(always)]
                    |c| r.past(x, c - F::c(m * 0.5 - offset)),
                )
            }
        };
        let [qx, qy] = disk_fields(self.bits);
        V2::new(code(qx, true), code(qy, false))
    }
}

impl<P: DiskProjection> Codec for Concentric<P> {
    type P<F: Float> = V3<F>;
    type C<F: Float> = F::U;
    #[inline]
    fn quants(&self) -> Quants {
        disk_quants(self.bits)
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    /// `(a, b)·0.5 + 0.5` of the folded canonical input's disk point, and `z < 0`: the
    /// half radius from the projection, the angle from the model's [`atan2_pi`].
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V3<F> {
        let f = Folded::of(v);
        let rho = f.w.xy().length_squared().sqrt().named("rho");
        let half = P::half_radius(&f, rho).named("half_r");
        let x_major = f.w.x.abs().ge(f.w.y.abs());
        let major = F::sel(x_major, f.w.x, f.w.y).named("major");
        let minor = F::sel(x_major, f.w.y, f.w.x).named("minor");
        let t = helper!(atan2_pi(minor, major.abs()))
        .named("t");
        let along = F::sel(major.lt(F::c(0.0)), -half, half);
        let across = half * t * F::c(4.0);
        let enc = V2::new(
            F::sel(x_major, along, across),
            F::sel(x_major, across, along),
        ) + F::c(0.5);
        V3::from_xy(enc.named("enc"), f.h)
    }
    /// The square point `s = enc·2 - 1` back on the disk: with `a` the coordinate of
    /// larger magnitude (`x` on a tie) and `b` the other, the radius is `r = |a|`
    /// (computed as `max(|s.x|, |s.y|)`) and the angle from `a`'s half axis
    /// `φ = (π/4)·(b/r)`, so the disk point is `(a·cos φ, r·sin φ)`, axes swapped back
    /// ([`sincos_quarter_pi`]); the projection lifts it, and z is negated where the
    /// hemisphere bit is set. Every code lies on the disk, so every code decodes within
    /// its hemisphere.
    ///
    /// Written so that no rounding an implementation may do differently decides a
    /// branch: `s = enc·2 - 1` is exact even when contracted, so the side of the square
    /// is the same everywhere, and the sine and cosine of `|φ| ≤ π/4` take no range
    /// reduction (on a diagonal `φ` is exactly `±π/4`, where a reduction would branch on
    /// a quotient). Both sides' points are computed and one is chosen last, so that
    /// codes on either side of a diagonal are smooth functions up to the choice. That
    /// is what lets the decoder's bound be proven in reasonable time.
    #[inline(always)]
    fn direction<F: Float>(&self, enc: V3<F>) -> V3<F> {
        let s = (enc.xy() * F::c(2.0) - F::c(1.0)).named("s");
        let r = s.x.abs().at_least(s.y.abs()).named("r");
        let div = F::sel(r.gt(F::c(0.0)), r, F::c(1.0));
        let angle = (s / div * F::c(0.25)).named("angle");
        // Both sides' points, then the choice: each is a smooth function of the code.
        let on_x = helper!(sincos_quarter_pi(angle.y))
        .named("on_x");
        let on_y = helper!(sincos_quarter_pi(angle.x))
        .named("on_y");
        let x_side = V2::new(s.x * on_x.y, r * on_x.x);
        let y_side = V2::new(r * on_y.x, s.y * on_y.y);
        let x_major = s.x.abs().ge(s.y.abs());
        let p = V2::new(
            F::sel(x_major, x_side.x, y_side.x),
            F::sel(x_major, x_side.y, y_side.y),
        )
        .named("disk");
        let (xy, z) = P::lift(p);
        V3::from_xy(xy, unfold(z, enc.z))
    }
    /// The codes of [`Concentric::codes`] at `c + ½`, the hemisphere bit from the sign
    /// of the canonical `z`.
    const EXACT_ROUNDING: bool = true;
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V3<F> {
        let f = Folded::of(v);
        V3::from_xy(self.codes(&f, 0.5), f.h)
    }
}
