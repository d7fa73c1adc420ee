//! What the tangent-plane frame codecs share (`octangle`, `diamond`): the normal as an
//! octahedral code, the tangent as one number that places it in the plane orthogonal to
//! the *decoded* normal, around a basis both sides derive from the normal's code alone.
//!
//! The basis is Jeremy Ong's ("Tangent spaces and diamond encoding", 2023): of the
//! decoded normal `n`, `b1 = (n.y, -n.x, 0)` where `|n.y| > |n.z|`, else
//! `b1 = (n.z, 0, -n.x)`, and `b2 = n × b1`. Both have the length of `b1` (at least
//! `1/√2`), so the coordinates `(t·b1, t·b2)` give the tangent's direction in the plane
//! without normalizing either. The branch is decided on the code's integer octahedral
//! point ([`oct_point`]), where `|y| > |z|` has one answer on every implementation, in the
//! encoder and the decoder alike: a basis that jumps at the branch can then never be
//! taken one way by the encoder and the other by the decoder.
//!
//! The encoder is portable ([`crate::codecs::toolkit::exact`]): the normal's code is
//! oct's portable one ([`oct_codes`]), and the tangent's coordinates are fixed-point
//! integers held in floats, every product rounded to a unit before it is summed
//! ([`projection`]), so neither a contraction nor a division or root error can move them.
//! The one number is then decided from those integers by each codec's exact rounding.

use crate::codecs::core::codec::{pack, sign_not_zero, unpack};
use crate::codecs::functions::function::{Emitted, Inputs, Role};
use crate::codecs::core::info::Info;
use crate::codecs::core::spec::{Family, Spec, Tracing};
use crate::codecs::functions::words::{Declared, chained, generic_function, tracer};
use crate::codecs::frames::frame::{FRAME, TBN, cross, handedness, tbn, TBN_DECODER, tbn_doc, tbn_function};
use crate::codecs::octahedral::oct::oct_codes;
use crate::codecs::toolkit::exact::{canonical, snorm_ratio_within, unit_on_grid};
use crate::codecs::toolkit::fixed_trig::{self, atan2_pi};
use crate::codecs::toolkit::quant::{Code, Quant};
use crate::codecs::toolkit::trig::sincos_pi;
use crate::model::enclosure::Encl;
use crate::model::num::helper;
use crate::model::{Bool, Float, V2, V3, V4};

/// The fixed-point unit of the tangent's components and coordinates: `2^-21` of the
/// tangent scaled so that its largest component is in `[2, 4)`.
const T_UNIT: f32 = (1u32 << 21) as f32;
/// The fixed-point unit of the basis: `2^-24`, f32's spacing just below 1.
const B_UNIT: f32 = (1u32 << 24) as f32;
/// Below this sum of coordinate magnitudes (in [`T_UNIT`]s, so `2^-13` of a tangent
/// whose largest component is in `[2, 4)`) the tangent has no usable direction in the
/// plane: it is zero, NaN, infinite or parallel to the normal to within about `2^-14`.
pub const DEGENERATE: f32 = 256.0;

/// The octahedral point of the normal's codes `c` (snorm, largest code `m`) in integers:
/// `(x, y, m - |x| - |y|)`, below the equator folded to `((m - |y|)·sign x, (m - |x|)·sign y)`,
/// so that `|x| + |y| + |z| = m`. Exact in f32 (integers below `2^17`); a hostile code
/// `-m - 1` reads as `-m`, as a snorm fetch clamps it. Never zero.
#[inline(always)]
pub fn oct_point<F: Float>(c: V2<F>, m: f32) -> V3<F> {
    let c = c.map(
        #[inline(always)]
        |x| x.at_least(F::c(-m)),
    );
    let a = c.abs();
    let z = (F::c(m) - a.x - a.y).named("pz");
    let s = sign_not_zero(c);
    let folded = V2::new((F::c(m) - a.y) * s.x, (F::c(m) - a.x) * s.y);
    V3::from_xy(V2::sel_all(z.lt(F::c(0.0)), folded, c), z).named("p")
}

/// Whether the basis is the first of the two: `|y| > |z|` of the octahedral point (so of
/// the normal, which is the point scaled).
#[inline(always)]
pub fn y_branch<F: Float>(p: V3<F>) -> F::B {
    p.y.abs().gt(p.z.abs())
}

