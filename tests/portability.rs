//! The adversarial evaluator and the portability report: `Dev` with no deviation is the
//! reference bit for bit; each class deviates where the APIs allow and only there; and
//! what the report measures on the catalogue.

use unitpack::codecs::Spec;
use unitpack::codecs::functions::function::Role;
use unitpack::codecs::functions::inputs::generate;
use unitpack::measure::portability::{Functions, Options, run, ulp_distance};
use unitpack::model::Float;
use unitpack::model::deviant::{
    Class, Classes, DIV_ULP, Dev, Deviation, ITEM_HASH, Mode, SQRT_ULP, begin_item, item_chose,
    item_state, with,
};

fn specs(ids: &[&str]) -> Vec<Spec> {
    ids.iter()
        .map(|s| s.parse().expect("a valid spec"))
        .collect()
}

fn under<R>(class: Class, mode: Mode, f: impl FnOnce() -> R) -> R {
    with(Some(Deviation::new(class, mode)), f)
}

/// With no deviation set, `eval_dev` is `eval` on every sampled input of every function.
#[test]
fn reference_class_reproduces_eval() {
    for spec in specs(&[
        "oct16",
        "oct24p",
        "oct24p:layout=rgb8",
        "snorm16x3",
        "stereo_scaled16",
        "snorm12x2",
    ]) {
        for f in &spec.emitted().functions {
            let input = generate(&f.inputs, f.in_words);
            let n = input.len() / f.in_words;
            let (mut a, mut b) = (vec![0; f.out_words], vec![0; f.out_words]);
            let mut checked = 0;
            for i in (0..n).step_by((n >> 14).max(1)).chain(0..n.min(10_000)) {
                let x = &input[i * f.in_words..][..f.in_words];
                (f.eval)(x, &mut a);
                with(None, || (f.eval_dev)(x, &mut b));
                assert_eq!(a, b, "{} {} on {x:?}", spec.id(), f.name);
                checked += 1;
            }
            assert!(checked > 1000);
        }
    }
}

/// An item's stream is seeded by `(seed·2^64 + index)·K` modulo `2^128`, made odd: the
/// product wraps for every seed above 0 (a plain `*` panicked there in a debug build, so
/// `verify --portable` could not run one). Checked against the product worked out here
/// from 64-bit limbs, and `begin_item` at a seed and item whose product wraps seeds the
/// same deviations each time.
#[test]
fn item_state_is_the_product_modulo_2_128() {
    let limbs = |a: u128, k: u128| {
        let (a0, a1) = (u128::from(a as u64), a >> 64);
        let (k0, k1) = (u128::from(k as u64), k >> 64);
        let low = a0 * k0;
        // Only the low 64 bits of the cross products reach the result's high half.
        let high = ((low >> 64) as u64)
            .wrapping_add((a0 * k1) as u64)
            .wrapping_add((a1 * k0) as u64);
        u128::from(high) << 64 | u128::from(low as u64)
    };
    for (seed, index) in [(0, 5), (1, 0), (7, 1 << 40), (u64::MAX, u64::MAX)] {
        let a = u128::from(seed) << 64 | u128::from(index);
        assert_eq!(
            item_state(seed, index),
            limbs(a, ITEM_HASH) | 1,
            "{seed} {index}"
        );
    }
    assert_eq!(item_state(0, 0), 1);
    let draws = || {
        under(Class::Div, Mode::Seeded(u64::MAX), || {
            begin_item(u64::MAX);
            (0..16).map(|_| div(1.0, 3.0).to_bits()).collect::<Vec<_>>()
        })
    };
    let first = draws();
    assert_eq!(first, draws());
    assert!(first.iter().any(|&b| b != first[0]), "{first:?}");
}

/// The report agrees: no class, no change. And a run that measures nothing is not a pass
/// by accident: the same specs do change under the classes below.
#[test]
fn empty_class_list_reports_nothing() {
    let r = run(&specs(&["oct16"]), &[], &Options::default());
    assert!(r.rows.is_empty());
    assert!(r.packed_encoders_portable());
}

