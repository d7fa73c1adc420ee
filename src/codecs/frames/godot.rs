//! Godot 4's compressed vertex normal and tangent (`ARRAY_FLAG_COMPRESS_ATTRIBUTES`, 4.2
//! and later): the rotation taking the standard basis to the frame's rows `(t, b, n)`, as
//! an octahedral axis in the normal attribute (unorm16×2) and an angle in the position's
//! `w` (unorm16) whose half of the range carries the bitangent's sign. Encoded by
//! `_get_axis_angle` and the vertex loop of `RenderingServer::_surface_set_data`
//! (servers/rendering_server.cpp), with `Basis::get_axis_angle` (core/math/basis.cpp) and
//! `Vector3::octahedron_encode` (core/math/vector3.cpp); decoded as the forward shaders'
//! vertex stage does (`oct_to_vec3`, then `axis_angle_to_tbn` on
//! `abs(angle·2 - 1)·π`, the sign being `angle > 0.5`).
//!
//! The encoder is Godot's arithmetic, in its order, every branch computed and the taken
//! one selected: `normalized()` (a division by the root of `x² + y² + z²`, zero staying
//! zero), the bitangent `normalize(n × t)`, `get_axis_angle`'s singularity tests (its
//! thresholds as Godot compares them, float against float or double), its 180° branch,
//! and `acos((trace - 1)/2)`. That `acosf` is fdlibm's (glibc's up to 2.40, FreeBSD's
//! msun), written out here from its float operations, so the codes are the ones Godot
//! writes on those systems; a platform whose `acosf` differs by an ulp can move an angle
//! code by one. Godot's double steps, `θ/π·0.5 + 0.5` (or `(1 - θ/π)·0.5`) rounded once
//! to float, are computed with `θ·(1/2π)` as an exact two-float product and one final
//! rounding, which agrees with the double computation except where the exact value lies
//! within about `2^-46` of a rounding boundary. The input policy fills in what Godot
//! leaves undefined: a zero, NaN or infinite normal, and a tangent with no usable
//! bitangent (zero, NaN, infinite, parallel to the normal), which is replaced by the
//! canonical tangent of [`crate::codecs::frames::frame`]. Godot does not make the tangent
//! orthogonal to the normal, so neither does this encoder.
//!
//! The decoder's angle is in half turns, `abs(a·2 - 1)`, and its sine and cosine are the
//! model's [`sincos_pi`] (within `2.5·10^-7` of the exact values) rather than a driver's
//! `cos(angle·π)`: the same frame to that precision, and the same bits on every path.

use crate::codecs::core::codec::pack;
use crate::codecs::functions::function::Emitted;
use crate::codecs::core::ieee;
use crate::codecs::core::info::{Info, Sizes, FloatForm};
use crate::codecs::core::spec::{Family, Spec, Tracing};
use crate::codecs::frames::frame::{
    FieldFrame, TBN_DECODER, canonical_tangent, cross, field_frame_emitted, handedness, policy_normal, tbn_doc, usable,
};
use crate::codecs::toolkit::quant::Quant;
use crate::codecs::toolkit::trig::sincos_pi;
use crate::model::num::helper;
use crate::model::{Bool, Float, Lane, Uint, V2, V3, V4};
use std::f64::consts::PI;

/// The stored fields: the axis's two octahedral coordinates and the angle, unorm16 each.
const QUANTS: [Quant; 3] = [Quant::Unorm(16); 3];

