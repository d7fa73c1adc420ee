//! `choose --sample FILE`: the vectors of a user's own data, which the candidates' errors
//! are measured over instead of the seeded uniform vectors. Real data is not uniform (a
//! tangent-space normal map crowds around +Z, a hard-surface mesh sits on the axes), so
//! the ranking a uniform sample gives may not be the one an asset gets.
//!
//! FILE is a glTF 2.0 asset (`.gltf` with its buffers, or `.glb`: every mesh primitive's
//! `NORMAL`, float or quantized as `KHR_mesh_quantization` allows, read through the
//! `gltf` crate), a tangent-space normal map (`.png`, RGB8 or RGB16, each component
//! `n·½ + ½`, read as `convert-normal-map` reads it) or a stream of vectors as `encode` reads them:
//! raw little-endian `f32` triples where the name ends in `.bin`, `.f32` or `.raw`, else
//! text lines `x y z` (blank and `#` lines skipped). A stream is read in bounded memory:
//! past [`KEPT`] vectors a seeded reservoir keeps a uniform subsample of them, and the
//! figures say so; on a terminal a progress bar shows the bytes read, then the specs
//! measured. Zero, NaN and infinite vectors have no direction to measure against;
//! they are left out and counted.
//!
//! `choose --use frame --sample FILE` reads tangent frames instead ([`read_frames`]): a
//! glTF primitive's `NORMAL` and `TANGENT` paired element by element, or `encode`'s frame
//! records (seven numbers). A frame is left out where its normal or tangent has no
//! direction, or its tangent lies along its normal (no bitangent to measure).

use super::grammar;
use crate::choice::catalogue::{Catalogue, Entry, FrameEntry};
use crate::codecs::Spec;
use crate::support::png_file;
use anyhow::{Context, Result, bail};
use rand_core::Rng;
use rand_pcg::Pcg64Mcg;
use std::collections::HashSet;
use std::io::{BufRead, BufReader, Read};
use std::path::Path;

/// The most vectors measured: larger inputs are subsampled to this many.
pub const KEPT: usize = 1 << 20;

/// The reservoir's seed, so that a subsample, and its figures, repeat exactly.
const SEED: u128 = 0x0075_6e69_7470_6163_6b5f_7361_6d70_6c65;

/// A user's vectors (`N` = 3) or tangent frames (`N` = 7: `n`, `t` and the bitangent's
/// sign, as `encode` reads a frame) and what the figures over them must say.
pub struct Sample<const N: usize = 3> {
    /// The file, as the user named it.
    pub name: String,
    /// The items measured (all of them, or the subsample).
    pub vectors: Vec<[f32; N]>,
    /// Items with a direction read from the file.
    pub read: u64,
    /// Items left out: a zero, NaN or infinite vector (or a frame's normal or tangent).
    pub left_out: u64,
}

/// A user's tangent frames.
pub type FrameSample = Sample<7>;

impl<const N: usize> Sample<N> {
    /// What the items are called.
    const ITEMS: &'static str = if N == 3 { "vectors" } else { "frames" };

    /// The sample in words, as the legend and the line above the table give it: the file,
    /// how many items, whether subsampled, how many repeat an earlier one.
    pub fn describe(&self) -> String {
        let mut seen = HashSet::with_capacity(self.vectors.len());
        let repeats = self
            .vectors
            .iter()
            .filter(|v| !seen.insert(v.map(f32::to_bits)))
            .count();
        let items = Self::ITEMS;
        let mut s = if self.read > self.vectors.len() as u64 {
            format!(
                "{} {items} of {} (a seeded uniform subsample of its {})",
                self.vectors.len(),
                self.name,
                self.read
            )
        } else {
            format!("the {} {items} of {}", self.vectors.len(), self.name)
        };
        s.push_str(&format!(
            ", {repeats} of them repeats of an earlier one (each counted)"
        ));
        if self.left_out > 0 {
            let what = if N == 3 {
                "zero, NaN or infinite vectors"
            } else {
                "frames with a zero, NaN or infinite normal or tangent, or a tangent along \
                 the normal,"
            };
            s.push_str(&format!("; {} {what} left out", self.left_out));
        }
        s
    }
}

