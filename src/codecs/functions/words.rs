//! Values crossing the verification boundary as raw 32-bit words, and the constructor
//! that turns one generic function into a [`Function`] with all its evaluations: `f32`,
//! the adversarial `Dev`, and four or eight SIMD lanes, moving items between memory and
//! lanes a whole group at a time.

use crate::codecs::functions::function::{Function, Inputs, Role, Stages};
use crate::model::avx2_lanes::{self, F8, WIDTH};
use crate::model::deviant::{Dev, DevU};
use crate::model::lanes::{F4, LaneIo, U4};
use crate::model::trace::{Module, trace_module};
use crate::model::{V2, V3, V4};
use std::sync::Arc;

/// Values that cross the verification boundary as raw 32-bit words (`W = u32`), or as
/// [`Lanes`] of four items' words at a time.
pub trait Bits<W = u32>: Sized {
    const WORDS: usize;
    fn read(w: &[W]) -> Self;
    fn write(self, w: &mut [W]);
}

/// One word of four items, for the [`F4`] evaluation.
pub type Lanes = [u32; 4];
/// One word of eight items, for the [`F8`] evaluation where the processor has AVX2 (of
/// four, never run, off x86-64).
pub type Lanes8 = [u32; WIDTH];

/// Float and integer lanes read and written through [`LaneIo`].
macro_rules! lane_bits {
    ($F:ty, $U:ty, $n:literal) => {
        impl Bits<[u32; $n]> for $F {
            const WORDS: usize = 1;
            #[inline(always)]
            fn read(w: &[[u32; $n]]) -> Self {
                <$F>::from_words(w[0])
            }
            #[inline(always)]
            fn write(self, w: &mut [[u32; $n]]) {
                w[0] = self.words();
            }
        }
        impl Bits<[u32; $n]> for $U {
            const WORDS: usize = 1;
            #[inline(always)]
            fn read(w: &[[u32; $n]]) -> Self {
                <$F>::u_from_words(w[0])
            }
            #[inline(always)]
            fn write(self, w: &mut [[u32; $n]]) {
                w[0] = <$F>::u_words(self);
            }
        }
    };
}
lane_bits!(F4, U4, 4);
#[cfg(target_arch = "x86_64")]
lane_bits!(F8, crate::model::avx2_lanes::U8, 8);
impl Bits for f32 {
    const WORDS: usize = 1;
    #[inline(always)]
    fn read(w: &[u32]) -> Self {
        f32::from_bits(w[0])
    }
    fn write(self, w: &mut [u32]) {
        w[0] = self.to_bits();
    }
}
impl Bits for u32 {
    const WORDS: usize = 1;
    #[inline(always)]
    fn read(w: &[u32]) -> Self {
        w[0]
    }
    fn write(self, w: &mut [u32]) {
        w[0] = self;
    }
}
impl Bits for Dev {
    const WORDS: usize = 1;
    #[inline(always)]
    fn read(w: &[u32]) -> Self {
        Dev::new(f32::from_bits(w[0]))
    }
    fn write(self, w: &mut [u32]) {
        w[0] = self.value().to_bits();
    }
}
impl Bits for DevU {
    const WORDS: usize = 1;
    #[inline(always)]
    fn read(w: &[u32]) -> Self {
        DevU(w[0])
    }
    fn write(self, w: &mut [u32]) {
        w[0] = self.0;
    }
}
impl<W, T: Bits<W> + crate::model::Lane> Bits<W> for V2<T> {
    const WORDS: usize = 2;
    #[inline(always)]
    fn read(w: &[W]) -> Self {
        V2::new(T::read(&w[0..]), T::read(&w[1..]))
    }
    #[inline(always)]
    fn write(self, w: &mut [W]) {
        self.x.write(&mut w[0..]);
        self.y.write(&mut w[1..]);
    }
}
/// Several arguments, one after the other.
impl<W, A: Bits<W>, B: Bits<W>> Bits<W> for (A, B) {
    const WORDS: usize = A::WORDS + B::WORDS;
    #[inline(always)]
    fn read(w: &[W]) -> Self {
        (A::read(w), B::read(&w[A::WORDS..]))
    }
    #[inline(always)]
    fn write(self, w: &mut [W]) {
        self.0.write(w);
        self.1.write(&mut w[A::WORDS..]);
    }
}
/// Three results, one after the other (a TBN decoder's columns).
impl<W, A: Bits<W>, B: Bits<W>, C: Bits<W>> Bits<W> for (A, B, C) {
    const WORDS: usize = A::WORDS + B::WORDS + C::WORDS;
    #[inline(always)]
    fn read(w: &[W]) -> Self {
        let (a, b) = <(A, B)>::read(w);
        (a, b, C::read(&w[A::WORDS + B::WORDS..]))
    }
    #[inline(always)]
    fn write(self, w: &mut [W]) {
        (self.0, self.1).write(w);
        self.2.write(&mut w[A::WORDS + B::WORDS..]);
    }
}
impl<W, T: Bits<W> + crate::model::Lane> Bits<W> for V3<T> {
    const WORDS: usize = 3;
    #[inline(always)]
    fn read(w: &[W]) -> Self {
        V3::new(T::read(&w[0..]), T::read(&w[1..]), T::read(&w[2..]))
    }
    #[inline(always)]
    fn write(self, w: &mut [W]) {
        self.x.write(&mut w[0..]);
        self.y.write(&mut w[1..]);
        self.z.write(&mut w[2..]);
    }
}
impl<W, T: Bits<W> + crate::model::Lane> Bits<W> for V4<T> {
    const WORDS: usize = 4;
    #[inline(always)]
    fn read(w: &[W]) -> Self {
        V4::new(
            T::read(&w[0..]),
            T::read(&w[1..]),
            T::read(&w[2..]),
            T::read(&w[3..]),
        )
    }
    #[inline(always)]
    fn write(self, w: &mut [W]) {
        self.x.write(&mut w[0..]);
        self.y.write(&mut w[1..]);
        self.z.write(&mut w[2..]);
        self.w.write(&mut w[3..]);
    }
}