fn div(a: f32, b: f32) -> f32 {
    (Dev::new(a) / Dev::new(b)).value()
}

/// Division stays within 2.5 ULP of the exact quotient, reaches both ends 2 floats away
/// from the correctly rounded one in the worst modes, and varies under seeds.
#[test]
fn div_within_bound_and_reaching_both_ends() {
    let mut seen = std::collections::BTreeSet::new();
    let cases = [
        (1.0f32, 3.0f32),
        (2.0, 7.0),
        (-5.0, 11.0),
        (1.0, 1.5),
        (0.1, 0.3),
    ];
    for (a, b) in cases {
        let r = a / b;
        let exact = f64::from(a) / f64::from(b);
        let lo = under(Class::Div, Mode::Lowest, || div(a, b));
        let hi = under(Class::Div, Mode::Highest, || div(a, b));
        assert_eq!(lo, r.next_down().next_down(), "{a}/{b}");
        assert_eq!(hi, r.next_up().next_up(), "{a}/{b}");
        for seed in 0..200 {
            let q = under(Class::Div, Mode::Seeded(seed), || {
                begin_item(0);
                div(a, b)
            });
            let ulp = f64::from(r.next_up()) - f64::from(r);
            assert!(
                (f64::from(q) - exact).abs() <= DIV_ULP * ulp,
                "{a}/{b} → {q}"
            );
            seen.insert((a.to_bits(), q.to_bits()));
        }
    }
    // Five cases, at least four different quotients each.
    assert!(seen.len() >= 20, "{}", seen.len());
    // Unchanged without the class, and under another one.
    assert_eq!(
        under(Class::Sqrt, Mode::Lowest, || div(1.0, 3.0)),
        1.0 / 3.0
    );
}

fn sqrt(x: f32) -> f32 {
    Dev::new(x).sqrt().value()
}

/// The square root stays within `SQRT_ULP` of the exact root; the worst ends are the
/// farthest floats that bound allows (6 floats either side of the correctly rounded root
/// inside a binade).
#[test]
fn sqrt_within_bound_and_reaching_both_ends() {
    for x in [2.0f32, 3.0, 0.5, 1e-3, 123.456, 3.9] {
        let r = x.sqrt();
        let exact = f64::from(x).sqrt();
        let ulp = f64::from(r.next_up()) - f64::from(r);
        let lo = under(Class::Sqrt, Mode::Lowest, || sqrt(x));
        let hi = under(Class::Sqrt, Mode::Highest, || sqrt(x));
        for q in [lo, hi] {
            assert!(
                (f64::from(q) - exact).abs() <= SQRT_ULP * ulp,
                "sqrt {x} → {q}"
            );
        }
        assert_eq!(ulp_distance(lo.to_bits(), r.to_bits()), 6, "sqrt {x}");
        assert_eq!(ulp_distance(hi.to_bits(), r.to_bits()), 6, "sqrt {x}");
    }
    // Exact zero and one: the root of 1 is 1 ± ULPs, the root of 0 stays 0.
    assert_eq!(under(Class::Sqrt, Mode::Lowest, || sqrt(0.0)), 0.0);
    assert!(under(Class::Sqrt, Mode::Lowest, || sqrt(1.0)) < 1.0);
}

/// `a*b + c` rounds once under `fma` where the two roundings differ: with
/// `a = b = 1 + 2^-12`, `a*a = 1 + 2^-11 + 2^-24` rounds to `1 + 2^-11`, so subtracting
/// that rounded value leaves 0 unfused and `2^-24` fused.
#[test]
fn fma_rounds_a_product_and_sum_once() {
    let a = 1.0 + 2f32.powi(-12);
    let c = -(1.0 + 2f32.powi(-11));
    let f = || (Dev::new(a) * Dev::new(a) + Dev::new(c)).value();
    assert_eq!(a * a + c, 0.0);
    assert_eq!(with(None, f), 0.0);
    assert_eq!(under(Class::Fma, Mode::Highest, f), 2f32.powi(-24));
    assert_eq!(under(Class::Fma, Mode::Lowest, f), 0.0);
    // Through a negation and a subtraction too: c - (-(a*a)) fuses as fma(a, a, c).
    let g = || (Dev::new(c) - -(Dev::new(a) * Dev::new(a))).value();
    assert_eq!(under(Class::Fma, Mode::Highest, g), 2f32.powi(-24));
    // A select in between ends the product: no fusion.
    let h = || {
        let p = Dev::new(a) * Dev::new(a);
        (Dev::sel(p.gt(Dev::c(0.0)), p, Dev::c(1.0)) + Dev::new(c)).value()
    };
    assert_eq!(under(Class::Fma, Mode::Highest, h), 0.0);
    // Excess precision rounds the same expression once as well.
    assert_eq!(under(Class::Excess, Mode::Highest, f), 2f32.powi(-24));
}

