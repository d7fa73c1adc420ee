//! What every tangent-frame codec shares: the frame a decoder returns, the handedness
//! rule, and the input policy for degenerate frames.
//!
//! A frame is a normal `n` and a tangent `t` whose `w` is the bitangent's sign, glTF's
//! convention: the bitangent is `cross(n, t.xyz)·t.w`. Encoders take `(n, t)`; decoders
//! return the struct [`FRAME`] of `n` (vec3) and `t` (vec4, `w` = ±1), so that a vertex
//! shader passes `t` on as a glTF tangent attribute would be.

use crate::codecs::core::codec::{Params, dequantize, unpack};
use crate::codecs::core::spec::Spec;
use crate::codecs::functions::decode_boxes::{fetched_range, field_codes};
use crate::codecs::functions::function::{Emitted, Enclose, Inputs, Role};
use crate::codecs::functions::words::{
    Bits, Declared, Lanes, Lanes8, Tracer, chained, declared, generic_function, trace_declared,
    tracer,
};
use crate::codecs::toolkit::quant::Quant;
use crate::model::avx2_lanes::F8;
use crate::model::deviant::Dev;
use crate::model::enclosure::Encl;
use crate::model::lanes::F4;
use crate::model::trace::{Shape, Tf, Value};
use crate::model::{Bool, Float, V2, V3, V4};
use std::sync::Arc;

/// The struct every frame decoder returns: `n` and `t` (with the sign in `w`).
pub const FRAME: Shape = Shape {
    name: "frame",
    fields: &["n", "t"],
};

/// The struct every frame's TBN decoder returns: the columns of the matrix that takes
/// tangent space to the frame's space, `t`, `b` and `n` (`mat3x3(t, b, n)`).
pub const TBN: Shape = Shape {
    name: "tbn",
    fields: &["t", "b", "n"],
};

/// The TBN columns of a decoded frame: `t.xyz`, the bitangent `cross(n, t.xyz)·t.w`
/// (glTF's), and `n`.
#[inline(always)]
pub fn tbn<F: Float>((n, t): (V3<F>, V4<F>)) -> (V3<F>, V3<F>, V3<F>) {
    let t3 = V3::new(t.x, t.y, t.z);
    (t3, cross(n, t3) * t.w, n)
}

/// The name of every frame spec's TBN decoder ([`tbn_function`]), by which
/// [`emitted`] gives it the enclosure of the TBN's nine outputs.
pub const TBN_DECODER: &str = "decode_tbn";

/// A frame spec's `decode_tbn`: its packed `decode` chained with [`tbn`]
/// ([`chained`]), so that the decoder's body is not compiled again; traced by `trace`,
/// [`tbn`] of the decoder's traced body.
pub(crate) fn tbn_function(decode: &Declared, trace: Tracer) -> Declared {
    let decode = decode.function();
    let step = generic_function!(
        "tbn",
        Role::Decode,
        Inputs::Frames,
        <F> [] |f: (V3<F>, V4<F>)| tbn(f)
    );
    let chain = chained(TBN_DECODER, Role::Decode, decode.inputs.clone(), decode, &step);
    Declared::new(chain, trace)
}

/// A frame format stored as its float form's fields, whose packed decoder is that float
/// form on the fetched fields (Filament's qtangent64, Godot's axis-angle): its five
/// functions are declared once, for every such format, by [`field_frame_emitted`].
pub trait FieldFrame: 'static {
    /// The float form: one value per field.
    type P<F: Float>: Params<F>;
    /// The fields, packed in two words.
    const QUANTS: &'static [Quant];
    /// The float form's parameter, as the emitted code names it.
    const PARAM: &'static str;
    /// The frame of the float form: `decode_float`.
    fn frame<F: Float>(p: Self::P<F>) -> (V3<F>, V4<F>);
    /// The float form of a frame: `encode_float`.
    fn encode_float<F: Float>(n: V3<F>, t: V4<F>) -> Self::P<F>;
    /// The packed code of a frame: `encode`.
    fn encode<F: Float>(n: V3<F>, t: V4<F>) -> V2<F::U>;
}

/// The packed decoder of a [`FieldFrame`]: the fields fetched, then its float form.
#[inline(always)]
pub fn field_decode<C: FieldFrame, F: Float>(code: V2<F::U>) -> (V3<F>, V4<F>) {
    let p: C::P<F> = dequantize(C::QUANTS, unpack::<F, C::P<F>, V2<F::U>>(C::QUANTS, code));
    C::frame(p.named_p(C::PARAM))
}

