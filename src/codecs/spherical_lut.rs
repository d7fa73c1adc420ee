//! Spherical coordinates through lookup textures (first seed, method 3a): method 3's
//! `((atan2(y, x)/π, z) + 1)·½` with the arctangent and the sine and cosine replaced by
//! two 256×256 textures, so that encoding and decoding are one fetch each and almost no
//! arithmetic.
//!
//! A shader cannot call a texture it was not given, so the emitted functions are the
//! pieces around the fetches:
//!
//! ```text
//! encode:  t = atan_texel(v)            integer texel of the atan LUT (textureLoad / texelFetch)
//!          a = atan_lut[t].r            the fetched unorm8 value
//!          code = encode(v, a)          x = a's byte, y = z·½ + ½ as unorm8 (R8G8, x lowest)
//! decode:  t = sincos_texel(code)       integer texel of the sin/cos LUT
//!          n = decode_float(sincos_lut[t].rgb)    rgb·2 - 1
//! ```
//!
//! `atan_texel` is the texel that nearest sampling at the seed's coordinates `n.xy·½ + ½`
//! selects, `floor(256·(n.xy·½ + ½))` clamped to 255, decided exactly from the input
//! (never through a rounded quotient), so every implementation reads the same texel.
//! Sampling at the texel's centre, `(t + ½)/256`, fetches the same texel with nearest
//! filtering.
//!
//! The tables ([`atan_lut`], [`sincos_lut`]) are computed in f64 and rounded to the
//! nearest byte (ties up, a value within `1e-9` of a tie counting as one); `unitpack generate` writes them to `generated/lut/` as PNG
//! and as raw bytes, row `j` (the texel's y) after row `j - 1`:
//! - `lut=seed` (the default) is the seed's UnityScript: the atan table at texel corners,
//!   `A(i, j) = (atan2(j/128 - 1, i/128 - 1) + π)/2π`, and the sin/cos table at
//!   `φ = (i/128 - 1)·π`, `z = j/128 - 1`, storing `(cos φ·r, sin φ·r, z)·½ + ½` with
//!   `r = sqrt(1 - z²)`. Its decode reads codes as `c/128 - 1` where the encoder wrote
//!   `c/127.5 - 1`, which is why the seed measures it below method 3 (PSNR 36.5 dB against
//!   40.2): near the poles the mismatch costs several degrees.
//! - `lut=matched`: the atan table at texel centres `((i + ½)/128 - 1, (j + ½)/128 - 1)`,
//!   and the sin/cos table at `φ = (i/127.5 - 1)·π`, `z = j/127.5 - 1`, the inverse of the
//!   encoder's own quantization. Same functions, same textures' sizes and formats.
//!
//! The atan table is single-channel (upload as R8 unorm; the seed's Alpha8), the sin/cos
//! table RGBA8 with A = 255. Both are sampled with nearest filtering and clamping (or
//! read with integer coordinates). On the CPU (`Batch`, the CLI) the encoder and decoder
//! fetch from the same tables in memory, a texel's byte `c` read as `c·(1/255)` as
//! lavapipe's texture unit returns it.

use super::codec::Domain;
use super::exact::{canonical_or_z, decided, length2, past_root_ratio, unorm_sqrt_ratio};
use super::family::{Family, Info, OptDesc, OptKind, Sizes, Table};
use super::functions::{Emitted, Enclose, Extra, Inputs, Role, fetched_range, function, through_table};
use super::quant::Quant;
use super::spec::Spec;
use crate::model::deviant::Dev;
use crate::model::enclosure::Encl;
use crate::model::lanes::F4;
use crate::model::trace::{Tf, define, trace_module};
use crate::model::{Float, Uint, V2, V3};
use std::sync::{Arc, OnceLock};

pub static FAMILY: SphericalLutFamily = SphericalLutFamily;

pub struct SphericalLutFamily;

/// Texels per side of both tables.
pub const SIZE: usize = 256;

/// A table texel's channel, and each stored code's field.
const BYTE: Quant = Quant::Unorm(8);

static OPTIONS: &[OptDesc] = &[OptDesc {
    key: "lut",
    help: "the tables' content: seed = the seed's UnityScript (atan at texel corners; its sin/cos table reads codes as c/128 - 1, the encoder writes c/127.5 - 1); matched = atan at texel centres and a sin/cos table that inverts the encoder's quantization",
    kind: OptKind::Choice(&["seed", "matched"]),
}];

static INFO: Info = Info {
    name: "spherical_lut",
    title: "azimuth and z through an atan2 and a sin/cos lookup texture (256×256)",
    sizes: Sizes::Total(&[16]),
    domain: Some(Domain::Sphere),
    precise: false,
    source: "Pranckevičius method 3a",
    edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z (atan texel (128, 128))",
    decode_note: "the sin/cos table's texel·2 - 1, not renormalized: unit length to within the table's rounding (each component within 1/255)",
    options: OPTIONS,
};

