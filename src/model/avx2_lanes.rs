//! The vocabulary on eight lanes at once ([`F8`], [`U8`], [`M8`] over AVX2 registers): what
//! the CPU batches run where the processor has AVX2, chosen at run time, so that a build
//! for the baseline x86-64 target needs no `target-cpu` flag. Like the four SSE2 lanes of
//! [`super::lanes`], every operation is the scalar model's, lane by lane, bit for bit; the
//! newer instructions make several of them shorter:
//!
//! - `round` and `floor` are `vroundps`, which returns exactly what the model's steps
//!   (`(|x| + 2^23) - 2^23` with the sign of `x`, and one less where that exceeds `x`)
//!   return for every number; a NaN lane keeps its input, as in the model;
//! - selects are one `vblendvps`, on masks that are all ones or all zeros per lane;
//! - `u32 → f32` converts directly when no lane has its top bit set (every code the models
//!   convert), and otherwise through the two exact 16-bit halves the SSE2 lanes always use;
//! - `f32 → u32` truncates directly and takes the SSE2 lanes' `[2^31, 2^32)` path only when
//!   a lane reaches 2^31.
//!
//! Sound by construction: the module is private to the crate, and its values exist only
//! inside functions compiled with `#[target_feature(enable = "avx2")]` (or AVX2 and
//! AVX-512VL) that run after [`available`] (or [`avx512_available`]) said yes
//! ([`crate::codecs::functions::function::Function::eval_many`], the typed slices of [`crate::api`]).
//! Those functions must inline everything the models call: an operation left in a function
//! compiled for the baseline target becomes a call to an out-of-line intrinsic. So the
//! operations here, and the models' generic functions, methods and closures in
//! `src/codecs` and `src/model/vec.rs`, are `#[inline(always)]`. A closure bound by `let`
//! is written `{ #[inline(always)] |..| .. }`, because the block's tail is the one place
//! there that Rust accepts the attribute, and arrays are mapped with
//! [`crate::model::each`], since `[T; N]::map` may leave its closure out of line.

use super::lanes::LaneIo;
use super::num::{Bool, Float, Kind, Lane, Uint};
use std::arch::x86_64::*;
use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Sub};

/// Eight f32 lanes.
#[derive(Clone, Copy, Debug)]
pub(crate) struct F8(__m256);
/// Eight u32 lanes.
#[derive(Clone, Copy, Debug)]
pub(crate) struct U8(__m256i);
/// Eight comparison results, all bits set where true.
#[derive(Clone, Copy, Debug)]
pub(crate) struct M8(__m256i);

/// Whether this processor runs the eight-lane code (checked once, then cached by std).
#[inline]
pub fn available() -> bool {
    is_x86_feature_detected!("avx2")
}

/// Whether this processor also runs the eight-lane code compiled for AVX-512F and VL
/// ([`crate::codecs::functions::function::Width::EightAvx512`]; checked once, then cached by std).
#[inline]
pub fn avx512_available() -> bool {
    available() && is_x86_feature_detected!("avx512f") && is_x86_feature_detected!("avx512vl")
}

/// [`super::lanes::operations`] on eight AVX2 lanes; `None` where the processor has no AVX2.
pub fn operations(a: [f32; 8], b: [f32; 8]) -> Option<Vec<(&'static str, [u32; 8])>> {
    /// # Safety
    /// The processor must have AVX2.
    #[target_feature(enable = "avx2")]
    unsafe fn on_avx2(a: [f32; 8], b: [f32; 8]) -> Vec<(&'static str, [u32; 8])> {
        super::lanes::operations::<F8, 8>(a, b)
    }
    // SAFETY: the processor has AVX2 (checked first).
    available().then(|| unsafe { on_avx2(a, b) })
}

/// Runs an AVX2 intrinsic. SAFETY (every use): an [`F8`], [`U8`] or [`M8`] exists only
/// in code reached after [`available`] returned true (see the module documentation).
macro_rules! avx {
    ($e:expr) => {
        unsafe { $e }
    };
}

/// Lanes per evaluation.
pub(crate) const WIDTH: usize = 8;

const SIGN: i32 = i32::MIN;

