//! Quaternion tangent frames. `qtangent64` is Filament's: `packTangentFrame` (libs/math/include/math/mat3.h)
//! stored as SHORT4 by `packSnorm16` (libs/math/include/math/norm.h), as
//! `SurfaceOrientation::buildWithSuppliedTangents` (libs/geometry/src/SurfaceOrientation.cpp)
//! builds them from a normal and a glTF tangent, and decoded by `toTangentFrame`
//! (shaders/src/common_math.glsl) with the bitangent sign of `q.w`
//! (shaders/src/shading_parameters.fs).
//!
//! Every step is Filament's arithmetic, in its order: the bitangent `b = w > 0 ? t × n :
//! n × t` and the tangent made orthogonal as `w > 0 ? n × b : b × n`; the quaternion of
//! the matrix with columns `(t, n × t, n)` by `extractQuat` (the trace's sign, then the
//! largest diagonal element), divided by its length, made positive (`w ≥ 0`), `w` raised
//! to `bias = 1/32767` with `xyz` scaled by `sqrt(1 - bias²)`, and negated where
//! `(t × n)·b < 0`, which is where the frame is right-handed (`w > 0`); then
//! `round(clamp(q, -1, 1)·32767)` with halves away from zero. The input policy of the
//! frame codecs ([`crate::codecs::frames::frame`]) is applied first: it changes nothing a
//! Filament user passes (a unit normal, a tangent off it, `w = ±1`), and gives the
//! degenerate frames Filament leaves undefined (zero or NaN vectors, a tangent parallel
//! to the normal, `w` of 0 or NaN) a stated frame.
//!
//! `qtangent32` is the same rotation in 32 bits, smallest three, with a portable encoder
//! of its own ([`crate::codecs::frames::smallest_three`]); its decoder ends in the same
//! rotation columns as Filament's ([`crate::codecs::frames::frame::rotation_columns`]).

use crate::codecs::functions::function::{Emitted, Inputs, Role};
use crate::model::enclosure::Encl;
use crate::codecs::core::info::{Info, Sizes, FloatForm};
use crate::codecs::core::spec::{Family, Spec, Tracing};
use crate::codecs::core::codec::pack;
use crate::codecs::functions::words::{declared, tracer};
use crate::codecs::frames::frame::{
    FieldFrame, FRAME, TBN, TBN_DECODER, canonical_tangent, cross, dot, field_frame_emitted, handedness, policy_normal, rotation_columns,
    tbn, tbn_doc, tbn_function, usable,
};
use crate::codecs::frames::smallest_three;
use crate::codecs::toolkit::quant::{Quant, round_half_away};
use crate::model::num::helper;
use crate::model::{Bool, Float, V2, V3, V4};

/// The stored fields: the quaternion's x, y, z and w as snorm16, in that order.
const QUANTS: [Quant; 4] = [Quant::Snorm(16); 4];

pub static QTANGENT: QTangent = QTangent {
    info: Info {
        name: "qtangent",
        title: "quaternion tangent frame (64 bits: Filament's SHORT4; 32: smallest three)",
        sizes: Sizes::Total(&[32, 64]),
        domain: None,
        source: "Filament at google/filament 03c2a90: libs/math/include/math/mat3.h (packTangentFrame), TMatHelpers.h (extractQuat), norm.h (packSnorm16), libs/geometry/src/SurfaceOrientation.cpp (buildWithSuppliedTangents), shaders/src/common_math.glsl (toTangentFrame); 32 bits: smallest three (the largest component dropped, its index stored)",
        edge_policy: "Filament's arithmetic for every frame it defines; w of 0 or NaN counts as +1; a normal with |x| + |y| + |z| below 2^-60 (zero, denormal), NaN or infinite encodes as +Z; a normal of squared length outside [2^-20, 2^20] is first divided by its largest component; a tangent whose orthogonalised squared length is below 2^-60 or not finite (zero, NaN, infinite, parallel to the normal) is replaced by the canonical tangent of Duff et al. (2017)",
        decode_note: "Filament's toTangentFrame on the fetched quaternion, not renormalized: n and t are unit and orthogonal to the quaternion's quantization (a few 2^-15)",
        // No `guarantee` option: qtangent64 is Filament's arithmetic (the lean tier,
        // `ieee::asked` by its engine), qtangent32 portable.
        float_form: FloatForm::Absent,
        options: &[],
    },
};