pub static GODOT: GodotAxisAngle = GodotAxisAngle {
    info: Info {
        name: "godot_axis_angle",
        title: "Godot 4's compressed vertex normal and tangent: octahedral axis and angle, unorm16×3",
        sizes: Sizes::Fixed(48),
        domain: None,
        source: "Godot 4 at godotengine/godot: servers/rendering_server.cpp at 000e39d (_get_axis_angle, _surface_set_data), core/math/basis.cpp at 2fcd40f (get_axis_angle), core/math/vector3.cpp at 9a46de9 (octahedron_encode), core/math/math_funcs.h at 46f79eb (acos, is_zero_approx), servers/rendering/renderer_rd/shaders/forward_clustered/scene_forward_clustered.glsl at 333f0f9 (oct_to_vec3, axis_angle_to_tbn); fdlibm's acosf (FreeBSD msun e_acosf.c; glibc's through 2.40)",
        edge_policy: "Godot's arithmetic for every frame it defines, the tangent not made orthogonal; w < 0 is reflected, any other w (0, NaN) is not; a normal with |x| + |y| + |z| below 2^-60 (zero, denormal), NaN or infinite encodes as +Z; a normal of squared length outside [2^-20, 2^20] is first divided by its largest component; a tangent whose bitangent normalize(n) × normalize(t) has squared length below 2^-60 or not finite (zero, NaN, infinite, parallel to the normal) is replaced by the canonical tangent of Duff et al. (2017)",
        decode_note: "Godot's oct_to_vec3 and axis_angle_to_tbn, the angle's sine and cosine from the model's polynomial: each component within 2^-20 of that decode evaluated exactly on every sampled code; n and t unit and orthogonal within 2^-20",
        float_form: FloatForm::Absent,
        options: &[ieee::ENGINE_OPTION],
    },
};

/// The godot_axis_angle family (one size, 48 bits).
pub struct GodotAxisAngle {
    info: Info,
}

impl Family for GodotAxisAngle {
    fn info(&self) -> &Info {
        &self.info
    }
    /// Godot's encoder is the only one: the codes are Godot's.
    fn precise(&self) -> bool {
        false
    }
    fn emitted(&self, spec: &Spec, _: Tracing) -> Emitted {
        field_frame_emitted::<GodotAxisAngle>(spec)
    }
    fn engine(&self, _spec: &Spec) -> Option<&'static str> {
        Some("Godot")
    }
    fn function_doc(&self, _spec: &Spec, name: &str) -> Option<Vec<String>> {
        const CODE: &str = "word 0 holds the axis's octahedral x (bits 0–15) and y (bits 16–31) as Godot's normal attribute stores them, word 1 the angle (bits 0–15) as Godot stores it in the position's w; unorm16 each";
        let input = format!(
            "In: a normal n and a tangent t whose w is the bitangent's sign (glTF's convention: bitangent = cross(n, t.xyz)·t.w); {}.",
            self.info.edge_policy
        );
        Some(match name {
            TBN_DECODER => tbn_doc(),
            "decode_float" => vec!["In: the axis's octahedral x and y and the angle, each in [0, 1], as unorm16 fetches of the code return them.".into()],
            "decode" => vec![
                format!("In: the packed code, two 32-bit words: {CODE}."),
                format!("Out: the frame: n, and t with the bitangent's sign (±1) in t.w; {}.", self.info.decode_note),
            ],
            "encode_float" => vec![
                input,
                "Out: Godot's unquantized fields: the axis's octahedron_encode (x, y in [0, 1]) and the angle, in [0.500008, 1] for t.w ≥ 0 and [0, 0.49999] for t.w < 0.".into(),
            ],
            _ => vec![
                "In: as for encode_float.".into(),
                format!("Out: the packed code, two 32-bit words: {CODE}; each field (uint16_t)CLAMP(x·65535, 0, 65535), truncated."),
            ],
        })
    }
    fn frames(&self) -> bool {
        true
    }
    /// Cross products, the rotation's sums of products and fdlibm's polynomials: Mesa's
    /// OpenGL compiler fuses them without `precise`.
    fn contracted(&self, _spec: &Spec) -> bool {
        true
    }
}

/// `f32` of a double constant compared with a float `x` as C++ does (`x < d` with `x`
/// promoted): the smallest float not below `d`, so that `x < d ⇔ x < up(d)`.
fn up(d: f64) -> f32 {
    let f = d as f32;
    if f64::from(f) < d {
        f32::from_bits(f.to_bits() + 1)
    } else {
        f
    }
}

/// Godot's `CMP_EPSILON` (0.00001, a double).
const CMP_EPSILON: f64 = 0.00001;

