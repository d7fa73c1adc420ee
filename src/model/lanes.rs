//! The vocabulary on four lanes at once ([`F4`], [`U4`], [`M4`] over `wide`'s SSE2 types),
//! so that the CPU batches evaluate the same generic codec definitions four vectors per
//! step on every x86-64 processor (eight per step on AVX2 lanes where the processor has
//! them, [`super::avx2_lanes`]). Every operation is the scalar model's, lane by lane, bit for bit: IEEE `+ - * /`
//! and `sqrt` are correctly rounded in both; `round`, `floor`, `abs` and negation are
//! written here with the very steps the scalar `f32` model uses (`src/model/num.rs`), and
//! the conversions emulate Rust's `as` (saturating `f32 → u32`, correctly rounded
//! `u32 → f32`) for every input, rather than trust instructions whose edge cases (signs
//! of zero, NaN, out-of-range values) differ.

use super::num::{Bool, Float, Kind, Lane, Uint};
use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Sub};
use wide::bytemuck::cast;
use wide::{f32x4, i32x4, u32x4};

/// Four f32 lanes.
#[derive(Clone, Copy, Debug)]
pub struct F4(pub f32x4);
/// Four u32 lanes.
#[derive(Clone, Copy, Debug)]
pub struct U4(pub u32x4);
/// Four comparison results, all bits set where true.
#[derive(Clone, Copy, Debug)]
pub struct M4(pub u32x4);

const SIGN: u32 = 0x8000_0000;

impl F4 {
    #[inline(always)]
    fn bits(self) -> u32x4 {
        cast(self.0)
    }
    #[inline(always)]
    fn of_bits(b: u32x4) -> F4 {
        F4(cast(b))
    }
    #[inline(always)]
    fn mask(m: f32x4) -> M4 {
        M4(cast(m))
    }
    /// `f32::round_ties_even` as the scalar model computes it: `(|x| + 2^23) - 2^23` with
    /// the sign of `x` below 2^23, `x` itself above (and for infinities and NaN).
    #[inline(always)]
    fn round_even(self) -> F4 {
        let two_23 = f32x4::splat(8_388_608.0);
        let a = self.abs();
        let r = F4((a.0 + two_23) - two_23).bits() | (self.bits() & u32x4::splat(SIGN));
        F4::sel(a.lt(F4(two_23)), F4::of_bits(r), self)
    }
}

/// Lanes to and from the words of `N` items, one word each: how the batch runner and the
/// slice APIs move items between memory and the evaluation (f32 lanes as their bits).
pub trait LaneIo<const N: usize>: Float {
    fn from_words(w: [u32; N]) -> Self;
    fn words(self) -> [u32; N];
    fn u_from_words(w: [u32; N]) -> Self::U;
    fn u_words(u: Self::U) -> [u32; N];
    /// `N` items of three words each (vectors, as their `f32` bits, and three-word codes)
    /// as three lanes: lane `j` holds word `j` of every item.
    #[inline(always)]
    fn u_from_items3(items: &[[u32; 3]; N]) -> [Self::U; 3] {
        std::array::from_fn(|j| Self::u_from_words(std::array::from_fn(|k| items[k][j])))
    }
    /// The inverse of [`LaneIo::u_from_items3`]: word `j` of item `k` from lane `j`.
    #[inline(always)]
    fn u_to_items3(lanes: [Self::U; 3], items: &mut [[u32; 3]; N]) {
        let words = lanes.map(Self::u_words);
        for (k, item) in items.iter_mut().enumerate() {
            *item = std::array::from_fn(|j| words[j][k]);
        }
    }
    /// `N` items of two words each (64-bit codes) as two lanes, as
    /// [`LaneIo::u_from_items3`].
    #[inline(always)]
    fn u_from_items2(items: &[[u32; 2]; N]) -> [Self::U; 2] {
        std::array::from_fn(|j| Self::u_from_words(std::array::from_fn(|k| items[k][j])))
    }
    /// `N` items of seven words each (a decoded frame: `n`, then `t` with the sign) from
    /// seven lanes, as [`LaneIo::u_to_items3`].
    #[inline(always)]
    fn u_to_items7(lanes: [Self::U; 7], items: &mut [[u32; 7]; N]) {
        let words = lanes.map(Self::u_words);
        for (k, item) in items.iter_mut().enumerate() {
            *item = std::array::from_fn(|j| words[j][k]);
        }
    }
}

