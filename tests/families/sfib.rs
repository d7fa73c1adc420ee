//! The spherical Fibonacci codec's encoder returns the nearest point of the set (to the
//! `2^-18` its fixed-point comparison resolves): checked against a brute-force search over
//! every point that could be nearer, with the codec's own decoder as the definition of
//! where each point is.

use unitpack::codecs::angular::sfib::{GOLDEN, Sfib, longitude};
use unitpack::codecs::toolkit::exact::{canonical_or_z, fixed_length2, root};
use unitpack::codecs::toolkit::fixed_decode::fixed_target;
use unitpack::model::V3;
use unitpack::support::sampling::random_unit_vectors;

fn decode(c: &Sfib, i: u32) -> [f32; 3] {
    c.index_direction::<f32>(i).to_array()
}

fn dist2(a: [f32; 3], b: [f32; 3]) -> f64 {
    a.iter()
        .zip(&b)
        .map(|(x, y)| (f64::from(*x) - f64::from(*y)).powi(2))
        .sum()
}

/// Queries: seeded random directions, then directions within a few points of each pole
/// and of the equator, where the lattice and the mirroring change.
fn queries(count: usize, c: &Sfib) -> Vec<[f32; 3]> {
    let mut q = random_unit_vectors(7, count, false);
    let near = (4.0 * c.step()).sqrt();
    for k in 0..64 {
        let a = f64::from(k) * 0.7;
        let t = near * f64::from(k % 8) / 4.0;
        let (s, co) = (t.sin(), t.cos());
        for z in [co, -co] {
            q.push([(s * a.cos()) as f32, (s * a.sin()) as f32, z as f32]);
        }
        let e = near * (f64::from(k % 5) - 2.0);
        q.push([a.cos() as f32, a.sin() as f32, e as f32]);
    }
    q
}

/// Every index whose point could be within `chord` of `q`: its `z` is within `chord`.
fn window(c: &Sfib, q: [f32; 3], chord: f64) -> std::ops::RangeInclusive<u32> {
    let s = c.step();
    let index_at = |z: f64| (1.0 - unitpack::codecs::angular::sfib::EPSILON * s - z) / s;
    let z = f64::from(q[2]);
    let lo = (index_at(z + chord) - 3.0).max(0.0);
    let hi = (index_at(z - chord) + 3.0).min(c.points() - 1.0);
    lo as u32..=hi as u32
}

/// The encoder's own measure, computed independently: the squared distance in units of
/// `2^-21` between the fixed-point point and the input's fixed-point direction, summed
/// exactly (in u64) and rounded once to f32.
fn fixed_measure(c: &Sfib, aim: [f32; 3], i: u32) -> f32 {
    let p = c.fixed_point::<f32>(i).to_array();
    let exact: u64 = p
        .iter()
        .zip(&aim)
        .map(|(a, b)| ((a - b).abs() as u64).pow(2))
        .sum();
    exact as f32
}

fn nearest_is_chosen(bits: u32, count: usize) {
    let c = Sfib::new(bits).unwrap();
    let mut worst = 0f64;
    for q in queries(count, &c) {
        let j = c.encode_index::<f32>(V3::from_array(q));
        // Exactly the nearest in the encoder's fixed-point measure, the lower index on ties.
        let (w, _) = canonical_or_z(V3::from_array(q));
        let aim = fixed_target(w, root(fixed_length2(w)), 21).to_array();
        let chosen = fixed_measure(&c, aim, j);
        let reach = f64::from(chosen).sqrt() / f64::from(1u32 << 21) + 2f64.powi(-18);
        for i in window(&c, q, reach) {
            let m = fixed_measure(&c, aim, i);
            assert!(
                m > chosen || m == chosen && i >= j,
                "sfib{bits}: {q:?} encodes as {j} (fixed-point measure {chosen}), but point {i} measures {m}"
            );
        }
        let d = dist2(decode(&c, j), q);
        for i in window(&c, q, d.sqrt()) {
            let e = dist2(decode(&c, i), q);
            // The encoder measures in fixed point, units of 2^-21, within a few units of
            // these decodes: a point nearer by less than 2^-18 may lose to it.
            assert!(
                e.sqrt() >= d.sqrt() - 2f64.powi(-18),
                "sfib{bits}: {q:?} encodes as {j} at squared distance {d:e}, but point {i} is at {e:e}"
            );
        }
        worst = worst.max(d.sqrt());
    }
    println!("sfib{bits}: largest chord to the chosen point {worst:e}");
}

#[test]
fn sfib16_encoder_chooses_the_nearest_point() {
    nearest_is_chosen(16, 20_000);
}

#[test]
fn sfib24_encoder_chooses_the_nearest_point() {
    nearest_is_chosen(24, 1_000);
}

#[test]
fn sfib32_encoder_chooses_the_nearest_point() {
    nearest_is_chosen(32, 200);
}

/// The longitude is the fractional part of `i·(Φ - 1)` for every index, the last ones of
/// a 32-bit code included, where an f32 product would have no fractional digits left:
/// checked against the exact fraction of `i·GOLDEN / 2^64` (to the decoder's 24 bits of a
/// turn plus the trigonometry's error, scaled by the point's distance from the axis).
#[test]
fn longitude_is_the_exact_fraction_for_every_size() {
    for bits in [16, 24, 32] {
        let c = Sfib::new(bits).unwrap();
        let last = (c.points() - 1.0) as u32;
        for i in [
            1u32,
            2,
            3,
            1000,
            65_535,
            (1 << 15) + 3,
            last / 2 + 1,
            last - 1,
            last,
        ] {
            let p = decode(&c, i);
            let turn = f64::from(p[1]).atan2(f64::from(p[0])) / std::f64::consts::TAU;
            let product = u128::from(i) * u128::from(unitpack::codecs::angular::sfib::GOLDEN);
            let frac = (product as u64) as f64 / 2f64.powi(64);
            let diff = (turn - frac).rem_euclid(1.0);
            let diff = diff.min(1.0 - diff);
            let r = f64::from(p[0]).hypot(f64::from(p[1]));
            assert!(
                diff * r < 1e-6,
                "sfib{bits} point {i}: longitude {turn} turns, exact {frac}, radius {r}"
            );
        }
    }
}

/// `longitude` is the top 24 bits (rounded, plus half a turn) of the low 64 bits of
/// `i·GOLDEN`, for indices across the whole 32-bit range, the carries from the low
/// halves included.
#[test]
fn longitude_matches_the_128_bit_product() {
    let mut i = 0x9e37_79b9u32;
    let edges = [
        0,
        1,
        0xffff,
        0x1_0000,
        0x7fff_ffff,
        0x8000_0000,
        0xffff_fffe,
        u32::MAX,
    ];
    for k in 0..100_000 {
        i = i.wrapping_mul(0x2c9277b5).wrapping_add(0xac564b05);
        let i = if k < edges.len() { edges[k] } else { i };
        let fraction = (u128::from(i) * u128::from(GOLDEN)) as u64;
        let top = (fraction >> 32) as u32;
        let want = top.wrapping_add(128 + (1 << 31)) >> 8;
        assert_eq!(longitude(i), want, "index {i:#x}");
    }
}
