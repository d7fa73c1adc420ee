//! Draco's f64 encoder arithmetic, reproduced exactly with 32-bit operations, so that
//! `draco_oct` writes Draco's codes on every input: ties and tiny components included.
//!
//! Draco (`FloatVectorToQuantizedOctahedralCoords`) computes in f64, each operation
//! rounded to 53 bits, ties to even: `a = (|x| + |y|) + |z|`, `s = 1/a`, and for x and y
//! `floor(v·s·c + ½)` (three more roundings: `v·s`, `·c`, `+ ½`). Near a code boundary
//! those roundings decide the code, so each is done here exactly as f64 would: in
//! integers held as 16-bit limbs in 32-bit words, and in f32 operations that are exact
//! everywhere (products by powers of two, floors, a float less its floor). Floats are
//! otherwise only estimates that integer comparisons correct, so a quotient a few ULP off
//! or a contracted sum changes nothing.
//!
//! 1. Scale (`exact::scaled`): the largest magnitude into `[2, 4)`, exact in f64 too, so
//!    it changes no rounding; scaled components below `2^-126` count as zero (no f64
//!    rounding of the sum can see below `2^-110` of the largest, and their codes are 0).
//! 2. `|x| + |y|`, larger `L` plus smaller `S`: exact in 53 bits unless `S` has bits below
//!    `u = ulp₅₃(L)`, and then (no carry is possible) it is `L + S'`, `S'` the multiple of
//!    `u` nearest `S` (ties to even): `round(S/u)·u`, exact in f32.
//! 3. `a`: `L + S' + |z|` in limbs on the grid `2^-61` with a sticky bit for bits below
//!    it, rounded to 53 bits (it lies in `[2, 12)`, so 10 to 12 bits go). Exact but for
//!    a carry out of two terms' sub-grid bits, which needs both x and y below `2^-37` of
//!    z: their codes are then 0 whatever `a`'s last bit, and `a` is far from Draco's
//!    threshold (the low 29 bits of `1e-6`'s significand are far from zero).
//! 4. `s = 1/a`: `floor(2^117/A)` (`A = a·2^60`) by long division in 16-bit digits, each
//!    estimated in f32 (within a few hundredths, even with a quotient 2.5 ULP off) and
//!    corrected by exact remainders, then rounded to 53 bits.
//! 5. `v·s` and then `·c`: exact limb products, each rounded to 53 bits.
//! 6. `floor(RN(q + ½))`: the rounding of `q + ½` moves no floor, `floor(RN(q + ½)) =
//!    floor(q + ½)`, for every double `q` but `½ - 2^-54` (whose `q + ½` rounds up to 1),
//!    and that is `RN(p·c)` for no double `p` at Draco's `c = 2^(N-1) - 1` (N = 8 to 16;
//!    see the test). With `q` at least `2^21` of its own units, the floor is decided by its
//!    top 23 bits, and for a negative `q` also by whether any bit below them is set.
//!
//! Denormal input components read as zero (an implementation may flush them), where
//! Draco's C++ keeps them: the one place the codes can part, and only in `i2`'s sign.

use crate::codecs::toolkit::exact::{MIN_NORMAL, normal_or_zero, scaled};
use crate::model::{Bool, Float, Lane, Uint, V3};

/// Draco's `1e-6`, the f64 `0x3EB0C6F7A0B5ED8D`: its 53-bit significand (times `2^-72`).
const THRESHOLD_SIGNIFICAND: u64 = 0x10_C6F7_A0B5_ED8D;

/// A number as 16-bit limbs, lowest first.
type Limbs<U, const N: usize> = [U; N];

/// Draco's `floor(x·s·c + ½)` and `floor(y·s·c + ½)` (as floats), and whether its
/// `a > 1e-6` holds (it has a direction), for the input `v` and `c = center_value`.
/// Meaningful where `v` is finite; any input gives defined values.
#[inline(always)]
pub fn draco_codes<F: Float>(v: V3<F>, c: u32) -> (F, F, F::B) {
    let zero = F::c(0.0);
    let (w, scale, finite) = scaled(v);
    // Invalid input computes on (2, 0, 0): every conversion below stays in range.
    let w = V3::sel_all(finite, w, V3::new(F::c(2.0), zero, zero))
        .map(
            #[inline(always)]
            |x| normal_or_zero(x.abs(), MIN_NORMAL),
        )
        .named("draco_scaled");
    // |x| + |y| rounded to 53 bits: the larger plus the smaller rounded to its ulp.
    let l = w.x.at_least(w.y).named("draco_larger");
    let s = w.x.at_most(w.y);
    // The exponent field, at least 67: `L < 2^-60` only where z is the largest, and then
    // `L + S < 2^-59` is below half of `a`'s last place either way. (Magnitude bits: an
    // implementation may give `-0` for a zero's magnitude.)
    let el = l.magnitude_bits().shr(23);
    let el = F::U::sel(el.lt(F::U::c(67)), F::U::c(67), el);
    let ulp = (el - F::U::c(52)).shl(23).as_float();
    let per_ulp = (F::U::c(306) - el).shl(23).as_float();
    let s = ((s * per_ulp).round() * ulp).named("draco_smaller");
    let a = rounded_sum::<F>([l, s, w.z]);
    let e = F::U::c(255) - scale.to_bits().shr(23);
    let recip = reciprocal::<F>(a);
    let code = {
        #[inline(always)]
        |x: F, negative: F::B| times_center::<F>(x, negative, recip, c)
    };
    (
        code(w.x, v.x.lt(zero)).named("i0"),
        code(w.y, v.y.lt(zero)).named("i1"),
        finite.and(above_threshold::<F>(a, e)),
    )
}

