//! Portable quantization: codes decided only by operations that every implementation
//! rounding `+ - *` to nearest and keeping the order of operations computes identically.
//!
//! A GPU may return a quotient or a square root a few ULP away from the correctly rounded
//! one, contract `a*b + c` into one rounding, flush denormals and lose the sign of a zero
//! (`crate::model::deviant` lists what each API allows). A code computed as
//! `round(x / d * M)` therefore changes wherever `x / d * M` lies within a few ULP of a
//! half-integer. The functions here still *estimate* the code that way, then correct the
//! estimate by ±1 with comparisons between single products, `|n|·M` against
//! `(c ± ½)·d`: a product is correctly rounded everywhere, and a product that feeds a
//! comparison (not an addition) cannot be contracted. Whatever the estimate was, the
//! corrected code is the one integer `c` with `(c - ½)·d ≤ |n|·M < (c + ½)·d` (each side
//! rounded once), a function of the input alone.
//!
//! Every value these comparisons see must be normal, so the input is first brought to a
//! canonical form by [`canonical`]: scaled by a power of two (exact), with denormal and
//! negligible components set to zero, which makes flushing and sign-of-zero loss
//! irrelevant.
//!
//! What this cannot absorb: sums and products rounded in another direction (D3D11 lets
//! hardware truncate, Vulkan's default rounding mode may be toward zero, WGSL names none)
//! or regrouped (WGSL and SPIR-V without `NoContraction` may reassociate). Both move the
//! correctly rounded values the comparisons rely on; only exact (integer) arithmetic would
//! survive them.

use crate::codecs::toolkit::quant::Quant;
use crate::model::{Bool, Float, Lane, Uint, V3, each};

/// The smallest normal f32, `2^-126`.
pub const MIN_NORMAL: f32 = f32::MIN_POSITIVE;
/// After [`canonical`] scaling, components below this are set to zero. The largest
/// component is at least 2, so a zeroed component is below `2^-40` of it: far below the
/// resolution of any code (a direction moves by less than `2^-40` rad), while every
/// product of what remains, down to the low half of a split square, stays normal.
const NEGLIGIBLE: f32 = 1.0 / (1u64 << 39) as f32;
/// The exponent field of an f32.
const EXPONENT: u32 = 0x7f80_0000;

/// The input in canonical form, and whether it has a direction.
///
/// Denormal components become `+0` (an implementation may flush them, so none may
/// matter); the vector is scaled by the power of two `2^(128 - E)`, `E` the biased
/// exponent of its largest component, which puts that component in `[2, 4)` exactly;
/// components then below `2^-39` become `+0`. The result has no denormal, and no
/// component whose sign could be lost. `ok` is false for zero, NaN, infinite and
/// all-denormal input: the scale is then infinite or zero and the scaled sum of magnitudes
/// NaN or outside `[2, 12)`.
#[inline(always)]
pub fn canonical<F: Float>(v: V3<F>) -> (V3<F>, F::B) {
    let (w, _, ok) = scaled(v);
    (
        w.map(
            #[inline(always)]
            |x| normal_or_zero(x, NEGLIGIBLE),
        )
        .named("w"),
        ok,
    )
}

/// [`canonical`] before its negligible components are set to zero: the input with
/// denormal components `+0`, scaled by the power of two `2^(128 - E)` that puts its largest
/// component in `[2, 4)`; that scale; and whether the input has a direction. A scaled
/// component may be denormal (below `2^-126` of a largest one in `[2, 4)`).
#[inline(always)]
pub fn scaled<F: Float>(v: V3<F>) -> (V3<F>, F, F::B) {
    let v = v
        .map(
            #[inline(always)]
            |x| normal_or_zero(x, MIN_NORMAL),
        )
        .named("normal");
    let a = v.abs();
    let m =
        a.x.at_least(a.y)
            .named("larger")
            .at_least(a.z)
            .named("largest");
    let scale = (F::U::c(EXPONENT) - (m.to_bits() & F::U::c(EXPONENT)))
        .as_float()
        .named("scale");
    let w = (v * scale).named("scaled");
    let b = w.abs();
    let sum = (b.x + b.y + b.z).named("sum");
    let ok = sum
        .ge(F::c(2.0))
        .and(sum.lt(F::c(16.0)).named("sum_below_16"))
        .named("ok");
    (w, scale, ok)
}

/// `x`, or `+0` where `|x|` is below `least` (NaN is kept: `x < least` is false for it, so
/// a NaN survives to spoil the sums that decide validity).
#[inline(always)]
pub fn normal_or_zero<F: Float>(x: F, least: f32) -> F {
    F::sel(x.abs().lt(F::c(least)), F::c(0.0), x)
}

/// [`canonical`], with invalid input replaced by `(0, 0, 2)` (canonical +Z), so that the
/// integer conversions that follow stay in range (a NaN or infinite float has no defined
/// u32 in C); the caller still selects its answer for invalid input by `ok`.
#[inline(always)]
pub fn canonical_or_z<F: Float>(v: V3<F>) -> (V3<F>, F::B) {
    let (w, ok) = canonical(v);
    let z = V3::new(F::c(0.0), F::c(0.0), F::c(2.0));
    (V3::sel_all(ok, w, z).named("w"), ok)
}

