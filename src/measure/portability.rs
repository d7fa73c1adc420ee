//! Portability: every emitted function evaluated by the adversarial
//! [`Dev`](crate::model::deviant::Dev) under each deviation [`Class`] a conformant GPU may
//! take, compared as raw bits with the exact `f32` reference.
//!
//! Bit-exact verification on lavapipe proves the code on an implementation that rounds
//! every operation correctly; this module asks what changes on one that uses every liberty
//! the APIs allow. A packed encoder ([`Role::Encode`]) must not change under any class:
//! its code is data that another implementation decodes; nor may a lookup table's texel
//! ([`Role::LutTexel`]). The lean tier's encoders (`guarantee=ieee`), documented not
//! portable, are measured and marked, not failed. Float outputs report their
//! largest deviation in ULP; decoders also their largest absolute deviation, which must
//! stay within the bound [`crate::measure::decode_bound`] proves and their doc comments state. It
//! needs no GPU, so it builds without the `verify` feature.
//!
//! ```no_run
//! use unitpack::model::deviant::Class;
//! use unitpack::measure::portability::{Options, run};
//! let report = run(&unitpack::Spec::all(), &Class::ALL.map(Into::into), &Options::default());
//! print!("{}", report.table());
//! println!("packed encoders portable: {}", report.packed_encoders_portable());
//! ```

use crate::codecs::Spec;
use crate::codecs::functions::function::{Emitted, Function, Inputs, Role, first_with_same_code};
use crate::codecs::functions::inputs::{edge_vectors, generate};
use crate::measure::figures::Bound;
pub use crate::measure::figures::UNIT;
pub use crate::model::deviant::{Class, Classes, Deviation, Mode};
use crate::model::deviant::{begin_item, item_chose, with};
use crate::model::trace::Module;
use std::collections::HashMap;
use std::fmt::Write;
use std::ops::Range;
use std::sync::Arc;

/// What [`run`] evaluates.
#[derive(Clone, Debug)]
pub struct Options {
    /// Seeds of the [`Mode::Seeded`] runs.
    pub seeds: Vec<u64>,
    /// Also run [`Mode::Lowest`], [`Mode::Highest`] and [`Mode::Last`] (the deviation
    /// wherever allowed: under `denorm`, what SwiftShader computes).
    pub worst_ends: bool,
    /// Seeds of the [`Mode::Site`] runs: one choice per operation for every item.
    pub sites: Vec<u64>,
    /// Evaluate at most this many items per function, evenly spread over the verify inputs
    /// (encoders: every edge vector plus this many others); `None`: all of them.
    pub sample: Option<usize>,
    /// Which functions to evaluate.
    pub functions: Functions,
}

/// The functions [`run`] evaluates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Functions {
    All,
    /// Those with integer outputs ([`integer_output`]: the packed encoders and lookup
    /// texels), which the guarantee says never change.
    IntegerOutputs,
    /// The decoders, whose proven bounds the report holds them to.
    Decoders,
}

impl Functions {
    fn take(self, role: Role) -> bool {
        match self {
            Functions::All => true,
            Functions::IntegerOutputs => integer_output(role),
            Functions::Decoders => matches!(role, Role::Decode | Role::DecodeFloat),
        }
    }
}

impl Default for Options {
    /// Three seeds and both worst-case ends over 2^14 items per function: a few seconds
    /// per spec.
    fn default() -> Options {
        Options {
            seeds: vec![1, 2, 3],
            worst_ends: true,
            sites: Vec::new(),
            sample: Some(1 << 14),
            functions: Functions::All,
        }
    }
}

impl Options {
    /// What `verify --portable` runs: [`Options::default`] and three per-site seeds.
    pub fn cli() -> Options {
        Options {
            sites: vec![1, 2, 3],
            ..Options::default()
        }
    }
    /// The modes each class runs in.
    pub fn modes(&self) -> Vec<Mode> {
        let mut m: Vec<Mode> = self.seeds.iter().map(|&s| Mode::Seeded(s)).collect();
        if self.worst_ends {
            m.extend([Mode::Lowest, Mode::Highest, Mode::Last]);
        }
        m.extend(self.sites.iter().map(|&s| Mode::Site(s)));
        m
    }
}

/// What `verify --portable` measures: each class alone, and
/// [`Classes::WITHOUT_NO_CONTRACTION`] together.
pub fn cli_classes() -> Vec<Classes> {
    let mut c: Vec<Classes> = Class::ALL.map(Into::into).to_vec();
    c.push(Classes::WITHOUT_NO_CONTRACTION);
    c
}

