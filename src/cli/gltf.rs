//! `gltf IN OUT --normals SPEC --tangents FRAME_SPEC`: a glTF asset with its normals, or
//! its tangent frames, or both, encoded by specs.
//!
//! With `gltf_normal8` or `gltf_normal16` (glTF's own quantization) each mesh primitive's
//! `NORMAL` becomes a normalized `BYTE` or `SHORT` accessor of the codes, 4-byte aligned
//! per element, and `KHR_mesh_quantization` is declared used and required: any viewer
//! loads the result. With any other vector spec the codes go to an application-specific
//! attribute `_UNITPACK_<ID>` beside the original `NORMAL` (glTF allows custom attributes
//! whose names start with `_`; they may not be `UNSIGNED_INT`, so a code's 32-bit words
//! are stored as pairs of `UNSIGNED_SHORT`, `VEC2` for one word and `VEC4` for two), for
//! a renderer that decodes with the emitted functions. A frame spec (`--tangents`) takes
//! each primitive's `NORMAL` and `TANGENT` together and writes its codes the same way.
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
use std::collections::{BTreeMap, BTreeSet};
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

/// The new bytes: each accessor's codes, 4-byte aligned, in one new buffer, or after the
/// GLB's BIN chunk where it has one that buffer 0 holds.
struct Appended {
    buffer: usize,
    base: usize,
    data: Vec<u8>,
}

impl Appended {
    /// Appends `codes` (`count` items of `words` words) as a new buffer view and accessor
    /// stored as `store` says; returns the accessor's index.
    fn push(
        &mut self,
        doc: &mut Value,
        codes: &[u32],
        count: usize,
        words: usize,
        store: &Storage,
    ) -> Result<usize> {
        self.data.resize(self.data.len().next_multiple_of(4), 0);
        let offset = self.base + self.data.len();
        self.data.extend(codes.iter().flat_map(|w| w.to_le_bytes()));
        let views = array(doc, "bufferViews")?;
        views.push(json!({
            "buffer": self.buffer,
            "byteOffset": offset,
            "byteLength": codes.len() * 4,
            "byteStride": words * 4,
            "target": ARRAY_BUFFER,
        }));
        let view = views.len() - 1;
        let accessors = array(doc, "accessors")?;
        let mut a = json!({
            "bufferView": view,
            "componentType": store.component_type,
            "count": count,
            "type": store.kind,
        });
        if store.normalized {
            a["normalized"] = json!(true);
        }
        accessors.push(a);
        Ok(accessors.len() - 1)
    }
}

