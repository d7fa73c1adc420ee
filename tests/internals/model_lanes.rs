use unitpack::model::avx2_lanes;
use unitpack::model::lanes::{F4, operations};
use unitpack::model::num::{Bool, Float, Uint};

const EDGES: [f32; 26] = [
    0.0,
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

/// The scalar model's result of operation `what` on `a` and `b`, as raw bits (masks 0/1).
fn scalar(what: &str, a: f32, b: f32) -> u32 {
    let (u, v) = (a.to_bits(), b.to_bits());
    let m = |c: bool| u32::from(c);
    match what {
        "fadd" => (a + b).to_bits(),
        "fsub" => (a - b).to_bits(),
        "fmul" => (a * b).to_bits(),
        "fdiv" => (a / b).to_bits(),
        "fneg" => (-a).to_bits(),
        "fabs" => Float::abs(a).to_bits(),
        "fsqrt" => Float::sqrt(a).to_bits(),
        "ffloor" => Float::floor(a).to_bits(),
        "fround" => Float::round(a).to_bits(),
        "to_u" => Float::to_u(a),
        "lt" => m(a < b),
        "le" => m(a <= b),
        "gt" => m(a > b),
        "ge" => m(a >= b),
        "eq" => m(a == b),
        "and" => m(Float::lt(a, b).and(a >= b.abs())),
        "or" => m(Float::lt(a, b).or(a == b)),
        "not" => m(Float::lt(a, b).not()),
        "fsel" => f32::sel(a < b, a, b).to_bits(),
        "fto_f" => (u as f32).to_bits(),
        "as_float" => u,
        "add_u" => u.wrapping_add(v),
        "sub_u" => u.wrapping_sub(v),
        "mul_u" => u.wrapping_mul(v),
        "and_u" => u & v,
        "or_u" => u | v,
        "lt_u" => m(u < v),
        "shr" => u >> 7,
        "shl" => u << 9,
        "usel" => u32::sel(u < v, u, v),
        "at_least_nonzero" => (if a >= -1.0 { a } else { -1.0 }).to_bits(),
        // Two's complement fields, sign-extended by integer shifts.
        "signed8" => ((((u & 0xff) << 24) as i32 >> 24) as f32).to_bits(),
        "signed10" => (((u >> 22 << 22) as i32 >> 22) as f32).to_bits(),
        "signed16" => ((((u & 0xffff) << 16) as i32 >> 16) as f32).to_bits(),
        "signed24" => (((u >> 8 << 8) as i32 >> 8) as f32).to_bits(),
        // The word moves: item k's words are u, v, u ^ v, u + v, u - v, u·v and !u.
        "items2_0" | "items3_0" | "to_items3_0" | "to_items7_0" => u,
        "items2_1" | "items3_1" | "to_items3_1" | "to_items7_1" => v,
        "items3_2" | "to_items3_2" | "to_items7_2" => u ^ v,
        "to_items7_3" => u.wrapping_add(v),
        "to_items7_4" => u.wrapping_sub(v),
        "to_items7_5" => u.wrapping_mul(v),
        "to_items7_6" => !u,
        _ => panic!("no scalar model for {what}"),
    }
}

/// Every operation's lanes against the scalar model. A NaN's sign and payload are not a
/// model value: the compiler may commute `a + b`, and x86 returns the first operand's
/// NaN. Every other result is compared as raw bits.
fn check<const N: usize>(lanes: &str, a: [f32; N], b: [f32; N], got: &[(&str, [u32; N])]) {
    assert_eq!(
        got.len(),
        50,
        "{lanes}: every operation and word move is checked"
    );
    for (what, got) in got {
        for k in 0..N {
            let want = scalar(what, a[k], b[k]);
            let nan = |u: u32| f32::from_bits(u).is_nan();
            if what.starts_with('f') && nan(want) && nan(got[k]) {
                continue;
            }
            assert_eq!(
                got[k], want,
                "{lanes} {what}({:e}, {:e}) lane {k}: {:#010x}, the model {want:#010x}",
                a[k], b[k], got[k]
            );
        }
    }
}

/// Lane sets drawn from `pool`, rotated so that every value meets several neighbours.
fn lane_sets<const N: usize>(pool: &[f32]) -> Vec<([f32; N], [f32; N])> {
    let n = pool.len();
    (0..n)
        .map(|i| {
            (
                std::array::from_fn(|k| pool[(i + k * k + k) % n]),
                std::array::from_fn(|k| pool[(i + 3 * k + 3) % n]),
            )
        })
        .collect()
}

/// Pools that take every path of the conversions: all edges (lanes at or past 2^31 and
/// negative bit patterns), and non-negative values below 2^31 only (the direct
/// conversions of the eight AVX2 lanes).
fn pools() -> [Vec<f32>; 2] {
    [
        EDGES.to_vec(),
        EDGES
            .iter()
            .copied()
            .filter(|x| x.to_bits() >> 31 == 0 && *x < 2_147_483_648.0)
            .collect(),
    ]
}

#[test]
fn every_operation_on_four_lanes_matches_the_scalar_model_bit_for_bit() {
    for pool in pools() {
        for (a, b) in lane_sets::<4>(&pool) {
            check("4 lanes", a, b, &operations::<F4, 4>(a, b));
        }
    }
}

#[test]
fn every_operation_on_eight_avx2_lanes_matches_the_scalar_model_bit_for_bit() {
    // Off x86-64 there are no eight-lane operations to test.
    let wanted = cfg!(target_arch = "x86_64");
    assert_eq!(
        avx2_lanes::available(),
        wanted,
        "the CPU batches' eight-lane path needs a processor with AVX2 to be tested"
    );
    for pool in pools() {
        for (a, b) in lane_sets::<8>(&pool) {
            let got = avx2_lanes::operations(a, b);
            assert_eq!(got.is_some(), wanted, "eight-lane operations ran");
            if let Some(got) = got {
                check("8 lanes", a, b, &got);
            }
        }
    }
}