/// Every operation of the vocabulary on the lanes `a` and `b` (and on their bits as
/// integers), and the word moves between items and lanes ([`LaneIo`]'s transposes, which
/// the AVX2 lanes override with shuffles), by name, as raw result bits (masks as 0/1): what
/// `tests/internals/model_lanes.rs` compares with the scalar model for each lane type.
#[inline(always)]
pub fn operations<L: LaneIo<N>, const N: usize>(
    a: [f32; N],
    b: [f32; N],
) -> Vec<(&'static str, [u32; N])> {
    let (x, y) = (
        L::from_words(a.map(f32::to_bits)),
        L::from_words(b.map(f32::to_bits)),
    );
    let (u, v) = (x.to_bits(), y.to_bits());
    let m = |m: L::B| L::u_words(L::U::sel(m, L::U::c(1), L::U::c(0)));
    let f = |v: L| v.words();
    // The word moves between items and lanes, on items whose words are `u`, `v` and
    // words made of them, so that a lane or item out of place shows.
    let (au, bu) = (a.map(f32::to_bits), b.map(f32::to_bits));
    let words7: [[u32; N]; 7] = [
        au,
        bu,
        std::array::from_fn(|k| au[k] ^ bu[k]),
        std::array::from_fn(|k| au[k].wrapping_add(bu[k])),
        std::array::from_fn(|k| au[k].wrapping_sub(bu[k])),
        std::array::from_fn(|k| au[k].wrapping_mul(bu[k])),
        au.map(|w| !w),
    ];
    let items2: [[u32; 2]; N] = std::array::from_fn(|k| [0, 1].map(|j| words7[j][k]));
    let items3: [[u32; 3]; N] = std::array::from_fn(|k| [0, 1, 2].map(|j| words7[j][k]));
    let [i2x, i2y] = L::u_from_items2(&items2).map(L::u_words);
    let [i3x, i3y, i3z] = L::u_from_items3(&items3).map(L::u_words);
    let mut back3 = [[0; 3]; N];
    L::u_to_items3([0, 1, 2].map(|j| L::u_from_words(words7[j])), &mut back3);
    let mut back7 = [[0; 7]; N];
    L::u_to_items7(words7.map(L::u_from_words), &mut back7);
    // Word `j` of every item, as lanes.
    let item3 = |j: usize| -> [u32; N] { std::array::from_fn(|k| back3[k][j]) };
    let item7 = |j: usize| -> [u32; N] { std::array::from_fn(|k| back7[k][j]) };
    vec![
        ("fadd", f(x + y)),
        ("fsub", f(x - y)),
        ("fmul", f(x * y)),
        ("fdiv", f(x / y)),
        ("fneg", f(-x)),
        ("fabs", f(x.abs())),
        ("fsqrt", f(x.sqrt())),
        ("ffloor", f(x.floor())),
        ("fround", f(x.round())),
        ("to_u", L::u_words(x.to_u())),
        ("lt", m(x.lt(y))),
        ("le", m(x.le(y))),
        ("gt", m(x.gt(y))),
        ("ge", m(x.ge(y))),
        ("eq", m(x.eq(y))),
        ("and", m(x.lt(y).and(x.ge(y.abs())))),
        ("or", m(x.lt(y).or(x.eq(y)))),
        ("not", m(x.lt(y).not())),
        ("fsel", f(L::sel(x.lt(y), x, y))),
        ("fto_f", f(u.to_f())),
        ("as_float", f(u.as_float())),
        ("add_u", L::u_words(u.wrapping_add(v))),
        ("sub_u", L::u_words(u.wrapping_sub(v))),
        ("mul_u", L::u_words(u.wrapping_mul(v))),
        ("and_u", L::u_words(u & v)),
        ("or_u", L::u_words(u | v)),
        ("lt_u", m(u.lt(v))),
        ("shr", L::u_words(u.shr(7))),
        ("shl", L::u_words(u.shl(9))),
        ("usel", L::u_words(L::U::sel(u.lt(v), u, v))),
        ("at_least_nonzero", f(x.at_least_nonzero(-1.0))),
        ("signed8", f((u & L::U::c(0xff)).signed_field(8))),
        ("signed10", f(u.shr(22).signed_field(10))),
        ("signed16", f((u & L::U::c(0xffff)).signed_field(16))),
        ("signed24", f(u.shr(8).signed_field(24))),
        ("items2_0", i2x),
        ("items2_1", i2y),
        ("items3_0", i3x),
        ("items3_1", i3y),
        ("items3_2", i3z),
        ("to_items3_0", item3(0)),
        ("to_items3_1", item3(1)),
        ("to_items3_2", item3(2)),
        ("to_items7_0", item7(0)),
        ("to_items7_1", item7(1)),
        ("to_items7_2", item7(2)),
        ("to_items7_3", item7(3)),
        ("to_items7_4", item7(4)),
        ("to_items7_5", item7(5)),
        ("to_items7_6", item7(6)),
    ]
}

