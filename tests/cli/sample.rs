//! `choose --sample FILE`: the errors over a user's own vectors. The figures of a row are
//! recomputed here from `encode` and `decode` of the same vectors (angles in f64, the
//! nearest-rank 99th percentile), the candidates are the plain query's, and every input
//! form (text, raw f32, a normal map) says which sample it is, bad input naming where.

use crate::common::*;
use serde_json::Value;

/// `n` seeded vectors (xorshift, not the tool's generator), components in [-1, 1).
fn seeded(n: usize, mut s: u64) -> Vec<[f32; 3]> {
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 40) as f32 / (1u64 << 23) as f32 - 1.0
    };
    (0..n).map(|_| [next(), next(), next()]).collect()
}

fn text(vs: &[[f32; 3]]) -> String {
    vs.iter()
        .map(|v| format!("{} {} {}\n", v[0], v[1], v[2]))
        .collect()
}

fn binary(vs: &[[f32; 3]]) -> Vec<u8> {
    vs.iter()
        .flat_map(|v| v.iter().flat_map(|x| x.to_le_bytes()))
        .collect()
}

fn ok_stdin(args: &[&str], stdin: &str) -> Run {
    let r = run_stdin(args, stdin);
    assert_eq!(r.code, 0, "unitpack {args:?}: {r:?}");
    r
}

fn row<'a>(rows: &'a [Value], spec: &str) -> &'a Value {
    rows.iter()
        .find(|r| r["spec"] == spec)
        .unwrap_or_else(|| panic!("{spec} is ranked"))
}

fn num(v: &Value, key: &str) -> f64 {
    v[key].as_f64().unwrap_or_else(|| panic!("{key} of {v}"))
}

/// The angle between two vectors in degrees, both normalized in f64.
fn angle(a: [f32; 3], b: [f32; 3]) -> f64 {
    let (a, b) = (a.map(f64::from), b.map(f64::from));
    let dot: f64 = (0..3).map(|i| a[i] * b[i]).sum();
    let len = |v: [f64; 3]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    (dot / (len(a) * len(b)))
        .clamp(-1.0, 1.0)
        .acos()
        .to_degrees()
}

#[test]
fn a_rows_figures_are_its_round_trip_over_the_samples_vectors() {
    let dir = tempdir();
    let vs = seeded(3000, 0x1234_5678_9abc_def1);
    let file = dir.path().join("mesh.txt");
    std::fs::write(&file, text(&vs)).unwrap();
    let path = file.to_str().unwrap();
    let query = ["--bits", "16", "--domain", "sphere"];
    let rows = chosen(&[&query[..], &["--sample", path]].concat());
    // The candidates are the plain query's, each measured over the sample.
    let plain = chosen(&query);
    let ids = |r: &[Value]| {
        let mut v: Vec<String> = r.iter().map(|e| e["spec"].to_string()).collect();
        v.sort();
        v
    };
    assert_eq!(ids(&rows), ids(&plain), "the same candidates");
    for spec in ["oct16", "spherical16", "draco_oct8"] {
        let codes = ok_stdin(&["encode", spec], &text(&vs)).stdout;
        let decoded = ok_stdin(&["decode", spec], &codes).stdout;
        let mut angles: Vec<f64> = vs
            .iter()
            .zip(decoded.lines())
            .map(|(v, line)| angle(*v, parse_vec(line)))
            .collect();
        assert_eq!(angles.len(), vs.len());
        let mean = angles.iter().sum::<f64>() / angles.len() as f64;
        let max = angles.iter().copied().fold(0.0, f64::max);
        angles.sort_by(f64::total_cmp);
        let p99 = angles[(angles.len() * 99).div_ceil(100) - 1];
        let r = row(&rows, spec);
        for (key, want) in [("mean", mean), ("max", max), ("p99", p99)] {
            let got = num(r, key);
            assert!(
                (got - want).abs() <= 1e-9 * want.max(1e-9),
                "{spec} {key}: {got}, the round trip gives {want}"
            );
        }
        assert_ne!(
            num(r, "max"),
            num(row(&plain, spec), "max"),
            "{spec}: the seeded figure was replaced"
        );
    }
    // Under --use too: the candidates are the seeded ranking's.
    for use_ in ["gbuffer", "vertex", "asset", "normal-map"] {
        let q = ["--use", use_, "--bits", "32"];
        assert_eq!(
            ids(&chosen(&[&q[..], &["--sample", path]].concat())),
            ids(&chosen(&q)),
            "--use {use_}: the same candidates"
        );
    }
    // The table names the sample above and below it.
    let t = ok(&[
        "choose", "--bits", "16", "--domain", "sphere", "--sample", path,
    ])
    .stdout;
    let over = format!("the 3000 vectors of {path}, 0 of them repeats");
    assert!(t.lines().next().unwrap().contains(&over), "{t}");
    assert!(
        t.contains("over the sample") && t.contains("99th percentile"),
        "{t}"
    );
}

