//! Crytek's Best Fit Normals with its lookup table (Kaplanyan 2010, survey §2.2
//! "CrytekBFN"): an RGB8 normal (`n·½ + ½`, decoded by renormalizing, like `unorm3`)
//! whose length is chosen per direction, so that the stored vector's direction is nearer
//! the input than the unit vector's rounding would be. The length comes from a
//! 512×512 single-channel table indexed by the direction, folded by symmetry.
//!
//! A shader cannot call a texture it was not given, so the emitted functions are the
//! pieces around the fetch:
//!
//! ```text
//! encode:  t = fitting_texel(v)           integer texel of the fitting table
//!          a = fitting_table[t].r         the fetched unorm8 value, the scale k/255
//!          code = encode(v, a)            (n / max|n|)·(k/255)·½ + ½ as unorm8×3
//! decode:  n = decode(code)               unorm3's: enc·2 - 1, renormalized
//! ```
//!
//! The texel is Crytek's texture coordinate, `(mid, minor/mid)` of the input's sorted
//! magnitudes (`|n|`'s largest component is the major axis), read with nearest filtering:
//! `floor(512·mid/|n|)` and `floor(512·minor/mid)` (a zero `mid` reads row 0), each
//! clamped to 511 and decided from the canonical input by comparing products
//! ([`fixed_ratio`]; `|n|` from [`root`], `2^-22` relative), never through a rounded
//! quotient, so every implementation reads the same texel. Where a product's rounding
//! decides a near tie, the texel may be either neighbour of the boundary (the same one
//! everywhere).
//!
//! The table ([`fitting_table`]) follows Crytek's generator as published (a search per
//! texel for the length whose unorm8 rounding has the least relative error): texel `(i, j)` stands
//! for the unit direction with `mid = (i + ½)/512` and `minor = mid·(j + ½)/512`, scaled
//! so that its largest component is 1; for each odd `k` in 3 … 255 the vector times
//! `k/255` is rounded to unorm8 (`·½ + ½`), and the texel stores the first `k` with the
//! least relative error `max|q - p|/(k/255)` of that rounding. An odd `k` puts the major
//! component exactly on a code (`127.5 ± k/2`). Computed in f64 from products, quotients
//! and square roots alone, which IEEE 754 rounds correctly, so every machine writes the
//! same bytes; `unitpack generate` writes it to `generated/lut/` (PNG and raw bytes, row
//! `j` after row `j - 1`).
//!
//! The packed encoder decides each byte exactly: each component's ratio to the major one,
//! `r = floor(|w|/major·2^20)` ([`fixed_ratio`]), times `k` in integers, gives
//! `128 + floor(r·k/2^21)` for a non-negative component and `128 - ceil(r·k/2^21)` for a
//! negative one: `round(127.5 ± (r/2^20)·k/2)`, ties up, for `r` on its `2^-20` grid.
//! Zero, NaN and infinite input encode as +Z at the scale 1, `(128, 128, 255)`, whatever
//! was fetched.

use crate::codecs::core::codec::pack;
use crate::codecs::core::info::Domain;
use crate::codecs::toolkit::exact::{canonical_or_z, fixed_length2, fixed_ratio, root};
use crate::codecs::core::info::{Info, Sizes, FloatForm};
use crate::codecs::core::spec::{Family, Table, TableFormat, Tracing};
use crate::codecs::functions::function::{Emitted, Extra, Inputs, Role, WordsMap};
use crate::codecs::core::pipeline::{codec_decoders, through_table};
use crate::codecs::functions::words::{declared, trace_declared};
use crate::codecs::toolkit::quant::Quant;
use crate::codecs::core::spec::Spec;
use crate::codecs::component::unorm3::Unorm3;
use crate::model::{Float, Uint, V2, V3};
use std::sync::{Arc, OnceLock};

pub static FAMILY: CrytekBfnFamily = CrytekBfnFamily;

pub struct CrytekBfnFamily;

/// Texels per side of the fitting table.
pub const SIZE: usize = 512;

/// `log2(SIZE)`: the texel coordinates' fixed point.
const SIZE_BITS: u32 = 9;

/// The fixed point of a component's ratio to the major one.
const RATIO_BITS: u32 = 20;

/// The table's byte, and each stored component's field.
const BYTE: Quant = Quant::Unorm(8);

/// The stored fields: x, y, z as unorm8, x lowest (an RGB8 texel).
const FIELDS: [Quant; 3] = [BYTE; 3];

static INFO: Info = Info {
    name: "crytek_bfn",
    title: "Crytek's best fit normals: RGB8 scaled by a fitting table's length (512×512)",
    sizes: Sizes::Total(&[24]),
    domain: Some(Domain::Sphere),
    source: "Cigolle et al. 2014 §2.2 (Kaplanyan 2010, CryENGINE 3)",
    edge_policy: "zero, NaN and infinite input encode as +Z at the scale 1, (128, 128, 255), whatever was fetched",
    decode_note: "decode re-normalizes (v / sqrt(v·v)); every code decodes to a unit vector",
    float_form: FloatForm::Continuous {
        seam: "nowhere: every stored vector points along its direction (its fitted length only shifts the filter's weights)",
    },
    options: &[],
};

