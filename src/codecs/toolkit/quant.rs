//! Scalar quantization (survey eqs. 1–2) and bit-field packing of integer codes.
//!
//! Codes are carried as integral `f32` values: every code of up to 24 bits is exact in
//! f32, so the model never needs signed integers, and two's complement fields of up to 23
//! bits come from `c + 2^b`, converted and masked (see [`Quant::field_at`]); wider ones
//! from `c < 0 ? c + 2^b : c`. A float field ([`Quant::Half`], [`Quant::Single`])
//! carries its value instead, which f32 holds exactly.

use crate::codecs::toolkit::half::{half_bits, half_value};
use crate::model::{Float, Uint, V2, V3};

/// How one parameter is stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Quant {
    /// `c = round(clamp(x,-1,1)·M)`, `x = max(c·(1/M), -1)`, `M = 2^(b-1)-1`; two's complement field.
    Snorm(u32),
    /// `c = round(clamp(x,0,1)·M)`, `x = c·(1/M)`, `M = 2^b-1`.
    Unorm(u32),
    /// An IEEE binary16 field ([`crate::codecs::toolkit::half`]): the "code" is the f16 value itself, held
    /// exactly in f32, and the field its bits; a zero is stored as +0.
    Half,
    /// An IEEE binary32 field: the "code" is the value itself and the field its bits; a
    /// zero is stored as +0, and a field with a zero exponent (a denormal, which an
    /// implementation may flush) is read as +0.
    Single,
}