#[test]
fn text_raw_floats_and_a_normal_map_are_read_as_samples() {
    let dir = tempdir();
    let d = dir.path();
    // The six axes, with a comment, a blank line and a CRLF line end.
    let axes = "# axes\n1 0 0\n-1 0 0\n\n0 1 0\r\n0 -1 0\n0 0 1\n0 0 -1\n";
    std::fs::write(d.join("axes.txt"), axes).unwrap();
    let axis_vs: Vec<[f32; 3]> = axes
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| parse_vec(l.trim()))
        .collect();
    std::fs::write(d.join("axes.f32"), binary(&axis_vs)).unwrap();
    let from_text = chosen(&[
        "--bits",
        "16",
        "--sample",
        d.join("axes.txt").to_str().unwrap(),
    ]);
    let from_raw = chosen(&[
        "--bits",
        "16",
        "--sample",
        d.join("axes.f32").to_str().unwrap(),
    ]);
    assert_eq!(from_text, from_raw, "the same vectors, the same answer");
    // An octahedral code holds every axis exactly.
    let oct = row(&from_text, "oct16");
    assert_eq!(
        [num(oct, "mean"), num(oct, "max"), num(oct, "p99")],
        [0.0; 3]
    );
    // A map of one normal in four texels: four vectors, three repeats; all above the
    // horizon, so the hemisphere codecs are ranked on what they hold.
    let mut png = Vec::new();
    let mut e = png::Encoder::new(&mut png, 2, 2);
    e.set_color(png::ColorType::Rgb);
    let mut w = e.write_header().unwrap();
    w.write_image_data(&[200, 128, 220].repeat(4)).unwrap();
    w.finish().unwrap();
    let map = d.join("map.png");
    std::fs::write(&map, &png).unwrap();
    let map = map.to_str().unwrap();
    let t = ok(&[
        "choose",
        "--use",
        "normal-map",
        "--bits",
        "16",
        "--sample",
        map,
    ])
    .stdout;
    let over = format!("errors over the 4 vectors of {map}, 3 of them repeats of an earlier one");
    assert!(t.starts_with(&over), "{t}");
}

/// Twice the kept size, +Z then +X: a uniform subsample holds both (its vectors are all
/// repeats but two), where keeping the first 2^20 would hold +Z alone.
#[test]
fn a_stream_beyond_the_kept_size_is_subsampled_the_same_way_each_time() {
    let dir = tempdir();
    let n = 2 << 20;
    let file = dir.path().join("big.bin");
    let vs: Vec<[f32; 3]> = (0..n)
        .map(|i| {
            if i < n / 2 {
                [0.0, 0.0, 1.0]
            } else {
                [1.0, 0.0, 0.0]
            }
        })
        .collect();
    std::fs::write(&file, binary(&vs)).unwrap();
    let args = [
        "choose",
        "--bits",
        "32",
        "--domain",
        "hemisphere",
        "--portable",
        "--sample",
        file.to_str().unwrap(),
    ];
    let first = ok(&args).stdout;
    let want = format!(
        "1048576 vectors of {} (a seeded uniform subsample of its {n}), 1048574 of them repeats",
        file.display()
    );
    assert!(first.contains(&want), "{first}");
    assert_eq!(ok(&args).stdout, first, "the subsample is seeded");
}