impl Family for CrytekBfnFamily {
    fn info(&self) -> &Info {
        &INFO
    }
    fn precise(&self) -> bool {
        // The fitting table is itself the encoder's choice of code.
        false
    }
    fn emitted(&self, spec: &Spec, _: Tracing) -> Emitted {
        emitted(&spec.id())
    }
    fn tables(&self, spec: &Spec) -> Vec<Table> {
        vec![Table {
            stem: format!("{}_fitting", spec.id()),
            width: SIZE as u32,
            height: SIZE as u32,
            channels: 1,
            format: TableFormat::Unorm8,
            bytes: fitting_table().to_vec(),
        }]
    }
    fn function_doc(&self, _spec: &Spec, name: &str) -> Option<Vec<String>> {
        let lines: &[&str] = match name {
            "fitting_texel" => &[
                "In: any vector; zero, NaN and infinite input read texel (0, 0).",
                "Out: the integer texel (x, y) of the 512×512 fitting table to read with textureLoad / texelFetch / Load: Crytek's coordinate (mid, minor/mid) of |n|'s sorted components as nearest sampling selects it, floor(512·mid/|n|) and floor(512·minor/mid) (0 where mid is 0), each clamped to 511 and decided exactly (the same texel on every implementation). Sample at (t + ½)/512 for the same texel through a nearest sampler.",
            ],
            "encode" => &[
                "In: any vector, and `fetched`, the fitting table's value at fitting_texel(v) as a unorm8 fetch returns it (k/255).",
                "Out: the packed code, uint (bits 0–7 x, 8–15 y, 16–23 z; bits 24–31 clear): (n / max|n|)·(k/255)·½ + ½ as unorm8, each byte decided exactly (the ratio to the major component on a 2^-20 grid, ties up); (128, 128, 255) for zero, NaN and infinite input.",
            ],
            "encode_float" => &[
                "In: any vector, and `fetched` as for encode.",
                "Out: (n / max|n|)·fetched·½ + ½ of the normalized input, unquantized, for an RGB8 unorm render target (Crytek's shader output).",
            ],
            _ => return None,
        };
        Some(lines.iter().map(|l| l.to_string()).collect())
    }
}

/// The fitting table, `SIZE × SIZE` bytes, row `j` (the texel's y) after row `j - 1`.
pub fn fitting_table() -> &'static [u8] {
    static TABLE: OnceLock<Vec<u8>> = OnceLock::new();
    TABLE.get_or_init(|| {
        // 2^18 texels of 127 trials each: rows on every core.
        let rows: Vec<usize> = (0..SIZE).collect();
        crate::support::par::map(&rows, |&j| (0..SIZE).map(|i| best_scale(i, j)).collect::<Vec<u8>>())
            .concat()
    })
}

/// The first odd `k` in 3 … 255 with the least relative rounding error of the texel's
/// direction scaled by `k/255` (see the module's documentation). Every trial's error is
/// computed first, in a loop LLVM runs on SIMD lanes, and the first least one is then
/// picked: the same bytes as trying each `k` in turn (`unitpack generate` builds the table
/// each run; docs/design/speed.md).
fn best_scale(i: usize, j: usize) -> u8 {
    const TRIALS: usize = 127;
    const TWO_52: f64 = 4_503_599_627_370_496.0;
    let n = SIZE as f64;
    let mid = (i as f64 + 0.5) / n;
    let minor = mid * (j as f64 + 0.5) / n;
    let major = (1.0 - mid * mid - minor * minor).max(0.0).sqrt();
    let top = major.max(mid);
    let d = [mid / top, minor / top, major / top];
    let mut errs = [0f64; TRIALS];
    for (m, e) in errs.iter_mut().enumerate() {
        let t = (3 + 2 * m) as f64 / 255.0;
        let err = d
            .iter()
            .map(|&c| {
                let p = t * c;
                // floor of `x` in [0.5, 255.5] in float arithmetic alone: `as` saturates
                // (and libm's floor is a call), which kept the loop off the lanes.
                // `x + 2^52 - 2^52` is `x` rounded to an integer, one too many where
                // that rounded up.
                let x = (p * 0.5 + 0.5) * 255.0 + 0.5;
                let r = (x + TWO_52) - TWO_52;
                let code = if r > x { r - 1.0 } else { r };
                (code / 255.0 * 2.0 - 1.0 - p).abs()
            })
            .fold(0.0, f64::max);
        *e = err / t;
    }
    let mut best = 0;
    for (m, &e) in errs.iter().enumerate() {
        if e < errs[best] {
            best = m;
        }
    }
    (3 + 2 * best) as u8
}

