//! What the hemisphere-to-disk codecs (`stereo`, `eqarea`, `eqdist`; survey §2) and their
//! concentric-map and elliptical-map variants ([`crate::codecs::azimuthal::concentric`],
//! [`crate::codecs::azimuthal::ellipse`]) share: the layout of a hemisphere bit
//! beside two unorm parameters, the folded canonical input, and [`DiskProjection`].
//!
//! Layout: a total of `B` bits is one hemisphere bit and two parameters of `⌈(B-1)/2⌉`
//! and `⌊(B-1)/2⌋` bits (16 = 1 + 8 + 7), x in the lowest bits, then y, then the
//! hemisphere bit (1 for `z < 0`) at bit `B - 1`. Parameters are the disk point `p`
//! stored as unorm `p·0.5 + 0.5`. This is the split that reproduces the survey's Table 1
//! rows (1 + 7 + 7, a wasted bit, makes every mean about 30 % worse; snorm parameters are
//! within 1 % of unorm ones, unorm matches best at 16 bits).

use crate::codecs::toolkit::exact::{canonical_or_z, fixed_length2, one_if, past_root_ratio, root};
use crate::codecs::toolkit::fixed_decode::{BITS, fixed_square_point, fixed_target, nearest_decoded};
use crate::codecs::toolkit::quant::{Quant, Quants};
use crate::model::{Float, V2, V3};

/// The two parameters' fields of a `bits`-bit code.
pub fn disk_fields(bits: u32) -> [Quant; 2] {
    let rest = bits - 1;
    [Quant::Unorm(rest.div_ceil(2)), Quant::Unorm(rest / 2)]
}

/// The parameters' fields and the hemisphere bit.
pub fn disk_quants(bits: u32) -> Quants {
    let [qx, qy] = disk_fields(bits);
    Quants::new(&[qx, qy, Quant::Unorm(1)])
}

/// The input folded onto the +Z hemisphere, as the portable encoders see it.
#[derive(Clone, Copy)]
pub struct Folded<F: Float> {
    /// The canonical input ([`canonical_or_z`]: invalid input is canonical +Z).
    pub w: V3<F>,
    /// Its length ([`root`]).
    pub l: F,
    /// `l + |w.z|`: `l·(1 + |z|)` of the unit direction, a sum of positives, never 0.
    pub a: F,
    /// The hemisphere bit: 1 where the canonical `z < 0` (a `-0` is already `+0` there,
    /// so the equator is on the +Z side).
    pub h: F,
}

impl<F: Float> Folded<F> {
    #[inline(always)]
    pub fn of(v: V3<F>) -> Self {
        let (w, _) = canonical_or_z(v);
        let l = root(fixed_length2(w));
        Folded {
            w,
            l,
            a: l + w.z.abs(),
            h: one_if(w.z.lt(F::c(0.0))),
        }
    }
}

/// `z` on the hemisphere the bit `h` (0 or 1) names ([`Float::negated_where`], so that a
/// `z` of `1 - q` keeps the model's signed zero on every compiler).
#[inline(always)]
pub fn unfold<F: Float>(z: F, h: F) -> F {
    z.negated_where(h.gt(F::c(0.5)))
}

/// The disk point of codes `c` in units of `2^-21` ([`crate::codecs::toolkit::fixed_decode`]), for the
/// precise searches, and `q = |p|²`: [`fixed_square_point`] of the parameters' fields.
#[inline(always)]
pub fn fixed_disk_point<F: Float>(bits: u32, c: V2<F>) -> (V2<F>, F) {
    fixed_square_point(disk_fields(bits), c)
}

/// A disk codec's precise codes: of the four codes around `base` (the floors), in the
/// input's hemisphere, the one whose fixed-point decode (`decode(codes, h)`) is nearest
/// the input's by exact squared distance ([`nearest_decoded`]), with the hemisphere bit.
#[inline(always)]
pub fn nearest_disk_codes<F: Float>(
    bits: u32,
    f: &Folded<F>,
    base: V2<F>,
    decode: impl Fn(V2<F>, F) -> V3<F>,
) -> V3<F> {
    let target = fixed_target(f.w, f.l, BITS);
    let best = nearest_decoded(
        disk_fields(bits),
        base,
        target,
        #[inline(always)]
        |c| decode(c, f.h),
    );
    V3::from_xy(best, f.h)
}

