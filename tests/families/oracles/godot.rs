//! Oracle: Godot 4's compressed vertex normal and tangent (`ARRAY_FLAG_COMPRESS_ATTRIBUTES`),
//! re-expressed here in plain scalar Rust (no Godot code is used). `real_t` is `float`
//! (Godot's default build); where Godot computes in `double` so does this port.
//!
//! Source followed, repository `godotengine/godot`:
//! * `servers/rendering_server.cpp` at `000e39de5ec67caba1d61ce9d4e39dc59bd29414`:
//!   `_get_axis_angle` (rows `tangent`, `normal.cross(tangent).normalized()`, `normal`, both
//!   vectors `normalized()` first; the angle mapped to `CLAMP((1.0 - a / Math::PI) * 0.5,
//!   0.0, 0.49999)` for `d < 0.0`, else `CLAMP((a / Math::PI) * 0.5 + 0.5, 0.500008, 1.0)`,
//!   in double) and `_surface_set_data`'s compressed vertex loop (the axis's
//!   `octahedron_encode()` and the angle stored as `(uint16_t)CLAMP(v * 65535, 0, 65535)`).
//! * `core/math/basis.cpp` at `2fcd40f1b10f4d5bcc39e4d8e26f315392302396`:
//!   `Basis::get_axis_angle` (singularity by `is_zero_approx` of the three differences,
//!   identity by `is_diagonal()` and `abs(trace - 3) < 3 * CMP_EPSILON`, the 180° branch,
//!   `double s` and `acos((trace - 1) / 2)`) and `is_diagonal`.
//! * `core/math/vector3.cpp` at `9a46de9cf6ced34b2d65b0952327d37434230124`:
//!   `octahedron_encode`; `core/math/vector3.h`: `normalize` (`lengthsq == 0` gives zero,
//!   else a division by `sqrt(lengthsq)`), `cross`, `length_squared` (`x*x + y*y + z*z`).
//! * `core/math/math_funcs.h` at `46f79eb1aed66ac1ccc25c6664f5de9aba2af294`: `acos(float)`
//!   (`p_x < -1 ? PI : (p_x > 1 ? 0 : ::acosf(p_x))`), `is_zero_approx(float)`
//!   (`abs(p_value) < (float)CMP_EPSILON`), `CMP_EPSILON` 0.00001 (a double).
//! * `servers/rendering/renderer_rd/shaders/forward_clustered/scene_forward_clustered.glsl`
//!   at `333f0f910f164851218c5ece26d4c4b4931d4a30`: `oct_to_vec3`, `axis_angle_to_tbn` and
//!   the compressed branch of the vertex stage (`binormal_sign = angle > 0.5 ? 1.0 : -1.0`,
//!   `angle = abs(angle * 2.0 - 1.0) * M_PI`), evaluated here in f64 as the exact decode.
//! * `::acosf`: fdlibm's `__ieee754_acosf` (FreeBSD `lib/msun/src/e_acosf.c`, the same
//!   code as glibc's `sysdeps/ieee754/flt-32/e_acosf.c` up to 2.40, which equals glibc
//!   2.36's `acosf` on every float in [-1, 1]).

use std::f64::consts::PI;

type V3 = [f32; 3];

/// `u × v` as Godot's `Vector3::cross` computes it.
pub fn cross(u: V3, v: V3) -> V3 {
    [
        (u[1] * v[2]) - (u[2] * v[1]),
        (u[2] * v[0]) - (u[0] * v[2]),
        (u[0] * v[1]) - (u[1] * v[0]),
    ]
}

/// Godot's `Vector3::normalized`: zero stays zero.
pub fn normalized(v: V3) -> V3 {
    let l2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    if l2 == 0.0 {
        return [0.0; 3];
    }
    let l = l2.sqrt();
    [v[0] / l, v[1] / l, v[2] / l]
}

/// fdlibm's `acosf` for `x` in [-1, 1].
pub fn acosf(x: f32) -> f32 {
    let pi = f32::from_bits(0x4049_0fda);
    let pio2_hi = f32::from_bits(0x3fc9_0fda);
    let pio2_lo = f32::from_bits(0x33a2_2168);
    let ps = [
        0x3e2a_aaab,
        0xbea6_b090,
        0x3e4e_0aa8,
        0xbd24_1146,
        0x3a4f_7f04,
        0x3811_ef08,
    ]
    .map(f32::from_bits);
    let qs = [0xc019_d139, 0x4001_572d, 0xbf30_3361, 0x3d9d_c62e].map(f32::from_bits);
    let r = |z: f32| {
        let p = z * (ps[0] + z * (ps[1] + z * (ps[2] + z * (ps[3] + z * (ps[4] + z * ps[5])))));
        let q = 1.0 + z * (qs[0] + z * (qs[1] + z * (qs[2] + z * qs[3])));
        p / q
    };
    let hx = x.to_bits() as i32;
    let ix = hx & 0x7fff_ffff;
    if ix == 0x3f80_0000 {
        return if hx > 0 { 0.0 } else { pi + 2.0 * pio2_lo };
    }
    if ix < 0x3f00_0000 {
        if ix <= 0x2300_0000 {
            return pio2_hi + pio2_lo;
        }
        return pio2_hi - (x - (pio2_lo - x * r(x * x)));
    }
    if hx < 0 {
        let z = (1.0 + x) * 0.5;
        let s = z.sqrt();
        let w = r(z) * s - pio2_lo;
        return pi - 2.0 * (s + w);
    }
    let z = (1.0 - x) * 0.5;
    let s = z.sqrt();
    let df = f32::from_bits(s.to_bits() & 0xffff_f000);
    let c = (z - df * df) / (s + df);
    let w = r(z) * s + c;
    2.0 * (df + w)
}

