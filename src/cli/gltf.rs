//! `gltf IN OUT --normals SPEC`: a glTF asset with its normals encoded by a spec.
//!
//! With `gltf_normal8` or `gltf_normal16` (glTF's own quantization) each mesh primitive's
//! `NORMAL` becomes a normalized `BYTE` or `SHORT` accessor of the codes, 4-byte aligned
//! per element, and `KHR_mesh_quantization` is declared used and required: any viewer
//! loads the result. With any other vector spec the codes go to an application-specific
//! attribute `_UNITPACK_<ID>` beside the original `NORMAL` (glTF allows custom attributes
//! whose names start with `_`; they may not be `UNSIGNED_INT`, so a code's 32-bit words
//! are stored as pairs of `UNSIGNED_SHORT`, `VEC2` for one word and `VEC4` for two), for
//! a renderer that decodes with the emitted functions.
//!
//! Everything else is kept: the new codes are appended (to the GLB's `BIN` chunk, or as
//! a new buffer in a `data:` URI for a `.gltf`), accessors and buffer views are only
//! added, and the JSON is rewritten with its members in their order (`serde_json`'s
//! `preserve_order`), so images, animations, extras and unknown extensions pass
//! through; the original accessors stay, now unreferenced where replaced. Morph targets'
//! `NORMAL` deltas are not unit vectors and are left as they are.

use super::output;
use super::sample::gltf_normals;
use crate::codecs::Spec;
use crate::codecs::core::spec::Family;
use crate::codecs::functions::function::Role;
use crate::support::atomic::write_atomic_with;
use anyhow::{Context, Result, bail};
use serde_json::{Value, json};
use std::path::Path;

/// glTF's component types.
const BYTE: u32 = 5120;
const UNSIGNED_SHORT: u32 = 5123;
const SHORT: u32 = 5122;
/// A buffer view's target for vertex attributes.
const ARRAY_BUFFER: u32 = 34962;
const QUANTIZATION: &str = "KHR_mesh_quantization";

/// How the codes of one spec are stored.
struct Storage {
    /// The attribute the codes take: `NORMAL` itself, or `_UNITPACK_<ID>`.
    attribute: String,
    component_type: u32,
    normalized: bool,
    kind: &'static str,
}

fn storage(spec: &Spec, words: usize) -> Result<Storage> {
    if spec.info().name == crate::codecs::component::gltf_normal::FAMILY.info().name {
        let short = spec.bits() > 24;
        return Ok(Storage {
            attribute: "NORMAL".into(),
            component_type: if short { SHORT } else { BYTE },
            normalized: true,
            kind: "VEC3",
        });
    }
    let kind = match words {
        1 => "VEC2",
        2 => "VEC4",
        n => bail!(
            "{spec}'s code is {n} words ({} bits): no glTF attribute type holds it (a custom \
             attribute is at most four UNSIGNED_SHORT, 64 bits)",
            spec.bits()
        ),
    };
    Ok(Storage {
        attribute: format!("_UNITPACK_{}", spec.id().to_ascii_uppercase()),
        component_type: UNSIGNED_SHORT,
        normalized: false,
        kind,
    })
}

/// A GLB's JSON and BIN chunks.
struct Glb {
    json: Vec<u8>,
    bin: Option<Vec<u8>>,
}

fn read_glb(bytes: &[u8], name: &str) -> Result<Glb> {
    let word = |at: usize| -> Result<u32> {
        bytes
            .get(at..at + 4)
            .map(|b| u32::from_le_bytes(b.try_into().expect("4 bytes")))
            .with_context(|| format!("{name}: the GLB ends at byte {}", bytes.len()))
    };
    if bytes.get(..4) != Some(b"glTF") || word(4)? != 2 {
        bail!("{name} is not a GLB of glTF 2.0 (its header is not `glTF`, version 2)");
    }
    let mut at = 12;
    let mut chunks = Vec::new();
    while at < bytes.len().min(word(8)? as usize) {
        let len = word(at)? as usize;
        let kind = word(at + 4)?;
        let body = bytes
            .get(at + 8..at + 8 + len)
            .with_context(|| format!("{name}: a chunk runs past the end of the file"))?;
        chunks.push((kind, body.to_vec()));
        at += 8 + len;
    }
    let mut chunks = chunks.into_iter();
    let json = match chunks.next() {
        Some((0x4e4f_534a, json)) => json,
        _ => bail!("{name}: the GLB's first chunk is not its JSON"),
    };
    let bin = chunks
        .find(|(kind, _)| *kind == 0x004e_4942)
        .map(|(_, b)| b);
    Ok(Glb { json, bin })
}

