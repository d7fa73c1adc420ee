use unitpack::codecs::toolkit::lattice::*;

#[test]
fn square_shifted_is_the_truncated_square_to_nine_units() {
    for x in [
        0u32,
        1,
        0xffff,
        0x1_0000,
        0x12_3456,
        (1 << 27) - 1,
        77_777_777,
    ] {
        let exact = (u64::from(x) * u64::from(x)) >> 29;
        let got = u64::from(square_shifted(x));
        assert!(got <= exact && exact - got <= 9, "{x}: {got} vs {exact}");
    }
}

#[test]
fn magnitude_of_twos_complement() {
    assert_eq!(magnitude(5u32), 5);
    assert_eq!(magnitude(0u32.wrapping_sub(5)), 5);
    assert_eq!(magnitude(0u32), 0);
}

#[test]
fn norm_shift_keeps_squares_below_two_to_24() {
    assert_eq!(norm_shift(127.0), 0);
    assert_eq!(norm_shift(2047.0), 0);
    assert_eq!(norm_shift(4095.0), 0);
    assert_eq!(norm_shift(32767.0), 6);
    // Every lattice bound of the codecs (M and 2M for 4- to 16-bit fields): the
    // largest `|d|²` fits, and one bit less shift would not.
    for b in 4..=16u32 {
        for m in [(1u64 << (b - 1)) - 1, 2 * ((1u64 << (b - 1)) - 1)] {
            let shift = norm_shift(m as f32);
            assert!((m * m) >> shift < 1 << 24, "{m}");
            assert!(shift == 0 || (m * m) >> (shift - 1) >= 1 << 24, "{m}");
        }
    }
}
