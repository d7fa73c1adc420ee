//! The CPU library: construction errors, slices, and round trips.

use unitpack::api::{
    Batch, CpuCodec, Cube, Float16x3, Float32x3, Frame, FrameBatch, HemiEqArea, HemiEqDist,
    HemiOct, HemiStereo, Oct, Paraboloid, ParaboloidSquare, RoundTrip, Snorm3, SphericalZ,
    StereoScaled, Transcoder, Unorm3, Width, XySignZ, XyStereo, combine_paraboloid_pd,
};
use unitpack::measure::quality::angle_deg;
use unitpack::support::sampling::random_unit_vectors;

#[test]
fn invalid_sizes_list_the_allowed_ones() {
    let e = Oct::new(17).unwrap_err().to_string();
    assert!(e.contains("16, 20, 22, 24, 32"), "{e}");
    let e = HemiOct::new(20).unwrap_err().to_string();
    assert!(e.contains("16, 24, 32"), "{e}");
    assert!(StereoScaled::new(16).unwrap().with_scale(0.0).is_err());
    assert!(StereoScaled::new(16).unwrap().with_scale(f32::NAN).is_err());
    assert!(StereoScaled::new(16).unwrap().with_scale(2.0).is_ok());
}

/// The slices run four (SSE2) or eight (AVX2) vectors per step on SIMD lanes; on either,
/// every item must be the single call's bits, for 1-, 2- and 3-word codes, fast and precise, over lengths that leave a
/// partial last group, the edge vectors and every decoded code's bits.
#[test]
fn slices_compute_the_single_calls_bits() {
    fn check<C: CpuCodec>(name: &str, e: unitpack::api::Encoder<C>)
    where
        C::C<f32>: PartialEq + std::fmt::Debug,
    {
        let mut vs = random_unit_vectors(21, 4099, false);
        vs.extend(unitpack::verify::inputs::edge_vectors());
        vs.extend([[1e30, -1e30, 0.5], [0.0, 0.0, -1.0], [3.0, 4.0, 0.0]]);
        // Every lane width up to the one the processor would pick (eight needs AVX2; the
        // AVX-512VL copy of the eight runs where the processor has that too).
        let widths = match Width::widest() {
            Width::Four => vec![Width::Four],
            Width::Eight => vec![Width::Four, Width::Eight],
            Width::EightAvx512 => vec![Width::Four, Width::Eight, Width::EightAvx512],
        };
        assert!(
            !cfg!(target_arch = "x86_64") || widths.len() > 1,
            "the eight-lane slices need a processor with AVX2 to be tested"
        );
        for &width in &widths {
            for len in [vs.len(), 1, 2, 3, 5, 9] {
                let vs = &vs[..len];
                let mut codes = vec![e.encode([0.0, 0.0, 1.0]); len];
                e.encode_slice_on(width, vs, &mut codes);
                let mut back = vec![[0f32; 3]; len];
                e.decode_slice_on(width, &codes, &mut back);
                for ((v, c), b) in vs.iter().zip(&codes).zip(&back) {
                    assert_eq!(*c, e.encode(*v), "{name} on {width:?}: {v:?}");
                    assert_eq!(
                        b.map(f32::to_bits),
                        e.decode(*c).map(f32::to_bits),
                        "{name} on {width:?}"
                    );
                }
            }
        }
    }
    check("oct16", Oct::new(16).unwrap().fast());
    check("oct32p", Oct::new(32).unwrap().precise());
    check("hemioct24p", HemiOct::new(24).unwrap().precise());
    check("snorm16x3", Snorm3::two_words().fast());
    check("snorm11_11_10", Snorm3::snorm11_11_10().fast());
    check("float16x3", Float16x3.fast());
    check("float32x3", Float32x3.fast());
    check("cube24p", Cube::new(24).unwrap().precise());
}

#[test]
fn slices_match_single_calls_and_round_trip_within_the_codec_error() {
    let vs = random_unit_vectors(3, 4096, false);
    for bits in [16, 24, 32] {
        let oct = Oct::new(bits).unwrap().precise();
        let mut codes = vec![0u32; vs.len()];
        oct.encode_slice(&vs, &mut codes);
        let mut back = vec![[0f32; 3]; vs.len()];
        oct.decode_slice(&codes, &mut back);
        // Survey Table 1 max error of octNP, with a little room for the sample.
        let bound = match bits {
            16 => 0.64,
            24 => 0.040,
            _ => 0.0025,
        };
        for ((v, c), b) in vs.iter().zip(&codes).zip(&back) {
            assert_eq!(*c, oct.encode(*v));
            assert_eq!(b.map(f32::to_bits), oct.decode(*c).map(f32::to_bits));
            let a = angle_deg(*v, *b);
            assert!(a <= bound, "oct{bits}p: {v:?} decodes {a}° away");
        }
    }
}

