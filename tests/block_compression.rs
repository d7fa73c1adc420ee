//! Normal maps under block compression (the fourth seed's question whether a projection
//! that spreads the hemisphere more evenly survives BC5 and DXT5 better): a deterministic
//! tangent-space normal map, each hemisphere codec's two parameters stored unorm8
//! (`p·0.5 + 0.5`, as the texel layouts store them), compressed, decompressed and
//! reconstructed by the codec's float decoder, and the angle to the map's own normal
//! measured. The table in docs/design/block-compression.md is written by this test
//! (`UNITPACK_REFRESH=1`).

use texpresso::{Algorithm, COLOUR_WEIGHTS_UNIFORM, Format, Params};
use unitpack::api::{HemiOct, Paraboloid, ParaboloidSquare, Xy, XyStereo};
use unitpack::codecs::Codec;
use unitpack::measure::quality::angle_deg;
use unitpack::model::{V2, V3};
use unitpack::report::doc_tables::replace_block;

/// The map's side in texels.
const SIZE: usize = 256;

/// The height at `(u, v)` in texels: two long waves, an 8×8 grid of raised-cosine
/// rivets of varied heights with steep flanks, and short ripples: smooth regions, where
/// block compression does well, and sharp ones, where it does not (the table states the
/// tilts the map holds).
fn height(u: f64, v: f64) -> f64 {
    use std::f64::consts::PI;
    let (s, t) = (u / SIZE as f64, v / SIZE as f64);
    let waves =
        6.0 * (2.0 * PI * (3.0 * s + t)).sin() + 4.0 * (2.0 * PI * (5.0 * t - 2.0 * s) + 1.0).sin();
    let cell = SIZE as f64 / 8.0;
    let (cu, cv) = ((u / cell).floor(), (v / cell).floor());
    let (du, dv) = (u - (cu + 0.5) * cell, v - (cv + 0.5) * cell);
    let radius = 0.4 * cell;
    let d = (du * du + dv * dv).sqrt();
    // A raised cosine of amplitude `k·2·radius/π` has a largest slope of `k`.
    let amp = (0.6 + 0.4 * ((cu * 7.0 + cv * 3.0) % 5.0) / 4.0) * 2.0 * radius / PI;
    let rivet = if d < radius {
        amp * 0.5 * (1.0 + (PI * d / radius).cos())
    } else {
        0.0
    };
    let ripples = 0.15 * (u * 0.45).sin() * (v * 0.6 + 0.25 * u).cos();
    waves + rivet + ripples
}

/// The normal maps: the height's central differences scaled by `strength` (bumpier
/// maps tilt further from +Z), each texel's normal normalized in f64 and rounded to f32.
const MAPS: [(&str, f64); 3] = [("gentle", 0.5), ("medium", 1.0), ("steep", 1.5)];

fn normal_map(strength: f64) -> Vec<[f32; 3]> {
    let mut map = Vec::with_capacity(SIZE * SIZE);
    for y in 0..SIZE {
        for x in 0..SIZE {
            let (u, v) = (x as f64, y as f64);
            let dx = (height(u + 0.5, v) - height(u - 0.5, v)) * strength;
            let dy = (height(u, v + 0.5) - height(u, v - 0.5)) * strength;
            let l = (dx * dx + dy * dy + 1.0).sqrt();
            map.push([(-dx / l) as f32, (-dy / l) as f32, (1.0 / l) as f32]);
        }
    }
    map
}

/// A hemisphere codec's float forms: the two parameters in `[-1, 1]` and back.
struct Reconstruction {
    name: &'static str,
    params: Box<dyn Fn([f32; 3]) -> [f32; 2]>,
    direction: Box<dyn Fn([f32; 2]) -> [f32; 3]>,
}

