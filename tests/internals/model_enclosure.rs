use unitpack::model::deviant::{DIV_ULP, SQRT_ULP};
use unitpack::model::enclosure::*;
use unitpack::model::num::Float;

fn point(x: f32) -> Encl {
    Encl::c(x)
}

#[test]
fn correctly_rounded_arithmetic_of_undeviated_values_does_not_deviate() {
    let a = Encl::range(0.25, 0.5, ulp(0.25));
    let b = point(3.0);
    let s = (a - point(1.0)) * b;
    assert_eq!(s.deviation(), 0.0);
    assert_eq!(s.reference(), (-2.25, -1.5));
    // The same product feeding a sum may be contracted: then it deviates.
    assert!((a * b - point(1.0)).deviation() > 0.0);
}

#[test]
fn a_product_feeding_a_sum_may_be_contracted() {
    let a = point(1.1);
    let s = a * a + point(1.0);
    // fma(a, a, 1) differs from RN(RN(a·a) + 1) by up to half a ULP of the product
    // plus a rounding of the sum.
    assert!(s.deviation() > 0.0 && s.deviation() <= 0.5 * ulp(1.21) + ulp(2.21));
}

#[test]
fn division_and_root_take_their_latitude() {
    let q = point(1.0) / point(3.0);
    assert!((q.deviation() / ulp(1.0 / 3.0) - (DIV_ULP + 0.5)).abs() < 1e-9);
    let r = point(2.0).sqrt();
    assert!((r.deviation() / ulp(2f64.sqrt()) - (SQRT_ULP + 0.5)).abs() < 1e-9);
}

#[test]
fn a_clamp_moves_no_further_than_its_operands() {
    // 1, and a division's latitude puts the deviant on either side.
    let d = point(3.0) / point(3.0);
    assert!(d.deviants().1 > 1.0 && d.deviation() > 0.0);
    assert_eq!((point(1.0) - d).sqrt().deviation(), f64::INFINITY);
    let c = d.at_most(point(1.0));
    assert!(c.deviants().1 <= 1.0 && c.deviation() <= d.deviation());
    assert!((point(1.0) - c).sqrt().deviation().is_finite());
}

#[test]
fn what_cannot_be_bounded_is_unbounded() {
    let maybe_zero = Encl::range(-1.0, 1.0, ulp(1.0));
    assert_eq!((point(1.0) / maybe_zero).deviation(), f64::INFINITY);
    assert_eq!(maybe_zero.sqrt().deviation(), f64::INFINITY);
}

#[test]
fn a_select_on_a_deviated_comparison_covers_the_jump() {
    let x = point(1.0) / point(3.0);
    let m = x.lt(point(1.0 / 3.0));
    let s = Encl::sel(m, point(0.0), point(1.0));
    assert!(s.deviation() >= 1.0);
    let m = x.lt(point(0.5));
    let s = Encl::sel(m, point(0.0), point(1.0));
    assert_eq!(s.deviation(), 0.0);
}

#[test]
fn only_values_on_a_fine_grid_can_be_flushed() {
    let a = Encl::range(-1.0, 1.0, ulp(1.0 / 127.0));
    assert_eq!((a * a).deviation(), 0.0);
    let tiny = Encl::range(0.0, 1e-30, ulp(1e-30));
    assert!((tiny * tiny).deviation() >= MIN_NORMAL);
}