#[test]
#[should_panic(expected = "lengths differ")]
fn slice_length_mismatch_is_refused() {
    let oct = Oct::new(16).unwrap().fast();
    oct.encode_slice(&[[0.0, 0.0, 1.0]; 2], &mut [0u32; 3]);
}

/// The non-generic batch API computes the typed encoders' bits, for one-, two- and
/// three-word codes, fast and precise, with an option; decoding those codes likewise.
#[test]
fn batches_match_the_typed_encoders_bit_for_bit() {
    let mut vs = random_unit_vectors(9, 2048, false);
    vs.extend([[0.0, 0.0, 0.0], [f32::NAN, 1.0, 0.0], [1e30, -1e30, 3.0]]);
    let check = |spec: &str,
                 words: usize,
                 enc: &dyn Fn([f32; 3]) -> Vec<u32>,
                 dec: &dyn Fn(&[u32]) -> [f32; 3]| {
        let b = Batch::new(spec).unwrap();
        assert_eq!(b.words(), words, "{spec}");
        let mut codes = vec![0u32; vs.len() * words];
        b.encode(&vs, &mut codes);
        let mut back = vec![[0f32; 3]; vs.len()];
        b.decode(&codes, &mut back);
        for ((v, c), d) in vs.iter().zip(codes.chunks(words)).zip(&back) {
            assert_eq!(c, &enc(*v)[..], "{spec}: {v:?}");
            assert_eq!(
                d.map(f32::to_bits),
                dec(c).map(f32::to_bits),
                "{spec}: {c:x?}"
            );
        }
    };
    let oct = Oct::new(24).unwrap().precise();
    check("oct24p", 1, &|v| vec![oct.encode(v)], &|c| oct.decode(c[0]));
    let oct = Oct::new(16).unwrap().fast();
    check("oct16", 1, &|v| vec![oct.encode(v)], &|c| oct.decode(c[0]));
    let s = StereoScaled::new(24)
        .unwrap()
        .with_scale(2.0)
        .unwrap()
        .fast();
    check("stereo_scaled24:scale=2", 1, &|v| vec![s.encode(v)], &|c| {
        s.decode(c[0])
    });
    let h = Float16x3.fast();
    check("float16x3", 2, &|v| h.encode(v).to_array().to_vec(), &|c| {
        h.decode(unitpack::model::V2::new(c[0], c[1]))
    });
    let f = Float32x3.fast();
    check("float32x3", 3, &|v| f.encode(v).to_array().to_vec(), &|c| {
        f.decode(unitpack::model::V3::new(c[0], c[1], c[2]))
    });
}

#[test]
fn batch_refuses_helpers_and_bad_specs() {
    for helper in ["snorm12x2", "paraboloid_pd"] {
        let e = Batch::new(helper).err().unwrap().to_string();
        assert!(e.contains("is a helper, not a codec"), "{e}");
    }
    let e = Batch::new("oct17").err().unwrap().to_string();
    assert!(e.contains("16, 20, 22, 24, 32"), "{e}");
}

/// `FrameBatch` computes the model's bits: every seeded and edge frame (a count that ends
/// in a partial group of lanes) encoded as the encoder's single calls encode it, and every
/// resulting code decoded as the decoder's single calls decode it.
#[test]
fn frame_batches_compute_the_single_calls_bits() {
    let input = unitpack::codecs::functions::inputs::frames();
    let frames: Vec<Frame> = input
        .chunks_exact(7)
        .map(|x| {
            let f = |i: usize| f32::from_bits(x[i]);
            Frame {
                n: [f(0), f(1), f(2)],
                t: [f(3), f(4), f(5), f(6)],
            }
        })
        .collect();
    assert_ne!(frames.len() % 8, 0, "a partial group");
    for spec in [
        "qtangent64",
        "qtangent32",
        "godot_axis_angle",
        "octangle32",
        "octangle48",
        "diamond32",
    ] {
        let batch = FrameBatch::new(spec).unwrap();
        let e = spec.parse::<unitpack::codecs::Spec>().unwrap().emitted();
        let single = |role| e.functions.iter().find(|f| f.role == role).unwrap();
        let mut codes = vec![0u32; frames.len() * batch.words()];
        batch.encode(&frames, &mut codes);
        let mut back = vec![Frame::default(); frames.len()];
        batch.decode(&codes, &mut back);
        let words = batch.words();
        for ((x, c), b) in input
            .chunks_exact(7)
            .zip(codes.chunks_exact(words))
            .zip(&back)
        {
            let (mut want, mut frame) = (vec![0u32; words], [0u32; 7]);
            (single(unitpack::codecs::functions::function::Role::Encode).eval)(x, &mut want);
            assert_eq!(c, &want[..], "{spec} encode of {x:x?}");
            (single(unitpack::codecs::functions::function::Role::Decode).eval)(c, &mut frame);
            let got: Vec<u32> = b.n.iter().chain(&b.t).map(|v| v.to_bits()).collect();
            assert_eq!(got, frame, "{spec} decode of {c:x?}");
        }
    }
    let e = FrameBatch::new("oct16").err().unwrap().to_string();
    assert!(e.contains("use Batch"), "{e}");
}

