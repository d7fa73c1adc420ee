use unitpack::model::num::Float;

/// Every sign and exponent, with a spread of mantissas and their edges (the ties and
/// the largest values below 2^23 included): the same bits as the standard library.
#[test]
fn inline_rounding_matches_the_standard_library() {
    let mantissas = (0..1u32 << 23)
        .step_by(61)
        .chain([1, 2, 0x3f_ffff, 0x40_0000, 0x40_0001, 0x7f_fffe, 0x7f_ffff]);
    for sign in [0, 1u32 << 31] {
        for exp in 0..256u32 {
            for m in mantissas.clone() {
                let x = f32::from_bits(sign | exp << 23 | m);
                let (r, f) = (Float::round(x), Float::floor(x));
                let (want_r, want_f) = (x.round_ties_even(), x.floor());
                assert_eq!(
                    r.to_bits(),
                    want_r.to_bits(),
                    "round {x:e} ({:#010x})",
                    x.to_bits()
                );
                assert_eq!(
                    f.to_bits(),
                    want_f.to_bits(),
                    "floor {x:e} ({:#010x})",
                    x.to_bits()
                );
            }
        }
    }
}