impl LaneIo<4> for F4 {
    #[inline(always)]
    fn from_words(w: [u32; 4]) -> Self {
        F4(cast(w))
    }
    #[inline(always)]
    fn words(self) -> [u32; 4] {
        cast(self.0)
    }
    #[inline(always)]
    fn u_from_words(w: [u32; 4]) -> U4 {
        U4(u32x4::new(w))
    }
    #[inline(always)]
    fn u_words(u: U4) -> [u32; 4] {
        u.0.to_array()
    }
}

impl Lane for F4 {
    const KIND: Kind = Kind::F32;
}
impl Lane for U4 {
    const KIND: Kind = Kind::U32;
}
impl Lane for M4 {
    const KIND: Kind = Kind::Bool;
}
super::num::value_eval!(F4, U4, M4);

impl Bool for M4 {
    #[inline(always)]
    fn and(self, o: Self) -> Self {
        M4(self.0 & o.0)
    }
    #[inline(always)]
    fn or(self, o: Self) -> Self {
        M4(self.0 | o.0)
    }
    #[inline(always)]
    fn not(self) -> Self {
        M4(!self.0)
    }
}

/// `m ? t : f` on bits.
#[inline(always)]
fn blend(m: M4, t: u32x4, f: u32x4) -> u32x4 {
    (t & m.0) | (f & !m.0)
}

macro_rules! binary {
    ($t:ident, $tr:ident, $f:ident) => {
        impl $tr for $t {
            type Output = $t;
            #[inline(always)]
            fn $f(self, o: $t) -> $t {
                $t(self.0.$f(o.0))
            }
        }
    };
}
binary!(F4, Add, add);
binary!(F4, Sub, sub);
binary!(F4, Mul, mul);
binary!(F4, Div, div);
binary!(U4, Add, add);
binary!(U4, Sub, sub);
binary!(U4, BitAnd, bitand);
binary!(U4, BitOr, bitor);

impl Neg for F4 {
    type Output = F4;
    /// The sign bit flipped, as scalar negation does (`0 - x` would turn -0 into +0).
    #[inline(always)]
    fn neg(self) -> F4 {
        F4::of_bits(self.bits() ^ u32x4::splat(SIGN))
    }
}