/// fdlibm's `acosf` (`__ieee754_acosf`), its three ranges all computed and the one `x`
/// falls in selected by the bits of `x`, as fdlibm decides; `|x| > 1` is not reached
/// (Godot's `Math::acos` clamps first). Its rational approximation's coefficients are
/// fdlibm's.
#[inline(always)]
pub fn fdlibm_acosf<F: Float>(x: F) -> F {
    // fdlibm's constants, by their bits as its source lists them.
    const PI_F: f32 = f32::from_bits(0x4049_0fda);
    const PIO2_HI: f32 = f32::from_bits(0x3fc9_0fda);
    const PIO2_LO: f32 = f32::from_bits(0x33a2_2168);
    const PS: [u32; 6] = [
        0x3e2a_aaab,
        0xbea6_b090,
        0x3e4e_0aa8,
        0xbd24_1146,
        0x3a4f_7f04,
        0x3811_ef08,
    ];
    const QS: [u32; 4] = [0xc019_d139, 0x4001_572d, 0xbf30_3361, 0x3d9d_c62e];
    let (ps, qs) = (PS.map(f32::from_bits), QS.map(f32::from_bits));
    let one = F::c(1.0);
    // p(z)/q(z), fdlibm's r, with p = z·(pS0 + z·(pS1 + …)) and q = 1 + z·(qS1 + …).
    let ratio = {
        #[inline(always)]
        |z: F| {
            let mut p = F::c(ps[5]);
            for c in ps[..5].iter().rev() {
                p = F::c(*c) + z * p;
            }
            let p = z * p;
            let mut q = F::c(qs[3]);
            for c in qs[..3].iter().rev() {
                q = F::c(*c) + z * q;
            }
            p / (one + z * q)
        }
    };
    let bits = x.magnitude_bits();
    // |x| < 0.5.
    let r = ratio(x * x);
    let small = F::c(PIO2_HI) - (x - (F::c(PIO2_LO) - x * r));
    let small = F::sel(
        bits.lt(F::U::c(0x2300_0001)),
        F::c(PIO2_HI + PIO2_LO),
        small,
    );
    // x ≤ -0.5.
    let z = ((one + x) * F::c(0.5)).named("z");
    let s = z.sqrt();
    let w = ratio(z) * s - F::c(PIO2_LO);
    let negative = F::c(PI_F) - F::c(2.0) * (s + w);
    // x ≥ 0.5: the root split into its top bits and a correction.
    let z = ((one - x) * F::c(0.5)).named("z");
    let s = z.sqrt();
    let df = (s.to_bits() & F::U::c(0xffff_f000)).as_float();
    let c = (z - df * df) / (s + df);
    let w = ratio(z) * s + c;
    let positive = F::c(2.0) * (df + w);
    let at_one = F::sel(x.lt(F::c(0.0)), F::c(PI_F + 2.0 * PIO2_LO), F::c(0.0));
    F::sel(
        bits.lt(F::U::c(0x3f00_0000)),
        small,
        F::sel(
            bits.lt(F::U::c(0x3f80_0001))
                .and(bits.lt(F::U::c(0x3f80_0000)).not()),
            at_one,
            F::sel(x.lt(F::c(0.0)), negative, positive),
        ),
    )
}

/// Godot's `Vector3::normalized`: `v / sqrt(x² + y² + z²)`, the zero vector where the
/// squared length is 0.
#[inline(always)]
fn normalized<F: Float>(v: V3<F>) -> V3<F> {
    let l2 = v.length_squared();
    let zero = l2.eq(F::c(0.0));
    let l = F::sel(zero, F::c(1.0), l2).sqrt();
    V3::sel_all(zero, V3::splat(F::c(0.0)), v / V3::splat(l))
}