impl LaneIo<8> for F8 {
    #[inline(always)]
    fn from_words(w: [u32; 8]) -> Self {
        U8::from_array(w).as_float()
    }
    #[inline(always)]
    fn words(self) -> [u32; 8] {
        self.to_bits().to_array()
    }
    #[inline(always)]
    fn u_from_words(w: [u32; 8]) -> U8 {
        U8::from_array(w)
    }
    #[inline(always)]
    fn u_words(u: U8) -> [u32; 8] {
        u.to_array()
    }
    /// Six half-register loads and five in-lane shuffles. LLVM's own lowering of the word
    /// moves took about twice the shuffles: the oct16 decoder ran an eighth faster with
    /// these.
    #[inline(always)]
    fn u_from_items3(items: &[[u32; 3]; 8]) -> [U8; 3] {
        let p = items.as_ptr().cast::<f32>();
        // SAFETY (with `avx!`'s): words `i..i + 4` of `i <= 20` lie within the 24 words.
        let half = {
            #[inline(always)]
            |i: usize| avx!(_mm_loadu_ps(p.add(i)))
        };
        let pair = {
            #[inline(always)]
            |lo: usize, hi: usize| avx!(_mm256_set_m128(half(hi), half(lo)))
        };
        // Items 0|4, 1|5 and 2|6 start each 128-bit half of m03, m14 and m25.
        let (m03, m14, m25) = (pair(0, 12), pair(4, 16), pair(8, 20));
        let xy = avx!(_mm256_shuffle_ps::<0b10_01_11_10>(m14, m25)); // x2 y2 x3 y3
        let yz = avx!(_mm256_shuffle_ps::<0b01_00_10_01>(m03, m14)); // y0 z0 y1 z1
        let x = avx!(_mm256_shuffle_ps::<0b10_00_11_00>(m03, xy));
        let y = avx!(_mm256_shuffle_ps::<0b11_01_10_00>(yz, xy));
        let z = avx!(_mm256_shuffle_ps::<0b11_00_11_01>(yz, m25));
        let u = {
            #[inline(always)]
            |l: __m256| U8(avx!(_mm256_castps_si256(l)))
        };
        [u(x), u(y), u(z)]
    }
    /// Two loads, two in-lane shuffles and two 64-bit permutes: the words of items
    /// 0, 1, 4, 5 | 2, 3, 6, 7 gathered per half, then the middle quarters swapped.
    #[inline(always)]
    fn u_from_items2(items: &[[u32; 2]; 8]) -> [U8; 2] {
        let p = items.as_ptr().cast::<f32>();
        // SAFETY (with `avx!`'s): words `0..8` and `8..16` are the 16 words.
        let (a, b) = (avx!(_mm256_loadu_ps(p)), avx!(_mm256_loadu_ps(p.add(8))));
        let lane = {
            #[inline(always)]
            |l: __m256| {
                let q = avx!(_mm256_castps_si256(l));
                U8(avx!(_mm256_permute4x64_epi64::<0b11_01_10_00>(q)))
            }
        };
        [
            lane(avx!(_mm256_shuffle_ps::<0b10_00_10_00>(a, b))),
            lane(avx!(_mm256_shuffle_ps::<0b11_01_11_01>(a, b))),
        ]
    }
    /// Six in-lane shuffles and three 128-bit permutes, the inverse of
    /// [`LaneIo::u_from_items3`] above.
    #[inline(always)]
    fn u_to_items3(lanes: [U8; 3], items: &mut [[u32; 3]; 8]) {
        let f = {
            #[inline(always)]
            |l: U8| avx!(_mm256_castsi256_ps(l.0))
        };
        let (x, y, z) = (f(lanes[0]), f(lanes[1]), f(lanes[2]));
        let xy = avx!(_mm256_shuffle_ps::<0b10_00_10_00>(x, y)); // x0 x2 y0 y2
        let yz = avx!(_mm256_shuffle_ps::<0b11_01_11_01>(y, z)); // y1 y3 z1 z3
        let zx = avx!(_mm256_shuffle_ps::<0b11_01_10_00>(z, x)); // z0 z2 x1 x3
        let r03 = avx!(_mm256_shuffle_ps::<0b10_00_10_00>(xy, zx)); // x0 y0 z0 x1
        let r14 = avx!(_mm256_shuffle_ps::<0b11_01_10_00>(yz, xy)); // y1 z1 x2 y2
        let r25 = avx!(_mm256_shuffle_ps::<0b11_01_11_01>(zx, yz)); // z2 x3 y3 z3
        let p = items.as_mut_ptr().cast::<f32>();
        // SAFETY (with `avx!`'s): words `i..i + 8` of `i <= 16` lie within the 24 words.
        let store = {
            #[inline(always)]
            |i: usize, v: __m256| avx!(_mm256_storeu_ps(p.add(i), v))
        };
        store(0, avx!(_mm256_permute2f128_ps::<0x20>(r03, r14)));
        store(8, avx!(_mm256_permute2f128_ps::<0x30>(r25, r03)));
        store(16, avx!(_mm256_permute2f128_ps::<0x31>(r14, r25)));
    }
    /// An 8×8 transpose (the seven lanes and a zero one: four unpacks, eight in-lane
    /// shuffles and eight 128-bit permutes), each item's row stored whole in turn so that
    /// the next row overwrites the padding word, the last row by a masked store. The
    /// frame decoders' output moved word by word otherwise, which cost more than the
    /// decode itself.
    #[inline(always)]
    fn u_to_items7(lanes: [U8; 7], items: &mut [[u32; 7]; 8]) {
        let f = {
            #[inline(always)]
            |l: U8| avx!(_mm256_castsi256_ps(l.0))
        };
        let r = [
            f(lanes[0]),
            f(lanes[1]),
            f(lanes[2]),
            f(lanes[3]),
            f(lanes[4]),
            f(lanes[5]),
            f(lanes[6]),
            avx!(_mm256_setzero_ps()),
        ];
        let lo = {
            #[inline(always)]
            |a: usize, b: usize| avx!(_mm256_unpacklo_ps(r[a], r[b]))
        };
        let hi = {
            #[inline(always)]
            |a: usize, b: usize| avx!(_mm256_unpackhi_ps(r[a], r[b]))
        };
        // t: pairs of words 0/1, 2/3, 4/5, 6/7 interleaved per item pair.
        let (t0, t1, t2, t3) = (lo(0, 1), hi(0, 1), lo(2, 3), hi(2, 3));
        let (t4, t5, t6, t7) = (lo(4, 5), hi(4, 5), lo(6, 7), hi(6, 7));
        let (u0, u1) = (
            avx!(_mm256_shuffle_ps::<0x44>(t0, t2)),
            avx!(_mm256_shuffle_ps::<0xee>(t0, t2)),
        );
        let (u2, u3) = (
            avx!(_mm256_shuffle_ps::<0x44>(t1, t3)),
            avx!(_mm256_shuffle_ps::<0xee>(t1, t3)),
        );
        let (u4, u5) = (
            avx!(_mm256_shuffle_ps::<0x44>(t4, t6)),
            avx!(_mm256_shuffle_ps::<0xee>(t4, t6)),
        );
        let (u6, u7) = (
            avx!(_mm256_shuffle_ps::<0x44>(t5, t7)),
            avx!(_mm256_shuffle_ps::<0xee>(t5, t7)),
        );
        let rows = [
            avx!(_mm256_permute2f128_ps::<0x20>(u0, u4)),
            avx!(_mm256_permute2f128_ps::<0x20>(u1, u5)),
            avx!(_mm256_permute2f128_ps::<0x20>(u2, u6)),
            avx!(_mm256_permute2f128_ps::<0x20>(u3, u7)),
            avx!(_mm256_permute2f128_ps::<0x31>(u0, u4)),
            avx!(_mm256_permute2f128_ps::<0x31>(u1, u5)),
            avx!(_mm256_permute2f128_ps::<0x31>(u2, u6)),
            avx!(_mm256_permute2f128_ps::<0x31>(u3, u7)),
        ];
        // The last item's seven words go out as the group's last eight, behind item 6's
        // last word: two lane permutes and a blend, where a masked store of seven words
        // would be a slow microcoded instruction on AMD's processors.
        let last = avx!(_mm256_blend_ps::<1>(
            _mm256_permutevar8x32_ps(rows[7], _mm256_setr_epi32(0, 0, 1, 2, 3, 4, 5, 6)),
            _mm256_permutevar8x32_ps(rows[6], _mm256_set1_epi32(6)),
        ));
        let p = items.as_mut_ptr().cast::<f32>();
        // SAFETY (with `avx!`'s): row `k < 7` writes words `7k..7k + 8`, within the 56
        // words (`7·6 + 8 = 50`), and `last` words 48 to 55, after them.
        for (k, row) in rows.iter().enumerate().take(7) {
            avx!(_mm256_storeu_ps(p.add(7 * k), *row));
        }
        avx!(_mm256_storeu_ps(p.add(48), last));
    }
}