/// The qtangent family: Filament's 64 bits, and smallest three in 32.
pub struct QTangent {
    info: Info,
}

impl Family for QTangent {
    fn info(&self) -> &Info {
        &self.info
    }
    /// At 64 bits Filament's encoder is the only one: the codes are Filament's. At 32 bits
    /// not offered yet: a search among the neighbouring codes of the three kept
    /// components would lower the error; no precise spec fits the suite's time budget.
    fn precise(&self) -> bool {
        false
    }
    fn emitted(&self, spec: &Spec, _: Tracing) -> Emitted {
        if spec.bits() == 32 {
            emitted32(spec)
        } else {
            field_frame_emitted::<QTangent>(spec)
        }
    }
    fn engine(&self, spec: &Spec) -> Option<&'static str> {
        (spec.bits() == 64).then_some("Filament")
    }
    fn function_doc(&self, spec: &Spec, name: &str) -> Option<Vec<String>> {
        if spec.bits() == 32 {
            return Some(doc32(name));
        }
        const CODE: &str = "word 0 holds x (bits 0–15) and y (bits 16–31), word 1 z and w, each snorm16 (two's complement): Filament's SHORT4 as stored";
        let input = format!(
            "In: a normal n and a tangent t whose w is the bitangent's sign (glTF's convention: bitangent = cross(n, t.xyz)·t.w); {}.",
            self.info.edge_policy
        );
        Some(match name {
            TBN_DECODER => tbn_doc(),
            "decode_float" => vec!["In: the quaternion (x, y, z, w) in [-1, 1], as a snorm16 fetch of the code returns it.".into()],
            "decode" => vec![
                format!("In: the packed code, two 32-bit words: {CODE}."),
                format!("Out: the frame: n, and t with the bitangent's sign (±1) in t.w; {}.", self.info.decode_note),
            ],
            "encode_float" => vec![
                input,
                "Out: Filament's packTangentFrame quaternion (x, y, z, w) in [-1, 1], unquantized: w ≥ 1/32767 for a right-handed frame (t.w ≥ 0), w ≤ -1/32767 for a reflected one. A t.w of 0 counts as right-handed, where Filament's SurfaceOrientation (its test is w > 0) builds the reflected frame: write ±1 where both must agree.".into(),
            ],
            _ => vec![
                "In: as for encode_float.".into(),
                format!("Out: the packed code, two 32-bit words: {CODE}; packSnorm16 of the quaternion, round(clamp(q, -1, 1)·32767) with halves away from zero."),
            ],
        })
    }
    fn frames(&self) -> bool {
        true
    }
    /// Filament's cross products and `extractQuat`'s sums of products: Mesa's OpenGL
    /// compiler fuses them without `precise` (`unitpack verify qtangent64` on Mesa
    /// 22.3.6's llvmpipe: 42 of 65536 sampled codes moved). qtangent32's encoder is exact.
    fn contracted(&self, spec: &Spec) -> bool {
        spec.bits() == 64
    }
}

