//! The CPU library: construction errors, slices, and round trips.

use unitpack::api::{CpuCodec, HemiOct, Oct, Snorm3, StereoScaled};
use unitpack::quality::{angle_deg, random_unit_vectors};

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