/// `b1` of the unit normal `n`: `(n.y, -n.x, 0)` on the first branch, else
/// `(n.z, 0, -n.x)`. Orthogonal to `n`; exact (selections and negations).
#[inline(always)]
pub fn first_axis<F: Float>(branch: F::B, n: V3<F>) -> V3<F> {
    V3::sel_all(
        branch,
        V3::new(n.y, -n.x, F::c(0.0)),
        V3::new(n.z, F::c(0.0), -n.x),
    )
    .named("b1")
}

/// `round(a·b·2^-24)` ([`fixed_trig::mul`] at the unit `2^-24`): one rounded product, an
/// exact scaling and a rounding to an integer, so a function of `a` and `b` alone that no
/// contraction can reach.
#[inline(always)]
pub fn fixed_mul<F: Float>(a: F, b: F) -> F {
    fixed_trig::mul(a, b, fixed_trig::FINE)
}

/// `a·b` of two fixed-point vectors, each product by [`fixed_mul`], the integers summed
/// (exactly, every partial sum below `2^24`).
#[inline(always)]
pub fn fixed_dot<F: Float>(a: V3<F>, b: V3<F>) -> F {
    fixed_mul(a.x, b.x) + fixed_mul(a.y, b.y) + fixed_mul(a.z, b.z)
}

/// `a × b` of two fixed-point vectors, each product by [`fixed_mul`].
#[inline(always)]
pub fn fixed_cross<F: Float>(a: V3<F>, b: V3<F>) -> V3<F> {
    V3::new(
        fixed_mul(a.y, b.z) - fixed_mul(a.z, b.y),
        fixed_mul(a.z, b.x) - fixed_mul(a.x, b.z),
        fixed_mul(a.x, b.y) - fixed_mul(a.y, b.x),
    )
}

/// The normal's octahedral codes (`quant` per axis, oct's portable fast encoder),
/// and the tangent's coordinates `(u, v) = (t·b1, t·b2)` in the basis of the decoded
/// normal, as integers in units of `2^-21` of the tangent scaled to `[2, 4)`, with
/// whether the tangent has a direction in the plane (see [`DEGENERATE`]).
///
/// The decoded normal is the code's octahedral point made unit on the `2^-24` grid by
/// [`unit_on_grid`], whose digits are decided in integers; the basis follows by
/// [`first_axis`] and a [`fixed_cross`]; the tangent is [`canonical`] (a power-of-two
/// scaling, denormals to zero), rounded to `2^-21`. Every quantity is an integer below
/// `2^24` held in a float, every product rounded to an integer before it is summed.
#[inline(always)]
pub fn projection<F: Float>(quant: Quant, n: V3<F>, t: V4<F>) -> (V2<F>, F, F, F::B) {
    let codes = oct_codes(quant, n).named("normal");
    let p = oct_point(codes, quant.max_code());
    let (pc, _) = canonical(p);
    let nn = (unit_on_grid(pc) * F::c(B_UNIT)).named("n");
    let b1 = first_axis(y_branch(p), nn);
    let b2 = fixed_cross(nn, b1).named("b2");
    let (w, ok) = canonical(V3::new(t.x, t.y, t.z));
    let tt = (w * F::c(T_UNIT))
        .map(
            #[inline(always)]
            |x| x.round(),
        )
        .named("t");
    let u = fixed_dot(tt, b1).named("u");
    let v = fixed_dot(tt, b2).named("v");
    let usable = ok.and((u.abs() + v.abs()).ge(F::c(DEGENERATE)));
    (codes, u, v, usable)
}

/// The sign field: 1 for a reflected frame (`w < 0`), 0 otherwise ([`handedness`]).
#[inline(always)]
pub fn sign_field<F: Float>(t: V4<F>) -> F {
    F::sel(handedness(t.w).lt(F::c(0.0)), F::c(1.0), F::c(0.0))
}

/// The decoded frame from the normal's codes `c` (snorm, largest code `m`), the
/// tangent's direction in the plane `d = (along b1, along b2)` (any length) and the sign
/// field: `n` the octahedral point normalized, `t` = `d.x·b1 + d.y·b2` divided by
/// `|b1|·|d|` (so unit), `t.w`
/// -1 where the sign field is set, else +1.
#[inline(always)]
pub fn frame_of<F: Float>(c: V2<F>, m: f32, d: V2<F>, sign: F) -> (V3<F>, V4<F>) {
    let p = oct_point(c, m);
    let n = (p * (F::c(1.0) / p.length_squared().sqrt())).named("n");
    let branch = y_branch(p);
    let b1 = first_axis(branch, n);
    let b2 = cross(n, b1).named("b2");
    let w = (b1 * d.x + b2 * d.y).named("w");
    // |w| = |b1|·|d| (b2 is orthogonal to b1 and as long), with |b1|² selected whole:
    // each basis's is at least ½, where `w·w` of a box of codes that may take either
    // basis could reach zero (the decoder's proven bound needs that).
    let b1_2 = F::sel(branch, n.y * n.y + n.x * n.x, n.z * n.z + n.x * n.x).named("b1_2");
    let t = w * (F::c(1.0) / (b1_2 * d.length_squared()).sqrt());
    let s = F::sel(sign.gt(F::c(0.5)), F::c(-1.0), F::c(1.0));
    (n, V4::new(t.x, t.y, t.z, s))
}

