//! `gltf IN OUT --normals SPEC`: what it writes is valid glTF by the Khronos validator
//! (`tools/gltf-js`, pinned), its quantized normals are gltf-transform's `quantize()`
//! integers, a custom attribute's codes are `encode`'s, and everything else in the asset
//! is kept.

use crate::common::*;
use serde_json::{Value, json};
use std::path::Path;

#[path = "../families/oracles/gltf_transform.rs"]
mod gltf_transform;

/// `n` seeded unit normals (xorshift, not the tool's generator).
fn normals(n: usize, mut s: u64) -> Vec<[f32; 3]> {
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 40) as f64 / (1u64 << 23) as f64 - 1.0
    };
    (0..n)
        .map(|_| {
            let v = [next(), next(), next()];
            let l = v.iter().map(|x| x * x).sum::<f64>().sqrt();
            v.map(|x| (x / l) as f32)
        })
        .collect()
}

fn floats(vs: &[[f32; 3]]) -> Vec<u8> {
    vs.iter()
        .flat_map(|v| v.iter().flat_map(|x| x.to_le_bytes()))
        .collect()
}

/// An asset of one triangle-list primitive (positions and `normals`, a multiple of three),
/// an image and its texture, a material, extras and an extension nobody knows, as JSON
/// whose buffer is `uri`.
fn asset(normals: &[[f32; 3]], uri: Option<&str>) -> Value {
    let n = normals.len();
    let mut buffer = json!({"byteLength": 24 * n});
    if let Some(u) = uri {
        buffer["uri"] = json!(u);
    }
    json!({
        "asset": {"version": "2.0", "generator": "unitpack tests"},
        "extras": {"kept": [1, 2.5, "three"]},
        "extensionsUsed": ["EXT_nobody_knows"],
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "name": "node"}],
        "images": [{"uri": "tex.png"}],
        "textures": [{"source": 0}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1.0]}}],
        "buffers": [buffer],
        "bufferViews": [
            {"buffer": 0, "byteLength": 12 * n, "target": 34962},
            {"buffer": 0, "byteOffset": 12 * n, "byteLength": 12 * n, "target": 34962}
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3",
             "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0]},
            {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC3"}
        ],
        "meshes": [{"primitives": [{
            "attributes": {"POSITION": 0, "NORMAL": 1},
            "material": 0,
            "extensions": {"EXT_nobody_knows": {"a": 1}}
        }]}]
    })
}

/// Positions on a small grid (within the accessor's min and max), then the normals.
fn buffer(normals: &[[f32; 3]]) -> Vec<u8> {
    let pos: Vec<[f32; 3]> = (0..normals.len())
        .map(|i| [(i % 2) as f32, ((i / 2) % 2) as f32, 0.0])
        .collect();
    [floats(&pos), floats(normals)].concat()
}

/// A GLB's JSON and BIN chunk.
fn read_glb(bytes: &[u8]) -> (Value, Vec<u8>) {
    let word = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap()) as usize;
    assert_eq!(&bytes[..4], b"glTF");
    assert_eq!(word(8), bytes.len(), "the header's length");
    let jl = word(12);
    let json = serde_json::from_slice(&bytes[20..20 + jl]).unwrap();
    let bl = word(20 + jl);
    (json, bytes[28 + jl..28 + jl + bl].to_vec())
}

/// The Khronos validator's report of each file: (errors, warnings, messages).
fn validate(files: &[&Path]) -> Vec<(u64, u64, String)> {
    let dir = manifest_dir().join("tools/gltf-js");
    assert!(
        dir.join("node_modules/gltf-validator/package.json")
            .exists(),
        "the glTF validator is not installed: run `npm ci --prefix tools/gltf-js` \
         (Node.js and npm: the Debian packages `nodejs` and `npm`)"
    );
    let out = std::process::Command::new("node")
        .arg(dir.join("validate.mjs"))
        .args(files)
        .output()
        .unwrap_or_else(|e| panic!("running `node` (the Debian package `nodejs`): {e}"));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| {
            let v: Value = serde_json::from_str(l).unwrap();
            (
                v["errors"].as_u64().unwrap(),
                v["warnings"].as_u64().unwrap(),
                v["messages"].to_string(),
            )
        })
        .collect()
}