fn reconstruction<C>(name: &'static str, c: C) -> Reconstruction
where
    C: Codec<P<f32> = V2<f32>> + Copy + 'static,
{
    Reconstruction {
        name,
        params: Box::new(move |n| c.params::<f32>(V3::from_array(n)).to_array()),
        direction: Box::new(move |p| c.direction::<f32>(V2::from_array(p)).to_array()),
    }
}

fn reconstructions() -> Vec<Reconstruction> {
    vec![
        reconstruction("orthographic (`xy16`)", Xy::new(16).unwrap()),
        reconstruction("stereographic (`xy_stereo16`)", XyStereo::new(16).unwrap()),
        reconstruction("paraboloid (`paraboloid16`)", Paraboloid::new(16).unwrap()),
        reconstruction(
            "paraboloid_square (`paraboloid_square16`)",
            ParaboloidSquare::new(16).unwrap(),
        ),
        reconstruction("hemi-octahedral (`hemioct16`)", HemiOct::new(16).unwrap()),
    ]
}

/// A parameter in `[-1, 1]` as the unorm8 byte of `p·0.5 + 0.5`, and back.
fn to_byte(p: f32) -> u8 {
    ((p.clamp(-1.0, 1.0) * 0.5 + 0.5) * 255.0).round() as u8
}
fn from_byte(b: u8) -> f32 {
    f32::from(b) / 255.0 * 2.0 - 1.0
}

/// Where a texel's two parameters live: a texture format and the channels of `x` and
/// `y`, the others set as the layout sets them.
#[derive(Clone, Copy)]
struct Storage {
    name: &'static str,
    /// `None`: the RGBA8 texel itself, uncompressed.
    format: Option<Format>,
    x: usize,
    y: usize,
    /// The texel before `x` and `y` are written.
    fill: [u8; 4],
}

const STORAGES: [Storage; 4] = [
    Storage {
        name: "RGBA8",
        format: None,
        x: 0,
        y: 1,
        fill: [0, 0, 0, 255],
    },
    Storage {
        name: "BC5 (x R, y G)",
        format: Some(Format::Bc5),
        x: 0,
        y: 1,
        fill: [0, 0, 0, 255],
    },
    Storage {
        name: "DXT5nm (x A, y G, R = 1)",
        format: Some(Format::Bc3),
        x: 3,
        y: 1,
        fill: [255, 0, 0, 0],
    },
    Storage {
        name: "DXT1 (x R, y G)",
        format: Some(Format::Bc1),
        x: 0,
        y: 1,
        fill: [0, 0, 0, 255],
    },
];

/// Mean and sample maximum of the angular error over every texel of the map.
#[derive(Clone, Copy, Debug)]
struct Error {
    mean: f64,
    max: f64,
}

/// The format's palette for endpoints `a0`, `a1` (BC4, as texpresso decodes it): six
/// values between them when `a0 > a1`, else four between them plus 0 and 255.
fn palette(a0: u8, a1: u8) -> [u8; 8] {
    let (a, b) = (i32::from(a0), i32::from(a1));
    let mut p = [a0, a1, 0, 0, 0, 0, 0, 255];
    if a > b {
        for i in 1..7 {
            p[1 + i as usize] = (((7 - i) * a + i * b) / 7) as u8;
        }
    } else {
        for i in 1..5 {
            p[1 + i as usize] = (((5 - i) * a + i * b) / 5) as u8;
        }
    }
    p
}

/// One BC4 block of 16 values: libsquish's range fit (the values' own range for the
/// six-value palette, the range without 0 and 255 for the four-value one, each value
/// given its nearest entry, the palette with the smaller squared error kept), with each
/// palette built from its own endpoints. texpresso 2.0.2 fits against a six-value
/// palette whose first two entries are the other palette's endpoints, so its blocks
/// decode one or two levels off wherever those differ; its colour fit is unaffected.
fn bc4_block(v: [u8; 16]) -> [u8; 8] {
    let lo = *v.iter().min().unwrap();
    let hi = *v.iter().max().unwrap();
    let inner = v.iter().copied().filter(|&x| x != 0 && x != 255);
    let lo5 = inner.clone().min().unwrap_or(lo);
    let hi5 = inner.max().unwrap_or(lo5);
    let fit = |a0: u8, a1: u8| {
        let p = palette(a0, a1);
        let mut idx = [0u8; 16];
        let mut err = 0u32;
        for (i, &x) in v.iter().enumerate() {
            let d = |k: usize| u32::from(x.abs_diff(p[k]));
            let k = (0..8).min_by_key(|&k| d(k)).unwrap();
            idx[i] = k as u8;
            err += d(k) * d(k);
        }
        (err, a0, a1, idx)
    };
    let (six, four) = (fit(hi, lo), fit(lo5, hi5));
    let (_, a0, a1, idx) = if six.0 < four.0 { six } else { four };
    let bits: u64 = idx
        .iter()
        .enumerate()
        .map(|(i, &k)| u64::from(k) << (3 * i))
        .sum();
    let mut block = [a0, a1, 0, 0, 0, 0, 0, 0];
    block[2..].copy_from_slice(&bits.to_le_bytes()[..6]);
    block
}

/// Replaces the BC4 blocks of `blocks` (BC5's R and G, DXT5's A) with [`bc4_block`]'s.
fn refit_bc4(texels: &[u8], blocks: &mut [u8], format: Format) {
    // (channel, offset of its BC4 block within the compressed block)
    let channels: &[(usize, usize)] = match format {
        Format::Bc5 => &[(0, 0), (1, 8)],
        Format::Bc3 => &[(3, 0)],
        _ => return,
    };
    let wide = SIZE / 4;
    for (b, block) in blocks.chunks_exact_mut(format.block_size()).enumerate() {
        let (bx, by) = (b % wide, b / wide);
        for &(ch, off) in channels {
            let v: [u8; 16] = std::array::from_fn(|i| {
                let (x, y) = (4 * bx + i % 4, 4 * by + i / 4);
                texels[4 * (y * SIZE + x) + ch]
            });
            block[off..off + 8].copy_from_slice(&bc4_block(v));
        }
    }
}

/// The refitted BC4 blocks decode (through texpresso's decoder) to within half a step of
/// the coarser palette over the block's own range (the four-value one: a fifth of it),
/// plus the decoder's truncation.
#[test]
fn bc4_blocks_decode_near_their_values() {
    let mut state = 0x2545_f491_u32;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        state
    };
    for _ in 0..2000 {
        let (base, spread) = ((next() % 256) as u8, next() % 64 + 1);
        let v: [u8; 16] = std::array::from_fn(|_| base.saturating_add((next() % spread) as u8));
        let (lo, hi) = (*v.iter().min().unwrap(), *v.iter().max().unwrap());
        let mut block = [0u8; 16];
        block[..8].copy_from_slice(&bc4_block(v));
        block[8..].copy_from_slice(&bc4_block(v));
        let got = Format::Bc5.decompress_block(&block);
        let step = f64::from(hi - lo) / 5.0;
        for (i, (&x, t)) in v.iter().zip(got).enumerate() {
            for c in [t[0], t[1]] {
                let e = f64::from(x.abs_diff(c));
                assert!(
                    e <= step / 2.0 + 1.0,
                    "{v:?}: texel {i} decodes to {c}, not {x}"
                );
            }
        }
    }
}