/// `Basis::get_axis_angle` of the matrix with rows `r`: the axis and the angle in
/// radians, Godot's three cases (identity, 180°, general) all computed.
#[inline(always)]
fn axis_angle<F: Float>(r: [V3<F>; 3]) -> (V3<F>, F) {
    let at = {
        #[inline(always)]
        |i: usize, j: usize| r[i].to_array()[j]
    };
    let zero_approx = {
        #[inline(always)]
        |x: F| x.abs().lt(F::c(CMP_EPSILON as f32))
    };
    let below = {
        #[inline(always)]
        |x: F, d: f64| x.lt(F::c(up(d)))
    };
    let singular = zero_approx(at(0, 1) - at(1, 0))
        .and(zero_approx(at(0, 2) - at(2, 0)))
        .and(zero_approx(at(1, 2) - at(2, 1)));
    let diagonal = zero_approx(at(0, 1))
        .and(zero_approx(at(0, 2)))
        .and(zero_approx(at(1, 0)))
        .and(zero_approx(at(1, 2)))
        .and(zero_approx(at(2, 0)))
        .and(zero_approx(at(2, 1)));
    let trace = (at(0, 0) + at(1, 1) + at(2, 2)).named("trace");
    let identity = diagonal.and(below((trace - F::c(3.0)).abs(), 3.0 * CMP_EPSILON));
    // 180°: the axis from the largest diagonal term.
    let half = {
        #[inline(always)]
        |x: F| (x + F::c(1.0)) * F::c(0.5)
    };
    let quarter = {
        #[inline(always)]
        |a: F, b: F| (a + b) * F::c(0.25)
    };
    let (xx, yy, zz) = (half(at(0, 0)), half(at(1, 1)), half(at(2, 2)));
    let (xy, xz, yz) = (
        quarter(at(0, 1), at(1, 0)),
        quarter(at(0, 2), at(2, 0)),
        quarter(at(1, 2), at(2, 1)),
    );
    let h = F::c(std::f64::consts::FRAC_1_SQRT_2 as f32);
    // The largest term's root, and the other two divided by it.
    let major = {
        #[inline(always)]
        |d: F, a: F, b: F| {
            let root = d.sqrt();
            (below(d, CMP_EPSILON), root, a / root, b / root)
        }
    };
    let (flat, x, y, z) = major(xx, xy, xz);
    let on_x = V3::sel_all(flat, V3::new(F::c(0.0), h, h), V3::new(x, y, z));
    let (flat, y, x, z) = major(yy, xy, yz);
    let on_y = V3::sel_all(flat, V3::new(h, F::c(0.0), h), V3::new(x, y, z));
    let (flat, z, x, y) = major(zz, xz, yz);
    let on_z = V3::sel_all(flat, V3::new(h, h, F::c(0.0)), V3::new(x, y, z));
    let half_turn = V3::sel_all(
        xx.gt(yy).and(xx.gt(zz)),
        on_x,
        V3::sel_all(yy.gt(zz), on_y, on_z),
    );
    // The general case: the axis from the skew part, the angle from the trace.
    let d = V3::new(
        at(2, 1) - at(1, 2),
        at(0, 2) - at(2, 0),
        at(1, 0) - at(0, 1),
    );
    let s = d.length_squared().sqrt();
    let s = F::sel(below(s, CMP_EPSILON), F::c(1.0), s);
    let general = d / V3::splat(s);
    let c = (trace - F::c(1.0)) * F::c(0.5);
    // Godot's Math::acos clamps: π below -1, 0 above 1.
    let angle = F::sel(
        c.lt(F::c(-1.0)),
        F::c(PI as f32),
        F::sel(c.gt(F::c(1.0)), F::c(0.0), helper!(fdlibm_acosf(c))),
    );
    let axis = V3::sel_all(
        singular,
        V3::sel_all(identity, V3::new(F::c(0.0), F::c(1.0), F::c(0.0)), half_turn),
        general,
    );
    let angle = F::sel(
        singular,
        F::sel(identity, F::c(0.0), F::c(PI as f32)),
        angle,
    );
    (axis, angle)
}

