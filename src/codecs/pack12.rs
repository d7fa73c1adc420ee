//! snorm12×2 ↔ unorm8×3 (survey §3.3, Listings 4–5): two 12-bit parameters in the three
//! bytes of an RGB8 texel, stored biased (`u = c + 2047`, bytes `u.x>>4`,
//! `(u.x&15)<<4 | u.y>>8`, `u.y&255`). Each direction exists in an integer form and a
//! float-only form for hardware without fast integers; `tests/pack12.rs` proves the two
//! forms bit-equal on all 2^24 inputs. The unpack ends in `(s - 2047)·(1/2047)` rather than
//! the listing's `s·(1/2047) - 1`, which misses zero by an ulp.

use super::codec::{Codec, Domain, precise_search};
use super::oct::{Oct, oct_direction, oct_params};
use super::quant::{Quant, Quants};
use crate::model::{Float, Uint, V2, V3};

const BIAS: f32 = 2047.0;

/// The biased 12-bit integers `round(clamp(f,-1,1)·2047 + 2047)`.
fn biased<F: Float>(f: V2<F>) -> V2<F> {
    let c = f.map(|x| Quant::Snorm(12).clamp(x));
    (c * F::c(BIAS) + F::c(BIAS)).round().named("u")
}

/// Bytes of biased integers, with float arithmetic only (exact: every value is an integer
/// below 2^12 and every scale a power of two).
fn bytes_float<F: Float>(u: V2<F>) -> V3<F> {
    let x16 = (u.x * F::c(1.0 / 16.0)).named("x16");
    let hi = x16.floor().named("hi");
    let t = (u.y * F::c(1.0 / 256.0)).floor().named("t");
    V3::new(hi, (x16 - hi) * F::c(256.0) + t, u.y - t * F::c(256.0))
}

/// Float-only pack (Listing 5): unorm8 values in [0, 1] for an RGB8 target.
pub fn to_unorm8x3<F: Float>(f: V2<F>) -> V3<F> {
    bytes_float(biased(f)) * F::c(1.0 / 255.0)
}

/// Integer pack (Listing 4): the same values through shifts and masks.
pub fn to_unorm8x3_int<F: Float>(f: V2<F>) -> V3<F> {
    let u = biased(f).to_u();
    let b = V3::new(
        u.x.shr(4),
        (u.x & F::U::c(15)).shl(4) | u.y.shr(8),
        u.y & F::U::c(255),
    );
    b.map(|x| x.to_f()) * F::c(1.0 / 255.0)
}

/// `(s - 2047)·(1/2047)`, clamped to [-1, 1].
fn unbias<F: Float>(s: V2<F>) -> V2<F> {
    let f = (s - F::c(BIAS)) * F::c(1.0 / BIAS);
    V2::sel(f.le(V2::splat(F::c(1.0))), f, V2::splat(F::c(1.0)))
}

/// Float-only unpack (Listing 5) of unorm8 values as delivered by an RGB8 fetch.
pub fn from_unorm8x3<F: Float>(u: V3<F>) -> V2<F> {
    let b = (u * F::c(255.0)).round().named("b");
    let y16 = (b.y * F::c(1.0 / 16.0)).named("y16");
    let hi = y16.floor().named("hi");
    let s = V2::new(b.x * F::c(16.0) + hi, (y16 - hi) * F::c(4096.0) + b.z);
    unbias(s)
}

/// Integer unpack (Listing 4).
pub fn from_unorm8x3_int<F: Float>(u: V3<F>) -> V2<F> {
    let b = (u * F::c(255.0)).round().to_u().named("b");
    let p = V2::new(b.x.shl(4) | b.y.shr(4), (b.y & F::U::c(15)).shl(8) | b.z);
    unbias(p.to_f())
}

/// oct24 in the three bytes of an RGB8 texel (survey §3.3). The float form is the
/// three unorm8 values; the packed form is the RGB8 texel (R in the lowest byte).
#[derive(Clone, Copy, Debug)]
pub struct Oct24Rgb8;

impl Codec for Oct24Rgb8 {
    type P<F: Float> = V3<F>;
    type C<F: Float> = F::U;
    fn quants(&self) -> Quants {
        Quants::new(&[Quant::Unorm(8); 3])
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    fn params<F: Float>(&self, v: V3<F>) -> V3<F> {
        let e = oct_params(v).named("e");
        F::call("snorm12x2_to_unorm8x3", e, to_unorm8x3)
    }
    fn direction<F: Float>(&self, u: V3<F>) -> V3<F> {
        let e = F::call("unorm8x3_to_snorm12x2", u, from_unorm8x3).named("e");
        oct_direction(e)
    }
    /// The oct24 precise search, then its 12-bit codes split into bytes.
    fn precise_codes<F: Float>(&self, v: V3<F>) -> V3<F> {
        let c = precise_search(&Oct { bits: 24 }, v, "oct24_decode_float");
        bytes_float(c + F::c(BIAS))
    }
}
