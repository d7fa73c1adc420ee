use unitpack::codecs::toolkit::fixed_decode::*;
use unitpack::model::{V2, V3};

#[test]
fn odd_square_quarter_is_exact_at_the_largest_codes() {
    let t = V2::new(65535.0f32, -65533.0);
    let q = u64::from(odd_square_quarter(t));
    assert_eq!(4 * q + 2, 65535u64 * 65535 + 65533 * 65533);
}

#[test]
fn distance_is_the_exact_square_sum() {
    let d = V3::new(2_097_152.0f32, -3.0, 0.0);
    let u = V3::new(-2_097_152.0f32, 1.0, 5.0);
    // (2^22)² + 16 + 25, rounded once to f32.
    let exact = (1u64 << 44) + 41;
    assert_eq!(distance(d, u).0, exact as f32);
}