/// A projection of the hemisphere onto the unit disk, as the codecs that map its disk
/// onto the square ([`crate::codecs::azimuthal::concentric`], [`crate::codecs::azimuthal::ellipse`]) use it: the radius of the folded input's disk
/// point (the point's azimuth is the input's), and the way back from a disk point.
pub trait DiskProjection: Copy + Send + Sync + std::fmt::Debug + 'static {
    /// Half the disk radius, `r/2`, in floats (the `encode_float` model), given `rho`,
    /// the float length of `f.w.xy`.
    fn half_radius<F: Float>(f: &Folded<F>, rho: F) -> F;
    /// The disk radius as the portable encoders decide it.
    fn radius<F: Float>(f: &Folded<F>) -> Radius<F>;
    /// The +Z-hemisphere direction of the disk point `p`, as its `xy` and `z`.
    fn lift<F: Float>(p: V2<F>) -> (V2<F>, F);
}

/// A disk radius `r` as functions of the input alone, so that whether `r·x` lies past a
/// boundary `k` is decided the same on every implementation (see [`crate::codecs::toolkit::exact`]).
pub enum Radius<F> {
    /// `r = sqrt(rho2 / d)`, `rho2 ≥ 0` and `d > 0` deterministic.
    Root { rho2: F, d: F },
    /// `r = θ/(π/2)`: `t` the polar angle in units of `2^-23` half turns, an integer;
    /// `rho2` the deterministic `|w.xy|²` of the input whose disk point this is.
    Angle { t: F, rho2: F },
}

impl<F: Float> Radius<F> {
    /// Any estimate of `r` (within a few ULP), for a first guess of a code.
    #[inline(always)]
    pub fn estimate(&self) -> F {
        match *self {
            Radius::Root { rho2, d } => (rho2 / d).sqrt(),
            Radius::Angle { t, .. } => t * F::c(ANGLE_TO_RADIUS),
        }
    }
    /// `1` where `r·x ≥ k`, else `0`. `x` and `k` are deterministic; the products are
    /// single roundings meeting in a comparison (for a root, of squares, with the signs
    /// decided first by [`past_root_ratio`]), so no contraction or regrouping reaches
    /// them. `x` may be negative only where `r > 0`.
    #[inline(always)]
    pub fn past(&self, x: F, k: F) -> F {
        match *self {
            Radius::Root { rho2, d } => past_root_ratio(x, rho2 * (x * x), k, k * k * d),
            Radius::Angle { t, .. } => one_if((t * x * F::c(ANGLE_TO_RADIUS)).ge(k)),
        }
    }
    /// The two sides of `(r²/ρ²)·s·scale` against `k` (`s, k ≥ 0`, `scale > 0` a
    /// literal; `ρ = |w.xy|` of the input whose disk point `r·w.xy/ρ` this radius belongs
    /// to), each multiplied by the same positive factor, as products of deterministic
    /// values meeting in a comparison: `(s·scale, k·d)` for a root (`r²/ρ² = 1/d`),
    /// `(s·t²·2^-44·scale, k·ρ²)` for an angle. The literal is the last factor: Mesa
    /// moves a literal out of a product used once, `(a·#b)·c` into `(a·c)·#b`, which
    /// rounds differently. This is what a quadric in the disk point's squared
    /// coordinates asks of the radius ([`crate::codecs::azimuthal::ellipse`]).
    #[inline(always)]
    pub fn square_sides(&self, s: F, k: F, scale: f64) -> (F, F) {
        match *self {
            Radius::Root { d, .. } => (s * F::c(scale as f32), k * d),
            Radius::Angle { t, rho2 } => (
                s * t * t * F::c((scale * f64::from(ANGLE_SQUARED)) as f32),
                k * rho2,
            ),
        }
    }
}

/// `r² = t²·2^-44` from units of `2^-23` half turns (the square of `ANGLE_TO_RADIUS`).
const ANGLE_SQUARED: f32 = 1.0 / 17_592_186_044_416.0;

/// `r = θ/(π/2) = 2·(θ/π)`, from units of `2^-23` half turns: `2^-22`.
const ANGLE_TO_RADIUS: f32 = 1.0 / 4_194_304.0;
