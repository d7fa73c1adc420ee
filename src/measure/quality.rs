//! Error methodology (survey §4.1): seeded random unit vectors from normalized
//! Gaussian triples, codec arithmetic in f32, angular error in f64 after normalizing both
//! vectors, `|acos(dot)|` in degrees.

use crate::codecs::Spec;
use crate::codecs::core::info::Domain;
use crate::codecs::functions::function::{Emitted, Role};
use crate::measure::figures::{ErrorStats, FrameBaseline, FrameStats, VECTOR_SEED};
use crate::support::memo::Memo;
use crate::support::sampling::random_unit_vectors;

/// Angle between two vectors in degrees, both normalized in f64.
pub fn angle_deg(a: [f32; 3], b: [f32; 3]) -> f64 {
    let a = a.map(f64::from);
    let b = b.map(f64::from);
    let la = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    let lb = (b[0] * b[0] + b[1] * b[1] + b[2] * b[2]).sqrt();
    let d = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / (la * lb);
    d.clamp(-1.0, 1.0).acos().abs().to_degrees()
}

/// `Σ (aₖ - bₖ)² / 3` in f64: one normal's share of the seed's MSE.
pub fn component_mse(a: [f32; 3], b: [f32; 3]) -> f64 {
    a.iter()
        .zip(&b)
        .map(|(x, y)| (f64::from(*x) - f64::from(*y)).powi(2))
        .sum::<f64>()
        / 3.0
}

pub fn measure(spec: &Spec, samples: usize) -> Option<ErrorStats> {
    let domain = spec.info().domain?;
    let e = spec.emitted();
    Some(measure_emitted(&e, domain, samples))
}

/// `vs` through a codec's packed encoder and decoder, eight or four vectors per step on
/// the lanes, bit for bit the scalar model (`verify`'s `cpu/8 lanes` and `cpu/4 lanes`
/// paths): the search encoders cost thousands of operations each.
fn round_trip(e: &Emitted, vs: &[[f32; 3]]) -> Vec<[f32; 3]> {
    let find = |r: Role| e.cpu_function(r).expect("codec function");
    let (enc, dec) = (find(Role::Encode), find(Role::Decode));
    let input: Vec<u32> = vs.iter().flat_map(|v| v.map(f32::to_bits)).collect();
    let mut codes = vec![0u32; vs.len() * enc.out_words];
    enc.eval_many(&input, &mut codes);
    let mut out = vec![0u32; vs.len() * 3];
    dec.eval_many(&codes, &mut out);
    out.chunks_exact(3)
        .map(|o| [o[0], o[1], o[2]].map(f32::from_bits))
        .collect()
}

pub fn measure_emitted(e: &Emitted, domain: Domain, samples: usize) -> ErrorStats {
    let vs = random_unit_vectors(VECTOR_SEED, samples, domain == Domain::Hemisphere);
    let out = round_trip(e, &vs);
    let (mut sum, mut max, mut squares) = (0f64, 0f64, 0f64);
    for (v, &n) in vs.iter().zip(&out) {
        let a = angle_deg(*v, n);
        sum += a;
        max = max.max(a);
        squares += component_mse(*v, n);
    }
    ErrorStats {
        mean: sum / samples as f64,
        max,
        mse: squares / samples as f64,
        samples,
    }
}

/// A spec's round-trip errors over the vectors `vs` (a user's own sample), with the 99th
/// percentile of the angle (the nearest rank); `None` for a spec that codes no direction.
pub fn errors_over(spec: &Spec, vs: &[[f32; 3]]) -> Option<(ErrorStats, f64)> {
    spec.info().domain?;
    let out = round_trip(&spec.emitted(), vs);
    let mut angles: Vec<f64> = vs
        .iter()
        .zip(&out)
        .map(|(v, &n)| angle_deg(*v, n))
        .collect();
    // A user's vectors need not be unit length (a normal map's `2c/M - 1`): the MSE
    // compares directions, the input's made unit in f64 first.
    let unit = |v: [f32; 3]| {
        let l = v.iter().map(|&x| f64::from(x).powi(2)).sum::<f64>().sqrt();
        v.map(|x| (f64::from(x) / l) as f32)
    };
    let squares: f64 = vs
        .iter()
        .zip(&out)
        .map(|(v, &n)| component_mse(unit(*v), n))
        .sum();
    let n = vs.len().max(1);
    let stats = ErrorStats {
        mean: angles.iter().sum::<f64>() / n as f64,
        max: angles.iter().copied().fold(0.0, f64::max),
        mse: squares / n as f64,
        samples: vs.len(),
    };
    let rank = (vs.len() * 99).div_ceil(100).max(1) - 1;
    let p99 = if angles.is_empty() {
        0.0
    } else {
        *angles
            .select_nth_unstable_by(rank.min(vs.len() - 1), f64::total_cmp)
            .1
    };
    Some((stats, p99))
}

