//! Sphere error maps: the round-trip error of a spec's packed code over the sphere, as
//! images. Each cell of a view holds the largest error of [`PER_CELL`] seeded points
//! jittered inside it (a per-cell sample maximum), so that a narrow band of large error
//! is not averaged away. Two views: equirectangular (longitude across, latitude down,
//! +Z at the top) and octahedral (the sphere unfolded onto the square as the `oct`
//! codecs unfold it: +Z in the centre, −Z at the corners). Cells outside a hemisphere
//! codec's domain are drawn grey.

use crate::codecs::Spec;
use crate::codecs::core::info::Domain;
use crate::codecs::functions::function::Role;
use crate::measure::quality::angle_deg;
use rand_core::Rng;
use rand_pcg::Pcg64Mcg;

/// Equirectangular view: width × height cells.
pub const EQUIRECT: (usize, usize) = (256, 128);
/// Octahedral view: side × side cells.
pub const OCTAHEDRAL: usize = 128;
/// Seeded points per cell.
pub const PER_CELL: usize = 4;
/// The maps' seed.
pub const SEED: u128 = 0x0075_6e69_7470_6163_6b5f_6d61_7073;
/// Vectors of the error sample behind the histogram (its first ones: the same vectors
/// as the error figures' sample, which it begins).
pub const HISTOGRAM_SAMPLES: usize = 1 << 16;

/// A view's cells, row by row; `None` outside the domain.
pub struct Map {
    pub width: usize,
    pub height: usize,
    pub cells: Vec<Option<f64>>,
}

impl Map {
    /// The largest cell.
    pub fn max(&self) -> f64 {
        self.cells.iter().flatten().fold(0.0, |a, &b| a.max(b))
    }
}

/// A spec's maps and the errors of its histogram sample.
pub struct SpecMaps {
    pub equirect: Map,
    pub octahedral: Map,
    pub histogram: Vec<f64>,
}

/// A unit vector from the octahedral square's point `(u, v)` in `[-1, 1]²`.
fn from_octahedral(u: f64, v: f64) -> [f64; 3] {
    let z = 1.0 - u.abs() - v.abs();
    let (x, y) = if z < 0.0 {
        ((1.0 - v.abs()) * u.signum(), (1.0 - u.abs()) * v.signum())
    } else {
        (u, v)
    };
    let l = (x * x + y * y + z * z).sqrt();
    [x / l, y / l, z / l]
}

/// A unit vector from longitude `lon` and the sine of latitude `z`.
fn from_lon_z(lon: f64, z: f64) -> [f64; 3] {
    let r = (1.0 - z * z).max(0.0).sqrt();
    [r * lon.cos(), r * lon.sin(), z]
}

