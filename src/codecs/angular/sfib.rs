//! Spherical Fibonacci point sets (Keinert et al. 2015, "Spherical Fibonacci Mapping"),
//! beyond the survey: the code is the index `i` of one of `n = 2^b` points spread over
//! the sphere along a spiral, so every code is a point and no code is wasted on a square
//! that the sphere does not fill.
//!
//! Point `i` has `z = 1 - (i + ε)·s` with `s = 2/(n - 1 + 2ε)` and longitude
//! `φ = 2π·frac(i·(Φ - 1))` (Φ the golden ratio). The offset `ε` of the first and last
//! point from the poles is ours, chosen by a one-off measurement that the tests do not
//! repeat: the spiral leaves its largest holes in the polar caps, and over a dense grid
//! of directions within 3° of a pole the farthest one from its nearest point (16 bits)
//! was 0.610° with Keinert's `ε = ½` and 0.580° with `ε = ¼`, the least of any `ε` we
//! tried (0 to 0.72; elsewhere the largest distance was about 0.558°).
//!
//! Layout: the index, first field lowest — a `B`-bit code stores `i`'s low `B/2` bits in
//! the first field and its high `B/2` bits in the second (both unorm), so the packed word
//! is `i` itself.
//!
//! Decoding evaluates `frac(i·(Φ - 1))` in fixed point, with `Φ - 1` to 64 bits
//! (`2^64/Φ`, [`GOLDEN`]) and 32-bit integer products of 16-bit halves: the fraction is
//! exact to `2^-32` turns for every index before it is rounded to the 24 bits a float
//! holds (`2^-25` turns), where an f32 product would have no fraction left above `2^24`
//! points. `1 - |z|` is formed from the distance in index to the nearer pole, where it is
//! small, so points near the poles keep their precision.
//!
//! Encoding is Keinert's inverse mapping: near the query, the points form a lattice in
//! `(φ, z)` spanned by the index steps `F_k` and `F_{k+1}` (consecutive Fibonacci numbers,
//! `k` from the query's `1 - z²`). Queries in the southern hemisphere are mirrored onto
//! the northern one (point `n - 1 - i` is point `i` with `z ↦ -z` and `φ ↦ M - φ`,
//! [`Sfib::mirror_turn`]), so that `z` is always measured from the nearer pole, and
//! candidate indices before the pole are replaced by the real points `-1 - i`. Keinert
//! takes the four corners of the query's lattice cell as candidates; here the nine
//! lattice points around the nearest one, so that the cell's corners stay among them
//! where an implementation's rounding moves the query across a cell's edge. The basis
//! and the hemisphere are chosen from the input's fixed-point direction, and the winner is
//! decided in fixed point ([`Sfib::fixed_point`], squared distances summed exactly in
//! integers and rounded once), so the packed code is portable like the other codecs'.
//! `tests/families/sfib.rs` checks the choice against a brute-force search over every point that
//! could be nearer, both in the fixed-point measure (exactly) and in the decoder's
//! floats (to `2^-18`).

use crate::model::num::helper;
use crate::codecs::core::codec::Codec;
use crate::codecs::core::info::Domain;
use crate::codecs::core::info::{Info, Sizes, FloatForm};
use crate::codecs::core::codec_family::CodecFamily;
use crate::codecs::core::pipeline::codec_functions;
use crate::codecs::toolkit::index::Halves;
use crate::codecs::toolkit::quant::Quants;
use crate::codecs::core::spec::SpecError;
use crate::codecs::toolkit::exact::{canonical_or_z, fixed_length2, fixed_root, float_of, root, sum_of_squares};
use crate::codecs::toolkit::fixed_decode::{BITS, ONE, fixed_target};
use crate::codecs::toolkit::fixed_trig::{self, FINE};
use crate::codecs::toolkit::trig::{atan2_pi, sincos_pi};
use crate::model::{Bool, Float, Lane, Uint, V2, V3};
use std::sync::OnceLock;