/// The widest item a lane evaluation takes or returns, in words (a precise search's
/// vector and fetched texels).
const MAX_WORDS: usize = 32;

/// `f` on every item of `input` into `output`, `N` items per group: each group's words
/// transposed into lanes on the stack, evaluated, and transposed back. A last partial
/// group is padded with its last item and only its real items are written. Inlined into
/// the function compiled for the lanes, so the transposes are too; `f` has one call site,
/// so its body (inlined, hundreds of lane operations) is compiled once, not once more for
/// the partial group.
#[inline(always)]
fn in_groups<L: LaneIo<N>, A: Bits<[u32; N]>, R: Bits<[u32; N]>, const N: usize>(
    f: &impl Fn(A) -> R,
    input: &[u32],
    output: &mut [u32],
) {
    let (iw, ow) = (A::WORDS, R::WORDS);
    assert!(
        iw <= MAX_WORDS && ow <= MAX_WORDS,
        "items of at most {MAX_WORDS} words"
    );
    let mut lanes_in = [[0u32; N]; MAX_WORDS];
    let mut lanes_out = [[0u32; N]; MAX_WORDS];
    let (lanes_in, lanes_out) = (&mut lanes_in[..iw], &mut lanes_out[..ow]);
    let items = input.len() / iw;
    let whole = items / N;
    let (mut pad_in, mut pad_out) = ([[0u32; MAX_WORDS]; N], [[0u32; MAX_WORDS]; N]);
    let (pad_in, pad_out) = (pad_in.as_flattened_mut(), pad_out.as_flattened_mut());
    let groups = items.div_ceil(N);
    // The last partial group is padded before the loop, so that the loop's only branches
    // choose where a group's words come from and go to: with the padding inside it, LLVM
    // computed the padded items' indices for every group (about a fifth of a frame
    // decoder's instructions).
    if whole < groups {
        let rest = &input[whole * N * iw..items * iw];
        for (k, item) in pad_in[..N * iw].chunks_exact_mut(iw).enumerate() {
            let from = k.min(rest.len() / iw - 1) * iw;
            item.copy_from_slice(&rest[from..][..iw]);
        }
    }
    for g in 0..groups {
        let s = if g < whole {
            &input[g * N * iw..][..N * iw]
        } else {
            &pad_in[..N * iw]
        };
        to_lanes::<L, N>(s, lanes_in);
        f(A::read(lanes_in)).write(lanes_out);
        let d = if g < whole {
            &mut output[g * N * ow..][..N * ow]
        } else {
            &mut pad_out[..N * ow]
        };
        from_lanes::<L, N>(lanes_out, d);
    }
    if whole < groups {
        let d = &mut output[whole * N * ow..items * ow];
        d.copy_from_slice(&pad_out[..d.len()]);
    }
}