fn uniform(rng: &mut Pcg64Mcg) -> f64 {
    (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// The points of every cell of both views (equirectangular first), `PER_CELL` each.
fn points() -> Vec<[f32; 3]> {
    let mut rng = Pcg64Mcg::new(SEED);
    let (w, h) = EQUIRECT;
    let mut out = Vec::with_capacity((w * h + OCTAHEDRAL * OCTAHEDRAL) * PER_CELL);
    for row in 0..h {
        // Latitude from +90° at the top row down to −90°.
        let lat = |t: f64| std::f64::consts::FRAC_PI_2 - std::f64::consts::PI * t / h as f64;
        let (z_top, z_bottom) = (lat(row as f64).sin(), lat(row as f64 + 1.0).sin());
        for col in 0..w {
            for _ in 0..PER_CELL {
                let lon = -std::f64::consts::PI
                    + std::f64::consts::TAU * (col as f64 + uniform(&mut rng)) / w as f64;
                // Uniform in area within the cell: z uniform between its edges.
                let z = z_bottom + (z_top - z_bottom) * uniform(&mut rng);
                out.push(from_lon_z(lon, z).map(|c| c as f32));
            }
        }
    }
    let n = OCTAHEDRAL as f64;
    for row in 0..OCTAHEDRAL {
        for col in 0..OCTAHEDRAL {
            for _ in 0..PER_CELL {
                let u = -1.0 + 2.0 * (col as f64 + uniform(&mut rng)) / n;
                let v = 1.0 - 2.0 * (row as f64 + uniform(&mut rng)) / n;
                out.push(from_octahedral(u, v).map(|c| c as f32));
            }
        }
    }
    out
}

/// The maps of `spec` (a codec spec).
pub fn measure(spec: &Spec) -> SpecMaps {
    let e = spec.emitted();
    let hemisphere = spec.info().domain == Some(Domain::Hemisphere);
    let enc = e.cpu_function(Role::Encode).expect("a codec encodes");
    let dec = e.cpu_function(Role::Decode).expect("a codec decodes");
    let errors = |vs: &[[f32; 3]]| -> Vec<f64> {
        let input: Vec<u32> = vs.iter().flat_map(|v| v.map(f32::to_bits)).collect();
        let mut codes = vec![0u32; vs.len() * enc.out_words];
        enc.eval_many(&input, &mut codes);
        let mut out = vec![0u32; vs.len() * 3];
        dec.eval_many(&codes, &mut out);
        vs.iter()
            .zip(out.chunks_exact(3))
            .map(|(v, o)| angle_deg(*v, [o[0], o[1], o[2]].map(f32::from_bits)))
            .collect()
    };
    let pts = points();
    let err = errors(&pts);
    let cell = |i: usize| -> Option<f64> {
        let p = &pts[i * PER_CELL..][..PER_CELL];
        // A hemisphere codec's cell counts when its points are in the domain.
        if hemisphere && p.iter().any(|v| v[2] < 0.0) {
            return None;
        }
        Some(
            err[i * PER_CELL..][..PER_CELL]
                .iter()
                .fold(0.0, |a, &b| a.max(b)),
        )
    };
    let (w, h) = EQUIRECT;
    let equirect = Map {
        width: w,
        height: h,
        cells: (0..w * h).map(cell).collect(),
    };
    let octahedral = Map {
        width: OCTAHEDRAL,
        height: OCTAHEDRAL,
        cells: (w * h..w * h + OCTAHEDRAL * OCTAHEDRAL).map(cell).collect(),
    };
    let sample = crate::support::sampling::random_unit_vectors(
        crate::measure::figures::VECTOR_SEED,
        HISTOGRAM_SAMPLES,
        hemisphere,
    );
    SpecMaps {
        equirect,
        octahedral,
        histogram: errors(&sample),
    }
}

/// Where a sample's vectors lie: each cell of both views counts the vectors in it
/// (`None`: none), so that a reader sees which parts of a spec's error maps the sample
/// weighs (`report --sample`).
pub struct Density {
    pub equirect: Map,
    pub octahedral: Map,
}

/// The cells of both views that `v` (nonzero) falls in, row-major indices: the
/// equirectangular row by latitude (`asin(z)`, +90° at the top), its column by longitude
/// from −180°; the octahedral cell where the `oct` unfold puts it.
fn cells_of(v: [f32; 3]) -> (usize, usize) {
    let v = v.map(f64::from);
    let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let u = v.map(|c| c / len);
    let (w, h) = EQUIRECT;
    let lon = u[1].atan2(u[0]);
    let lat = u[2].clamp(-1.0, 1.0).asin();
    let col = (((lon + std::f64::consts::PI) / std::f64::consts::TAU) * w as f64) as usize;
    let row = (((std::f64::consts::FRAC_PI_2 - lat) / std::f64::consts::PI) * h as f64) as usize;
    let l1 = u[0].abs() + u[1].abs() + u[2].abs();
    let (x, y) = (u[0] / l1, u[1] / l1);
    let (a, b) = if u[2] < 0.0 {
        ((1.0 - y.abs()) * x.signum(), (1.0 - x.abs()) * y.signum())
    } else {
        (x, y)
    };
    let n = OCTAHEDRAL as f64;
    let oc = (((a + 1.0) / 2.0) * n) as usize;
    let or = (((1.0 - b) / 2.0) * n) as usize;
    (
        row.min(h - 1) * w + col.min(w - 1),
        or.min(OCTAHEDRAL - 1) * OCTAHEDRAL + oc.min(OCTAHEDRAL - 1),
    )
}

/// The density of `vectors` (each nonzero and finite, as a sample holds them).
pub fn density(vectors: &[[f32; 3]]) -> Density {
    let (w, h) = EQUIRECT;
    let mut eq = vec![0u64; w * h];
    let mut oct = vec![0u64; OCTAHEDRAL * OCTAHEDRAL];
    for &v in vectors {
        let (e, o) = cells_of(v);
        eq[e] += 1;
        oct[o] += 1;
    }
    let cells = |c: Vec<u64>| c.into_iter().map(|n| (n > 0).then_some(n as f64)).collect();
    Density {
        equirect: Map {
            width: w,
            height: h,
            cells: cells(eq),
        },
        octahedral: Map {
            width: OCTAHEDRAL,
            height: OCTAHEDRAL,
            cells: cells(oct),
        },
    }
}

/// A density map as RGB pixels, each cell `scale` pixels square: the log of the count on
/// the maps' colours, from one vector (the bottom) to the densest cell of the two views
/// (the top); grey where there is none.
pub fn density_pixels(d: &Density, map: &Map, scale: usize) -> (u32, u32, Vec<u8>) {
    let top = d.equirect.max().max(d.octahedral.max()).max(2.0);
    paint(map, scale, |n| colour((n.ln() / top.ln()).clamp(0.0, 1.0)))
}

/// The colour of `t` in `[0, 1]` on the maps' scale (viridis).
pub fn colour(t: f64) -> [u8; 3] {
    let c = colorous::VIRIDIS.eval_continuous(t.clamp(0.0, 1.0));
    [c.r, c.g, c.b]
}

/// Grey: outside the domain.
const OUTSIDE: [u8; 3] = [200, 200, 200];

/// The error, in degrees, at the bottom and the top of the one colour scale every map of
/// every family shares, so that two pages compare by eye: the colour follows log10 of the
/// error, clamped to this range (a smaller error takes the bottom colour, a larger the top).
pub const SCALE_DEGREES: (f64, f64) = (1e-3, 10.0);

/// Where `e` degrees lies on the shared scale, in `[0, 1]`.
pub fn scale_position(e: f64) -> f64 {
    let (lo, hi) = SCALE_DEGREES;
    ((e.max(lo).log10() - lo.log10()) / (hi.log10() - lo.log10())).clamp(0.0, 1.0)
}

/// `map` as RGB pixels, each cell `scale` pixels square, coloured on the shared scale.
pub fn pixels(map: &Map, scale: usize) -> (u32, u32, Vec<u8>) {
    paint(map, scale, |e| colour(scale_position(e)))
}

/// `map` as RGB pixels, each cell `scale` pixels square in the colour `of` gives its
/// value, grey where it has none.
fn paint(map: &Map, scale: usize, of: impl Fn(f64) -> [u8; 3]) -> (u32, u32, Vec<u8>) {
    let (w, h) = (map.width * scale, map.height * scale);
    let mut px = Vec::with_capacity(w * h * 3);
    for y in 0..h {
        for x in 0..w {
            let c = map.cells[(y / scale) * map.width + x / scale].map_or(OUTSIDE, &of);
            px.extend_from_slice(&c);
        }
    }
    (w as u32, h as u32, px)
}

/// The legend: the shared scale from its bottom (left) to its top (right), `width` ×
/// `height` pixels, evenly spaced in log10 of the error.
pub fn legend(width: usize, height: usize) -> (u32, u32, Vec<u8>) {
    let mut px = Vec::with_capacity(width * height * 3);
    for _ in 0..height {
        for x in 0..width {
            px.extend_from_slice(&colour(x as f64 / (width - 1) as f64));
        }
    }
    (width as u32, height as u32, px)
}