#[test]
#[should_panic(expected = "words() = 2 words per input vector")]
fn batch_output_length_is_checked() {
    Batch::new("snorm16x3")
        .unwrap()
        .encode(&[[0.0, 0.0, 1.0]; 2], &mut [0u32; 2]);
}

/// The documented layouts: snorm11_11_10 is x in bits 0–10, y in 11–21, z in 22–31;
/// snorm5x3 is three 5-bit fields from bit 0, bit 15 clear; two's complement fields.
#[test]
fn snorm_layouts_put_x_lowest() {
    let c = Snorm3::snorm11_11_10().fast();
    assert_eq!(c.encode([1.0, 0.0, 0.0]), 1023);
    assert_eq!(c.encode([0.0, -1.0, 0.0]), 1025 << 11);
    assert_eq!(c.encode([0.0, 0.0, 1.0]), 511 << 22);
    assert_eq!(c.decode(0x7ff), [-1.0, 0.0, 0.0]);
    let c = Snorm3::one_word(5).unwrap().fast();
    assert_eq!(c.encode([0.0, 0.0, -1.0]), 17 << 10);
    assert_eq!(c.encode([0.6, 0.8, 0.0]), (12 << 5) | 9);
    assert_eq!(c.decode(15 << 5), [0.0, 1.0, 0.0]);
    assert!(Snorm3::one_word(6).is_err());
}

/// float16x3 is an RGBA16_FLOAT texel's first three channels: x low in word 0, y high,
/// z low in word 1; halves as IEEE 754 rounds them (0.6 → 0x38cd, 0.8 → 0x3a66).
#[test]
fn float16x3_codes_are_rgba16_float_texels() {
    let c = Float16x3.fast();
    assert_eq!(c.encode([0.6, 0.8, 0.0]).to_array(), [0x3a66_38cd, 0]);
    assert_eq!(c.encode([0.0, 0.0, -2.0]).to_array(), [0, 0xbc00]);
    assert_eq!(c.encode([-0.0, 0.0, 1.0]).to_array(), [0, 0x3c00]);
    let v = c.decode(unitpack::model::V2::new(0x3a66_38cd, 0));
    assert_eq!(v, [0.600_097_66, 0.799_804_7, 0.0]);
    // An infinite or NaN half, or three zeros, decode as +Z.
    for code in [[0x7c00, 0], [0, 0x7e01], [0x8000_8000, 0x8000]] {
        let v = c.decode(unitpack::model::V2::new(code[0], code[1]));
        assert_eq!(v, [0.0, 0.0, 1.0], "{code:x?}");
    }
}

/// float32x3's components depend on the input's magnitude, not only on its direction
/// (the canonical input is floored to `2^-21` of its largest component's binade before
/// the integer arithmetic), within a proven bound: each output component is within
/// `√3·2^-22` (the floors' angle) `+ 2^-23` (the rounded integer length) `+ 2^-25` (the
/// grid) of the exact direction's, so two magnitudes differ by under 19 units of
/// `2^-24`. Checked over integer and random multiples of seeded directions, with the
/// sample maximum of the difference printed.
#[test]
fn float32x3_magnitude_moves_components_within_the_proven_bound() {
    let c = Float32x3.fast();
    let per = 3f64.sqrt() * 2f64.powi(-22) + 2f64.powi(-23) + 2f64.powi(-25);
    let mut rng = 0x2545_f491_4f6c_dd1du64;
    let mut worst = 0f64;
    let dirs = random_unit_vectors(11, 2000, false);
    for d in &dirs {
        let exact = {
            let n = d.iter().map(|x| f64::from(*x).powi(2)).sum::<f64>().sqrt();
            d.map(|x| f64::from(x) / n)
        };
        let base = c.encode(*d).to_array().map(f32::from_bits);
        for k in 1..=40u32 {
            rng ^= rng << 13;
            rng ^= rng >> 7;
            rng ^= rng << 17;
            let scale = if k <= 20 {
                k as f32
            } else {
                (rng >> 40) as f32 / (1u32 << 20) as f32 + 0.001
            };
            let v = d.map(|x| x * scale);
            let got = c.encode(v).to_array().map(f32::from_bits);
            for i in 0..3 {
                let e = (f64::from(got[i]) - exact[i]).abs();
                assert!(e <= per, "{v:?}: component {i} {} vs {}", got[i], exact[i]);
                worst = worst.max((f64::from(got[i]) - f64::from(base[i])).abs());
            }
        }
    }
    println!(
        "float32x3: sample max component difference between magnitudes {} units of 2^-24 \
         ({} directions × 40 scalings)",
        worst * 2f64.powi(24),
        dirs.len()
    );
    assert!(worst <= 2.0 * per);
}