impl Family for SphericalLutFamily {
    fn info(&self) -> &'static Info {
        &INFO
    }
    fn variants(&self) -> &'static [&'static str] {
        &["spherical_lut16:lut=matched"]
    }
    fn emitted(&self, spec: &Spec) -> Emitted {
        emitted(&spec.id(), SphericalLut::of(spec))
    }
    fn tables(&self, spec: &Spec) -> Vec<Table> {
        let lut = SphericalLut::of(spec);
        let table = |what: &str, channels: u8, bytes: Vec<u8>| Table {
            stem: format!("{}_{what}", spec.id()),
            width: SIZE as u32,
            height: SIZE as u32,
            channels,
            bytes,
        };
        vec![
            table("atan", 1, lut.atan().to_vec()),
            table("sincos", 4, lut.sincos().concat()),
        ]
    }
    fn function_doc(&self, name: &str) -> Option<Vec<String>> {
        let lines: &[&str] = match name {
            "atan_texel" => &[
                "In: any vector; input is normalized first, zero, NaN and infinite input read the texel of +Z.",
                "Out: the integer texel (x, y) of the 256×256 atan table to read with textureLoad / texelFetch / Load: floor(256·(n.xy·½ + ½)) clamped to 255, the texel nearest sampling at n.xy·½ + ½ selects, decided exactly (the same texel on every implementation). Sample at (t + ½)/256 for the same texel through a nearest sampler.",
            ],
            "encode" => &[
                "In: any vector, and `fetched`, the atan table's value at atan_texel(v) as a unorm8 fetch returns it (c/255).",
                "Out: the packed code, uint (bits 0–7: x, the fetched byte; bits 8–15: y, z·½ + ½ of the normalized input as unorm8, rounded exactly).",
            ],
            "encode_float" => &[
                "In: any vector, and `fetched` as for encode.",
                "Out: (fetched, z·½ + ½) of the normalized input, unquantized, for an RG8 unorm render target.",
            ],
            "sincos_texel" => &[
                "In: a packed code (bits 0–7 x, 8–15 y); other bits are ignored.",
                "Out: the integer texel (x, y) of the 256×256 sin/cos table to read with textureLoad / texelFetch / Load (a nearest sampler at (code + ½)/256 reads the same).",
            ],
            "decode_float" => &[
                "In: the sin/cos table's texel at sincos_texel(code), its .rgb as a unorm8 fetch returns it.",
            ],
            _ => return None,
        };
        Some(lines.iter().map(|l| l.to_string()).collect())
    }
}

/// Which tables a spec uses (`lut=`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SphericalLut {
    /// The seed's UnityScript.
    Seed,
    /// Atan at texel centres, sin/cos at the encoder's own code values.
    Matched,
}

impl SphericalLut {
    fn of(spec: &Spec) -> SphericalLut {
        [SphericalLut::Seed, SphericalLut::Matched][spec.choice(0)]
    }

    /// The atan table, `SIZE × SIZE` bytes, row `j` (the texel's y) after row `j - 1`.
    pub fn atan(self) -> &'static [u8] {
        static SEED: OnceLock<Vec<u8>> = OnceLock::new();
        static MATCHED: OnceLock<Vec<u8>> = OnceLock::new();
        let cell = match self {
            SphericalLut::Seed => &SEED,
            SphericalLut::Matched => &MATCHED,
        };
        cell.get_or_init(|| atan_lut(self))
    }

    /// The sin/cos table, `SIZE × SIZE` RGBA8 texels (A = 255), rows as [`SphericalLut::atan`].
    pub fn sincos(self) -> &'static [[u8; 4]] {
        static SEED: OnceLock<Vec<[u8; 4]>> = OnceLock::new();
        static MATCHED: OnceLock<Vec<[u8; 4]>> = OnceLock::new();
        let cell = match self {
            SphericalLut::Seed => &SEED,
            SphericalLut::Matched => &MATCHED,
        };
        cell.get_or_init(|| sincos_lut(self))
    }

    /// Where the atan table samples texel `i` (a texel's corner, or its centre).
    fn atan_at(self, i: usize) -> f64 {
        let i = i as f64;
        match self {
            SphericalLut::Seed => i / 128.0 - 1.0,
            SphericalLut::Matched => (i + 0.5) / 128.0 - 1.0,
        }
    }

    /// The parameter in `[-1, 1]` the sin/cos table's texel `i` stands for.
    fn sincos_at(self, i: usize) -> f64 {
        let i = i as f64;
        match self {
            SphericalLut::Seed => i / 128.0 - 1.0,
            SphericalLut::Matched => i / 127.5 - 1.0,
        }
    }
}