/// `x·x` as the sum of three products that are exact in f32, so that no contraction of
/// the additions that follow can change them: `x = h + l` with `h` the top 12 significant
/// bits (a mask of the bits, no arithmetic) and `l = x - h` (exact) the other 12.
/// Returns `(h·h, 2h·l, l·l)`. `x` is a canonical component: zero or above `2^-39`,
/// so every product is zero or normal.
#[inline(always)]
fn split_square<F: Float>(x: F) -> [F; 3] {
    let h = (x.to_bits() & F::U::c(0xffff_f000))
        .as_float()
        .named("split_hi");
    let l = (x - h).named("split_lo");
    [h * h, (h + h) * l, l * l]
}

/// `w·w` of a canonical vector, computed from exact products only (so contraction cannot
/// change it) in a fixed order: large terms first, then the cross terms, then the small
/// ones. Deterministic, within a few ULP of the exact square length.
#[inline(always)]
pub fn length2<F: Float>(w: V3<F>) -> F {
    let [x, y, z] = [split_square(w.x), split_square(w.y), split_square(w.z)];
    let big = x[0] + y[0] + z[0];
    let cross = x[1] + y[1] + z[1];
    let small = x[2] + y[2] + z[2];
    (big + cross + small).named("len2")
}

/// The fixed-point scale of [`fixed_length2`]: canonical magnitudes are below 4, so
/// `floor(|x|·2^21) < 2^23` and a sum of three squares is below `2^48`.
pub const FIXED_SCALE: f32 = (1u32 << 21) as f32;

/// `Σ xᵢ²` of canonical components, computed exactly in integers and rounded once, so
/// that neither contraction nor any regrouping of the sum can change it (a float sum of
/// several terms can be regrouped: Mesa's NIR turns `(a·b + c) + d` into
/// `a·b + (c + d)` on paths without `NoContraction`, and WGSL never forbids it).
///
/// Each `|xᵢ|` becomes `A = floor(|xᵢ|·2^21)` (a power-of-two scaling, a floor and a
/// conversion, each exact), below `2^23`; with 12-bit limbs `A = a₁·2^12 + a₀`,
/// `A² = a₁²·2^24 + 2a₁a₀·2^12 + a₀²` is accumulated as `hi·2^24 + lo` in 32-bit
/// integers (every partial product below `2^24`, so nothing wraps), carried, and
/// converted as `hi·2^24 + lo` (both below `2^24`, so both exact): the one rounding is
/// that last addition of two floats. Absolute error about `2^-21` per component (a
/// relative `2^-22` of a canonical vector's length), then that rounding.
#[inline(always)]
fn fixed_sum_of_squares<F: Float, const N: usize>(x: [F; N]) -> F {
    let a = each(
        x,
        #[inline(always)]
        |x| {
            (x.abs() * F::c(FIXED_SCALE))
                .floor()
                .named("fixed_f")
                .to_u()
                .named("fixed")
        },
    );
    sum_of_squares::<F, N>(a) * F::c(1.0 / (FIXED_SCALE * FIXED_SCALE))
}

/// `Σ aᵢ²` of three or fewer integers below `2^24` whose squares sum below `2^48`, exact
/// in 32-bit integers and rounded once (see `fixed_sum_of_squares`), kept as
/// `hi·2^24 + lo` (both then below `2^24`, so both convert exactly).
#[inline(always)]
pub fn sum_of_squares<F: Float, const N: usize>(a: [F::U; N]) -> F {
    joined(square_sum_parts::<F, N>(a))
}

/// `hi·2^24 + lo` as a float: two exact conversions, an exact product and one rounding.
#[inline(always)]
pub fn joined<F: Float>((hi, lo): (F::U, F::U)) -> F {
    hi.to_f() * F::c((1u32 << 24) as f32) + lo.to_f()
}

/// The exact `Σ aᵢ² = hi·2^24 + lo` of [`sum_of_squares`], both parts below `2^24`:
/// with 12-bit limbs `a = a₁·2^12 + a₀`, every partial product is below `2^24`, so
/// nothing wraps before the carry.
#[inline(always)]
pub fn square_sum_parts<F: Float, const N: usize>(a: [F::U; N]) -> (F::U, F::U) {
    let limb = F::U::c(0xfff);
    let low24 = F::U::c(0xff_ffff);
    let (mut hi, mut lo) = (F::U::c(0), F::U::c(0));
    for a in a {
        let (a1, a0) = (a.shr(12).named("limb1"), (a & limb).named("limb0"));
        let cross = a1.wrapping_mul(a0).named("limb_cross");
        hi = (hi + a1.wrapping_mul(a1) + cross.shr(11)).named("hi");
        lo = (lo + a0.wrapping_mul(a0) + (cross.shl(13) & low24)).named("lo");
    }
    ((hi + lo.shr(24)).named("hi"), (lo & low24).named("lo"))
}

/// A 32-bit integer as the nearest f32, the same on every implementation: a conversion
/// of an integer above `2^24` may round either way (Vulkan leaves the direction to the
/// implementation), so the top and the low 12 bits are converted exactly and added
/// (the product by `2^12` is exact, so contracting the addition changes nothing).
#[inline(always)]
pub fn float_of<F: Float>(x: F::U) -> F {
    x.shr(12).to_f() * F::c(4096.0) + (x & F::U::c(0xfff)).to_f()
}

