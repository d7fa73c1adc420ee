//! The inputs every function is verified on: every code up to 24 bits, seeded
//! random codes above; seeded random unit vectors plus every edge case for encoders.

use crate::codecs::functions::function::Inputs;
use crate::codecs::toolkit::half::half_value;
use crate::codecs::toolkit::quant::{Quant, field_offsets};
use crate::support::sampling::random_unit_vectors;
use rand_core::Rng;
use rand_pcg::Pcg64Mcg;

/// Random items for budgets above 24 bits and for encoders.
pub const RANDOM_ITEMS: usize = 1 << 20;
const CODE_SEED: u128 = 0x636f_6465_735f_7365_6564_5f75_6e69_7470;

/// Encoder edge cases: axes and signed zeros, octant and seam boundaries, denormals,
/// zero, NaN, infinities, non-unit lengths.
pub fn edge_vectors() -> Vec<[f32; 3]> {
    let specials = [
        0.0,
        -0.0,
        1.0,
        -1.0,
        0.5,
        -0.5,
        f32::MIN_POSITIVE,
        -f32::MIN_POSITIVE,
        1e-45,
        -1e-45,
        f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::MAX,
        -f32::MAX,
        1e-30,
        1e30,
        3.0,
        std::f32::consts::FRAC_1_SQRT_2,
        -std::f32::consts::FRAC_1_SQRT_2,
        1.0 / 3.0,
    ];
    let mut out = Vec::new();
    for &x in &specials {
        for &y in &specials {
            for &z in &specials {
                out.push([x, y, z]);
            }
        }
    }
    // Seams and fold lines of the square: |x| + |y| = 1 on the equator, x = ±y.
    for i in 0..=64 {
        let t = i as f32 / 64.0;
        for (sx, sy) in [(1.0, 1.0), (-1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)] {
            out.push([sx * t, sy * (1.0 - t), 0.0]);
            out.push([sx * t, sy * (1.0 - t), -0.0]);
            out.push([sx * t, sy * t, 1.0 - t]);
            out.push([sx * t, sy * t, t - 1.0]);
        }
    }
    out
}

/// Every code of the fields, or above 24 bits every value of each 16-bit field (f16
/// fields: every pattern; f32 fields: every sign, exponent and top 7 fraction bits, so
/// zeros, denormals, infinities and NaNs) followed by seeded random codes, as packed words.
pub fn codes(q: &[Quant], words: usize) -> Vec<u32> {
    let total: u32 = q.iter().map(|q| q.bits()).sum();
    let mut out = Vec::new();
    if total <= 24 {
        out.extend(0..1u32 << total);
        // The same codes with garbage in the unused high bits, which decoders ignore.
        let mut rng = Pcg64Mcg::new(CODE_SEED);
        out.extend((0..4096).map(|_| rng.next_u32() | (u32::MAX << total)));
        return out;
    }
    for item in wide_codes(q) {
        out.extend(item.iter().take(words));
    }
    out
}

/// The items above 24 bits: the sweeps, then seeded random words.
fn wide_codes(q: &[Quant]) -> impl Iterator<Item = [u32; 3]> + use<'_> {
    let mut rng = Pcg64Mcg::new(CODE_SEED);
    let random = (0..RANDOM_ITEMS).map(move |_| [0; 3].map(|_: u32| rng.next_u32()));
    (0..sweep_items(q))
        .map(|k| swept(q, k))
        .chain(texel_pairs(q))
        .chain(random)
}

/// For an RGBA8 texel (four 8-bit fields): every pair of channels takes every pair of
/// values, the other two full (255). A texel layout's decoder reads two channels (xra
/// three, of which R or A is full), so this covers every texel an encoder writes, where
/// random words alone would meet most, not all.
fn texel_pairs(q: &[Quant]) -> impl Iterator<Item = [u32; 3]> + use<> {
    let texel = q.len() == 4 && q.iter().all(|f| f.bits() == 8);
    let pairs: &[(u32, u32)] = if texel {
        &[(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)]
    } else {
        &[]
    };
    pairs.iter().flat_map(|&(i, j)| {
        (0..1u32 << 16).map(move |k| {
            let hole = !(0xff << (8 * i) | 0xff << (8 * j));
            [hole | (k & 0xff) << (8 * i) | (k >> 8) << (8 * j), 0, 0]
        })
    })
}

/// Items that give every 16-bit field every value: 2^16 when the layout has such a field
/// (or an f32 field, whose top 16 bits take every value).
fn sweep_items(q: &[Quant]) -> u32 {
    if q.iter().any(|f| f.bits() == 16 || *f == Quant::Single) {
        1 << 16
    } else {
        0
    }
}

