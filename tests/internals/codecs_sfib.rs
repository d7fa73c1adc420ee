use unitpack::codecs::angular::sfib::*;

/// [`GOLDEN`] is `2^64·(√5 - 1)/2` rounded down: `√5·2^62` by an integer square root,
/// then `2·(√5·2^62 - 2^62)` is within two units of it.
#[test]
fn golden_is_the_fixed_point_golden_ratio() {
    let target: u128 = 5 << 124;
    let mut r: u128 = 1 << 63;
    while r * r > target || (r + 1) * (r + 1) <= target {
        r = (r + target / r) / 2;
    }
    let approx = 2 * (r - (1u128 << 62));
    assert!(approx.abs_diff(u128::from(GOLDEN)) <= 2, "{approx:x}");
}
