//! `qtangent32`: the frame's rotation as a unit quaternion in 32 bits, "smallest three": the
//! largest of its four components is dropped (its index stored, its sign made positive by
//! negating the quaternion, which is the same rotation), the other three are stored as
//! snorm fields over `[-1/√2, 1/√2]` (no dropped component can be smaller than one kept,
//! so a kept one never exceeds `1/√2`), and the bitangent's sign takes one bit. Fields,
//! first lowest: 10, 10 and 9 bits for the kept components in x, y, z, w order, then the
//! index (2 bits) and the sign (bit 31).
//!
//! The encoder is portable ([`crate::codecs::toolkit::exact`]). The frame is made a
//! rotation matrix in fixed point: the normal made unit on the `2^-24` grid by
//! [`unit_on_grid`], the tangent made orthogonal to it (Gram–Schmidt, every product
//! rounded to an integer before it is summed) and unit the same way, the bitangent their
//! fixed-point cross product. With the matrix's entries integers in units of `2^-22`,
//! every quaternion quantity is an exact integer sum: `4·q_i²` from the diagonal and
//! `4·q_i·q_j` from the off-diagonal pairs. The dropped component is the largest `4·q_i²`
//! (exact comparisons, the earlier of equal ones), and each kept component's field is
//! `√2·q_j = (4·q_L·q_j) / √(2·4·q_L²)` rounded by [`snorm_sqrt_ratio`], which decides the
//! code by comparisons of single products: no root or quotient decides a code.
//!
//! The decoder restores the dropped component as `√max(1 - Σ kept², ¼)` and returns Filament's
//! rotation columns of the quaternion ([`rotation_columns`]).

use crate::codecs::core::codec::{pack, unpack};
use crate::codecs::frames::frame::rotation_columns;
use crate::codecs::frames::tangent_plane::{
    DEGENERATE, first_axis, fixed_cross, fixed_dot, fixed_mul, sign_field, y_branch,
};
use crate::codecs::toolkit::exact::{canonical, canonical_or_z, snorm_sqrt_ratio, unit_on_grid};
use crate::codecs::toolkit::quant::{Code, Quant};
use crate::model::{Bool, Float, V3, V4};

/// The fields: the three kept components (snorm 10, 10, 9) and the tag, the dropped
/// component's index plus 4 for a reflected frame (unorm 3: bits 29–30 the index, bit 31
/// the sign).
pub const QUANTS: [Quant; 4] = [
    Quant::Snorm(10),
    Quant::Snorm(10),
    Quant::Snorm(9),
    Quant::Unorm(3),
];

pub const EDGE_POLICY: &str = "the normal is made unit (a zero, denormal, NaN or infinite normal counts as +Z); the tangent is made orthogonal to it (Gram–Schmidt); a tangent whose orthogonal part is below 2^-13 of its largest component (zero, NaN, infinite, parallel to the normal) is replaced by b1 = (n.y, -n.x, 0) where |n.y| > |n.z|, else (n.z, 0, -n.x) (+X for the normal +Z); w < 0 is reflected, any other w (0, NaN) is not";
pub const DECODE_NOTE: &str = "the rotation's columns of the quaternion whose dropped component is √max(1 - Σ kept², ¼): n and t unit and orthogonal within 4·10^-6 for every code the encoder writes";

/// The fixed-point unit of unit vectors: `2^-24`, f32's spacing just below 1.
const GRID: f32 = (1u32 << 24) as f32;
/// The fixed-point unit of the tangent before it is made orthogonal: `2^-21` of the
/// tangent scaled so that its largest component is in `[2, 4)`.
const T_UNIT: f32 = (1u32 << 21) as f32;
/// The fixed-point unit of the rotation matrix's entries, `2^-22`: a sum of four of
/// them (`1 + m00 + m11 + m22`) is an integer of at most `2^24`, exact in f32.
const ONE: f32 = (1u32 << 22) as f32;

/// The rotation matrix of the frame `(n, t)`, columns `(t, n × t, n)`, its entries
/// integers in units of `2^-22`: see the module's doc. A zero, denormal, NaN or infinite
/// normal is +Z (as oct's); a tangent whose part orthogonal to the normal is below
/// [`DEGENERATE`] (`2^-13` of its largest component, or zero, NaN, infinite) is replaced
/// by Ong's first axis of the normal ([`first_axis`]: +X for +Z).
#[inline(always)]
pub fn rotation<F: Float>(n: V3<F>, t: V4<F>) -> [V3<F>; 3] {
    let (nc, _) = canonical_or_z(n);
    let nn = (unit_on_grid(nc) * F::c(GRID)).named("n");
    let (w, ok) = canonical(V3::new(t.x, t.y, t.z));
    let round = {
        #[inline(always)]
        |x: F| x.round()
    };
    let tt = (w * F::c(T_UNIT)).map(round).named("t");
    // Gram–Schmidt: t - (t·n)·n, each product rounded to a unit of the tangent.
    let along = fixed_dot(tt, nn).named("along");
    let g = (tt - nn.map(
        #[inline(always)]
        |c| fixed_mul(along, c),
    ))
    .named("g");
    let usable = ok.and((g.x.abs() + g.y.abs() + g.z.abs()).ge(F::c(DEGENERATE)));
    let g = V3::sel_all(usable, g, first_axis(y_branch(nn), nn));
    let (gc, _) = canonical_or_z(g);
    let tu = (unit_on_grid(gc) * F::c(GRID)).named("tu");
    let b = fixed_cross(nn, tu).named("b");
    [tu, b, nn].map(
        #[inline(always)]
        |c| (c * F::c(ONE / GRID)).map(round),
    )
}