/// The bytes an accessor's elements take, element by element (`stride` apart, `size` each).
fn elements(bytes: &[u8], view: &Value, accessor: &Value, size: usize) -> Vec<Vec<u8>> {
    let offset = view["byteOffset"].as_u64().unwrap_or(0) as usize
        + accessor["byteOffset"].as_u64().unwrap_or(0) as usize;
    let stride = view["byteStride"].as_u64().map_or(size, |s| s as usize);
    (0..accessor["count"].as_u64().unwrap() as usize)
        .map(|i| bytes[offset + i * stride..][..size].to_vec())
        .collect()
}

/// Every member of the input's JSON but those the rewrite adds to is in the output as it
/// was; the arrays it adds to begin with the input's.
fn kept(input: &Value, output: &Value) {
    for (k, v) in input.as_object().unwrap() {
        match k.as_str() {
            "buffers" | "bufferViews" | "accessors" | "extensionsUsed" => {
                let out = output[k].as_array().unwrap();
                for (i, x) in v.as_array().unwrap().iter().enumerate() {
                    if k == "buffers" && i == 0 && out[0].get("uri").is_none() {
                        // The GLB's BIN chunk, grown by the codes.
                        assert!(out[0]["byteLength"].as_u64() > x["byteLength"].as_u64());
                    } else {
                        assert_eq!(&out[i], x, "{k}[{i}] is kept");
                    }
                }
            }
            "meshes" => {
                let mut want = v.clone();
                let mut got = output[k].clone();
                for m in [&mut want, &mut got] {
                    m[0]["primitives"][0]
                        .as_object_mut()
                        .unwrap()
                        .remove("attributes");
                }
                assert_eq!(got, want, "the meshes but their attributes");
            }
            _ => assert_eq!(&output[k], v, "{k} is kept"),
        }
    }
    let keys = |v: &Value| v.as_object().unwrap().keys().cloned().collect::<Vec<_>>();
    let got: Vec<String> = keys(output)
        .into_iter()
        .filter(|k| input.get(k).is_some())
        .collect();
    assert_eq!(got, keys(input), "the members in their order");
}