/// One whole group of `N` items (`s`, `N·lanes.len()` words) into lanes. Items of two
/// words (64-bit codes) and three (vectors) take the lanes' own transposes
/// ([`LaneIo::u_from_items2`], [`LaneIo::u_from_items3`]), other items of 1 to 4 words
/// (codes) and of 7 (tangent frames) go through fixed-size arrays ([`to_lanes_of`]).
#[inline(always)]
fn to_lanes<L: LaneIo<N>, const N: usize>(s: &[u32], lanes: &mut [[u32; N]]) {
    match lanes.len() {
        1 => to_lanes_of::<1, N>(s, lanes),
        2 => {
            let items = s.as_chunks::<2>().0.try_into().expect("a whole group");
            for (lane, u) in lanes.iter_mut().zip(L::u_from_items2(items)) {
                *lane = L::u_words(u);
            }
        }
        3 => {
            let items = s.as_chunks::<3>().0.try_into().expect("a whole group");
            for (lane, u) in lanes.iter_mut().zip(L::u_from_items3(items)) {
                *lane = L::u_words(u);
            }
        }
        4 => to_lanes_of::<4, N>(s, lanes),
        7 => to_lanes_of::<7, N>(s, lanes),
        w => {
            for (j, lane) in lanes.iter_mut().enumerate() {
                for (k, l) in lane.iter_mut().enumerate() {
                    *l = s[k * w + j];
                }
            }
        }
    }
}

/// [`to_lanes`] for items of `W` words. A group as a fixed-size array of fixed-size items
/// is what LLVM moves with whole-register loads and shuffles; indexed through slices, the
/// eight-lane decoders' three outputs went out as six 128-bit stores and 15 % slower.
#[inline(always)]
fn to_lanes_of<const W: usize, const N: usize>(s: &[u32], lanes: &mut [[u32; N]]) {
    let items: &[[u32; W]; N] = s.as_chunks::<W>().0.try_into().expect("a whole group");
    let lanes: &mut [[u32; N]; W] = lanes.try_into().expect("W lanes");
    for k in 0..N {
        for j in 0..W {
            lanes[j][k] = items[k][j];
        }
    }
}

/// Lanes into one whole group of `N` items (`d`, `N·lanes.len()` words), as [`to_lanes`]
/// ([`LaneIo::u_to_items3`] for three words).
#[inline(always)]
fn from_lanes<L: LaneIo<N>, const N: usize>(lanes: &[[u32; N]], d: &mut [u32]) {
    match lanes.len() {
        1 => from_lanes_of::<1, N>(lanes, d),
        2 => from_lanes_of::<2, N>(lanes, d),
        3 => {
            let items = d.as_chunks_mut::<3>().0.try_into().expect("a whole group");
            let u = {
                #[inline(always)]
                |j: usize| L::u_from_words(lanes[j])
            };
            L::u_to_items3([u(0), u(1), u(2)], items);
        }
        4 => from_lanes_of::<4, N>(lanes, d),
        7 => {
            let items = d.as_chunks_mut::<7>().0.try_into().expect("a whole group");
            let u = {
                #[inline(always)]
                |j: usize| L::u_from_words(lanes[j])
            };
            L::u_to_items7([u(0), u(1), u(2), u(3), u(4), u(5), u(6)], items);
        }
        w => {
            for (k, item) in d.chunks_exact_mut(w).enumerate() {
                for (o, lane) in item.iter_mut().zip(lanes) {
                    *o = lane[k];
                }
            }
        }
    }
}