// The methods the models call are `#[inline]`: the CPU slices evaluate them once per group
// of lanes, and only inlined into the slice's loop do a codec's fields (widths, scales,
// offsets) become constants worked out once per slice (README, "Speed").
impl Quant {
    #[inline]
    pub fn bits(self) -> u32 {
        match self {
            Quant::Snorm(b) | Quant::Unorm(b) => b,
            Quant::Half => 16,
            Quant::Single => 32,
        }
    }
    /// The largest code, `M` (for [`Quant::Half`], the largest finite f16).
    #[inline]
    pub fn max_code(self) -> f32 {
        match self {
            Quant::Snorm(b) => ((1u32 << (b - 1)) - 1) as f32,
            Quant::Unorm(b) => ((1u64 << b) - 1) as f32,
            Quant::Half => 65504.0,
            Quant::Single => f32::MAX,
        }
    }
    #[inline]
    pub fn min_code(self) -> f32 {
        match self {
            Quant::Snorm(_) | Quant::Half | Quant::Single => -self.max_code(),
            Quant::Unorm(_) => 0.0,
        }
    }
    #[inline]
    fn lo(self) -> f32 {
        match self {
            Quant::Snorm(_) | Quant::Half | Quant::Single => -1.0,
            Quant::Unorm(_) => 0.0,
        }
    }
    pub fn name(self) -> String {
        match self {
            Quant::Snorm(b) => format!("snorm{b}"),
            Quant::Unorm(b) => format!("unorm{b}"),
            Quant::Half => "float16".to_string(),
            Quant::Single => "float32".to_string(),
        }
    }
    /// Clamps to the storage range; NaN goes to the low end (comparisons with NaN are false).
    #[inline(always)]
    pub fn clamp<F: Float>(self, x: F) -> F {
        x.clamped(F::c(self.lo()), F::c(1.0))
    }
    /// The code nearest to `x`, ties to even.
    #[inline(always)]
    pub fn quantize<F: Float>(self, x: F) -> F {
        match self {
            Quant::Half => half_value(half_bits(self.clamp(x))),
            Quant::Single => self.clamp(x),
            _ => (self.clamp(x) * F::c(self.max_code())).round(),
        }
    }
    /// The code nearest to `x`, ties to even, for an `x` already in range and not NaN
    /// (an integer field).
    #[inline(always)]
    pub fn quantize_in_range<F: Float>(self, x: F) -> F {
        assert!(!self.is_float(), "a float field is stored, not rounded");
        (x * F::c(self.max_code())).round()
    }
    /// The code at or below `x`: where a precise search starts. Precise searches step
    /// through integer codes, which a float field does not have.
    #[inline(always)]
    pub fn floor_code<F: Float>(self, x: F) -> F {
        assert!(!self.is_float(), "no precise search over float fields");
        (self.clamp(x) * F::c(self.max_code())).floor()
    }
    /// Clamps a candidate code to the valid codes.
    #[inline(always)]
    pub fn clamp_code<F: Float>(self, c: F) -> F {
        c.at_most(F::c(self.max_code()))
    }
    #[inline(always)]
    pub fn dequantize<F: Float>(self, c: F) -> F {
        match self {
            Quant::Snorm(_) => (c * F::c(1.0 / self.max_code())).at_least_nonzero(-1.0),
            Quant::Unorm(_) => c * F::c(1.0 / self.max_code()),
            Quant::Half | Quant::Single => c,
        }
    }
    /// Whether the field holds a float's bits rather than an integer code.
    #[inline]
    pub fn is_float(self) -> bool {
        matches!(self, Quant::Half | Quant::Single)
    }
    /// The unsigned bit field of a code, shifted left by `sh`. A snorm code of up to 23
    /// bits is stored as `(c + 2^b) & mask`: `c + 2^b` is positive and below `2^24`, so
    /// exact and safely converted, and the mask drops the `2^b` (or the shift does, for
    /// a field that ends at bit 32) — one instruction fewer than `c < 0 ? c + 2^b : c`,
    /// which a wider field still needs (`2^24 + c` is not exact).
    #[inline(always)]
    pub fn field_at<F: Float>(self, c: F, sh: u32) -> F::U {
        let shifted = {
            #[inline(always)]
            |u: F::U| if sh == 0 { u } else { u.shl(sh) }
        };
        match self {
            Quant::Snorm(b) if b < 24 => {
                let u = shifted((c + F::c((1u32 << b) as f32)).to_u());
                if sh + b == 32 {
                    u
                } else {
                    u & F::U::c(self.mask() << sh)
                }
            }
            _ => shifted(self.to_field(c)),
        }
    }
    /// The unsigned bit field of a code.
    #[inline(always)]
    fn to_field<F: Float>(self, c: F) -> F::U {
        match self {
            Quant::Snorm(b) => {
                let wrapped = c + F::c((1u64 << b) as f32);
                F::sel(c.lt(F::c(0.0)), wrapped, c).to_u()
            }
            Quant::Unorm(_) => c.to_u(),
            // Selects may lose the sign of a zero on some implementations, so a zero
            // is always stored as +0.
            Quant::Half => {
                let h = half_bits(c);
                F::U::sel((h & F::U::c(0x7fff)).lt(F::U::c(1)), F::U::c(0), h)
            }
            Quant::Single => plus_zero_below_normal(c.to_bits()),
        }
    }
    /// The code held in an unsigned bit field (already masked to `bits`).
    #[inline(always)]
    pub fn from_field<F: Float>(self, u: F::U) -> F {
        match self {
            Quant::Snorm(b) if b <= 24 => u.signed_field(b),
            Quant::Snorm(b) => {
                let c = u.to_f();
                let wrapped = c - F::c((1u64 << b) as f32);
                F::sel(c.gt(F::c(self.max_code())), wrapped, c)
            }
            Quant::Unorm(_) => u.to_f(),
            Quant::Half => half_value(u),
            Quant::Single => plus_zero_below_normal(u).as_float(),
        }
    }
    #[inline]
    pub fn mask(self) -> u32 {
        ((1u64 << self.bits()) - 1) as u32
    }
}

/// A parameter in `[-1, 1]` has two storages: a snorm field holds `c = p·M`, a unorm
/// field (a normal-map texel's channel) `c = (p·½ + ½)·M`. Both are the point
/// `p = s/M` of the signed lattice value `s`: the snorm code itself, or `2c - M`
/// for a unorm code (odd integers), which the fixed-point decodes of the precise
/// searches take.
#[inline(always)]
pub fn signed_code<F: Float>(q: Quant, c: F) -> F {
    match q {
        Quant::Unorm(_) => c + c - F::c(q.max_code()),
        _ => c,
    }
}

/// The code of the signed lattice value `s` ([`signed_code`]): `s`, or `(s + M)/2`.
#[inline(always)]
pub fn unsigned_code<F: Float>(q: Quant, s: F) -> F {
    match q {
        Quant::Unorm(_) => (s + F::c(q.max_code())) * F::c(0.5),
        _ => s,
    }
}

/// The code `p = 0` rounds to: `0`, or for a unorm field `(M + 1)/2` (ties up), the
/// code invalid input takes in either storage.
#[inline]
pub fn zero_code(q: Quant) -> f32 {
    match q {
        Quant::Unorm(_) => (q.max_code() + 1.0) * 0.5,
        _ => 0.0,
    }
}