/// [`length2`] computed the `fixed_sum_of_squares` way, immune to regrouping.
#[inline(always)]
pub fn fixed_length2<F: Float>(w: V3<F>) -> F {
    fixed_sum_of_squares([w.x, w.y, w.z]).named("len2")
}

/// `N = round(sqrt(S))` for the exact integer `S = Σ Aᵢ²` of three integers `Aᵢ < 2^23`
/// with `2^44 ≤ S < 3·2^46` (a canonical vector on `fixed_sum_of_squares`'s grid), given
/// as its parts `hi·2^24 + lo` and as `s`, `S·2^-42` rounded once to f32.
///
/// `s` only estimates: [`root`]'s digits of `sqrt(s)`, within `2^-20` of the root of a
/// value within a relative `2^-24` of `S·2^-42`, give an `n₀` within two units of `N`.
/// The digits are then decided in integers: `S - n²` is computed modulo `2^32` from the
/// exact parts (`|S - n²|` stays far below `2^31` for `n` near `N`, so the wrapped
/// difference is exact), and `n` steps by one where `S - n² > n` (then `n + ½` is passed)
/// or `S - n² < 1 - n` (then `n - ½` is not reached); two such steps reach `N`, which
/// is the one integer with `1 - N ≤ S - N² ≤ N`. Without them a unit input would come
/// out one ULP long about half the time.
#[inline(always)]
pub fn rounded_root<F: Float>(s: F, parts: (F::U, F::U)) -> F::U {
    let n0 = (root(s).named("norm") * F::c(FIXED_SCALE)).to_u();
    settled_root::<F>(n0, parts)
}

/// [`rounded_root`]'s two integer steps from an estimate `n0` within two units of
/// `N = round(sqrt(S))`.
#[inline(always)]
pub fn settled_root<F: Float>(n0: F::U, (hi, lo): (F::U, F::U)) -> F::U {
    let u = {
        #[inline(always)]
        |v: u32| F::U::c(v)
    };
    let wide = hi.shl(24).wrapping_add(lo).named("wide");
    // S - n² + 2^30: positive, so unsigned comparisons order it.
    let bias = u(1 << 30);
    let step = {
        #[inline(always)]
        |n: F::U| {
            let e = wide
                .wrapping_sub(n.wrapping_mul(n))
                .wrapping_add(bias)
                .named("rest");
            let up = (bias + n).lt(e);
            let down = e.lt(bias.wrapping_sub(n) + u(1));
            F::U::sel(up, n + u(1), F::U::sel(down, n.wrapping_sub(u(1)), n)).named("n")
        }
    };
    step(step(n0))
}

/// The direction of a canonical `w` as components on the `2^-24` grid (f32's spacing in
/// `[½, 1)`), each a function of `w` alone: the components on the grid of
/// `fixed_sum_of_squares`, `Aᵢ = floor(|wᵢ|·2^21)` (below `2^23`), and their length
/// `N·2^-21` ([`rounded_root`]), give `kᵢ = round(Aᵢ·2^24 / N)`
/// (ties up), clamped to `2^24`, with the sign of `wᵢ` (a zero is `+0` or `-0`).
///
/// The quotient is only an estimate `k₀`; the exact remainder `r = Aᵢ·2^24 - k₀·N` is
/// computed modulo `2^32` in integers (it is far below `2^31` in magnitude, so the
/// wrapped difference is its two's complement), and the correction
/// `floor((2r + N) / 2N)` is estimated again and checked by the sign and size of the
/// integer remainder it leaves. No rounding of a float decides a digit, so no
/// deviation class can change the result. The direction is `A`'s, within `√3·2^-22` rad
/// of `w`'s (each floor moves a component of a vector longer than 2 by under `2^-21`);
/// the grid adds at most `2^-25` per component.
#[inline(always)]
pub fn unit_on_grid<F: Float>(w: V3<F>) -> V3<F> {
    let u = {
        #[inline(always)]
        |v: u32| F::U::c(v)
    };
    let a = w.map(
        #[inline(always)]
        |x| (x.abs() * F::c(FIXED_SCALE)).floor().to_u().named("fixed"),
    );
    let parts = square_sum_parts::<F, 3>([a.x, a.y, a.z]);
    let s = joined::<F>(parts) * F::c(1.0 / (FIXED_SCALE * FIXED_SCALE));
    let n = rounded_root(s, parts);
    let nf = n.to_f().named("nf");
    let one = F::c((1u32 << 24) as f32);
    let component = {
        #[inline(always)]
        |a: F::U, x: F| {
            let k0 = (a.to_f() / nf * one).round().to_u().named("k0");
            let r = a.shl(24).wrapping_sub(k0.wrapping_mul(n)).named("r");
            // 2r + N + 16N: the correction plus 8, which is non-negative for |k₀ - k| ≤ 8.
            let t = r.shl(1).wrapping_add(n).wrapping_add(n.shl(4)).named("t");
            let two_n = n.shl(1).named("two_n");
            let q0 = (float_of::<F>(t) / (nf * F::c(2.0)))
                .floor()
                .to_u()
                .named("q0");
            let rest = t.wrapping_sub(q0.wrapping_mul(two_n)).named("rest");
            let negative = rest.lt(u(0x8000_0000)).not().named("negative");
            let over = rest.lt(two_n).not().and(negative.not());
            let q = F::U::sel(
                over,
                q0 + u(1),
                F::U::sel(negative, q0.wrapping_sub(u(1)), q0),
            );
            let k = k0.wrapping_add(q).wrapping_sub(u(8)).named("k");
            let k = F::U::sel(u(1 << 24).lt(k), u(1 << 24), k);
            let v = (k.to_f() * F::c(1.0 / (1u32 << 24) as f32)).named("v");
            F::sel(x.lt(F::c(0.0)), -v, v)
        }
    };
    V3::new(
        component(a.x, w.x),
        component(a.y, w.y),
        component(a.z, w.z),
    )
}