/// Under `reassoc` a sum may be regrouped: `(1 + u) + u` with `u = 2^-24` is 1 (each
/// half-ULP tie rounds to even) while `1 + (u + u)` is `1 + 2^-23`; and `a*b + a*c` may be
/// factored as `a*(b + c)`.
#[test]
fn reassoc_regroups_sums_and_factors_products() {
    let u = 2f32.powi(-24);
    let f = || ((Dev::new(1.0) + Dev::new(u)) + Dev::new(u)).value();
    assert_eq!(with(None, f), 1.0);
    assert_eq!(under(Class::Reassoc, Mode::Lowest, f), 1.0);
    assert_eq!(
        under(Class::Reassoc, Mode::Highest, f),
        1.0 + 2f32.powi(-23)
    );
    // With b = fl(1/3) and c its next float: 3b + 3c = 2, but 3(b + c) = 2 + 2^-22.
    let (a, b) = (3.0f32, 1.0f32 / 3.0);
    let c = b.next_up();
    let g = || (Dev::new(a) * Dev::new(b) + Dev::new(a) * Dev::new(c)).value();
    let unfactored = a * b + a * c;
    let factored = a * (b + c);
    assert_ne!(unfactored, factored);
    let both = [
        under(Class::Reassoc, Mode::Lowest, g),
        under(Class::Reassoc, Mode::Highest, g),
    ];
    assert_eq!(both, [unfactored.min(factored), unfactored.max(factored)]);
}

/// Under `round` an inexact `+`, `-` or `*` may give either neighbour of the exact value;
/// an exact one may not change.
#[test]
fn round_takes_either_neighbour_of_an_inexact_result() {
    let u = 2f32.powi(-24);
    let add = || (Dev::new(1.0) + Dev::new(u)).value();
    assert_eq!(under(Class::Round, Mode::Lowest, add), 1.0);
    assert_eq!(
        under(Class::Round, Mode::Highest, add),
        1.0 + 2f32.powi(-23)
    );
    let third = 1.0f32 / 3.0;
    let mul = || (Dev::new(third) * Dev::new(3.0)).value();
    let exact = f64::from(third) * 3.0;
    for m in [Mode::Lowest, Mode::Highest] {
        let r = under(Class::Round, m, mul);
        assert!(
            (f64::from(r) - exact).abs() < f64::from(f32::EPSILON),
            "{r}"
        );
    }
    assert_ne!(
        under(Class::Round, Mode::Lowest, mul),
        under(Class::Round, Mode::Highest, mul)
    );
    let exact_sum = || (Dev::new(1.0) + Dev::new(2.0)).value();
    assert_eq!(under(Class::Round, Mode::Highest, exact_sum), 3.0);
    assert_eq!(under(Class::Round, Mode::Lowest, exact_sum), 3.0);
}