/// Rewrites IN to OUT (see the module) and says what it did and the error over the asset.
pub fn run(
    input: &Path,
    out: &Path,
    normals: Option<&str>,
    tangents: Option<&str>,
    force: bool,
) -> Result<String> {
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
    let normals: Option<Spec> = normals.map(str::parse).transpose()?;
    if let Some(spec) = &normals
        && (spec.info().domain.is_none() || spec.family().frames())
    {
        bail!("--normals takes a vector codec spec; {spec} is not one");
    }
    let tangents: Option<Spec> = tangents.map(str::parse).transpose()?;
    if let Some(spec) = &tangents
        && !spec.family().frames()
    {
        bail!(
            "--tangents takes a tangent-frame spec (`unitpack choose --use frame` lists them); \
             {spec} is not one"
        );
    }
    if normals.is_none() && tangents.is_none() {
        bail!("name --normals SPEC, --tangents SPEC or both");
    }
    let bytes = std::fs::read(input).with_context(|| format!("cannot read {name}"))?;
    let found = gltf_normals(input, &bytes)?;
    let pairs: BTreeSet<(usize, usize)> = found
        .primitives
        .iter()
        .zip(&found.tangents)
        .filter_map(|(&n, t)| Some((n, (*t)?)))
        .collect();
    if tangents.is_some() && pairs.is_empty() {
        bail!(
            "{name} has no mesh primitive with both NORMAL and TANGENT: no tangent frames to encode"
        );
    }
    let (json_bytes, mut bin) = if glb {
        let g = read_glb(&bytes, &name)?;
        (g.json, g.bin)
    } else {
        (bytes.clone(), None)
    };
    let mut doc: Value =
        serde_json::from_slice(&json_bytes).with_context(|| format!("{name}: its JSON"))?;
    // A spec's functions, and how its codes are stored.
    let encoder = |spec: &Spec| {
        let e = spec.emitted();
        let words = e
            .cpu_function(Role::Encode)
            .expect("a codec encodes")
            .out_words;
        storage(spec, words).map(|s| (e, s))
    };
    let normals = normals.map(|s| encoder(&s).map(|e| (s, e))).transpose()?;
    let tangents = tangents.map(|s| encoder(&s).map(|e| (s, e))).transpose()?;

    let buffers = array(&mut doc, "buffers")?;
    let into_bin = glb && bin.is_some() && buffers.first().is_some_and(|b| b.get("uri").is_none());
    let mut added = if into_bin {
        Appended {
            buffer: 0,
            base: bin.as_ref().map_or(0, Vec::len).next_multiple_of(4),
            data: Vec::new(),
        }
    } else {
        Appended {
            buffer: buffers.len(),
            base: 0,
            data: Vec::new(),
        }
    };
    // NORMAL accessor → its codes' accessor.
    let mut replaced = BTreeMap::new();
    let mut all_normals = Vec::new();
    if let Some((_, (e, store))) = &normals {
        let enc = e.cpu_function(Role::Encode).expect("a codec encodes");
        for (&accessor, vs) in &found.accessors {
            let input: Vec<u32> = vs.iter().flat_map(|v| v.map(f32::to_bits)).collect();
            let mut codes = vec![0u32; vs.len() * enc.out_words];
            enc.eval_many(&input, &mut codes);
            let new = added.push(&mut doc, &codes, vs.len(), enc.out_words, store)?;
            replaced.insert(accessor, new);
            all_normals.extend_from_slice(vs);
        }
    }
    // (NORMAL, TANGENT) accessors → the frame codes' accessor.
    let mut framed = BTreeMap::new();
    let mut all_frames = Vec::new();
    if let Some((_, (e, store))) = &tangents {
        let enc = e.cpu_function(Role::Encode).expect("a codec encodes");
        for &(n, t) in &pairs {
            let frames: Vec<[f32; 7]> = found.accessors[&n]
                .iter()
                .zip(&found.tangent_accessors[&t])
                .map(|(n, t)| [n[0], n[1], n[2], t[0], t[1], t[2], t[3]])
                .collect();
            let input: Vec<u32> = frames.iter().flat_map(|f| f.map(f32::to_bits)).collect();
            let mut codes = vec![0u32; frames.len() * enc.out_words];
            enc.eval_many(&input, &mut codes);
            let new = added.push(&mut doc, &codes, frames.len(), enc.out_words, store)?;
            framed.insert((n, t), new);
            all_frames.extend(frames);
        }
    }
    let buffers = array(&mut doc, "buffers")?;
    if into_bin {
        let b = bin.as_mut().expect("a BIN chunk");
        b.resize(added.base, 0);
        b.extend(&added.data);
        buffers[0]["byteLength"] = json!(b.len());
    } else {
        use base64::Engine;
        let uri = format!(
            "data:application/octet-stream;base64,{}",
            base64::engine::general_purpose::STANDARD.encode(&added.data)
        );
        buffers.push(json!({ "byteLength": added.data.len(), "uri": uri }));
    }
    // Every primitive's attributes, by the accessors it named before any was replaced.
    let (mut with_normals, mut with_frames) = (0, 0);
    for mesh in array(&mut doc, "meshes")? {
        let Some(prims) = mesh.get_mut("primitives").and_then(Value::as_array_mut) else {
            continue;
        };
        for p in prims {
            let Some(attrs) = p.get_mut("attributes").and_then(Value::as_object_mut) else {
                continue;
            };
            let index = |key: &str| attrs.get(key).and_then(Value::as_u64).map(|i| i as usize);
            let (n, t) = (index("NORMAL"), index("TANGENT"));
            let frame = n.zip(t).and_then(|nt| framed.get(&nt));
            if let (Some((_, (_, store))), Some(&new)) = (&tangents, frame) {
                attrs.insert(store.attribute.clone(), json!(new));
                with_frames += 1;
            }
            if let (Some((_, (_, store))), Some(&new)) =
                (&normals, n.and_then(|n| replaced.get(&n)))
            {
                attrs.insert(store.attribute.clone(), json!(new));
                with_normals += 1;
            }
        }
    }
    if normals
        .as_ref()
        .is_some_and(|(_, (_, store))| store.attribute == "NORMAL")
    {
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
    let mut text = format!("wrote {}\n", out.display());
    if let Some((spec, (_, store))) = &normals {
        let accessors = found.accessors.len();
        text += &normals_said(spec, store, &all_normals, accessors, with_normals);
    }
    if let Some((spec, (_, store))) = &tangents {
        text += &frames_said(spec, store, &all_frames, pairs.len(), with_frames);
    }
    Ok(text)
}

/// What `--normals` did: how the normals are stored, and their error over the asset.
fn normals_said(
    spec: &Spec,
    store: &Storage,
    all: &[[f32; 3]],
    accessors: usize,
    primitives: usize,
) -> String {
    // Zero, NaN and infinite normals have no direction to measure against: encoded (to
    // the spec's documented code) but left out of the figures, and counted.
    let measured: Vec<[f32; 3]> = all
        .iter()
        .copied()
        .filter(super::sample::measurable)
        .collect();
    let left_out = all.len() - measured.len();
    let figures = match crate::measure::quality::errors_over(spec, &measured) {
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
    format!(
        "{} normals of {accessors} accessors ({primitives} primitives) encoded as {spec}, \
         {how}\n{figures}\n",
        all.len(),
    )
}

/// What `--tangents` did: how the frames are stored, and their errors over the asset.
fn frames_said(
    spec: &Spec,
    store: &Storage,
    all: &[[f32; 7]],
    pairs: usize,
    primitives: usize,
) -> String {
    let measured: Vec<[f32; 7]> = all
        .iter()
        .copied()
        .filter(super::sample::measurable)
        .collect();
    let left_out = all.len() - measured.len();
    let figures = match crate::measure::quality::frames_over(spec, &measured) {
        Some(st) if !measured.is_empty() => {
            let pair = |[mean, max]: [f64; 2]| format!("{mean:.5}° / {max:.5}°");
            format!(
                "error over the asset's {} frames with a direction, mean / max: normal {}, \
                 tangent {}, bitangent {}, handedness flips {} (a sample maximum, not a \
                 bound){}",
                measured.len(),
                pair(st.normal),
                pair(st.tangent),
                pair(st.bitangent),
                st.flips,
                if left_out > 0 {
                    format!(
                        "; {left_out} frames with a zero, NaN or infinite normal or tangent, \
                         or a tangent along the normal, left out"
                    )
                } else {
                    String::new()
                }
            )
        }
        _ => format!("no frame of the asset has a direction ({left_out} left out)"),
    };
    format!(
        "{} tangent frames of {pairs} NORMAL and TANGENT accessor pairs ({primitives} \
         primitives) encoded as {spec}, attribute {} ({} UNSIGNED_SHORT), NORMAL and \
         TANGENT kept\n{figures}\n",
        all.len(),
        store.attribute,
        store.kind
    )
}