/// `t`, in `[0, 4)` and normal or zero, on the grid `2^-61` as four 16-bit limbs (the top
/// one below `2^15`), and whether any bit lies below the grid: floors of power-of-two
/// multiples and differences with them, each exact.
#[inline(always)]
fn grid_limbs<F: Float>(t: F) -> (Limbs<F::U, 4>, F::B) {
    let limb = F::c(65536.0);
    let top = t * F::c(8192.0);
    let l3 = top.floor();
    let r = (top - l3) * limb;
    let l2 = r.floor();
    let r = (r - l2) * limb;
    let l1 = r.floor();
    let r = (r - l1) * limb;
    let l0 = r.floor();
    ([l0, l1, l2, l3].map(F::to_u), r.gt(l0))
}

/// Limbs with their carries moved up (each but the top one below `2^16`).
#[inline(always)]
fn carried<U: Uint, const N: usize>(mut l: Limbs<U, N>) -> Limbs<U, N> {
    let mask = U::c(0xffff);
    for i in 0..N - 1 {
        l[i + 1] = l[i + 1] + l[i].shr(16);
        l[i] = l[i] & mask;
    }
    l
}

/// `x` with its low `d` bits rounded off to nearest, ties to even (`sticky`: whether bits
/// below `x` were set, `None` where there are none); the result may carry past 16 bits.
#[inline(always)]
fn rounded_off<F: Float>(x: F::U, d: u32, sticky: Option<F::B>) -> F::U {
    let (mask, half) = ((1u32 << d) - 1, 1u32 << (d - 1));
    let rest = x & F::U::c(mask);
    let over = F::U::c(half).lt(rest);
    let at_half = rest.lt(F::U::c(half)).not().and(over.not());
    let odd = (x.shr(d) & F::U::c(1)).lt(F::U::c(1)).not();
    let tie_up = sticky.map_or(odd, |s| s.or(odd));
    let up = over.or(at_half.and(tie_up));
    (x & F::U::c(!mask)) + F::U::sel(up, F::U::c(1 << d), F::U::c(0))
}

/// A number's lowest limb `low` rounded to 53 significant bits, which takes `d + 2` bits off
/// where its top limb `top` reaches `2^(k + 1)`, `d + 1` where it reaches `2^k`, else `d`.
#[inline(always)]
fn rounded_by_top<F: Float>(low: F::U, top: F::U, k: u32, d: u32, sticky: F::B) -> F::U {
    let sticky = Some(sticky);
    F::U::sel(
        at_least_pow2(top, k + 1),
        rounded_off::<F>(low, d + 2, sticky),
        F::U::sel(
            at_least_pow2(top, k),
            rounded_off::<F>(low, d + 1, sticky),
            rounded_off::<F>(low, d, sticky),
        ),
    )
}

/// `x ≥ 2^k`.
#[inline(always)]
fn at_least_pow2<U: Uint>(x: U, k: u32) -> U::B {
    x.lt(U::c(1 << k)).not()
}

/// `x` is not zero.
#[inline(always)]
fn nonzero<U: Uint>(x: U) -> U::B {
    x.lt(U::c(1)).not()
}

/// The three terms' sum rounded to 53 bits, as `A = a·2^60` in four limbs: the sum lies in
/// `[2, 12)`, so on the grid `2^-61` it has 63 to 65 bits, of which 10 to 12 go; the
/// rounded sum is then even on that grid and halves exactly.
#[inline(always)]
fn rounded_sum<F: Float>(t: [F; 3]) -> Limbs<F::U, 4> {
    let parts = t.map(grid_limbs::<F>);
    let sticky = parts[0].1.or(parts[1].1).or(parts[2].1);
    let n = carried([0, 1, 2, 3].map(
        #[inline(always)]
        |i| parts[0].0[i] + parts[1].0[i] + parts[2].0[i],
    ));
    let r = rounded_by_top::<F>(n[0], n[3], 15, 10, sticky);
    let n = carried([r, n[1], n[2], n[3]]);
    let half = {
        #[inline(always)]
        |i: usize| (n[i].shr(1) | (n[i + 1] & F::U::c(1)).shl(15)).named("draco_sum")
    };
    [half(0), half(1), half(2), n[3].shr(1).named("draco_sum")]
}

