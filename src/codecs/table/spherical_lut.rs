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
//! The precise encoder (`spherical_lut16p`) refines that code against the decoder's own
//! table: it fetches the sin/cos texels of the 3×3 block of codes around it and keeps
//! the one nearest the input in angle:
//!
//! ```text
//! encode:  t = atan_texel(v);  a = atan_lut[t].r
//!          c = encode_fast(v, a)                     the fast code
//!          s_k = sincos_lut[precise_texel(c, k)].rgb  for k = 0..8, the block row by row
//!          code = encode(v, c, s_0, …, s_8)
//! ```
//!
//! Its `encode_float` takes `encode`'s arguments and returns the chosen code's bytes as
//! `c/255` (an RG8 render target stores exactly that code), like every precise float form.
//!
//! The choice is made in integers, like the other precise encoders' ([`crate::codecs::toolkit::lattice`]): each
//! candidate's direction is `d = 2·byte - 255` of its fetched texel (its decode times
//! 255), the input is `A = ±floor(|w|·2^12)` of the canonical input `w` (largest
//! component in `[2, 4)`), and `sin²` of their angle is compared as `|A×d|²/|d|²`:
//! `|A×d|²` summed exactly in integers and rounded once, the two ratios compared by two
//! correctly rounded products ([`Closeness::of_small`]), the fast code first on ties. So
//! every implementation picks the same code. The fixed point moves the input's direction
//! by at most `√3·2^-13` rad (0.012°), so the chosen texel is within twice that,
//! `4.2·10^-4` rad, of the block's nearest.
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

use crate::model::num::helper;
use crate::codecs::core::info::Domain;
use crate::codecs::toolkit::exact::{canonical_or_z, decided, length2, past_root_ratio, unorm_sqrt_ratio};
use crate::codecs::core::info::{Info, OptDesc, OptKind, Sizes, FloatForm, seam};
use crate::codecs::core::spec::{Family, Table, TableFormat, Tracing};
use crate::codecs::functions::decode_boxes::fetched_range;
use crate::codecs::functions::function::{Emitted, Enclose, Extra, Function, Inputs, Role, WordsMap};
use crate::codecs::core::pipeline::through_table;
use crate::codecs::functions::words::{Declared, declared, trace_declared};
use crate::codecs::toolkit::lattice::{Closeness, Measure};
use crate::codecs::toolkit::quant::Quant;
use crate::codecs::core::spec::Spec;
use crate::model::enclosure::Encl;
use crate::model::{Float, Lane, Uint, V2, V3};
use std::sync::{Arc, OnceLock};

pub static FAMILY: SphericalLutFamily = SphericalLutFamily;

pub struct SphericalLutFamily;

/// Texels per side of both tables.
pub const SIZE: usize = 256;

/// A table texel's channel, and each stored code's field.
const BYTE: Quant = Quant::Unorm(8);

const TABLES: OptDesc = OptDesc {
    key: "lut",
    help: "the tables' content: seed = the seed's UnityScript (atan at texel corners; its sin/cos table reads codes as c/128 - 1, the encoder writes c/127.5 - 1); matched = atan at texel centres and a sin/cos table that inverts the encoder's quantization",
    kind: OptKind::Choice(&["seed", "matched"]),
};

static INFO: Info = Info {
    name: "spherical_lut",
    title: "azimuth and z through an atan2 and a sin/cos lookup texture (256×256)",
    sizes: Sizes::Total(&[16]),
    domain: Some(Domain::Sphere),
    source: "Pranckevičius method 3a",
    edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z (atan texel (128, 128); the precise encoder keeps that code)",
    decode_note: "the sin/cos table's texel·2 - 1, not renormalized: unit length to within the table's rounding (each component within 1/255)",
    float_form: FloatForm::Continuous { seam: seam::AZIMUTH_WRAP },
    options: &[TABLES],
};