/// Item `k` of the sweep: the `i`-th 16-bit field holds `k` times an odd constant (a
/// permutation of the 2^16 values, a different one per field), other fields random-looking
/// values of the same kind (an f32 field the same in its top 16 bits, zeros below, so
/// that infinities and zeros occur); packed like [`crate::codecs::core::codec::pack`].
fn swept(q: &[Quant], k: u32) -> [u32; 3] {
    const ODD: [u32; 4] = [1, 40_503, 9_973, 54_251];
    let offs = field_offsets(q);
    let mut w = [0u32; 3];
    for (i, (f, off)) in q.iter().zip(offs).enumerate() {
        let v = match f {
            Quant::Single => (k.wrapping_mul(ODD[i]) & 0xffff) << 16,
            _ => k.wrapping_mul(ODD[i]) & f.mask(),
        };
        w[(off / 32) as usize] |= v << (off % 32);
    }
    w
}

/// The value a texture fetch returns for code `c`: `c/M`, correctly rounded, clamped at
/// -1; a float field's code is its value.
pub(crate) fn fetched(q: Quant, c: f32) -> f32 {
    match q {
        Quant::Half | Quant::Single => c,
        _ => (c / q.max_code()).max(-1.0),
    }
}

/// What a fetch delivers for one field's raw bits, as f32 bits.
fn fetched_field(q: Quant, field: u32) -> u32 {
    let c = match q {
        Quant::Half => half_value::<f32>(field),
        Quant::Single => f32::from_bits(field),
        Quant::Snorm(b) if field as f32 > q.max_code() => field as f32 - (1u64 << b) as f32,
        _ => field as f32,
    };
    fetched(q, c).to_bits()
}

/// Float parameters for every code (or random codes), as a fetch delivers them. Fields
/// of at most 16 bits read their value from a table made once per field, so that the
/// 2^24 items of a 24-bit code cost no division each.
pub fn float_codes(q: &[Quant]) -> Vec<u32> {
    let total: u32 = q.iter().map(|q| q.bits()).sum();
    let offs = field_offsets(q);
    let tables: Vec<Option<Vec<u32>>> = q
        .iter()
        .map(|&f| (f.bits() <= 16).then(|| (0..=f.mask()).map(|v| fetched_field(f, v)).collect()))
        .collect();
    let fill = |words: [u32; 3], out: &mut [u32]| {
        for (((quant, off), table), out) in q.iter().zip(&offs).zip(&tables).zip(out) {
            let word = words[(off / 32) as usize] >> (off % 32);
            let field = if quant.bits() == 32 {
                word
            } else {
                word & quant.mask()
            };
            *out = match table {
                Some(t) => t[field as usize],
                None => fetched_field(*quant, field),
            };
        }
    };
    let fields = q.len();
    if total > 24 {
        let mut out = Vec::new();
        for words in wide_codes(q) {
            let at = out.len();
            out.resize(at + fields, 0);
            fill(words, &mut out[at..]);
        }
        return out;
    }
    // Every code, split between the cores: 2^24 codes took a second on one.
    let n = 1usize << total;
    let mut out = vec![0u32; n * fields];
    let threads = std::thread::available_parallelism().map_or(1, |t| t.get());
    let per = n.div_ceil(threads).max(1);
    std::thread::scope(|s| {
        for (t, share) in out.chunks_mut(per * fields).enumerate() {
            let fill = &fill;
            s.spawn(move || {
                for (j, item) in share.chunks_mut(fields).enumerate() {
                    fill([(t * per + j) as u32, 0, 0], item);
                }
            });
        }
    });
    out
}

/// Input words for a function, `in_words` per item.
pub fn generate(inputs: &Inputs, in_words: usize) -> Vec<u32> {
    match inputs {
        Inputs::Vectors => vectors().to_vec(),
        Inputs::Frames => frames().to_vec(),
        Inputs::Codes(q) => codes(q, in_words),
        Inputs::FloatCodes(q) => float_codes(q),
        Inputs::CodesAndIndex(q, n) => {
            assert_eq!(in_words, 2, "a code and an index");
            codes(q, 1)
                .into_iter()
                .flat_map(|c| (0..*n).flat_map(move |k| [c, k]))
                .collect()
        }
        Inputs::CodesWith(q, extra) => {
            assert_eq!(in_words, 1 + extra.words, "{extra:?} after a code");
            let c = codes(q, 1);
            let mut out = Vec::with_capacity(c.len() * in_words);
            for c in c {
                let words = (extra.of)(&[c]);
                assert_eq!(words.len(), extra.words, "{extra:?}");
                out.push(c);
                out.extend(words);
            }
            out
        }
        Inputs::VectorsWith(extra) => {
            assert_eq!(in_words, 3 + extra.words, "{extra:?} after a vector");
            let v = vectors();
            let mut out = Vec::with_capacity(v.len() / 3 * in_words);
            for v in v.chunks_exact(3) {
                let words = (extra.of)(v);
                assert_eq!(words.len(), extra.words, "{extra:?}");
                out.extend_from_slice(v);
                out.extend(words);
            }
            out
        }
    }
}

/// The edge vectors and the seeded random ones, as f32 bits: made once per process,
/// since every encoder takes the same ones.
fn vectors() -> &'static [u32] {
    static VECTORS: std::sync::OnceLock<Vec<u32>> = std::sync::OnceLock::new();
    VECTORS.get_or_init(|| {
        let mut v = edge_vectors();
        v.extend(random_unit_vectors(CODE_SEED, RANDOM_ITEMS, false));
        v.iter().flat_map(|a| a.map(f32::to_bits)).collect()
    })
}