pub static FAMILY: CodecFamily<Sfib> = CodecFamily::new(
    Info {
        name: "sfib",
        title: "spherical Fibonacci point set, the code is the point's index",
        sizes: Sizes::Total(&[16, 24, 32]),
        domain: Some(Domain::Sphere),
        source: "Keinert et al. 2015 (Spherical Fibonacci Mapping), beyond the survey",
        edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z (index 0); the encoder returns the nearest point to within 2^-18 (checked by brute force)",
        decode_note: "every code decodes to a unit vector to within the trig approximations' error (about 2.5e-7)",
        float_form: FloatForm::Unfilterable {
            why: FloatForm::INDEX_SPLIT,
            seam: "everywhere: neighbouring points have unrelated indices",
        },
        options: &[],
    },
    |bits| Sfib { bits },
    codec_functions,
)
.with_helper_doc(|name| match name {
    "index_direction" => Some(
        "The direction of point `i`: `z` from the index's distance to the nearer pole, \
         `φ = 2π·frac(i·(Φ - 1))` in 64-bit fixed point from 32-bit products."
            .into(),
    ),
    "fixed_point" => Some(
        "Point `i` in fixed point (units of 2^-21), its root decided by comparing squares \
         and every product rounded or floored before a sum: a function of `i` alone, within \
         a few units of the decoder's point."
            .into(),
    ),
    "fixed_sincos_pi" => Some(
        "(sin(π·t), cos(π·t)) in fixed point: `t` and the results in units of 2^-24, every \
         product rounded to a unit before the next sum."
            .into(),
    ),
    "encode_index" => Some(
        "The index of the point nearest the input: the nine lattice points around the \
         input in the local Fibonacci lattice, compared by the squared distance (summed \
         exactly in integers, rounded once) of their fixed-point decodes to the input's \
         fixed-point direction, the lower index on ties, so that no rounding latitude of an \
         implementation can change the code."
            .into(),
    ),
    _ => None,
});

/// `2^64·(Φ - 1) = 2^64/Φ`, rounded down: the longitude step in 64-bit fixed point.
pub const GOLDEN: u64 = 0x9E37_79B9_7F4A_7C15;

/// The offset of the first and last point from the poles, in index steps.
pub const EPSILON: f64 = 0.25;

/// Lattice coordinates are offset by this before conversion, so that they convert as
/// non-negative integers (they stay well inside `±2^22` for every size).
const OFFSET: u32 = 1 << 22;

/// Indices at or past this, formed from lattice coordinates, are negative (two's
/// complement): candidates a few steps beyond the pole.
const NEGATIVE: u32 = 0xC000_0000;

#[derive(Clone, Copy, Debug)]
pub struct Sfib {
    pub bits: u32,
}

impl Sfib {
    /// The codec with the given total bit budget; an invalid size is an error listing
    /// the allowed ones.
    pub fn new(bits: u32) -> Result<Sfib, SpecError> {
        FAMILY.codec(bits)
    }

    /// The number of points, `n = 2^b`.
    pub fn points(&self) -> f64 {
        2f64.powi(self.bits as i32)
    }

    /// `n - 1`: the last index, and the mask of a valid one.
    fn last(&self) -> u32 {
        (((1u64) << self.bits) - 1) as u32
    }

    /// The spacing `s` of the points in `z`.
    pub fn step(&self) -> f64 {
        2.0 / (self.points() - 1.0 + 2.0 * EPSILON)
    }