/// Whether a vector (`N` = 3), or a frame's normal and tangent (`N` = 7), each have a
/// direction to measure an error against: finite, not zero, and the tangent not along
/// the normal.
pub(super) fn measurable<const N: usize>(v: &[f32; N]) -> bool {
    let finite = v.iter().all(|x| x.is_finite());
    let zero = |c: &[f32]| c.iter().all(|&x| x == 0.0);
    finite && !zero(&v[..3]) && (N != 7 || !zero(&v[3..6]) && !along(&v[..6]))
}

/// Whether a frame's tangent lies along its normal (`[n, t]`): no bitangent, so no angle
/// to measure it by.
fn along(nt: &[f32]) -> bool {
    let [n, t] = [0, 3].map(|k| [0, 1, 2].map(|i| f64::from(nt[k + i])));
    (0..3).all(|i| n[(i + 1) % 3] * t[(i + 2) % 3] == n[(i + 2) % 3] * t[(i + 1) % 3])
}

/// A seeded reservoir of at most [`KEPT`] items: after `n` offers every one of them
/// is kept with the same chance (Algorithm R).
struct Reservoir<const N: usize> {
    kept: Vec<[f32; N]>,
    offered: u64,
    left_out: u64,
    rng: Pcg64Mcg,
}

impl<const N: usize> Reservoir<N> {
    fn new() -> Reservoir<N> {
        Reservoir {
            kept: Vec::new(),
            offered: 0,
            left_out: 0,
            rng: Pcg64Mcg::new(SEED),
        }
    }

    fn offer(&mut self, v: [f32; N]) {
        if !measurable(&v) {
            self.left_out += 1;
            return;
        }
        self.offered += 1;
        if self.kept.len() < KEPT {
            self.kept.push(v);
        } else {
            let j = self.rng.next_u64() % self.offered;
            if let Some(slot) = self.kept.get_mut(j as usize) {
                *slot = v;
            }
        }
    }

    fn finish(self, name: &str) -> Result<Sample<N>> {
        if self.kept.is_empty() {
            bail!(
                "{name} holds no {} with a direction ({} {})",
                if N == 3 { "vector" } else { "frame" },
                self.left_out,
                if N == 3 {
                    "zero, NaN or infinite"
                } else {
                    "with a zero, NaN or infinite normal or tangent, or a tangent along the normal"
                }
            );
        }
        Ok(Sample {
            name: name.to_string(),
            vectors: self.kept,
            read: self.offered,
            left_out: self.left_out,
        })
    }
}

/// Reads FILE's vectors (see the module).
pub fn read(path: &Path) -> Result<Sample> {
    let (name, ext) = name_and_extension(path);
    if ext == "gltf" || ext == "glb" {
        return gltf_reservoirs(path, &name)?.0.finish(&name);
    }
    let mut r = Reservoir::new();
    if ext == "png" {
        let image = png_file::read(path)?;
        for v in super::convert::conventional_vectors(&image, path)? {
            r.offer(v);
        }
        return r.finish(&name);
    }
    read_stream(path, r, grammar::parse_vector)
}

/// Reads FILE's tangent frames: a glTF asset's primitives that have both `NORMAL` and
/// `TANGENT` (its `w` the bitangent's sign), or a stream of frames as `encode` reads them
/// (text lines `nx ny nz tx ty tz w`, or raw records of seven little-endian `f32`).
pub fn read_frames(path: &Path) -> Result<FrameSample> {
    let (name, ext) = name_and_extension(path);
    if ext == "gltf" || ext == "glb" {
        return match gltf_reservoirs(path, &name)?.1 {
            Some(frames) => frames.finish(&name),
            None => Err(no_tangents(&name)),
        };
    }
    if ext == "png" {
        bail!(
            "{name}: a normal map holds normals, not tangent frames; --use frame samples a glTF asset's NORMAL and TANGENT, or frames as `encode` reads them"
        );
    }
    read_stream(path, Reservoir::new(), grammar::parse_frame)
}