/// `0.5 + θ/(2π)` (or `0.5 - θ/(2π)` where `reflected`) rounded once to f32, as Godot's
/// double arithmetic gives it, from exact operations only, so that no compiler's
/// regrouping or simplification can change it (a two-sum's `(0.5 - s) + hi` is, to a
/// shader compiler that does not keep exactness, zero).
///
/// The sum is rounded on the grid `g` of its binade, read from the exponent bits of a
/// float estimate. Its terms are `0.5` and the exact products of `θ` and `1/2π` split in
/// 12-bit halves (Dekker's), plus `θ` times the constant's low part; each, scaled by
/// `±1/g` (exact), is cut into its integer part (mod 2^32, as an unsigned integer) and
/// its fraction floored to `2^-24`, and the parts are added as integers, which no
/// regrouping changes. Agrees with the double computation except where the exact value
/// lies within about `2^-46` of a rounding boundary, or within an ulp of a power of two.
#[inline(always)]
fn half_turns<F: Float>(theta: F, reflected: F::B) -> F {
    let c = 0.5 / PI;
    let c1 = c as f32;
    let c2 = (c - f64::from(c1)) as f32;
    let c1h = f32::from_bits(c1.to_bits() & 0xffff_f000);
    let c1l = c1 - c1h;
    let th = (theta.to_bits() & F::U::c(0xffff_f000)).as_float().named("theta_hi");
    let tl = (theta - th).named("theta_lo");
    let sign = F::sel(reflected, F::c(-1.0), F::c(1.0));
    let estimate = (F::c(0.5) + theta * F::c(c1) * sign).named("estimate");
    // The grid, 2^(e - 150) for the estimate's biased exponent e (at least 40: smaller
    // sums are clamped to 0), and ±its inverse.
    let u = {
        #[inline(always)]
        |v: u32| F::U::c(v)
    };
    let e = estimate.magnitude_bits().shr(23).named("exponent");
    let e = F::U::sel(e.lt(u(40)), u(40), e).named("exponent");
    let grid = e.wrapping_sub(u(23)).shl(23).as_float().named("grid");
    let inverse = u(277).wrapping_sub(e).shl(23).as_float().named("inv_grid");
    let scale = (inverse * sign).named("scale");
    let terms = [
        F::c(0.5) * inverse,
        th * F::c(c1h) * scale,
        th * F::c(c1l) * scale,
        tl * F::c(c1h) * scale,
        tl * F::c(c1l) * scale,
        theta * F::c(c2) * scale,
    ];
    let (mut whole, mut part) = (u(0), u(0));
    for p in terms {
        let p = p.named("term");
        let i = p.floor().named("whole");
        part = part.wrapping_add(((p - i) * F::c(16_777_216.0)).floor().to_u());
        let a = i.abs();
        let low = (a - (a * F::c(1.0 / 4_294_967_296.0)).floor() * F::c(4_294_967_296.0)).to_u();
        whole = whole.wrapping_add(F::U::sel(i.lt(F::c(0.0)), u(0).wrapping_sub(low), low));
    }
    let r = whole.wrapping_add(part.wrapping_add(u(1 << 23)).shr(24)).named("r");
    let r = F::U::sel(u(1 << 24).lt(r), u(1 << 24), r);
    F::sel(estimate.gt(F::c(0.0)), r.to_f() * grid, F::c(0.0))
}

/// `Vector3::octahedron_encode` of the unit axis: `n / (|x| + |y| + |z|)`, folded where
/// `z < 0`, then `o·0.5 + 0.5`.
#[inline(always)]
fn octahedron_encode<F: Float>(a: V3<F>) -> V2<F> {
    let n = a / V3::splat(a.x.abs() + a.y.abs() + a.z.abs());
    let sign = {
        #[inline(always)]
        |x: F| F::sel(x.ge(F::c(0.0)), F::c(1.0), F::c(-1.0))
    };
    let folded = V2::new(
        (F::c(1.0) - n.y.abs()) * sign(n.x),
        (F::c(1.0) - n.x.abs()) * sign(n.y),
    );
    let o = V2::sel_all(n.z.ge(F::c(0.0)), n.xy(), folded);
    o.map(
        #[inline(always)]
        |x| x * F::c(0.5) + F::c(0.5),
    )
}

/// `_get_axis_angle` of the frame after the input policy, and the axis's
/// `octahedron_encode`: the three fields Godot stores, unquantized (`encode_float`).
#[inline(always)]
pub fn axis_angle_fields<F: Float>(n: V3<F>, t: V4<F>) -> V3<F> {
    let n = normalized(policy_normal(n)).named("n");
    let bitangent = {
        #[inline(always)]
        |t: V3<F>| {
            let t = normalized(t);
            (t, cross(n, t))
        }
    };
    let (_, b) = bitangent(V3::new(t.x, t.y, t.z));
    let t3 = V3::sel_all(
        usable(b.length_squared()),
        V3::new(t.x, t.y, t.z),
        canonical_tangent(n),
    );
    let (tangent, b) = bitangent(t3);
    let (axis, angle) = axis_angle([tangent.named("t"), normalized(b).named("b"), n]);
    let reflected = handedness(t.w).lt(F::c(0.0));
    let v = half_turns(angle.named("angle"), reflected).named("v");
    let v = F::sel(
        reflected,
        v.clamped(F::c(0.0), F::c(0.49999f64 as f32)),
        v.clamped(F::c(0.500008f64 as f32), F::c(1.0)),
    );
    let o = octahedron_encode(axis.named("axis"));
    V3::new(o.x, o.y, v)
}