/// How a family stores the tangent's direction in the plane, in a unorm field of `k` bits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Turn {
    /// The angle from `b1` towards `b2`: `2^k` codes around the circle, code `a` at
    /// `a·2π/2^k`.
    Angle,
    /// Ong's diamond: the direction `(x, y)` scaled to `|x| + |y| = 1`, placed on a
    /// cycle of `4M` codes (`M = 2^(k-2) - 1`): `3M - round(M·x)` for `y ≥ 0`,
    /// `M + round(M·x)` for `y < 0`, `4M` wrapping to 0. A ratio, no trigonometry.
    Diamond,
}

impl Turn {
    /// The snorm field whose largest code is the diamond's `M`.
    fn diamond_quant(k: u32) -> Quant {
        Quant::Snorm(k - 1)
    }
    /// The code of the tangent direction `(u, v)` (integers, not both small), decided
    /// exactly: for [`Turn::Angle`] the fixed-point [`atan2_pi`] (units of `2^-23` half
    /// turns) scaled to the codes by a power of two and rounded; for
    /// [`Turn::Diamond`] the ratio `u/(|u| + |v|)` rounded by
    /// [`snorm_ratio_within`]'s comparisons of single products.
    #[inline(always)]
    pub fn code<F: Float>(self, k: u32, u: F, v: F) -> F {
        match self {
            Turn::Angle => {
                let h = atan2_pi(v, u);
                let a = (h * F::c((2.0f64).powi(k as i32 - 24) as f32)).round();
                F::sel(a.lt(F::c(0.0)), a + F::c((1u32 << k) as f32), a).named("angle")
            }
            Turn::Diamond => {
                let q = Self::diamond_quant(k);
                let m = q.max_code();
                let c = snorm_ratio_within(q, u, (u.abs() + v.abs()).named("l1")).named("ratio");
                let a = F::sel(v.ge(F::c(0.0)), F::c(3.0 * m) - c, F::c(m) + c);
                F::sel(a.ge(F::c(4.0 * m)), F::c(0.0), a).named("diamond")
            }
        }
    }
    /// The code of `b1` itself, which a tangent without a direction in the plane takes.
    fn canonical(self, k: u32) -> f32 {
        match self {
            Turn::Angle => 0.0,
            Turn::Diamond => 2.0 * Self::diamond_quant(k).max_code(),
        }
    }
    /// The direction in the plane of the code `a` (any `k`-bit integer): the angle's
    /// `(cos, sin)` by the model's [`sincos_pi`] of the angle in half turns, centred on
    /// `[-1, 1)`; the diamond's `(x, ±(1 - |x|))`, codes past `4M` read as `4M`.
    #[inline(always)]
    pub fn direction<F: Float>(self, k: u32, a: F) -> V2<F> {
        match self {
            Turn::Angle => {
                let whole = F::c((1u32 << k) as f32);
                let j = F::sel(a.ge(F::c((1u32 << (k - 1)) as f32)), a - whole, a);
                let sc = helper!(sincos_pi(j * F::c(2.0 / (1u32 << k) as f32))).named("sc");
                V2::new(sc.y, sc.x)
            }
            Turn::Diamond => {
                let m = Self::diamond_quant(k).max_code();
                let a = a.at_most(F::c(4.0 * m));
                let upper = a.ge(F::c(2.0 * m));
                let x = (F::sel(upper, F::c(3.0 * m) - a, a - F::c(m)) * F::c(1.0 / m)).named("x");
                let y = F::c(1.0) - x.abs();
                // A product with the selected sign, not `sel(upper, y, -y)`: see
                // [`Float::negated_where`].
                V2::new(x, y * F::sel(upper, F::c(1.0), F::c(-1.0)))
            }
        }
    }
}

