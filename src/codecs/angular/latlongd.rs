//! The survey's `latlongD` (Smith et al. 2012, "Optimal Spherical Coordinates", with the
//! precise decoder): latitude rings of nearly equal-area patches, numbered ring by ring
//! from +Z, each code one patch, decoded to the patch's centre through a table of rings.
//!
//! **Rings.** `Nφ` rings at the polar angles `θ_j = π·j/(Nφ - 1)`, the poles one patch
//! each. Ring `j` holds `Nθ(j)` patches at the azimuths `φ = π·(2k/Nθ(j) - 1)`, as few as
//! keep every point of the ring's band (`θ_j ± π/(2(Nφ - 1))`) within `ε` of a patch
//! centre: with `p = π·min(j, Nφ - 1 - j)/(Nφ - 1)` and `p' = p + π/(2(Nφ - 1))`,
//! `Nθ(j) = ceil(π / acos((cos ε - cos p·cos p')/(sin p·sin p')))`, computed in a form
//! without cancellation ([`counts`]). For a size of `B`
//! bits, `ε` is the least for which the rings hold at most `2^B` patches (found by
//! bisection), and `Nφ` the count of rings whose least `ε` was smallest in a one-off scan
//! (kept as [`RINGS`]; the tests check that two ring counts either side need more at 16
//! and 24 bits): 227 rings and `ε = 0.562432°` at 16 bits (65,536 patches), 3629 and
//! 0.035069° at 24 (16,777,216), 58075 and 0.00219148° at 32 (4,294,967,144; the 152
//! codes above decode as -Z). By construction every point of a patch is within `ε` of its
//! centre; the codec's error adds what the encoder's angle grid (`2^-23` half turns) can
//! move an input across a patch boundary and the decoder's float error, a few `10^-5`
//! degrees, which no proof here bounds (the 32-bit sample max is 0.00221°). The table is
//! computed in f64 with `libm`'s functions, which compute the same bits on every machine.
//!
//! **The ring table**: entry `j` is `(offset, count)`, two u32: the first code of ring
//! `j` and `Nθ(j)` (`unitpack generate` writes it to `generated/lut/` as raw
//! little-endian words). Bind it as a storage buffer of `vec2<u32>` (or an RG32UI texture
//! of your own layout).
//!
//! ```text
//! encode:  j = encode_ring(v)             the input's ring, round(θ·(Nφ - 1)/π)
//!          code = encode(v, rings[j])     offset + round(φ·count/2π) (mod count)
//! decode:  g = decode_ring(code)          the ring's first guess
//!          p = decode_params(code, g, rings[g], rings[g + 1])
//!          n = decode_float(p)            the patch centre (the fast latlong's grid_direction)
//! ```
//!
//! `decode_ring` inverts the equal-area count: a code's fraction of the sphere's patches,
//! `u = (c + ½)/total` (mirrored onto the northern half), is at the polar angle
//! `acos(1 - 2u)`, in rings `G`; the guess is `floor(G)`, and the code's ring is `g` or
//! `g + 1` wherever `|G - ring| < 1`: `tests/families/latlongd.rs` checks that for every code at
//! 16 and 24 bits, and at 32 at every ring's first and last code, where the real-valued
//! `G`, which is monotone in the code, is also checked within 0.9 rings of the ring (the
//! model's `G` follows it to within a few hundredths of a ring, the trigonometry's
//! error).
//!
//! Every integer output (the rings, the code, the parameters `decode_params` hands to
//! `decode_float`) is decided exactly: angles from the model's fixed-point trigonometry
//! ([`fixed_trig`]), quotients by comparing products ([`fixed_ratio`]), conversions of
//! words above `2^24` by [`float_of`], so every implementation computes the same.

