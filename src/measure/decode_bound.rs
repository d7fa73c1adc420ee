//! Proven bounds on how far a decoder's output can move on a conformant implementation.
//!
//! `verify --portable` samples the guaranteed deviations one class at a time; this proves
//! a bound for all guaranteed classes at once (`div`, `sqrt`, `fma`, `denorm`, `zero`, see
//! [`crate::model::enclosure`]) over *every* code. The decoder runs on [`Encl`] over boxes
//! of codes; each box yields an enclosure of every reference output and every deviation
//! within it. The boxes are refined where the bound is largest (branch and bound) until the
//! largest box bound, rounded up to whole units of `2^-24`, is what a single code already
//! reaches, or an evaluation budget is spent: either way the stated bound covers every box,
//! so every code.

use crate::codecs::Spec;
use crate::codecs::functions::decode_boxes::float_code_range;
use crate::codecs::functions::function::Inputs;
use crate::codecs::functions::function::{Enclose, Function, Role};
use crate::codecs::toolkit::quant::Quant;
use crate::measure::figures::{Bound, UNIT};
use crate::model::enclosure::Encl;
use crate::model::trace::Module;
use crate::support::memo::Memo;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Box evaluations allowed per function before the bound is stated as it stands, with
/// what a single code reaches beside it ([`Bound::reached`]): sound, but not shown tight.
pub const BUDGET: usize = 600_000;