/// float32x3 is an RGB32_FLOAT texel, one word per component (x first), each on the
/// 2^-24 grid: 0.6 and 0.8 are f32's own nearest values there; the axes are exact.
#[test]
fn float32x3_codes_are_rgb32_float_texels() {
    let c = Float32x3.fast();
    assert_eq!(
        c.encode([0.6, 0.0, 0.8]).to_array(),
        [0.6f32.to_bits(), 0, 0x3f4c_cccc]
    );
    assert_eq!(c.encode([0.0, -3.0, 0.0]).to_array(), [0, 0xbf80_0000, 0]);
    assert_eq!(
        c.encode([f32::NAN, 0.0, 1.0]).to_array(),
        [0, 0, 0x3f80_0000]
    );
    for v in unitpack::support::sampling::random_unit_vectors(5, 1000, false) {
        let code = c.encode(v).to_array();
        for (w, x) in code.iter().zip(v) {
            let y = f32::from_bits(*w);
            assert_eq!((y * 16_777_216.0).fract(), 0.0, "{v:?}: {y} off the grid");
            assert!((y - x).abs() <= 2f32.powi(-21), "{v:?} → {y}");
        }
        assert_eq!(
            c.decode(unitpack::model::V3::from_array(code)),
            code.map(f32::from_bits)
        );
    }
    // Infinite or NaN components, or no nonzero one, decode as +Z; denormals read as +0.
    for code in [
        [0x7f80_0000, 0, 0],
        [0, 0x7fc0_0001, 0],
        [0x8000_0000, 1, 0x8000_0001],
    ] {
        let v = c.decode(unitpack::model::V3::from_array(code));
        assert_eq!(v, [0.0, 0.0, 1.0], "{code:x?}");
    }
    assert_eq!(
        c.decode(unitpack::model::V3::from_array([1, 0x3f80_0000, 0])),
        [0.0, 1.0, 0.0]
    );
    // A NaN beside a valid component is not read as a zero.
    assert_eq!(
        c.decode(unitpack::model::V3::from_array([
            0x7fc0_0000,
            0x3f80_0000,
            0
        ])),
        [0.0, 0.0, 1.0]
    );
}

/// stereo16 is x in bits 0–7 (unorm8), y in bits 8–14 (unorm7), the hemisphere bit (set
/// for z < 0) in bit 15; the disk centre is between codes, and ties go up.
#[test]
fn stereo_layout_is_x_y_then_the_hemisphere_bit() {
    let c = HemiStereo::new(16).unwrap().fast();
    assert_eq!(c.encode([0.0, 0.0, 1.0]), 128 | 64 << 8);
    assert_eq!(c.encode([0.0, 0.0, -1.0]), 128 | 64 << 8 | 1 << 15);
    assert_eq!(c.encode([1.0, 0.0, 0.0]), 255 | 64 << 8);
    assert_eq!(c.encode([0.0, -1.0, -0.0]), 128);
    let v = c.decode(255 | 64 << 8 | 1 << 15);
    assert!(v[0] > 0.9999 && v[2].abs() < 1e-4, "{v:?}");
    assert!(HemiStereo::new(18).is_err());
}

/// eqarea shares stereo's layout; the square's corners decode to the opposite pole of
/// their hemisphere.
#[test]
fn eqarea_layout_and_corners() {
    let c = HemiEqArea::new(16).unwrap().fast();
    assert_eq!(c.encode([0.0, 0.0, 1.0]), 128 | 64 << 8);
    assert_eq!(c.encode([0.0, 0.0, -1.0]), 128 | 64 << 8 | 1 << 15);
    assert_eq!(c.encode([1.0, 0.0, 0.0]), 255 | 64 << 8);
    assert_eq!(c.decode(255 | 127 << 8), [0.0, 0.0, -1.0]);
    assert_eq!(c.decode(1 << 15), [-0.0, -0.0, 1.0]);
}

/// eqdist shares stereo's layout; the disk's edge is the equator and the square's
/// corners lie 127° (√2 · 90°) from their hemisphere's pole.
#[test]
fn eqdist_layout_and_corners() {
    let c = HemiEqDist::new(16).unwrap().fast();
    assert_eq!(c.encode([0.0, 0.0, 1.0]), 128 | 64 << 8);
    assert_eq!(c.encode([0.0, 0.0, -1.0]), 128 | 64 << 8 | 1 << 15);
    assert_eq!(c.encode([1.0, 0.0, 0.0]), 255 | 64 << 8);
    // 45° from +Z towards +X: radius ½, code 127.5 + 63.75.
    let h = std::f32::consts::FRAC_1_SQRT_2;
    assert_eq!(c.encode([h, 0.0, h]), 191 | 64 << 8);
    let v = c.decode(255 | 127 << 8);
    let polar = f64::from(v[2]).acos().to_degrees();
    assert!((polar - 90.0 * 2f64.sqrt()).abs() < 0.01, "{v:?}: {polar}°");
    let v = c.decode(255 | 127 << 8 | 1 << 15);
    assert!(
        (f64::from(-v[2]).acos().to_degrees() - 127.279).abs() < 0.01,
        "{v:?}"
    );
}