fn write_glb(json: &[u8], bin: Option<&[u8]>) -> Result<Vec<u8>> {
    let pad = |v: &mut Vec<u8>, with: u8| v.resize(v.len().next_multiple_of(4), with);
    let mut json = json.to_vec();
    pad(&mut json, b' ');
    let bin = bin.map(|b| {
        let mut b = b.to_vec();
        pad(&mut b, 0);
        b
    });
    let total = 12 + 8 + json.len() + bin.as_ref().map_or(0, |b| 8 + b.len());
    if total > u32::MAX as usize {
        bail!(
            "the new GLB would be {total} bytes: a GLB holds at most 4 GiB (its lengths are 32-bit)"
        );
    }
    let mut out = Vec::with_capacity(total);
    out.extend(b"glTF");
    out.extend(2u32.to_le_bytes());
    out.extend((total as u32).to_le_bytes());
    out.extend((json.len() as u32).to_le_bytes());
    out.extend(0x4e4f_534au32.to_le_bytes());
    out.extend(&json);
    if let Some(b) = bin {
        out.extend((b.len() as u32).to_le_bytes());
        out.extend(0x004e_4942u32.to_le_bytes());
        out.extend(&b);
    }
    Ok(out)
}

/// `array[key]` of `v`, made an empty array where absent.
fn array<'a>(v: &'a mut Value, key: &str) -> Result<&'a mut Vec<Value>> {
    v.as_object_mut()
        .context("the glTF JSON is not an object")?
        .entry(key)
        .or_insert_with(|| json!([]))
        .as_array_mut()
        .with_context(|| format!("the glTF's {key} is not an array"))
}