/// Under a per-site mode an operation makes the same choice for every item: each of 64
/// seeds rounds 200 inexact sums (one per item) either all to nearest or all to the other
/// neighbour, and both happen across the seeds; a seeded mode mixes them.
#[test]
fn a_site_chooses_the_same_for_every_item() {
    let items: Vec<(f32, f32)> = (0..200)
        .map(|i| {
            (
                1.0 + i as f32 * 2f32.powi(-10),
                2f32.powi(-24) * (1.0 + i as f32 / 512.0),
            )
        })
        .collect();
    let nearest = |mode: Mode| -> Vec<bool> {
        items
            .iter()
            .enumerate()
            .map(|(i, &(a, b))| {
                under(Class::Round, mode, || {
                    begin_item(i as u64);
                    (Dev::new(a) + Dev::new(b)).value() == a + b
                })
            })
            .collect()
    };
    let mut seen = [false; 2];
    for seed in 0..64 {
        let n = nearest(Mode::Site(seed));
        assert!(n.iter().all(|&x| x == n[0]), "seed {seed}: {n:?}");
        seen[usize::from(n[0])] = true;
    }
    assert_eq!(seen, [true, true]);
    let mixed = nearest(Mode::Seeded(1));
    assert!(mixed.contains(&true) && mixed.contains(&false));
}

/// Under `contract` a comparison may take a product whole: `a*b` rounds to exactly `c`
/// while the exact product is below it, so `a*b < c` is false as written and true when
/// contracted; `fma` alone (a C compiler's latitude) never does this, and a classes set
/// takes both at once.
#[test]
fn contract_compares_a_product_whole() {
    let (a, b) = (1.0 + 2f32.powi(-13), 1.0 - 2f32.powi(-13));
    let c = a * b;
    assert!(f64::from(a) * f64::from(b) < f64::from(c));
    let less = || (Dev::new(a) * Dev::new(b)).lt(Dev::new(c)).0;
    assert!(!less());
    for class in [Class::Fma, Class::Reassoc, Class::Div, Class::Denorm] {
        for mode in [Mode::Lowest, Mode::Highest, Mode::Site(1), Mode::Seeded(1)] {
            assert!(!under(class, mode, less), "{class:?} {mode:?}");
        }
    }
    let both: Vec<bool> = [Mode::Lowest, Mode::Highest]
        .into_iter()
        .map(|m| {
            with(
                Some(Deviation::new(
                    Classes::of(&[Class::Fma, Class::Contract]),
                    m,
                )),
                less,
            )
        })
        .collect();
    assert_eq!(both, [false, true]);
}

/// Denormal operands and results may become zeros of their sign.
#[test]
fn denorm_flushes_inputs_and_outputs() {
    let d = f32::from_bits(1); // the smallest denormal
    let m = f32::MIN_POSITIVE;
    // An output: MIN_POSITIVE/2 is denormal.
    let half = || (Dev::new(m) * Dev::c(0.5)).value();
    assert_eq!(with(None, half), m / 2.0);
    assert_eq!(under(Class::Denorm, Mode::Lowest, half).to_bits(), 0);
    // An input: d + 1 vs 0 + 1 is the same, but d * 2^100 is not.
    let big = || (Dev::new(d) * Dev::c(2f32.powi(100))).value();
    assert_eq!(under(Class::Denorm, Mode::Highest, big), d * 2f32.powi(100));
    assert_eq!(under(Class::Denorm, Mode::Lowest, big), 0.0);
    // The sign is kept: -d flushes to -0.
    let neg = || (Dev::new(-d) * Dev::c(1.0)).value();
    assert_eq!(
        under(Class::Denorm, Mode::Highest, neg).to_bits(),
        (-0f32).to_bits()
    );
    // floor(-d) is -1, or -0 once flushed; comparisons see flushed operands.
    assert_eq!(
        under(Class::Denorm, Mode::Highest, || Dev::new(-d)
            .floor()
            .value())
        .to_bits(),
        (-0f32).to_bits()
    );
    assert!(under(
        Class::Denorm,
        Mode::Lowest,
        || Dev::new(d).gt(Dev::c(0.0)).0 as u8 == 0
    ));
    // Normal values are never touched.
    assert_eq!(
        under(Class::Denorm, Mode::Lowest, || (Dev::new(m) * Dev::c(1.0))
            .value()),
        m
    );
}