/// One changed item: its input, the reference output and the deviant one.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Example {
    pub mode: Mode,
    pub input: Vec<u32>,
    pub reference: Vec<u32>,
    pub deviant: Vec<u32>,
}

/// One function under one class, over every mode.
#[derive(Clone, Debug)]
pub struct Row {
    /// The spec id.
    pub spec: String,
    /// The function's local name (`encode`, `decode_float`, ...).
    pub function: &'static str,
    pub role: Role,
    pub class: Classes,
    /// Items evaluated (in each mode).
    pub items: usize,
    /// Items whose output bits changed in at least one mode.
    pub changed: usize,
    /// Changed items per mode, in [`PortabilityReport::modes`] order.
    pub by_mode: Vec<usize>,
    /// Float outputs: the largest distance in ULP over all lanes, items and modes (a
    /// sign-of-zero change is 0 ULP; `u64::MAX` when a NaN appeared or vanished). `None`
    /// for packed codes, where any change is a different code.
    pub max_ulp: Option<u64>,
    /// Decoders: the largest `|deviant − reference|` of an output component, in units of
    /// [`UNIT`] (`2^-24`; infinite when a NaN appeared or vanished).
    pub max_dev: Option<f64>,
    /// Decoders: the bound [`crate::measure::decode_bound`] proves for every code and every
    /// guaranteed class at once, in units of [`UNIT`].
    pub bound: Option<f64>,
    /// Decoders: the box of codes (an inclusive range per field) where the bound is
    /// attained.
    pub bound_at: Option<Vec<(i64, i64)>>,
    /// The first changed item.
    pub example: Option<Example>,
    /// Whether the function's doc comment promises the guarantee: every decoder (held to
    /// its bound) and lookup texel, and every packed encoder but those it calls not
    /// portable (the lean tier, `guarantee=ieee`), whose changes are measured, not failures.
    pub promised: bool,
}

impl Row {
    /// A packed encoder whose codes changed under a class the portability guarantee
    /// covers ([`Class::guaranteed`]), or a decoder that moved further than its proven
    /// bound under one (which would be a flaw in the proof).
    pub fn fails(&self) -> bool {
        self.class.guaranteed()
            && (integer_output(self.role) && self.promised && self.changed > 0
                || self.exceeds_bound())
    }
    /// A decoder output moved further than the proven bound.
    pub fn exceeds_bound(&self) -> bool {
        matches!((self.max_dev, self.bound), (Some(d), Some(b)) if d > b)
    }
}

/// The result of [`run`].
#[derive(Clone, Debug)]
pub struct PortabilityReport {
    pub classes: Vec<Classes>,
    pub modes: Vec<Mode>,
    /// Per spec, function and class, in that order.
    pub rows: Vec<Row>,
}

/// Whether `role` returns integers that must not change under any class: packed codes,
/// and the lookup-table texels an encoder or decoder reads (another texel is another
/// code).
pub fn integer_output(role: Role) -> bool {
    matches!(role, Role::Encode | Role::LutTexel)
}

/// Whether outputs of `role` are floats.
fn float_output(role: Role) -> bool {
    !integer_output(role)
}

/// Distance in ULP between two f32 bit patterns; `u64::MAX` when exactly one is NaN.
pub fn ulp_distance(a: u32, b: u32) -> u64 {
    let nan = |x: u32| x & 0x7fff_ffff > 0x7f80_0000;
    if nan(a) || nan(b) {
        return if nan(a) && nan(b) { 0 } else { u64::MAX };
    }
    let line = |x: u32| {
        let m = i64::from(x & 0x7fff_ffff);
        if x >> 31 == 1 { -m } else { m }
    };
    (line(a) - line(b)).unsigned_abs()
}

/// `|a − b|` of two f32 bit patterns in units of [`UNIT`]; infinite when exactly one is
/// NaN.
fn abs_units(a: u32, b: u32) -> f64 {
    let (a, b) = (f32::from_bits(a), f32::from_bits(b));
    match (a.is_nan(), b.is_nan()) {
        (true, true) => 0.0,
        (false, false) => (f64::from(a) - f64::from(b)).abs() / UNIT,
        _ => f64::INFINITY,
    }
}

