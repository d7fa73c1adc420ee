//! An adversarial evaluator: the model's vocabulary evaluated the way a conformant GPU is
//! *allowed* to evaluate it, rather than the way lavapipe and Rust's `f32` do.
//!
//! [`Dev`] (with [`DevU`] and [`DevB`]) implements [`Float`], so every codec runs on it
//! unchanged: the same generic code the `f32` reference and the tracer run. Which
//! liberty it takes is a thread-local [`Deviation`] set by [`with`]: one [`Class`] and a
//! [`Mode`]. With no deviation set, `Dev` computes exactly what `f32` computes.
//!
//! Each operation that a class touches has a small set of allowed results; the mode picks
//! one per operation: [`Mode::Seeded`] uniformly from a seeded stream (reseeded per item by
//! [`begin_item`], so a result does not depend on which other items ran), [`Mode::Lowest`]
//! and [`Mode::Highest`] always the lowest or highest (in IEEE total order, so `-0 < +0`),
//! [`Mode::Site`] by a hash of the seed and the operation's place in the function, the same
//! for every item, as a compiler fuses or regroups an instruction for every input or for
//! none, and [`Mode::Last`] always the deviation (under `denorm`, SwiftShader's flushing). A [`Deviation`] takes a set of classes ([`Classes`]) at once: an implementation
//! that contracts also regroups, and the changes an NVIDIA H100 made on the paths without
//! `NoContraction` are reproduced only by `fma`, `reassoc` and `contract` together, per
//! site (`tests/portability.rs`, over the codes kept in `tests/data/`).
//!
//! What the APIs allow, and how each class models it (Vulkan: "Precision and Operation of
//! SPIR-V Instructions"; D3D11 functional spec §3.1 "Floating-point rules"; WGSL §15
//! "Floating Point Evaluation"):
//!
//! | class | allowance | model |
//! |---|---|---|
//! | `div` | `x / y` within 2.5 ULP (Vulkan, WGSL) | the correctly rounded quotient stepped by up to ±3 floats, kept where within 2.5 ULP of the exact quotient and of the same sign; the worst modes give the farthest floats |
//! | `sqrt` | inherited from `1.0 / inversesqrt(x)`: inversesqrt 2 ULP, divide 2.5 ULP | within [`SQRT_ULP`] = 6.5 ULP of the exact root, see there |
//! | `fma` | `a*b + c` may be contracted unless `NoContraction` / `precise` (WGSL never guarantees it, GLSL only with `precise`) | a product remembers its factors; an add or subtract with such an operand may round `a*b + c` once (`mul_add`) |
//! | `denorm` | denormals may be flushed on input and output of arithmetic (D3D: always, sign preserved; Vulkan without float-controls) | each operand of `+ - * /`, `sqrt`, `floor`, `round` and the comparisons, and each result of the arithmetic, may become a zero of the same sign |
//! | `zero` | the sign of zero may be lost (Vulkan without `SignedZeroInfNanPreserve`, SSE2-only `floor`/`roundEven` on Mesa) | a zero produced by `floor`, `round`, `abs` or a select may have either sign |
//! | `excess` | excess precision (C's `FLT_EVAL_METHOD`; Mesa with `GALLIUM_NOSSE=1`) | see [`Class::Excess`] |
//! | `reassoc` | reassociation and combination of operations unless `NoContraction` / `precise` (SPIR-V's `NoContraction`: "such operations are not allowed to reassociate", so without it they are; WGSL §15.7.5 "Reassociation and Fusion") | a sum remembers its operands: `(a + b) + c` may become `a + (b + c)` or `(a + c) + b`; `a*b + a*c` may become `a*(b + c)` (a rule of Mesa's `nir_opt_algebraic` for operations not marked exact) |
//! | `round` | `+ - *` rounded to either neighbour of the exact result (WGSL names no rounding mode; Vulkan's default may be round-toward-zero unless the shader declares `RoundingModeRTE`) | each result of `+ - *` may be the other neighbour of the exact value |
//! | `contract` | a multiply combined with any other instruction unless `NoContraction` / `precise` (SPIR-V: `NoContraction` "cannot be combined with another instruction"; WGSL §15.7.5) | a comparison may take a remembered product whole (`a*b < c` as `fma(a, b, -c) < 0`); a product may be distributed over a remembered sum (`(u + v)*k` as `u*k + v*k`, or with one product fused) or regrouped with a remembered product (`(f*g)*k` as `f*(g*k)`); under `div` too, a quotient may be `a*(1/b)`, a product the next operation may take whole |
//!
//! Division and square root outside the normal range, where Vulkan allows anything, are
//! still held to the same ULP bounds: the model looks for fragile codes, not for every
//! result a pathological driver could return.

