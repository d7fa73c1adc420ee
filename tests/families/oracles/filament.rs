//! Oracle: Filament's quaternion tangent frames, re-expressed here in plain scalar Rust
//! (no Filament code is used).
//!
//! Source followed, repository `google/filament`:
//! * `libs/math/include/math/mat3.h` at `03c2a9020637a1aa52ef25d5eb9ebc1d972c2a96`
//!   (identical at `bd7247c6ca1f59e09af0c97c8a74b321a2928ddf`): `TMat33::packTangentFrame`;
//!   a `TMat33` is built from columns, `m[c][r]`.
//! * `libs/math/include/math/TMatHelpers.h` at `0a27487808117407a549021483ef9997928dd919`:
//!   `extractQuat` (the trace's sign, then the largest diagonal element, `next = {1, 2, 0}`).
//! * `libs/math/include/math/TQuatHelpers.h` at `0fbc6658a23bdf75308edef6cb00f416acf4965b`:
//!   `normalize` (`length(q) ? q / length(q) : identity`, the division per component,
//!   `dot` summed x, y, z, w in order) and `positive` (`q.w < 0 ? -q : q`).
//! * `libs/math/include/math/norm.h` at `3abc492371d2496f2c6a64075df3344b214f85d5`:
//!   `packSnorm16(v) = int16(round(clamp(v, -1, 1) * 32767))`, `std::round` halving away
//!   from zero.
//! * `libs/geometry/src/SurfaceOrientation.cpp` at `11119524463c5f9da5e28d507a2351d2c6ee90a8`:
//!   `buildWithSuppliedTangents`: `b = w > 0 ? cross(t, n) : cross(n, t)`, then
//!   `t = w > 0 ? cross(n, b) : cross(b, n)`, then `packTangentFrame({t, b, n})`.
//! * `shaders/src/common_math.glsl` at `0157671288886439f9e36c3225fee7ce0c8ba8d2`:
//!   `toTangentFrame(q, n, t)`, vector expressions evaluated lane by lane, left to right.
//! * `shaders/src/surface_getters.vs` at `0ca04f04d18e61a10c299b5cb0872fc6ca2b2035`: the
//!   fetch `float4(tangent) * (1.0 / 32767.0)`; `shaders/src/shading_parameters.fs` at
//!   `078c585cc28f7bc69896c0af03ade58bc83a722f`: the bitangent's sign
//!   `q.w < 0.0 ? -1.0 : 1.0`.

type V3 = [f32; 3];

fn cross(u: V3, v: V3) -> V3 {
    [
        u[1] * v[2] - v[1] * u[2],
        u[2] * v[0] - v[2] * u[0],
        u[0] * v[1] - v[0] * u[1],
    ]
}

fn dot(u: V3, v: V3) -> f32 {
    let mut r = 0.0f32;
    for i in 0..3 {
        r += u[i] * v[i];
    }
    r
}

/// `extractQuat` of the matrix with columns `m`, as `[x, y, z, w]`.
fn extract_quat(m: [V3; 3]) -> [f32; 4] {
    let mut q = [0.0f32; 4];
    let trace = m[0][0] + m[1][1] + m[2][2];
    if trace > 0.0 {
        let mut s = (trace + 1.0).sqrt();
        q[3] = 0.5 * s;
        s = 0.5 / s;
        q[0] = (m[1][2] - m[2][1]) * s;
        q[1] = (m[2][0] - m[0][2]) * s;
        q[2] = (m[0][1] - m[1][0]) * s;
    } else {
        let mut i = 0;
        if m[1][1] > m[0][0] {
            i = 1;
        }
        if m[2][2] > m[i][i] {
            i = 2;
        }
        const NEXT: [usize; 3] = [1, 2, 0];
        let j = NEXT[i];
        let k = NEXT[j];
        let mut s = ((m[i][i] - (m[j][j] + m[k][k])) + 1.0).sqrt();
        q[i] = 0.5 * s;
        if s != 0.0 {
            s = 0.5 / s;
        }
        q[3] = (m[j][k] - m[k][j]) * s;
        q[j] = (m[i][j] + m[j][i]) * s;
        q[k] = (m[i][k] + m[k][i]) * s;
    }
    q
}

/// `packTangentFrame(m)` with 16-bit storage.
pub fn pack_tangent_frame(m: [V3; 3]) -> [f32; 4] {
    let mut q = extract_quat([m[0], cross(m[2], m[0]), m[2]]);
    let length = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]).sqrt();
    q = if length != 0.0 {
        q.map(|c| c / length)
    } else {
        [0.0, 0.0, 0.0, 1.0]
    };
    if q[3] < 0.0 {
        q = q.map(|c| -c);
    }
    let bias = 1.0f32 / ((1 << 15) - 1) as f32;
    if q[3] < bias {
        q[3] = bias;
        let factor = (1.0 - f64::from(bias) * f64::from(bias)).sqrt() as f32;
        for c in &mut q[..3] {
            *c *= factor;
        }
    }
    if dot(cross(m[0], m[2]), m[1]) < 0.0 {
        q = q.map(|c| -c);
    }
    q
}

/// `packSnorm16`.
pub fn pack_snorm16(v: f32) -> i16 {
    (v.clamp(-1.0, 1.0) * 32767.0).round() as i16
}

/// `buildWithSuppliedTangents` for one vertex: the normal, the tangent and its `w`, as
/// the SHORT4 Filament stores.
pub fn encode(n: V3, t: V3, w: f32) -> [i16; 4] {
    let b = if w > 0.0 { cross(t, n) } else { cross(n, t) };
    let t = if w > 0.0 { cross(n, b) } else { cross(b, n) };
    pack_tangent_frame([t, b, n]).map(pack_snorm16)
}

/// `toTangentFrame(q, n, t)` and the bitangent's sign: `(n, t, sign)`.
pub fn to_tangent_frame(q: [f32; 4]) -> (V3, V3, f32) {
    let [x, y, z, w] = q;
    // vec3(0, 0, 1) + vec3(2, -2, -2) * q.x * q.zwx + vec3(2, 2, -2) * q.y * q.wzy
    let n = [
        (0.0 + 2.0 * x * z) + 2.0 * y * w,
        (0.0 + -2.0 * x * w) + 2.0 * y * z,
        (1.0 + -2.0 * x * x) + -2.0 * y * y,
    ];
    // vec3(1, 0, 0) + vec3(-2, 2, -2) * q.y * q.yxw + vec3(-2, 2, 2) * q.z * q.zwx
    let t = [
        (1.0 + -2.0 * y * y) + -2.0 * z * z,
        (0.0 + 2.0 * y * x) + 2.0 * z * w,
        (0.0 + -2.0 * y * w) + 2.0 * z * x,
    ];
    (n, t, if w < 0.0 { -1.0 } else { 1.0 })
}

/// The fetch of a stored component: `float(c) * (1.0 / 32767.0)`.
pub fn fetch(c: i16) -> f32 {
    f32::from(c) * (1.0 / 32767.0)
}