/// [`from_lanes`] for items of `W` words, as [`to_lanes_of`].
#[inline(always)]
fn from_lanes_of<const W: usize, const N: usize>(lanes: &[[u32; N]], d: &mut [u32]) {
    let items: &mut [[u32; W]; N] = d.as_chunks_mut::<W>().0.try_into().expect("a whole group");
    let lanes: &[[u32; N]; W] = lanes.try_into().expect("W lanes");
    for k in 0..N {
        for j in 0..W {
            items[k][j] = lanes[j][k];
        }
    }
}

/// One inclusive range per field → an enclosure per output lane.
/// A [`Function`] from its `f32`, [`Dev`], [`F4`] and [`F8`] instantiations of one
/// generic function (`generic_function!` below writes all four from one body).
#[allow(clippy::too_many_arguments)]
pub(crate) fn function<A, R, AD, RD, AL, RL, AW, RW>(
    name: &'static str,
    role: Role,
    inputs: Inputs,
    f: impl Fn(A) -> R + Send + Sync + 'static,
    f_dev: impl Fn(AD) -> RD + Send + Sync + 'static,
    f_lanes: impl Fn(AL) -> RL + Send + Sync + 'static,
    f_lanes8: impl Fn(AW) -> RW + Send + Sync + 'static,
) -> Function
where
    A: Bits + 'static,
    R: Bits + 'static,
    AD: Bits + 'static,
    RD: Bits + 'static,
    AL: Bits<Lanes> + 'static,
    RL: Bits<Lanes> + 'static,
    AW: Bits<Lanes8> + 'static,
    RW: Bits<Lanes8> + 'static,
{
    assert_eq!((A::WORDS, R::WORDS), (AD::WORDS, RD::WORDS));
    assert_eq!((A::WORDS, R::WORDS), (AL::WORDS, RL::WORDS));
    assert_eq!((A::WORDS, R::WORDS), (AW::WORDS, RW::WORDS));
    Function {
        name,
        role,
        inputs,
        in_words: A::WORDS,
        out_words: R::WORDS,
        eval: per_item::eval(f),
        eval_dev: per_item::eval(f_dev),
        eval_lanes: four::eval(f_lanes),
        eval_lanes8: eight::eval(name, f_lanes8),
        enclose: None,
        parts: Vec::new(),
        stages: None,
    }
}

/// `then` applied to the outputs of `first`, as one function named `name`: each
/// evaluation runs `first`'s over its items and `then`'s over the results, which is bit
/// for bit the composed body (the intermediate values pass through words unchanged). A
/// function that is another's plus a cheap step (a frame decoder's TBN columns, a
/// layout's packing of shared fields) is then compiled once, not once more per caller:
/// each generic body is four instances (`f32`, [`Dev`], [`F4`], [`F8`]) of everything it
/// inlines. `eval_dev`'s callers pass one item per call, so its deviation sites follow
/// each other as in the composed body.
pub(crate) fn chained(
    name: &'static str,
    role: Role,
    inputs: Inputs,
    first: &Function,
    then: &Function,
) -> Function {
    assert_eq!(first.out_words, then.in_words, "{name}: the steps' words");
    let (iw, mw) = (first.in_words, first.out_words);
    let compose = |a: &crate::codecs::functions::function::Eval,
                   b: &crate::codecs::functions::function::Eval|
     -> crate::codecs::functions::function::Eval {
        let (a, b) = (a.clone(), b.clone());
        Arc::new(move |i: &[u32], o: &mut [u32]| {
            // One item per call (`eval_dev`'s callers, `portability`) stays on the stack.
            let words = i.len() / iw * mw;
            let (mut small, mut large) = ([0u32; 64], Vec::new());
            let mid = if words <= small.len() {
                &mut small[..words]
            } else {
                large.resize(words, 0);
                &mut large[..]
            };
            a(i, mid);
            b(mid, o);
        })
    };
    Function {
        name,
        role,
        inputs,
        in_words: iw,
        out_words: then.out_words,
        eval: compose(&first.eval, &then.eval),
        eval_dev: compose(&first.eval_dev, &then.eval_dev),
        eval_lanes: compose(&first.eval_lanes, &then.eval_lanes),
        eval_lanes8: compose(&first.eval_lanes8, &then.eval_lanes8),
        enclose: None,
        parts: Vec::new(),
        stages: Some(Stages {
            first: first.eval.clone(),
            mid_words: mw,
            then: then.eval.clone(),
        }),
    }
}