/// [`measure`] for every spec, on all cores; the same result as one at a time.
pub fn measure_all(specs: &[Spec], samples: usize) -> Vec<Option<ErrorStats>> {
    crate::support::par::map(specs, |spec| measure(spec, samples))
}

/// What a spec's figures are known by: its name and the sample size.
pub type StatsKey = (String, usize);

/// Every spec's figures this process knows.
static MEMO: Memo<StatsKey, Option<ErrorStats>> = Memo::new();

/// [`measure_all`], each spec measured once per process (the doc comments of every
/// include state its figures, and a search encoder's take a noticeable fraction of a
/// second).
pub fn measure_all_once(specs: &[Spec], samples: usize) -> Vec<Option<ErrorStats>> {
    let key = |s: &Spec| (s.to_string(), samples);
    let todo: Vec<Spec> = specs
        .iter()
        .filter(|s| !MEMO.contains(&key(s)))
        .cloned()
        .collect();
    let measured = measure_all(&todo, samples);
    MEMO.extend(todo.iter().map(key).zip(measured.iter().copied()));
    specs
        .iter()
        .map(|s| MEMO.get(&key(s)).expect("every spec is measured"))
        .collect()
}

/// Every spec's figures this process knows: what a store that outlives the process saves.
/// They are the model's, so only meaningful to the same build.
pub fn export() -> Vec<(StatsKey, Option<ErrorStats>)> {
    MEMO.export()
}

/// Takes figures an earlier run of the same build measured ([`export`]) as measured.
pub fn import(stats: impl IntoIterator<Item = (StatsKey, Option<ErrorStats>)>) {
    MEMO.extend(stats);
}

type F3 = [f64; 3];

fn cross3(a: F3, b: F3) -> F3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn unit3(a: F3) -> F3 {
    let l = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    a.map(|c| c / l)
}

fn angle3(a: F3, b: F3) -> f64 {
    let (a, b) = (unit3(a), unit3(b));
    (a[0] * b[0] + a[1] * b[1] + a[2] * b[2])
        .clamp(-1.0, 1.0)
        .acos()
        .to_degrees()
}

/// The frames the figures are measured on: the seeded orthonormal ones (every fourth
/// seeded frame, whose tangent is tilted off the normal's plane, left out: a tangent
/// generator such as MikkTSpace writes it orthogonal, and an encoder that does not make
/// it so, as Godot's does not, would be measured on input it is not given).
fn reference_frames() -> Vec<[f32; 7]> {
    let edges = crate::codecs::functions::inputs::edge_frames().len();
    crate::codecs::functions::inputs::frames()[edges * 7..]
        .chunks_exact(7)
        .enumerate()
        .filter(|(i, _)| !crate::codecs::functions::inputs::tilted(*i))
        .map(|(_, x)| std::array::from_fn(|i| f32::from_bits(x[i])))
        .collect()
}

/// The statistics of frames decoded from the reference frames `input`, `(n', t', sign')`
/// each.
fn frame_stats(input: &[[f32; 7]], decoded: impl Iterator<Item = (F3, F3, f64)>) -> FrameStats {
    let (mut sum, mut max, mut flips) = ([0f64; 3], [0f64; 3], 0);
    for (x, (n2, t2, s2)) in input.iter().zip(decoded) {
        let x = x.map(f64::from);
        let n = unit3([x[0], x[1], x[2]]);
        let t = [x[3], x[4], x[5]];
        let d = t[0] * n[0] + t[1] * n[1] + t[2] * n[2];
        let t = unit3([t[0] - d * n[0], t[1] - d * n[1], t[2] - d * n[2]]);
        let s = if x[6] < 0.0 { -1.0 } else { 1.0 };
        let b = cross3(n, t).map(|c| c * s);
        let b2 = cross3(n2, t2).map(|c| c * s2);
        for (k, a) in [angle3(n, n2), angle3(t, t2), angle3(b, b2)]
            .into_iter()
            .enumerate()
        {
            sum[k] += a;
            max[k] = max[k].max(a);
        }
        flips += usize::from(s2 != s);
    }
    let mean = |k: usize| sum[k] / input.len() as f64;
    FrameStats {
        samples: input.len(),
        normal: [mean(0), max[0]],
        tangent: [mean(1), max[1]],
        bitangent: [mean(2), max[2]],
        flips,
    }
}

/// Every frame spec's figures this process knows, by id. Only frame specs are entered: a vector spec's `None` costs nothing to work out.
static FRAME_MEMO: Memo<String, Option<FrameStats>> = Memo::new();

/// Every frame spec's figures this process knows, as [`export`] does the vector specs'.
pub fn export_frames() -> Vec<(String, Option<FrameStats>)> {
    FRAME_MEMO.export()
}

/// Takes frame figures an earlier run of the same build measured ([`export_frames`]).
pub fn import_frames(stats: impl IntoIterator<Item = (String, Option<FrameStats>)>) {
    FRAME_MEMO.extend(stats);
}

