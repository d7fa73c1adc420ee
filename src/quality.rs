//! Error methodology (survey §4.1): seeded random unit vectors from normalized
//! Gaussian triples, codec arithmetic in f32, angular error in f64 after normalizing both
//! vectors, `|acos(dot)|` in degrees.

use crate::codecs::Spec;
use crate::codecs::core::codec::Domain;
use crate::codecs::core::function::{Emitted, Role};
use crate::memo::Memo;
use crate::sampling::random_unit_vectors;

/// Seeds are fixed so that every run, and every file generated, is identical.
pub const VECTOR_SEED: u128 = 0x756e_6974_7061_636b_5f76_6563_746f_7273;

/// Angle between two vectors in degrees, both normalized in f64.
pub fn angle_deg(a: [f32; 3], b: [f32; 3]) -> f64 {
    let a = a.map(f64::from);
    let b = b.map(f64::from);
    let la = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    let lb = (b[0] * b[0] + b[1] * b[1] + b[2] * b[2]).sqrt();
    let d = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / (la * lb);
    d.clamp(-1.0, 1.0).acos().abs().to_degrees()
}

/// Round-trip error of a spec's packed encode → decode: the angle in degrees (mean and
/// sample max), and the first seed's metric, the mean squared error of the components of
/// `n - n'` (its MSE over the `abs(n1 - n2)` difference image: three channels per
/// normal, peak 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ErrorStats {
    pub mean: f64,
    pub max: f64,
    pub mse: f64,
    pub samples: usize,
}

impl ErrorStats {
    /// `10·log10(1 / MSE)` in dB, the seed's PSNR for a peak of 1.
    pub fn psnr(&self) -> f64 {
        -10.0 * self.mse.log10()
    }
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

pub fn measure_emitted(e: &Emitted, domain: Domain, samples: usize) -> ErrorStats {
    let find = |r: Role| e.cpu_function(r).expect("codec function");
    let (enc, dec) = (find(Role::Encode), find(Role::Decode));
    let vs = random_unit_vectors(VECTOR_SEED, samples, domain == Domain::Hemisphere);
    // Eight or four vectors per step on the lanes, bit for bit the scalar model (`verify`'s
    // `cpu/8 lanes` and `cpu/4 lanes` paths): the search encoders cost thousands of operations each.
    let input: Vec<u32> = vs.iter().flat_map(|v| v.map(f32::to_bits)).collect();
    let mut codes = vec![0u32; samples * enc.out_words];
    enc.eval_many(&input, &mut codes);
    let mut out = vec![0u32; samples * 3];
    dec.eval_many(&codes, &mut out);
    let (mut sum, mut max, mut squares) = (0f64, 0f64, 0f64);
    for (v, o) in vs.iter().zip(out.chunks_exact(3)) {
        let n = [o[0], o[1], o[2]].map(f32::from_bits);
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

/// [`measure`] for every spec, on all cores; the same result as one at a time.
pub fn measure_all(specs: &[Spec], samples: usize) -> Vec<Option<ErrorStats>> {
    crate::par::map(specs, |spec| measure(spec, samples))
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