// The evaluations are built in modules of their own because rustc compiles a generic
// function's instances, and its closures', in the codegen unit of the module that defines
// it, and never splits a module's unit: built in `function` itself, every codec's
// evaluations made one unit that kept the library's build on a single core for most of
// its length. Apart, the units compile on every core.

/// The per-item evaluations, `f32` and [`Dev`].
mod per_item {
    use super::*;

    pub(super) fn eval<A: Bits + 'static, R: Bits + 'static>(
        f: impl Fn(A) -> R + Send + Sync + 'static,
    ) -> crate::codecs::functions::function::Eval {
        Arc::new(move |i, o| {
            for (i, o) in i.chunks_exact(A::WORDS).zip(o.chunks_exact_mut(R::WORDS)) {
                f(A::read(i)).write(o)
            }
        })
    }
}

/// The four-lane evaluation.
mod four {
    use super::*;

    pub(super) fn eval<A: Bits<Lanes> + 'static, R: Bits<Lanes> + 'static>(
        f: impl Fn(A) -> R + Send + Sync + 'static,
    ) -> crate::codecs::functions::function::LanesEval {
        Arc::new(move |i, o| in_groups::<F4, _, _, 4>(&f, i, o))
    }
}

/// The eight-lane evaluation, compiled for AVX2.
mod eight {
    use super::*;

    pub(super) fn eval<A: Bits<Lanes8> + 'static, R: Bits<Lanes8> + 'static>(
        name: &'static str,
        f: impl Fn(A) -> R + Send + Sync + 'static,
    ) -> crate::codecs::functions::function::LanesEval {
        Arc::new(move |i, o| {
            assert!(
                avx2_lanes::available(),
                "{name}: the eight-lane evaluation needs a processor with AVX2"
            );
            // SAFETY: the processor has AVX2 (checked just above).
            unsafe { on_avx2(&f, i, o) }
        })
    }

    /// [`in_groups`] of `f` on eight lanes, compiled for AVX2: `f` and everything it calls
    /// inline here (the lane operations are `#[inline(always)]`), so the [`F8`] operations
    /// become AVX2 instructions rather than calls.
    ///
    /// # Safety
    /// The processor must have AVX2.
    #[cfg_attr(target_arch = "x86_64", target_feature(enable = "avx2"))]
    unsafe fn on_avx2<A: Bits<Lanes8>, R: Bits<Lanes8>>(
        f: &impl Fn(A) -> R,
        i: &[u32],
        o: &mut [u32],
    ) {
        in_groups::<F8, _, _, WIDTH>(f, i, o)
    }
}

/// `generic_function!(name, role, inputs, <F> [captures] |x: Type<F>| body)`: a [`Function`]
/// whose `eval`, `eval_dev`, `eval_lanes` and `eval_lanes8` are the one generic `body`
/// with `F` = `f32`, [`Dev`], [`F4`] and [`F8`], so neither the adversarial nor the
/// lane evaluations can drift from the reference. Each capture is cloned into all four
/// closures.
macro_rules! generic_function {
    ($name:expr, $role:expr, $inputs:expr, <$F:ident> [$($c:ident),*] |$x:ident: $A:ty| $body:expr) => {
        $crate::codecs::functions::words::function(
            $name,
            $role,
            $inputs,
            {
                $(let $c = $c.clone();)*
                type $F = f32;
                move |$x: $A| $body
            },
            {
                $(let $c = $c.clone();)*
                type $F = $crate::model::deviant::Dev;
                move |$x: $A| $body
            },
            {
                $(let $c = $c.clone();)*
                type $F = $crate::model::lanes::F4;
                move |$x: $A| $body
            },
            {
                $(let $c = $c.clone();)*
                type $F = $crate::model::avx2_lanes::F8;
                #[inline(always)]
                move |$x: $A| $body
            },
        )
    };
}
pub(crate) use generic_function;