/// A [`FieldFrame`]'s [`Emitted`]: `decode_float`, `decode`, `decode_tbn`, `encode_float`
/// and `encode`, traced and evaluated from the same declarations.
pub(crate) fn field_frame_emitted<C: FieldFrame>(spec: &Spec) -> Emitted
where
    C::P<f32>: Bits,
    C::P<Dev>: Bits,
    C::P<F4>: Bits<Lanes>,
    C::P<F8>: Bits<Lanes8>,
    C::P<Tf>: Value,
{
    let decode = declared!(
        "decode",
        Role::Decode,
        Inputs::Codes(C::QUANTS.to_vec()),
        ["code"] => FRAME,
        <F> [] |c: V2<<F as Float>::U>| field_decode::<C, F>(c)
    );
    let decode_tbn = tbn_function(
        &decode,
        tracer!(["code"] => TBN, <F> [] |c: V2<<F as Float>::U>| tbn(field_decode::<C, F>(c))),
    );
    let functions = vec![
        declared!(
            "decode_float",
            Role::DecodeFloat,
            Inputs::FloatCodes(C::QUANTS.to_vec()),
            [C::PARAM] => FRAME,
            <F> [] |p: C::P<F>| C::frame(p)
        ),
        decode,
        decode_tbn,
        declared!(
            "encode_float",
            Role::EncodeFloat,
            Inputs::Frames,
            ["n", "t"],
            <F> [] |f: (V3<F>, V4<F>)| C::encode_float(f.0, f.1)
        ),
        declared!(
            "encode",
            Role::Encode,
            Inputs::Frames,
            ["n", "t"],
            <F> [] |f: (V3<F>, V4<F>)| C::encode(f.0, f.1)
        ),
    ];
    emitted(
        spec,
        functions,
        C::QUANTS,
        Some(|p: C::P<Encl>| C::frame(p)),
        |c: C::P<Encl>| C::frame(dequantize(C::QUANTS, c)),
        false,
    )
}

/// The doc comment of a frame family's `decode_tbn`.
pub fn tbn_doc() -> Vec<String> {
    vec![
        "In: as for decode.".into(),
        "Out: the TBN matrix's columns t, b, n, for mat3x3(t, b, n) (which takes tangent space to the frame's space): t and n as decode returns them, b = cross(n, t.xyz)·t.w (glTF's bitangent).".into(),
    ]
}

/// The handedness of `w`: -1 where `w < 0`, else +1, so that 0, -0 and NaN count as +1
/// (glTF's default handedness) and the sign survives any other value.
#[inline(always)]
pub fn handedness<F: Float>(w: F) -> F {
    F::sel(w.lt(F::c(0.0)), F::c(-1.0), F::c(1.0))
}

/// `a × b`, each lane `a.y·b.z - a.z·b.y` and so on, as Filament, Godot and glam write it.
#[inline(always)]
pub fn cross<F: Float>(a: V3<F>, b: V3<F>) -> V3<F> {
    V3::new(
        a.y * b.z - a.z * b.y,
        a.z * b.x - a.x * b.z,
        a.x * b.y - a.y * b.x,
    )
}

/// The third and first columns of the rotation matrix of the unit quaternion `q`, `n` and
/// `t`, as Filament's `toTangentFrame` (shaders/src/common_math.glsl) computes them: written as its vector expressions
/// evaluate lane by lane, without its additions of literal zeros (which change nothing
/// but the sign of a zero result).
#[inline(always)]
pub fn rotation_columns<F: Float>(q: V4<F>) -> (V3<F>, V3<F>) {
    let two = F::c(2.0);
    let (x2, y2, z2) = ((two * q.x).named("x2"), (two * q.y).named("y2"), (two * q.z).named("z2"));
    let n = V3::new(
        x2 * q.z + y2 * q.w,
        y2 * q.z - x2 * q.w,
        F::c(1.0) - x2 * q.x - y2 * q.y,
    );
    let t = V3::new(
        F::c(1.0) - y2 * q.y - z2 * q.z,
        y2 * q.x + z2 * q.w,
        z2 * q.x - y2 * q.w,
    );
    (n, t)
}

/// `a · b`, summed left to right.
#[inline(always)]
pub fn dot<F: Float>(a: V3<F>, b: V3<F>) -> F {
    a.x * b.x + a.y * b.y + a.z * b.z
}

/// Whether a squared length is one the frame arithmetic can use: at least `2^-60` (a
/// tangent orthogonalised against a unit normal keeps a component of at least `2^-30`
/// off it) and finite. Zero, NaN and infinite lengths are not.
#[inline(always)]
pub fn usable<F: Float>(length2: F) -> F::B {
    length2
        .ge(F::c(f32::from_bits(0x2180_0000)))
        .and(length2.le(F::c(f32::MAX)))
}