/// Indices of the items evaluated: all, or every edge vector of an encoder plus `n`
/// evenly spread others.
fn sample(inputs: &Inputs, items: usize, n: Option<usize>) -> Vec<usize> {
    let Some(n) = n else {
        return (0..items).collect();
    };
    let first = match inputs {
        Inputs::Vectors | Inputs::VectorsWith(_) => edge_vectors().len().min(items),
        _ => 0,
    };
    let rest = items - first;
    let mut out: Vec<usize> = (0..first).collect();
    if rest <= n {
        out.extend(first..items);
    } else {
        out.extend((0..n).map(|k| first + k * rest / n));
    }
    out
}

/// Items of one function per part of its measurement: parts of about this many items,
/// from every function, are what the cores take in turn, so that a precise search, which
/// costs thousands of deviant operations per item, is spread over every core rather than
/// left to one at the end.
const PART_ITEMS: usize = 512;

/// What every part of one function's measurement reads: the sampled items' words, their
/// indices among the verify inputs (which seed their deviations), and a decoder's bound.
struct Prepared {
    input: Vec<u32>,
    index: Vec<usize>,
    proven: Option<Bound>,
}

fn prepare(module: &Module, f: &Function, sample_n: Option<usize>) -> Prepared {
    let iw = f.in_words;
    let all = generate(&f.inputs, iw);
    let index = sample(&f.inputs, all.len() / iw, sample_n);
    let input = index
        .iter()
        .flat_map(|&i| &all[i * iw..][..iw])
        .copied()
        .collect();
    Prepared {
        input,
        index,
        proven: crate::measure::decode_bound::cached(module, f),
    }
}

/// What one class did to a run of items, over every mode.
struct Part {
    changed: usize,
    by_mode: Vec<usize>,
    max_ulp: Option<u64>,
    max_dev: Option<f64>,
    /// The run's first changed item in mode order, then item order, with its mode's index.
    example: Option<(usize, Example)>,
}

/// The items `items` of a function ([`Prepared`]) under each class in every mode.
fn measure_part(
    f: &Function,
    p: &Prepared,
    classes: &[Classes],
    modes: &[Mode],
    items: Range<usize>,
) -> Vec<Part> {
    let (iw, ow) = (f.in_words, f.out_words);
    let n = items.len();
    let input = &p.input[items.start * iw..items.end * iw];
    let index = &p.index[items];
    let mut reference = vec![0u32; n * ow];
    for k in 0..n {
        (f.eval)(&input[k * iw..][..iw], &mut reference[k * ow..][..ow]);
    }
    let mut out = vec![0u32; ow];
    let bound = p.proven.as_ref().map(|b| b.units);
    classes
        .iter()
        .map(|&class| {
            let mut changed = vec![false; n];
            let mut part = Part {
                changed: 0,
                by_mode: Vec::new(),
                max_ulp: float_output(f.role).then_some(0u64),
                max_dev: bound.map(|_| 0f64),
                example: None,
            };
            // The first mode's outputs, and which items it computed without a choice: those
            // come out the same in every mode ([`item_chose`]) and are not evaluated again.
            let mut first = vec![0u32; n * ow];
            let mut forced = vec![false; n];
            for (m, &mode) in modes.iter().enumerate() {
                let mut count = 0;
                with(
                    Some(Deviation {
                        classes: class,
                        mode,
                    }),
                    || {
                        for k in 0..n {
                            let inp = &input[k * iw..][..iw];
                            let kept = &mut first[k * ow..][..ow];
                            if m > 0 && forced[k] {
                                out.copy_from_slice(kept);
                            } else {
                                begin_item(index[k] as u64);
                                (f.eval_dev)(inp, &mut out);
                                if m == 0 {
                                    kept.copy_from_slice(&out);
                                    forced[k] = !item_chose();
                                }
                            }
                            let r = &reference[k * ow..][..ow];
                            if out != r {
                                count += 1;
                                changed[k] = true;
                                if let Some(u) = &mut part.max_ulp {
                                    let d = r.iter().zip(&out).map(|(&a, &b)| ulp_distance(a, b));
                                    *u = d.fold(*u, u64::max);
                                }
                                if let Some(d) = &mut part.max_dev {
                                    *d = r
                                        .iter()
                                        .zip(&out)
                                        .map(|(&a, &b)| abs_units(a, b))
                                        .fold(*d, f64::max);
                                }
                                part.example.get_or_insert_with(|| {
                                    let example = Example {
                                        mode,
                                        input: inp.to_vec(),
                                        reference: r.to_vec(),
                                        deviant: out.clone(),
                                    };
                                    (m, example)
                                });
                            }
                        }
                    },
                );
                part.by_mode.push(count);
            }
            part.changed = changed.iter().filter(|&&c| c).count();
            part
        })
        .collect()
}