fn measure(map: &[[f32; 3]], r: &Reconstruction, s: Storage) -> Error {
    let mut texels: Vec<u8> = Vec::with_capacity(map.len() * 4);
    for &n in map {
        let p = (r.params)(n);
        let mut t = s.fill;
        t[s.x] = to_byte(p[0]);
        t[s.y] = to_byte(p[1]);
        texels.extend_from_slice(&t);
    }
    let stored = match s.format {
        None => texels,
        Some(format) => {
            // Colour blocks (DXT1, DXT5nm's green): libsquish's cluster fit, uniform
            // weights since only G carries data in DXT5nm's. The BC4 blocks (BC5's two
            // channels, DXT5's alpha) are then refitted by `refit_bc4`.
            let params = Params {
                algorithm: Algorithm::ClusterFit,
                weights: COLOUR_WEIGHTS_UNIFORM,
                weigh_colour_by_alpha: false,
            };
            let mut blocks = vec![0u8; format.compressed_size(SIZE, SIZE)];
            format.compress(&texels, SIZE, SIZE, params, &mut blocks);
            refit_bc4(&texels, &mut blocks, format);
            let mut out = vec![0u8; texels.len()];
            format.decompress(&blocks, SIZE, SIZE, &mut out);
            out
        }
    };
    let (mut sum, mut max) = (0.0f64, 0.0f64);
    for (n, t) in map.iter().zip(stored.chunks_exact(4)) {
        let v = (r.direction)([from_byte(t[s.x]), from_byte(t[s.y])]);
        let e = angle_deg(*n, v);
        sum += e;
        max = max.max(e);
    }
    Error {
        mean: sum / map.len() as f64,
        max,
    }
}