#[test]
fn bad_samples_name_the_line_or_record() {
    let dir = tempdir();
    let d = dir.path();
    let write = |name: &str, bytes: &[u8]| {
        let p = d.join(name);
        std::fs::write(&p, bytes).unwrap();
        p.to_str().unwrap().to_string()
    };
    let cases = [
        (
            write("bad.txt", b"1 0 0\n0 1 0\n0 1\n"),
            "line 3: expected three numbers",
        ),
        (write("bad.bin", &[0u8; 13]), "ends 1 bytes into record 2"),
        (
            write("zero.txt", b"0 0 0\nnan 0 1\n"),
            "holds no vector with a direction (2 zero, NaN or infinite)",
        ),
        (
            d.join("missing.txt").to_str().unwrap().to_string(),
            "cannot open",
        ),
    ];
    for (file, want) in &cases {
        let err = fails(&["choose", "--bits", "16", "--sample", file], "");
        assert!(err.contains(want), "{file}: {err}");
    }
    // Frames: seven numbers a line, 28 bytes a record, a normal map none.
    let frame_cases = [
        (
            write("vectors.txt", b"0 0 1\n"),
            "line 1: expected seven numbers",
        ),
        (
            write("short.f32", &[0u8; 40]),
            "ends 12 bytes into record 2",
        ),
        (
            write("along.txt", b"0 0 1 0 0 2 1\n"),
            "holds no frame with a direction (1 with a zero, NaN or infinite normal or \
             tangent, or a tangent along the normal)",
        ),
        (write("map.png", b"not read"), "a normal map holds normals"),
    ];
    for (file, want) in &frame_cases {
        let err = fails(&["choose", "--use", "frame", "--sample", file], "");
        assert!(err.contains(want), "{file}: {err}");
    }
    // Zero and NaN vectors among good ones are left out and counted.
    let some = write("some.txt", b"0 0 1\n0 0 0\n1 0 0\n");
    let t = ok(&["choose", "--bits", "16", "--sample", &some]).stdout;
    assert!(
        t.contains("the 2 vectors of") && t.contains("1 zero, NaN or infinite vectors left out"),
        "{t}"
    );
}