impl Family for SphericalLutFamily {
    fn info(&self) -> &Info {
        &INFO
    }
    fn precise(&self) -> bool {
        // Its precise encoder searches the lattice in integers (`encode_codes`).
        true
    }
    fn variants(&self) -> &'static [&'static str] {
        &["spherical_lut16:lut=matched"]
    }
    fn emitted(&self, spec: &Spec, _: Tracing) -> Emitted {
        emitted(&spec.id(), SphericalLut::of(spec), spec.precise())
    }
    /// A precise spec reads its fast spec's tables (same files, same names).
    fn tables(&self, spec: &Spec) -> Vec<Table> {
        let lut = SphericalLut::of(spec);
        let table = |what: &str, channels: u8, bytes: Vec<u8>| Table {
            stem: format!("{}_{what}", spec.fast().id()),
            width: SIZE as u32,
            height: SIZE as u32,
            channels,
            format: TableFormat::Unorm8,
            bytes,
        };
        vec![
            table("atan", 1, lut.atan().to_vec()),
            table("sincos", 4, lut.sincos().concat()),
        ]
    }
    fn function_doc(&self, spec: &Spec, name: &str) -> Option<Vec<String>> {
        let lines: &[&str] = match name {
            "encode" if spec.precise() => &[
                "In: any vector; `code`, encode_fast(v, fetched) for it; s0 … s8, the sin/cos table's .rgb at precise_texel(code, k) for k = 0 … 8, as a unorm8 fetch returns them.",
                "Out: the packed code, uint (bits 0–7 x, 8–15 y): of the 3×3 block of codes around `code`, the one whose sin/cos texel (its decode) is nearest the input in angle (within 4.2e-4 rad), decided deterministically from integers (the input scaled by a power of two to a largest component in [2, 4), in steps of 2^-12; each texel as 2·byte - 255); `code` on ties and for zero, NaN and infinite input.",
            ],
            "encode_float" if spec.precise() => &[
                "In: as encode.",
                "Out: the bytes (x, y) of encode's code as c/255, for an RG8 unorm render target, which stores exactly that code.",
            ],
            "encode_fast" => &[
                "In: any vector, and `fetched`, the atan table's value at atan_texel(v) as a unorm8 fetch returns it (c/255).",
                "Out: the fast encoder's code, uint (bits 0–7: x, the fetched byte; bits 8–15: y, z·½ + ½ of the normalized input as unorm8, rounded exactly): where encode's search starts.",
            ],
            "precise_texel" => &[
                "In: a code (bits 0–7 x, 8–15 y; other bits are ignored) and k in 0 … 8 (a larger k reads as 8).",
                "Out: the integer texel (x, y) of the sin/cos table holding the decode of the precise search's candidate k: the code's bytes moved by (k mod 3 - 1, k div 3 - 1), x wrapping around mod 256 (the azimuth is periodic), y clamped to [0, 255]. Row by row; k = 4 is the code itself. The candidate's code is the texel's x | y << 8.",
            ],
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
        if spec.chose(&TABLES, "matched") {
            SphericalLut::Matched
        } else {
            SphericalLut::Seed
        }
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
#[inline(always)]
pub fn atan_texel<F: Float>(v: V3<F>) -> V2<F::U> {
    let (w, _) = canonical_or_z(v);
    let s = length2(w).named("s");
    let root = s.sqrt();
    V2::new(texel_of(w.x, s, root), texel_of(w.y, s, root)).map(#[inline(always)] |t| t.to_u())
}

/// `min(floor(128·x/sqrt(s) + 128), 255)`: the texel boundary `k = c + 1` is passed
/// where `x·128 ≥ (c + 1 - 128)·sqrt(s)`, decided by [`past_root_ratio`] from squares,
/// so the float estimate (a quotient) never decides a texel.
#[inline(always)]
fn texel_of<F: Float>(x: F, s: F, root: F) -> F {
    let big2 = (x * x * F::c(16384.0)).named("big2");
    let estimate = (x / root * F::c(128.0) + F::c(128.0)).floor();
    decided(BYTE, estimate, #[inline(always)] |c| {
        let k = c - F::c(127.0);
        past_root_ratio(x, big2, k, k * k * s)
    })
}

/// The packed code of `v` with the atan table's fetched value: x = its byte (a fetch's
/// `c/255` rounds back to `c` under any rounding of the product), y = the unorm8 code of
/// the normalized input's `z·½ + ½`, nearest, ties up, decided exactly.
#[inline(always)]
pub fn encode<F: Float>(v: V3<F>, fetched: F) -> F::U {
    let (w, _) = canonical_or_z(v);
    let s = length2(w);
    let codes = V2::new(
        BYTE.quantize(fetched),
        unorm_sqrt_ratio(BYTE, w.z, s, s.sqrt(), 0.5),
    );
    crate::codecs::core::codec::pack(&FIELDS, codes)
}

/// The float form: `(fetched, z·½ + ½)` of the normalized input.
#[inline(always)]
pub fn encode_float<F: Float>(v: V3<F>, fetched: F) -> V2<F> {
    let u = crate::codecs::core::codec::unit_or_z(v);
    V2::new(fetched, (u.z + F::c(1.0)) * F::c(0.5))
}

/// The sin/cos texel of a code: its two bytes.
#[inline(always)]
pub fn sincos_texel<F: Float>(code: F::U) -> V2<F::U> {
    V2::new(code & F::U::c(0xff), code.shr(8) & F::U::c(0xff))
}

/// The seed's `sclook·2 - 1`, written `(t - ½)·2` (exact for every byte's fetch at
/// or above ¼, and never contracted into a different rounding).
#[inline(always)]
pub fn decode_float<F: Float>(rgb: V3<F>) -> V3<F> {
    (rgb - F::c(0.5)) * F::c(2.0)
}

/// The candidates of the precise search: the 3×3 block of codes around the fast code.
const BLOCK: u32 = 9;

/// The input's fixed point for the precise search, `2^12`: canonical components are
/// below 4, so `|A| < 4√3·2^12`, and a texel's `d = 2·byte - 255` has `|d| ≤ 255√3`, so
/// `|A|·|d| < 12·255·2^12 < 2^23.6` and `|d| < 2^12`, as [`Closeness::of_small`] needs.
const ANGLE_FIXED: f32 = (1u32 << 12) as f32;

/// The texel of the precise search's candidate `k` (a larger `k` reads as 8): the code's
/// bytes moved by `(k mod 3 - 1, k div 3 - 1)`, x wrapping mod 256, y clamped to
/// `[0, 255]`. All in integers, so every implementation fetches the same texels.
#[inline(always)]
pub fn precise_texel<F: Float>(code: F::U, k: F::U) -> V2<F::U> {
    let c = { #[inline(always)] |v: u32| F::U::c(v) };
    let k = F::U::sel(k.lt(c(BLOCK)), k, c(BLOCK - 1));
    // The row, 0 … 2 (dy + 1), and the column, 0 … 2 (dx + 1).
    let row = F::U::sel(k.lt(c(3)), c(0), F::U::sel(k.lt(c(6)), c(1), c(2)));
    let col = k - row.wrapping_mul(c(3));
    moved::<F::U>(code, col, row)
}

/// The code's texel moved by `(col - 1, row - 1)` (`col`, `row` in 0 … 2), x wrapping
/// mod 256, y clamped to `[0, 255]`.
#[inline(always)]
fn moved<U: Uint>(code: U, col: U, row: U) -> V2<U> {
    let x = ((code & U::c(0xff)) + col + U::c(255)) & U::c(0xff);
    // y + row - 1 in [-1, 256], clamped: below 1 is row 0 at y = 0.
    let y = (code.shr(8) & U::c(0xff)) + row;
    let y = U::sel(y.lt(U::c(1)), U::c(1), y) - U::c(1);
    V2::new(x, U::sel(y.lt(U::c(256)), y, U::c(255)))
}

/// The texel's code, `x | y << 8`.
#[inline(always)]
fn code_of<U: Uint>(t: V2<U>) -> U {
    t.x | t.y.shl(8)
}

/// The nine fetched sin/cos texels of the precise encoder's parameters, nested in pairs
/// (a function's parameters are a vector, a scalar or a pair of them).
pub type Block<F> = (
    V3<F>,
    (V3<F>, (V3<F>, (V3<F>, (V3<F>, (V3<F>, (V3<F>, (V3<F>, V3<F>))))))),
);

#[inline(always)]
fn block_array<F: Copy>(b: Block<F>) -> [V3<F>; 9] {
    let (s0, (s1, (s2, (s3, (s4, (s5, (s6, (s7, s8)))))))) = b;
    [s0, s1, s2, s3, s4, s5, s6, s7, s8]
}

/// The precise code: of the candidates `precise_texel(code, k)`, the one whose fetched
/// texel `s[k]` is nearest the input in angle ([`Closeness::of_small`] of `2·byte - 255`
/// against the input at [`ANGLE_FIXED`]), `code` (k = 4) first on ties; `code` for
/// invalid input.
#[inline(always)]
pub fn encode_precise<F: Float>(v: V3<F>, code: F::U, s: Block<F>) -> F::U {
    let s = block_array(s);
    let (w, ok) = canonical_or_z(v);
    let a = w
        .map(#[inline(always)] |x| {
            let m = (x.abs() * F::c(ANGLE_FIXED)).floor().to_u();
            F::U::sel(x.lt(F::c(0.0)), F::U::c(0).wrapping_sub(m), m)
        })
        .named("afix");
    let direction = { #[inline(always)] |t: V3<F>| {
        t.map(#[inline(always)] |t| {
            let b = BYTE.quantize(t).to_u();
            (b + b).wrapping_sub(F::U::c(255))
        })
    } };
    let candidate = { #[inline(always)] |k: u32| {
        // The block's centre is the code itself.
        let code = if k == 4 {
            code & F::U::c(0xffff)
        } else {
            code_of(moved(code, F::U::c(k % 3), F::U::c(k / 3)))
        };
        (code, Closeness::<F>::of_small(a, direction(s[k as usize])))
    } };
    let (first, mut best_c) = candidate(4);
    let mut best = first;
    for k in [0, 1, 2, 3, 5, 6, 7, 8] {
        let (code, c) = candidate(k);
        let better = c.closer(best_c);
        best = F::U::sel(better, code, best).named("best");
        best_c = Measure::sel(better, c, best_c);
    }
    F::U::sel(ok, best, first)
}