/// FILE's vectors and, for a glTF asset with tangent frames, its frames from the same read
/// (`report --sample`, whose pages rank both). The second part's error says why the
/// frames' figures stay the seeded ones: the file holds no frame, or none with a direction.
pub fn read_with_frames(path: &Path) -> Result<(Sample, Result<FrameSample>)> {
    let (name, ext) = name_and_extension(path);
    if ext == "gltf" || ext == "glb" {
        let (vectors, frames) = gltf_reservoirs(path, &name)?;
        let frames = match frames {
            Some(frames) => frames.finish(&name),
            None => Err(no_tangents(&name)),
        };
        return Ok((vectors.finish(&name)?, frames));
    }
    let frames = anyhow::anyhow!(
        "{name} is not a glTF asset, whose NORMAL and TANGENT are the only tangent frames a sample of vectors comes with"
    );
    Ok((read(path)?, Err(frames)))
}

/// A glTF asset's normals (every primitive's `NORMAL`, in order) and its tangent frames
/// (each primitive's `NORMAL` and `TANGENT` paired), `None` where no primitive has
/// `TANGENT`.
fn gltf_reservoirs(path: &Path, name: &str) -> Result<(Reservoir<3>, Option<Reservoir<7>>)> {
    let bytes = std::fs::read(path).with_context(|| format!("cannot read {name}"))?;
    let g = gltf_normals(path, &bytes)?;
    let (mut vectors, mut frames) = (Reservoir::new(), None);
    for (n, t) in g.primitives.iter().zip(&g.tangents) {
        for &v in &g.accessors[n] {
            vectors.offer(v);
        }
        if let Some(t) = t {
            let r = frames.get_or_insert_with(Reservoir::new);
            for (n, t) in g.accessors[n].iter().zip(&g.tangent_accessors[t]) {
                r.offer([n[0], n[1], n[2], t[0], t[1], t[2], t[3]]);
            }
        }
    }
    Ok((vectors, frames))
}

/// An asset without tangent frames, in words.
fn no_tangents(name: &str) -> anyhow::Error {
    anyhow::anyhow!(
        "{name} has no mesh primitive with both NORMAL and TANGENT: its tangent frames cannot be sampled"
    )
}

/// The file's name as the user gave it, and its extension in lower case.
fn name_and_extension(path: &Path) -> (String, String) {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .unwrap_or_default();
    (path.display().to_string(), ext)
}

/// A stream of items as `encode` reads them: raw little-endian `f32` records where the
/// name ends in `.bin`, `.f32` or `.raw`, else text lines read by `parse`.
fn read_stream<const N: usize>(
    path: &Path,
    mut r: Reservoir<N>,
    parse: fn(&str) -> Result<[f32; N], grammar::LineError>,
) -> Result<Sample<N>> {
    let (name, ext) = name_and_extension(path);
    let item = if N == 3 { "a vector" } else { "a frame" };
    let file = std::fs::File::open(path).with_context(|| format!("cannot open {name}"))?;
    // A stream may be large: its bytes read show on a terminal.
    let bar = progress(file.metadata().map_or(0, |m| m.len()), "reading the sample");
    let mut input = BufReader::new(bar.wrap_read(file));
    if matches!(ext.as_str(), "bin" | "f32" | "raw") {
        let mut record = vec![0u8; 4 * N];
        let mut at = 0u64;
        loop {
            let mut filled = 0;
            while filled < record.len() {
                match input.read(&mut record[filled..]) {
                    Ok(0) => break,
                    Ok(n) => filled += n,
                    Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
                    Err(e) => return Err(e).with_context(|| format!("cannot read {name}")),
                }
            }
            if filled == 0 {
                break;
            }
            if filled < record.len() {
                bail!(
                    "{name} ends {filled} bytes into record {} ({item} is {} bytes: {N} \
                     little-endian f32; a text file needs another extension than .bin, .f32 \
                     or .raw)",
                    at + 1,
                    4 * N
                );
            }
            r.offer(std::array::from_fn(|i| {
                f32::from_le_bytes(record[4 * i..4 * i + 4].try_into().expect("4 bytes"))
            }));
            at += 1;
        }
        bar.finish_and_clear();
        return r.finish(&name);
    }
    let mut line = String::new();
    let mut number = 0u64;
    loop {
        line.clear();
        let n = input
            .by_ref()
            .take(super::stream::MAX_LINE as u64 + 1)
            .read_line(&mut line)
            .with_context(|| {
                format!(
                    "cannot read {name} as text at line {} (raw f32 records need the \
                     extension .bin, .f32 or .raw)",
                    number + 1
                )
            })?;
        if n == 0 {
            break;
        }
        number += 1;
        if n > super::stream::MAX_LINE {
            bail!(
                "{name}: line {number} is longer than {} bytes",
                super::stream::MAX_LINE
            );
        }
        let text = line
            .trim_start_matches('\u{feff}')
            .trim_end_matches(['\n', '\r']);
        let t = text.trim_start_matches([' ', '\t']);
        if t.is_empty() || t.starts_with('#') {
            continue;
        }
        let v = parse(text)
            .map_err(|e| anyhow::anyhow!("{name}: line {number}: {e}: {}", grammar::quote(text)))?;
        r.offer(v);
    }
    bar.finish_and_clear();
    r.finish(&name)
}

