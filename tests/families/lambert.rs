//! The first seed's erratum: for unit input its methods 4 (spheremap), 5 (CryEngine 3)
//! and 6 (Lambert) are one mapping. The seed's own encoder formulas are evaluated here in
//! f64 and compared; `spheremap` and `cry3` share `lambert`'s encoders (so their codes
//! are equal by construction, which is checked too), and their decoders — the seed's
//! plain and optimized ones — are compared with Lambert's over every 16-bit code.

use unitpack::api::{CpuCodec, Cry3, Lambert, Spheremap};
use unitpack::measure::quality::angle_deg;
use unitpack::support::sampling::random_unit_vectors;

fn unit(v: [f32; 3]) -> [f64; 3] {
    let v = v.map(f64::from);
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|x| x / l)
}

/// Method 4 as printed: `f = 2z + 1`, `g = n·n`, `enc = n.xy / sqrt(g + f) · ½ + ½`.
fn seed_spheremap(n: [f64; 3]) -> [f64; 2] {
    let f = n[2] * 2.0 + 1.0;
    let g = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    let p = (g + f).sqrt();
    [n[0] / p * 0.5 + 0.5, n[1] / p * 0.5 + 0.5]
}

/// Method 5 as printed: `enc = normalize(n.xy) · sqrt(-½z + ½) · ½ + ½`.
fn seed_cry3(n: [f64; 3]) -> [f64; 2] {
    let l = (n[0] * n[0] + n[1] * n[1]).sqrt();
    let r = (-n[2] * 0.5 + 0.5).sqrt();
    [n[0] / l * r * 0.5 + 0.5, n[1] / l * r * 0.5 + 0.5]
}

/// Method 6 as printed: `enc = n.xy / sqrt(8z + 8) + ½`.
fn seed_lambert(n: [f64; 3]) -> [f64; 2] {
    let f = (n[2] * 8.0 + 8.0).sqrt();
    [n[0] / f + 0.5, n[1] / f + 0.5]
}

#[test]
fn the_seed_encoders_of_methods_4_5_6_are_one_mapping() {
    let mut worst = 0f64;
    for v in random_unit_vectors(45, 1 << 16, false) {
        let n = unit(v);
        let l = seed_lambert(n);
        for e in [seed_spheremap(n), seed_cry3(n)] {
            for k in 0..2 {
                worst = worst.max((e[k] - l[k]).abs());
            }
        }
    }
    // f64 rounding only: a different mapping would differ by far more.
    assert!(worst < 1e-12, "the seed's encoders differ by {worst:e}");
}

/// Our codes are Lambert's, and they are the seed's formulas rounded to the nearest code
/// wherever the seed's value is not within f32 precision of a rounding boundary.
#[test]
fn spheremap_and_cry3_codes_are_lambert_codes_and_the_seed_formulas_rounded() {
    let mut vs = random_unit_vectors(46, 1 << 16, false);
    vs.extend([
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
        [0.0, 0.0, 0.0],
        [f32::NAN, 0.0, 1.0],
        [3.0, -4.0, 0.0],
    ]);
    for bits in [16, 24, 32] {
        let m = f64::from((1u32 << (bits / 2)) - 1);
        for precise in [false, true] {
            let pick = |c: Lambert| if precise { c.precise() } else { c.fast() };
            let lambert = pick(Lambert::new(bits).unwrap());
            let sm = Spheremap::new(bits).unwrap();
            let cry = Cry3::new(bits).unwrap();
            let (sm, cry) = if precise {
                (sm.precise(), cry.precise())
            } else {
                (sm.fast(), cry.fast())
            };
            for v in &vs {
                let c = lambert.encode(*v);
                assert_eq!(sm.encode(*v), c, "spheremap{bits} of {v:?}");
                assert_eq!(cry.encode(*v), c, "cry3_{bits} of {v:?}");
            }
        }
        // The fast codes against the seed's spheremap formula, rounded in f64. At 32
        // bits a code step nears the f32 precision of the encoder's lengths around -Z,
        // where the mapping magnifies them; the codes there are Lambert's (above).
        if bits == 32 {
            continue;
        }
        let fast = Spheremap::new(bits).unwrap().fast();
        let mask = (1u32 << (bits / 2)) - 1;
        let mut near_ties = 0;
        for v in &vs[..1 << 16] {
            let e = seed_spheremap(unit(*v));
            let code = fast.encode(*v);
            for (k, &p) in e.iter().enumerate() {
                let x = p * m;
                // Within f32 precision of a boundary the code may go either way: the
                // encoder decides with f32 lengths and roots, which are exact only up
                // to their own rounding.
                if (x - x.floor() - 0.5).abs() < x * 2f64.powi(-20) {
                    near_ties += 1;
                    continue;
                }
                let got = (code >> (k as u32 * bits / 2)) & mask;
                assert_eq!(f64::from(got), x.round(), "spheremap{bits} of {v:?}: {x}");
            }
        }
        // Two components each of 2^16 vectors: 19 and 456 are skipped.
        assert!(
            near_ties < 1 << 10,
            "spheremap{bits}: {near_ties} near-ties"
        );
    }
}

/// A packed decoder on the CPU.
type Decode<'a> = dyn Fn(u32) -> [f32; 3] + 'a;

/// Every 16-bit code decodes to nearly the same direction through all five decoders:
/// the seed's plain and optimized spheremap and CryEngine 3 decoders, and Lambert's.
#[test]
fn the_seed_decoders_agree_with_lambert_on_every_16_bit_code() {
    let lambert = Lambert::new(16).unwrap().fast();
    let sm = Spheremap::new(16).unwrap();
    let cry = Cry3::new(16).unwrap();
    let (sm_plain, sm_opt) = (sm.fast(), sm.optimized().fast());
    let (cry_plain, cry_opt) = (cry.fast(), cry.optimized().fast());
    let decoders: [(&str, &Decode); 4] = [
        ("spheremap16", &|c| sm_plain.decode(c)),
        ("spheremap16_optimized", &|c| sm_opt.decode(c)),
        ("cry3_16", &|c| cry_plain.decode(c)),
        ("cry3_16_optimized", &|c| cry_opt.decode(c)),
    ];
    for (name, decode) in decoders {
        let mut worst = 0f64;
        for code in 0..1u32 << 16 {
            let o = decode(code);
            let len = o.iter().map(|x| f64::from(*x).powi(2)).sum::<f64>().sqrt();
            assert!(
                (len - 1.0).abs() < 1e-5,
                "{name}: {code:#x} → {o:?} is not unit"
            );
            worst = worst.max(angle_deg(lambert.decode(code), o));
        }
        // Different orders of f32 operations; the quantization step is about 0.9°.
        assert!(worst < 0.01, "{name}: {worst}° from lambert16's decode");
        // The corners outside the disk decode as -Z (x and y may be -0: a zero root
        // times a negative coordinate).
        assert_eq!(decode(0), [0.0, 0.0, -1.0], "{name}");
    }
}