/// The fields the packed encoder stores: the kept components' codes, and the tag.
#[inline(always)]
pub fn encode_fields<F: Float>(n: V3<F>, t: V4<F>) -> V4<F> {
    let m = rotation(n, t);
    let e = {
        #[inline(always)]
        |c: usize, r: usize| m[c].to_array()[r]
    };
    let one = F::c(ONE);
    let (a, b, c) = (e(0, 0), e(1, 1), e(2, 2));
    // 4·q², in units of 2^-22, for x, y, z, w: sums of integers below 2^24, exact.
    let squares = [
        one + a - b - c,
        one - a + b - c,
        one - a - b + c,
        one + a + b + c,
    ];
    // 4·q_i·q_j, likewise.
    let xy = (e(0, 1) + e(1, 0)).named("xy");
    let xz = (e(0, 2) + e(2, 0)).named("xz");
    let yz = (e(1, 2) + e(2, 1)).named("yz");
    let wx = (e(1, 2) - e(2, 1)).named("wx");
    let wy = (e(2, 0) - e(0, 2)).named("wy");
    let wz = (e(0, 1) - e(1, 0)).named("wz");
    // The products with the dropped component of the kept ones, in x, y, z, w order.
    let kept = [[xy, xz, wx], [xy, yz, wy], [xz, yz, wz], [wx, wy, wz]];
    let mut largest = squares[0];
    let mut index = F::c(0.0);
    let mut d = kept[0];
    for i in 1..4 {
        let more = squares[i].gt(largest);
        largest = F::sel(more, squares[i], largest).named("largest");
        index = F::sel(more, F::c(i as f32), index).named("index");
        d = [0, 1, 2].map(
            #[inline(always)]
            |j| F::sel(more, kept[i][j], d[j]),
        );
    }
    // √2·q_j = 4·q_L·q_j / √(2·4·q_L²), the square in units of 2^-22 scaled once more.
    let s = (largest * F::c(2.0 * ONE)).named("s");
    let code = {
        #[inline(always)]
        |j: usize| snorm_sqrt_ratio(QUANTS[j], d[j], s)
    };
    let tag = index + F::c(4.0) * sign_field(t);
    V4::new(code(0), code(1), code(2), tag).named("codes")
}

/// The packed encoder: [`encode_fields`], packed.
#[inline(always)]
pub fn encode<F: Float, C: Code<F>>(n: V3<F>, t: V4<F>) -> C {
    pack(&QUANTS, encode_fields(n, t))
}

/// The decoded frame from the unpacked integer fields: the kept components read back
/// (`max(c, -M)/(M·√2)`), the dropped one `√max(1 - Σ kept², ¼)` at its index, and the
/// rotation's columns `t` and `n` with the tag's sign in `t.w`.
///
/// The largest of a unit quaternion's four components is at least ½, so every code the
/// encoder writes has `1 - Σ kept² ≥ ¼` but for its rounding. The floor keeps the root
/// away from zero, where a change in the last place of its argument would move the
/// result by far more (the decoder's proven bound is over every code, and a code whose
/// kept components are too long to be a unit quaternion's has a root near zero).
#[inline(always)]
pub fn decode_fields<F: Float>(c: V4<F>) -> (V3<F>, V4<F>) {
    let kept = [c.x, c.y, c.z];
    let v = [0, 1, 2].map(
        #[inline(always)]
        |j| {
            let m = QUANTS[j].max_code();
            (kept[j].at_least(F::c(-m)) * F::c((1.0 / (f64::from(m) * 2f64.sqrt())) as f32))
                .named("kept")
        },
    );
    let rest = (F::c(1.0) - (v[0] * v[0] + v[1] * v[1] + v[2] * v[2])).at_least(F::c(0.25));
    let r = rest.sqrt().named("dropped");
    let reflected = c.w.ge(F::c(4.0));
    let index = F::sel(reflected, c.w - F::c(4.0), c.w).named("index");
    let at = {
        #[inline(always)]
        |i: f32| index.eq(F::c(i))
    };
    let q = V4::new(
        F::sel(at(0.0), r, v[0]),
        F::sel(at(0.0), v[0], F::sel(at(1.0), r, v[1])),
        F::sel(at(3.0), v[2], F::sel(at(2.0), r, v[1])),
        F::sel(at(3.0), r, v[2]),
    )
    .named("q");
    let (n, t) = rotation_columns(q);
    let s = F::sel(reflected, F::c(-1.0), F::c(1.0));
    (n, V4::new(t.x, t.y, t.z, s))
}

/// The packed decoder: the fields unpacked as integers, then [`decode_fields`].
#[inline(always)]
pub fn decode<F: Float, C: Code<F>>(code: C) -> (V3<F>, V4<F>) {
    decode_fields(unpack::<F, V4<F>, C>(&QUANTS, code).named("fields"))
}