/// `x² + y²` of a canonical vector, the `fixed_sum_of_squares` way.
#[inline(always)]
pub fn fixed_length2_xy<F: Float>(w: V3<F>) -> F {
    fixed_sum_of_squares([w.x, w.y]).named("rho2")
}

/// The grid of [`root`]'s high part, `2^-9`: a root below 8 is `k·2^-9 + l` with
/// `k < 2^12`, so the high part has 12 significant bits and its square is exact.
const ROOT_HIGH: f32 = 1.0 / 512.0;
/// The grid of [`root`]'s low part, `2^-21`: `l = j·2^-21` with `j < 2^12`.
const ROOT_LOW: f32 = 1.0 / (1u32 << 21) as f32;

/// `sqrt(s)` for `4 ≤ s < 64` (the [`fixed_length2`] of a canonical vector) as a
/// function of `s` alone: an implementation's square root (within a few ULP) is only an
/// estimate, and the result's digits are decided by comparing squares with `s`, like a
/// code.
///
/// The high part `H = k·2^-9` (`k < 2^12`) is the estimate truncated, then stepped by one
/// unit where `H² ≤ s < (H + 2^-9)²` fails: both squares are exact (12 and 13 bits). The
/// low part `l = j·2^-21` (`j < 2^12`) is estimated from `(s - H²) / (H + √s)`, then
/// stepped by one unit where `(H + l)² ≤ s < (H + l + 2^-21)²` fails: `H + l` is exact
/// (24 bits) and each square is one correctly rounded product meeting `s` in a
/// comparison, so no contraction or regrouping can reach it. The result is the root
/// truncated to `2^-21`, give or take one unit where the rounding of a square decides a
/// near tie: within `2^-20`, about `2^-22` relative, like a rounding. It is returned as
/// one product, `(k·2^12 + j)·2^-21` (exact integers), not as the sum `H + l`, which an
/// optimiser could regroup with the caller's next addition.
#[inline(always)]
pub fn root<F: Float>(s: F) -> F {
    let (u, v) = (F::c(ROOT_HIGH), F::c(ROOT_LOW));
    let estimate = s.sqrt().named("root_estimate");
    let k0 = (estimate * F::c(1.0 / ROOT_HIGH)).floor().named("root_k0");
    let h0 = (k0 * u).named("root_h0");
    let h1 = (h0 + u).named("root_h1");
    let up = (h1 * h1).le(s);
    let down = (h0 * h0).gt(s);
    let k = stepped(k0, up, down).named("root_k");
    let h = (k * u).named("root_h");
    let r = (s - h * h).named("root_rest");
    let j0 = (r / (h + estimate) * F::c(1.0 / ROOT_LOW))
        .floor()
        .named("root_j0");
    let (m0, m1) = (
        (h + j0 * v).named("root_m0"),
        (h + (j0 + F::c(1.0)) * v).named("root_m1"),
    );
    let up = (m1 * m1).le(s);
    let down = (m0 * m0).gt(s);
    let j = stepped(j0, up, down).named("root_j");
    // One product of an integer below 2^24: a sum here could be regrouped with the
    // caller's next addition.
    ((k * F::c(ROOT_HIGH / ROOT_LOW) + j) * v).named("root")
}

/// `sqrt(s)` for `s ≥ 2^-120` as a function of `s` alone: `s` is scaled by an even power
/// of two (read from its exponent bits, so exact) into `[4, 16)`, where [`root`] decides
/// its digits, and the root scaled back. About `2^-22` relative, like a rounding.
#[inline(always)]
pub fn root_of<F: Float>(s: F) -> F {
    // `x = (E + 1) >> 1` of the biased exponent E: s·2^(2·(64 - x) + 2) is in [4, 16).
    let x = s
        .to_bits()
        .shr(23)
        .wrapping_add(F::U::c(1))
        .shr(1)
        .named("half_exponent");
    let down = F::U::c(257)
        .wrapping_sub(x.shl(1))
        .shl(23)
        .as_float()
        .named("root_down");
    let up = (F::U::c(62) + x).shl(23).as_float().named("root_up");
    root(s * down) * up
}

/// `floor(sqrt(s))` for `0 ≤ s ≤ 2^42`, as a function of `s` alone: the root (within
/// 6.5 ULP, under 1.7 units below `2^21`) is only an estimate, stepped twice by one where
/// `e² ≤ s < (e + 1)²` fails (each square one rounded product meeting `s` in a
/// comparison). Within one unit of the exact floor where a square's rounding decides a
/// near tie.
#[inline(always)]
pub fn fixed_root<F: Float>(s: F) -> F {
    let step = {
        #[inline(always)]
        |e: F| {
            let f = (e + F::c(1.0)).named("root_next");
            stepped(e, (f * f).le(s), (e * e).gt(s))
        }
    };
    step(step(s.sqrt().floor().named("root_estimate")).named("root_step")).named("root")
}