/// `x` in `[0, 1]` as the nearest byte, ties up. A value within `1e-9` of a tie counts
/// as one: the tables hold exact ties (`sin(-π)·r·½ + ½ = ½`, or `z = -15/17` where
/// `r = 8/17`) that f64 computes a hair below.
fn byte(x: f64) -> u8 {
    (x * 255.0 + 0.5 + 1e-9).floor().clamp(0.0, 255.0) as u8
}

/// The atan table: `(atan2(y, x) + π)/2π` at each texel's sample point.
pub fn atan_lut(lut: SphericalLut) -> Vec<u8> {
    use std::f64::consts::PI;
    (0..SIZE * SIZE)
        .map(|k| {
            let (x, y) = (lut.atan_at(k % SIZE), lut.atan_at(k / SIZE));
            byte((y.atan2(x) + PI) / (2.0 * PI))
        })
        .collect()
}

/// The sin/cos table: the direction `(cos φ·r, sin φ·r, z)·½ + ½` of each texel,
/// `φ = π·p(i)`, `z = p(j)`, `r = sqrt(1 - z²)`; A = 255.
pub fn sincos_lut(lut: SphericalLut) -> Vec<[u8; 4]> {
    use std::f64::consts::PI;
    (0..SIZE * SIZE)
        .map(|k| {
            let (phi, z) = (PI * lut.sincos_at(k % SIZE), lut.sincos_at(k / SIZE));
            let r = (1.0 - z * z).max(0.0).sqrt();
            let half = |c: f64| byte(c * 0.5 + 0.5);
            [half(phi.cos() * r), half(phi.sin() * r), half(z), 255]
        })
        .collect()
}

/// The field of each code: x (the fetched atan byte) lowest, then y (z).
const FIELDS: [Quant; 2] = [BYTE, BYTE];

/// The atan texel of `v`: per coordinate, `floor(256·(n·½ + ½))` clamped to 255 for the
/// normalized input's `x` and `y`.
pub fn atan_texel<F: Float>(v: V3<F>) -> V2<F::U> {
    let (w, _) = canonical_or_z(v);
    let s = length2(w).named("s");
    let root = s.sqrt();
    V2::new(texel_of(w.x, s, root), texel_of(w.y, s, root)).map(|t| t.to_u())
}

/// `min(floor(128·x/sqrt(s) + 128), 255)`: the texel boundary `k = c + 1` is passed
/// where `x·128 ≥ (c + 1 - 128)·sqrt(s)`, decided by [`past_root_ratio`] from squares,
/// so the float estimate (a quotient) never decides a texel.
fn texel_of<F: Float>(x: F, s: F, root: F) -> F {
    let big2 = (x * x * F::c(16384.0)).named("big2");
    let estimate = (x / root * F::c(128.0) + F::c(128.0)).floor();
    decided(BYTE, estimate, |c| {
        let k = c - F::c(127.0);
        past_root_ratio(x, big2, k, k * k * s)
    })
}

/// The packed code of `v` with the atan table's fetched value: x = its byte (a fetch's
/// `c/255` rounds back to `c` under any rounding of the product), y = the unorm8 code of
/// the normalized input's `z·½ + ½`, nearest, ties up, decided exactly.
pub fn encode<F: Float>(v: V3<F>, fetched: F) -> F::U {
    let (w, _) = canonical_or_z(v);
    let s = length2(w);
    let codes = V2::new(
        BYTE.quantize(fetched),
        unorm_sqrt_ratio(BYTE, w.z, s, s.sqrt(), 0.5),
    );
    super::codec::pack(&FIELDS, codes)
}

/// The float form: `(fetched, z·½ + ½)` of the normalized input.
pub fn encode_float<F: Float>(v: V3<F>, fetched: F) -> V2<F> {
    let u = super::codec::unit_or_z(v);
    V2::new(fetched, (u.z + F::c(1.0)) * F::c(0.5))
}

/// The sin/cos texel of a code: its two bytes.
pub fn sincos_texel<F: Float>(code: F::U) -> V2<F::U> {
    V2::new(code & F::U::c(0xff), code.shr(8) & F::U::c(0xff))
}

/// The seed's `sclook·2 - 1`, written `(t - ½)·2` (exact for every byte's fetch at
/// or above ¼, and never contracted into a different rounding).
pub fn decode_float<F: Float>(rgb: V3<F>) -> V3<F> {
    (rgb - F::c(0.5)) * F::c(2.0)
}