/// An item is marked as having had a choice exactly when some operation allowed results
/// that differ, which the report relies on to evaluate a forced item in one mode only; a
/// new item starts unmarked.
#[test]
fn item_chose_marks_only_operations_with_different_allowed_results() {
    let chose = |class: Class, f: &dyn Fn()| {
        under(class, Mode::Seeded(7), || {
            begin_item(0);
            f();
            item_chose()
        })
    };
    let third = || {
        let _ = div(1.0, 3.0);
    };
    assert!(
        chose(Class::Div, &third),
        "1/3 has neighbours within 2.5 ULP"
    );
    assert!(
        !chose(Class::Sqrt, &third),
        "sqrt's class leaves division alone"
    );
    let normal = || {
        let _ = (Dev::new(1.5) * Dev::c(3.0)).value();
    };
    assert!(!chose(Class::Denorm, &normal), "no denormal to flush");
    let tiny = || {
        let _ = (Dev::new(f32::MIN_POSITIVE) * Dev::c(0.5)).value();
    };
    assert!(chose(Class::Denorm, &tiny), "a denormal product may flush");
    under(Class::Div, Mode::Lowest, || {
        third();
        begin_item(1);
        assert!(!item_chose(), "begin_item clears the mark");
    });
}

/// `floor(-0.25)` is `-1`, but `floor(-0.0)` and `round(-0.25)` are zeros whose sign may be
/// lost; `abs` and selects may produce either zero.
#[test]
fn zero_loses_sign_in_floor_round_abs_select() {
    let plus = |f: &dyn Fn() -> f32| under(Class::Zero, Mode::Highest, f).to_bits();
    let minus = |f: &dyn Fn() -> f32| under(Class::Zero, Mode::Lowest, f).to_bits();
    let floor = || Dev::new(-0.0).floor().value();
    let round = || Dev::new(-0.25).round().value();
    let abs = || Dev::new(-0.0).abs().value();
    let sel = || {
        Dev::sel(
            unitpack::model::deviant::DevB(true),
            Dev::new(-0.0),
            Dev::c(1.0),
        )
        .value()
    };
    assert_eq!(with(None, floor).to_bits(), (-0f32).to_bits());
    assert_eq!(with(None, round).to_bits(), (-0f32).to_bits());
    for f in [&floor as &dyn Fn() -> f32, &round, &abs, &sel] {
        assert_eq!(plus(f), 0);
        assert_eq!(minus(f), (-0f32).to_bits());
    }
    // Non-zero results keep their value and sign; arithmetic zeros are left alone.
    assert_eq!(
        under(Class::Zero, Mode::Highest, || Dev::new(-0.25)
            .floor()
            .value()),
        -1.0
    );
    assert_eq!(
        under(Class::Zero, Mode::Highest, || (Dev::new(-0.0)
            * Dev::c(1.0))
        .value())
        .to_bits(),
        (-0f32).to_bits()
    );
}

/// The report counts what changed and flags packed encoders only.
#[test]
fn report_counts_changes_and_renders() {
    let opts = Options {
        seeds: vec![1],
        worst_ends: true,
        sites: Vec::new(),
        sample: Some(1 << 10),
        functions: Functions::All,
    };
    let r = run(
        &specs(&["oct16"]),
        &[Class::Div.into(), Class::Zero.into()],
        &opts,
    );
    assert_eq!(r.rows.len(), 4 * 2);
    assert_eq!(r.modes.len(), 4);
    for row in &r.rows {
        assert!(row.changed <= row.items);
        assert_eq!(row.by_mode.len(), 4);
        assert!(row.by_mode.iter().all(|&n| n <= row.changed));
        assert_eq!(row.max_ulp.is_none(), row.role == Role::Encode);
        assert_eq!(row.example.is_some(), row.changed > 0);
    }
    let t = r.table();
    assert!(
        t.contains("oct16") && t.contains("div") && t.contains("zero"),
        "{t}"
    );
    let j = r.json();
    assert!(j.starts_with("{\"classes\":[\"div\",\"zero\"]"), "{j}");
    assert_eq!(j.matches("\"spec\":\"oct16\"").count(), 8);
    assert!(j.contains(&format!(
        "\"packed_encoders_portable\":{}",
        r.packed_encoders_portable()
    )));
}

