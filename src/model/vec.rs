//! Small vectors over any [`Lane`]. Every componentwise operation computes its lanes and
//! hands them to [`Lane::fuse`], which is free when evaluating and lets the tracer print
//! one vector statement (`let p = v.xy * r;`) instead of one statement per lane.

use super::num::{Float, Lane, Uint};
use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Sub};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct V2<T> {
    pub x: T,
    pub y: T,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct V3<T> {
    pub x: T,
    pub y: T,
    pub z: T,
}

/// Four lanes: an RGBA texel as a texture fetch delivers it (`x` = R … `w` = A).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct V4<T> {
    pub x: T,
    pub y: T,
    pub z: T,
    pub w: T,
}

macro_rules! vector {
    ($V:ident, $n:literal, $($f:ident : $i:literal),+) => {
        impl<T: Lane> $V<T> {
            #[inline(always)]
            pub fn new($($f: T),+) -> Self {
                Self { $($f),+ }
            }
            #[inline(always)]
            pub fn splat(v: T) -> Self {
                Self { $($f: v),+ }
            }
            #[inline(always)]
            pub fn to_array(self) -> [T; $n] {
                [$(self.$f),+]
            }
            #[inline(always)]
            pub fn from_array(a: [T; $n]) -> Self {
                Self { $($f: a[$i]),+ }
            }
            /// Applies `f` to every lane and records the result as one vector operation.
            #[inline(always)]
            pub fn map<R: Lane>(self, f: impl Fn(T) -> R) -> $V<R> {
                $V::from_array(R::fuse([$(f(self.$f)),+]))
            }
            /// Combines two vectors lane by lane as one vector operation.
            #[inline(always)]
            pub fn zip<O: Lane, R: Lane>(self, o: $V<O>, f: impl Fn(T, O) -> R) -> $V<R> {
                $V::from_array(R::fuse([$(f(self.$f, o.$f)),+]))
            }
            /// Names the vector in emitted code.
            #[inline(always)]
            pub fn named(self, name: &'static str) -> Self {
                Self::from_array(T::named_lanes(self.to_array(), name))
            }
        }

        impl<F: Float> $V<F> {
            #[inline(always)]
            pub fn abs(self) -> Self { self.map(#[inline(always)] |x| F::abs(x)) }
            #[inline(always)]
            pub fn floor(self) -> Self { self.map(#[inline(always)] |x| F::floor(x)) }
            #[inline(always)]
            pub fn round(self) -> Self { self.map(#[inline(always)] |x| F::round(x)) }
            #[inline(always)]
            pub fn lt(self, o: Self) -> $V<F::B> { self.zip(o, F::lt) }
            #[inline(always)]
            pub fn le(self, o: Self) -> $V<F::B> { self.zip(o, F::le) }
            #[inline(always)]
            pub fn gt(self, o: Self) -> $V<F::B> { self.zip(o, F::gt) }
            #[inline(always)]
            pub fn ge(self, o: Self) -> $V<F::B> { self.zip(o, F::ge) }
            /// Lane-wise select with a vector mask.
            #[inline(always)]
            pub fn sel(m: $V<F::B>, t: Self, f: Self) -> Self {
                $V::from_array(F::fuse([$(F::sel(m.$f, t.$f, f.$f)),+]))
            }
            /// Select of whole vectors with one scalar mask.
            #[inline(always)]
            pub fn sel_all(m: F::B, t: Self, f: Self) -> Self {
                $V::from_array(F::fuse([$(F::sel(m, t.$f, f.$f)),+]))
            }
            #[inline(always)]
            pub fn to_u(self) -> $V<F::U> { self.map(#[inline(always)] |x| F::to_u(x)) }
            /// Lane-wise [`Float::at_least`].
            #[inline(always)]
            pub fn at_least(self, lo: F) -> Self { self.map(#[inline(always)] |x| x.at_least(lo)) }
            /// Lane-wise [`Float::at_most`].
            #[inline(always)]
            pub fn at_most(self, hi: F) -> Self { self.map(#[inline(always)] |x| x.at_most(hi)) }
            /// Lane-wise [`Float::clamped`].
            #[inline(always)]
            pub fn clamped(self, lo: F, hi: F) -> Self { self.map(#[inline(always)] |x| x.clamped(lo, hi)) }
            /// `self / sqrt(self·self)`, or `fallback` when the squared length is not
            /// positive (the zero vector, and NaN lanes). Squared lengths that overflow give
            /// zero lanes, and denormal ones lose precision: scale first where inputs may be
            /// that large or small.
            #[inline(always)]
            pub fn normalize_or(self, fallback: Self) -> Self {
                let len2 = self.length_squared().named("len2");
                let ok = len2.gt(F::c(0.0));
                let safe = F::sel(ok, len2, F::c(1.0));
                let v = self / safe.sqrt();
                Self::sel_all(ok, v, fallback)
            }
            /// Sum of squares, evaluated left to right: `((x*x) + (y*y)) + ...`.
            #[inline(always)]
            pub fn length_squared(self) -> F {
                let s = self.zip(self, #[inline(always)] |a, b| a * b);
                let a = s.to_array();
                let mut acc = a[0];
                for v in &a[1..] {
                    acc = acc + *v;
                }
                acc
            }
        }

        impl<U: Uint> $V<U> {
            #[inline(always)]
            pub fn to_f(self) -> $V<U::F> { self.map(#[inline(always)] |x| U::to_f(x)) }
        }

        impl<T: Lane + Add<Output = T>> Add for $V<T> {
            type Output = Self;
            #[inline(always)]
            fn add(self, o: Self) -> Self { self.zip(o, #[inline(always)] |a, b| a + b) }
        }
        impl<T: Lane + Sub<Output = T>> Sub for $V<T> {
            type Output = Self;
            #[inline(always)]
            fn sub(self, o: Self) -> Self { self.zip(o, #[inline(always)] |a, b| a - b) }
        }
        impl<T: Lane + Mul<Output = T>> Mul for $V<T> {
            type Output = Self;
            #[inline(always)]
            fn mul(self, o: Self) -> Self { self.zip(o, #[inline(always)] |a, b| a * b) }
        }
        impl<T: Lane + Div<Output = T>> Div for $V<T> {
            type Output = Self;
            #[inline(always)]
            fn div(self, o: Self) -> Self { self.zip(o, #[inline(always)] |a, b| a / b) }
        }
        impl<T: Lane + BitAnd<Output = T>> BitAnd for $V<T> {
            type Output = Self;
            #[inline(always)]
            fn bitand(self, o: Self) -> Self { self.zip(o, #[inline(always)] |a, b| a & b) }
        }
        impl<T: Lane + BitOr<Output = T>> BitOr for $V<T> {
            type Output = Self;
            #[inline(always)]
            fn bitor(self, o: Self) -> Self { self.zip(o, #[inline(always)] |a, b| a | b) }
        }
        impl<T: Lane + Neg<Output = T>> Neg for $V<T> {
            type Output = Self;
            #[inline(always)]
            fn neg(self) -> Self { self.map(#[inline(always)] |a| -a) }
        }
        /// Vector-by-scalar products print as `v * s`, as in hand-written shaders.
        impl<F: Float> Mul<F> for $V<F> {
            type Output = Self;
            #[inline(always)]
            fn mul(self, s: F) -> Self { self.map(#[inline(always)] |a| a * s) }
        }
        impl<F: Float> Div<F> for $V<F> {
            type Output = Self;
            #[inline(always)]
            fn div(self, s: F) -> Self { self.map(#[inline(always)] |a| a / s) }
        }
        impl<F: Float> Add<F> for $V<F> {
            type Output = Self;
            #[inline(always)]
            fn add(self, s: F) -> Self { self.map(#[inline(always)] |a| a + s) }
        }
        impl<F: Float> Sub<F> for $V<F> {
            type Output = Self;
            #[inline(always)]
            fn sub(self, s: F) -> Self { self.map(#[inline(always)] |a| a - s) }
        }
    };
}

vector!(V2, 2, x: 0, y: 1);
vector!(V3, 3, x: 0, y: 1, z: 2);
vector!(V4, 4, x: 0, y: 1, z: 2, w: 3);

impl<T: Lane> V2<T> {
    #[inline(always)]
    pub fn yx(self) -> Self {
        V2::from_array(T::fuse([self.y, self.x]))
    }
}

impl<T: Lane> V3<T> {
    #[inline(always)]
    pub fn xy(self) -> V2<T> {
        V2::from_array(T::fuse([self.x, self.y]))
    }
    #[inline(always)]
    pub fn from_xy(xy: V2<T>, z: T) -> Self {
        V3::from_array(T::fuse([xy.x, xy.y, z]))
    }
}

/// `f` of every element of `a`, first to last (as `a.map(f)` evaluates them), inlined
/// whole. `[T; N]::map` hands its closure to a std function that is not always inlined;
/// left in a function compiled for the baseline target, the eight lanes' operations in
/// that closure become calls to out-of-line intrinsics (`src/model/avx2_lanes.rs`).
/// `N` must be at least 1 (checked when compiled): the first result fills the array.
#[inline(always)]
pub fn each<T: Copy, R: Copy, const N: usize>(a: [T; N], f: impl Fn(T) -> R) -> [R; N] {
    const { assert!(N > 0, "each: an empty array has no first element") };
    let mut out = [f(a[0]); N];
    for k in 1..N {
        out[k] = f(a[k]);
    }
    out
}