/// `a > 1e-6` for the unscaled sum, `A = a·2^(188 - e)` (`e` the biased exponent of the
/// input's largest component): certain from `e` alone except for `e` of 105 to 107, where
/// `A` is compared with the threshold's significand at that scale.
#[inline(always)]
fn above_threshold<F: Float>(a: Limbs<F::U, 4>, e: F::U) -> F::B {
    let is = {
        #[inline(always)]
        |k: u32| e.lt(F::U::c(k)).not().and(F::U::c(k).lt(e).not())
    };
    let over = {
        #[inline(always)]
        |shift: u32| {
            let t = THRESHOLD_SIGNIFICAND << shift;
            let k: [F::U; 4] = std::array::from_fn(|i| F::U::c(((t >> (16 * i)) & 0xffff) as u32));
            exceeds::<F, 4>(a, k, false)
        }
    };
    e.lt(F::U::c(108))
        .not()
        .or(is(107).and(over(9)))
        .or(is(106).and(over(10)))
        .or(is(105).and(over(11)))
}

/// `a > b` (or `a ≥ b` with `or_equal`) of two limb numbers, from the top limb down.
#[inline(always)]
fn exceeds<F: Float, const N: usize>(
    a: Limbs<F::U, N>,
    b: Limbs<F::U, N>,
    or_equal: bool,
) -> F::B {
    let mut r = if or_equal {
        a[0].lt(b[0]).not()
    } else {
        b[0].lt(a[0])
    };
    for i in 1..N {
        let equal = a[i].lt(b[i]).not().and(b[i].lt(a[i]).not());
        r = b[i].lt(a[i]).or(equal.and(r));
    }
    r
}

/// `a·q` for 16-bit limbs and `q < 2^16`: every partial product plus carry fits 32 bits.
#[inline(always)]
fn times<U: Uint>(a: Limbs<U, 4>, q: U) -> Limbs<U, 5> {
    let mask = U::c(0xffff);
    let p0 = a[0].wrapping_mul(q);
    let p1 = a[1].wrapping_mul(q) + p0.shr(16);
    let p2 = a[2].wrapping_mul(q) + p1.shr(16);
    let p3 = a[3].wrapping_mul(q) + p2.shr(16);
    [p0 & mask, p1 & mask, p2 & mask, p3 & mask, p3.shr(16)]
}

/// `r - p·2^(16k)`, which is not negative, with borrows.
#[inline(always)]
fn less<U: Uint>(r: &mut Limbs<U, 8>, k: usize, p: Limbs<U, 5>) {
    let mut borrow = U::c(0);
    for (i, p) in p.into_iter().enumerate() {
        let d = (r[k + i] + U::c(0x1_0000)).wrapping_sub(p).wrapping_sub(borrow);
        r[k + i] = d & U::c(0xffff);
        borrow = U::c(1) - d.shr(16);
    }
}

/// `s = RN₅₃(1/a)` as `s·2^57` in four limbs, from `A = a·2^60`: `floor(2^117/A)` one
/// 16-bit digit at a time (an f32 estimate within 1/32 of the digit, lowered by one, then
/// raised at most twice while the exact remainder allows), rounded to 53 bits with the
/// remainder as sticky (`s` in `(1/12, 1/2]` keeps 54 to 56 of its bits).
#[inline(always)]
fn reciprocal<F: Float>(a: Limbs<F::U, 4>) -> Limbs<F::U, 4> {
    let p = |k: i32| F::c(2f32.powi(k));
    let estimate = a[3].to_f() * p(48) + a[2].to_f() * p(32) + a[1].to_f() * p(16);
    let inverse = (F::c(1.0) / estimate).named("draco_inverse");
    let zero = F::U::c(0);
    let mut r = [zero; 8];
    r[7] = F::U::c(1 << 5);
    let divisor = [a[0], a[1], a[2], a[3], zero];
    let mut q = [zero; 4];
    for k in (0..4).rev() {
        let top = r[k + 4].to_f() * p(64) + r[k + 3].to_f() * p(48) + r[k + 2].to_f() * p(32);
        let guess = ((top * inverse).floor() - F::c(1.0)).at_least(F::c(0.0));
        let mut digit = guess.to_u();
        less(&mut r, k, times(a, digit));
        for _ in 0..2 {
            // r ≥ A·2^(16k): a fifth limb, or the four below at least A's (no limb is
            // compared with a zero constant, which C compilers flag as always false).
            let window: Limbs<F::U, 4> = std::array::from_fn(|i| r[k + i]);
            let more = nonzero(r[k + 4]).or(exceeds::<F, 4>(window, a, true));
            let lowered = {
                let mut t = r;
                less(&mut t, k, divisor);
                t
            };
            for i in k..k + 5 {
                r[i] = F::U::sel(more, lowered[i], r[i]);
            }
            digit = digit + F::U::sel(more, F::U::c(1), zero);
        }
        q[k] = digit.named("draco_digit");
    }
    let sticky = nonzero(r[0] | r[1] | r[2] | r[3]);
    let low = rounded_by_top::<F>(q[0], q[3], 6, 1, sticky);
    carried([low, q[1], q[2], q[3]]).map(
        #[inline(always)]
        |l| l.named("draco_recip"),
    )
}