use crate::model::num::helper;
use crate::codecs::core::codec::unpack;
use crate::codecs::core::info::Domain;
use crate::codecs::toolkit::exact::{canonical_or_z, fixed_ratio, float_of, root_of};
use crate::codecs::core::info::{Info, Sizes, FloatForm, seam};
use crate::codecs::core::spec::{Family, Table, TableFormat, Tracing};
use crate::codecs::toolkit::fixed_trig::{self, ONE};
use crate::codecs::functions::decode_boxes::fetched_range;
use crate::codecs::functions::function::{Emitted, Enclose, Extra, Function, Inputs, Role, WordsMap};
use crate::codecs::core::pipeline::through_table;
use crate::codecs::functions::words::{Declared, declared, trace_declared};
use crate::codecs::angular::latlong::grid_direction;
use crate::codecs::toolkit::quant::Quant;
use crate::codecs::core::spec::Spec;
use crate::codecs::core::storage;
use crate::codecs::angular::spherical::fixed_angles;
use crate::model::enclosure::Encl;
use crate::model::{Bool, Float, Uint, V2, V3};
use std::sync::{Arc, OnceLock};

pub static FAMILY: LatlongDFamily = LatlongDFamily;

pub struct LatlongDFamily;

static INFO: Info = Info {
    name: "latlongd",
    title: "latitude rings of equal-area patches numbered by ring, decoded through a ring table",
    sizes: Sizes::Total(&[16, 24, 32]),
    domain: Some(Domain::Sphere),
    source: "Cigolle et al. 2014 §2.3 (Smith et al. 2012), precise decoder",
    edge_policy: "input is normalized first; zero, NaN and infinite input encode as code 0 (+Z), whatever was fetched",
    decode_note: "decodes are unit length to within the trig approximations' error (about 2.5e-7)",
    float_form: FloatForm::Unfilterable {
        why: FloatForm::INDEX_SPLIT,
        seam: seam::AZIMUTH_WRAP,
    },
    options: &[],
};

/// The ring counts `Nφ` of the three sizes, from a one-off scan for the least `ε`.
pub const RINGS: [(u32, u32); 3] = [(16, 227), (24, 3629), (32, 58075)];

/// The fixed point of the azimuth's fraction of a turn in `decode_params`.
const TURN_BITS: u32 = 24;

