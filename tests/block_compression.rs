//! Normal maps under block compression (the fourth seed's question whether a projection
//! that spreads the hemisphere more evenly survives BC5 and DXT5 better): a deterministic
//! tangent-space normal map, each hemisphere codec's two parameters stored unorm8
//! (`p·0.5 + 0.5`, as the texel layouts store them), compressed, decompressed and
//! reconstructed by the codec's float decoder, and the angle to the map's own normal
//! measured. The README's table is written by this test (`UPDATE_README=1`).

use texpresso::{Algorithm, COLOUR_WEIGHTS_UNIFORM, Format, Params};
use unitpack::api::{HemiOct, Paraboloid, ParaboloidSquare, Xy, XyStereo};
use unitpack::codecs::Codec;
use unitpack::doc_tables::replace_block;
use unitpack::model::{V2, V3};
use unitpack::quality::angle_deg;

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
            // libsquish's cluster fit; uniform weights, since only G carries data in
            // the colour block of DXT5nm.
            let params = Params {
                algorithm: Algorithm::ClusterFit,
                weights: COLOUR_WEIGHTS_UNIFORM,
                weigh_colour_by_alpha: false,
            };
            let mut blocks = vec![0u8; format.compressed_size(SIZE, SIZE)];
            format.compress(&texels, SIZE, SIZE, params, &mut blocks);
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

/// Every map × reconstruction × storage, and the README's table of them.
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
/// for every reconstruction; and the README holds this very table.
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
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md");
    let text = std::fs::read_to_string(&path).unwrap();
    let fresh = replace_block(&text, "block_compression", "block_compression", &body)
        .expect("README.md lacks the markers of the block_compression block");
    if std::env::var_os("UPDATE_README").is_some() {
        std::fs::write(&path, &fresh).unwrap();
        return;
    }
    assert!(
        fresh == text,
        "README.md's block compression table is stale: run \
         `UPDATE_README=1 cargo test --release --test block_compression`"
    );
}
