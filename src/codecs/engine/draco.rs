//! Draco's octahedral normal quantization (`KHR_draco_mesh_compression`; google/draco
//! 4723893, `src/draco/compression/attributes/normal_compression_utils.h`, last changed
//! in v1.5.4): `OctahedronToolBox`'s `FloatVectorToQuantizedOctahedralCoords`,
//! `CanonicalizeOctahedralCoords` and `QuantizedOctahedralCoordsToUnitVector`, as
//! `attribute_octahedron_transform.cc` calls them. N quantization bits (`draco_oct10`,
//! Draco's `quantization_bits`) give `(s, t)` in `0..=2^N - 2`, stored here as two N-bit
//! fields, s lowest. Draco's octahedron is centred on +X: the right hemisphere maps to
//! `s = y + c`, `t = z + c` in units of `c = 2^(N-1) - 1`.
//!
//! Draco encodes in f64: `i = floor(v/|v|₁·c + ½)` for x and y, z from the remainder
//! `c - |i₀| - |i₁|` (folded into y where negative), then the integer map to `(s, t)` and
//! the canonical form of the border. An f32 chain would differ from it near every code
//! boundary, and exact arithmetic on the ties and near-ties where Draco's own roundings
//! decide, so x's and y's codes follow Draco's f64 operations one rounding at a time, in
//! 32-bit integers ([`draco_codes`]): Draco's codes for every finite input (a denormal
//! component reads as zero). Input whose L1 norm is at most `1e-6` (Draco's threshold,
//! decided on its f64 sum) and NaN input encode as +X, `(c, c)`, as in Draco; infinite
//! input as +Z, `(c, 2c)`, what Draco's f64 arithmetic gives where its cast is defined.
//!
//! The decoder is Draco's f32 arithmetic: `s·(2/(2^N - 2)) - 1`, the fold, and
//! `v·(1/sqrt(v·v))`, or the zero vector where `v·v < 1e-6` (never for a code Draco
//! writes).

use crate::codecs::core::codec::Codec;
use crate::codecs::core::info::Domain;
use crate::codecs::core::codec_family::CodecFamily;
use crate::codecs::core::ieee;
use crate::codecs::core::info::{Info, Sizes, FloatForm, seam};
use crate::codecs::core::pipeline::codec_functions;
use crate::codecs::core::spec::SpecError;
use crate::codecs::engine::draco_f64::draco_codes;
use crate::codecs::toolkit::quant::{Quant, Quants};
use crate::model::num::helper;
use crate::model::{Bool, Float, Uint, V2, V3};

pub static FAMILY: CodecFamily<DracoOct> = CodecFamily::new(
    Info {
        name: "draco_oct",
        title: "Draco's octahedral normal quantization, (s, t) in N bits each",
        sizes: Sizes::PerField {
            count: 2,
            per: &[8, 10, 12, 14, 16],
        },
        domain: Some(Domain::Sphere),
        source: "Draco 1.5.4+ (google/draco 4723893): src/draco/compression/attributes/normal_compression_utils.h (OctahedronToolBox), called by src/draco/attributes/attribute_octahedron_transform.cc",
        edge_policy: "Draco's: NaN input and input whose L1 norm is at most 1e-6 encode as +X, (c, c); infinite input as +Z, (c, 2c), as Draco's f64 arithmetic gives (its cast is undefined where x or y is infinite)",
        decode_note: "QuantizedOctahedralCoordsToUnitVector: a unit vector (to rounding) for every code Draco writes",
        float_form: FloatForm::Continuous { seam: seam::OCTAHEDRAL_FOLD },
        options: &[ieee::ENGINE_OPTION],
    },
    |bits| DracoOct { n: bits / 2 },
    codec_functions,
)
.with_engine("Draco")
.with_helper_doc(|name| (name == "round_codes").then(|| ROUND_CODES_DOC.to_string()));

/// What the emitted `round_codes` helper is: not the shared helper's comparison of
/// rounded products, but Draco's f64 steps.
const ROUND_CODES_DOC: &str = "Draco's integer codes (as floats): its f64 arithmetic repeated one rounding at a time in 32-bit integers and exact float steps, a quotient only estimating a digit that integers then correct, so division error and contraction cannot change them. A denormal component counts as zero, but for the sign of z.";

impl DracoOct {
    /// The codec with `n` quantization bits.
    pub fn new(n: u32) -> Result<DracoOct, SpecError> {
        FAMILY.codec(2 * n)
    }
}

#[derive(Clone, Copy, Debug)]
pub struct DracoOct {
    /// Draco's `quantization_bits`.
    pub n: u32,
}