/// Measured: under `zero` (the SSE2-only Mesa path), the precise oct encoders' float
/// outputs change the sign of zeros while their packed codes do not, as the issue
/// observed on Mesa.
#[test]
fn zero_changes_precise_float_outputs_not_codes() {
    let r = run(
        &specs(&["oct16p", "oct24p"]),
        &[Class::Zero.into()],
        &Options::default(),
    );
    for row in &r.rows {
        match row.role {
            Role::EncodeFloat => {
                assert!(row.changed > 0, "{} {}", row.spec, row.function);
                assert_eq!(row.max_ulp, Some(0), "sign of zero only: {}", row.spec);
            }
            Role::Encode => assert_eq!(row.changed, 0, "{} encode", row.spec),
            _ => {}
        }
    }
    assert!(r.packed_encoders_portable(), "{}", r.table());
}

/// Every encoder whose codec declares it portable (and says so in its doc comment) keeps
/// every code under every guaranteed class, in every mode; every other packed encoder
/// does change under one, so no claim is missing either. Over every edge vector and 2^12
/// others per encoder, a quarter of `verify --portable`'s sample: the precise searches
/// cost thousands of deviant operations per item, and the whole catalogue runs here.
#[test]
fn declared_portable_encoders_never_change() {
    let all = Spec::all();
    let opts = Options {
        functions: Functions::IntegerOutputs,
        sample: Some(1 << 12),
        ..Options::default()
    };
    let report = run(&all, &Class::GUARANTEED.map(Into::into), &opts);
    let mut portable = 0;
    for spec in &all {
        let e = spec.emitted();
        let id = spec.id();
        let encode = || {
            report
                .rows
                .iter()
                .filter(|r| r.spec == id && r.role == Role::Encode)
        };
        if !e.functions.iter().any(|f| f.role == Role::Encode) {
            continue;
        }
        let lean = unitpack::codecs::core::ieee::asked(spec);
        assert_eq!(
            e.portable_encoder, !lean,
            "{id}: every encoder is portable but the lean tier's"
        );
        if e.portable_encoder {
            portable += 1;
            for r in encode() {
                assert_eq!(
                    r.changed,
                    0,
                    "{id} under {}: {:?}",
                    r.class.name(),
                    r.example
                );
            }
        } else {
            assert!(
                encode().any(|r| r.changed > 0),
                "{id} does not change: declare it portable"
            );
        }
    }
    // Every packed encoder of the catalogue is portable (issue #7's promise) but the lean
    // tier's, so a codec added without the exact forms fails here.
    let encoders = all
        .iter()
        .filter(|s| !unitpack::codecs::core::ieee::asked(s))
        .filter(|s| s.emitted().functions.iter().any(|f| f.role == Role::Encode))
        .count();
    assert_eq!(portable, encoders);
    assert!(portable >= 51, "{portable}");
    // A lookup table's texel decides a code as much as the encoder does: it must not
    // move either (spherical_lut16's atan_texel and sincos_texel).
    let texels: Vec<_> = report
        .rows
        .iter()
        .filter(|r| r.role == Role::LutTexel)
        .collect();
    assert!(texels.len() >= 4, "{}", texels.len());
    for r in texels {
        assert_eq!(
            r.changed,
            0,
            "{} {} under {}: {:?}",
            r.spec,
            r.function,
            r.class.name(),
            r.example
        );
    }
}

/// What the README's API table says lies outside the guarantee does reach the portable
/// encoders: either-neighbour rounding moves oct16 codes, and regrouped sums move oct32
/// codes (its comparisons feed on a three-term L1 sum).
#[test]
fn portable_encoders_still_change_under_reassociation_and_rounding() {
    let specs: Vec<Spec> = ["oct16", "oct32"].map(|s| s.parse().unwrap()).to_vec();
    assert!(specs.iter().all(|s| s.emitted().portable_encoder));
    let opts = Options {
        functions: Functions::IntegerOutputs,
        ..Options::default()
    };
    let report = run(&specs, &[Class::Reassoc.into(), Class::Round.into()], &opts);
    let changed = |id: &str, class: Class| {
        report
            .rows
            .iter()
            .filter(|r| r.spec == id && r.role == Role::Encode && r.class == class.into())
            .map(|r| r.changed)
            .sum::<usize>()
    };
    assert!(changed("oct16", Class::Round) > 0);
    assert!(changed("oct32", Class::Reassoc) > 0);
    assert!(!report.rows.iter().any(|r| r.class.guaranteed()));
}