/// A glTF asset's normals, every primitive's: float ones in a `.gltf` whose buffer is a
/// file with a percent-escaped name, and quantized ones (`KHR_mesh_quantization`,
/// normalized `BYTE` padded to 4 bytes) in a `.glb`. Each gives the figures of the same
/// vectors as text: the floats themselves, and `max(c/127, -1)` of the bytes.
#[test]
fn a_gltf_assets_normals_are_its_sample() {
    let dir = tempdir();
    let d = dir.path();
    let vs = seeded(40, 99);
    // .gltf: two primitives, 30 and 10 float normals, in "mesh data.bin".
    std::fs::write(d.join("mesh data.bin"), binary(&vs)).unwrap();
    let gltf = serde_json::json!({
        "asset": {"version": "2.0"},
        "buffers": [{"uri": "mesh%20data.bin", "byteLength": 480}],
        "bufferViews": [{"buffer": 0, "byteLength": 480}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 30, "type": "VEC3"},
            {"bufferView": 0, "byteOffset": 360, "componentType": 5126, "count": 10, "type": "VEC3"}
        ],
        "meshes": [{"primitives": [{"attributes": {"NORMAL": 0}}, {"attributes": {"NORMAL": 1}}]}]
    });
    std::fs::write(d.join("mesh.gltf"), gltf.to_string()).unwrap();
    std::fs::write(d.join("mesh.txt"), text(&vs)).unwrap();
    let query = ["--bits", "16", "--domain", "sphere"];
    let sampled = |file: &str| {
        let rows = chosen(&[&query[..], &["--sample", d.join(file).to_str().unwrap()]].concat());
        rows.iter()
            .map(|r| {
                (
                    r["spec"].to_string(),
                    num(r, "mean"),
                    num(r, "max"),
                    num(r, "p99"),
                )
            })
            .collect::<Vec<_>>()
    };
    assert_eq!(sampled("mesh.gltf"), sampled("mesh.txt"));
    // .glb: the bytes of normalized BYTE normals, with -128 among them.
    let codes: Vec<[i8; 3]> = vec![[127, 0, 0], [-128, 5, 9], [3, -100, 60], [0, 0, 127]];
    let bin: Vec<u8> = codes
        .iter()
        .flat_map(|c| [c[0] as u8, c[1] as u8, c[2] as u8, 0])
        .collect();
    let json = serde_json::json!({
        "asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_mesh_quantization"],
        "extensionsRequired": ["KHR_mesh_quantization"],
        "buffers": [{"byteLength": bin.len()}],
        "bufferViews": [{"buffer": 0, "byteLength": bin.len(), "byteStride": 4}],
        "accessors": [{"bufferView": 0, "componentType": 5120, "normalized": true, "count": 4, "type": "VEC3"}],
        "meshes": [{"primitives": [{"attributes": {"NORMAL": 0}}]}]
    });
    let glb = glb(&json, &bin);
    std::fs::write(d.join("quantized.glb"), glb).unwrap();
    let fetched: Vec<[f32; 3]> = codes
        .iter()
        .map(|c| c.map(|x| (f32::from(x) / 127.0).max(-1.0)))
        .collect();
    std::fs::write(d.join("quantized.txt"), text(&fetched)).unwrap();
    assert_eq!(sampled("quantized.glb"), sampled("quantized.txt"));
    let t = ok(&[
        "choose",
        "--bits",
        "16",
        "--sample",
        d.join("quantized.glb").to_str().unwrap(),
    ])
    .stdout;
    assert!(t.contains("the 4 vectors of"), "{t}");
    // An asset without normals, and a NORMAL of another type, are refused by name.
    let none = serde_json::json!({"asset": {"version": "2.0"}, "meshes": []}).to_string();
    std::fs::write(d.join("none.gltf"), none).unwrap();
    let err = fails(
        &["choose", "--sample", d.join("none.gltf").to_str().unwrap()],
        "",
    );
    assert!(err.contains("no mesh primitive with a NORMAL"), "{err}");
}

/// `n` seeded tangent frames as `encode` reads them: a direction for the normal, a
/// tangent made orthogonal to it in f64, and signs alternating.
fn seeded_frames(n: usize) -> Vec<[f32; 7]> {
    let ns = seeded(n, 7);
    let others = seeded(n, 8);
    ns.iter()
        .zip(&others)
        .enumerate()
        .map(|(i, (a, b))| {
            let [a, b] = [a, b].map(|v| v.map(f64::from));
            let d: f64 =
                (0..3).map(|k| a[k] * b[k]).sum::<f64>() / (0..3).map(|k| a[k] * a[k]).sum::<f64>();
            let t = [0, 1, 2].map(|k| b[k] - d * a[k]);
            let w = if i % 2 == 0 { 1.0 } else { -1.0 };
            [a[0], a[1], a[2], t[0], t[1], t[2], w].map(|x| x as f32)
        })
        .collect()
}

fn frame_text(fs: &[[f32; 7]]) -> String {
    fs.iter()
        .map(|f| f.map(|x| x.to_string()).join(" ") + "\n")
        .collect()
}