impl DracoOct {
    /// `max_value = 2^N - 2`, the largest s or t.
    fn max_value(&self) -> f32 {
        ((1u32 << self.n) - 2) as f32
    }
    /// `center_value = max_value / 2`.
    fn center(&self) -> f32 {
        ((1u32 << (self.n - 1)) - 1) as f32
    }
    fn field(&self) -> Quant {
        Quant::Unorm(self.n)
    }
    /// `QuantizedOctahedralCoordsToUnitVector` on integer codes.
    #[inline(always)]
    fn unit_vector<F: Float>(&self, st: V2<F>) -> V3<F> {
        let scale = F::c(2.0 / self.max_value());
        let p = st.map(
            #[inline(always)]
            |c| c * scale - F::c(1.0),
        );
        let x = F::c(1.0) - p.x.abs() - p.y.abs();
        let neg = -x;
        let off = F::sel(neg.lt(F::c(0.0)), F::c(0.0), neg).named("x_offset");
        let yz = p.map(
            #[inline(always)]
            |a| a + F::sel(a.lt(F::c(0.0)), off, -off),
        );
        let v = V3::new(x, yz.x, yz.y).named("v");
        let ns = v.length_squared().named("norm_squared");
        let d = F::c(1.0) / ns.sqrt();
        // `norm_squared < 1e-6` compared in f64: below the f32 just above 1e-6.
        let tiny = ns.lt(F::c(NORM_SQUARED_FLOOR));
        V3::sel_all(tiny, V3::splat(F::c(0.0)), v * d)
    }
}

/// The least f32 above the f64 `1e-6`: `x < 1e-6` in f64 is `x < NORM_SQUARED_FLOOR` for
/// an f32 `x`, and `x > 1e-6` is `x ≥ NORM_SQUARED_FLOOR`.
const NORM_SQUARED_FLOOR: f32 = 1.000_000_1e-6;

impl Codec for DracoOct {
    type P<F: Float> = V2<F>;
    type C<F: Float> = F::U;
    #[inline]
    fn quants(&self) -> Quants {
        Quants::new(&[self.field(); 2])
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    /// The float form: `(s, t)` as an N-bit unorm fetch reads them, already quantized.
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V2<F> {
        let q = self.field();
        helper!(self.round_codes(v)).map(
            #[inline(always)]
            |c| q.dequantize(c),
        )
    }
    /// The fetched values back to `(s, t)`, then Draco's decoder.
    #[inline(always)]
    fn direction<F: Float>(&self, p: V2<F>) -> V3<F> {
        let m = F::c(self.field().max_code());
        let st = p.map(
            #[inline(always)]
            |x| (x * m).round(),
        );
        self.unit_vector(st)
    }
    #[inline(always)]
    fn decode_codes<F: Float>(&self, st: V2<F>) -> V3<F> {
        self.unit_vector(st)
    }
    /// `FloatVectorToQuantizedOctahedralCoords`, its f64 roundings reproduced exactly
    /// ([`draco_codes`]).
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V2<F> {
        let zero = F::c(0.0);
        let (c, mv) = (self.center(), self.max_value());
        let cf = F::c(c);
        let (i0, i1, ok) = draco_codes(v, c as u32);
        let i2 = (cf - i0.abs() - i1.abs()).named("i2");
        let folded = i2.lt(zero);
        let i1 = F::sel(folded, F::sel(i1.gt(zero), i1 + i2, i1 - i2), i1).named("i1");
        let i2 = F::sel(folded, zero, i2);
        let i2 = F::sel(v.z.lt(zero), -i2, i2).named("i2");
        // IntegerVectorToQuantizedOctahedralCoords.
        let mvf = F::c(mv);
        let right = V2::new(i1 + cf, i2 + cf);
        let left = V2::new(
            F::sel(i1.lt(zero), i2.abs(), mvf - i2.abs()),
            F::sel(i2.lt(zero), i1.abs(), mvf - i1.abs()),
        );
        let st = V2::sel_all(i0.ge(zero), right, left).named("st");
        // CanonicalizeOctahedralCoords: the border's duplicate points to one code each.
        let (s, t) = (st.x, st.y);
        let eq = {
            #[inline(always)]
            |a: F, b: f32| a.eq(F::c(b))
        };
        let corner = eq(s, 0.0)
            .and(eq(t, 0.0).or(eq(t, mv)))
            .or(eq(s, mv).and(eq(t, 0.0)));
        let mirror = F::c(2.0 * c);
        let (s, t) = (
            F::sel(
                corner,
                mvf,
                F::sel(
                    eq(s, 0.0).and(t.gt(cf)).or(eq(s, mv).and(t.lt(cf))),
                    s,
                    F::sel(eq(t, mv).and(s.lt(cf)).or(eq(t, 0.0).and(s.gt(cf))), mirror - s, s),
                ),
            ),
            F::sel(
                corner,
                mvf,
                F::sel(eq(s, 0.0).and(t.gt(cf)).or(eq(s, mv).and(t.lt(cf))), mirror - t, t),
            ),
        );
        // Invalid input: +X, but an infinite one (without NaN) is +Z, as Draco's f64
        // arithmetic gives: its scale 1/∞ = 0 zeroes the finite components, and the
        // infinite ones' NaN, cast to an integer, is 0 in a port (undefined in C++).
        let bits = v.map(
            #[inline(always)]
            |x| x.magnitude_bits(),
        );
        let nan = {
            #[inline(always)]
            |b: F::U| b.lt(F::U::c(0x7f80_0001)).not()
        };
        let inf = {
            #[inline(always)]
            |b: F::U| b.lt(F::U::c(0x7f80_0000)).not().and(nan(b).not())
        };
        let any_nan = nan(bits.x).or(nan(bits.y)).or(nan(bits.z));
        let any_inf = inf(bits.x).or(inf(bits.y)).or(inf(bits.z));
        let plus_z = any_inf.and(any_nan.not());
        let invalid = V2::new(cf, F::sel(plus_z, mirror, cf));
        V2::sel_all(ok, V2::new(s, t), invalid).named("codes")
    }
}