/// The precise float form: the chosen code's bytes as `c/255`, which an RG8 unorm render
/// target stores as exactly that code.
#[inline(always)]
pub fn encode_float_precise<F: Float>(v: V3<F>, code: F::U, s: Block<F>) -> V2<F> {
    let chosen = helper!("encode" => encode_precise(v, code, s));
    let chosen: V2<F> = crate::codecs::core::codec::unpack(&FIELDS, chosen);
    crate::codecs::core::codec::dequantize(&FIELDS, chosen)
}

/// The emitted functions, and the CPU encoder and decoder that fetch from the tables.
fn emitted(spec_id: &str, lut: SphericalLut, precise: bool) -> Emitted {
    // The fast code's function: the packed encoder of a fast spec, the search's first
    // step in a precise one.
    let fast_name = if precise { "encode_fast" } else { "encode" };
    let texel = declared!(
        "atan_texel",
        Role::LutTexel,
        Inputs::Vectors,
        ["v"],
        <F> [] |v: V3<F>| atan_texel(v)
    );
    let with_atan = Inputs::VectorsWith(fetch_atan(lut));
    let enc = declared!(
        fast_name,
        Role::Encode,
        with_atan.clone(),
        ["v", "fetched"],
        <F> [] |va: (V3<F>, F)| encode(va.0, va.1)
    );
    let sincos = declared!(
        "sincos_texel",
        Role::LutTexel,
        Inputs::Codes(FIELDS.to_vec()),
        ["code"],
        <F> [] |c: <F as Float>::U| sincos_texel::<F>(c)
    );
    let mut dec_float = declared!(
        "decode_float",
        Role::DecodeFloat,
        Inputs::FloatCodes(vec![BYTE; 3]),
        ["rgb"],
        <F> [] |rgb: V3<F>| decode_float(rgb)
    );
    dec_float.function_mut().enclose = Some(Enclose {
        eval: Arc::new(|r: &[(i64, i64)]| {
            let rgb = V3::from_array(std::array::from_fn(|i| fetched_range(BYTE, r[i])));
            decode_float::<Encl>(rgb).to_array().to_vec()
        }),
        whole_field: None,
        unread: &[],
        fixed: Vec::new(),
        budget: None,
        parts: None,
    });
    let atan_lookup: WordsMap = Arc::new(move |t: &[u32]| vec![atan_fetch(lut, t).to_bits()]);
    let fast_cpu = through_table(
        "encode",
        Role::Encode,
        Inputs::Vectors,
        texel.function(),
        atan_lookup.clone(),
        enc.function(),
        true,
    );
    let dec_cpu = through_table(
        "decode",
        Role::Decode,
        Inputs::Codes(FIELDS.to_vec()),
        sincos.function(),
        Arc::new(move |t: &[u32]| sincos_fetch(lut, t)),
        dec_float.function(),
        false,
    );
    let mut functions = vec![dec_float, sincos];
    let cpu = if precise {
        let p = precise_functions(lut, &fast_cpu);
        functions.extend([texel, enc, p.texel, p.encode, p.encode_float]);
        vec![p.cpu_encode, p.cpu_encode_float, dec_cpu]
    } else {
        let enc_float = declared!(
            "encode_float",
            Role::EncodeFloat,
            with_atan,
            ["v", "fetched"],
            <F> [] |va: (V3<F>, F)| encode_float(va.0, va.1)
        );
        let enc_float_cpu = through_table(
            "encode_float",
            Role::EncodeFloat,
            Inputs::Vectors,
            texel.function(),
            atan_lookup,
            enc_float.function(),
            true,
        );
        functions.extend([texel, enc_float, enc]);
        vec![fast_cpu, enc_float_cpu, dec_cpu]
    };
    let (module, functions) = trace_declared(functions);
    Emitted {
        module,
        functions,
        cpu,
        namespace: spec_id.to_string(),
        portable_encoder: true,
    }
}