/// `floor(n / d · 2^bits)` for `d > 0` and `|n| ≤ d` (both normal or `n` zero), as a
/// function of `n` and `d` alone: the quotient is only an estimate (a division within
/// 2.5 ULP is within `2.5·2^(bits-24)` units of the truth), stepped by one unit as many
/// times as that can be off where `e·d ≤ n·2^bits < (e + 1)·d` fails (single products
/// meeting in comparisons, like a code; `n·2^bits` is exact). Within one unit of the exact
/// floor where a product's rounding decides a near tie.
#[inline(always)]
pub fn fixed_ratio<F: Float>(n: F, d: F, bits: u32) -> F {
    let one = F::c((1u32 << bits) as f32);
    let big = (n * one).named("big");
    let step = {
        #[inline(always)]
        |e: F| stepped(e, ((e + F::c(1.0)) * d).le(big), (e * d).gt(big))
    };
    let off = (2.5 * f64::from(1u32 << bits) / f64::from(1u32 << 24)).floor() as u32;
    let mut e = (n / d * one).floor().named("ratio_estimate");
    for _ in 0..=off {
        e = step(e).named("ratio");
    }
    e
}

/// `1 + z` of the unit direction of a canonical `w` whose length is `l` (from
/// [`root`]), as the ratio `a / b` times `1/l`: `(l + w.z) / 1` on the upper hemisphere,
/// `ρ² / (l - w.z)` on the lower, where the sum would cancel (`ρ² = w.x² + w.y²` from
/// [`fixed_length2_xy`]). `a > 0` for every direction but -Z, where `a = 0`; `b > 0` always.
/// Selects of sums, no product: contraction cannot reach them.
#[inline(always)]
pub fn one_plus_z<F: Float>(w: V3<F>, l: F) -> (F, F) {
    let north = w.z.ge(F::c(0.0));
    let a = F::sel(north, l + w.z, fixed_length2_xy(w)).named("opz_a");
    let b = F::sel(north, F::c(1.0), l - w.z).named("opz_b");
    (a, b)
}

/// The canonical input with what the projections from -Z need: its length `l` (from
/// [`root`]) and `1 + z` as `a / b` ([`one_plus_z`]).
#[derive(Clone, Copy)]
pub struct OnePlusZ<F: Float> {
    pub w: V3<F>,
    /// Whether the input has a direction ([`canonical`]).
    pub ok: F::B,
    pub l: F,
    pub a: F,
    pub b: F,
}

impl<F: Float> OnePlusZ<F> {
    /// From any input, invalid input standing in as +Z ([`canonical_or_z`]).
    #[inline(always)]
    pub fn of(v: V3<F>) -> Self {
        let (w, ok) = canonical_or_z(v);
        let l = root(fixed_length2(w));
        let (a, b) = one_plus_z(w, l);
        OnePlusZ { w, ok, l, a, b }
    }
    /// Whether this is -Z, where `a = 0` and the projections have no finite value.
    #[inline(always)]
    pub fn at_pole(&self) -> F::B {
        self.a.le(F::c(0.0))
    }
    /// The same with -Z replaced by canonical +Z (`l = 2`, `a = 4`, `b = 1`), for a
    /// search that needs parameters to start from; the caller replaces the pole's answer.
    #[inline(always)]
    pub fn off_pole(self) -> Self {
        let pole = self.at_pole();
        let z = {
            #[inline(always)]
            |x: F, at: f32| F::sel(pole, F::c(at), x)
        };
        OnePlusZ {
            w: V3::sel_all(pole, V3::new(F::c(0.0), F::c(0.0), F::c(2.0)), self.w),
            ok: self.ok,
            l: z(self.l, 2.0),
            a: z(self.a, 4.0),
            b: z(self.b, 1.0),
        }
    }
}

/// `p + q` of two non-negative products, as a function of their rounded values alone:
/// an implementation may contract `p + q` into `fma(a, b, q)`, so each is first put
/// through a floor on a grid of `2^-27` of the larger one's binade (the grid read from
/// its exponent bits, so exact), which no contraction reaches; the two integers are
/// added (rounded once, `2^-24`) and scaled back by the power of two. Within `2^-23` of
/// the sum, relative; below `2^-87` the grid stops shrinking (such a sum is `0`, give
/// or take).
#[inline(always)]
pub fn settled_sum<F: Float>(p: F, q: F) -> F {
    let u = {
        #[inline(always)]
        |v: u32| F::U::c(v)
    };
    // The larger one's biased exponent, clamped to 40 ..= 254 (a zero reads as 0).
    let e = p.at_least(q).to_bits().shr(23).named("exponent");
    let e = F::U::sel(e.lt(u(40)), u(40), e).named("exponent");
    let e = F::U::sel(u(254).lt(e), u(254), e).named("exponent");
    // 2^(154 - e) and its inverse as exponent fields: 27 ..= 241 and 13 ..= 227.
    let scale = u(281).wrapping_sub(e).shl(23).as_float().named("scale");
    let back = e.wrapping_sub(u(27)).shl(23).as_float().named("back");
    ((p * scale).floor() + (q * scale).floor()) * back
}