/// The fields stored: `(uint16_t)CLAMP(x·65535, 0, 65535)` each (a truncation), packed.
#[inline(always)]
pub fn encode<F: Float>(n: V3<F>, t: V4<F>) -> V2<F::U> {
    let f = helper!("encode_float" => axis_angle_fields(n, t));
    let codes = f.map(
        #[inline(always)]
        |x| (x * F::c(65535.0)).clamped(F::c(0.0), F::c(65535.0)).floor(),
    );
    pack(&QUANTS, codes.named("codes"))
}

/// The shaders' `oct_to_vec3(e)`: `(e, 1 - |e.x| - |e.y|)`, the lower half folded back by
/// `max(-z, 0)·-sign(e)`, normalized.
#[inline(always)]
pub fn oct_to_vec3<F: Float>(e: V2<F>) -> V3<F> {
    let z = F::c(1.0) - e.x.abs() - e.y.abs();
    let t = (-z).at_least(F::c(0.0)).named("t");
    let sign = {
        #[inline(always)]
        |x: F| {
            F::sel(
                x.gt(F::c(0.0)),
                F::c(1.0),
                F::sel(x.lt(F::c(0.0)), F::c(-1.0), F::c(0.0)),
            )
        }
    };
    let v = V3::new(e.x - t * sign(e.x), e.y - t * sign(e.y), z);
    v / V3::splat(v.length_squared().sqrt())
}

/// The vertex shader's decode of the fetched fields `f` (axis x, axis y, angle in
/// `[0, 1]`): the axis by [`oct_to_vec3`], the sign `angle > 0.5 ? 1 : -1`, and
/// `axis_angle_to_tbn(axis, abs(angle·2 - 1)·π)`'s normal and tangent rows.
#[inline(always)]
pub fn axis_angle_to_frame<F: Float>(f: V3<F>) -> (V3<F>, V4<F>) {
    let e = V2::new(f.x, f.y).map(
        #[inline(always)]
        |x| x * F::c(2.0) - F::c(1.0),
    );
    let axis = helper!(oct_to_vec3(e)).named("axis");
    let sign = F::sel(f.z.gt(F::c(0.5)), F::c(1.0), F::c(-1.0));
    let turns = (f.z * F::c(2.0) - F::c(1.0)).abs().named("turns");
    let sc = helper!(sincos_pi(turns)).named("sc");
    let (s, c) = (sc.x, sc.y);
    let omc = (axis * V3::splat(F::c(1.0) - c)).named("omc");
    let sa = (axis * V3::splat(s)).named("sa");
    let n = V3::new(
        omc.z * axis.x - sa.y,
        omc.z * axis.y + sa.x,
        omc.z * axis.z + c,
    );
    let t = V4::new(
        omc.x * axis.x + c,
        omc.x * axis.y - sa.z,
        omc.x * axis.z + sa.y,
        sign,
    );
    (n, t)
}

/// Godot's frame as its three unorm16 fields: the packed decoder is
/// [`axis_angle_to_frame`] on the fetched fields.
impl FieldFrame for GodotAxisAngle {
    type P<F: Float> = V3<F>;
    const QUANTS: &'static [Quant] = &QUANTS;
    const PARAM: &'static str = "f";
    #[inline(always)]
    fn frame<F: Float>(f: V3<F>) -> (V3<F>, V4<F>) {
        axis_angle_to_frame(f)
    }
    #[inline(always)]
    fn encode_float<F: Float>(n: V3<F>, t: V4<F>) -> V3<F> {
        axis_angle_fields(n, t)
    }
    #[inline(always)]
    fn encode<F: Float>(n: V3<F>, t: V4<F>) -> V2<F::U> {
        encode(n, t)
    }
}