/// One function's row per class: its parts ([`measure_part`], in item order) summed, as
/// one pass over every item would have counted them.
fn merge(f: &Function, p: &Prepared, classes: &[Classes], parts: &[&Vec<Part>]) -> Vec<Row> {
    classes
        .iter()
        .enumerate()
        .map(|(c, &class)| {
            let of_class = || parts.iter().map(move |p| &p[c]);
            let mut by_mode = Vec::new();
            for part in of_class() {
                by_mode.resize(part.by_mode.len(), 0);
                for (sum, n) in by_mode.iter_mut().zip(&part.by_mode) {
                    *sum += n;
                }
            }
            // The earliest mode's first changed item; the earliest part's within a mode.
            let example = of_class()
                .filter_map(|p| p.example.as_ref())
                .reduce(|a, b| if b.0 < a.0 { b } else { a })
                .map(|e| e.1.clone());
            Row {
                spec: String::new(),
                function: f.name,
                role: f.role,
                class,
                items: p.index.len(),
                changed: of_class().map(|p| p.changed).sum(),
                by_mode,
                max_ulp: of_class().filter_map(|p| p.max_ulp).reduce(u64::max),
                max_dev: of_class().filter_map(|p| p.max_dev).reduce(f64::max),
                bound: p.proven.as_ref().map(|b| b.units),
                bound_at: p.proven.as_ref().map(|b| b.at.clone()),
                example,
                promised: false,
            }
        })
        .collect()
}

/// Runs every function of every spec under each class in each mode of `opts`.
pub fn run(specs: &[Spec], classes: &[Classes], opts: &Options) -> PortabilityReport {
    let modes = opts.modes();
    let emitted: Vec<Arc<Emitted>> = specs.iter().map(Spec::emitted).collect();
    // A function with the code and inputs of an earlier one ([`first_with_same_code`]: a
    // precise spec's decoders are its fast spec's) deviates alike item by item: it is
    // measured once and its rows repeated under its own name.
    let same = first_with_same_code(&emitted);
    let mut jobs: Vec<(&Module, &Function, bool)> = Vec::new();
    let mut job_of: HashMap<(usize, usize), usize> = HashMap::new();
    let mut order: Vec<(String, &Function, usize)> = Vec::new();
    for (i, (spec, e)) in specs.iter().zip(&emitted).enumerate() {
        for (j, f) in e.functions.iter().enumerate() {
            if !opts.functions.take(f.role) {
                continue;
            }
            let promised = f.role != Role::Encode || e.portable_encoder;
            let job = match same[i][j] {
                Some(first) => job_of[&first],
                None => {
                    jobs.push((&e.module, f, promised));
                    job_of.insert((i, j), jobs.len() - 1);
                    jobs.len() - 1
                }
            };
            order.push((spec.id(), f, job));
        }
    }
    // On every core, a function at a time and then a part at a time: each item's
    // deviations are seeded by the item alone (`begin_item`), so the rows are the same as
    // one pass over every item, in the same order.
    let prepared =
        crate::support::par::map(&jobs, |(module, f, _)| prepare(module, f, opts.sample));
    let parts: Vec<(usize, Range<usize>)> = prepared
        .iter()
        .enumerate()
        .flat_map(|(job, p)| {
            let n = p.index.len();
            let part = move |k: usize| (job, k * PART_ITEMS..n.min((k + 1) * PART_ITEMS));
            (0..n.div_ceil(PART_ITEMS)).map(part)
        })
        .collect();
    let measured = crate::support::par::map(&parts, |(job, items)| {
        measure_part(
            jobs[*job].1,
            &prepared[*job],
            classes,
            &modes,
            items.clone(),
        )
    });
    let mut of_job: Vec<Vec<&Vec<Part>>> = vec![Vec::new(); jobs.len()];
    for ((job, _), m) in parts.iter().zip(&measured) {
        of_job[*job].push(m);
    }
    let rows: Vec<Vec<Row>> = jobs
        .iter()
        .zip(&prepared)
        .zip(&of_job)
        .map(|((&(_, f, promised), p), parts)| {
            let mut rows = merge(f, p, classes, parts);
            rows.iter_mut().for_each(|r| r.promised = promised);
            rows
        })
        .collect();
    let rows = order
        .into_iter()
        .flat_map(|(id, f, job)| {
            rows[job].iter().map(move |r| Row {
                spec: id.clone(),
                function: f.name,
                role: f.role,
                ..r.clone()
            })
        })
        .collect();
    PortabilityReport {
        classes: classes.to_vec(),
        modes,
        rows,
    }
}

