//! Seeded random unit vectors: the sample every error figure is measured on and part of
//! every encoder's verify inputs. A leaf module, so that both the error methodology
//! ([`crate::measure::quality`]) and the verify inputs ([`crate::codecs::functions::inputs`]) draw on it
//! without depending on each other.

use rand_core::Rng;
use rand_pcg::Pcg64Mcg;

fn uniform(rng: &mut Pcg64Mcg) -> f64 {
    // 53 random bits in (0, 1].
    ((rng.next_u64() >> 11) + 1) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// `n` seeded random unit vectors, normalized in f64 and rounded to f32; on the +Z
/// hemisphere (`z = |z|`) when asked.
pub fn random_unit_vectors(seed: u128, n: usize, hemisphere: bool) -> Vec<[f32; 3]> {
    let mut rng = Pcg64Mcg::new(seed);
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let mut g = [0f64; 3];
        for pair in [0, 2] {
            // Box–Muller: two Gaussians from two uniforms.
            let (u1, u2) = (uniform(&mut rng), uniform(&mut rng));
            let r = (-2.0 * u1.ln()).sqrt();
            let t = std::f64::consts::TAU * u2;
            g[pair] = r * t.cos();
            if pair == 0 {
                g[1] = r * t.sin();
            }
        }
        let len = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
        if len < 1e-9 {
            continue;
        }
        let z = if hemisphere { g[2].abs() } else { g[2] };
        out.push([(g[0] / len) as f32, (g[1] / len) as f32, (z / len) as f32]);
    }
    out
}