/// The code decided by `past(c)`: `1` where the parameter, scaled to codes, lies at or
/// past `c + ½` (the boundary between codes `c` and `c + 1`), `0` where not.
/// `estimate` (any rounding of the scaled parameter, within one code of it) is clamped
/// to the codes and stepped by one where `past` says so, so the result depends on `past`
/// alone; ties go up. `past` answers in floats built with selects, not in boolean logic:
/// boolean operations stay scalar in emitted code, which would leave the estimate used
/// both as scalars and, in the vector that returns the codes, recomputed; a driver may
/// round the two copies of its division differently.
#[inline(always)]
pub fn decided<F: Float>(q: Quant, estimate: F, past: impl Fn(F) -> F) -> F {
    let (lo, hi) = (F::c(q.min_code()), F::c(q.max_code()));
    let e = estimate.clamped(lo, hi).named("estimate");
    let up = F::sel(e.lt(hi), past(e), F::c(0.0)).named("up");
    let down = F::sel(e.gt(lo), past(e - F::c(1.0)) - F::c(1.0), F::c(0.0)).named("down");
    e + up + down
}

/// The code decided by `past(c)` alone (see [`decided`]), by bisection over all codes of
/// the unorm `q`: for a parameter whose float estimate can be many codes off (an
/// ill-conditioned inverse), at the cost of `bits` evaluations of `past`. The code is the
/// number of boundaries passed; `past` is taken to be `1` up to some boundary and `0`
/// beyond, and whatever it is, the result is a function of its answers alone. The first
/// round's boundary, the middle one `2^(b-1) - 1 + ½`, is a literal, which `past`'s
/// arithmetic cannot take (an expression of literals only is not emitted): the caller
/// answers it as `middle`.
#[inline(always)]
pub fn bisected<F: Float>(q: Quant, middle: F::B, past: impl Fn(F) -> F) -> F {
    let half = (1u64 << (q.bits() - 1)) as f32;
    let beyond = middle;
    let mut lo = F::sel(beyond, F::c(half), F::c(0.0));
    let mut hi = F::sel(beyond, F::c(q.max_code()), F::c(half - 1.0));
    // The codes lo ..= hi are 2^k in number, halved each round.
    for _ in 1..q.bits() {
        let mid = ((lo + hi + F::c(1.0)) * F::c(0.5)).floor().named("mid");
        let below = (mid - F::c(1.0)).named("mid_below");
        let beyond = past(below).gt(F::c(0.5)).named("beyond");
        lo = F::sel(beyond, mid, lo).named("lo");
        hi = F::sel(beyond, hi, below).named("hi");
    }
    lo
}

/// `1` where `m`, else `0`.
#[inline(always)]
pub fn one_if<F: Float>(m: F::B) -> F {
    F::sel(m, F::c(1.0), F::c(0.0)).named("one_if")
}

/// The unorm code of the parameter `x / a · ½ + ½` (`a > 0`, `|x| ≤ a` up to rounding)
/// at the boundaries `c + offset` (`½` rounds to the nearest code, ties up; `1` floors):
/// the boundary is passed where `x·(M/2) ≥ (c + offset - M/2)·a`, two products meeting
/// in a comparison, so [`decided`] steps the estimate by comparisons alone.
#[inline(always)]
pub fn unorm_ratio<F: Float>(q: Quant, x: F, a: F, offset: f32) -> F {
    let m = q.max_code();
    let t = (x * F::c(m * 0.5)).named("t");
    let estimate = (t / a + F::c(m * 0.5)).round();
    decided(
        q,
        estimate,
        #[inline(always)]
        |c| one_if(t.ge((c - F::c(m * 0.5 - offset)) * a)),
    )
}

/// The unorm code of the parameter `x / sqrt(s) · ½ + ½` (`s > 0`, `x² ≤ s` up to
/// rounding; `root` any estimate of `sqrt(s)`, used only for the first guess) at the
/// boundaries `c + offset` (`½` rounds, ties up; `1` floors): the boundary is passed
/// where `x·(M/2) ≥ k·sqrt(s)` (`k = c + offset - M/2`), which [`past_root_ratio`]
/// decides from `x²·(M²/4)` (the literal factor last) and `k²·s`.
#[inline(always)]
pub fn unorm_sqrt_ratio<F: Float>(q: Quant, x: F, s: F, root: F, offset: f32) -> F {
    let m = q.max_code();
    let big2 = (x * x * F::c((f64::from(m).powi(2) / 4.0) as f32)).named("big2");
    let estimate = (x / root * F::c(m * 0.5) + F::c(m * 0.5)).round();
    decided(
        q,
        estimate,
        #[inline(always)]
        |c| {
            let k = c - F::c(m * 0.5 - offset);
            past_root_ratio(x, big2, k, k * k * s)
        },
    )
}

/// `1` where `x·K ≥ k·sqrt(s)` (`K > 0`, `s > 0`), else `0`, from `big2 = (x·K)²`
/// and `k2s = k²·s` (each a product of exact or deterministic values): decided by the
/// signs of `x` and `k` and, where they agree, by the squares, so no root or quotient
/// decides it. What [`decided`] asks of a parameter `x / sqrt(s)` at the boundary `k`.
#[inline(always)]
pub fn past_root_ratio<F: Float>(x: F, big2: F, k: F, k2s: F) -> F {
    let far = F::sel(k.gt(F::c(0.0)), one_if(big2.ge(k2s)), F::c(1.0));
    let near = F::sel(k.lt(F::c(0.0)), one_if(big2.le(k2s)), F::c(0.0));
    F::sel(x.ge(F::c(0.0)), far, near)
}