/// The README's measured claim: the integer-decided precise searches, and the fast
/// lambert and stereo_scaled encoders (whose lengths are integer sums and whose roots are
/// single products), keep their codes under `reassoc` too, where the fast oct32 encoder
/// does not (above).
#[test]
fn integer_decided_encoders_keep_codes_under_reassociation() {
    let specs: Vec<Spec> = ["oct32p", "hemioct32p", "lambert32", "stereo_scaled32"]
        .map(|s| s.parse().unwrap())
        .to_vec();
    let opts = Options {
        functions: Functions::IntegerOutputs,
        ..Options::default()
    };
    let report = run(&specs, &[Class::Reassoc.into()], &opts);
    let rows: Vec<_> = report
        .rows
        .iter()
        .filter(|r| r.role == Role::Encode)
        .collect();
    assert!(!rows.is_empty());
    for r in rows {
        assert_eq!(r.changed, 0, "{} under reassoc: {:?}", r.spec, r.example);
    }
}

/// Flushing denormals never turns a float form's output into NaN: `atan2_pi` scales tiny
/// operands up before it divides (an implementation may flush a denormal divisor inside
/// the division though not in the comparison guarding it).
#[test]
fn denormal_flushing_gives_no_nan() {
    let r = run(
        &specs(&["spherical16", "spherical32p", "oct16", "lambert16", "xy16"]),
        &[Class::Denorm.into()],
        &Options::default(),
    );
    for row in &r.rows {
        assert_ne!(
            row.max_ulp,
            Some(u64::MAX),
            "{} {}: NaN under denorm",
            row.spec,
            row.function
        );
    }
}

/// One line of a kept run (`tests/data/h100_*.tsv`, `tests/data/h200_*.tsv`,
/// `tests/data/swiftshader_flushed_floats.tsv`): spec, function, input words,
/// the model's output words and the GPU's, and any further columns.
struct Kept {
    spec: String,
    function: String,
    input: Vec<u32>,
    model: Vec<u32>,
    gpu: Vec<u32>,
}

fn kept(file: &str) -> Vec<Kept> {
    let path = format!("{}/tests/data/{file}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let words = |s: &str| -> Vec<u32> {
        s.split(' ')
            .map(|w| u32::from_str_radix(w, 16).unwrap_or_else(|e| panic!("{w}: {e}")))
            .collect()
    };
    text.lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| {
            let c: Vec<&str> = l.split('\t').collect();
            Kept {
                spec: c[0].into(),
                function: c[1].into(),
                input: words(c[2]),
                model: words(c[3]),
                gpu: words(c[4]),
            }
        })
        .collect()
}

/// Each kept spec's emitted functions, by id.
type Emitted = std::collections::HashMap<
    String,
    std::sync::Arc<unitpack::codecs::functions::function::Emitted>,
>;

/// The function a kept line names.
fn kept_function<'a>(
    emitted: &'a mut Emitted,
    k: &Kept,
) -> &'a unitpack::codecs::functions::function::Function {
    emitted
        .entry(k.spec.clone())
        .or_insert_with(|| k.spec.parse::<Spec>().expect("a valid spec").emitted())
        .functions
        .iter()
        .find(|f| f.name == k.function)
        .unwrap_or_else(|| panic!("{} has no function {}", k.spec, k.function))
}