impl Uint for U4 {
    type F = F4;
    type B = M4;
    #[inline(always)]
    fn c(v: u32) -> Self {
        U4(u32x4::splat(v))
    }
    #[inline(always)]
    fn shl(self, n: u32) -> Self {
        U4(self.0 << n)
    }
    #[inline(always)]
    fn shr(self, n: u32) -> Self {
        U4(self.0 >> n)
    }
    /// `u as f32` (round to nearest, ties to even) for every `u`: the two 16-bit halves
    /// convert exactly, `hi·2^16` is exact, and their sum is rounded once.
    #[inline(always)]
    fn to_f(self) -> F4 {
        let half = |u: u32x4| f32x4::from_i32x4(cast::<u32x4, i32x4>(u));
        let hi = half(self.0 >> 16);
        let lo = half(self.0 & u32x4::splat(0xffff));
        F4(hi * f32x4::splat(65_536.0) + lo)
    }
    #[inline(always)]
    fn as_float(self) -> F4 {
        F4::of_bits(self.0)
    }
    #[inline(always)]
    fn sel(m: M4, t: Self, f: Self) -> Self {
        U4(blend(m, t.0, f.0))
    }
    #[inline(always)]
    fn wrapping_add(self, o: Self) -> Self {
        U4(self.0 + o.0)
    }
    #[inline(always)]
    fn wrapping_sub(self, o: Self) -> Self {
        U4(self.0 - o.0)
    }
    #[inline(always)]
    fn wrapping_mul(self, o: Self) -> Self {
        U4(self.0 * o.0)
    }
    #[inline(always)]
    fn lt(self, o: Self) -> M4 {
        M4(self.0.simd_lt(o.0))
    }
}

impl Float for F4 {
    type U = U4;
    type B = M4;
    #[inline(always)]
    fn c(v: f32) -> Self {
        F4(f32x4::splat(v))
    }
    #[inline(always)]
    fn abs(self) -> Self {
        F4::of_bits(self.bits() & u32x4::splat(!SIGN))
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        F4(self.0.sqrt())
    }
    #[inline(always)]
    fn floor(self) -> Self {
        let r = self.round_even();
        F4::sel(r.gt(self), r - F4::c(1.0), r)
    }
    #[inline(always)]
    fn round(self) -> Self {
        self.round_even()
    }
    #[inline(always)]
    fn lt(self, o: Self) -> M4 {
        F4::mask(self.0.simd_lt(o.0))
    }
    #[inline(always)]
    fn le(self, o: Self) -> M4 {
        F4::mask(self.0.simd_le(o.0))
    }
    #[inline(always)]
    fn gt(self, o: Self) -> M4 {
        F4::mask(self.0.simd_gt(o.0))
    }
    #[inline(always)]
    fn ge(self, o: Self) -> M4 {
        F4::mask(self.0.simd_ge(o.0))
    }
    #[inline(always)]
    fn eq(self, o: Self) -> M4 {
        F4::mask(self.0.simd_eq(o.0))
    }
    #[inline(always)]
    fn sel(m: M4, t: Self, f: Self) -> Self {
        F4::of_bits(blend(m, t.bits(), f.bits()))
    }
    /// `x as u32`, saturating as Rust's conversion does: NaN and `x ≤ -1` give 0 (and
    /// `(-1, 0)` truncates to 0), `x ≥ 2^32` gives `u32::MAX`; `[2^31, 2^32)` converts
    /// `x - 2^31` (exact there) and adds the top bit back.
    #[inline(always)]
    fn to_u(self) -> U4 {
        let two_31 = F4::c(2_147_483_648.0);
        let low = U4(cast(self.0.trunc_int()));
        let high = U4(cast((self - two_31).0.trunc_int())) + U4::c(SIGN);
        let r = U4::sel(self.ge(two_31), high, low);
        let r = U4::sel(self.ge(F4::c(4_294_967_296.0)), U4::c(u32::MAX), r);
        U4::sel(self.gt(F4::c(-1.0)), r, U4::c(0))
    }
    #[inline(always)]
    fn to_bits(self) -> U4 {
        U4(self.bits())
    }
}