/// Filament's `extractQuat` of the matrix whose columns are `m` (`m[column][row]`), as
/// `(x, y, z, w)`: every branch computed, the taken one selected.
#[inline(always)]
fn extract_quat<F: Float>(m: [V3<F>; 3]) -> V4<F> {
    let at = {
        #[inline(always)]
        |c: usize, r: usize| m[c].to_array()[r]
    };
    let half = F::c(0.5);
    let trace = (at(0, 0) + at(1, 1) + at(2, 2)).named("trace");
    // A positive trace.
    // Filament's `0.5/s` for `s = sqrt(a)`, written `1/sqrt(4a)`: the same value, since
    // scaling by 4 and 2 is exact. Drivers (Mesa's NIR) compute `1/sqrt` as a reciprocal
    // root, and rewrite `sqrt(a)` beside `1/sqrt(a)` as `a·rsq(a)`, which differs from
    // the root by an ulp or more: a root of `4a` shares nothing with the root of `a`.
    let a = trace + F::c(1.0);
    let s = a.sqrt();
    let r = F::c(1.0) / (a * F::c(4.0)).sqrt();
    let by_trace = V4::new(
        (at(1, 2) - at(2, 1)) * r,
        (at(2, 0) - at(0, 2)) * r,
        (at(0, 1) - at(1, 0)) * r,
        half * s,
    );
    // Otherwise from the largest diagonal element `i`, with `j` and `k` the next ones.
    let by_diagonal = {
        #[inline(always)]
        |i: usize| {
            let (j, k) = ((i + 1) % 3, (i + 2) % 3);
            let a = (at(i, i) - (at(j, j) + at(k, k))) + F::c(1.0);
            let s = a.sqrt();
            let r = F::sel(s.eq(F::c(0.0)), s, F::c(1.0) / (a * F::c(4.0)).sqrt());
            let mut q = [F::c(0.0); 4];
            q[i] = half * s;
            q[3] = (at(j, k) - at(k, j)) * r;
            q[j] = (at(i, j) + at(j, i)) * r;
            q[k] = (at(i, k) + at(k, i)) * r;
            V4::from_array(q)
        }
    };
    let one = at(1, 1).gt(at(0, 0));
    let d = F::sel(one, at(1, 1), at(0, 0));
    let two = at(2, 2).gt(d);
    let by_diagonal = V4::sel_all(
        two,
        by_diagonal(2),
        V4::sel_all(one, by_diagonal(1), by_diagonal(0)),
    );
    V4::sel_all(trace.gt(F::c(0.0)), by_trace, by_diagonal)
}

/// `packTangentFrame` of the frame `(n, t)` after the input policy: the quaternion
/// Filament stores, in `[-1, 1]` (`encode_float`).
#[inline(always)]
pub fn pack_tangent_frame<F: Float>(n: V3<F>, t: V4<F>) -> V4<F> {
    let positive = handedness(t.w).gt(F::c(0.0));
    let n = policy_normal(n).named("n");
    // SurfaceOrientation's bitangent and orthogonal tangent.
    let orthogonal = {
        #[inline(always)]
        |t: V3<F>| {
            let b = V3::sel_all(positive, cross(t, n), cross(n, t)).named("b");
            let t = V3::sel_all(positive, cross(n, b), cross(b, n)).named("t");
            (b, t)
        }
    };
    let (_, first) = orthogonal(V3::new(t.x, t.y, t.z));
    let t = V3::sel_all(
        usable(first.length_squared()),
        V3::new(t.x, t.y, t.z),
        canonical_tangent(n),
    );
    let (b, t) = orthogonal(t);
    let q = extract_quat([t, cross(n, t), n]).named("q");
    // normalize: q / length(q), or the identity where the length is 0.
    let l = q.length_squared().sqrt().named("norm");
    let some = l.eq(F::c(0.0)).not();
    let q = V4::sel_all(
        some,
        q / V4::splat(F::sel(some, l, F::c(1.0))),
        V4::new(F::c(0.0), F::c(0.0), F::c(0.0), F::c(1.0)),
    );
    // positive: w ≥ 0.
    let q = V4::sel_all(q.w.lt(F::c(0.0)), -q, q).named("q");
    // w never 0: raised to the bias. Filament then scales xyz by `sqrt(1 - bias²)`
    // evaluated in f64, which rounds to 1 in f32: xyz is unchanged.
    let bias = 1.0f32 / 32767.0;
    assert_eq!((1.0 - f64::from(bias) * f64::from(bias)).sqrt() as f32, 1.0);
    let q = V4::sel_all(q.w.lt(F::c(bias)), V4::new(q.x, q.y, q.z, F::c(bias)), q);
    // A reflection ((t × n)·b < 0) makes w negative.
    V4::sel_all(dot(cross(t, n), b).lt(F::c(0.0)), -q, q)
}