use super::num::{Bool, Float, Kind, Lane, Uint};
use rand_core::Rng;
use rand_pcg::Pcg64Mcg;
use std::cell::{Cell, RefCell};
use std::cmp::Ordering;
use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Sub};

/// The ULP bound used for `sqrt`. Vulkan states sqrt as "inherited from
/// 1.0 / inversesqrt()", with inversesqrt within 2 ULP and division within 2.5 ULP. For a
/// root `r = m·2^e` (`1 ≤ m < 2`), `1/r` has its mantissa `2/m` at the bottom of the next
/// binade when `m` is near 2, so 2 ULP of `1/r` is a relative error of up to `m·2^-23`,
/// which is `m² < 4` ULP of `r`; the division adds 2.5 ULP: 6.5 ULP of the exact root in
/// all. This is the envelope: for roots with a small mantissa fewer are reachable.
pub const SQRT_ULP: f64 = 6.5;
/// The ULP bound of division (Vulkan and WGSL).
pub const DIV_ULP: f64 = 2.5;

/// One kind of liberty an implementation may take.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Class {
    /// Division within [`DIV_ULP`] of the exact quotient.
    Div,
    /// Square root within [`SQRT_ULP`] of the exact root.
    Sqrt,
    /// Contraction of `a*b + c` into one rounding.
    Fma,
    /// Flush of denormal inputs and outputs of arithmetic to zero.
    Denorm,
    /// Loss of the sign of zero in `floor`, `round`, `abs` and selects.
    Zero,
    /// Excess precision: the results of `+ - * /` and `sqrt` are kept in f64 along chains of
    /// arithmetic (including negation and `abs`, which are exact) and rounded to f32 where
    /// the value is compared, selected, rounded to an integer (`floor`, `round`), converted
    /// or stored; any single result may also be rounded early (spilled). This is the
    /// `FLT_EVAL_METHOD == 1` model; x87's 64-bit significand rounds a little differently
    /// but is caught by the same fragility.
    Excess,
    /// Reassociation of sums and factoring of common factors, which SPIR-V allows on
    /// operations without `NoContraction` and WGSL allows always.
    Reassoc,
    /// Either neighbour of the exact result for `+ - *`.
    Round,
    /// Contraction beyond `a*b + c`: a comparison taking a product whole (`a*b < c` as
    /// `fma(a, b, -c) < 0`), a product distributed over a sum (`(u + v)*k` as
    /// `u*k + v*k`, one product possibly fused) or regrouped with another product
    /// (`(f*g)*k` as `f*(g*k)`), which SPIR-V allows on operations without `NoContraction`
    /// and WGSL always; C compilers contract only `a*b + c`.
    Contract,
}

impl Class {
    pub const ALL: [Class; 9] = [
        Class::Div,
        Class::Sqrt,
        Class::Fma,
        Class::Denorm,
        Class::Zero,
        Class::Excess,
        Class::Reassoc,
        Class::Round,
        Class::Contract,
    ];
    /// The classes a portable encoder is guaranteed against: what an implementation that
    /// rounds `+ - *` to nearest and keeps the order of operations (`precise`,
    /// `NoContraction`, C without fast math) may still do. Excess precision, reassociation
    /// and either-neighbour rounding are measured and reported, but the guarantee excludes
    /// them: they change the rounding of sums and products themselves, which only exact
    /// arithmetic survives; no conformant GPU path keeps f32 results wider, and C on x87 is
    /// outside the supported targets.
    pub const GUARANTEED: [Class; 5] = [
        Class::Div,
        Class::Sqrt,
        Class::Fma,
        Class::Denorm,
        Class::Zero,
    ];
    pub fn guaranteed(self) -> bool {
        Class::GUARANTEED.contains(&self)
    }
    pub fn name(self) -> &'static str {
        match self {
            Class::Div => "div",
            Class::Sqrt => "sqrt",
            Class::Fma => "fma",
            Class::Denorm => "denorm",
            Class::Zero => "zero",
            Class::Excess => "excess",
            Class::Reassoc => "reassoc",
            Class::Round => "round",
            Class::Contract => "contract",
        }
    }
}

/// A set of [`Class`]es taken at once: what one implementation may combine (a driver that
/// contracts `a*b + c` also computes `x / y` within its ULP bound, and may contract the
/// product its division became).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Classes(u16);