/// A table cell: `.` unchanged; changed items and, for floats, the max ULP; `!` marks a
/// packed code that changed under a guaranteed class, `x` one that changed under a class
/// outside the guarantee, `~` one of an encoder documented not portable.
fn cell(r: &Row) -> String {
    match (r.changed, r.max_ulp) {
        (0, _) => ".".into(),
        (n, None) if !r.promised => format!("{n}~"),
        (n, None) if r.class.guaranteed() => format!("{n}!"),
        (n, None) => format!("{n}x"),
        (n, Some(u64::MAX)) => format!("{n}/NaN"),
        (n, Some(u)) => format!("{n}/{u}u"),
    }
}

/// What [`cell`]'s forms and the last column mean, printed under the table: `229x` or
/// `14073/859030801u` is unreadable to someone who has not read this file.
pub fn legend() -> String {
    let names = |covered: bool| {
        let classes = Class::ALL.iter().filter(|c| c.guaranteed() == covered);
        classes.map(|c| c.name()).collect::<Vec<_>>().join(", ")
    };
    format!(
        "\
cells:  .       no output changed under the class
        N/Ku    N float outputs changed, by at most K units in the last place
                (0u: only the sign of a zero)
        N/NaN   N float outputs changed, a NaN appearing or vanishing among them
        N!      N packed codes changed under a class the guarantee covers: a failure
                (covered: {})
        Nx      N packed codes changed under a class it does not cover
                (not covered: {})
        N~      N packed codes changed of an encoder its doc comment calls not
                portable (the lean tier, guarantee=ieee): measured, not a failure
proven: ≤B (seen S): a decoder's proven bound on how far the covered classes move an
        output component, and the largest move seen, both in units of 2^-24
",
        names(true),
        names(false)
    )
}

fn json_str(s: &str) -> String {
    let mut o = String::from("\"");
    for ch in s.chars() {
        match ch {
            '"' => o.push_str("\\\""),
            '\\' => o.push_str("\\\\"),
            c if (c as u32) < 0x20 => {
                let _ = write!(o, "\\u{:04x}", c as u32);
            }
            c => o.push(c),
        }
    }
    o.push('"');
    o
}

fn json_words(w: &[u32]) -> String {
    let items: Vec<String> = w.iter().map(|x| x.to_string()).collect();
    format!("[{}]", items.join(","))
}

impl PortabilityReport {
    /// True when no packed encoder changed its code under any guaranteed class and mode.
    pub fn packed_encoders_portable(&self) -> bool {
        !self
            .rows
            .iter()
            .any(|r| integer_output(r.role) && r.fails())
    }
    /// True when, besides, every decoder stayed within its proven bound: what `verify
    /// --portable` exits 0 on.
    pub fn guarantees_hold(&self) -> bool {
        !self.rows.iter().any(Row::fails)
    }

    /// The rows whose outputs changed.
    pub fn changed(&self) -> impl Iterator<Item = &Row> {
        self.rows.iter().filter(|r| r.changed > 0)
    }