/// cube16 is s in bits 0–6 (unorm7), t in bits 7–12 (unorm6), the face in bits 13–15
/// (+X, -X, +Y, -Y, +Z, -Z = 0–5); on +X the coordinates are (y, z)/|x|, on +Y (z, x)/|y|,
/// on +Z (x, y)/|z|. Faces 6 and 7 decode as +Z and -Z; warpedcube shares the layout.
#[test]
fn cube_layout_is_s_t_then_the_face() {
    let c = Cube::new(16).unwrap().fast();
    assert_eq!(c.encode([0.0, 0.0, 1.0]), 64 | 32 << 7 | 4 << 13);
    assert_eq!(c.encode([-2.0, 0.0, 0.0]), 64 | 32 << 7 | 1 << 13);
    assert_eq!(c.encode([0.0, -1.0, 0.0]), 64 | 32 << 7 | 3 << 13);
    // On +Y, s is z/|y| and t is x/|y|.
    assert_eq!(c.encode([0.5, 1.0, -0.75]), 16 | 47 << 7 | 2 << 13);
    // Ties go to z, then y.
    assert_eq!(c.encode([1.0, 1.0, 1.0]) >> 13, 4);
    assert_eq!(c.encode([1.0, -1.0, 0.5]) >> 13, 3);
    assert_eq!(
        c.decode(127 | 63 << 7 | 6 << 13),
        c.decode(127 | 63 << 7 | 4 << 13)
    );
    assert_eq!(c.decode(7 << 13), c.decode(5 << 13));
    let v = c.decode(127 | 63 << 7);
    let third = 1.0 / 3f32.sqrt();
    assert!(v.iter().all(|x| (x - third).abs() < 1e-6), "{v:?}");
    let w = Cube::warped(16).unwrap().fast();
    // atan(-0.75)/(π/4) = -0.8193 → 11.47; atan(0.5)/(π/4) = 0.5903 → 50.10.
    assert_eq!(w.encode([0.5, 1.0, -0.75]), 11 | 50 << 7 | 2 << 13);
    assert!(Cube::warped(20).is_err());
}

/// xy_signz16 is x as snorm8 in bits 0–7, y as snorm7 in bits 8–14, the sign of z in bit
/// 15; the equator and -0 are on the +Z side, codes outside the disk decode with z = ±0.
#[test]
fn xy_signz_layout_is_x_y_then_the_sign_of_z() {
    let c = XySignZ::new(16).unwrap().fast();
    assert_eq!(c.encode([0.0, 0.0, 1.0]), 0);
    assert_eq!(c.encode([0.0, 0.0, -1.0]), 1 << 15);
    assert_eq!(c.encode([1.0, 0.0, -0.0]), 127);
    assert_eq!(c.encode([0.0, -1.0, 0.0]), 65 << 8);
    assert_eq!(c.encode([0.6, 0.0, -0.8]), 76 | 1 << 15);
    assert_eq!(c.decode(127 | 1 << 15), [1.0, 0.0, -0.0]);
    assert_eq!(c.decode(127 | 63 << 8)[2], 0.0);
    let v = c.decode(76 | 1 << 15);
    assert!((v[0] - 76.0 / 127.0).abs() < 1e-7 && v[2] < -0.79, "{v:?}");
    assert!(XySignZ::new(20).is_err());
}

/// spherical_z16 is the seed's `(atan2(y, x)/π, z)·0.5 + 0.5`: the azimuth as unorm8 in
/// bits 0–7, z as unorm8 in bits 8–15.
#[test]
fn spherical_z_layout_is_azimuth_then_z() {
    let c = SphericalZ::new(16).unwrap().fast();
    // +X: azimuth 0 → 127.5 → 128 (ties to even); z 0 → 128.
    assert_eq!(c.encode([1.0, 0.0, 0.0]), 128 | 128 << 8);
    // +Y: azimuth ½ → 191.25; -Z: z -1 → 0.
    assert_eq!(c.encode([0.0, 1.0, 0.0]), 191 | 128 << 8);
    assert_eq!(c.encode([0.0, 0.0, -1.0]), 128);
    // -X (azimuth exactly π) → 255.
    assert_eq!(c.encode([-1.0, 0.0, 0.0]) & 0xff, 255);
    let v = c.decode(255 << 8);
    assert_eq!(v[2], 1.0);
    assert!(v[0].abs() < 1e-7 && v[1].abs() < 1e-7, "{v:?}");
    assert!(SphericalZ::new(20).is_err());
}