/// `packSnorm16` of the quaternion, the four words packed (x and y in the first, z and w
/// in the second, each the low half first).
#[inline(always)]
pub fn encode<F: Float>(n: V3<F>, t: V4<F>) -> V2<F::U> {
    let q = helper!("encode_float" => pack_tangent_frame(n, t));
    let codes = q.map(
        #[inline(always)]
        |x| round_half_away(x.clamped(F::c(-1.0), F::c(1.0)) * F::c(32767.0)),
    );
    pack(&QUANTS, codes.named("codes"))
}

/// Filament's `toTangentFrame(q, n, t)` and the sign of `q.w` as `t.w`, for fetched
/// quaternion components (`decode_float`).
#[inline(always)]
pub fn to_tangent_frame<F: Float>(q: V4<F>) -> (V3<F>, V4<F>) {
    let (n, t) = rotation_columns(q);
    (n, V4::new(t.x, t.y, t.z, handedness(q.w)))
}


/// Filament's SHORT4 quaternion: the packed decoder is [`to_tangent_frame`] on the
/// fetched fields.
impl FieldFrame for QTangent {
    type P<F: Float> = V4<F>;
    const QUANTS: &'static [Quant] = &QUANTS;
    const PARAM: &'static str = "q";
    #[inline(always)]
    fn frame<F: Float>(q: V4<F>) -> (V3<F>, V4<F>) {
        to_tangent_frame(q)
    }
    #[inline(always)]
    fn encode_float<F: Float>(n: V3<F>, t: V4<F>) -> V4<F> {
        pack_tangent_frame(n, t)
    }
    #[inline(always)]
    fn encode<F: Float>(n: V3<F>, t: V4<F>) -> V2<F::U> {
        encode(n, t)
    }
}

/// The doc comments of qtangent32's functions.
fn doc32(name: &str) -> Vec<String> {
    const CODE: &str = "u32: the three kept components, √2 times each as snorm10 (bits 0–9), snorm10 (bits 10–19) and snorm9 (bits 20–28), in x, y, z, w order; the dropped (largest) component's index, 0–3 for x–w (bits 29–30); the sign (bit 31, set where reflected)";
    match name {
        TBN_DECODER => tbn_doc(),
        "decode" => vec![
            format!("In: the packed code, {CODE}."),
            format!("Out: the frame: n, and t with the bitangent's sign (±1) in t.w; {}.", smallest_three::DECODE_NOTE),
        ],
        _ => vec![
            format!("In: a normal n and a tangent t whose w is the bitangent's sign (glTF's convention: bitangent = cross(n, t.xyz)·t.w); {}.", smallest_three::EDGE_POLICY),
            format!("Out: the packed code, {CODE}: the unit quaternion of the rotation whose columns are (t, n × t, n), with its largest component positive."),
        ],
    }
}

/// qtangent32's functions: `decode`, `decode_tbn` and `encode`, on one-word codes.
fn emitted32(spec: &Spec) -> Emitted {
    use smallest_three::{QUANTS, decode, decode_fields, encode};
    let packed_decode = declared!(
        "decode",
        Role::Decode,
        Inputs::Codes(QUANTS.to_vec()),
        ["code"] => FRAME,
        <F> [] |c: <F as Float>::U| decode::<F, <F as Float>::U>(c)
    );
    let decode_tbn = tbn_function(
        &packed_decode,
        tracer!(["code"] => TBN, <F> [] |c: <F as Float>::U| tbn(decode::<F, <F as Float>::U>(c))),
    );
    let functions = vec![
        packed_decode,
        decode_tbn,
        declared!(
            "encode",
            Role::Encode,
            Inputs::Frames,
            ["n", "t"],
            <F> [] |f: (V3<F>, V4<F>)| encode::<F, <F as Float>::U>(f.0, f.1)
        ),
    ];
    crate::codecs::frames::frame::emitted(
        spec,
        functions,
        &QUANTS,
        None,
        |c: V4<Encl>| decode_fields(c),
        true,
    )
}