    /// One line per spec and function, one column per class: `.` when no output changed,
    /// `N/Ku` when N items changed by at most K ULP (`0u`: only the sign of a zero), `N!`
    /// when N packed codes changed under a guaranteed class, `Nx` under excess precision.
    pub fn table(&self) -> String {
        let mut t = String::new();
        let modes: Vec<String> = self.modes.iter().map(|m| m.name()).collect();
        let _ = writeln!(t, "modes: {}", modes.join(", "));
        let _ = write!(t, "{:<28} {:<34} {:>7}", "spec", "function", "items");
        // A column is as wide as its widest cell (`16318/877203419u` is wider than 12), so
        // that no row shifts the columns after it.
        let groups = || self.rows.chunks(self.classes.len().max(1));
        let widths: Vec<usize> = (0..self.classes.len())
            .map(|i| {
                let cells = groups().filter_map(|g| g.get(i)).map(|r| cell(r).len());
                cells.fold(self.classes[i].name().len().max(12), usize::max)
            })
            .collect();
        for (c, w) in self.classes.iter().zip(&widths) {
            let _ = write!(t, " {:>w$}", c.name());
        }
        t.push_str("  proven (2^-24)");
        t.push('\n');
        for group in groups() {
            let r = &group[0];
            let _ = write!(
                t,
                "{:<28} {:<34} {:>7}",
                r.spec,
                format!("{} ({:?})", r.function, r.role),
                r.items
            );
            for (r, w) in group.iter().zip(&widths) {
                let _ = write!(t, " {:>w$}", cell(r));
            }
            if let Some(b) = r.bound {
                let seen = group
                    .iter()
                    .filter(|r| r.class.guaranteed())
                    .filter_map(|r| r.max_dev)
                    .fold(0f64, f64::max);
                let _ = write!(t, "  ≤{b} (seen {seen:.2})");
            }
            t.push('\n');
        }
        let fails: Vec<String> = self
            .rows
            .iter()
            .filter(|r| r.fails())
            .map(|r| match (r.role, r.max_dev, r.bound) {
                (role, ..) if integer_output(role) => {
                    format!("{} {} under {}", r.spec, r.function, r.class.name())
                }
                (_, d, b) => format!(
                    "{} {} under {}: moved {:.2}·2^-24, beyond its proven bound {}·2^-24",
                    r.spec,
                    r.function,
                    r.class.name(),
                    d.unwrap_or(0.0),
                    b.unwrap_or(0.0)
                ),
            })
            .collect();
        t.push_str(&legend());
        if fails.is_empty() {
            t.push_str("packed encoders: portable under every guaranteed class (div, sqrt, fma, denorm, zero); decoders: within their proven bounds\n");
        } else {
            let _ = writeln!(t, "failures: {}", fails.len());
            for f in fails {
                let _ = writeln!(t, "  {f}");
            }
        }
        t
    }

    /// The report as JSON: classes, modes, `packed_encoders_portable`, `guarantees_hold`
    /// and every row (`max_ulp` is `null` for packed codes and `"NaN"` when a NaN appeared
    /// or vanished; decoders add `max_dev`, `bound` and `bound_at`, the box of codes where
    /// the bound is attained, one `[lo, hi]` per field).
    pub fn json(&self) -> String {
        let classes: Vec<String> = self.classes.iter().map(|c| json_str(&c.name())).collect();
        let modes: Vec<String> = self.modes.iter().map(|m| json_str(&m.name())).collect();
        let rows: Vec<String> = self
            .rows
            .iter()
            .map(|r| {
                let max_ulp = match r.max_ulp {
                    None => "null".to_string(),
                    Some(u64::MAX) => "\"NaN\"".to_string(),
                    Some(u) => u.to_string(),
                };
                let by_mode: Vec<String> = r.by_mode.iter().map(|n| n.to_string()).collect();
                let units = |x: Option<f64>| match x {
                    None => "null".to_string(),
                    Some(x) if x.is_finite() => format!("{x}"),
                    Some(_) => "\"inf\"".to_string(),
                };
                let example = match &r.example {
                    None => "null".to_string(),
                    Some(e) => format!(
                        "{{\"mode\":{},\"input\":{},\"reference\":{},\"deviant\":{}}}",
                        json_str(&e.mode.name()),
                        json_words(&e.input),
                        json_words(&e.reference),
                        json_words(&e.deviant)
                    ),
                };
                format!(
                    "{{\"spec\":{},\"function\":{},\"role\":{},\"class\":{},\"items\":{},\"changed\":{},\"by_mode\":[{}],\"max_ulp\":{},\"max_dev\":{},\"bound\":{},\"bound_at\":{},\"fails\":{},\"promised\":{},\"example\":{}}}",
                    json_str(&r.spec),
                    json_str(r.function),
                    json_str(&format!("{:?}", r.role)),
                    json_str(&r.class.name()),
                    r.items,
                    r.changed,
                    by_mode.join(","),
                    max_ulp,
                    units(r.max_dev),
                    units(r.bound),
                    r.bound_at.as_ref().map_or("null".to_string(), |at| {
                        let boxes: Vec<String> =
                            at.iter().map(|(a, b)| format!("[{a},{b}]")).collect();
                        format!("[{}]", boxes.join(","))
                    }),
                    r.fails(),
                    r.promised,
                    example
                )
            })
            .collect();
        format!(
            "{{\"classes\":[{}],\"modes\":[{}],\"packed_encoders_portable\":{},\"guarantees_hold\":{},\"rows\":[\n{}\n]}}\n",
            classes.join(","),
            modes.join(","),
            self.packed_encoders_portable(),
            self.guarantees_hold(),
            rows.join(",\n")
        )
    }
}