/// The snorm code of `n / d` (`d > 0`, both normal or `n` zero, both computed with
/// correctly rounded additions only): the integer `c ≤ M` with
/// `(c - ½)·d ≤ |n|·M < (c + ½)·d`, with the sign of `n` (`-0` counts as positive). Ties
/// (`|n|·M` equal to a product) round away from zero. `|n|` may exceed `d` by rounding
/// (`d` a root of floored squares): the code is then clamped to `M`.
#[inline(always)]
pub fn snorm_ratio<F: Float>(q: Quant, n: F, d: F) -> F {
    let (estimate, up, down) = snorm_ratio_steps(q, n, d);
    signed(n, corrected(q, estimate, up, down))
}

/// [`snorm_ratio`] where `|n| ≤ d` holds by monotone rounding: `d` is a correctly rounded
/// sum of non-negative terms whose exact sum is at least `|n|`, and `n` a correctly
/// rounded sum or difference no larger in magnitude (oct's `x` and `l1 - |y|`, hemioct's
/// `x ± y`). Then no clamp can trigger, for `M < 2^20`: `|n|/d ≤ 1` within 2.5 ULP, so the
/// estimate is in `[0, M]` (`M·(1 + 5·2^-24)` stays below `M + ½`); at `M` the step up needs
/// `fl(|n|·M) ≥ fl((M + ½)·d)`, which monotone rounding excludes (`fl(|n|·M) ≤ fl(d·M)`,
/// and `(M + ½)/M - 1 = 1/(2M)` exceeds `2^-21`, so the two products of `d` round apart);
/// at 0 the step down needs `|n|·M < -½·d`.
#[inline(always)]
pub fn snorm_ratio_within<F: Float>(q: Quant, n: F, d: F) -> F {
    debug_assert!(q.max_code() < (1u32 << 20) as f32);
    let (estimate, up, down) = snorm_ratio_steps(q, n, d);
    signed(n, stepped(estimate, up, down))
}

/// `round(|n|/d·M)` and the comparisons that step it to the exact code.
#[inline(always)]
fn snorm_ratio_steps<F: Float>(q: Quant, n: F, d: F) -> (F, F::B, F::B) {
    let a = n.abs().named("magnitude");
    let m = F::c(q.max_code());
    let estimate = (a / d * m).round().named("estimate");
    let big = (a * m).named("big");
    let up = big.ge((estimate + F::c(0.5)) * d);
    let down = big.lt((estimate - F::c(0.5)) * d);
    (estimate, up, down)
}

/// The snorm code of `n / sqrt(s)` (`s > 0`, `n² ≤ s` up to rounding, both exact or
/// correctly rounded functions of the input, `s` from [`length2`]): the integer `c ≤ M`
/// with `(c - ½)²·s ≤ (|n|·M)² < (c + ½)²·s` (each product rounded once), with the sign
/// of `n`.
///
/// `|n|·M` is taken as `|n·M|` (the same bits): squared as `(|n|·M)·(|n|·M)`, a product
/// by a constant squared, Slang's SPIR-V optimizer regroups it as `M²·(|n|·|n|)`, a
/// different rounding, where nothing marks the product `NoContraction`. The absolute
/// value of a product is not a product by a constant, and that rewrite leaves it alone.
#[inline(always)]
pub fn snorm_sqrt_ratio<F: Float>(q: Quant, n: F, s: F) -> F {
    let m = F::c(q.max_code());
    let big = (n * m).abs().named("big");
    let estimate = (big / s.sqrt()).round().named("estimate");
    let big2 = (big * big).named("big2");
    let hi = (estimate + F::c(0.5)).named("upper");
    let lo = (estimate - F::c(0.5)).named("lower");
    let up = big2.ge(hi * hi * s);
    // At code 0 the lower boundary is 0 itself (`lo² > 0` would wrongly step down).
    let down = estimate.gt(F::c(0.0)).and(big2.lt(lo * lo * s));
    signed(n, corrected(q, estimate, up, down))
}