/// A precise spec's own functions.
struct Precise {
    texel: Declared,
    encode: Declared,
    encode_float: Declared,
    /// The CPU encoders: the fast one, the block's fetches from the table in memory, then
    /// `encode` or `encode_float`.
    cpu_encode: Function,
    cpu_encode_float: Function,
}

/// The precise spec's `precise_texel`, `encode` and `encode_float`, and its CPU encoders
/// chained on the fast one (`fast_cpu`).
fn precise_functions(lut: SphericalLut, fast_cpu: &Function) -> Precise {
    type U<F> = <F as Float>::U;
    let search_texel = declared!(
        "precise_texel",
        Role::LutTexel,
        // Every code with each k, and k past the block (read as 8).
        Inputs::CodesAndIndex(FIELDS.to_vec(), 2 * BLOCK),
        ["code", "k"],
        <F> [] |x: (U<F>, U<F>)| precise_texel::<F>(x.0, x.1)
    );
    let block = block_fetch(lut);
    let fast = fast_cpu.eval.clone();
    let inputs = Inputs::VectorsWith(Extra {
        name: "encode_fast's code for the vector (through the atan table) and the sin/cos table's values at its 3×3 block",
        words: 1 + 3 * BLOCK as usize,
        of: {
            let block = block.clone();
            Arc::new(move |v: &[u32]| {
                let mut code = [0u32];
                fast(v, &mut code);
                block(&code)
            })
        },
    });
    let names = ["v", "code", "s0", "s1", "s2", "s3", "s4", "s5", "s6", "s7", "s8"];
    let search = declared!(
        "encode",
        Role::Encode,
        inputs.clone(),
        names,
        <F> [] |x: (V3<F>, (U<F>, Block<F>))| encode_precise(x.0, x.1.0, x.1.1)
    );
    let search_float = declared!(
        "encode_float",
        Role::EncodeFloat,
        inputs,
        names,
        <F> [] |x: (V3<F>, (U<F>, Block<F>))| encode_float_precise(x.0, x.1.0, x.1.1)
    );
    // What a shader runs: the fast code's two parts, the block's nine texels, the search.
    let chained = |name: &'static str, role: Role, last: &Function| {
        let mut cpu = through_table(name, role, Inputs::Vectors, fast_cpu, block.clone(), last, true);
        cpu.parts = [&fast_cpu.parts[..], &["precise_texel"; BLOCK as usize], &[name]].concat();
        cpu
    };
    Precise {
        cpu_encode: chained("encode", Role::Encode, search.function()),
        cpu_encode_float: chained("encode_float", Role::EncodeFloat, search_float.function()),
        texel: search_texel,
        encode: search,
        encode_float: search_float,
    }
}

/// A code's words → the code and the sin/cos table's `.rgb` at each `precise_texel(code,
/// k)`, as a unorm8 fetch returns them.
fn block_fetch(lut: SphericalLut) -> WordsMap {
    Arc::new(move |c: &[u32]| {
        let mut out = vec![c[0]];
        for k in 0..BLOCK {
            let t = precise_texel::<f32>(c[0], k);
            out.extend(sincos_fetch(lut, &[t.x, t.y]));
        }
        out
    })
}

/// A unorm8 texel's byte as the texture unit returns it: `c·(1/255)`, lavapipe's
/// conversion (tests/families/spherical_lut.rs checks it), which rounds back to `c` in
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
