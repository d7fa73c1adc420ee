//! What linear filtering and multisample resolves do to a spec's float form: the figure
//! a G-buffer or normal-map user needs and nobody publishes.
//!
//! A texture unit filters the stored parameters, not the directions they decode to. The
//! parameters stored are what the float form's format ([`crate::codecs::core::storage`])
//! keeps of `encode_float`'s output: `s(v) = store(encode_float(v))`, rounded to its
//! channels as a render target rounds (an unquantized float form to its own fields, a
//! float form wider than any format of its size to the wider format's channels). So
//! for two neighbours `a`, `b` and a weight `w`, the filtered texel decodes to
//! `decode_float(lerp(s(a), s(b), w))`, while what the shader wanted is the renormalized
//! lerp of the two decoded directions, `normalize(lerp(decode_float(s(a)),
//! decode_float(s(b)), w))`. The angle between the two
//! is the filtering error. A resolve (an MSAA resolve or a 2×2 box mip) is the same with
//! four samples averaged with equal weights.
//!
//! The samples are seeded ([`SEED`]): for each separation θ, [`PAIRS`] pairs of unit
//! vectors exactly θ apart (the first uniform on the spec's domain, the second θ away
//! in a uniform direction, both in the domain) with a weight uniform in (0, 1); and
//! [`PAIRS`] resolves of four vectors uniform in a cap of angular radius θ/2 around a
//! uniform centre (so no two are more than θ apart). The filtering itself is computed
//! in f64 and rounded to f32, as a texture unit's exact filter would deliver it; the
//! codec arithmetic is the model's, in f32, on the CPU lanes.

use crate::codecs::core::info::Domain;
use crate::codecs::core::storage::Format;
use crate::codecs::functions::function::{Emitted, Function, Inputs, Role};
use crate::codecs::toolkit::quant::Quant;
use crate::measure::quality::angle_deg;
use rand_core::Rng;
use rand_pcg::Pcg64Mcg;
use serde::{Deserialize, Serialize};

/// The separations measured, in degrees.
pub const SEPARATIONS: [f64; 4] = [1.0, 5.0, 20.0, 45.0];
/// Pairs (and resolves) per separation.
pub const PAIRS: usize = 4096;
/// The seed of every sample.
pub const SEED: u128 = 0x0075_6e69_7470_6163_6b5f_6669_6c74_6572;
/// The percentile reported beside the mean and maximum.
pub const PERCENTILE: f64 = 99.0;
/// The separation whose 99th percentile decides filterability (`choose --filterable`,
/// `--by filter`): neighbouring texels of a smooth surface differ by a few degrees.
pub const DECIDING_SEPARATION: f64 = 5.0;

/// The error over one kind of sample at one separation.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct FilterStats {
    pub separation: f64,
    pub mean: f64,
    /// The [`PERCENTILE`]th percentile (nearest rank).
    pub p99: f64,
    /// The sample maximum over [`PAIRS`] samples.
    pub max: f64,
    /// The fraction of samples whose error exceeds 1°.
    pub over_1deg: f64,
}

/// A spec's filtering figures: linear filtering of pairs and four-sample resolves, one
/// entry per [`SEPARATIONS`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Filtering {
    pub lerp: Vec<FilterStats>,
    pub resolve: Vec<FilterStats>,
}

impl Filtering {
    /// The larger of the lerp's and the resolve's 99th percentile at
    /// [`DECIDING_SEPARATION`]: what `--filterable` and `--by filter` read.
    pub fn deciding_p99(&self) -> f64 {
        let at = |v: &[FilterStats]| {
            v.iter()
                .find(|s| s.separation == DECIDING_SEPARATION)
                .map_or(f64::INFINITY, |s| s.p99)
        };
        at(&self.lerp).max(at(&self.resolve))
    }
}