/// The magnitudes sorted: `(major, mid, minor)`, as values (which axis does not matter).
#[inline(always)]
fn sorted<F: Float>(a: V3<F>) -> (F, F, F) {
    let (hi, lo) = (a.x.at_least(a.y), a.x.at_most(a.y));
    let z_major = a.z.ge(hi);
    let mid = F::sel(z_major, hi, a.z.at_least(lo));
    let minor = F::sel(z_major, lo, a.z.at_most(lo));
    (hi.at_least(a.z), mid, minor)
}

/// The fitting table's texel of `v` (see the module's documentation).
#[inline(always)]
pub fn fitting_texel<F: Float>(v: V3<F>) -> V2<F::U> {
    let (w, _) = canonical_or_z(v);
    let (_, mid, minor) = sorted(w.map(#[inline(always)] |x| x.abs()));
    let last = F::c((SIZE - 1) as f32);
    let l = root(fixed_length2(w)).named("l");
    let i = fixed_ratio(mid, l, SIZE_BITS).at_most(last);
    let has_mid = mid.gt(F::c(0.0));
    let ratio = fixed_ratio(minor, F::sel(has_mid, mid, F::c(1.0)), SIZE_BITS);
    let j = F::sel(has_mid, ratio, F::c(0.0)).at_most(last);
    V2::new(i, j).map(#[inline(always)] |t| t.to_u())
}

/// The packed code of `v` with the table's fetched scale (see the module's
/// documentation).
#[inline(always)]
pub fn encode<F: Float>(v: V3<F>, fetched: F) -> F::U {
    let (w, ok) = canonical_or_z(v);
    let a = w.map(#[inline(always)] |x| x.abs());
    let (major, _, _) = sorted(a);
    let k = BYTE.quantize(fetched).named("k").to_u();
    let u = { #[inline(always)] |x: u32| F::U::c(x) };
    let (w, a) = (w.to_array(), a.to_array());
    let byte = { #[inline(always)] |c: usize| {
        let (x, m) = (w[c], a[c]);
        let r = fixed_ratio(m, major, RATIO_BITS).to_u();
        let rk = r.wrapping_mul(k);
        let shift = RATIO_BITS + 1;
        let up = u(128) + rk.shr(shift);
        let down = u(128) - (rk + u((1 << shift) - 1)).shr(shift);
        F::U::sel(x.lt(F::c(0.0)), down, up).to_f()
    } };
    let bytes = V3::new(byte(0), byte(1), byte(2));
    let code = pack(&FIELDS, bytes);
    F::U::sel(ok, code, u(128 | 128 << 8 | 255 << 16))
}

/// Crytek's shader output: `(n / max|n|)·fetched·½ + ½` of the normalized input.
#[inline(always)]
pub fn encode_float<F: Float>(v: V3<F>, fetched: F) -> V3<F> {
    let u = crate::codecs::core::codec::unit_or_z(v);
    let (major, _, _) = sorted(u.map(#[inline(always)] |x| x.abs()));
    (u / major * fetched) * F::c(0.5) + F::c(0.5)
}

/// The emitted functions, and the CPU encoders that fetch from the table in memory.
fn emitted(spec_id: &str) -> Emitted {
    let texel = declared!(
        "fitting_texel",
        Role::LutTexel,
        Inputs::Vectors,
        ["v"],
        <F> [] |v: V3<F>| fitting_texel(v)
    );
    let with_scale = Inputs::VectorsWith(Extra {
        name: "the fitting table's value at fitting_texel(v)",
        words: 1,
        of: Arc::new(|v: &[u32]| {
            let t = fitting_texel::<f32>(V3::from_array(std::array::from_fn(|i| {
                f32::from_bits(v[i])
            })));
            vec![fetch(&[t.x, t.y]).to_bits()]
        }),
    });
    let enc = declared!(
        "encode",
        Role::Encode,
        with_scale.clone(),
        ["v", "fetched"],
        <F> [] |x: (V3<F>, F)| encode(x.0, x.1)
    );
    let enc_float = declared!(
        "encode_float",
        Role::EncodeFloat,
        with_scale,
        ["v", "fetched"],
        <F> [] |x: (V3<F>, F)| encode_float(x.0, x.1)
    );
    let lookup: WordsMap = Arc::new(|t: &[u32]| vec![fetch(t).to_bits()]);
    let cpu = [&enc, &enc_float]
        .map(|d| {
            let f = d.function();
            let (first, then) = (texel.function(), f);
            through_table(f.name, f.role, Inputs::Vectors, first, lookup.clone(), then, true)
        })
        .to_vec();
    let mut functions = codec_decoders(&Unorm3);
    functions.extend([texel, enc_float, enc]);
    let (module, functions) = trace_declared(functions);
    Emitted {
        module,
        functions,
        cpu,
        namespace: spec_id.to_string(),
        portable_encoder: true,
    }
}

/// The table's byte at the texel `t = [x, y]` as a unorm8 fetch returns it, `c·(1/255)`
/// (lavapipe's conversion, which [`encode`] rounds back to `c` however it is computed).
fn fetch(t: &[u32]) -> f32 {
    BYTE.dequantize(f32::from(fitting_table()[t[1] as usize * SIZE + t[0] as usize]))
}