impl Classes {
    /// What a path without `NoContraction` (WGSL, GLSL without `precise`) may take at
    /// once: `fma`, `reassoc` and `contract`. Per site, these reproduce what an H100
    /// changed on those paths (`tests/portability.rs`).
    pub const WITHOUT_NO_CONTRACTION: Classes =
        Classes::of(&[Class::Fma, Class::Reassoc, Class::Contract]);
    /// The set of `classes`.
    pub const fn of(classes: &[Class]) -> Classes {
        let mut bits = 0;
        let mut i = 0;
        while i < classes.len() {
            bits |= 1 << classes[i] as u16;
            i += 1;
        }
        Classes(bits)
    }
    pub fn contains(self, class: Class) -> bool {
        self.0 & 1 << class as u16 != 0
    }
    /// The members, in [`Class::ALL`] order.
    pub fn members(self) -> impl Iterator<Item = Class> {
        Class::ALL.into_iter().filter(move |&c| self.contains(c))
    }
    /// Whether the portability guarantee covers every member ([`Class::guaranteed`]).
    pub fn guaranteed(self) -> bool {
        self.members().all(Class::guaranteed)
    }
    /// The members' names joined by `+` (`fma+div`).
    pub fn name(self) -> String {
        self.members()
            .map(Class::name)
            .collect::<Vec<_>>()
            .join("+")
    }
}

impl From<Class> for Classes {
    fn from(c: Class) -> Classes {
        Classes::of(&[c])
    }
}

/// How an operation picks among its allowed results.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Mode {
    /// Uniformly, from a stream seeded by this seed and the item ([`begin_item`]).
    Seeded(u64),
    /// Always the lowest allowed result.
    Lowest,
    /// Always the highest allowed result.
    Highest,
    /// Per site: each operation of the function (its place in the evaluation, the same for
    /// every item of straight-line code) picks by a hash of this seed and the site, the
    /// same for every item, as a compiler decides once per instruction whether to fuse,
    /// regroup or approximate it. Where the number of allowed results depends on the
    /// values (a zero quotient has one), the pick is the hash modulo that number.
    Site(u64),
    /// Always the last allowed result in the order the class lists them, the result as
    /// computed being first: the deviation taken wherever the class allows one. Under
    /// `denorm` that is every denormal operand and every denormal result flushed to a zero
    /// of its sign, which is what SwiftShader does (and with it Chromium's WebGPU and
    /// WebGL 2 on a machine without a GPU).
    Last,
}

impl Mode {
    pub fn name(self) -> String {
        match self {
            Mode::Seeded(s) => format!("seed {s}"),
            Mode::Lowest => "lowest".into(),
            Mode::Highest => "highest".into(),
            Mode::Site(s) => format!("site {s}"),
            Mode::Last => "last".into(),
        }
    }
}

/// The classes and a mode: what [`Dev`] arithmetic does on this thread.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Deviation {
    pub classes: Classes,
    pub mode: Mode,
}

impl Deviation {
    pub fn new(classes: impl Into<Classes>, mode: Mode) -> Deviation {
        Deviation {
            classes: classes.into(),
            mode,
        }
    }
}

thread_local! {
    static ACTIVE: Cell<Option<Deviation>> = const { Cell::new(None) };
    static RNG: RefCell<Pcg64Mcg> = RefCell::new(Pcg64Mcg::new(1));
    /// Whether an operation since [`begin_item`] had allowed results that differ.
    static CHOSE: Cell<bool> = const { Cell::new(false) };
    /// The site of the operation being evaluated ([`Mode::Site`]): operations since
    /// [`begin_item`], and picks within the operation.
    static SITE: Cell<(u64, u64)> = const { Cell::new((0, 0)) };
}

/// Runs `f` with `dev` as this thread's deviation (`None`: exact `f32` arithmetic), and
/// restores the previous one afterwards, also when `f` panics.
pub fn with<R>(dev: Option<Deviation>, f: impl FnOnce() -> R) -> R {
    struct Restore(Option<Deviation>);
    impl Drop for Restore {
        fn drop(&mut self) {
            ACTIVE.with(|a| a.set(self.0));
        }
    }
    let _restore = Restore(ACTIVE.with(|a| a.replace(dev)));
    f()
}

/// Reseeds the stream of [`Mode::Seeded`] for item `index`, so that an item's deviations
/// depend only on the seed and the item, not on the items evaluated before it.
pub fn begin_item(index: u64) {
    CHOSE.with(|c| c.set(false));
    SITE.with(|s| s.set((0, 0)));
    if let Some(Deviation {
        mode: Mode::Seeded(seed),
        ..
    }) = ACTIVE.with(Cell::get)
    {
        RNG.with(|r| *r.borrow_mut() = Pcg64Mcg::new(item_state(seed, index)));
    }
}