/// How a [`Declared`] function defines itself in the module being traced, under the
/// name given: [`crate::model::trace::define`] (or `define_fields`) of the same generic
/// body with `F` = [`crate::model::trace::Tf`].
pub(crate) type Tracer = Box<dyn Fn(&'static str)>;

/// One emitted function, declared once: its evaluations ([`Function`]) and its tracing
/// ([`Tracer`]) come from the same entry ([`declared!`]), so that the include and the
/// model cannot name, order or type a function differently.
pub(crate) struct Declared {
    name: &'static str,
    /// `None` for a function defined in the include but verified only through those that
    /// chain it ([`Declared::unlisted`]).
    function: Option<Function>,
    trace: Tracer,
}

impl Declared {
    /// `function`, traced by `trace` under its name: for a function whose evaluation is
    /// composed ([`chained`]) while its traced body calls the steps as the include does.
    pub(crate) fn new(function: Function, trace: Tracer) -> Declared {
        Declared {
            name: function.name,
            function: Some(function),
            trace,
        }
    }

    /// The function's evaluations, to chain them (through a table).
    pub(crate) fn function(&self) -> &Function {
        self.function
            .as_ref()
            .expect("a listed function (not `unlisted`)")
    }

    /// The function, to set what only it has (a decoder's enclosure).
    pub(crate) fn function_mut(&mut self) -> &mut Function {
        self.function
            .as_mut()
            .expect("a listed function (not `unlisted`)")
    }

    /// Splits off the evaluations of a function that the include defines but `verify`
    /// checks only through the functions chained from it (a precise spec's search): the
    /// [`Function`] to chain, and the declaration that still traces it.
    pub(crate) fn unlisted(self) -> (Function, Declared) {
        let function = self.function.expect("declared with its evaluations");
        let traced = Declared {
            name: self.name,
            function: None,
            trace: self.trace,
        };
        (function, traced)
    }
}

/// The module of `declared`, each traced in order (decoders first, so that an encoder
/// calling one finds it with its parameter names), and their functions as `verify`
/// lists them.
pub(crate) fn trace_declared(declared: Vec<Declared>) -> (Module, Vec<Function>) {
    let module = trace_module(|| {
        for d in &declared {
            (d.trace)(d.name);
        }
    });
    let functions = declared.into_iter().filter_map(|d| d.function).collect();
    (module, functions)
}

/// `tracer!(param_names, <F> [captures] |x: Type<F>| body)`: the [`Tracer`] of a
/// [`generic_function!`] body, which defines it with `F` = [`crate::model::trace::Tf`]
/// and the parameter names of the array `param_names`; `tracer!(names => SHAPE, …)`
/// defines a function returning the struct `SHAPE`.
macro_rules! tracer {
    ($params:expr $(=> $shape:expr)?, <$F:ident> [$($c:ident),*] |$x:ident: $A:ty| $body:expr) => {{
        $(let $c = $c.clone();)*
        Box::new(move |name: &'static str| {
            $(let $c = $c.clone();)*
            type $F = $crate::model::trace::Tf;
            $crate::codecs::functions::words::tracer!(@define name, $params $(=> $shape)?, move |$x: $A| $body)
        }) as $crate::codecs::functions::words::Tracer
    }};
    (@define $name:ident, $params:expr, $f:expr) => {
        $crate::model::trace::define($name, &$params, $f)
    };
    (@define $name:ident, $params:expr => $shape:expr, $f:expr) => {
        $crate::model::trace::define_fields($name, &$params, $shape, $f)
    };
}
pub(crate) use tracer;

/// `declared!(name, role, inputs, param_names (=> SHAPE)?, <F> [captures] |x: Type<F>|
/// body)`: one emitted function from one generic body, its evaluations
/// ([`generic_function!`]) and its tracing ([`tracer!`]) alike.
macro_rules! declared {
    ($name:expr, $role:expr, $inputs:expr, $params:expr $(=> $shape:expr)?, <$F:ident> [$($c:ident),*] |$x:ident: $A:ty| $body:expr) => {
        $crate::codecs::functions::words::Declared::new(
            $crate::codecs::functions::words::generic_function!($name, $role, $inputs, <$F> [$($c),*] |$x: $A| $body),
            $crate::codecs::functions::words::tracer!($params $(=> $shape)?, <$F> [$($c),*] |$x: $A| $body),
        )
    };
}
pub(crate) use declared;