/// The emitted functions, and the CPU encoder and decoder that fetch from the tables.
fn emitted(spec_id: &str, lut: SphericalLut) -> Emitted {
    let module = trace_module(|| {
        define("decode_float", &["rgb"], |rgb: V3<Tf>| decode_float(rgb));
        define("sincos_texel", &["code"], |c: <Tf as Float>::U| {
            sincos_texel::<Tf>(c)
        });
        define("atan_texel", &["v"], |v: V3<Tf>| atan_texel(v));
        define("encode_float", &["v", "fetched"], |(v, a): (V3<Tf>, Tf)| {
            encode_float(v, a)
        });
        define("encode", &["v", "fetched"], |(v, a): (V3<Tf>, Tf)| encode(v, a));
    });
    let texel = function(
        "atan_texel",
        Role::LutTexel,
        Inputs::Vectors,
        |v: V3<f32>| atan_texel(v),
        |v: V3<Dev>| atan_texel(v),
        |v: V3<F4>| atan_texel(v),
    );
    let with_atan = Inputs::VectorsWith(fetch_atan(lut));
    let enc = function(
        "encode",
        Role::Encode,
        with_atan.clone(),
        |(v, a): (V3<f32>, f32)| encode(v, a),
        |(v, a): (V3<Dev>, Dev)| encode(v, a),
        |(v, a): (V3<F4>, F4)| encode(v, a),
    );
    let enc_float = function(
        "encode_float",
        Role::EncodeFloat,
        with_atan,
        |(v, a): (V3<f32>, f32)| encode_float(v, a),
        |(v, a): (V3<Dev>, Dev)| encode_float(v, a),
        |(v, a): (V3<F4>, F4)| encode_float(v, a),
    );
    let sincos = function(
        "sincos_texel",
        Role::LutTexel,
        Inputs::Codes(FIELDS.to_vec()),
        |c: u32| sincos_texel::<f32>(c),
        |c: crate::model::deviant::DevU| sincos_texel::<Dev>(c),
        |c: crate::model::lanes::U4| sincos_texel::<F4>(c),
    );
    let mut dec_float = function(
        "decode_float",
        Role::DecodeFloat,
        Inputs::FloatCodes(vec![BYTE; 3]),
        |rgb: V3<f32>| decode_float(rgb),
        |rgb: V3<Dev>| decode_float(rgb),
        |rgb: V3<F4>| decode_float(rgb),
    );
    dec_float.enclose = Some(Enclose {
        eval: Arc::new(|r: &[(i64, i64)]| {
            let rgb = V3::from_array(std::array::from_fn(|i| fetched_range(BYTE, r[i])));
            decode_float::<Encl>(rgb).to_array().to_vec()
        }),
        whole_field: None,
        unread: &[],
    });
    let cpu = vec![
        through_table(
            "encode",
            Role::Encode,
            Inputs::Vectors,
            &texel,
            Arc::new(move |t: &[u32]| vec![atan_fetch(lut, t).to_bits()]),
            &enc,
            true,
        ),
        through_table(
            "encode_float",
            Role::EncodeFloat,
            Inputs::Vectors,
            &texel,
            Arc::new(move |t: &[u32]| vec![atan_fetch(lut, t).to_bits()]),
            &enc_float,
            true,
        ),
        through_table(
            "decode",
            Role::Decode,
            Inputs::Codes(FIELDS.to_vec()),
            &sincos,
            Arc::new(move |t: &[u32]| sincos_fetch(lut, t)),
            &dec_float,
            false,
        ),
    ];
    Emitted {
        module,
        functions: vec![dec_float, sincos, texel, enc_float, enc],
        cpu,
        namespace: spec_id.to_string(),
        portable_encoder: true,
    }
}

/// A unorm8 texel's byte as the texture unit returns it: `c·(1/255)`, lavapipe's
/// conversion (tests/spherical_lut.rs checks it), which rounds back to `c` in
/// [`encode`] however it is computed.
fn fetch(c: u8) -> f32 {
    BYTE.dequantize(f32::from(c))
}

/// The atan table's value at the texel `t = [x, y]`.
fn atan_fetch(lut: SphericalLut, t: &[u32]) -> f32 {
    fetch(lut.atan()[t[1] as usize * SIZE + t[0] as usize])
}

/// The sin/cos table's `.rgb` at the texel `t = [x, y]`, as words.
fn sincos_fetch(lut: SphericalLut, t: &[u32]) -> Vec<u32> {
    let texel = lut.sincos()[t[1] as usize * SIZE + t[0] as usize];
    texel[..3].iter().map(|&c| fetch(c).to_bits()).collect()
}

/// The model's own fetch of the atan table for a vector (its words): what the verify
/// inputs of `encode(v, fetched)` pair each vector with.
fn fetch_atan(lut: SphericalLut) -> Extra {
    Extra {
        name: "the atan table's value at atan_texel(v)",
        words: 1,
        of: Arc::new(move |v: &[u32]| {
            let t = atan_texel::<f32>(V3::from_array(std::array::from_fn(|i| f32::from_bits(v[i]))));
            vec![atan_fetch(lut, &[t.x, t.y]).to_bits()]
        }),
    }
}