#[test]
fn quantized_normals_are_gltf_transforms_and_the_asset_validates() {
    let dir = tempdir();
    let d = dir.path();
    let ns = normals(63, 0x5eed);
    std::fs::write(d.join("tex.png"), tiny_png()).unwrap();
    // A .gltf with its buffer in a file: 8-bit normals, appended as a data: URI buffer.
    let input = asset(&ns, Some("mesh.bin"));
    std::fs::write(d.join("mesh.bin"), buffer(&ns)).unwrap();
    std::fs::write(
        d.join("mesh.gltf"),
        serde_json::to_string_pretty(&input).unwrap(),
    )
    .unwrap();
    let r = run_in(
        Some(d),
        &[
            "gltf",
            "mesh.gltf",
            "out8.gltf",
            "--normals",
            "gltf_normal8",
        ],
        "",
    );
    assert_eq!(r.code, 0, "{r:?}");
    assert!(
        r.stdout.contains("63 normals")
            && r.stdout
                .contains("error over the asset's 63 normals with a direction: mean"),
        "{r:?}"
    );
    let out: Value = serde_json::from_slice(&std::fs::read(d.join("out8.gltf")).unwrap()).unwrap();
    kept(&input, &out);
    assert_eq!(out["extensionsRequired"], json!(["KHR_mesh_quantization"]));
    assert!(
        out["extensionsUsed"]
            .as_array()
            .unwrap()
            .contains(&json!("KHR_mesh_quantization"))
    );
    let a = &out["accessors"][out["meshes"][0]["primitives"][0]["attributes"]["NORMAL"]
        .as_u64()
        .unwrap() as usize];
    assert_eq!(
        (
            a["componentType"].as_u64(),
            a["normalized"].as_bool(),
            a["type"].as_str()
        ),
        (Some(5120), Some(true), Some("VEC3"))
    );
    let view = &out["bufferViews"][a["bufferView"].as_u64().unwrap() as usize];
    let uri = out["buffers"][view["buffer"].as_u64().unwrap() as usize]["uri"]
        .as_str()
        .unwrap();
    use base64::Engine;
    let data = base64::engine::general_purpose::STANDARD
        .decode(uri.split_once(";base64,").unwrap().1)
        .unwrap();
    let want = gltf_transform::run(8, "NORMAL", &ns.concat());
    let port: Vec<i32> = ns
        .iter()
        .flat_map(|v| v.map(|x| gltf_transform::quantized(x, 8)))
        .collect();
    assert_eq!(want, port, "gltf-transform and its port agree");
    for (i, e) in elements(&data, view, a, 4).iter().enumerate() {
        assert_eq!(e[3], 0, "element {i}'s padding");
        let got: Vec<i32> = e[..3].iter().map(|&b| i32::from(b as i8)).collect();
        assert_eq!(got, want[3 * i..3 * i + 3], "element {i}: {:?}", ns[i]);
    }
    // A .glb: 16-bit normals, appended to its BIN chunk.
    let input = asset(&ns, None);
    std::fs::write(d.join("mesh.glb"), glb(&input, &buffer(&ns))).unwrap();
    let r = run_in(
        Some(d),
        &[
            "gltf",
            "mesh.glb",
            "out16.glb",
            "--normals",
            "gltf_normal16",
        ],
        "",
    );
    assert_eq!(r.code, 0, "{r:?}");
    let (out, bin) = read_glb(&std::fs::read(d.join("out16.glb")).unwrap());
    kept(&input, &out);
    assert_eq!(
        &bin[..24 * ns.len()],
        &buffer(&ns)[..],
        "the BIN chunk's bytes are kept"
    );
    assert_eq!(
        out["buffers"].as_array().unwrap().len(),
        1,
        "one buffer: the BIN chunk"
    );
    assert_eq!(
        out["buffers"][0]["byteLength"].as_u64().unwrap() as usize,
        bin.len()
    );
    let a = &out["accessors"][out["meshes"][0]["primitives"][0]["attributes"]["NORMAL"]
        .as_u64()
        .unwrap() as usize];
    assert_eq!(
        (a["componentType"].as_u64(), a["normalized"].as_bool()),
        (Some(5122), Some(true))
    );
    let view = &out["bufferViews"][a["bufferView"].as_u64().unwrap() as usize];
    let want = gltf_transform::run(16, "NORMAL", &ns.concat());
    for (i, e) in elements(&bin, view, a, 8).iter().enumerate() {
        assert_eq!(&e[6..], &[0, 0], "element {i}'s padding");
        let got: Vec<i32> = e[..6]
            .chunks(2)
            .map(|h| i32::from(i16::from_le_bytes([h[0], h[1]])))
            .collect();
        assert_eq!(got, want[3 * i..3 * i + 3], "element {i}: {:?}", ns[i]);
    }
    // Both pass the Khronos validator without an error or a warning (its notes on the
    // unknown extension and on the original accessors, now unused, are information).
    for (file, (errors, warnings, messages)) in ["out8.gltf", "out16.glb"]
        .iter()
        .zip(validate(&[&d.join("out8.gltf"), &d.join("out16.glb")]))
    {
        assert_eq!((errors, warnings), (0, 0), "{file}: {messages}");
    }
}