    /// The lattice bases the encoder chooses from, and the least `1 - z²` of each:
    /// computed once per process and size, since the f32 model's encoder reads them for
    /// every item.
    fn rows(&self) -> &'static [Row] {
        static ROWS: [OnceLock<Vec<Row>>; 33] = [const { OnceLock::new() }; 33];
        ROWS[self.bits as usize].get_or_init(|| self.make_rows())
    }

    fn make_rows(&self) -> Vec<Row> {
        let phi = (1.0 + 5f64.sqrt()) / 2.0;
        let density = self.points() * std::f64::consts::PI * 5f64.sqrt();
        let s = self.step();
        let mut fib = vec![0u64, 1];
        while fib.len() < 64 {
            let next = fib[fib.len() - 1] + fib[fib.len() - 2];
            fib.push(next);
        }
        // The longitude step of `f` index steps, in half turns, wrapped to (-1, 1].
        let dt = |f: u64| {
            let turns = (f as f64 * (phi - 1.0)).fract();
            2.0 * if turns > 0.5 { turns - 1.0 } else { turns }
        };
        (2..)
            .map(|k| {
                let (f0, f1) = (fib[k], fib[k + 1]);
                let (t0, t1) = (dt(f0), dt(f1));
                let (z0, z1) = (-s * f0 as f64, -s * f1 as f64);
                let det = t0 * z1 - t1 * z0;
                Row {
                    least: if k == 2 {
                        0.0
                    } else {
                        phi.powi(2 * k as i32) / density
                    },
                    f: [f0 as u32, f1 as u32],
                    inverse: [z1 / det, -t1 / det, -z0 / det, t0 / det],
                }
            })
            .take_while(|r| r.least <= 1.0)
            .collect()
    }

    /// `2·frac((n-1)·(Φ - 1))` wrapped to `[-1, 1)`: the longitude (in half turns) that
    /// point `n - 1 - i` adds to point `i`'s negated one.
    fn mirror_turn(&self) -> f64 {
        let top = (u64::from(self.last()).wrapping_mul(GOLDEN) >> 32) as f64;
        let t = top / 2f64.powi(31);
        if t >= 1.0 { t - 2.0 } else { t }
    }

    /// Whether point `i` is in the northern half, and its distance in index from the
    /// nearer pole (point `n - 1 - i` is point `i` mirrored).
    #[inline(always)]
    fn pole_distance<U: Uint>(&self, i: U) -> (U::B, U) {
        let north = i.lt(U::c(1 << (self.bits - 1)));
        let k = U::sel(north, i, U::c(self.last()).wrapping_sub(i)).named("k");
        (north, k)
    }

    /// The direction of point `i`.
    #[inline(always)]
    pub fn index_direction<F: Float>(&self, i: F::U) -> V3<F> {
        let c = F::U::c;
        // `1 - |z|` from the distance in index to the nearer pole, exact to rounding even
        // for the points nearest the poles.
        let (north, k) = self.pole_distance(i);
        let s = self.step();
        let fine = ((k & c(255)).to_f() * F::c(s as f32)).named("fine");
        let u = (k.shr(8).to_f() * F::c((256.0 * s) as f32) + (F::c((EPSILON * s) as f32) + fine))
            .named("u");
        let w = F::c(1.0) - u;
        let z = F::sel(north, w, -w);
        let r = (u * (F::c(2.0) - u)).sqrt().named("r");
        // Half turns in [-1, 1): 2^-23 per step of the 24-bit longitude.
        let t = F::c(-1.0) + longitude(i).to_f() * F::c(2f32.powi(-23));
        let sc = helper!(sincos_pi(t)).named("sc");
        V3::new(r * sc.y, r * sc.x, z)
    }

    /// Point `i` in fixed point, units of `2^-21`, as a function of `i` alone: what the
    /// encoder measures candidates by. Every product feeds only a floor, a round, a root
    /// decided by squares ([`fixed_root`]) or another product; `1 - |z|` and `1 + |z|`
    /// are each `(ε + index)·s`, the index converted the same everywhere ([`float_of`]),
    /// so `ρ² = (1 - |z|)(1 + |z|)` keeps its digits at the poles;
    /// `(sin φ, cos φ)` come from [`fixed_trig::sincos_pi`]. Within a few units of
    /// [`Sfib::index_direction`].
    #[inline(always)]
    pub fn fixed_point<F: Float>(&self, i: F::U) -> V3<F> {
        let c = F::U::c;
        let (north, k) = self.pole_distance(i);
        let s = F::c(self.step() as f32);
        let side = { #[inline(always)] |k: F::U| (F::c(EPSILON as f32) + float_of(k)) * s };
        let near = side(k).named("near");
        let far = side(c(self.last()).wrapping_sub(k)).named("far");
        let one = F::c(ONE as f32);
        let rho = fixed_root(near * far * F::c((ONE * ONE) as f32)).named("rho");
        let zm = (one - (near * one).floor()).named("zm");
        let z = F::sel(north, zm, -zm);
        // Half turns in units of 2^-24, in [-2^24, 2^24).
        let t = F::c(-FINE as f32) + longitude(i).to_f() * F::c(2.0);
        let sc = helper!("fixed_sincos_pi" => fixed_trig::sincos_pi(t)).named("sc");
        let scale = F::c((1.0 / FINE) as f32);
        V3::new(
            (rho * sc.y * scale).round(),
            (rho * sc.x * scale).round(),
            z,
        )
    }

    /// The index of the point nearest `v`: Keinert's inverse mapping proposes the
    /// candidates, fixed point decides among them. The candidates come from float
    /// arithmetic that an implementation may round differently (division, roots,
    /// contraction): the nine lattice points around the nearest one (not the four corners
    /// of the cell) contain the corners of the cell the input lies in even where such a
    /// difference moves the input across a cell's edge; the basis and the hemisphere,
    /// which change the candidates wholesale, are chosen from the input's fixed-point
    /// direction ([`fixed_target`]), a function of the input alone. Among the candidates
    /// the nearest to that direction by the squared distance of [`Sfib::fixed_point`]
    /// (summed exactly, [`sum_of_squares`], then rounded once), the lower index on ties.
    #[inline(always)]
    pub fn encode_index<F: Float>(&self, v: V3<F>) -> F::U {
        let c = F::U::c;
        let (w, _) = canonical_or_z(v);
        let l = root(fixed_length2(w));
        let aim = fixed_target(w, l, BITS);
        let u = (w / l).named("u");
        let rho2 = u.xy().length_squared().named("rho2");
        // The basis and the hemisphere from the fixed-point direction: `ρ²` summed exactly.
        let a = aim.map(#[inline(always)] |x| x.abs().to_u());
        let rho2_fixed = (sum_of_squares::<F, 2>([a.x, a.y])
            * F::c((1.0 / (ONE * ONE)) as f32))
        .named("rho2_fixed");
        let south = aim.z.lt(F::c(0.0));
        // Measured from the nearer pole: `|z| - z_0 = ε·s - (1 - |z|)`, with
        // `1 - |z| = ρ²/(1 + |z|)`, which keeps its digits near the pole.
        let below = (rho2 / (F::c(1.0) + u.z.abs())).named("below");
        let dz = (F::c((EPSILON * self.step()) as f32) - below).named("dz");
        let t = helper!(atan2_pi(u.y, u.x)).named("t");
        let t = F::sel(south, F::c(self.mirror_turn() as f32) - t, t).named("tn");
        // The lattice basis for the query's `1 - z²`: the last row whose least value it reaches.
        let rows = self.rows();
        let r0 = &rows[0];
        let mut f = [c(r0.f[0]), c(r0.f[1])];
        let inv0 = { #[inline(always)] |j: usize| F::c(r0.inverse[j] as f32) };
        let mut inv = [inv0(0), inv0(1), inv0(2), inv0(3)];
        for row in &rows[1..] {
            let take = rho2_fixed.ge(F::c(row.least as f32));
            let fj = { #[inline(always)] |j: usize| F::U::sel(take, c(row.f[j]), f[j]) };
            f = [fj(0), fj(1)];
            let invj = { #[inline(always)] |j: usize| F::sel(take, F::c(row.inverse[j] as f32), inv[j]) };
            inv = [invj(0), invj(1), invj(2), invj(3)];
        }
        // The lattice point nearest the input, less one step of each vector, offset to
        // convert as non-negative integers.
        let cell_of = { #[inline(always)] |j: usize| {
            let x = (t * inv[2 * j] + dz * inv[2 * j + 1]).round();
            (F::c((OFFSET - 1) as f32) + x).to_u()
        } };
        let cell = [cell_of(0), cell_of(1)];
        let corner = cell[0]
            .wrapping_mul(f[0])
            .wrapping_add(cell[1].wrapping_mul(f[1]))
            .wrapping_sub((f[0] + f[1]).shl(OFFSET.trailing_zeros()))
            .named("corner");
        let last = c(self.last());
        let mut best: Option<(F, F::U)> = None;
        for b in 0..3 {
            for a in 0..3 {
                let mut i = corner;
                for (j, steps) in [a, b].into_iter().enumerate() {
                    for _ in 0..steps {
                        i = i.wrapping_add(f[j]);
                    }
                }
                // Before the pole: reflect onto the real point `-1 - i`.
                let i = F::U::sel(c(NEGATIVE - 1).lt(i), c(u32::MAX).wrapping_sub(i), i);
                let i = F::U::sel(south, last.wrapping_sub(i), i) & last;
                let p = helper!(self.fixed_point(i));
                let e = (p - aim).map(#[inline(always)] |x| x.abs().to_u());
                let d = sum_of_squares::<F, 3>([e.x, e.y, e.z]).named("d");
                best = Some(match best {
                    None => (d, i),
                    Some((bd, bi)) => {
                        let nearer = d.lt(bd).or(d.eq(bd).and(i.lt(bi)));
                        (F::sel(nearer, d, bd), F::U::sel(nearer, i, bi))
                    }
                });
            }
        }
        best.expect("nine candidates").1
    }

    fn halves(&self) -> Halves {
        Halves { bits: self.bits }
    }
}

/// One lattice basis: used where `1 - z² ≥ least`.
struct Row {
    least: f64,
    /// The index steps `F_k`, `F_{k+1}`.
    f: [u32; 2],
    /// The inverse of the basis `[[Δt₀, Δt₁], [Δz₀, Δz₁]]`, row-major.
    inverse: [f64; 4],
}

/// The longitude `2·frac(i·(Φ - 1))` half turns as a 24-bit code `h`, the angle
/// `h·2^-23 - 1` half turns: half a turn is added in the integer domain and subtracted
/// exactly by the caller, so the angle lands in `[-1, 1)` with no wrapping select (and an
/// interval over many indices stays inside the trigonometry's domain). The fraction is
/// the top word of the 64-bit product `i·GOLDEN`, from 32-bit products of 16-bit halves
/// (every sum below stays under `2^32`), rounded to 24 bits.
#[inline(always)]
pub fn longitude<U: Uint>(i: U) -> U {
    let c = U::c;
    let lo = GOLDEN as u32;
    let (il, ih) = ((i & c(0xffff)).named("il"), i.shr(16).named("ih"));
    let (gl, gh) = (c(lo & 0xffff), c(lo >> 16));
    let (ll, lh, hl, hh) = (
        il.wrapping_mul(gl),
        il.wrapping_mul(gh),
        ih.wrapping_mul(gl),
        ih.wrapping_mul(gh),
    );
    let mid = (ll.shr(16) + (lh & c(0xffff)) + (hl & c(0xffff))).named("mid");
    let high = (hh + lh.shr(16) + hl.shr(16) + mid.shr(16)).named("high");
    let turns = i
        .wrapping_mul(c((GOLDEN >> 32) as u32))
        .wrapping_add(high)
        .named("turns");
    turns.wrapping_add(c(128 + (1 << 31))).shr(8).named("longitude")
}

impl Codec for Sfib {
    type P<F: Float> = V2<F>;
    type C<F: Float> = F::U;
    #[inline]
    fn quants(&self) -> Quants {
        self.halves().quants()
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    /// The chosen index's two fields as a texture fetch returns them (`c/M`).
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V2<F> {
        self.halves().fetched(self.round_codes(v))
    }
    /// The fields re-quantized (`round(p·M)`, exact for a fetched `c/M`), then the
    /// point of their index.
    #[inline(always)]
    fn direction<F: Float>(&self, p: V2<F>) -> V3<F> {
        self.decode_codes(self.halves().codes(p))
    }
    #[inline(always)]
    fn decode_codes<F: Float>(&self, codes: V2<F>) -> V3<F> {
        let i = self.halves().index(codes).named("i");
        helper!(self.index_direction(i))
    }
    /// [`Sfib::encode_index`], which no implementation's rounding latitude can change.
    const EXACT_ROUNDING: bool = true;
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V2<F> {
        let i = helper!(self.encode_index(v)).named("i");
        self.halves().fields(i)
    }
}