/// The f16 value nearest `n / √s` (`n` a component of a canonical vector, `s` its
/// [`length2`]), as an f32: [`snorm_sqrt_ratio`] on the f16 grid. The grid spacing
/// `1/q` is taken from the binade of an estimate, clamped to the f16 normal binades
/// (below `2^-14` the subnormal spacing `2^-24` is the lowest binade's); an estimate in
/// the neighbouring binade can only occur within a few ULP of the power of two between
/// them, which both grids round to. The code is then the integer `c` with
/// `(c - ½)²·s ≤ (|n|·q)² < (c + ½)²·s` (`|n|·q` exact, each other product rounded
/// once), times `1/q` (exact). A zero result is `+0` whatever the sign of `n`.
#[inline(always)]
pub fn half_sqrt_ratio<F: Float>(n: F, s: F) -> F {
    let u = {
        #[inline(always)]
        |v: u32| F::U::c(v)
    };
    let a = n.abs();
    let estimate = (a / s.sqrt()).named("half_estimate");
    // The biased exponent of the estimate (sign masked: a lost sign of zero is harmless),
    // clamped to the f16 normal binades 2^-14 .. 2^-1: 113 ..= 126.
    let e = (estimate.to_bits() & u(0x7fff_ffff))
        .shr(23)
        .named("exponent");
    let e = F::U::sel(e.lt(u(113)), u(113), e).named("exponent");
    let e = F::U::sel(u(126).lt(e), u(126), e).named("exponent");
    // q = 2^(10 - (e - 127)) and 1/q, built as exponent fields.
    let q = u(264).wrapping_sub(e).shl(23).as_float().named("half_grid");
    let q_inv = e.wrapping_sub(u(10)).shl(23).as_float().named("half_unit");
    let big = (a * q).named("big");
    let big2 = (big * big).named("big2");
    let c = (estimate * q).round().named("half_code");
    let hi = (c + F::c(0.5)).named("upper");
    let lo = (c - F::c(0.5)).named("lower");
    let up = big2.ge(hi * hi * s);
    let down = c.gt(F::c(0.0)).and(big2.lt(lo * lo * s));
    let c = stepped(c, up, down);
    let h = c * q_inv;
    F::sel(n.lt(F::c(0.0)).and(c.gt(F::c(0.0))), -h, h)
}

/// `floor(n / d · M)` for `|n| ≤ d` (`d > 0`): the integer `c`
/// in `[-M, M]` with `c·d ≤ n·M < (c + 1)·d` (each side rounded once), where a precise
/// search starts.
#[inline(always)]
pub fn floor_ratio<F: Float>(q: Quant, n: F, d: F) -> F {
    let m = F::c(q.max_code());
    let estimate = (n / d * m).floor().named("estimate");
    let big = (n * m).named("big");
    let up = big.ge((estimate + F::c(1.0)) * d);
    let down = big.lt(estimate * d);
    stepped(estimate, up, down).clamped(F::c(q.min_code()), m)
}

/// The code of the parameter `n / d` in the field `q`: a snorm field stores it as it is
/// ([`snorm_ratio`]), a unorm field as a normal-map texel channel does, `n/d·½ + ½`
/// ([`unorm_ratio`], ties up). One codec definition then serves both storages.
#[inline(always)]
pub fn ratio_code<F: Float>(q: Quant, n: F, d: F) -> F {
    match q {
        Quant::Unorm(_) => unorm_ratio(q, n, d, 0.5),
        _ => snorm_ratio(q, n, d),
    }
}

/// [`ratio_code`] where `|n| ≤ d` holds by monotone rounding ([`snorm_ratio_within`]).
#[inline(always)]
pub fn ratio_code_within<F: Float>(q: Quant, n: F, d: F) -> F {
    match q {
        Quant::Unorm(_) => unorm_ratio(q, n, d, 0.5),
        _ => snorm_ratio_within(q, n, d),
    }
}

/// The code of the parameter `n / sqrt(s)` in the field `q`, stored as [`ratio_code`]
/// says ([`snorm_sqrt_ratio`] or [`unorm_sqrt_ratio`]).
#[inline(always)]
pub fn sqrt_ratio_code<F: Float>(q: Quant, n: F, s: F) -> F {
    match q {
        Quant::Unorm(_) => unorm_sqrt_ratio(q, n, s, s.sqrt(), 0.5),
        _ => snorm_sqrt_ratio(q, n, s),
    }
}

/// The code at or below the parameter `n / d` in the field `q`, stored as [`ratio_code`]
/// says: where a precise search starts ([`floor_ratio`], or [`unorm_ratio`] at the
/// boundaries `c + 1`).
#[inline(always)]
pub fn floor_ratio_code<F: Float>(q: Quant, n: F, d: F) -> F {
    match q {
        Quant::Unorm(_) => unorm_ratio(q, n, d, 1.0),
        _ => floor_ratio(q, n, d),
    }
}

/// The estimate stepped by one where a comparison says so, within `[0, M]`.
#[inline(always)]
fn corrected<F: Float>(q: Quant, estimate: F, up: F::B, down: F::B) -> F {
    stepped(estimate, up, down).clamped(F::c(0.0), F::c(q.max_code()))
}

/// The estimate stepped by one where a comparison says so.
#[inline(always)]
fn stepped<F: Float>(estimate: F, up: F::B, down: F::B) -> F {
    let step_down = F::sel(down, F::c(-1.0), F::c(0.0)).named("step_down");
    estimate + F::sel(up, F::c(1.0), step_down).named("nudge")
}

/// `c` with the sign of `n`; a zero `n` gives `c` (which is then 0).
#[inline(always)]
fn signed<F: Float>(n: F, c: F) -> F {
    F::sel(n.lt(F::c(0.0)), -c, c)
}

/// `2^100` when the magnitude `m` is below `2^-100`, else 1: a factor that scales a tiny
/// numerator and divisor up exactly (the ratio unchanged) so that no denormal reaches a
/// division, where an implementation may flush it to zero though not in the comparison
/// guarding it (`0/0` is NaN).
#[inline(always)]
pub fn denormal_proof_scale<F: Float>(m: F) -> F {
    let tiny = 1.0 / (1u128 << 100) as f32;
    F::sel(m.lt(F::c(tiny)), F::c(1.0 / tiny), F::c(1.0))
}