/// The fields of a codec, without a heap allocation per encoded vector.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Quants {
    q: [Quant; 4],
    n: usize,
}

impl Quants {
    #[inline]
    pub fn new(fields: &[Quant]) -> Quants {
        let mut q = [fields[0]; 4];
        q[..fields.len()].copy_from_slice(fields);
        Quants { q, n: fields.len() }
    }
}

impl std::ops::Deref for Quants {
    type Target = [Quant];
    #[inline]
    fn deref(&self) -> &[Quant] {
        &self.q[..self.n]
    }
}

/// The bits of an f32 with zeros and denormals (exponent field 0) as `+0`, decided on the
/// bits: an implementation may flush a denormal or lose the sign of a zero, so neither
/// may reach a stored field or a decoded value.
#[inline(always)]
fn plus_zero_below_normal<U: Uint>(b: U) -> U {
    U::sel((b & U::c(0x7f80_0000)).lt(U::c(1)), U::c(0), b)
}

/// A packed code: one `u32`, two for layouts wider than 32 bits (snorm16×3), or three
/// (float32×3).
pub trait Code<F: Float>: crate::model::trace::Value {
    const WORDS: usize;
    fn word(self, i: usize) -> F::U;
    fn from_words(w: [F::U; 3]) -> Self;
}

impl<F: Float<U = U>, U: Uint<F = F>> Code<F> for U {
    const WORDS: usize = 1;
    #[inline]
    fn word(self, _: usize) -> U {
        self
    }
    #[inline]
    fn from_words(w: [U; 3]) -> Self {
        w[0]
    }
}

impl<F: Float<U = U>, U: Uint<F = F>> Code<F> for V2<U> {
    const WORDS: usize = 2;
    #[inline]
    fn word(self, i: usize) -> U {
        if i == 0 { self.x } else { self.y }
    }
    #[inline]
    fn from_words(w: [U; 3]) -> Self {
        V2::new(w[0], w[1])
    }
}

impl<F: Float<U = U>, U: Uint<F = F>> Code<F> for V3<U> {
    const WORDS: usize = 3;
    #[inline]
    fn word(self, i: usize) -> U {
        [self.x, self.y, self.z][i]
    }
    #[inline]
    fn from_words(w: [U; 3]) -> Self {
        V3::new(w[0], w[1], w[2])
    }
}

/// The width of a packed code: where its last field ends.
pub fn code_width(quants: &[Quant]) -> u32 {
    let offs = field_offsets(quants);
    quants
        .iter()
        .zip(offs)
        .map(|(q, o)| o + q.bits())
        .max()
        .unwrap_or(0)
}

/// Bit offset of each field, first field in the lowest bits, no field straddling a word.
/// A fixed array (unused entries 0): this runs once per encoded vector on the CPU.
#[inline]
pub fn field_offsets(quants: &[Quant]) -> [u32; 4] {
    let mut offs = [0; 4];
    let mut off = 0;
    for (o, q) in offs.iter_mut().zip(quants) {
        if off / 32 != (off + q.bits() - 1) / 32 {
            off = (off / 32 + 1) * 32;
        }
        *o = off;
        off += q.bits();
    }
    offs
}

/// C's `round`: halves away from zero (the model's `round` takes them to even). Exact
/// for every float: `|x| - floor(|x|)` is exact, and at `2^23` and above `x` is integral.
/// A NaN stays NaN.
#[inline(always)]
pub fn round_half_away<F: Float>(x: F) -> F {
    let a = x.abs();
    let f = a.floor();
    let r = f + F::sel((a - f).ge(F::c(0.5)), F::c(1.0), F::c(0.0));
    F::sel(x.lt(F::c(0.0)), -r, r)
}

/// C's conversion of a float to an integer (`int(x)`, `(uint)x`): toward zero, kept as a
/// float. A NaN stays NaN.
#[inline(always)]
pub fn truncated<F: Float>(x: F) -> F {
    let t = x.abs().floor();
    F::sel(x.lt(F::c(0.0)), -t, t)
}

/// Whether `x` is not NaN, decided on its bits: a float comparison of `x` with itself may
/// be folded to true where `precise` is absent.
#[inline(always)]
pub fn not_nan<F: Float>(x: F) -> F::B {
    x.magnitude_bits().lt(F::U::c(0x7f80_0001))
}