/// The H100's, H200's and SwiftShader's kept items still hold the model's outputs: each line's model column is what
/// the function computes today, and the GPU's column differs from it. A model change that
/// moves one of these outputs makes the data stale, and this says which line.
#[test]
fn gpu_items_hold_the_model_outputs() {
    for (file, lines) in [
        ("h100_naga_changed_codes.tsv", 2085),
        ("h100_naga_beyond_bound.tsv", 6),
        ("h100_gl_precise_changed_codes.tsv", 48),
        ("h200_changed_codes.tsv", 2783),
        ("h200_beyond_bound.tsv", 15),
        ("swiftshader_flushed_floats.tsv", SWIFTSHADER_LINES),
    ] {
        let items = kept(file);
        assert_eq!(items.len(), lines, "{file}");
        let mut emitted = Emitted::new();
        for k in &items {
            let f = kept_function(&mut emitted, k);
            let mut out = vec![0; f.out_words];
            (f.eval)(&k.input, &mut out);
            assert_eq!(
                out, k.model,
                "{file}: {} {} on {:08x?}: the model now gives {out:08x?}",
                k.spec, k.function, k.input
            );
            assert_ne!(k.gpu, k.model, "{file}: {} {}", k.spec, k.function);
        }
    }
}

/// Lines of `tests/data/swiftshader_flushed_floats.tsv`.
const SWIFTSHADER_LINES: usize = 2838;

/// `verify --portable`'s denormal class predicts SwiftShader: with the flush taken at
/// every operation ([`Mode::Last`]: every denormal operand and result is zero, its sign
/// kept), the model gives, item for item, the float-form outputs SwiftShader changed and
/// the lean tier's codes it changed
/// (`tests/data/swiftshader_flushed_floats.tsv`, kept from `wgsl/naga on swiftshader`,
/// which runs the same module as lavapipe, and checked against the Tint and ANGLE runs).
#[test]
fn the_denormal_class_predicts_what_swiftshader_changes() {
    let items = kept("swiftshader_flushed_floats.tsv");
    assert_eq!(items.len(), SWIFTSHADER_LINES);
    let mut emitted = Emitted::new();
    let mut functions = std::collections::BTreeSet::new();
    for (i, k) in items.iter().enumerate() {
        let f = kept_function(&mut emitted, k);
        let mut out = vec![0; f.out_words];
        with(Some(Deviation::new(Class::Denorm, Mode::Last)), || {
            begin_item(i as u64);
            (f.eval_dev)(&k.input, &mut out);
        });
        assert_eq!(
            out, k.gpu,
            "{} {} on {:08x?}: SwiftShader gave {:08x?}, the denormal class {out:08x?}",
            k.spec, k.function, k.input, k.gpu
        );
        functions.insert((k.spec.as_str(), k.function.as_str()));
    }
    assert!(functions.len() >= 50, "{} functions", functions.len());
}

/// The deviation model predicts what the H100 did on the naga paths: per site
/// ([`Mode::Site`]: each operation fused, regrouped or compared whole the same way for
/// every input, as a compiler decides per instruction), under `fma`, `reassoc` and
/// `contract` at once,
/// 16 seeds reproduce the H100's own code for nearly every item it changed (2055 of 2085
/// measured), in each of the 43 functions. Only the code the H100 wrote counts: a change
/// to some other code would not be a prediction.
#[test]
fn per_site_contraction_reproduces_the_h100s_codes() {
    let items = kept("h100_naga_changed_codes.tsv");
    let set = Classes::WITHOUT_NO_CONTRACTION;
    let mut emitted = Emitted::new();
    let mut reproduced = std::collections::BTreeMap::<String, usize>::new();
    for (i, k) in items.iter().enumerate() {
        let f = kept_function(&mut emitted, k);
        let mut out = vec![0; f.out_words];
        let hit = (0..16).any(|seed| {
            with(Some(Deviation::new(set, Mode::Site(seed))), || {
                begin_item(i as u64);
                (f.eval_dev)(&k.input, &mut out);
            });
            out == k.gpu
        });
        *reproduced
            .entry(format!("{} {}", k.spec, k.function))
            .or_default() += usize::from(hit);
    }
    let missed: Vec<_> = reproduced.iter().filter(|(_, n)| **n == 0).collect();
    assert_eq!(reproduced.len(), 43);
    assert!(missed.is_empty(), "no H100 code reproduced in {missed:?}");
    let total: usize = reproduced.values().sum();
    assert!(total >= 2000, "{total} of {} reproduced", items.len());
}