/// Draco's `floor(RN(RN(RN(x·s)·c) + ½))` for a scaled component's magnitude `x` (normal
/// or zero) of sign `negative`, `s·2^57` in `recip`, as a float.
#[inline(always)]
fn times_center<F: Float>(x: F, negative: F::B, recip: Limbs<F::U, 4>, c: u32) -> F {
    let bits = x.magnitude_bits();
    let exponent = bits.shr(23);
    let significand = (bits & F::U::c(0x7f_ffff)) + F::U::c(0x80_0000);
    // P = significand·S, below 2^80 and (for a normal x) at least 2^76.
    let lo = times(recip, significand & F::U::c(0xffff));
    let hi = times(recip, significand.shr(16));
    let prod = carried([
        lo[0],
        lo[1] + hi[0],
        lo[2] + hi[1],
        lo[3] + hi[2],
        lo[4] + hi[3],
        hi[4],
    ]);
    // Rounded to 53 bits: 24 to 27 go, 16 + `s` for the `s` its top limb gives.
    let sticky = Some(nonzero(prod[0]));
    let wider = [13, 14, 15].map(
        #[inline(always)]
        |k| at_least_pow2(prod[4], k),
    );
    let r1 = by_width::<F>(wider, |s| rounded_off::<F>(prod[1], s, sticky));
    let pr = carried([r1, prod[2], prod[3], prod[4], prod[5]]);
    // Its 53 bits (shifted down by 16 + `s`), and the exponent that shift adds.
    let pn: Limbs<F::U, 4> = std::array::from_fn(|i| {
        by_width::<F>(wider, |s| {
            let v = pr[i].shr(s) | pr[i + 1].shl(16 - s);
            if i < 3 { v & F::U::c(0xffff) } else { v }
        })
    });
    let drop = by_width::<F>(wider, |s| F::U::c(16 + s));
    // Q = Pn·c rounded to 53 bits: Pn in [2^52, 2^53], so Q has 52 + b or 53 + b bits.
    let b = 32 - c.leading_zeros();
    let qm = times(pn, F::U::c(c));
    let top = 52 + b;
    let wide = nonzero(qm[(top / 16) as usize].shr(top % 16));
    let wide = if top / 16 < 4 { wide.or(nonzero(qm[4])) } else { wide };
    let q0 = F::U::sel(
        wide,
        rounded_off::<F>(qm[0], b, None),
        rounded_off::<F>(qm[0], b - 1, None),
    );
    let qr = carried([q0, qm[1], qm[2], qm[3], qm[4]]);
    // q = Qr·2^(exponent + drop - 207) below 2^15: its bits from 2^(30 + b) up decide.
    let k = 30 + b;
    let head = qr[2].shr(k - 32) + qr[3].shl(48 - k) + qr[4].shl(64 - k);
    let tail = nonzero((qr[2] & F::U::c((1 << (k - 32)) - 1)) | qr[1] | qr[0]);
    let field = exponent + drop + F::U::c(k);
    let normal = field.lt(F::U::c(81)).not();
    let unit = F::U::sel(normal, field.wrapping_sub(F::U::c(80)), F::U::c(1))
        .shl(23)
        .as_float();
    let h = F::sel(normal, head.to_f() * unit, F::c(0.0)).named("draco_head");
    let up = (h + F::c(0.5)).floor();
    let t = F::c(0.5) - h;
    let down = t.floor();
    let down = down - F::sel(t.eq(down).and(tail), F::c(1.0), F::c(0.0));
    F::sel(negative, down, up)
}

/// `f(s)` for the `s` of 8 to 11 that `wider` picks: `wider[j]` holds where the product's
/// top limb reaches `2^(13 + j)`, so `s` is 8 plus the number that hold.
#[inline(always)]
fn by_width<F: Float>(wider: [F::B; 3], f: impl Fn(u32) -> F::U) -> F::U {
    F::U::sel(
        wider[2],
        f(11),
        F::U::sel(wider[1], f(10), F::U::sel(wider[0], f(9), f(8))),
    )
}