/// A progress bar of `len` steps on a terminal's stderr, hidden elsewhere (a script's
/// stderr stays clean).
fn progress(len: u64, what: &str) -> indicatif::ProgressBar {
    use std::io::IsTerminal;
    if !std::io::stderr().is_terminal() {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(len);
    bar.set_style(
        indicatif::ProgressStyle::with_template(&format!(
            "{what} {{bar:30}} {{percent}}% ({{elapsed}})"
        ))
        .expect("a valid template"),
    );
    bar
}

/// A glTF asset's `NORMAL` attributes: each mesh primitive's accessor index, in mesh
/// order, and each such accessor's vectors, read once however many primitives share it;
/// and the same of each primitive's `TANGENT`, where it has one.
pub(super) struct GltfNormals {
    pub primitives: Vec<usize>,
    pub accessors: std::collections::BTreeMap<usize, Vec<[f32; 3]>>,
    pub tangents: Vec<Option<usize>>,
    pub tangent_accessors: std::collections::BTreeMap<usize, Vec<[f32; 4]>>,
}

/// Every mesh primitive's `NORMAL` (and `TANGENT`) of a glTF asset: float, or normalized
/// `BYTE`/`SHORT` read as glTF's rule `max(c/M, -1)` (`KHR_mesh_quantization`); sparse
/// accessors with their substitutions applied. The JSON is read without the crate's validation, which
/// refuses the extensions it does not know (the quantization among them) even where only
/// the attributes matter.
pub(super) fn gltf_normals(path: &Path, bytes: &[u8]) -> Result<GltfNormals> {
    use std::collections::btree_map::Entry::Vacant;
    let name = path.display();
    // The crate's validation checks every index and enum, which its readers then trust;
    // of its complaints the extensions it does not know and the data it misses (glTF lets
    // a primitive leave out POSITION, for one) are let through.
    if let Err(e) = gltf::Gltf::from_slice(bytes) {
        use gltf::json::validation::Error as Invalid;
        let known = match &e {
            gltf::Error::Validation(errors) => errors
                .iter()
                .find(|(_, err)| !matches!(err, Invalid::Unsupported | Invalid::Missing)),
            _ => None,
        };
        match (&e, known) {
            (gltf::Error::Validation(_), None) => {}
            (gltf::Error::Validation(_), Some((at, err))) => {
                bail!(
                    "{name} is not a valid glTF 2.0 asset: {}: {err}",
                    at.as_str()
                )
            }
            _ => {
                return Err(anyhow::anyhow!("{e}"))
                    .with_context(|| format!("{name} is not a glTF 2.0 asset"));
            }
        }
    }
    let gltf = gltf::Gltf::from_slice_without_validation(bytes)
        .with_context(|| format!("{name} is not a glTF 2.0 asset"))?;
    for ext in gltf.extensions_required() {
        if ext == "KHR_draco_mesh_compression"
            || ext.starts_with("EXT_meshopt")
            || ext.starts_with("KHR_meshopt")
        {
            bail!(
                "{name} requires {ext}: its compressed geometry is not read; decompress it first (gltf-transform's `copy` does)"
            );
        }
    }
    let buffers: Vec<Vec<u8>> = gltf
        .buffers()
        .map(|b| match b.source() {
            // Only buffer 0 may be the GLB's BIN chunk; another without a URI is an
            // extension's fallback, whose bytes are not in the file.
            gltf::buffer::Source::Bin if b.index() == 0 => gltf.blob.clone().with_context(|| {
                format!("{name}: buffer 0 is the GLB's BIN chunk, which it lacks")
            }),
            gltf::buffer::Source::Bin => Ok(Vec::new()),
            gltf::buffer::Source::Uri(uri) => buffer_at(path, uri)
                .with_context(|| format!("{name}: buffer {} ({uri})", b.index())),
        })
        .collect::<Result<_>>()?;
    let data = |b: gltf::Buffer| buffers.get(b.index()).map(Vec::as_slice);
    let mut out = GltfNormals {
        primitives: Vec::new(),
        accessors: Default::default(),
        tangents: Vec::new(),
        tangent_accessors: Default::default(),
    };
    for mesh in gltf.meshes() {
        for (k, prim) in mesh.primitives().enumerate() {
            let Some(a) = prim.get(&gltf::Semantic::Normals) else {
                continue;
            };
            let at = |what: &str, a: &gltf::Accessor| {
                format!(
                    "{name}: mesh {} primitive {k}: {what} (accessor {})",
                    mesh.index(),
                    a.index()
                )
            };
            out.primitives.push(a.index());
            if let Vacant(slot) = out.accessors.entry(a.index()) {
                slot.insert(accessor::<3>(&a, data, &at("NORMAL", &a))?);
            }
            let t = prim.get(&gltf::Semantic::Tangents);
            if let Some(t) = &t {
                if t.count() != a.count() {
                    bail!(
                        "{} has {} elements, its NORMAL {}",
                        at("TANGENT", t),
                        t.count(),
                        a.count()
                    );
                }
                if let Vacant(slot) = out.tangent_accessors.entry(t.index()) {
                    slot.insert(accessor::<4>(t, data, &at("TANGENT", t))?);
                }
            }
            out.tangents.push(t.map(|t| t.index()));
        }
    }
    if out.primitives.is_empty() {
        bail!("{name} has no mesh primitive with a NORMAL attribute");
    }
    Ok(out)
}

/// One `NORMAL` (`N` = 3) or `TANGENT` (`N` = 4) accessor's elements: float, or
/// normalized `BYTE`/`SHORT` as glTF reads them, `max(c/M, -1)`.
fn accessor<'a, 's, const N: usize>(
    a: &gltf::Accessor<'a>,
    data: impl Clone + Fn(gltf::Buffer<'a>) -> Option<&'s [u8]>,
    at: &str,
) -> Result<Vec<[f32; N]>>
where
    [f32; N]: gltf::accessor::Item,
    [i8; N]: gltf::accessor::Item,
    [i16; N]: gltf::accessor::Item,
{
    use gltf::accessor::{DataType, Dimensions, Iter};
    let (dims, named) = if N == 3 {
        (Dimensions::Vec3, "VEC3")
    } else {
        (Dimensions::Vec4, "VEC4")
    };
    if a.dimensions() != dims {
        bail!("{at} is {:?}, not {named}", a.dimensions());
    }
    // A sparse accessor without a buffer view is its count of zeros plus its
    // substitutions: bounded here, where a count alone could claim gigabytes.
    if a.view().is_none() && a.count() > MAX_ELEMENTS {
        bail!(
            "{at} claims {} elements, more than {MAX_ELEMENTS}",
            a.count()
        );
    }
    if a.view().is_none() && a.sparse().is_none() {
        bail!("{at} has no buffer view: all its elements are zero, which have no direction");
    }
    let short = || format!("{at} points outside its buffer");
    Ok(match (a.data_type(), a.normalized()) {
        (DataType::F32, _) => Iter::<[f32; N]>::new(a.clone(), data)
            .with_context(short)?
            .collect(),
        (DataType::I8, true) => Iter::<[i8; N]>::new(a.clone(), data)
            .with_context(short)?
            .map(|v| v.map(|c| (f32::from(c) / 127.0).max(-1.0)))
            .collect(),
        (DataType::I16, true) => Iter::<[i16; N]>::new(a.clone(), data)
            .with_context(short)?
            .map(|v| v.map(|c| (f32::from(c) / 32767.0).max(-1.0)))
            .collect(),
        (t, n) => bail!(
            "{at} is {t:?}{}: glTF's NORMAL and TANGENT are FLOAT, or normalized BYTE or SHORT with KHR_mesh_quantization",
            if n { " normalized" } else { "" }
        ),
    })
}

/// The most elements a NORMAL or TANGENT accessor without a buffer view may have (2^28,
/// 3 GiB of floats).
const MAX_ELEMENTS: usize = 1 << 28;

/// A buffer's bytes from its URI: a base64 `data:` URI, or a file beside the asset
/// (percent-escapes decoded).
pub(super) fn buffer_at(asset: &Path, uri: &str) -> Result<Vec<u8>> {
    use base64::Engine;
    if let Some(rest) = uri.strip_prefix("data:") {
        let (_, payload) = rest
            .split_once(";base64,")
            .context("a data URI without base64 data")?;
        return base64::engine::general_purpose::STANDARD
            .decode(payload)
            .context("its base64 data is not valid");
    }
    let mut file = Vec::new();
    let bytes = uri.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        let hex = |j: usize| (bytes.get(j).copied()).and_then(|b| (b as char).to_digit(16));
        match (bytes[i], hex(i + 1), hex(i + 2)) {
            (b'%', Some(h), Some(l)) => {
                file.push((h * 16 + l) as u8);
                i += 3;
            }
            (b, _, _) => {
                file.push(b);
                i += 1;
            }
        }
    }
    let file = String::from_utf8(file).context("its URI is not UTF-8 once unescaped")?;
    let at = asset.parent().unwrap_or(Path::new(".")).join(&file);
    std::fs::read(&at).with_context(|| format!("cannot read {}", at.display()))
}

/// The catalogue's specs that `keep` names, each re-measured over `sample` (mean, sample
/// max, MSE and the 99th percentile); every other figure (ALU, bounds, filtering) is the
/// catalogue's. `choose` keeps the specs its seeded ranking holds (no constraint reads an
/// error figure, so the candidates are the same), the report every spec.
pub fn remeasure(c: &Catalogue, keep: impl Fn(&Entry) -> bool, sample: &Sample) -> Catalogue {
    let kept: Vec<&Entry> = c.specs.iter().filter(|e| keep(e)).collect();
    let bar = progress(kept.len() as u64, "measuring each spec over the sample");
    let figures = crate::support::par::map(&kept, |e| {
        let spec: Spec = e.spec.parse().expect("the catalogue's ids are specs");
        let f = crate::measure::quality::errors_over(&spec, &sample.vectors);
        bar.inc(1);
        f
    });
    bar.finish_and_clear();
    let specs = kept
        .into_iter()
        .zip(figures)
        .filter_map(|(e, f)| {
            let (stats, p99) = f?;
            Some(Entry {
                mean: stats.mean,
                max: stats.max,
                mse: stats.mse,
                p99: Some(p99),
                ..e.clone()
            })
        })
        .collect();
    Catalogue {
        samples: sample.vectors.len(),
        over: Some(sample.describe()),
        specs,
        ..c.clone()
    }
}

/// The catalogue with every tangent-frame spec re-measured over `sample` (angle errors and
/// handedness flips); their ALU counts and engines are the catalogue's.
pub fn remeasure_frames(c: &Catalogue, sample: &FrameSample) -> Catalogue {
    let bar = progress(
        c.frames.len() as u64,
        "measuring each frame spec over the sample",
    );
    let frames = crate::support::par::map(&c.frames, |e| {
        let spec: Spec = e.spec.parse().expect("the catalogue's ids are specs");
        let st = crate::measure::quality::frames_over(&spec, &sample.vectors)
            .expect("a tangent-frame spec");
        bar.inc(1);
        FrameEntry {
            normal: st.normal,
            tangent: st.tangent,
            bitangent: st.bitangent,
            flips: st.flips,
            ..e.clone()
        }
    });
    bar.finish_and_clear();
    Catalogue {
        frame_samples: sample.vectors.len(),
        frames_over: Some(sample.describe()),
        frames,
        ..c.clone()
    }
}