impl F8 {
    #[inline(always)]
    fn mask(m: __m256) -> M8 {
        M8(avx!(_mm256_castps_si256(m)))
    }
    /// `r` where `self` is a number, `self` where it is NaN (the model's NaN passes its
    /// rounding steps unchanged; `vroundps` would quiet a signalling one).
    #[inline(always)]
    fn unless_nan(self, r: __m256) -> F8 {
        let nan = avx!(_mm256_cmp_ps::<_CMP_UNORD_Q>(self.0, self.0));
        F8(avx!(_mm256_blendv_ps(r, self.0, nan)))
    }
}

impl U8 {
    #[inline(always)]
    pub(crate) fn from_array(w: [u32; 8]) -> U8 {
        U8(avx!(_mm256_loadu_si256(w.as_ptr().cast())))
    }
    #[inline(always)]
    pub(crate) fn to_array(self) -> [u32; 8] {
        let mut w = [0u32; 8];
        avx!(_mm256_storeu_si256(w.as_mut_ptr().cast(), self.0));
        w
    }
    /// Whether any lane has its top bit set.
    #[inline(always)]
    fn any_top_bit(self) -> bool {
        avx!(_mm256_movemask_ps(_mm256_castsi256_ps(self.0))) != 0
    }
}

impl Lane for F8 {
    const KIND: Kind = Kind::F32;
}
impl Lane for U8 {
    const KIND: Kind = Kind::U32;
}
impl Lane for M8 {
    const KIND: Kind = Kind::Bool;
}
super::num::value_eval!(F8, U8, M8);

