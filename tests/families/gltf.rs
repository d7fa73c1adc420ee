//! glTF's quantized normals (`gltf_normal8`, `gltf_normal16`) against gltf-transform:
//! its own `quantize()` run by Node.js (`tools/gltf-js`, pinned by its lockfile) on
//! seeded, edge and near-tie vectors, and a port of its `quantizeAttribute` here on more;
//! the decoders against glTF's rule `max(c/M, -1)`, normalized.

use crate::engine::{function, inputs, run};
use crate::oracles::gltf_transform;
use unitpack::codecs::functions::function::Role;

/// The vectors the encoders are held on: the engine formats' seeded and edge vectors,
/// and around every rounding boundary `(k + ½)/M` (the nearest f32 and four neighbours
/// on each side, both signs), three to a vector.
fn held_inputs(m: u32) -> Vec<[f32; 3]> {
    let mut v = inputs();
    let mut near = Vec::new();
    for k in 0..m {
        let tie = ((f64::from(k) + 0.5) / f64::from(m)) as f32;
        for step in -4i32..=4 {
            let x = f32::from_bits(tie.to_bits().wrapping_add_signed(step));
            near.push(x);
            near.push(-x);
        }
    }
    near.extend([
        0.5,
        -0.5,
        1.0,
        -1.0,
        1.0 + f32::EPSILON,
        2.0,
        -3.0,
        f32::MIN_POSITIVE,
    ]);
    near.extend([1e-45, -1e-45, 0.0, -0.0, f32::NAN, -f32::NAN, f32::INFINITY]);
    near.resize(near.len().div_ceil(3) * 3, 0.25);
    v.extend(near.chunks(3).map(|c| [c[0], c[1], c[2]]));
    v
}

/// The three components a code holds, sign-extended: the accessor's element as its bytes
/// lie in the buffer (little-endian words, x first, the padding zero).
fn components(words: &[u32], bits: u32) -> [i32; 3] {
    if bits == 8 {
        assert_eq!(words[0] >> 24, 0, "the padding byte of {:#010x}", words[0]);
        [0, 8, 16].map(|s| i32::from((words[0] >> s) as u8 as i8))
    } else {
        assert_eq!(words[1] >> 16, 0, "the padding of {:#010x}", words[1]);
        [words[0], words[0] >> 16, words[1]].map(|w| i32::from(w as u16 as i16))
    }
}

#[test]
fn encoders_write_gltf_transforms_integers() {
    for bits in [8u32, 16] {
        let m = (1u32 << (bits - 1)) - 1;
        let vs = held_inputs(m);
        let enc = function(&format!("gltf_normal{bits}"), Role::Encode);
        let got: Vec<[i32; 3]> = vs
            .iter()
            .map(|v| components(&run(&enc, &v.map(f32::to_bits)), bits))
            .collect();
        // The port, on every held vector.
        for (v, got) in vs.iter().zip(&got) {
            let want = v.map(|x| gltf_transform::quantized(x, bits));
            assert_eq!(
                *got,
                want,
                "gltf_normal{bits}: {v:?} ({:08x?}) → {got:?}, the port gives {want:?}",
                v.map(f32::to_bits)
            );
        }
        // gltf-transform itself.
        let want = gltf_transform::run(bits, "NORMAL", &vs.concat());
        for (i, (v, got)) in vs.iter().zip(&got).enumerate() {
            let want = &want[3 * i..3 * i + 3];
            assert_eq!(
                got.as_slice(),
                want,
                "gltf_normal{bits}: {v:?} ({:08x?}) → {got:?}, gltf-transform writes {want:?}",
                v.map(f32::to_bits)
            );
        }
    }
}

/// Every code of `gltf_normal8` whose components lie in `-128..=127` on a lattice of
/// step 5 (every x and y, z every fifth) and a seeded sample of 16-bit codes decode to
/// `max(c/M, -1)` normalized, computed here in f64, within 2^-22 per component; the
/// all-zero code to +Z exactly.
#[test]
fn decoders_read_gltfs_rule_normalized() {
    let mut rng = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = move || {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        rng
    };
    for bits in [8u32, 16] {
        let m = f64::from((1u32 << (bits - 1)) - 1);
        let dec = function(&format!("gltf_normal{bits}"), Role::Decode);
        let codes: Vec<[i32; 3]> = if bits == 8 {
            (-128..=127)
                .flat_map(|x| {
                    (-128..=127).flat_map(move |y| (-128..=127).step_by(5).map(move |z| [x, y, z]))
                })
                .chain([[0, 0, 0], [-128, -128, -128], [127, 127, 127]])
                .collect()
        } else {
            (0..200_000)
                .map(|_| {
                    let r = next();
                    [
                        r as u16 as i16,
                        (r >> 16) as u16 as i16,
                        (r >> 32) as u16 as i16,
                    ]
                    .map(i32::from)
                })
                .chain([[0, 0, 0], [-32768, -32768, -32768], [32767, 0, 0]])
                .collect()
        };
        for c in codes {
            let words = if bits == 8 {
                vec![
                    c.iter()
                        .enumerate()
                        .fold(0u32, |w, (i, &x)| w | (x as u8 as u32) << (8 * i)),
                ]
            } else {
                vec![
                    (c[0] as u16 as u32) | (c[1] as u16 as u32) << 16,
                    c[2] as u16 as u32,
                ]
            };
            let got: Vec<f32> = run(&dec, &words).into_iter().map(f32::from_bits).collect();
            if c == [0, 0, 0] {
                assert_eq!(
                    got.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
                    [0.0f32, 0.0, 1.0].map(f32::to_bits),
                    "gltf_normal{bits}: the zero code"
                );
                continue;
            }
            let f = c.map(|x| (f64::from(x) / m).max(-1.0));
            let len = f.iter().map(|x| x * x).sum::<f64>().sqrt();
            for (k, (&g, &w)) in got.iter().zip(&f).enumerate() {
                let want = w / len;
                assert!(
                    (f64::from(g) - want).abs() <= 2f64.powi(-22),
                    "gltf_normal{bits}: code {c:?} component {k}: {g} ({:#010x}), glTF's rule gives {want}",
                    g.to_bits()
                );
            }
        }
    }
}