/// `Basis::get_axis_angle` of the rows `m`.
fn get_axis_angle(m: [V3; 3]) -> (V3, f32) {
    const CMP_EPSILON: f64 = 0.00001;
    let zero = |v: f32| v.abs() < CMP_EPSILON as f32;
    if zero(m[0][1] - m[1][0]) && zero(m[0][2] - m[2][0]) && zero(m[1][2] - m[2][1]) {
        let diagonal = zero(m[0][1])
            && zero(m[0][2])
            && zero(m[1][0])
            && zero(m[1][2])
            && zero(m[2][0])
            && zero(m[2][1]);
        if diagonal && f64::from((m[0][0] + m[1][1] + m[2][2] - 3.0).abs()) < 3.0 * CMP_EPSILON {
            return ([0.0, 1.0, 0.0], 0.0);
        }
        let (xx, yy, zz) = (
            (m[0][0] + 1.0) / 2.0,
            (m[1][1] + 1.0) / 2.0,
            (m[2][2] + 1.0) / 2.0,
        );
        let xy = (m[0][1] + m[1][0]) / 4.0;
        let xz = (m[0][2] + m[2][0]) / 4.0;
        let yz = (m[1][2] + m[2][1]) / 4.0;
        let h = std::f64::consts::FRAC_1_SQRT_2 as f32;
        let small = |v: f32| f64::from(v) < CMP_EPSILON;
        let axis = if xx > yy && xx > zz {
            if small(xx) {
                [0.0, h, h]
            } else {
                let x = xx.sqrt();
                [x, xy / x, xz / x]
            }
        } else if yy > zz {
            if small(yy) {
                [h, 0.0, h]
            } else {
                let y = yy.sqrt();
                [xy / y, y, yz / y]
            }
        } else if small(zz) {
            [h, h, 0.0]
        } else {
            let z = zz.sqrt();
            [xz / z, yz / z, z]
        };
        return (axis, PI as f32);
    }
    let d = [m[2][1] - m[1][2], m[0][2] - m[2][0], m[1][0] - m[0][1]];
    let mut s = f64::from((d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt());
    if s.abs() < CMP_EPSILON {
        s = 1.0;
    }
    let axis = d.map(|v| (f64::from(v) / s) as f32);
    let c = (m[0][0] + m[1][1] + m[2][2] - 1.0) / 2.0;
    let angle = if c < -1.0 {
        PI as f32
    } else if c > 1.0 {
        0.0
    } else {
        acosf(c)
    };
    (axis, angle)
}

/// `Vector3::octahedron_encode`.
fn octahedron_encode(v: V3) -> [f32; 2] {
    let l1 = v[0].abs() + v[1].abs() + v[2].abs();
    let n = [v[0] / l1, v[1] / l1, v[2] / l1];
    let sign = |x: f32| if x >= 0.0 { 1.0 } else { -1.0 };
    let o = if n[2] >= 0.0 {
        [n[0], n[1]]
    } else {
        [
            (1.0 - n[1].abs()) * sign(n[0]),
            (1.0 - n[0].abs()) * sign(n[1]),
        ]
    };
    o.map(|x| x * 0.5 + 0.5)
}

/// What Godot stores for the normal `n` and tangent `t` with handedness `w`: the axis's
/// two unorm16 words and the angle's.
pub fn encode(n: V3, t: V3, w: f32) -> [u16; 3] {
    let normal = normalized(n);
    let tangent = normalized(t);
    let binormal = normalized(cross(normal, tangent));
    let (axis, angle) = get_axis_angle([tangent, binormal, normal]);
    let a = f64::from(angle);
    let angle = if w < 0.0 {
        ((1.0 - a / PI) * 0.5).clamp(0.0, 0.49999) as f32
    } else {
        ((a / PI) * 0.5 + 0.5).clamp(0.500008, 1.0) as f32
    };
    let store = |v: f32| (v * 65535.0).clamp(0.0, 65535.0) as u16;
    let o = octahedron_encode(axis);
    [store(o[0]), store(o[1]), store(angle)]
}

/// The vertex stage's decode of the three unorm16 words, in f64: `n`, `t` and the
/// bitangent's sign.
pub fn decode(c: [u16; 3]) -> ([f64; 3], [f64; 3], f64) {
    let f = c.map(|c| f64::from(c) / 65535.0);
    let e = [f[0] * 2.0 - 1.0, f[1] * 2.0 - 1.0];
    let mut v = [e[0], e[1], 1.0 - e[0].abs() - e[1].abs()];
    let t = (-v[2]).max(0.0);
    let sign = |x: f64| {
        if x > 0.0 {
            1.0
        } else if x < 0.0 {
            -1.0
        } else {
            0.0
        }
    };
    v[0] += t * -sign(v[0]);
    v[1] += t * -sign(v[1]);
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let axis = v.map(|x| x / l);
    let s = if f[2] > 0.5 { 1.0 } else { -1.0 };
    let angle = (f[2] * 2.0 - 1.0).abs() * PI;
    let (sn, cs) = angle.sin_cos();
    let omc = axis.map(|a| (1.0 - cs) * a);
    let sa = axis.map(|a| sn * a);
    let tangent = [
        omc[0] * axis[0] + cs,
        omc[0] * axis[1] - sa[2],
        omc[0] * axis[2] + sa[1],
    ];
    let normal = [
        omc[2] * axis[0] - sa[1],
        omc[2] * axis[1] + sa[0],
        omc[2] * axis[2] + cs,
    ];
    (normal, tangent, s)
}