impl Bool for M8 {
    #[inline(always)]
    fn and(self, o: Self) -> Self {
        M8(avx!(_mm256_and_si256(self.0, o.0)))
    }
    #[inline(always)]
    fn or(self, o: Self) -> Self {
        M8(avx!(_mm256_or_si256(self.0, o.0)))
    }
    #[inline(always)]
    fn not(self) -> Self {
        M8(avx!(_mm256_xor_si256(self.0, _mm256_set1_epi32(-1))))
    }
}

macro_rules! binary {
    ($t:ident, $tr:ident, $f:ident, $op:ident) => {
        impl $tr for $t {
            type Output = $t;
            #[inline(always)]
            fn $f(self, o: $t) -> $t {
                $t(avx!($op(self.0, o.0)))
            }
        }
    };
}
binary!(F8, Add, add, _mm256_add_ps);
binary!(F8, Sub, sub, _mm256_sub_ps);
binary!(F8, Mul, mul, _mm256_mul_ps);
binary!(F8, Div, div, _mm256_div_ps);
binary!(U8, Add, add, _mm256_add_epi32);
binary!(U8, Sub, sub, _mm256_sub_epi32);
binary!(U8, BitAnd, bitand, _mm256_and_si256);
binary!(U8, BitOr, bitor, _mm256_or_si256);

impl Neg for F8 {
    type Output = F8;
    /// The sign bit flipped, as scalar negation does.
    #[inline(always)]
    fn neg(self) -> F8 {
        F8(avx!(_mm256_xor_ps(self.0, _mm256_set1_ps(-0.0))))
    }
}

impl Uint for U8 {
    type F = F8;
    type B = M8;
    #[inline(always)]
    fn c(v: u32) -> Self {
        U8(avx!(_mm256_set1_epi32(v as i32)))
    }
    #[inline(always)]
    fn shl(self, n: u32) -> Self {
        U8(avx!(_mm256_sll_epi32(self.0, _mm_cvtsi32_si128(n as i32))))
    }
    #[inline(always)]
    fn shr(self, n: u32) -> Self {
        U8(avx!(_mm256_srl_epi32(self.0, _mm_cvtsi32_si128(n as i32))))
    }
    /// The field sign-extended by two shifts, then converted (exact: `b ≤ 24`).
    #[inline(always)]
    fn signed_field(self, b: u32) -> F8 {
        assert!(b <= 24, "a field of {b} bits");
        let n = avx!(_mm_cvtsi32_si128((32 - b) as i32));
        F8(avx!(_mm256_cvtepi32_ps(_mm256_sra_epi32(
            _mm256_sll_epi32(self.0, n),
            n
        ))))
    }
    /// `u as f32` (round to nearest, ties to even) for every `u`: a signed conversion
    /// when every lane is below 2^31, else the sum of the exactly converted halves
    /// `hi·2^16 + lo`, rounded once.
    #[inline(always)]
    fn to_f(self) -> F8 {
        if !self.any_top_bit() {
            return F8(avx!(_mm256_cvtepi32_ps(self.0)));
        }
        let hi = F8(avx!(_mm256_cvtepi32_ps(_mm256_srli_epi32::<16>(self.0))));
        let lo = F8(avx!(_mm256_cvtepi32_ps(_mm256_and_si256(
            self.0,
            _mm256_set1_epi32(0xffff)
        ))));
        hi * F8::c(65_536.0) + lo
    }
    #[inline(always)]
    fn as_float(self) -> F8 {
        F8(avx!(_mm256_castsi256_ps(self.0)))
    }
    #[inline(always)]
    fn sel(m: M8, t: Self, f: Self) -> Self {
        U8(avx!(_mm256_blendv_epi8(f.0, t.0, m.0)))
    }
    #[inline(always)]
    fn wrapping_add(self, o: Self) -> Self {
        self + o
    }
    #[inline(always)]
    fn wrapping_sub(self, o: Self) -> Self {
        self - o
    }
    #[inline(always)]
    fn wrapping_mul(self, o: Self) -> Self {
        U8(avx!(_mm256_mullo_epi32(self.0, o.0)))
    }
    /// Unsigned `<` as a signed comparison with both top bits flipped.
    #[inline(always)]
    fn lt(self, o: Self) -> M8 {
        let s = avx!(_mm256_set1_epi32(SIGN));
        M8(avx!(_mm256_cmpgt_epi32(
            _mm256_xor_si256(o.0, s),
            _mm256_xor_si256(self.0, s)
        )))
    }
}