/// The state [`begin_item`] seeds an item's stream with: `(seed·2^64 + index)` times an
/// odd constant, modulo `2^128` (a multiplicative hash, which wraps by design: a plain
/// `*` overflows for every seed above 0 and panics in a debug build), made odd as
/// `Pcg64Mcg` wants.
pub fn item_state(seed: u64, index: u64) -> u128 {
    (u128::from(seed) << 64 | u128::from(index)).wrapping_mul(ITEM_HASH) | 1
}

/// The odd multiplier of [`item_state`].
pub const ITEM_HASH: u128 = 0x9e37_79b9_7f4a_7c15_f39c_c060_5ced_c835;

/// Whether an operation since the last [`begin_item`] had more than one distinct allowed
/// result. Where none had, every mode computes the same result for the item (each
/// operation's choice is forced), so a caller that has one mode's result has them all.
pub fn item_chose() -> bool {
    CHOSE.with(Cell::get)
}

/// The mode, when `class` is an active class.
#[inline(always)]
fn active(class: Class) -> Option<Mode> {
    ACTIVE.with(|a| {
        a.get()
            .filter(|d| d.classes.contains(class))
            .map(|d| d.mode)
    })
}

/// Marks the start of an operation: the next site of [`Mode::Site`].
#[inline(always)]
fn site() {
    SITE.with(|s| s.set((s.get().0 + 1, 0)));
}

/// A hash of `seed` and the current site and pick ([`Mode::Site`]), advancing the pick.
fn site_hash(seed: u64) -> u64 {
    let (op, k) = SITE.with(|s| {
        let v = s.get();
        s.set((v.0, v.1 + 1));
        v
    });
    // SplitMix64's finalizer over the three words: every bit of each moves the result.
    let mut z =
        seed ^ op.wrapping_mul(0x9e37_79b9_7f4a_7c15) ^ k.wrapping_mul(0xc2b2_ae3d_27d4_eb4f);
    z = (z ^ z >> 30).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ z >> 27).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ z >> 31
}

/// This thread's deviation: read once per operation by the arithmetic that every class
/// may touch (the adversarial runs spend most of their time there).
#[inline(always)]
fn deviation() -> Option<Deviation> {
    ACTIVE.with(Cell::get)
}

/// Index of the chosen one of `n` allowed results, `cmp` ordering them.
fn pick(mode: Mode, n: usize, cmp: impl Fn(usize, usize) -> Ordering) -> usize {
    // A site's picks advance whatever their number of results, so that the next pick of
    // the operation is the same pick on every item.
    let site = match mode {
        Mode::Site(seed) => site_hash(seed),
        _ => 0,
    };
    if n == 1 {
        return 0;
    }
    if (1..n).any(|i| cmp(i, 0).is_ne()) {
        CHOSE.with(|c| c.set(true));
    }
    match mode {
        Mode::Seeded(_) => RNG.with(|r| (r.borrow_mut().next_u64() % n as u64) as usize),
        Mode::Site(_) => (site % n as u64) as usize,
        Mode::Lowest => (1..n).fold(0, |m, i| if cmp(i, m).is_lt() { i } else { m }),
        Mode::Highest => (1..n).fold(0, |m, i| if cmp(i, m).is_gt() { i } else { m }),
        Mode::Last => n - 1,
    }
}

/// Picks one of the allowed f32 results.
fn pick_f32(mode: Mode, c: &[f32]) -> f32 {
    c[pick(mode, c.len(), |i, j| c[i].total_cmp(&c[j]))]
}

/// A denormal becomes a zero of its sign.
fn flush(x: f32) -> f32 {
    if x.is_subnormal() {
        0f32.copysign(x)
    } else {
        x
    }
}

/// `op` with each of: the operands as given or flushed, the result as computed or flushed.
fn flushing<const N: usize>(mode: Mode, a: [f32; N], op: impl Fn([f32; N]) -> f32) -> f32 {
    let mut c = [0f32; 4];
    let mut n = 0;
    let ins: &[[f32; N]] = &[a, a.map(flush)];
    for &i in &ins[..if a.iter().any(|x| x.is_subnormal()) {
        2
    } else {
        1
    }] {
        let r = op(i);
        c[n] = r;
        n += 1;
        if r.is_subnormal() {
            c[n] = flush(r);
            n += 1;
        }
    }
    pick_f32(mode, &c[..n])
}