/// xy_stereo16 is (x, y)/(1 + z) as snorm8×2, x in bits 0–7; the horizon maps onto the
/// unit circle and input below it is projected onto it first.
#[test]
fn xy_stereo_layout_and_horizon() {
    let c = XyStereo::new(16).unwrap().fast();
    assert_eq!(c.encode([0.0, 0.0, 1.0]), 0);
    assert_eq!(c.encode([1.0, 0.0, 0.0]), 127);
    assert_eq!(c.encode([0.0, -1.0, -0.5]), 0x81 << 8);
    assert_eq!(c.encode([0.0, 0.0, -1.0]), 0);
    // 0.6/(1 + 0.8) = 1/3 → 42.33.
    assert_eq!(c.encode([0.6, 0.0, 0.8]), 42);
    assert_eq!(c.decode(127), [1.0, 0.0, 0.0]);
    assert!(XyStereo::new(20).is_err());
}

/// paraboloid16 is snorm8×2 of the point where the ray meets z = 1 - (x² + y²), x in bits
/// 0–7: the horizon maps onto the unit circle, and (1, 0, 1) onto 1/φ (the golden ratio).
#[test]
fn paraboloid_layout_and_horizon() {
    let c = Paraboloid::new(16).unwrap().fast();
    assert_eq!(c.encode([0.0, 0.0, 1.0]), 0);
    assert_eq!(c.encode([1.0, 0.0, 0.0]), 127);
    assert_eq!(c.encode([0.0, -1.0, -0.5]), 0x81 << 8);
    assert_eq!(c.encode([0.0, 0.0, -1.0]), 0);
    assert_eq!(c.encode([f32::NAN, 0.0, 1.0]), 0);
    // 0.618034·127 = 78.49.
    assert_eq!(c.encode([1.0, 0.0, 1.0]), 78);
    assert_eq!(c.decode(127), [1.0, 0.0, 0.0]);
    assert!(Paraboloid::new(20).is_err());
}

/// The codes are the seed's quadratic solved in f64 (`a·t² + z·t - 1 = 0`,
/// `p = n.xy·t`) and rounded, wherever that value is not within f32 precision of a
/// rounding boundary (the encoder decides with f32 lengths).
#[test]
fn paraboloid_codes_are_the_seed_quadratic_rounded() {
    for bits in [16, 24] {
        let c = Paraboloid::new(bits).unwrap().fast();
        let half = bits / 2;
        let m = f64::from((1u32 << (half - 1)) - 1);
        let mut near_ties = 0;
        for v in random_unit_vectors(47, 1 << 16, true) {
            let n = v.map(f64::from);
            let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            let n = n.map(|x| x / l);
            let a = n[0] * n[0] + n[1] * n[1];
            let t = (-n[2] + (n[2] * n[2] + 4.0 * a).sqrt()) / (2.0 * a);
            let code = c.encode(v);
            for (k, nk) in n[..2].iter().enumerate() {
                let x = nk * t * m;
                if (x.abs() - x.abs().floor() - 0.5).abs() < x.abs() * 2f64.powi(-20) {
                    near_ties += 1;
                    continue;
                }
                let field = (code >> (k as u32 * half)) & ((1 << half) - 1);
                // Two's complement field, sign-extended.
                let got = ((field << (32 - half)) as i32) >> (32 - half);
                assert_eq!(f64::from(got), x.round(), "paraboloid{bits} of {v:?}");
            }
        }
        assert!(
            near_ties < 1 << 10,
            "paraboloid{bits}: {near_ties} near-ties"
        );
    }
}

/// paraboloid_square16 is snorm8×2 of the point where the ray meets
/// z = (1 - x²)(1 - y²), x in bits 0–7: the square's edges are the horizon (its corners
/// the diagonals), and on an axis the surface is the paraboloid's, so (1, 0, 1) still
/// meets it at 1/φ.
#[test]
fn paraboloid_square_layout_and_horizon() {
    for c in [
        ParaboloidSquare::new(16).unwrap().fast(),
        ParaboloidSquare::new(16).unwrap().precise(),
    ] {
        assert_eq!(c.encode([0.0, 0.0, 1.0]), 0);
        assert_eq!(c.encode([1.0, 0.0, 0.0]), 127);
        assert_eq!(c.encode([1.0, -1.0, 0.0]), 0x817f);
        assert_eq!(c.encode([0.0, -1.0, -0.5]), 0x81 << 8);
        for bad in [
            [0.0, 0.0, -1.0],
            [0.0; 3],
            [f32::NAN, 0.0, 1.0],
            [f32::INFINITY, 1.0, 0.0],
        ] {
            assert_eq!(c.encode(bad), 0, "{bad:?}");
        }
        // 0.618034·127 = 78.49.
        assert_eq!(c.encode([1.0, 0.0, 1.0]), 78);
        assert_eq!(c.decode(127), [1.0, 0.0, 0.0]);
        let d = c.decode(0x7f7f);
        assert_eq!(d[2], 0.0);
        assert!(
            (d[0] - std::f32::consts::FRAC_1_SQRT_2).abs() < 1e-7,
            "{d:?}"
        );
    }
    assert!(ParaboloidSquare::new(20).is_err());
}