/// Rewrites IN to OUT (see the module) and says what it did and the error over the asset.
pub fn run(input: &Path, out: &Path, normals: &str, force: bool) -> Result<String> {
    let name = input.display().to_string();
    let ext = |p: &Path| {
        p.extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .unwrap_or_default()
    };
    let glb = match (ext(input).as_str(), ext(out).as_str()) {
        ("glb", "glb") => true,
        ("gltf", "gltf") => false,
        (i, o) => bail!(
            "IN and OUT are both .gltf or both .glb (got .{i} and .{o}): the container is kept"
        ),
    };
    if output::is_stdout(out) {
        bail!("gltf writes a file: name OUT, not -");
    }
    if super::convert::same_file(input, out) {
        bail!(
            "{} is both IN and OUT; write the new asset elsewhere",
            out.display()
        );
    }
    if out.exists() && !force {
        bail!("{} exists; pass --force to replace it", out.display());
    }
    if !glb {
        let dir = |p: &Path| {
            let parent = p.parent().filter(|d| !d.as_os_str().is_empty());
            parent.unwrap_or(Path::new(".")).canonicalize()
        };
        if dir(input).ok() != dir(out).ok() {
            bail!(
                "write OUT beside IN ({}): a .gltf names its buffers and images by paths \
                 relative to itself",
                input
                    .parent()
                    .filter(|d| !d.as_os_str().is_empty())
                    .map_or(".".into(), |d| d.display().to_string())
            );
        }
    }
    let spec: Spec = normals.parse()?;
    if spec.info().domain.is_none() || spec.family().frames() {
        bail!("--normals takes a vector codec spec; {spec} is not one");
    }
    let bytes = std::fs::read(input).with_context(|| format!("cannot read {name}"))?;
    let found = gltf_normals(input, &bytes)?;
    let (json_bytes, mut bin) = if glb {
        let g = read_glb(&bytes, &name)?;
        (g.json, g.bin)
    } else {
        (bytes.clone(), None)
    };
    let mut doc: Value =
        serde_json::from_slice(&json_bytes).with_context(|| format!("{name}: its JSON"))?;
    let e = spec.emitted();
    let enc = e.cpu_function(Role::Encode).expect("a codec encodes");
    let store = storage(&spec, enc.out_words)?;

    // The new bytes: each NORMAL accessor's codes, 4-byte aligned, in one new buffer, or
    // after the GLB's BIN chunk where it has one that buffer 0 holds.
    let buffers = array(&mut doc, "buffers")?;
    let into_bin = glb && bin.is_some() && buffers.first().is_some_and(|b| b.get("uri").is_none());
    let (buffer, base) = if into_bin {
        (0, bin.as_ref().map_or(0, Vec::len).next_multiple_of(4))
    } else {
        (buffers.len(), 0)
    };
    let mut data: Vec<u8> = Vec::new();
    let mut replaced = std::collections::BTreeMap::new();
    let mut all = Vec::new();
    for (&accessor, vs) in &found.accessors {
        let input: Vec<u32> = vs.iter().flat_map(|v| v.map(f32::to_bits)).collect();
        let mut codes = vec![0u32; vs.len() * enc.out_words];
        enc.eval_many(&input, &mut codes);
        data.resize(data.len().next_multiple_of(4), 0);
        let offset = base + data.len();
        data.extend(codes.iter().flat_map(|w| w.to_le_bytes()));
        let views = array(&mut doc, "bufferViews")?;
        views.push(json!({
            "buffer": buffer,
            "byteOffset": offset,
            "byteLength": codes.len() * 4,
            "byteStride": enc.out_words * 4,
            "target": ARRAY_BUFFER,
        }));
        let view = views.len() - 1;
        let accessors = array(&mut doc, "accessors")?;
        let mut a = json!({
            "bufferView": view,
            "componentType": store.component_type,
            "count": vs.len(),
            "type": store.kind,
        });
        if store.normalized {
            a["normalized"] = json!(true);
        }
        accessors.push(a);
        replaced.insert(accessor, accessors.len() - 1);
        all.extend_from_slice(vs);
    }
    // The buffer that holds them.
    let buffers = array(&mut doc, "buffers")?;
    if into_bin {
        let b = bin.as_mut().expect("a BIN chunk");
        b.resize(base, 0);
        b.extend(&data);
        buffers[0]["byteLength"] = json!(b.len());
    } else {
        use base64::Engine;
        let uri = format!(
            "data:application/octet-stream;base64,{}",
            base64::engine::general_purpose::STANDARD.encode(&data)
        );
        buffers.push(json!({ "byteLength": data.len(), "uri": uri }));
    }
    // Every primitive's attribute.
    let mut primitives = 0;
    for mesh in array(&mut doc, "meshes")? {
        let Some(prims) = mesh.get_mut("primitives").and_then(Value::as_array_mut) else {
            continue;
        };
        for p in prims {
            let Some(attrs) = p.get_mut("attributes").and_then(Value::as_object_mut) else {
                continue;
            };
            let Some(&new) = attrs
                .get("NORMAL")
                .and_then(Value::as_u64)
                .and_then(|i| replaced.get(&(i as usize)))
            else {
                continue;
            };
            attrs.insert(store.attribute.clone(), json!(new));
            primitives += 1;
        }
    }
    if store.attribute == "NORMAL" {
        for key in ["extensionsUsed", "extensionsRequired"] {
            let list = array(&mut doc, key)?;
            if !list.iter().any(|x| x == QUANTIZATION) {
                list.push(json!(QUANTIZATION));
            }
        }
    }
    let bytes = if glb {
        write_glb(&serde_json::to_vec(&doc)?, bin.as_deref())?
    } else {
        let mut s = serde_json::to_string_pretty(&doc)?;
        s.push('\n');
        s.into_bytes()
    };
    write_atomic_with(out, &bytes, force)?;
    // Zero, NaN and infinite normals have no direction to measure against: encoded (to
    // the spec's documented code) but left out of the figures, and counted.
    let measured: Vec<[f32; 3]> = all
        .iter()
        .copied()
        .filter(|v| v.iter().all(|x| x.is_finite()) && v.iter().any(|&x| x != 0.0))
        .collect();
    let left_out = all.len() - measured.len();
    let figures = match crate::measure::quality::errors_over(&spec, &measured) {
        Some((stats, p99)) if !measured.is_empty() => format!(
            "error over the asset's {} normals with a direction: mean {:.5}°, p99 {p99:.5}°, \
             max {:.5}° (the round trip of each; a sample maximum, not a bound){}",
            measured.len(),
            stats.mean,
            stats.max,
            if left_out > 0 {
                format!("; {left_out} zero, NaN or infinite normals left out")
            } else {
                String::new()
            }
        ),
        _ => format!("no normal of the asset has a direction ({left_out} zero, NaN or infinite)"),
    };
    let how = if store.attribute == "NORMAL" {
        format!(
            "NORMAL as {QUANTIZATION} {}",
            if store.component_type == SHORT {
                "SHORT"
            } else {
                "BYTE"
            }
        )
    } else {
        format!(
            "attribute {} ({} UNSIGNED_SHORT), NORMAL kept",
            store.attribute, store.kind
        )
    };
    Ok(format!(
        "wrote {}: {} normals of {} accessors ({primitives} primitives) encoded as {spec}, \
         {how}\n{figures}\n",
        out.display(),
        all.len(),
        found.accessors.len(),
    ))
}