struct Boxed {
    dev: f64,
    r: Vec<(i64, i64)>,
}
impl PartialEq for Boxed {
    fn eq(&self, o: &Self) -> bool {
        self.dev.total_cmp(&o.dev) == Ordering::Equal
    }
}
impl Eq for Boxed {}
impl PartialOrd for Boxed {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Boxed {
    fn cmp(&self, o: &Self) -> Ordering {
        self.dev.total_cmp(&o.dev)
    }
}

fn deviation(out: &[Encl]) -> f64 {
    out.iter().map(|e| e.deviation()).fold(0.0, f64::max)
}

fn single(r: &[(i64, i64)]) -> bool {
    r.iter().all(|&(a, b)| a == b)
}

/// Halves `r` along side `k`.
fn split(r: &[(i64, i64)], k: usize) -> [Vec<(i64, i64)>; 2] {
    let (a, b) = r[k];
    let mid = a + (b - a) / 2;
    let mut lo = r.to_vec();
    let mut hi = r.to_vec();
    lo[k].1 = mid;
    hi[k].0 = mid + 1;
    [lo, hi]
}

/// Divides `r` into about `n` boxes per side.
fn grid(r: &[(i64, i64)], n: i64) -> Vec<Vec<(i64, i64)>> {
    let mut out = vec![vec![]];
    for &(a, b) in r {
        let step = ((b - a + 1) + n - 1) / n;
        let parts: Vec<(i64, i64)> = (0..n)
            .map(|k| (a + k * step, (a + (k + 1) * step - 1).min(b)))
            .filter(|p| p.0 <= p.1)
            .collect();
        out = out
            .into_iter()
            .flat_map(|prefix| {
                parts.iter().map(move |&p| {
                    let mut v = prefix.clone();
                    v.push(p);
                    v
                })
            })
            .collect();
    }
    out
}

/// Proves a bound for `f` over every code in `ranges`.
pub fn prove(ranges: &[(i64, i64)], f: &Enclose) -> Bound {
    let evaluations = std::cell::Cell::new(0);
    let eval = |r: &[(i64, i64)]| {
        evaluations.set(evaluations.get() + 1);
        deviation(&(f.eval)(r))
    };
    let mut heap = BinaryHeap::new();
    let mut best_single = 0f64;
    // A field the decoder does not read is proven at its lowest value: the enclosure
    // cannot depend on it.
    let ranges: Vec<(i64, i64)> = ranges
        .iter()
        .enumerate()
        .map(|(k, &(a, b))| {
            if let Some(&(_, v)) = f.fixed.iter().find(|x| x.0 == k) {
                (v, v)
            } else if f.unread.contains(&k) {
                (a, a)
            } else {
                (a, b)
            }
        })
        .collect();
    let per_side = match ranges.iter().filter(|r| r.0 < r.1).count() {
        1 => 4096,
        2 => 64,
        _ => 16,
    };
    let mut boxes = grid(&ranges, per_side);
    if let Some(k) = f.whole_field {
        boxes = boxes
            .into_iter()
            .flat_map(|r| {
                (r[k].0..=r[k].1).map(move |v| {
                    let mut one = r.clone();
                    one[k] = (v, v);
                    one
                })
            })
            .collect();
    }
    for r in boxes {
        let centre: Vec<(i64, i64)> = r
            .iter()
            .map(|&(a, b)| (a + (b - a) / 2, a + (b - a) / 2))
            .collect();
        best_single = best_single.max(eval(&centre));
        let dev = eval(&r);
        heap.push(Boxed { dev, r });
    }
    let units = |d: f64| (d / UNIT).ceil();
    loop {
        let top = heap.pop().expect("boxes remain");
        if single(&top.r) {
            best_single = best_single.max(top.dev);
        }
        if single(&top.r)
            || units(top.dev) <= units(best_single)
            || evaluations.get() >= f.budget.unwrap_or(BUDGET)
        {
            return Bound {
                units: units(top.dev),
                at: top.r,
                reached: units(best_single),
            };
        }
        // Halve the side whose halves bound lowest: fields do not matter equally (a
        // bit field may carry the high bits of one parameter and the low bits of another).
        // On a tie (both unbounded, say) the side with the lower other half, then the
        // widest side: what is unbounded (an f16 field's infinities and NaNs) is isolated
        // rather than a narrow side halved again and again.
        let key = |h: &[Boxed; 2], k: usize| {
            let (lo, hi) = (h[0].dev.min(h[1].dev), h[0].dev.max(h[1].dev));
            (hi, lo, -((top.r[k].1 - top.r[k].0) as f64))
        };
        let halves = (0..top.r.len())
            .filter(|&k| top.r[k].0 < top.r[k].1)
            .map(|k| (k, split(&top.r, k).map(|r| Boxed { dev: eval(&r), r })))
            .min_by(|(i, a), (j, b)| {
                let ((a0, a1, a2), (b0, b1, b2)) = (key(a, *i), key(b, *j));
                a0.total_cmp(&b0)
                    .then(a1.total_cmp(&b1))
                    .then(a2.total_cmp(&b2))
            })
            .map(|(_, h)| h)
            .expect("a box of more than one code has a side to halve");
        for b in halves {
            if single(&b.r) {
                best_single = best_single.max(b.dev);
            }
            heap.push(b);
        }
    }
}

/// The codes a decoder function takes, one range per field.
fn code_ranges(f: &Function) -> Option<Vec<(i64, i64)>> {
    let q = match (&f.inputs, f.role) {
        (Inputs::FloatCodes(q), Role::DecodeFloat) => {
            return Some(q.iter().map(|q| float_code_range(*q)).collect());
        }
        (Inputs::Codes(q), Role::Decode) => q,
        _ => return None,
    };
    Some(q.iter().map(|q: &Quant| (0, i64::from(q.mask()))).collect())
}

/// The proven bound of a decoder function (`None` for other functions).
pub fn of(f: &Function) -> Option<Bound> {
    let e = f.enclose.as_ref()?;
    Some(prove(&e.parts.clone().or_else(|| code_ranges(f))?, e))
}

/// Every bound this process knows, by [`key`].
static CACHE: Memo<u128, Option<Bound>> = Memo::new();

/// What identifies a decoder's bound: its trace and its callees' in `module`, and the
/// codes it takes, hashed to 128 bits (two of std's SipHashes with fixed keys, over the
/// text with different prefixes: no two of the catalogue's few hundred decoders meet by
/// chance). The hash is the same in every run of one build; a store that outlives the
/// process ([`export`]) must be tied to the build.
fn key(module: &Module, f: &Function) -> u128 {
    use std::hash::{Hash, Hasher};
    let text = format!(
        "{:?} {:?} {:?} {:?} {}",
        code_ranges(f),
        f.enclose.as_ref().map(|e| &e.parts),
        f.enclose.as_ref().map(|e| e.whole_field),
        f.enclose.as_ref().map(|e| &e.fixed),
        module.identity(f.name),
    );
    let half = |prefix: u8| {
        let mut h = std::collections::hash_map::DefaultHasher::new();
        prefix.hash(&mut h);
        text.hash(&mut h);
        h.finish()
    };
    u128::from(half(0)) << 64 | u128::from(half(1))
}

/// [`of`], computed once per process for each distinct decoder (the doc comments of
/// every include state it). A precise spec's decoders are its fast spec's, so each is
/// proven once.
pub fn cached(module: &Module, f: &Function) -> Option<Bound> {
    code_ranges(f)?;
    let key = key(module, f);
    if let Some(b) = CACHE.get(&key) {
        return b;
    }
    let b = of(f);
    CACHE.extend([(key, b.clone())]);
    b
}

/// Every bound this process knows, by its key: what a store that outlives the process
/// saves. Keys are only meaningful to the same build (see [`key`]).
pub fn export() -> Vec<(u128, Option<Bound>)> {
    CACHE.export()
}

/// Takes bounds an earlier run of the same build proved ([`export`]) as proven.
pub fn import(bounds: impl IntoIterator<Item = (u128, Option<Bound>)>) {
    CACHE.extend(bounds);
}

/// Proves the bound of every decoder of `specs` not yet [`cached`], on every core.
pub fn prove_all(specs: &[Spec]) {
    let mut todo = std::collections::BTreeMap::new();
    for spec in specs {
        let e = spec.emitted();
        for f in e.functions.iter().filter(|f| f.enclose.is_some()).cloned() {
            let key = key(&e.module, &f);
            if !CACHE.contains(&key) {
                todo.insert(key, f);
            }
        }
    }
    let todo: Vec<_> = todo.into_iter().collect();
    let bounds = crate::support::par::map(&todo, |(_, f)| of(f));
    CACHE.extend(todo.into_iter().map(|(key, _)| key).zip(bounds));
}