/// The second seed's detail combine: with no detail it is the paraboloid's direction
/// (here on points where both forms of the height are exact); a detail slope tilts the
/// normal against it, scaled by the primary's height, so it vanishes on the horizon;
/// outside the disk the point alone is the direction.
#[test]
fn paraboloid_pd_combines_as_the_seed_writes() {
    let close = |a: [f32; 3], b: [f64; 3]| {
        let l = (b[0] * b[0] + b[1] * b[1] + b[2] * b[2]).sqrt();
        (0..3).all(|k| (f64::from(a[k]) - b[k] / l).abs() < 2e-7)
    };
    for (pn, pd, want) in [
        ([0.0, 0.0], [0.0, 0.0], [0.0, 0.0, 1.0]),
        ([0.5, 0.0], [0.0, 0.0], [0.5, 0.0, 0.75]),
        ([0.0, 0.0], [0.5, 0.0], [-0.5, 0.0, 1.0]),
        ([0.0, 0.0], [0.25, -0.75], [-0.25, 0.75, 1.0]),
        // nz = 0.75: the slope is scaled by it before it is added.
        ([0.5, 0.0], [0.0, 1.0], [0.5, -0.75, 0.75]),
        // On the horizon the detail has no effect.
        ([1.0, 0.0], [0.7, -0.3], [1.0, 0.0, 0.0]),
        ([0.0, -1.5], [0.7, -0.3], [0.0, -1.0, 0.0]),
    ] {
        let got = combine_paraboloid_pd(pn, pd);
        assert!(close(got, want), "{pn:?} {pd:?}: {got:?} vs {want:?}");
    }
    // With no detail, the paraboloid decode of the same point, to within rounding.
    let c = Paraboloid::new(16).unwrap().fast();
    for code in 0..=0xffffu32 {
        let field = |k: u32| f32::from(((code >> (8 * k)) & 0xff) as u8 as i8).max(-127.0) / 127.0;
        let got = combine_paraboloid_pd([field(0), field(1)], [0.0, 0.0]);
        let want = c.decode(code);
        assert!(
            (0..3).all(|k| (got[k] - want[k]).abs() < 4e-7),
            "{code:#06x}: {got:?} vs {want:?}"
        );
    }
}

/// The root of the quartic along the ray of unit `n` (`n.z ≥ 0`), solved in f64 by
/// bisection: the larger coordinate `s` where `(1 - s²)(1 - r²s²)·m = n.z·s`, and `g'(s)`
/// there (how far a small error in the surface moves `s`).
fn square_root_f64(n: [f64; 3]) -> ([f64; 2], f64) {
    let (ax, ay) = (n[0].abs(), n[1].abs());
    let (m, small) = (ax.max(ay), ax.min(ay));
    let r = if m > 0.0 { small / m } else { 0.0 };
    let g = |s: f64| (1.0 - s * s) * (1.0 - r * r * s * s) * m - n[2] * s;
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..80 {
        let mid = 0.5 * (lo + hi);
        if g(mid) >= 0.0 { lo = mid } else { hi = mid }
    }
    let s = lo;
    let slope = -2.0 * s * (1.0 - r * r * s * s) * m - 2.0 * r * r * s * (1.0 - s * s) * m - n[2];
    let (px, py) = if ax >= ay { (s, r * s) } else { (r * s, s) };
    ([px.copysign(n[0]), py.copysign(n[1])], slope)
}

/// The fast codes are the quartic's root (solved in f64) rounded, wherever that value is
/// not within reach of the encoder's fixed-point error (a few units of 2^-21 in the
/// surface, divided by the slope) of a rounding boundary, and within that reach of it
/// everywhere. At 16 and 24 bits the margin is rarely needed; at 32 bits a unit of 2^-21
/// is 1/64 of a code, so there it often is.
#[test]
fn paraboloid_square_codes_are_the_quartic_root_rounded() {
    for bits in [16, 24, 32] {
        let c = ParaboloidSquare::new(bits).unwrap().fast();
        let half = bits / 2;
        let m = f64::from((1u32 << (half - 1)) - 1);
        let mut near_ties = 0;
        let samples = random_unit_vectors(53, 1 << 16, true);
        for v in &samples {
            let n = v.map(f64::from);
            let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            let n = n.map(|x| x / l);
            let (p, slope) = square_root_f64([n[0], n[1], n[2].max(0.0)]);
            let reach = m * 8.0 * 2f64.powi(-21) * (1.0 + 1.0 / slope.abs());
            let code = c.encode(*v);
            for (k, pk) in p.iter().enumerate() {
                let x = pk * m;
                let field = (code >> (k as u32 * half)) & ((1 << half) - 1);
                let got = f64::from(((field << (32 - half)) as i32) >> (32 - half));
                assert!(
                    (got - x).abs() <= 0.5 + reach,
                    "paraboloid_square{bits} of {v:?}: {got} for {x}"
                );
                if (x.abs() - x.abs().floor() - 0.5).abs() < reach {
                    near_ties += 1;
                    continue;
                }
                assert_eq!(got, x.round(), "paraboloid_square{bits} of {v:?}");
            }
        }
        if bits < 32 {
            assert!(
                near_ties < samples.len() / 8,
                "paraboloid_square{bits}: {near_ties} near-ties"
            );
        }
    }
}