/// The figures of `spec` over `frames`, from `encode` and `decode` of them: the normal,
/// the tangent made orthogonal to it and the bitangent `cross(n, t)·sign`, each angle
/// in f64, `[mean, max]`, and the frames whose sign changed.
fn frame_figures(spec: &str, frames: &[[f32; 7]]) -> ([[f64; 2]; 3], usize) {
    let codes = ok_stdin(&["encode", spec], &frame_text(frames)).stdout;
    let decoded = ok_stdin(&["decode", spec], &codes).stdout;
    let unit = |v: [f64; 3]| {
        let l = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        v.map(|x| x / l)
    };
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let angle = |a: [f64; 3], b: [f64; 3]| {
        let (a, b) = (unit(a), unit(b));
        (a[0] * b[0] + a[1] * b[1] + a[2] * b[2])
            .clamp(-1.0, 1.0)
            .acos()
            .to_degrees()
    };
    let (mut sum, mut max, mut flips) = ([0f64; 3], [0f64; 3], 0);
    for (f, line) in frames.iter().zip(decoded.lines()) {
        let g: Vec<f64> = line
            .split(' ')
            .map(|x| f64::from(x.parse::<f32>().unwrap()))
            .collect();
        let x = f.map(f64::from);
        let n = unit([x[0], x[1], x[2]]);
        let d: f64 = (0..3).map(|k| x[3 + k] * n[k]).sum();
        let t = unit([0, 1, 2].map(|k| x[3 + k] - d * n[k]));
        let s = if x[6] < 0.0 { -1.0 } else { 1.0 };
        let (n2, t2, s2) = ([g[0], g[1], g[2]], [g[3], g[4], g[5]], g[6]);
        let b = cross(n, t).map(|c| c * s);
        let b2 = cross(n2, t2).map(|c| c * s2);
        for (k, (u, v)) in [(n, n2), (t, t2), (b, b2)].into_iter().enumerate() {
            let a = angle(u, v);
            sum[k] += a;
            max[k] = max[k].max(a);
        }
        flips += usize::from(s2 != s);
    }
    let m = frames.len() as f64;
    ([0, 1, 2].map(|k| [sum[k] / m, max[k]]), flips)
}