/// The floats within `bound` ULP of `exact` (of which `r` is the correctly rounded value).
/// The ULP is the gap between the two floats around `exact`, as in Vulkan's definition.
/// Zero, infinite and NaN results are kept as they are, and no result changes sign: a
/// tiny quotient could reach the other sign within the bound, but every division and
/// root algorithm computes the sign apart from the magnitude.
fn within_ulp(mode: Mode, r: f32, exact: f64, bound: f64) -> f32 {
    let (c, n) = within_ulp_all(r, exact, bound);
    pick_f32(mode, &c[..n])
}

/// The candidates of [`within_ulp`]: `r` first, then the others, and their number.
fn within_ulp_all(r: f32, exact: f64, bound: f64) -> ([f32; 16], usize) {
    let mut c = [0f32; 16];
    if r == 0.0 || !r.is_finite() {
        c[0] = r;
        return (c, 1);
    }
    let a = r.abs();
    let ulp = if f64::from(a) <= exact.abs() {
        f64::from(a.next_up()) - f64::from(a)
    } else {
        f64::from(a) - f64::from(a.next_down())
    };
    let steps = bound.ceil() as usize + 1;
    let mut n = 0;
    let mut push = |x: f32| {
        if (f64::from(x) - exact).abs() <= bound * ulp
            && x.is_sign_negative() == r.is_sign_negative()
        {
            c[n] = x;
            n += 1;
        }
    };
    let (mut lo, mut hi) = (r, r);
    push(r);
    for _ in 0..steps {
        lo = lo.next_down();
        hi = hi.next_up();
        push(lo);
        push(hi);
    }
    (c, n)
}

/// A sign-of-zero choice for a result that may lose it.
fn any_zero(mode: Mode, r: f32) -> f32 {
    if r == 0.0 {
        pick_f32(mode, &[r, -r])
    } else {
        r
    }
}

/// What a value remembers beyond its f32 bits, per class.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Ext {
    None,
    /// `fma`: the value is `round(a*b)` and a following add may use the exact product.
    Product(f32, f32),
    /// `excess`: the unrounded value; the f32 bits are its rounding.
    Wide(f64),
    /// `reassoc`: the value is `a + b`, which a following add may regroup.
    Sum(f32, f32),
}

/// A float under the active [`Deviation`]. Its f32 value ([`Dev::value`]) is what a
/// comparison, a conversion or a store sees.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dev {
    x: f32,
    ext: Ext,
}

/// A `u32` whose float conversions produce [`Dev`]. Integer arithmetic is exact
/// everywhere, so it never deviates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DevU(pub u32);

/// The mask type of [`Dev`] comparisons.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DevB(pub bool);

impl Dev {
    pub fn new(x: f32) -> Dev {
        Dev { x, ext: Ext::None }
    }
    /// The value as stored: the f32 bits (a kept-wide value rounded, a remembered product
    /// as its rounding).
    pub fn value(self) -> f32 {
        self.x
    }
    fn wide(self) -> f64 {
        match self.ext {
            Ext::Wide(w) => w,
            _ => f64::from(self.x),
        }
    }
    /// An excess-precision result: kept wide, or rounded early.
    fn excess(mode: Mode, w: f64) -> Dev {
        let narrow = w as f32;
        let c = [f64::from(narrow), w];
        let i = pick(mode, if c[0] == w { 1 } else { 2 }, |i, j| {
            c[i].total_cmp(&c[j])
        });
        Dev {
            x: narrow,
            ext: if i == 1 { Ext::Wide(w) } else { Ext::None },
        }
    }
    /// `+ - * /` and `sqrt` on `N` operands: `op` in f32, `wide` in f64, `exact` the f64
    /// value a `div`/`sqrt` deviation is measured against.
    #[inline(always)]
    fn arith<const N: usize>(
        a: [Dev; N],
        op: impl Fn([f32; N]) -> f32,
        wide: impl Fn([f64; N]) -> f64,
    ) -> Dev {
        Dev::arith_under(deviation(), a, op, wide)
    }

    /// [`Dev::arith`] under `dev`, the deviation the caller has read.
    #[inline(always)]
    fn arith_under<const N: usize>(
        dev: Option<Deviation>,
        a: [Dev; N],
        op: impl Fn([f32; N]) -> f32,
        wide: impl Fn([f64; N]) -> f64,
    ) -> Dev {
        let Some(Deviation { classes, mode }) = dev else {
            return Dev::new(op(a.map(|d| d.x)));
        };
        if classes.contains(Class::Excess) {
            Dev::excess(mode, wide(a.map(Dev::wide)))
        } else if classes.contains(Class::Denorm) {
            Dev::new(flushing(mode, a.map(|d| d.x), op))
        } else {
            Dev::new(op(a.map(|d| d.x)))
        }
    }
}