/// A tangent-plane frame family: its [`Turn`] and its layouts.
pub struct TangentPlane {
    info: Info,
    turn: Turn,
}

impl TangentPlane {
    pub const fn new(info: Info, turn: Turn) -> Self {
        TangentPlane { info, turn }
    }
}

/// The fields of each size: the normal's octahedral x and y (snorm), the tangent's turn
/// (unorm, `k` bits) and the sign (1 bit), first field lowest.
///
/// 32 bits are 11 + 11 + 9 + 1 for either turn: over the seeded orthonormal frames
/// 12 + 12 + 7 + 1 leaves the tangent 24 times the normal's error (sample max 1.41° to
/// 0.059°, `unitpack list`), 11 + 11 + 9 + 1 about three times (0.4° to 0.12°). The
/// normal keeps the finer share: every pixel's shading reads it directly, while a
/// tangent error turns a normal map's perturbation only by that error times the sine of
/// the perturbation's tilt. 48 bits are 16 + 16 + 15 + 1, both errors alike.
fn quants(bits: u32) -> &'static [Quant; 4] {
    const BITS32: [Quant; 4] = [Quant::Snorm(11), Quant::Snorm(11), Quant::Unorm(9), Quant::Unorm(1)];
    const BITS48: [Quant; 4] = [Quant::Snorm(16), Quant::Snorm(16), Quant::Unorm(15), Quant::Unorm(1)];
    if bits == 32 { &BITS32 } else { &BITS48 }
}

/// The fields the packed encoder stores: the normal's octahedral codes and the tangent's
/// turn from [`projection`], the sign from [`sign_field`].
#[inline(always)]
pub fn encode_fields<F: Float>(turn: Turn, q: &[Quant; 4], n: V3<F>, t: V4<F>) -> V4<F> {
    let k = q[2].bits();
    let (codes, u, v, usable) = projection(q[0], n, t);
    let a = F::sel(usable, turn.code(k, u, v), F::c(turn.canonical(k)));
    V4::new(codes.x, codes.y, a, sign_field(t)).named("codes")
}

/// The packed encoder: [`encode_fields`], packed.
#[inline(always)]
pub fn encode<F: Float, C: Code<F>>(turn: Turn, q: &[Quant; 4], n: V3<F>, t: V4<F>) -> C {
    pack(q, encode_fields(turn, q, n, t))
}

/// The packed decoder: the fields unpacked as integers, then [`frame_of`] of the turn's
/// [`Turn::direction`].
#[inline(always)]
pub fn decode<F: Float, C: Code<F>>(turn: Turn, q: &[Quant; 4], code: C) -> (V3<F>, V4<F>) {
    let c: V4<F> = unpack::<F, V4<F>, C>(q, code).named("fields");
    decode_fields(turn, q, c)
}

/// [`decode`] from the unpacked integer fields.
#[inline(always)]
pub fn decode_fields<F: Float>(turn: Turn, q: &[Quant; 4], c: V4<F>) -> (V3<F>, V4<F>) {
    let d = turn.direction(q[2].bits(), c.z);
    frame_of(V2::new(c.x, c.y), q[0].max_code(), d, c.w)
}

pub const EDGE_POLICY: &str = "the normal's code is oct's (a zero, denormal, NaN or infinite normal encodes as +Z); the tangent is taken in the plane orthogonal to the decoded normal (its projection there, which is Gram–Schmidt against that normal); a tangent whose projection is below 2^-13 of its largest component (zero, NaN, infinite, parallel to the normal) encodes as b1, the basis's first axis (+X for the normal +Z); w < 0 is reflected, any other w (0, NaN) is not";
pub const DECODE_NOTE: &str = "n the octahedral point normalized, t its stored direction in the plane normalized: each unit, and orthogonal to each other, within 4·10^-6";