/// [`FrameStats`] of a tangent-frame spec's packed encode → decode (`None` for a vector
/// spec), measured once per process (or taken from [`import_frames`]).
pub fn measure_frames(spec: &Spec) -> Option<FrameStats> {
    if !spec.family().frames() {
        return None;
    }
    if let Some(s) = FRAME_MEMO.get(&spec.id()) {
        return s;
    }
    let stats = frames_over(spec, &reference_frames());
    FRAME_MEMO.extend([(spec.id(), stats)]);
    stats
}

/// A frame spec's figures over `frames` (`n`, `t` and the bitangent's sign each, as
/// `encode` takes them: a user's sample), through its packed encoder and decoder; `None`
/// for a vector spec.
pub fn frames_over(spec: &Spec, frames: &[[f32; 7]]) -> Option<FrameStats> {
    spec.family().frames().then(|| {
        let e = spec.emitted();
        let find = |r: Role| e.cpu_function(r).expect("frame function");
        let (enc, dec) = (find(Role::Encode), find(Role::Decode));
        let input: Vec<u32> = frames.iter().flatten().map(|v| v.to_bits()).collect();
        let mut codes = vec![0u32; frames.len() * enc.out_words];
        enc.eval_many(&input, &mut codes);
        let mut out = vec![0u32; frames.len() * 7];
        dec.eval_many(&codes, &mut out);
        frame_stats(
            frames,
            out.chunks_exact(7).map(|o| {
                let f = |i: usize| f64::from(f32::from_bits(o[i]));
                ([f(0), f(1), f(2)], [f(3), f(4), f(5)], f(6))
            }),
        )
    })
}

/// `vs` through oct's fast encoder and its decoder at `bits` bits (any even size, the
/// catalogue's or not): the portable nearest codes, dequantized and unfolded, as the
/// `oct` specs compute them.
fn oct_round_trip(bits: u32, vs: &[[f32; 3]]) -> Vec<[f32; 3]> {
    use crate::codecs::octahedral::oct::{oct_codes, oct_direction};
    use crate::codecs::toolkit::quant::Quant;
    use crate::model::V3;
    let q = Quant::Snorm(bits / 2);
    vs.iter()
        .map(|v| {
            let c = oct_codes::<f32>(q, V3::new(v[0], v[1], v[2]));
            oct_direction(crate::codecs::core::codec::dequantize(&[q, q], c)).to_array()
        })
        .collect()
}

/// The comparison a frame spec of `bits` bits is measured against: the normal and the
/// orthogonalised tangent each in its own octahedral code (`oct` fast, the largest even
/// sizes from 8 to 32 bits whose sum leaves a bit for the sign, split as evenly as they can
/// be, the normal's the larger;
/// sizes the catalogue does not list are the same model at that size, see
/// [`oct_round_trip`]) and the sign in one bit.
/// Returns the specs and their total bits with the [`FrameStats`] of the same frames.
pub fn oct_frame_baseline(bits: u32) -> FrameBaseline {
    static MEMO: Memo<u32, FrameBaseline> = Memo::new();
    if let Some(b) = MEMO.get(&bits) {
        return b;
    }
    let b = frame_baseline(bits);
    MEMO.extend([(bits, b.clone())]);
    b
}

/// [`oct_frame_baseline`], measured.
fn frame_baseline(bits: u32) -> FrameBaseline {
    let (a, b) = (8..=32)
        .step_by(2)
        .flat_map(|a| (8..=a).step_by(2).map(move |b| (a, b)))
        .filter(|&(a, b)| a + b < bits)
        .max_by_key(|&(a, b)| (a + b, b))
        .expect("a pair of oct sizes within the budget");
    // The specs as `oct_round_trip` models them: the oct family's, at these sizes.
    use crate::codecs::core::spec::Family;
    let oct = crate::codecs::octahedral::oct::FAMILY.info().name;
    let (normal, tangent) = (format!("{oct}{a}"), format!("{oct}{b}"));
    let frames = reference_frames();
    let normals: Vec<[f32; 3]> = frames.iter().map(|x| [x[0], x[1], x[2]]).collect();
    let n2 = oct_round_trip(a, &normals);
    // The tangent made orthogonal to the normal and unit, in f64, then rounded.
    let tangents: Vec<[f32; 3]> = frames
        .iter()
        .map(|x| {
            let x = x.map(f64::from);
            let n = unit3([x[0], x[1], x[2]]);
            let d = x[3] * n[0] + x[4] * n[1] + x[5] * n[2];
            unit3([x[3] - d * n[0], x[4] - d * n[1], x[5] - d * n[2]]).map(|c| c as f32)
        })
        .collect();
    let t2 = oct_round_trip(b, &tangents);
    let stats = frame_stats(
        &frames,
        n2.iter().zip(&t2).zip(&frames).map(|((n, t), x)| {
            (
                n.map(f64::from),
                t.map(f64::from),
                if x[6] < 0.0 { -1.0 } else { 1.0 },
            )
        }),
    );
    ((normal, tangent, a + b + 1), stats)
}