crate::model::num::value_eval!(Dev, DevU, DevB);

impl Lane for Dev {
    const KIND: Kind = Kind::F32;
}
impl Lane for DevU {
    const KIND: Kind = Kind::U32;
}
impl Lane for DevB {
    const KIND: Kind = Kind::Bool;
}

impl Bool for DevB {
    fn and(self, o: Self) -> Self {
        DevB(self.0 & o.0)
    }
    fn or(self, o: Self) -> Self {
        DevB(self.0 | o.0)
    }
    fn not(self) -> Self {
        DevB(!self.0)
    }
}

impl Add for DevU {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        DevU(self.0.wrapping_add(o.0))
    }
}
impl Sub for DevU {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        DevU(self.0.wrapping_sub(o.0))
    }
}
impl BitAnd for DevU {
    type Output = Self;
    fn bitand(self, o: Self) -> Self {
        DevU(self.0 & o.0)
    }
}
impl BitOr for DevU {
    type Output = Self;
    fn bitor(self, o: Self) -> Self {
        DevU(self.0 | o.0)
    }
}

impl Uint for DevU {
    type F = Dev;
    type B = DevB;
    fn c(v: u32) -> Self {
        DevU(v)
    }
    fn shl(self, n: u32) -> Self {
        DevU(self.0 << n)
    }
    fn shr(self, n: u32) -> Self {
        DevU(self.0 >> n)
    }
    fn to_f(self) -> Dev {
        Dev::new(self.0 as f32)
    }
    fn as_float(self) -> Dev {
        Dev::new(f32::from_bits(self.0))
    }
    fn sel(m: DevB, t: Self, f: Self) -> Self {
        if m.0 { t } else { f }
    }
    fn wrapping_add(self, o: Self) -> Self {
        self + o
    }
    fn wrapping_sub(self, o: Self) -> Self {
        self - o
    }
    fn wrapping_mul(self, o: Self) -> Self {
        DevU(self.0.wrapping_mul(o.0))
    }
    fn lt(self, o: Self) -> DevB {
        DevB(self.0 < o.0)
    }
}

/// Under `round`: the other neighbour of `exact` beside `r` (an f32 result whose exact value
/// is `exact`), if `r` is inexact.
fn other_neighbour(r: f32, exact: f64) -> Option<f32> {
    match f64::from(r).partial_cmp(&exact) {
        Some(Ordering::Less) => Some(r.next_up()),
        Some(Ordering::Greater) => Some(r.next_down()),
        _ => None,
    }
}

/// Up to 12 allowed results of one operation.
struct Results {
    c: [f32; 12],
    n: usize,
}

impl Results {
    fn new(r: f32) -> Results {
        let mut c = [0f32; 12];
        c[0] = r;
        Results { c, n: 1 }
    }
    fn push(&mut self, x: f32) {
        self.c[self.n] = x;
        self.n += 1;
    }
    fn pick(&self, mode: Mode) -> f32 {
        pick_f32(mode, &self.c[..self.n])
    }
}

/// `a + b` under the active classes that touch a sum: `round` (either neighbour of the
/// exact sum), `fma` (a remembered product operand fused with the other operand) and
/// `reassoc` (a remembered sum operand regrouped with the other operand, two remembered
/// products with a common factor factored); the result remembers its operands under
/// `reassoc` and `contract` (which may distribute a product over it).
fn sum(d: Deviation, a: Dev, b: Dev) -> Dev {
    let cs = d.classes;
    let mut r = Results::new(a.x + b.x);
    if cs.contains(Class::Round) {
        let exact = f64::from(a.x) + f64::from(b.x);
        if let Some(o) = other_neighbour(a.x + b.x, exact) {
            r.push(o);
        }
    }
    for (p, q) in [(a, b), (b, a)] {
        match p.ext {
            Ext::Product(f, g) if cs.contains(Class::Fma) => r.push(f.mul_add(g, q.x)),
            Ext::Sum(u, v) if cs.contains(Class::Reassoc) => {
                r.push(u + (v + q.x));
                r.push((u + q.x) + v);
            }
            _ => {}
        }
    }
    if let (true, Ext::Product(p, q), Ext::Product(u, t)) =
        (cs.contains(Class::Reassoc), a.ext, b.ext)
    {
        for (f, g, h, k) in [(p, q, u, t), (p, q, t, u), (q, p, u, t), (q, p, t, u)] {
            if f.to_bits() == h.to_bits() {
                r.push(f * (g + k));
            }
        }
    }
    Dev {
        x: r.pick(d.mode),
        ext: if cs.contains(Class::Reassoc) || cs.contains(Class::Contract) {
            Ext::Sum(a.x, b.x)
        } else {
            Ext::None
        },
    }
}