impl Family for TangentPlane {
    fn info(&self) -> &Info {
        &self.info
    }
    /// Not offered yet. The normal's code could be oct's precise search
    /// ([`crate::codecs::octahedral::oct::oct_nearest_codes`], portable), which lowers the 32-bit normal's
    /// sample max from 0.118° to 0.078° (the tangent's turn is already the nearest to its
    /// fixed-point direction); three more specs did not fit the test suite's time budget.
    fn precise(&self) -> bool {
        false
    }
    fn emitted(&self, spec: &Spec, _: Tracing) -> Emitted {
        emitted(self.turn, spec)
    }
    fn function_doc(&self, spec: &Spec, name: &str) -> Option<Vec<String>> {
        let q = quants(spec.bits());
        let k = q[2].bits();
        let b = q[0].bits();
        let turn = match self.turn {
            Turn::Angle => format!("the tangent's angle from b1 towards b2, code a at a·2π/{}", 1u32 << k),
            Turn::Diamond => {
                let m = Turn::diamond_quant(k).max_code();
                format!("the tangent's diamond code, {} around the circle: with x = t·b1 / (|t·b1| + |t·b2|), 3·{m} - round({m}·x) where t·b2 ≥ 0, else {m} + round({m}·x)", 4.0 * m)
            }
        };
        let ty = if spec.bits() == 32 {
            "one 32-bit word"
        } else {
            "two 32-bit words"
        };
        let layout = if spec.bits() == 32 {
            format!("the normal's octahedral x (bits 0–{}) and y (bits {}–{}), snorm{b} (two's complement); {turn} (bits {}–30); the sign (bit 31, set where reflected)", b - 1, b, 2 * b - 1, 2 * b)
        } else {
            format!("word 0 holds the normal's octahedral x (bits 0–15) and y (bits 16–31), snorm16 (two's complement); word 1 {turn} (bits 0–14) and the sign (bit 15, set where reflected)")
        };
        let basis = "b1 = (n.y, -n.x, 0) where |n.y| > |n.z| on the code's octahedral point, else (n.z, 0, -n.x), and b2 = n × b1, of the decoded normal n";
        Some(match name {
            TBN_DECODER => tbn_doc(),
            "decode" => vec![
                format!("In: the packed code, {ty}: {layout}; {basis}."),
                format!("Out: the frame: n, and t with the bitangent's sign (±1) in t.w; {}.", self.info.decode_note),
            ],
            _ => vec![
                format!("In: a normal n and a tangent t whose w is the bitangent's sign (glTF's convention: bitangent = cross(n, t.xyz)·t.w); {}.", self.info.edge_policy),
                format!("Out: the packed code, {ty}: {layout}; {basis}."),
            ],
        })
    }
    fn frames(&self) -> bool {
        true
    }
}

fn emitted(turn: Turn, spec: &Spec) -> Emitted {
    let q = quants(spec.bits());
    // The CPU evaluations chain the layout's packing (per code type, cheap) with bodies
    // compiled once for every size ([`chained`]); the traced functions are whole.
    let fields = generic_function!(
        "encode_fields",
        Role::Encode,
        Inputs::Frames,
        <F> [turn, q] |f: (V3<F>, V4<F>)| encode_fields(turn, &q, f.0, f.1)
    );
    let frame = generic_function!(
        "frame",
        Role::Decode,
        Inputs::Codes(q.to_vec()),
        <F> [turn, q] |c: V4<F>| decode_fields(turn, &q, c)
    );
    macro_rules! functions {
        ($code:ty) => {{
            let unpacked = generic_function!(
                "unpack",
                Role::Decode,
                Inputs::Codes(q.to_vec()),
                <F> [q] |c: $code| unpack::<F, V4<F>, $code>(&q, c)
            );
            let packed = generic_function!(
                "pack",
                Role::Encode,
                Inputs::Frames,
                <F> [q] |c: V4<F>| pack::<F, V4<F>, $code>(&q, c)
            );
            let packed_decode = Declared::new(
                chained("decode", Role::Decode, Inputs::Codes(q.to_vec()), &unpacked, &frame),
                tracer!(["code"] => FRAME, <F> [turn, q] |c: $code| decode::<F, $code>(turn, &q, c)),
            );
            let decode_tbn = tbn_function(
                &packed_decode,
                tracer!(["code"] => TBN, <F> [turn, q] |c: $code| tbn(decode::<F, $code>(turn, &q, c))),
            );
            let packed_encode = Declared::new(
                chained("encode", Role::Encode, Inputs::Frames, &fields, &packed),
                tracer!(["n", "t"], <F> [turn, q] |f: (V3<F>, V4<F>)| {
                    let code: $code = encode(turn, &q, f.0, f.1);
                    code
                }),
            );
            vec![packed_decode, decode_tbn, packed_encode]
        }};
    }
    let functions = if spec.bits() == 32 {
        functions!(<F as Float>::U)
    } else {
        functions!(V2<<F as Float>::U>)
    };
    crate::codecs::frames::frame::emitted(
        spec,
        functions,
        q,
        None,
        move |c: V4<Encl>| decode_fields(turn, q, c),
        true,
    )
}