fn uniform(rng: &mut Pcg64Mcg) -> f64 {
    // 53 random bits in [0, 1).
    (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// A uniform unit vector (f64), on +Z for the hemisphere.
fn random_unit(rng: &mut Pcg64Mcg, hemisphere: bool) -> [f64; 3] {
    let z = 2.0 * uniform(rng) - 1.0;
    let z = if hemisphere { z.abs() } else { z };
    let phi = std::f64::consts::TAU * uniform(rng);
    let r = (1.0 - z * z).max(0.0).sqrt();
    [r * phi.cos(), r * phi.sin(), z]
}

/// `c` turned by `angle` (radians) towards the direction `phi` around it.
fn turned(c: [f64; 3], angle: f64, phi: f64) -> [f64; 3] {
    // An orthonormal basis (t, u) of the plane orthogonal to c.
    let helper = if c[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let t = normalize(cross(c, helper));
    let u = cross(c, t);
    let (s, k) = angle.sin_cos();
    let (sp, cp) = phi.sin_cos();
    std::array::from_fn(|i| c[i] * k + s * (cp * t[i] + sp * u[i]))
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn normalize(a: [f64; 3]) -> [f64; 3] {
    let l = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    a.map(|x| x / l)
}

fn to_f32(v: [f64; 3]) -> [f32; 3] {
    normalize(v).map(|x| x as f32)
}

/// Groups of `k` vectors: pairs θ apart (`k` = 2) or four in a cap of radius θ/2.
fn groups(seed_offset: u64, k: usize, theta: f64, hemisphere: bool) -> Vec<[f32; 3]> {
    let mut rng = Pcg64Mcg::new(SEED ^ u128::from(seed_offset));
    let mut out = Vec::with_capacity(PAIRS * k);
    while out.len() < PAIRS * k {
        let c = random_unit(&mut rng, hemisphere);
        let group: Vec<[f64; 3]> = if k == 2 {
            let phi = std::f64::consts::TAU * uniform(&mut rng);
            vec![c, turned(c, theta, phi)]
        } else {
            // Uniform in the cap: cos of the angle uniform in [cos(θ/2), 1].
            let lo = (theta / 2.0).cos();
            (0..k)
                .map(|_| {
                    let cos = lo + (1.0 - lo) * uniform(&mut rng);
                    let phi = std::f64::consts::TAU * uniform(&mut rng);
                    turned(c, cos.clamp(-1.0, 1.0).acos(), phi)
                })
                .collect()
        };
        if hemisphere && group.iter().any(|v| v[2] < 0.0) {
            continue;
        }
        out.extend(group.into_iter().map(to_f32));
    }
    out
}

/// The weights of each group's members: `(1 - w, w)` for pairs, `¼` each for resolves.
fn weights(seed_offset: u64, k: usize) -> Vec<f64> {
    if k == 4 {
        return vec![0.25; PAIRS * 4];
    }
    let mut rng = Pcg64Mcg::new(SEED ^ u128::from(seed_offset) ^ (1 << 64));
    (0..PAIRS)
        .flat_map(|_| {
            // In (0, 1): a zero weight is no filtering.
            let w = (uniform(&mut rng) * ((1u64 << 53) - 1) as f64 + 1.0) / (1u64 << 53) as f64;
            [1.0 - w, w]
        })
        .collect()
}

/// Parameters (the float form's words, any number of items) → three words a vector.
pub type Decoder<'a> = &'a (dyn Fn(&[u32], &mut [u32]) + Sync);

/// The filtering error of each group of `k` vectors of `vs` (`weights` one per vector,
/// summing to 1 in each group): the angle in degrees between the decoded filtered
/// parameters and the renormalized weighted sum of the decoded vectors, both from what
/// `storage` stores of the encoded parameters.
pub fn errors(
    enc: &Function,
    storage: &Format,
    dec: Decoder,
    k: usize,
    vs: &[[f32; 3]],
    weights: &[f64],
) -> Vec<f64> {
    let words = enc.out_words;
    let groups = vs.len() / k;
    let input: Vec<u32> = vs.iter().flat_map(|v| v.map(f32::to_bits)).collect();
    let mut params = vec![0u32; vs.len() * words];
    enc.eval_many(&input, &mut params);
    // What the render target stores of each item.
    for item in params.chunks_exact_mut(words) {
        let mut p: Vec<f32> = item.iter().map(|w| f32::from_bits(*w)).collect();
        storage.store(&mut p);
        for (w, x) in item.iter_mut().zip(p) {
            *w = x.to_bits();
        }
    }
    let mut decoded = vec![0u32; vs.len() * 3];
    dec(&params, &mut decoded);
    // The filtered parameters of each group, in f64, rounded once.
    let mut filtered = vec![0u32; groups * words];
    for g in 0..groups {
        for c in 0..words {
            let sum: f64 = (0..k)
                .map(|m| {
                    let p = f32::from_bits(params[(g * k + m) * words + c]);
                    weights[g * k + m] * f64::from(p)
                })
                .sum();
            filtered[g * words + c] = (sum as f32).to_bits();
        }
    }
    let mut out = vec![0u32; groups * 3];
    dec(&filtered, &mut out);
    (0..groups)
        .map(|g| {
            let mut want = [0f64; 3];
            for m in 0..k {
                let d = &decoded[(g * k + m) * 3..][..3];
                for (w, x) in want.iter_mut().zip(d) {
                    *w += weights[g * k + m] * f64::from(f32::from_bits(*x));
                }
            }
            let got = [0, 1, 2].map(|c| f32::from_bits(out[g * 3 + c]));
            let e = angle_deg(got, want.map(|x| x as f32));
            // A NaN decode (a filtered value outside the decoder's domain) counts as
            // the worst error.
            if e.is_nan() { 180.0 } else { e }
        })
        .collect()
}

/// The figures of sorted `errors`.
fn stats(separation: f64, errors: &mut [f64]) -> FilterStats {
    errors.sort_by(f64::total_cmp);
    let n = errors.len();
    let rank = ((PERCENTILE / 100.0 * n as f64).ceil() as usize).max(1) - 1;
    FilterStats {
        separation,
        mean: errors.iter().sum::<f64>() / n as f64,
        p99: errors[rank],
        max: errors[n - 1],
        over_1deg: errors.iter().filter(|&&e| e > 1.0).count() as f64 / n as f64,
    }
}

/// The filtering figures of a spec whose float form is `enc` (vector → parameters) and
/// `dec` (parameters → vector) on `domain`.
pub fn measure_functions(
    enc: &Function,
    storage: &Format,
    dec: Decoder,
    domain: Domain,
) -> Filtering {
    let hemisphere = domain == Domain::Hemisphere;
    let run = |k: usize, kind: u64| -> Vec<FilterStats> {
        SEPARATIONS
            .iter()
            .enumerate()
            .map(|(i, &deg)| {
                let offset = kind * 16 + i as u64;
                let vs = groups(offset, k, deg.to_radians(), hemisphere);
                let mut e = errors(enc, storage, dec, k, &vs, &weights(offset, k));
                stats(deg, &mut e)
            })
            .collect()
    };
    Filtering {
        lerp: run(2, 0),
        resolve: run(4, 1),
    }
}

/// The filtering figures of a spec ([`Emitted`] is its traced functions) whose float
/// form is stored in `storage`, or `None` when it has no CPU float form that takes a
/// vector alone.
///
/// A float form whose decoder reads a lookup table's texel beside the parameters
/// (`spherical_lut`: the texel of the sin/cos table at the code) is read as a shader
/// reads a filtered texel of it: the filtered parameters rounded to the nearest code of
/// each unorm field, and that code decoded through the table.
pub fn measure(e: &Emitted, storage: &Format, domain: Domain) -> Option<Filtering> {
    let enc = e.cpu_function(Role::EncodeFloat)?;
    if enc.in_words != 3 {
        return None;
    }
    let dec = e.cpu_function(Role::DecodeFloat)?;
    if dec.in_words == enc.out_words && dec.out_words == 3 {
        return Some(measure_functions(
            enc,
            storage,
            &|p, o| dec.eval_many(p, o),
            domain,
        ));
    }
    let code_dec = e.cpu_function(Role::Decode)?;
    let Inputs::Codes(fields) = &code_dec.inputs else {
        return None;
    };
    if code_dec.in_words != 1
        || fields.len() != enc.out_words
        || !fields.iter().all(|q| matches!(q, Quant::Unorm(_)))
    {
        return None;
    }
    let through_table = |params: &[u32], out: &mut [u32]| {
        // First field in the lowest bits, as every packed code.
        let codes: Vec<u32> = params
            .chunks_exact(fields.len())
            .map(|p| {
                let mut code = 0u32;
                let mut shift = 0;
                for (word, q) in p.iter().zip(fields) {
                    let m = q.max_code();
                    let c = (f32::from_bits(*word).clamp(0.0, 1.0) * m).round_ties_even();
                    code |= (c as u32) << shift;
                    shift += q.bits();
                }
                code
            })
            .collect();
        code_dec.eval_many(&codes, out)
    };
    Some(measure_functions(enc, storage, &through_table, domain))
}