impl Add for Dev {
    type Output = Dev;
    fn add(self, o: Dev) -> Dev {
        site();
        let dev = deviation();
        match dev {
            Some(d)
                if [Class::Reassoc, Class::Round, Class::Fma, Class::Contract]
                    .iter()
                    .any(|&c| d.classes.contains(c)) =>
            {
                sum(d, self, o)
            }
            _ => Dev::arith_under(dev, [self, o], |[a, b]| a + b, |[a, b]| a + b),
        }
    }
}

/// `a - b` is `a + (-b)` in IEEE arithmetic, zeros included; negation keeps a remembered
/// product, so `c - a*b` may fuse as `fma(-a, b, c)`.
impl Sub for Dev {
    type Output = Dev;
    fn sub(self, o: Dev) -> Dev {
        self + -o
    }
}

impl Mul for Dev {
    type Output = Dev;
    fn mul(self, o: Dev) -> Dev {
        site();
        let dev = deviation();
        let Some(d) = dev else {
            return Dev::new(self.x * o.x);
        };
        let cs = d.classes;
        let base = if cs.contains(Class::Round) || cs.contains(Class::Contract) {
            let mut r = Results::new(self.x * o.x);
            if cs.contains(Class::Round) {
                let exact = f64::from(self.x) * f64::from(o.x);
                if let Some(other) = other_neighbour(self.x * o.x, exact) {
                    r.push(other);
                }
            }
            if cs.contains(Class::Contract) {
                for (p, q) in [(self, o), (o, self)] {
                    match p.ext {
                        // `(u + v)·q` distributed, each product rounded or one fused.
                        Ext::Sum(u, v) => {
                            r.push(u * q.x + v * q.x);
                            r.push(u.mul_add(q.x, v * q.x));
                            r.push(v.mul_add(q.x, u * q.x));
                        }
                        // `(f·g)·q` regrouped.
                        Ext::Product(f, g) => {
                            r.push(f * (g * q.x));
                            r.push(g * (f * q.x));
                        }
                        _ => {}
                    }
                }
            }
            Dev::new(r.pick(d.mode))
        } else {
            Dev::arith_under(dev, [self, o], |[a, b]| a * b, |[a, b]| a * b)
        };
        // A product that a following add may fuse or factor remembers its factors (not
        // under `excess`, whose wide value is the product unrounded already).
        let remembered = [Class::Fma, Class::Reassoc, Class::Contract]
            .iter()
            .any(|&c| cs.contains(c));
        if remembered && !d.classes.contains(Class::Excess) {
            Dev {
                x: base.x,
                ext: Ext::Product(self.x, o.x),
            }
        } else {
            base
        }
    }
}

impl Div for Dev {
    type Output = Dev;
    /// Under `div`, a quotient within [`DIV_ULP`]; under `div` and `contract` together also
    /// `a · (1/b)`, the reciprocal multiply a driver divides with, remembered as a product
    /// that a following add or comparison may take whole.
    fn div(self, o: Dev) -> Dev {
        site();
        if let Some(mode) = active(Class::Div) {
            let exact = f64::from(self.x) / f64::from(o.x);
            let (mut c, mut n) = within_ulp_all(self.x / o.x, exact, DIV_ULP);
            let recip = 1.0 / o.x;
            let reciprocal = active(Class::Contract).is_some() && recip.is_finite() && recip != 0.0;
            if reciprocal {
                c[n] = self.x * recip;
                n += 1;
            }
            let i = pick(mode, n, |i, j| c[i].total_cmp(&c[j]));
            return Dev {
                x: c[i],
                ext: if reciprocal && i == n - 1 {
                    Ext::Product(self.x, recip)
                } else {
                    Ext::None
                },
            };
        }
        Dev::arith([self, o], |[a, b]| a / b, |[a, b]| a / b)
    }
}

/// Negation is exact and moves no data through arithmetic: it keeps what the value
/// remembers and is never flushed.
impl Neg for Dev {
    type Output = Dev;
    fn neg(self) -> Dev {
        Dev {
            x: -self.x,
            ext: match self.ext {
                Ext::None => Ext::None,
                Ext::Product(a, b) => Ext::Product(-a, b),
                Ext::Wide(w) => Ext::Wide(-w),
                Ext::Sum(a, b) => Ext::Sum(-a, -b),
            },
        }
    }
}