#[test]
fn another_spec_writes_a_custom_attribute_of_encodes_codes() {
    let dir = tempdir();
    let d = dir.path();
    let ns = normals(51, 0xface);
    std::fs::write(d.join("tex.png"), tiny_png()).unwrap();
    let input = asset(&ns, None);
    std::fs::write(d.join("mesh.glb"), glb(&input, &buffer(&ns))).unwrap();
    for (spec, kind, words) in [("oct16", "VEC2", 1), ("snorm16x3", "VEC4", 2)] {
        let out = format!("{spec}.glb");
        let r = run_in(Some(d), &["gltf", "mesh.glb", &out, "--normals", spec], "");
        assert_eq!(r.code, 0, "{r:?}");
        let (json, bin) = read_glb(&std::fs::read(d.join(&out)).unwrap());
        kept(&input, &json);
        let attrs = &json["meshes"][0]["primitives"][0]["attributes"];
        assert_eq!(attrs["NORMAL"], json!(1), "the original NORMAL stays");
        let name = format!("_UNITPACK_{}", spec.to_uppercase());
        let a = &json["accessors"][attrs[&name].as_u64().unwrap() as usize];
        assert_eq!(
            (a["componentType"].as_u64(), a["type"].as_str()),
            (Some(5123), Some(kind))
        );
        let view = &json["bufferViews"][a["bufferView"].as_u64().unwrap() as usize];
        let codes = run_bytes(
            &[
                "encode",
                spec,
                "--input-format",
                "binary",
                "--output-format",
                "binary",
            ],
            &floats(&ns),
        );
        assert_eq!(codes.code, 0, "{codes:?}");
        let got: Vec<u8> = elements(&bin, view, a, 4 * words).concat();
        assert_eq!(got, codes.out, "{spec}: the attribute holds encode's codes");
        assert!(json.get("extensionsRequired").is_none(), "nothing required");
        let (errors, warnings, messages) = validate(&[&d.join(&out)]).remove(0);
        assert_eq!((errors, warnings), (0, 0), "{out}: {messages}");
    }
}