macro_rules! compare {
    ($f:ident, $pred:ident) => {
        #[inline(always)]
        fn $f(self, o: Self) -> M8 {
            F8::mask(avx!(_mm256_cmp_ps::<$pred>(self.0, o.0)))
        }
    };
}

impl Float for F8 {
    type U = U8;
    type B = M8;
    #[inline(always)]
    fn c(v: f32) -> Self {
        F8(avx!(_mm256_set1_ps(v)))
    }
    #[inline(always)]
    fn abs(self) -> Self {
        F8(avx!(_mm256_andnot_ps(_mm256_set1_ps(-0.0), self.0)))
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        F8(avx!(_mm256_sqrt_ps(self.0)))
    }
    #[inline(always)]
    fn floor(self) -> Self {
        self.unless_nan(avx!(_mm256_round_ps::<
            { _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC },
        >(self.0)))
    }
    #[inline(always)]
    fn round(self) -> Self {
        self.unless_nan(avx!(_mm256_round_ps::<
            { _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC },
        >(self.0)))
    }
    compare!(lt, _CMP_LT_OQ);
    compare!(le, _CMP_LE_OQ);
    compare!(gt, _CMP_GT_OQ);
    compare!(ge, _CMP_GE_OQ);
    compare!(eq, _CMP_EQ_OQ);
    #[inline(always)]
    fn sel(m: M8, t: Self, f: Self) -> Self {
        F8(avx!(_mm256_blendv_ps(f.0, t.0, _mm256_castsi256_ps(m.0))))
    }
    /// `vmaxps` returns its second operand, `lo`, where `self` is NaN.
    #[inline(always)]
    fn at_least_nonzero(self, lo: f32) -> Self {
        debug_assert!(lo != 0.0 && !lo.is_nan(), "bound {lo}");
        F8(avx!(_mm256_max_ps(self.0, _mm256_set1_ps(lo))))
    }
    /// `x as u32`, saturating as Rust's conversion does: the signed truncation where
    /// `-1 < x < 2^31` (it gives 0 on `(-1, 0]`), 0 where `x ≤ -1` or NaN; when some lane
    /// reaches 2^31, `[2^31, 2^32)` converts `x - 2^31` (exact there) with the top bit
    /// added back, and `x ≥ 2^32` gives `u32::MAX`.
    #[inline(always)]
    fn to_u(self) -> U8 {
        let two_31 = F8::c(2_147_483_648.0);
        let above = U8(avx!(_mm256_cvttps_epi32(self.0)));
        let r = U8::sel(self.gt(F8::c(-1.0)), above, U8::c(0));
        let high = self.ge(two_31);
        if !U8(high.0).any_top_bit() {
            return r;
        }
        let top = U8(avx!(_mm256_cvttps_epi32((self - two_31).0))) + U8::c(SIGN as u32);
        let r = U8::sel(high, top, r);
        U8::sel(self.ge(F8::c(4_294_967_296.0)), U8::c(u32::MAX), r)
    }
    #[inline(always)]
    fn to_bits(self) -> U8 {
        U8(avx!(_mm256_castps_si256(self.0)))
    }
}