impl Dev {
    /// `floor` and `round`: on the rounded value, flushable, and losing the sign of a zero.
    fn integral(self, op: fn(f32) -> f32) -> Dev {
        site();
        let r = match active(Class::Denorm) {
            Some(mode) => flushing(mode, [self.x], |[a]| op(a)),
            None => op(self.x),
        };
        match active(Class::Zero) {
            Some(mode) => Dev::new(any_zero(mode, r)),
            None => Dev::new(r),
        }
    }
    /// Comparisons see the rounded values; under `denorm` their operands may be flushed;
    /// under `contract` a remembered product may be compared unrounded, as `a*b < c`
    /// rewritten to `fma(a, b, -c) < 0`: SPIR-V's `NoContraction` forbids combining a
    /// multiply with any other instruction, so without it (WGSL, GLSL without `precise`)
    /// a comparison may take the product whole. C compilers contract only `a*b + c`, so
    /// this is no `fma` liberty.
    fn compare(self, o: Dev, op: fn(f64, f64) -> bool) -> DevB {
        site();
        let (a, b) = (f64::from(self.x), f64::from(o.x));
        let mut c = [op(a, b), false, false, false];
        let mut n = 1;
        let dev = deviation();
        if let Some(Deviation { classes, mode }) = dev {
            if classes.contains(Class::Denorm) && (self.x.is_subnormal() || o.x.is_subnormal()) {
                c[n] = op(f64::from(flush(self.x)), f64::from(flush(o.x)));
                n += 1;
            }
            if classes.contains(Class::Contract) {
                let whole = |d: Dev| match d.ext {
                    Ext::Product(f, g) => Some(f64::from(f) * f64::from(g)),
                    _ => None,
                };
                if let Some(p) = whole(self) {
                    c[n] = op(p, b);
                    n += 1;
                }
                if let Some(p) = whole(o) {
                    c[n] = op(a, p);
                    n += 1;
                }
            }
            return DevB(c[pick(mode, n, |i, j| c[i].cmp(&c[j]))]);
        }
        DevB(c[0])
    }
}

impl Float for Dev {
    type U = DevU;
    type B = DevB;
    fn c(v: f32) -> Self {
        Dev::new(v)
    }
    /// Exact, so kept wide under `excess`; a zero result may lose its sign under `zero`.
    fn abs(self) -> Self {
        site();
        match self.ext {
            Ext::Wide(w) => Dev {
                x: self.x.abs(),
                ext: Ext::Wide(w.abs()),
            },
            _ => match active(Class::Zero) {
                Some(mode) => Dev::new(any_zero(mode, self.x.abs())),
                None => Dev::new(self.x.abs()),
            },
        }
    }
    fn sqrt(self) -> Self {
        site();
        if let Some(mode) = active(Class::Sqrt) {
            let exact = f64::from(self.x).sqrt();
            return Dev::new(within_ulp(mode, self.x.sqrt(), exact, SQRT_ULP));
        }
        Dev::arith([self], |[a]| a.sqrt(), |[a]| a.sqrt())
    }
    fn floor(self) -> Self {
        self.integral(f32::floor)
    }
    fn round(self) -> Self {
        self.integral(f32::round_ties_even)
    }
    fn lt(self, o: Self) -> DevB {
        self.compare(o, |a, b| a < b)
    }
    fn le(self, o: Self) -> DevB {
        self.compare(o, |a, b| a <= b)
    }
    fn gt(self, o: Self) -> DevB {
        self.compare(o, |a, b| a > b)
    }
    fn ge(self, o: Self) -> DevB {
        self.compare(o, |a, b| a >= b)
    }
    fn eq(self, o: Self) -> DevB {
        self.compare(o, |a, b| a == b)
    }
    /// The chosen value rounded (a select is where excess precision ends and where a
    /// product can no longer fuse); a zero may lose its sign under `zero`.
    fn sel(m: DevB, t: Self, f: Self) -> Self {
        site();
        let r = if m.0 { t.x } else { f.x };
        match active(Class::Zero) {
            Some(mode) => Dev::new(any_zero(mode, r)),
            None => Dev::new(r),
        }
    }
    fn to_u(self) -> DevU {
        DevU(self.x as u32)
    }
    /// The stored bits: a bitcast is no arithmetic, so nothing deviates.
    fn to_bits(self) -> DevU {
        DevU(self.x.to_bits())
    }
}