/// `choose --use frame --sample`: a glTF asset's primitives with NORMAL and TANGENT are
/// its frames (a primitive without TANGENT is not, a frame whose tangent has no direction
/// is left out and counted); each frame spec's figures are its round trip over them, the
/// same as over the frames written as text; a normal map has no frames.
#[test]
fn a_gltf_assets_tangent_frames_rank_the_frame_specs() {
    let dir = tempdir();
    let d = dir.path();
    let mut frames = seeded_frames(300);
    let normals_only = seeded(20, 5);
    // Frame 7's tangent is zero: left out.
    let mut stored = frames.clone();
    stored[7][3..6].copy_from_slice(&[0.0; 3]);
    frames.remove(7);
    let mut bin: Vec<u8> = Vec::new();
    for f in &stored {
        bin.extend(f[..3].iter().flat_map(|x| x.to_le_bytes()));
    }
    for f in &stored {
        bin.extend(f[3..].iter().flat_map(|x| x.to_le_bytes()));
    }
    bin.extend(binary(&normals_only));
    let (nb, tb) = (300 * 12, 300 * 16);
    let gltf = serde_json::json!({
        "asset": {"version": "2.0"},
        "buffers": [{"uri": "frames.bin", "byteLength": bin.len()}],
        "bufferViews": [
            {"buffer": 0, "byteLength": nb},
            {"buffer": 0, "byteOffset": nb, "byteLength": tb},
            {"buffer": 0, "byteOffset": nb + tb, "byteLength": 240}
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 300, "type": "VEC3"},
            {"bufferView": 1, "componentType": 5126, "count": 300, "type": "VEC4"},
            {"bufferView": 2, "componentType": 5126, "count": 20, "type": "VEC3"}
        ],
        "meshes": [{"primitives": [
            {"attributes": {"NORMAL": 0, "TANGENT": 1}},
            {"attributes": {"NORMAL": 2}}
        ]}]
    });
    std::fs::write(d.join("frames.bin"), &bin).unwrap();
    std::fs::write(d.join("frames.gltf"), gltf.to_string()).unwrap();
    std::fs::write(d.join("frames.txt"), frame_text(&frames)).unwrap();
    let asset = d.join("frames.gltf");
    let asset = asset.to_str().unwrap();
    let rows = chosen(&["--use", "frame", "--sample", asset]);
    assert!(rows.len() >= 5, "{rows:?}");
    for r in &rows {
        let spec = r["spec"].as_str().unwrap();
        let (want, flips) = frame_figures(spec, &frames);
        for (k, key) in ["normal", "tangent", "bitangent"].into_iter().enumerate() {
            for (i, w) in want[k].iter().enumerate() {
                let got = r[key][i].as_f64().unwrap();
                assert!(
                    (got - w).abs() <= 1e-9 * w.max(1.0),
                    "{spec} {key}[{i}]: {got} over the asset, {w} from encode and decode"
                );
            }
        }
        assert_eq!(r["flips"].as_u64(), Some(flips as u64), "{spec}");
    }
    let text = d.join("frames.txt");
    assert_eq!(
        rows,
        chosen(&["--use", "frame", "--sample", text.to_str().unwrap()])
    );
    let table = ok(&["choose", "--use", "frame", "--sample", asset]).stdout;
    let head = format!(
        "errors over the 299 frames of {asset}, 0 of them repeats of an earlier one (each \
         counted); 1 frames with a zero, NaN or infinite normal or tangent, or a tangent \
         along the normal, left out"
    );
    assert!(table.starts_with(&head), "{table}");
    assert!(
        table.contains(&format!("angle error over {}", &head[12..])),
        "{table}"
    );
    // The report over the asset: every frame spec's row of the frames page is its row
    // here, the frames are named, and a frame pick is the first choice of its command,
    // which names the sample.
    let out = d.join("report");
    ok(&["report", "--out", out.to_str().unwrap(), "--sample", asset]);
    let page = std::fs::read_to_string(out.join("frames.html")).unwrap();
    assert!(page.contains(&format!("over {},", &head[12..])), "{page}");
    for r in &rows {
        let id = r["spec"].as_str().unwrap();
        let v = frame_row_values(&page, id);
        for (k, key) in ["normal", "tangent", "bitangent"].into_iter().enumerate() {
            for i in 0..2 {
                assert_eq!(
                    v[1 + 2 * k + i].parse::<f64>().unwrap(),
                    r[key][i].as_f64().unwrap(),
                    "{id} {key}[{i}]"
                );
            }
        }
        assert_eq!(v[7].parse::<u64>().ok(), r["flips"].as_u64(), "{id}");
    }
    let args = ["--use", "frame", "--bits", "64", "--sample", asset];
    let first = &chosen(&args)[0]["spec"];
    let pick = page
        .lines()
        .find(|l| l.contains(&format!("<code>unitpack choose {}</code>", args.join(" "))))
        .unwrap_or_else(|| panic!("a pick for {args:?}"));
    assert!(pick.contains(&format!("data-spec={first}")), "{pick}");
    // A normal map, and an asset without TANGENT, hold no frames.
    std::fs::write(
        d.join("normals.gltf"),
        serde_json::json!({
            "asset": {"version": "2.0"},
            "buffers": [{"uri": "frames.bin", "byteLength": bin.len()}],
            "bufferViews": [{"buffer": 0, "byteLength": nb}],
            "accessors": [{"bufferView": 0, "componentType": 5126, "count": 300, "type": "VEC3"}],
            "meshes": [{"primitives": [{"attributes": {"NORMAL": 0}}]}]
        })
        .to_string(),
    )
    .unwrap();
    let r = run(&[
        "choose",
        "--use",
        "frame",
        "--sample",
        d.join("normals.gltf").to_str().unwrap(),
    ]);
    assert_eq!(r.code, 2, "{r:?}");
    assert!(
        r.stderr
            .contains("no mesh primitive with both NORMAL and TANGENT"),
        "{r:?}"
    );
}
