use unitpack::model::lanes::*;
use unitpack::model::num::{Float, Uint};
use wide::f32x4;

fn lanes(x: [f32; 4]) -> F4 {
    F4(f32x4::new(x))
}

/// Each operation against the scalar model on edge values, as raw bits.
#[test]
fn every_operation_matches_the_scalar_model_bit_for_bit() {
    let edges = [
        0.0f32,
        -0.0,
        0.5,
        -0.5,
        1.5,
        2.5,
        -2.5,
        1e-45,
        -1e-40,
        f32::MIN_POSITIVE,
        8_388_607.5,
        8_388_609.0,
        -8_388_608.0,
        2_147_483_520.0,
        2_147_483_648.0,
        4_294_967_040.0,
        4_294_967_296.0,
        -1.0,
        -0.999,
        3.4e38,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
        -f32::NAN,
        123.456,
        -7.75,
    ];
    let n = edges.len();
    for i in 0..n {
        let a = [
            edges[i],
            edges[(i + 1) % n],
            edges[(i + 5) % n],
            edges[(i + 11) % n],
        ];
        let b = [
            edges[(i + 3) % n],
            edges[i],
            edges[(i + 7) % n],
            edges[(i + 2) % n],
        ];
        let (x, y) = (lanes(a), lanes(b));
        // A NaN's sign and payload are not a model value: the compiler may commute
        // `a + b`, and x86 returns the first operand's NaN. Every other result is
        // compared as raw bits.
        let check = |what: &str, got: [u32; 4], want: &dyn Fn(f32, f32) -> u32| {
            for k in 0..4 {
                let w = want(a[k], b[k]);
                let nan = |u: u32| f32::from_bits(u).is_nan();
                if what.starts_with('f') && nan(w) && nan(got[k]) {
                    continue;
                }
                assert_eq!(got[k], w, "{what}({}, {})", a[k], b[k]);
            }
        };
        let fb = |v: F4| v.to_bits().0.to_array();
        let mb = |m: M4| m.0.to_array().map(|w| u32::from(w != 0));
        check("fadd", fb(x + y), &|a, b| (a + b).to_bits());
        check("fsub", fb(x - y), &|a, b| (a - b).to_bits());
        check("fmul", fb(x * y), &|a, b| (a * b).to_bits());
        check("fdiv", fb(x / y), &|a, b| (a / b).to_bits());
        check("fneg", fb(-x), &|a, _| (-a).to_bits());
        check("fabs", fb(x.abs()), &|a, _| Float::abs(a).to_bits());
        check("fsqrt", fb(x.sqrt()), &|a, _| Float::sqrt(a).to_bits());
        check("ffloor", fb(x.floor()), &|a, _| Float::floor(a).to_bits());
        check("fround", fb(x.round()), &|a, _| Float::round(a).to_bits());
        check("to_u", x.to_u().0.to_array(), &|a, _| Float::to_u(a));
        check("lt", mb(x.lt(y)), &|a, b| u32::from(a < b));
        check("le", mb(x.le(y)), &|a, b| u32::from(a <= b));
        check("gt", mb(x.gt(y)), &|a, b| u32::from(a > b));
        check("ge", mb(x.ge(y)), &|a, b| u32::from(a >= b));
        check("eq", mb(x.eq(y)), &|a, b| u32::from(a == b));
        let u = U4(x.to_bits().0);
        let v = U4(y.to_bits().0);
        let ub = |u: U4| u.0.to_array();
        let bits = |f: fn(u32, u32) -> u32| move |a: f32, b: f32| f(a.to_bits(), b.to_bits());
        check("fto_f", fb(u.to_f()), &bits(|a, _| (a as f32).to_bits()));
        check("mul_u", ub(u.wrapping_mul(v)), &bits(u32::wrapping_mul));
        check("sub_u", ub(u.wrapping_sub(v)), &bits(u32::wrapping_sub));
        check("lt_u", mb(u.lt(v)), &bits(|a, b| u32::from(a < b)));
        check("shr", ub(u.shr(7)), &bits(|a, _| a >> 7));
        check("shl", ub(u.shl(9)), &bits(|a, _| a << 9));
        let m = x.lt(y);
        check("fsel", fb(F4::sel(m, x, y)), &|a, b| {
            if a < b { a } else { b }.to_bits()
        });
    }
}