/// Random frames: fewer than vectors, since a frame encoder costs several vector encoders.
pub const RANDOM_FRAMES: usize = 1 << 18;
pub const FRAME_SEED: u128 = 0x6672_616d_6573_5f73_6565_645f_756e_6974;

/// Frame edge cases (`[n.x, n.y, n.z, t.x, t.y, t.z, w]`): every pairing of special
/// normals (axes, -Z, the octahedral fold, zero, NaN, infinite, denormal, non-unit) with
/// special tangents (axes, parallel and antiparallel to the normal, non-orthogonal,
/// zero, NaN, infinite) and handedness values (±1, ±0, NaN, ±2, ±infinity).
pub fn edge_frames() -> Vec<[f32; 7]> {
    let h = std::f32::consts::FRAC_1_SQRT_2;
    let normals: [[f32; 3]; 12] = [
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
        [1.0, 0.0, 0.0],
        [0.0, -1.0, 0.0],
        [h, h, 0.0],
        [-h, 0.0, -h],
        [0.0, 0.0, 0.0],
        [f32::NAN, 0.0, 1.0],
        [0.0, f32::INFINITY, 0.0],
        [1e-45, 0.0, 0.0],
        [0.0, 3.0, 0.0],
        [0.6, -0.48, 0.64],
    ];
    let tangents: [[f32; 3]; 9] = [
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, -1.0],
        [h, -h, 0.0],
        [1.0, 1.0, 1.0],
        [0.0, 0.0, 0.0],
        [f32::NAN, 1.0, 0.0],
        [f32::NEG_INFINITY, 0.0, 0.0],
        [1e-30, 0.0, 1e-30],
    ];
    let ws = [
        1.0,
        -1.0,
        0.0,
        -0.0,
        f32::NAN,
        2.0,
        -2.0,
        f32::INFINITY,
        f32::NEG_INFINITY,
    ];
    let mut out = Vec::new();
    for n in normals {
        let parallel = [n, n.map(|x| -x)];
        for t in tangents.iter().chain(&parallel) {
            for w in ws {
                out.push([n[0], n[1], n[2], t[0], t[1], t[2], w]);
            }
        }
    }
    out
}

/// A rotation's frame (tangent = R·x, normal = R·z) with handedness `w`, from the unit
/// quaternion `q` (x, y, z, w), computed in f64 and rounded once.
fn frame_of(q: [f64; 4], w: f32) -> [f32; 7] {
    let [x, y, z, s] = q;
    let t = [
        1.0 - 2.0 * (y * y + z * z),
        2.0 * (x * y + s * z),
        2.0 * (x * z - s * y),
    ];
    let n = [
        2.0 * (x * z + s * y),
        2.0 * (y * z - s * x),
        1.0 - 2.0 * (x * x + y * y),
    ];
    [n[0], n[1], n[2], t[0], t[1], t[2]]
        .map(|v| v as f32)
        .into_iter()
        .chain([w])
        .collect::<Vec<_>>()
        .try_into()
        .expect("seven")
}

/// Whether seeded frame `i` (counted after the edge frames) has its tangent tilted off
/// the normal's plane: every fourth.
pub fn tilted(i: usize) -> bool {
    i % 4 == 3
}

/// The edge frames, then seeded ones: orthonormal frames of uniformly random rotations of
/// both handednesses; the same with the tangent tilted off the normal's plane
/// (non-orthogonal input, a quarter of them); and rotations within 10^-3 radians of a half
/// turn, where a quaternion's largest component moves from w to the axis (the
/// quaternion sign flip).
pub fn frames() -> &'static [u32] {
    static FRAMES: std::sync::OnceLock<Vec<u32>> = std::sync::OnceLock::new();
    FRAMES.get_or_init(|| {
        let mut rng = Pcg64Mcg::new(FRAME_SEED);
        let mut gauss = || {
            let u1 = ((rng.next_u64() >> 11) as f64 + 0.5) / (1u64 << 53) as f64;
            let u2 = (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
            (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
        };
        let mut out = edge_frames();
        for i in 0..RANDOM_FRAMES {
            let w = if i % 2 == 0 { 1.0 } else { -1.0 };
            let mut q = [gauss(), gauss(), gauss(), gauss()];
            if i % 64 == 1 {
                // Near a half turn: w small against the axis.
                let a = [q[0], q[1], q[2]];
                let l = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
                let e = 5e-4 * gauss();
                q = [a[0] / l, a[1] / l, a[2] / l, e];
            }
            let l = q.iter().map(|c| c * c).sum::<f64>().sqrt();
            let mut f = frame_of(q.map(|c| c / l), w);
            if tilted(i) {
                // Tilt the tangent towards the normal.
                let k = 0.3 * gauss();
                for j in 0..3 {
                    f[3 + j] += (k * f64::from(f[j])) as f32;
                }
            }
            out.push(f);
        }
        out.iter().flat_map(|a| a.map(f32::to_bits)).collect()
    })
}