/// Every map × reconstruction × storage, and the documented table of them.
fn table() -> (Vec<Vec<Error>>, String) {
    let rs = reconstructions();
    let mut errors = Vec::new();
    let mut text = String::new();
    let mut rows = String::new();
    for (map_name, strength) in MAPS {
        let map = normal_map(strength);
        let tilts: Vec<f64> = map.iter().map(|&n| angle_deg(n, [0.0, 0.0, 1.0])).collect();
        let steep = tilts.iter().filter(|&&t| t > 30.0).count();
        text.push_str(&format!(
            "- {map_name} (strength {strength}): tilt from +Z mean {:.1}°, sample max {:.1}°, \
             over 30° at {:.1} % of the texels\n",
            tilts.iter().sum::<f64>() / tilts.len() as f64,
            tilts.iter().copied().fold(0.0, f64::max),
            100.0 * steep as f64 / tilts.len() as f64,
        ));
        for r in &rs {
            let row: Vec<Error> = STORAGES.iter().map(|&s| measure(&map, r, s)).collect();
            rows.push_str(&format!("| {map_name} | {} |", r.name));
            for e in &row {
                rows.push_str(&format!(" {:.3}° / {:.2}° |", e.mean, e.max));
            }
            rows.push('\n');
            errors.push(row);
        }
    }
    text.push_str("\n| map | reconstruction |");
    for s in STORAGES {
        text.push_str(&format!(" {} mean / max |", s.name));
    }
    text.push_str("\n|---|---|");
    text.push_str(&"---|".repeat(STORAGES.len()));
    text.push('\n');
    text.push_str(&rows);
    (errors, text)
}

/// Compression only adds error, BC5's two independent 8-bit-endpoint channels beat the
/// 6-bit green endpoints of DXT5nm's colour block, which beat DXT1's shared 5:6:5 block,
/// for every reconstruction; and docs/design/block-compression.md holds this very table.
#[test]
fn block_compression_table() {
    let (errors, body) = table();
    let rs = reconstructions();
    for (r, row) in rs.iter().cycle().zip(&errors) {
        let [raw, bc5, dxt5, dxt1] = [row[0], row[1], row[2], row[3]];
        // The uncompressed texel is the unorm8 grid alone: under a degree at worst.
        assert!(raw.max < 1.0, "{}: {raw:?}", r.name);
        for (what, c) in [("BC5", bc5), ("DXT5nm", dxt5), ("DXT1", dxt1)] {
            assert!(
                c.mean > raw.mean,
                "{}: {what} {c:?} vs RGBA8 {raw:?}",
                r.name
            );
        }
        assert!(bc5.mean < dxt5.mean, "{}: {bc5:?} vs {dxt5:?}", r.name);
        assert!(dxt5.mean < dxt1.mean, "{}: {dxt5:?} vs {dxt1:?}", r.name);
    }
    let b = unitpack::report::doc_tables::block("block_compression");
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(b.file);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", b.file));
    let fresh = replace_block(&text, b.test, b.name, &body).unwrap_or_else(|| {
        panic!(
            "{} lacks the markers of the block_compression block",
            b.file
        )
    });
    if unitpack::report::doc_tables::refreshing() {
        if fresh != text {
            std::fs::write(&path, &fresh).unwrap();
        }
        return;
    }
    assert!(
        fresh == text,
        "{}'s block compression table is stale: run `{}` \
         (or `UNITPACK_REFRESH=1 cargo test --release --test block_compression` for it alone)",
        b.file,
        unitpack::report::doc_tables::REFRESH_COMMAND
    );
}