/// `--tangents SPEC`: each primitive's NORMAL and TANGENT, as frames, go to
/// `_UNITPACK_<ID>` as `encode` writes their codes, beside both attributes (and beside
/// `--normals`' own attribute when both are asked); the asset validates; the errors over
/// its frames are printed.
#[test]
fn tangents_write_the_frame_codes_of_encode() {
    let dir = tempdir();
    let d = dir.path();
    let ns = normals(45, 0xbeef);
    // A unit tangent orthogonal to each normal (f64, then f32), signs alternating.
    let others = normals(45, 0xcafe);
    let frames: Vec<[f32; 7]> = ns
        .iter()
        .zip(&others)
        .enumerate()
        .map(|(i, (n, o))| {
            let [n, o] = [n, o].map(|v| v.map(f64::from));
            let d: f64 = (0..3).map(|k| n[k] * o[k]).sum();
            let t = [0, 1, 2].map(|k| o[k] - d * n[k]);
            let l = t.iter().map(|x| x * x).sum::<f64>().sqrt();
            let w = if i % 2 == 0 { 1.0 } else { -1.0 };
            [n[0], n[1], n[2], t[0] / l, t[1] / l, t[2] / l, w].map(|x| x as f32)
        })
        .collect();
    std::fs::write(d.join("tex.png"), tiny_png()).unwrap();
    let mut input = asset(&ns, None);
    let base = buffer(&ns);
    let tangent_bytes: Vec<u8> = frames
        .iter()
        .flat_map(|f| f[3..].iter().flat_map(|x| x.to_le_bytes()))
        .collect();
    input["buffers"][0]["byteLength"] = json!(base.len() + tangent_bytes.len());
    input["bufferViews"]
        .as_array_mut()
        .unwrap()
        .push(json!({"buffer": 0, "byteOffset": base.len(), "byteLength": tangent_bytes.len(), "target": 34962}));
    input["accessors"]
        .as_array_mut()
        .unwrap()
        .push(json!({"bufferView": 2, "componentType": 5126, "count": 45, "type": "VEC4"}));
    input["meshes"][0]["primitives"][0]["attributes"]["TANGENT"] = json!(2);
    std::fs::write(
        d.join("mesh.glb"),
        glb(&input, &[base, tangent_bytes].concat()),
    )
    .unwrap();
    let codes = run_bytes(
        &[
            "encode",
            "qtangent64",
            "--input-format",
            "binary",
            "--output-format",
            "binary",
        ],
        &frames
            .iter()
            .flat_map(|f| f.iter().flat_map(|x| x.to_le_bytes()))
            .collect::<Vec<u8>>(),
    );
    assert_eq!(codes.code, 0, "{codes:?}");
    for args in [
        &["--tangents", "qtangent64"][..],
        &["--normals", "gltf_normal16", "--tangents", "qtangent64"],
    ] {
        let r = run_in(
            Some(d),
            &[&["gltf", "mesh.glb", "out.glb", "--force"][..], args].concat(),
            "",
        );
        assert_eq!(r.code, 0, "{r:?}");
        assert!(
            r.stdout.contains(
                "45 tangent frames of 1 NORMAL and TANGENT accessor pairs (1 primitives) \
                 encoded as qtangent64, attribute _UNITPACK_QTANGENT64 (VEC4 UNSIGNED_SHORT)"
            ) && r
                .stdout
                .contains("error over the asset's 45 frames with a direction, mean / max: normal"),
            "{r:?}"
        );
        let (json, bin) = read_glb(&std::fs::read(d.join("out.glb")).unwrap());
        kept(&input, &json);
        let attrs = &json["meshes"][0]["primitives"][0]["attributes"];
        assert_eq!(attrs["TANGENT"], json!(2), "TANGENT stays");
        let a = &json["accessors"][attrs["_UNITPACK_QTANGENT64"].as_u64().unwrap() as usize];
        assert_eq!(
            (a["componentType"].as_u64(), a["type"].as_str()),
            (Some(5123), Some("VEC4"))
        );
        let view = &json["bufferViews"][a["bufferView"].as_u64().unwrap() as usize];
        let got: Vec<u8> = elements(&bin, view, a, 8).concat();
        assert_eq!(got, codes.out, "the attribute holds encode's frame codes");
        if args.len() == 4 {
            assert_ne!(attrs["NORMAL"], json!(1), "NORMAL quantized as well");
        } else {
            assert_eq!(attrs["NORMAL"], json!(1), "NORMAL stays");
        }
        let (errors, warnings, messages) = validate(&[&d.join("out.glb")]).remove(0);
        assert_eq!((errors, warnings), (0, 0), "{args:?}: {messages}");
    }
    // A vector spec is not a frame spec, and an asset without TANGENT has no frames.
    let r = run_in(
        Some(d),
        &["gltf", "mesh.glb", "x.glb", "--tangents", "oct16"],
        "",
    );
    assert!(
        r.code == 2 && r.stderr.contains("--tangents takes a tangent-frame spec"),
        "{r:?}"
    );
    std::fs::write(d.join("plain.glb"), glb(&asset(&ns, None), &buffer(&ns))).unwrap();
    let r = run_in(
        Some(d),
        &["gltf", "plain.glb", "x.glb", "--tangents", "qtangent64"],
        "",
    );
    assert!(
        r.code == 2
            && r.stderr
                .contains("no mesh primitive with both NORMAL and TANGENT"),
        "{r:?}"
    );
    assert!(!d.join("x.glb").exists());
}