impl Family for LatlongDFamily {
    fn info(&self) -> &Info {
        &INFO
    }
    fn precise(&self) -> bool {
        // Its encoder is latlong's; the ring table serves the decoder only.
        false
    }
    fn emitted(&self, spec: &Spec, _: Tracing) -> Emitted {
        emitted(&spec.id(), spec.bits())
    }
    fn tables(&self, spec: &Spec) -> Vec<Table> {
        let rings = Rings::of(spec.bits());
        vec![Table {
            stem: format!("{}_rings", spec.id()),
            width: rings.entries.len() as u32,
            height: 1,
            channels: 2,
            format: TableFormat::Uint32,
            bytes: rings
                .entries
                .iter()
                .flat_map(|e| e.iter().flat_map(#[inline(always)] |w| w.to_le_bytes()))
                .collect(),
        }]
    }
    fn function_doc(&self, spec: &Spec, name: &str) -> Option<Vec<String>> {
        let r = Rings::of(spec.bits());
        let (n, last) = (r.entries.len(), r.entries.len() - 1);
        let lines = match name {
            "encode_ring" => vec![
                "In: any vector; zero, NaN and infinite input read ring 0.".to_string(),
                format!("Out: the input's ring j in 0 … {last}, round(θ·{last}/π) of its polar angle θ, decided exactly (the same on every implementation): the entry of the ring table ({n} entries of (offset, count), u32 each) that encode reads."),
            ],
            "encode" => vec![
                "In: any vector, and `ring`, the ring table's entry (offset, count) at encode_ring(v).".to_string(),
                "Out: the packed code, offset + k with k = round(φ·count/2π) mod count of the input's azimuth φ + π, decided exactly; 0 (+Z) for zero, NaN and infinite input.".to_string(),
            ],
            "encode_float" => vec![
                "In: as encode.".to_string(),
                {
                    let h = spec.bits() / 2;
                    let m = (1u64 << h) - 1;
                    let stored = match storage::float_form_format(&[Quant::Unorm(h); 2]) {
                        Some((f, true)) => format!("for an {} render target ({} bits a texel), which stores exactly that code", f.texture.unwrap_or(f.vulkan), f.bits),
                        Some((f, false)) => format!("for an {} render target ({} bits a texel: no {}-bit format has two unorm{h} channels, and its wider channels round the values; decode the packed code where the exact code matters)", f.texture.unwrap_or(f.vulkan), f.bits, spec.bits()),
                        None => "which no real format stores exactly".to_string(),
                    };
                    format!("Out: encode's code as two unorm{h} fields (low bits first) read as c/{m}, {stored}.")
                },
            ],
            "decode_ring" => vec![
                "In: a packed code (bits above the size are ignored).".to_string(),
                format!("Out: the guess g in 0 … {} for the code's ring, from the equal-area count, decided exactly: fetch the ring table's entries g and g + 1 for decode_params (the code's ring is one of them).", last - 1),
            ],
            "decode_params" => vec![
                "In: a packed code (bits above the size are ignored), g = decode_ring(code), and the ring table's entries (offset, count) at g and g + 1.".to_string(),
                format!(
                    "Out: (k/count, j/{last}) of the code's patch k in its ring j, the parameters decode_float reads, decided exactly (k/count floored to 2^-24, within one unit where a product's rounding decides a near tie){}.",
                    if u64::from(r.total) < 1u64 << spec.bits() {
                        format!("; the {} codes at or past {} decode as -Z", (1u64 << spec.bits()) - u64::from(r.total), r.total)
                    } else {
                        String::new()
                    }
                ),
            ],
            "decode_float" => vec![
                "In: (azimuth, polar angle) as fractions of a turn and of a half turn, as decode_params returns them.".to_string(),
            ],
            _ => return None,
        };
        Some(lines)
    }
}

/// The ring table of one size.
#[derive(Debug)]
pub struct Rings {
    /// Per ring, `(offset, count)`.
    pub entries: Vec<[u32; 2]>,
    /// The number of patches (codes in use).
    pub total: u32,
    /// The error bound `ε`, in radians.
    pub epsilon: f64,
    /// The size.
    pub bits: u32,
}

impl Rings {
    /// The table of a size in [`RINGS`], computed once per process.
    pub fn of(bits: u32) -> &'static Rings {
        static TABLES: [OnceLock<Rings>; 3] = [const { OnceLock::new() }; 3];
        let at = RINGS
            .iter()
            .position(|&(b, _)| b == bits)
            .expect("a latlongd size");
        TABLES[at].get_or_init(|| Rings::build(bits, RINGS[at].1))
    }

    /// The rings of `nphi` latitudes with the least `ε` whose patches fit `2^bits` codes.
    pub fn build(bits: u32, nphi: u32) -> Rings {
        let budget = 1u64 << bits;
        let rings = ring_sines(nphi);
        let fits = |eps: f64| counts(&rings, nphi, eps).is_some_and(#[inline(always)] |c| c.iter().sum::<u64>() <= budget);
        let (mut lo, mut hi) = (1e-9, 0.2);
        for _ in 0..64 {
            let mid = 0.5 * (lo + hi);
            if fits(mid) {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        let counts = counts(&rings, nphi, hi).expect("the bisection's upper end fits");
        let mut offset = 0u64;
        let entries: Vec<[u32; 2]> = counts
            .iter()
            .map(|&n| {
                let e = [offset as u32, n as u32];
                offset += n;
                e
            })
            .collect();
        assert!(offset < 1u64 << 32, "the total fits a word");
        Rings {
            entries,
            total: offset as u32,
            epsilon: hi,
            bits,
        }
    }

    fn rings(&self) -> u32 {
        self.entries.len() as u32
    }

    /// The entry of ring `j` as words.
    fn entry(&self, j: u32) -> [u32; 2] {
        self.entries[j as usize]
    }
}

/// `sin p·sin q` of each ring between the poles (`p` its polar angle from the nearer
/// pole, so that mirrored rings compute the same count; `q = p + Δ/2`).
fn ring_sines(nphi: u32) -> Vec<f64> {
    let dphi = std::f64::consts::PI / f64::from(nphi - 1);
    let d = 0.5 * dphi;
    (1..nphi - 1)
        .map(|j| {
            let p = f64::from(j.min(nphi - 1 - j)) * dphi;
            libm::sin(p) * libm::sin(p + d)
        })
        .collect()
}

/// Patches per ring for `nphi` rings and error `eps` (radians); `None` where `eps` is too
/// small for the rings' spacing. The half-width `h` of a patch solves
/// `cos ε = cos p·cos q + sin p·sin q·cos h` (`q = p + Δ/2`, Δ the rings' spacing),
/// written without cancellation as
/// `sin²(h/2) = sin((ε - Δ/2)/2)·sin((ε + Δ/2)/2) / (sin p·sin q)`, so that the count
/// `ceil(π/h)` is accurate to f64's precision even at 32 bits, where `cos ε` is within
/// `10^-9` of 1.
///
/// `rings` holds [`ring_sines`]: the bisection over `eps` asks for the counts 64 times,
/// and only the numerator depends on `eps`.
fn counts(rings: &[f64], nphi: u32, eps: f64) -> Option<Vec<u64>> {
    use std::f64::consts::PI;
    let d = 0.5 * (PI / f64::from(nphi - 1));
    if eps <= d {
        return None;
    }
    let numerator = libm::sin(0.5 * (eps - d)) * libm::sin(0.5 * (eps + d));
    let mut out = vec![1u64];
    for &sines in rings {
        let s2 = numerator / sines;
        out.push(if s2 >= 1.0 {
            1
        } else {
            (PI / (2.0 * libm::asin(libm::sqrt(s2)))).ceil() as u64
        });
    }
    out.push(1);
    Some(out)
}

/// The code's fields: its low and high halves, both unorm (the word is the code).
fn fields(bits: u32) -> [Quant; 2] {
    [Quant::Unorm(bits / 2); 2]
}

/// The input's ring: `round(θ·(Nφ - 1))` of its polar angle `θ` in half turns from
/// [`fixed_angles`] (units of `2^-23`, `2θ - 1` there): one exact sum, one product with
/// a literal (`Nφ - 1` below `2^16`, so the literal is exact), rounded once.
#[inline(always)]
pub fn encode_ring<F: Float>(r: &Rings, v: V3<F>) -> F::U {
    let (theta, _) = fixed_angles(canonical_or_z(v).0);
    let scale = F::c((f64::from(r.rings() - 1) / (2.0 * ONE)) as f32);
    ((theta + F::c(ONE as f32)) * scale).round().to_u()
}

/// The code: `offset + k`, `k = round(t·count·2^-24)` of the azimuth `t = φ + 1` in units
/// of `2^-23` half turns (`[0, 2^24]`, exact), `count` wrapping to 0. The product of two
/// exact integers is rounded once; no sum follows it before the rounding to a code.
#[inline(always)]
pub fn encode<F: Float>(v: V3<F>, ring: V2<F::U>) -> F::U {
    let (w, ok) = canonical_or_z(v);
    let (_, phi) = fixed_angles(w);
    let t = phi + F::c(ONE as f32);
    let count = ring.y;
    let k = (t * count.to_f() * F::c((0.5 / ONE) as f32)).round().to_u();
    let k = F::U::sel(k.lt(count), k, F::U::c(0));
    F::U::sel(ok, ring.x.wrapping_add(k), F::U::c(0))
}

/// The code's two halves as `c/M`.
#[inline(always)]
pub fn encode_float<F: Float>(bits: u32, v: V3<F>, ring: V2<F::U>) -> V2<F> {
    let q = fields(bits);
    let code = helper!(encode(v, ring));
    crate::codecs::core::codec::dequantize(&q, unpack::<F, V2<F>, F::U>(&q, code))
}

/// The code's own bits (those above the size are ignored), a code past the last patch
/// read as the last (-Z).
#[inline(always)]
fn code_in_use<F: Float>(r: &Rings, code: F::U) -> F::U {
    let last = F::U::c(r.total - 1);
    let code = if r.bits < 32 {
        code & F::U::c((1u32 << r.bits) - 1)
    } else {
        code
    };
    F::U::sel(code.lt(last), code, last)
}

/// The guess `g` for the code's ring (see the module's documentation). With the code
/// mirrored onto the northern half (`cc`), `u = a/total` for `a = cc + ½` and
/// `1 - u = b/total`, so `G = atan2(2·sqrt(a·b), b - a)/π·(Nφ - 1)`: here
/// `2·sqrt(a·b) = sqrt(A·B)` with the integers `A = 2cc + 1` and `B = 2(total - cc) - 1`,
/// and `b - a = total - 1 - 2cc`, all formed in integers and converted by [`float_of`]
/// (no float sum a compiler could regroup), the root by [`root_of`], the angle by
/// [`fixed_trig::atan2_pi`]; then floored (the southern half: `Nφ - 1 - ceil`) and
/// clamped to `[0, Nφ - 2]`.
#[inline(always)]
pub fn decode_ring<F: Float>(r: &Rings, code: F::U) -> F::U {
    let u = { #[inline(always)] |x: u32| F::U::c(x) };
    let last = r.total - 1;
    let c = code_in_use::<F>(r, code);
    let south = c.lt(u(r.total.div_ceil(2))).not();
    let cc = F::U::sel(south, u(last).wrapping_sub(c), c);
    let a = float_of::<F>(cc + cc + u(1));
    // 2·(total - 1 - cc) + 1: the doubling is exact, and the sum has two terms.
    let b = float_of::<F>(u(last).wrapping_sub(cc)) * F::c(2.0) + F::c(1.0);
    let x = float_of::<F>(u(last).wrapping_sub(cc + cc));
    let th = fixed_trig::atan2_pi(root_of(a * b), x);
    let g = th * F::c((f64::from(r.rings() - 1) / ONE) as f32);
    let north = g.floor();
    // Nφ - 1 - ceil(G), the ceiling as the floor of the negation (exact).
    let southern = F::c((r.rings() - 1) as f32) + (F::c(0.0) - g).floor();
    let g = F::sel(south, southern, north).clamped(F::c(0.0), F::c((r.rings() - 2) as f32));
    g.to_u()
}

/// The parameters of the code's patch: ring `g + 1` where the code is at or past its
/// offset, else `g`; `k = code - offset`; `(k/count, ring/(Nφ - 1))`, the first by
/// [`fixed_ratio`] on a `2^-24` grid, the second one product with a literal.
#[inline(always)]
pub fn decode_params<F: Float>(r: &Rings, code: F::U, g: F::U, e0: V2<F::U>, e1: V2<F::U>) -> V2<F> {
    let c = code_in_use::<F>(r, code);
    let next = c.lt(e1.x).not();
    let ring = F::U::sel(next, g + F::U::c(1), g);
    let offset = F::U::sel(next, e1.x, e0.x);
    let count = F::U::sel(next, e1.y, e0.y);
    let k = c.wrapping_sub(offset);
    // Through an integer, so that a floor's zero keeps its sign (+0) everywhere.
    let turn = fixed_ratio(k.to_f(), count.to_f(), TURN_BITS).to_u().to_f()
        * F::c((1.0 / f64::from(1u32 << TURN_BITS)) as f32);
    let polar = ring.to_f() * F::c((1.0 / f64::from(r.rings() - 1)) as f32);
    V2::new(turn, polar)
}

/// `decode_params`' arguments as a function takes them: the code, the guess and the two
/// entries, nested in pairs.
type ParamsArgs<F> = (
    <F as Float>::U,
    (<F as Float>::U, (V2<<F as Float>::U>, V2<<F as Float>::U>)),
);

/// The emitted functions, and the CPU encoders and decoder that fetch from the ring table
/// in memory.
fn emitted(spec_id: &str, bits: u32) -> Emitted {
    type U<F> = <F as Float>::U;
    let r = Rings::of(bits);
    let q = fields(bits);
    // decode_float's parameters: any in [0, 1]² (unorm16 fetches as verify inputs; the
    // bound is proven over the whole square).
    let params = [Quant::Unorm(16); 2];
    let mut dec_float = declared!(
        "decode_float",
        Role::DecodeFloat,
        Inputs::FloatCodes(params.to_vec()),
        ["params"],
        <F> [] |p: V2<F>| grid_direction(p)
    );
    dec_float.function_mut().enclose = Some(Enclose {
        eval: Arc::new(move |b: &[(i64, i64)]| {
            let p = V2::new(fetched_range(params[0], b[0]), fetched_range(params[1], b[1]));
            grid_direction::<Encl>(p).to_array().to_vec()
        }),
        whole_field: None,
        unread: &[],
        fixed: Vec::new(),
        budget: None,
        parts: None,
    });
    let ring = declared!(
        "encode_ring",
        Role::LutTexel,
        Inputs::Vectors,
        ["v"],
        <F> [] |v: V3<F>| encode_ring(r, v)
    );
    let with_ring = Inputs::VectorsWith(Extra {
        name: "the ring table's entry at encode_ring(v)",
        words: 2,
        of: Arc::new(move |v: &[u32]| {
            let j = encode_ring::<f32>(r, V3::from_array(std::array::from_fn(|i| f32::from_bits(v[i]))));
            r.entry(j).to_vec()
        }),
    });
    let enc = declared!(
        "encode",
        Role::Encode,
        with_ring.clone(),
        ["v", "ring"],
        <F> [] |x: (V3<F>, V2<U<F>>)| encode(x.0, x.1)
    );
    let enc_float = declared!(
        "encode_float",
        Role::EncodeFloat,
        with_ring,
        ["v", "ring"],
        <F> [] |x: (V3<F>, V2<U<F>>)| encode_float(bits, x.0, x.1)
    );
    let guess = declared!(
        "decode_ring",
        Role::LutTexel,
        Inputs::Codes(q.to_vec()),
        ["code"],
        <F> [] |c: U<F>| decode_ring::<F>(r, c)
    );
    // A guess's words → the guess and the entries g and g + 1.
    let pair: WordsMap = Arc::new(move |g: &[u32]| {
        let mut out = vec![g[0]];
        out.extend(r.entry(g[0]));
        out.extend(r.entry(g[0] + 1));
        out
    });
    let params_fn = declared!(
        "decode_params",
        Role::LutTexel,
        Inputs::CodesWith(
            q.to_vec(),
            Extra {
                name: "decode_ring(code) and the ring table's entries there and after",
                words: 5,
                of: {
                    let pair = pair.clone();
                    Arc::new(move |c: &[u32]| pair(&[decode_ring::<f32>(r, c[0])]))
                },
            }
        ),
        ["code", "g", "ring0", "ring1"],
        <F> [] |x: ParamsArgs<F>| decode_params::<F>(r, x.0, x.1.0, x.1.1.0, x.1.1.1)
    );
    let lookup: WordsMap = Arc::new(move |j: &[u32]| r.entry(j[0]).to_vec());
    let cpu_enc = |d: &Declared| {
        let f = d.function();
        through_table(f.name, f.role, Inputs::Vectors, ring.function(), lookup.clone(), f, true)
    };
    let cpu = vec![
        cpu_enc(&enc),
        cpu_enc(&enc_float),
        cpu_decode(&q, guess.function(), pair, params_fn.function(), dec_float.function()),
    ];
    // `encode` before `encode_float`, which calls it: the first definition names the
    // parameters.
    let (module, functions) = trace_declared(vec![dec_float, ring, enc, enc_float, guess, params_fn]);
    Emitted {
        module,
        functions,
        cpu,
        namespace: spec_id.to_string(),
        portable_encoder: true,
    }
}

/// The CPU decoder: `decode_ring`, the two entries from the table in memory,
/// `decode_params`, then `decode_float`.
fn cpu_decode(
    q: &[Quant; 2],
    guess: &Function,
    pair: WordsMap,
    params: &Function,
    dec_float: &Function,
) -> Function {
    let to_params = through_table(
        "decode_params",
        Role::LutTexel,
        Inputs::Codes(q.to_vec()),
        guess,
        pair,
        params,
        true,
    );
    let same: WordsMap = Arc::new(|w: &[u32]| w.to_vec());
    let mut dec = through_table(
        "decode",
        Role::Decode,
        Inputs::Codes(q.to_vec()),
        &to_params,
        same,
        dec_float,
        false,
    );
    dec.parts = vec!["decode_ring", "decode_params", "decode_float"];
    dec
}