/// The normal an encoder works with: `n` itself where its squared length is within
/// `[2^-20, 2^20]` (every practical input, so an engine's arithmetic sees it unchanged),
/// else `n` divided by its largest magnitude; +Z where `|x| + |y| + |z|` is below `2^-60`
/// (zero, denormal), infinite or NaN.
#[inline(always)]
pub fn policy_normal<F: Float>(n: V3<F>) -> V3<F> {
    let a = n.abs();
    let m = a.x.at_least(a.y).at_least(a.z).named("largest");
    // The sum carries a NaN or an infinity of any component, which a maximum may drop.
    let l1 = a.x + a.y + a.z;
    let valid = l1.ge(F::c(f32::from_bits(0x2180_0000))).and(l1.le(F::c(f32::MAX)));
    let l2 = n.length_squared();
    let plain = l2
        .ge(F::c(f32::from_bits(0x3580_0000)))
        .and(l2.le(F::c(f32::from_bits(0x4980_0000))));
    let scaled = n * (F::c(1.0) / F::sel(valid, m, F::c(1.0)));
    let z = V3::new(F::c(0.0), F::c(0.0), F::c(1.0));
    V3::sel_all(valid, V3::sel_all(plain, n, scaled), z)
}

/// The canonical tangent of the normal `n` (any nonzero length): the first vector of
/// Duff et al.'s orthonormal basis ("Building an Orthonormal Basis, Revisited", JCGT
/// 2017) of `n/|n|`, `(1 + s·x²·a, s·x·y·a, -s·x)` with `s` = -1 where `z < 0`, else +1,
/// and `a = -1/(s + z)`. What a zero, NaN, infinite or parallel tangent is replaced by.
#[inline(always)]
pub fn canonical_tangent<F: Float>(n: V3<F>) -> V3<F> {
    let u = n * (F::c(1.0) / n.length_squared().sqrt());
    let s = F::sel(u.z.lt(F::c(0.0)), F::c(-1.0), F::c(1.0));
    let a = -(F::c(1.0) / (s + u.z));
    let sx = s * u.x;
    V3::new(F::c(1.0) + sx * u.x * a, sx * u.y * a, -sx)
}

/// Box evaluations for a frame decoder's bound. Its enclosures over boxes of codes stay
/// wider than a single code's (the basis or quaternion of a box is a union), so the
/// search never stops before its budget: at a sixth of the default, each decoder's bound
/// costs a sixth of the time and comes out a little looser.
const FRAME_BUDGET: usize = 100_000;

/// A decoded frame's enclosure: `n` and `t`.
type EnclosedFrame = (V3<Encl>, V4<Encl>);

/// A frame spec's [`Emitted`]: its `declared` functions, traced in order, whose decoders get
/// enclosures for their proven bounds ([`crate::measure::decode_bound`]) over boxes of the
/// `quants` fields: `decode_float` (where the spec has one) through `fetched` on the
/// fetched values, `decode` and `decode_tbn` (nine outputs, [`tbn`]) through `codes` on
/// the integer codes. `portable`: whether the
/// packed encoder is decided exactly (the engines' arithmetic is not).
pub(crate) fn emitted<P: Params<Encl> + 'static>(
    spec: &Spec,
    declared: Vec<Declared>,
    quants: &'static [Quant],
    fetched: Option<fn(P) -> EnclosedFrame>,
    codes: impl Fn(P) -> EnclosedFrame + Send + Sync + 'static,
    portable: bool,
) -> Emitted {
    let lanes = |(n, t): EnclosedFrame| {
        let mut v = n.to_array().to_vec();
        v.extend(t.to_array());
        v
    };
    // A TBN decoder's nine outputs: the frame's columns.
    let tbn_lanes = |f: EnclosedFrame| {
        let (t, b, n) = tbn(f);
        [t, b, n].iter().flat_map(|c| c.to_array()).collect::<Vec<_>>()
    };
    let enclose = |eval: crate::codecs::functions::function::BoxEval| {
        Some(Enclose {
            eval,
            whole_field: None,
            unread: &[],
            fixed: Vec::new(),
            budget: Some(FRAME_BUDGET),
            parts: None,
        })
    };
    let (module, mut functions) = trace_declared(declared);
    let codes = Arc::new(codes);
    for f in &mut functions {
        match f.role {
            Role::DecodeFloat => {
                let frame = fetched.expect("a float decoder's enclosure");
                f.enclose = enclose(Arc::new(move |r: &[(i64, i64)]| {
                    lanes(frame(P::build(|i| fetched_range(quants[i], r[i]))))
                }));
            }
            Role::Decode => {
                let frame = codes.clone();
                let out = if f.name == TBN_DECODER {
                    tbn_lanes
                } else {
                    lanes
                };
                f.enclose = enclose(Arc::new(move |r: &[(i64, i64)]| {
                    out(frame(P::build(|i| field_codes(quants[i], r[i]))))
                }));
            }
            _ => {}
        }
    }
    Emitted {
        module,
        functions,
        namespace: spec.id(),
        portable_encoder: portable,
        cpu: Vec::new(),
    }
}