#[test]
fn gltf_refuses_what_it_cannot_write_and_loses_nothing() {
    let dir = tempdir();
    let d = dir.path();
    let ns = normals(9, 1);
    std::fs::write(d.join("tex.png"), tiny_png()).unwrap();
    std::fs::write(d.join("mesh.glb"), glb(&asset(&ns, None), &buffer(&ns))).unwrap();
    std::fs::write(d.join("mesh.bin"), buffer(&ns)).unwrap();
    let gltf = asset(&ns, Some("mesh.bin")).to_string();
    std::fs::write(d.join("mesh.gltf"), &gltf).unwrap();
    std::fs::write(d.join("taken.glb"), b"not mine").unwrap();
    std::fs::create_dir(d.join("sub")).unwrap();
    let cases: [(&[&str], &str); 7] = [
        (
            &["mesh.glb", "taken.glb", "--normals", "oct16"],
            "exists; pass --force",
        ),
        (
            &["mesh.glb", "mesh.glb", "--normals", "oct16", "--force"],
            "both IN and OUT",
        ),
        (
            &["mesh.glb", "out.gltf", "--normals", "oct16"],
            "both .gltf or both .glb",
        ),
        (
            &["mesh.gltf", "sub/out.gltf", "--normals", "oct16"],
            "write OUT beside IN",
        ),
        (
            &["mesh.glb", "out.glb", "--normals", "qtangent64"],
            "takes a vector codec spec",
        ),
        (
            &["mesh.glb", "out.glb", "--normals", "float32x3"],
            "no glTF attribute type holds it",
        ),
        (
            &["mesh.glb", "out.glb", "--normals", "nosuch16"],
            "nosuch16",
        ),
    ];
    for (args, want) in cases {
        let r = run_in(Some(d), &[&["gltf"][..], args].concat(), "");
        assert_eq!(r.code, 2, "{args:?}: {r:?}");
        assert!(r.stderr.contains(want), "{args:?}: {}", r.stderr);
    }
    // A zero normal (no valid asset has one, but real ones do) is encoded, left out of the
    // figures and counted.
    let mut zero = ns.clone();
    zero[4] = [0.0, 0.0, 0.0];
    std::fs::write(d.join("zero.glb"), glb(&asset(&zero, None), &buffer(&zero))).unwrap();
    let r = run_in(
        Some(d),
        &["gltf", "zero.glb", "zero_out.glb", "--normals", "oct16"],
        "",
    );
    assert_eq!(r.code, 0, "{r:?}");
    assert!(
        r.stdout.contains("8 normals with a direction")
            && r.stdout
                .contains("1 zero, NaN or infinite normals left out")
            && !r.stdout.contains("NaN°"),
        "{r:?}"
    );
    // A NORMAL that names no accessor, and one that is not VEC3: refused by name.
    for (attrs, want) in [
        (json!({"NORMAL": 99}), "not a valid glTF 2.0 asset"),
        (json!({"NORMAL": 0}), "not VEC3"),
    ] {
        let mut bad = asset(&ns, None);
        bad["meshes"][0]["primitives"][0]["attributes"] = attrs;
        bad["accessors"][0]["type"] = json!("VEC2");
        std::fs::write(d.join("bad.glb"), glb(&bad, &buffer(&ns))).unwrap();
        let r = run_in(
            Some(d),
            &["gltf", "bad.glb", "out.glb", "--normals", "oct16"],
            "",
        );
        assert_eq!(r.code, 2, "{r:?}");
        assert!(r.stderr.contains(want), "{}", r.stderr);
    }
    assert_eq!(std::fs::read(d.join("taken.glb")).unwrap(), b"not mine");
    assert_eq!(std::fs::read_to_string(d.join("mesh.gltf")).unwrap(), gltf);
    assert!(!d.join("out.glb").exists() && !d.join("sub/out.gltf").exists());
}

/// A 1×1 RGB PNG.
fn tiny_png() -> Vec<u8> {
    let mut png = Vec::new();
    let mut e = png::Encoder::new(&mut png, 1, 1);
    e.set_color(png::ColorType::Rgb);
    let mut w = e.write_header().unwrap();
    w.write_image_data(&[10, 20, 30]).unwrap();
    w.finish().unwrap();
    png
}