/// unorm3 is an RGB8 texel of `n·0.5 + 0.5`: x in bits 0–7, y 8–15, z 16–23, the top byte
/// clear; invalid input is +Z, and the all-zero code decodes to (-1, -1, -1)/√3.
#[test]
fn unorm3_is_an_rgb8_texel() {
    let c = Unorm3.fast();
    assert_eq!(c.encode([0.0, 0.0, 1.0]), 128 | 128 << 8 | 255 << 16);
    assert_eq!(c.encode([f32::NAN, 0.0, 1.0]), 128 | 128 << 8 | 255 << 16);
    assert_eq!(c.encode([-1.0, 0.0, 0.0]), 128 << 8 | 128 << 16);
    // 0.6 → 0.8·255 = 204; -0.8 (as f32 inputs, normalized) → 25.5000009 → 26.
    assert_eq!(c.encode([0.6, -0.8, 0.0]), 204 | 26 << 8 | 128 << 16);
    let v = c.decode(0);
    let third = -1.0 / 3f32.sqrt();
    assert!(v.iter().all(|x| (x - third).abs() < 1e-6), "{v:?}");
}

/// Every catalogue codec transcodes to and from `oct24p`: the codes written are the
/// batches' decode then encode, and the reported angles are those between the two
/// decodes, computed here.
#[test]
fn transcoding_is_decode_then_encode_for_every_spec() {
    let hub = Batch::new("oct24p").unwrap();
    let vectors = random_unit_vectors(7, 64, true);
    for spec in unitpack::codecs::Spec::all() {
        let name = spec.to_string();
        if spec.info().domain.is_none() {
            // A packing helper has no decoder to read its codes with; a frame's codes
            // hold more than a vector.
            assert!(Transcoder::new(&name, "oct24p").is_err(), "{name}");
            continue;
        }
        let batch = Batch::new(&name).unwrap();
        for (from, to, f, t) in [
            (&batch, &hub, name.as_str(), "oct24p"),
            (&hub, &batch, "oct24p", name.as_str()),
        ] {
            let mut codes = vec![0u32; vectors.len() * from.words()];
            from.encode(&vectors, &mut codes);
            let tc = Transcoder::new(f, t).unwrap();
            assert_eq!((tc.from_words(), tc.to_words()), (from.words(), to.words()));
            let mut got = vec![0u32; vectors.len() * to.words()];
            let r = tc.transcode(&codes, &mut got);
            let mut v = vec![[0f32; 3]; vectors.len()];
            from.decode(&codes, &mut v);
            let mut want = vec![0u32; got.len()];
            to.encode(&v, &mut want);
            assert_eq!(got, want, "{f} -> {t}");
            let mut back = vec![[0f32; 3]; vectors.len()];
            to.decode(&got, &mut back);
            let angles: Vec<f64> = v
                .iter()
                .zip(&back)
                .map(|(a, b)| angle_deg(*a, *b))
                .collect();
            let max = angles.iter().cloned().fold(0.0, f64::max);
            assert_eq!(r.records, vectors.len() as u64, "{f} -> {t}");
            assert_eq!(r.max.to_bits(), max.to_bits(), "{f} -> {t}");
            assert_eq!(angles[r.max_at as usize - 1].to_bits(), max.to_bits());
            assert!(
                (r.sum - angles.iter().sum::<f64>()).abs() < 1e-9,
                "{f} -> {t}"
            );
        }
    }
}

/// Round trips measured in pieces add up to the whole: counts and sums add, the largest
/// keeps its record number counted from the first piece.
#[test]
fn round_trips_concatenate() {
    let (z, x) = ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
    let a = RoundTrip::default().with(z, z).with(z, x);
    assert_eq!((a.records, a.max, a.max_at), (2, 90.0, 2));
    let b = RoundTrip::default().with(x, x).with(z, [0.0, 0.0, -1.0]);
    let ab = a.then(b);
    assert_eq!((ab.records, ab.max, ab.max_at), (4, 180.0, 4));
    assert_eq!(ab.sum, 270.0);
    assert_eq!(ab.mean(), 67.5);
    let ba = b.then(a);
    assert_eq!((ba.max, ba.max_at), (180.0, 2));
    assert_eq!(RoundTrip::default().then(a), a);
    assert_eq!(a.then(RoundTrip::default()), a);
    // A zero vector's angle is undefined: it counts as the largest there is.
    let zero = RoundTrip::default().with([0.0; 3], z);
    assert_eq!(zero.max, 180.0);
}
