//! `unitpack report`: a static HTML report of the catalogue that a browser opens from
//! disk. The index holds the trade-off charts and every spec's figures; one page per
//! family holds, for each spec, its sphere error maps ([`maps`]), an error histogram,
//! the filtering figures, the guarantees, the formats and the include's signatures.
//!
//! Every number comes from the compiled-in catalogue ([`crate::choice::catalogue`]), the
//! one `list` and `choose` print, and sits in a `data-value` attribute beside its rounded
//! text, so a test can hold the two to each other. Only the maps and histograms are
//! computed here, seeded. The output is deterministic: the same build writes the same
//! bytes.
//!
//! The folder is the report's own: `report` writes into a new or empty folder, or into
//! one holding an earlier report (its `.unitpack-report` manifest), and replaces only the
//! files that manifest lists. Every file is prepared before any is written, each is
//! replaced atomically.

pub mod charts;
pub mod doc_tables;
pub mod maps;

use crate::choice::catalogue::{Catalogue, Entry};
use crate::choice::filtering::{self, DECIDING_SEPARATION, FilterStats};
use crate::choice::recommend::{Case, Winner};
use crate::codecs::{FAMILIES, Spec};
use crate::emit::Lang;
use crate::emit::lang::printer;
use anyhow::{Context, Result, bail};
use askama::Template;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The manifest of the files a report wrote, in the report's folder.
pub const MANIFEST: &str = ".unitpack-report";

#[derive(Template)]
#[template(path = "report/index.html")]
struct Index<'a> {
    picks_note: String,
    picks: Vec<String>,
    intro: String,
    filtering_note: String,
    families: Vec<FamilyLink<'a>>,
    charts: Vec<String>,
    deciding: f64,
    rows: Vec<String>,
}

#[derive(Template)]
#[template(path = "report/frames.html")]
struct FramesPage {
    intro: String,
    ranking_note: String,
    picks: Vec<String>,
    rows: Vec<String>,
}

struct FamilyLink<'a> {
    name: &'a str,
    title: &'a str,
}

#[derive(Template)]
#[template(path = "report/family.html")]
struct FamilyPage<'a> {
    name: &'a str,
    title: &'a str,
    source: &'a str,
    per_cell: usize,
    equirect_w: usize,
    equirect_h: usize,
    oct_w: usize,
    /// The shared colour scale's ends, degrees.
    scale_lo: String,
    scale_hi: String,
    /// A user's sample (`report --sample`), in words: its density maps then stand beside
    /// each spec's error maps.
    sample: Option<String>,
    specs: Vec<SpecSection>,
}

struct SpecSection {
    id: String,
    figures: Vec<String>,
    top: f64,
    top_text: String,
    histogram: String,
    not_filterable: Option<String>,
    filtering: Option<Vec<String>>,
    seam: String,
    signatures: String,
}

/// Pixels per map cell in the images (one: the page scales them up, pixelated).
const SCALE: usize = 1;
/// How much larger than its pixels the page shows a map.
const SHOWN: usize = 2;

/// A table cell of a number: its full value in `data-value`, `digits` decimals shown.
fn num(v: f64, digits: usize) -> String {
    format!("<td class=\"n\" data-value=\"{v}\">{v:.digits$}</td>")
}

/// A figure that spans decades (an MSE), to `digits` significant digits: `1.398e-5`, where a
/// fixed number of decimals printed meshopt_oct16's as 0.000000000.
fn sci(v: f64, digits: usize) -> String {
    let shown = digits.saturating_sub(1);
    format!("<td class=\"n\" data-value=\"{v}\">{v:.shown$e}</td>")
}

fn int(v: u32) -> String {
    format!("<td class=\"n\" data-value=\"{v}\">{v}</td>")
}

fn text(s: &str) -> String {
    format!("<td>{}</td>", escape(s))
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

fn bound(b: Option<f64>) -> String {
    match b {
        Some(u) => num(u, 1),
        None => "<td>—</td>".to_string(),
    }
}

fn filter_cell(e: &Entry) -> String {
    match e.filter_figure() {
        f if f.is_finite() => num(f, 4),
        _ => "<td>not filterable</td>".to_string(),
    }
}

fn formats_text(e: &Entry) -> String {
    let names: Vec<String> = e.formats.iter().map(|f| f.label()).collect();
    names.join(", ")
}

/// The index's row of a spec.
fn index_row(e: &Entry) -> String {
    format!(
        "<tr data-spec=\"{id}\"><td><a href=\"family/{fam}.html#{id}\">{id}</a></td>{}{}{}{}{}{}{}{}{}{}</tr>",
        int(e.bits),
        text(&e.domain),
        num(e.mean, 5),
        num(e.max, 5),
        int(e.alu.encode),
        int(e.alu.decode),
        text(if e.portable { "yes" } else { "no" }),
        bound(e.bounds.decode),
        filter_cell(e),
        text(&formats_text(e)),
        id = escape(&e.spec),
        fam = escape(&e.family),
    )
}

/// The figure rows of a spec's section: a name and a value each.
fn figure_rows(e: &Entry, c: &Catalogue) -> Vec<String> {
    let row = |name: &str, cell: String| format!("<tr><th>{name}</th>{cell}</tr>");
    let over = match c.over {
        Some(_) => format!("{} vectors of your sample", c.samples),
        None => format!("{} vectors", c.samples),
    };
    let mut rows = vec![
        row("bits", int(e.bits)),
        row("domain", text(&e.domain)),
        row(&format!("mean error (°, {over})"), num(e.mean, 5)),
        row("sample max (°)", num(e.max, 5)),
        row("MSE", sci(e.mse, 4)),
    ];
    if let Some(p) = e.p99 {
        rows.push(row("99th percentile (°)", num(p, 5)));
    }
    rows.extend([
        row("encode ALU", int(e.alu.encode)),
        row("encode_float ALU", int(e.alu.encode_float)),
        row("decode ALU", int(e.alu.decode)),
        row("decode_float ALU", int(e.alu.decode_float)),
        row(
            "packed encoder",
            text(if e.portable {
                "portable: the same code on every conformant GPU"
            } else {
                "not portable"
            }),
        ),
        row("proven decode bound (2^-24)", bound(e.bounds.decode)),
        row(
            "proven decode_float bound (2^-24)",
            bound(e.bounds.decode_float),
        ),
        row(
            &format!("filtering p99 at {DECIDING_SEPARATION}° (°)"),
            filter_cell(e),
        ),
    ]);
    for f in &e.formats {
        let unused = match f.unused_channels {
            0 => String::new(),
            n => format!(" ({n} channel{} unused)", if n == 1 { "" } else { "s" }),
        };
        let how = match (f.exact, f.filterable) {
            (true, true) => "stores the values exactly; filterable",
            (true, false) => "stores the values exactly; not filterable",
            (false, true) => {
                "wider channels that round the fields' values (or a block format); filterable"
            }
            (false, false) => "wider channels that round the fields' values; not filterable",
        };
        let note = f
            .note
            .as_deref()
            .map_or(String::new(), |n| format!("; {n}"));
        rows.push(row(
            &format!("format ({})", f.holds.name()),
            text(&format!(
                "{}{unused}: {} bits a texel or vertex, {how}{note}",
                f.spellings().join(" · "),
                f.bits
            )),
        ));
    }
    rows
}

fn filter_rows(kind: &str, stats: &[FilterStats]) -> Vec<String> {
    stats
        .iter()
        .map(|s| {
            format!(
                "<tr>{}{}{}{}{}{}</tr>",
                num(s.separation, 0),
                text(kind),
                num(s.mean, 4),
                num(s.p99, 4),
                num(s.max, 4),
                num(s.over_1deg, 4),
            )
        })
        .collect()
}

/// Where a spec's float form breaks, when pairs of neighbours 1° apart err by more than
/// their separation.
fn seam(e: &Entry, spec: &Spec) -> String {
    let (Some(f), Some(at)) = (&e.filtering, spec.family().float_form(spec).seam()) else {
        return String::new();
    };
    let Some(near) = f
        .lerp
        .iter()
        .find(|s| s.separation == filtering::SEPARATIONS[0])
    else {
        return String::new();
    };
    if near.over_1deg == 0.0 {
        return String::new();
    }
    format!(
        "{:.2}% of pairs {}° apart err by more than 1° when filtered: {}.",
        near.over_1deg * 100.0,
        near.separation,
        at
    )
}

/// The WGSL and GLSL signatures of a spec's public functions.
fn signatures(spec: &Spec) -> String {
    let e = spec.emitted();
    let ns = if e.namespace.is_empty() {
        String::new()
    } else {
        format!("{}_", e.namespace)
    };
    let mut out = String::new();
    for lang in [Lang::Wgsl, Lang::Glsl] {
        let backend = lang.backend(crate::emit::DEFAULT_PREFIX);
        let name = |local: &str| format!("{}{ns}{local}", crate::emit::DEFAULT_PREFIX);
        for pf in &e.functions {
            let Some(f) = e.module.funcs.iter().find(|f| f.name == pf.name) else {
                continue;
            };
            let p = printer::print(backend.as_ref(), f, &name);
            let line = match lang {
                Lang::Wgsl => {
                    let params: Vec<String> =
                        p.params.iter().map(|(n, t)| format!("{n}: {t}")).collect();
                    format!("fn {}({}) -> {}", p.name, params.join(", "), p.ret_ty)
                }
                _ => {
                    let params: Vec<String> =
                        p.params.iter().map(|(n, t)| format!("{t} {n}")).collect();
                    format!("{} {}({})", p.ret_ty, p.name, params.join(", "))
                }
            };
            out.push_str(&line);
            out.push('\n');
        }
        out.push('\n');
    }
    out.trim_end().to_string()
}

/// The files of a report: path relative to its folder → bytes.
type Files = BTreeMap<PathBuf, Vec<u8>>;

fn png(px: (u32, u32, Vec<u8>)) -> Result<Vec<u8>> {
    crate::support::png_file::encode(px.0, px.1, png::ColorType::Rgb, png::BitDepth::Eight, &px.2)
}

/// A user's sample as the report shows it beside the figures the catalogue holds over it
/// ([`Catalogue::over`], [`Catalogue::frames_over`]): the file, where its vectors lie,
/// and why the frame figures stay the seeded ones where they do.
pub struct UserSample {
    /// The file as the user named it: the pages' `choose` commands name it.
    pub file: String,
    /// Its vectors' density maps, beside each spec's error maps.
    pub density: maps::Density,
    /// Why its frames are not measured (it holds none), in words.
    pub frames_seeded: Option<String>,
}

/// Every file of the report, with `progress` told of each spec measured; `sample`, a
/// user's sample whose figures the catalogue holds, adds its density maps and names it.
pub fn render(
    catalogue: &Catalogue,
    sample: Option<&UserSample>,
    progress: &(dyn Fn() + Sync),
) -> Result<Files> {
    let specs: Vec<Spec> = catalogue
        .specs
        .iter()
        .map(|e| {
            e.spec
                .parse::<Spec>()
                .with_context(|| format!("the catalogue's {} is not a spec", e.spec))
        })
        .collect::<Result<_>>()?;
    let measured = crate::support::par::map(&specs, |s| {
        let m = maps::measure(s);
        progress();
        m
    });
    let mut files = Files::new();
    files.insert(
        "style.css".into(),
        include_bytes!("../../templates/report/style.css").to_vec(),
    );
    files.insert(
        "check.js".into(),
        include_bytes!("../../templates/report/check.js").to_vec(),
    );
    files.insert(
        "table.js".into(),
        include_bytes!("../../templates/report/table.js").to_vec(),
    );
    files.insert("maps/legend.png".into(), png(maps::legend(256, 12))?);
    if let Some(d) = sample.map(|s| &s.density) {
        files.insert(
            "maps/sample_equirect.png".into(),
            png(maps::density_pixels(d, &d.equirect, SCALE))?,
        );
        files.insert(
            "maps/sample_octahedral.png".into(),
            png(maps::density_pixels(d, &d.octahedral, SCALE))?,
        );
    }

    let mut sections: BTreeMap<&str, Vec<SpecSection>> = BTreeMap::new();
    for ((e, spec), m) in catalogue.specs.iter().zip(&specs).zip(&measured) {
        let top = m.equirect.max().max(m.octahedral.max());
        files.insert(
            format!("maps/{}_equirect.png", e.spec).into(),
            png(maps::pixels(&m.equirect, SCALE))?,
        );
        files.insert(
            format!("maps/{}_octahedral.png", e.spec).into(),
            png(maps::pixels(&m.octahedral, SCALE))?,
        );
        let histogram = charts::histogram(
            &format!(
                "{}: error of {} seeded vectors",
                e.spec,
                maps::HISTOGRAM_SAMPLES
            ),
            &m.histogram,
        )?;
        let filtering = e.filtering.as_ref().map(|f| {
            let mut rows = filter_rows("lerp of two", &f.lerp);
            rows.extend(filter_rows("resolve of four", &f.resolve));
            rows
        });
        sections
            .entry(e.family.as_str())
            .or_default()
            .push(SpecSection {
                id: e.spec.clone(),
                figures: figure_rows(e, catalogue),
                top,
                top_text: format!("{top:.4}"),
                histogram,
                not_filterable: e.not_filterable.clone(),
                filtering,
                seam: seam(e, spec),
                signatures: signatures(spec),
            });
    }
    let mut links = Vec::new();
    for f in FAMILIES {
        let info = f.info();
        let Some(specs) = sections.remove(info.name) else {
            continue;
        };
        links.push(FamilyLink {
            name: info.name,
            title: info.title,
        });
        let page = FamilyPage {
            name: info.name,
            title: info.title,
            source: info.source,
            per_cell: maps::PER_CELL,
            equirect_w: maps::EQUIRECT.0 * SCALE * SHOWN,
            equirect_h: maps::EQUIRECT.1 * SCALE * SHOWN,
            oct_w: maps::OCTAHEDRAL * SCALE * SHOWN,
            scale_lo: charts::tick(maps::SCALE_DEGREES.0),
            scale_hi: charts::tick(maps::SCALE_DEGREES.1),
            sample: sample.and(catalogue.over.clone()),
            specs,
        };
        files.insert(
            format!("family/{}.html", info.name).into(),
            page.render()
                .context("cannot render a family page")?
                .into_bytes(),
        );
    }
    let winners = crate::choice::recommend::winners(catalogue);
    // A pick's command names the sample where its figures are over it, so that running it
    // gives the same answer.
    let picked = |c: &Case, w: Option<&Winner>| {
        let over = match c.query.use_case {
            Some(crate::choice::query::Use::Frame) => catalogue.frames_over.is_some(),
            _ => catalogue.over.is_some(),
        };
        pick_rows(c, w, sample.filter(|_| over).map(|s| s.file.as_str()))
    };
    let frames_over = match (&catalogue.frames_over, sample) {
        (Some(over), _) => over.clone(),
        (
            None,
            Some(UserSample {
                frames_seeded: Some(why),
                ..
            }),
        ) => format!(
            "{} seeded orthonormal frames, not over the sample: {why}",
            catalogue.frame_samples
        ),
        (None, _) => format!("{} seeded orthonormal frames", catalogue.frame_samples),
    };
    let frames = FramesPage {
        intro: format!(
            "Each tangent-frame spec stores a normal, a tangent and the bitangent's sign. \
             Errors are the angle between each decoded vector and its reference over \
             {frames_over}, mean and sample maximum (not a bound), in degrees; a flip is a \
             frame whose handedness changed. ALU: the packed encoder and decoder. Engine: \
             the engine that reads these bits as they are."
        ),
        ranking_note: "Frames are encoded offline and decoded per vertex: choose --use frame \
             ranks them by the worst sample max of normal, tangent and bitangent × (1 + \
             decode ALU/100), leaving out any that flips a handedness."
            .into(),
        picks: winners
            .iter()
            .filter(|(c, _)| c.query.use_case == Some(crate::choice::query::Use::Frame))
            .flat_map(|(c, w)| picked(c, w.as_ref()))
            .collect(),
        rows: catalogue.frames.iter().map(frame_row).collect(),
    };
    files.insert(
        "frames.html".into(),
        frames
            .render()
            .context("cannot render the frames page")?
            .into_bytes(),
    );
    // What the error figures are over: the seeded vectors, or the user's sample.
    let same_as = match catalogue.over {
        Some(_) => "`unitpack choose --sample FILE --limit 0 --json`",
        None => "`unitpack list --json`",
    };
    let (over, seeded) = match &catalogue.over {
        Some(sample) => (sample.clone(), sample.clone()),
        None => (
            format!("{} vectors", catalogue.samples),
            format!(
                "{} seeded unit vectors (seed {}; hemisphere codecs over +Z)",
                catalogue.samples, catalogue.vector_seed
            ),
        ),
    };
    let index = Index {
        picks_note: format!(
            "What unitpack choose --use USE ranks first for each use and size: each spec \
             stored as the use stores it, within the bits (a texel's, a vertex's or a \
             record's), scored as error × (1 + ALU/100) with the instructions the use runs \
             per pixel or vertex. Error: the round trip's sample max over {over}; \
             where the use filters, the worse of it and the filtering p99 at \
             {DECIDING_SEPARATION}° apart. The line under each says what decided it."
        ),
        picks: winners
            .iter()
            .flat_map(|(c, w)| picked(c, w.as_ref()))
            .collect(),
        intro: format!(
            "Every spec of the catalogue: round-trip angular error of the packed code over \
             {seeded}, the mean and the \
             sample maximum (the largest error of that sample, not a bound); ALU \
             instructions of the packed encoder and decoder; whether the packed encoder \
             is portable; the proven bound of the decoder; the formats each writes to. \
             The same figures as {same_as}."
        ),
        filtering_note: format!(
            "Filtering: the angle between a filtered texel's decoded direction and the \
             renormalized lerp of the decoded neighbours, over {} pairs per separation \
             (seed {}); p99 is the 99th percentile, at {DECIDING_SEPARATION}° apart \
             (the larger of a two-texel lerp and a four-sample resolve).",
            catalogue.filter_pairs, catalogue.filter_seed
        ),
        families: links,
        charts: index_charts(catalogue)?,
        deciding: DECIDING_SEPARATION,
        rows: catalogue.specs.iter().map(index_row).collect(),
    };
    files.insert(
        "index.html".into(),
        index
            .render()
            .context("cannot render the index")?
            .into_bytes(),
    );
    Ok(files)
}

/// A case's two rows in a table of picks: the first choice and, under it, why.
fn pick_rows(case: &Case, w: Option<&Winner>, sample: Option<&str>) -> Vec<String> {
    let mut args = case.args();
    if let Some(file) = sample {
        args.extend(["--sample".to_string(), shell_word(file)]);
    }
    let command = format!(
        "<td><code>unitpack choose {}</code></td>",
        escape(&args.join(" "))
    );
    let Some(w) = w else {
        return vec![format!(
            "<tr class=\"pick\">{}{command}<td colspan=\"4\">none</td></tr>",
            text(&case.what())
        )];
    };
    let page = if case.query.use_case == Some(crate::choice::query::Use::Frame) {
        "frames.html".to_string()
    } else {
        format!("family/{}.html", escape(&w.family))
    };
    vec![
        format!(
            "<tr class=\"pick\" data-spec=\"{id}\">{}{command}<td><a href=\"{page}#{id}\">{id}</a></td>{}{}{}</tr>",
            text(&case.what()),
            text(&w.stored),
            num(w.error, 4),
            text(&format!("{} / {}", w.encode, w.decode)),
            id = escape(&w.spec),
        ),
        format!(
            "<tr class=\"why\"><td colspan=\"6\">{}</td></tr>",
            escape(&w.why)
        ),
    ]
}

/// `word` as a POSIX shell reads it back: as it is where it holds only characters no
/// shell treats specially, else single-quoted.
fn shell_word(word: &str) -> String {
    let plain = |c: char| c.is_ascii_alphanumeric() || "_./-+=:,@%".contains(c);
    if !word.is_empty() && word.chars().all(plain) {
        word.to_string()
    } else {
        format!("'{}'", word.replace('\'', "'\\''"))
    }
}

/// The frames page's row of a frame spec.
fn frame_row(f: &crate::choice::catalogue::FrameEntry) -> String {
    format!(
        "<tr id=\"{id}\" data-spec=\"{id}\"><td>{id}</td>{}{}{}{}{}{}{}{}{}{}{}</tr>",
        int(f.bits),
        num(f.normal[0], 5),
        num(f.normal[1], 5),
        num(f.tangent[0], 5),
        num(f.tangent[1], 5),
        num(f.bitangent[0], 5),
        num(f.bitangent[1], 5),
        int(f.flips as u32),
        int(f.alu.encode),
        int(f.alu.decode),
        text(f.engine.as_deref().unwrap_or("—")),
        id = escape(&f.spec),
    )
}

/// The index's trade-off charts.
fn index_charts(c: &Catalogue) -> Result<Vec<String>> {
    let kinds = [
        ("sphere", charts::SPHERE),
        ("hemisphere", charts::HEMISPHERE),
    ];
    let by_domain = |f: &dyn Fn(&Entry) -> Option<(f64, f64)>| -> Vec<charts::Series> {
        kinds
            .into_iter()
            .map(|(d, colour)| charts::Series {
                name: d,
                colour,
                points: c
                    .specs
                    .iter()
                    .filter(|e| e.domain == d)
                    .filter_map(|e| f(e).map(|(x, y)| (x, y, e.spec.clone())))
                    .collect(),
            })
            .collect()
    };
    let legend = charts::legend_html(&kinds);
    let charts = [
        charts::scatter(
            "Mean error against bits",
            "bits",
            "mean error (degrees)",
            false,
            true,
            &by_domain(&|e| Some((f64::from(e.bits), e.mean))),
        )?,
        charts::scatter(
            "Sample max against bits",
            "bits",
            "sample max (degrees)",
            false,
            true,
            &by_domain(&|e| Some((f64::from(e.bits), e.max))),
        )?,
        charts::scatter(
            "Decode ALU against mean error",
            "mean error (degrees)",
            "decode ALU instructions",
            true,
            false,
            &by_domain(&|e| Some((e.mean, f64::from(e.alu.decode)))),
        )?,
        charts::scatter(
            "Encode ALU against mean error",
            "mean error (degrees)",
            "encode ALU instructions",
            true,
            true,
            &by_domain(&|e| Some((e.mean, f64::from(e.alu.encode)))),
        )?,
        charts::scatter(
            &format!("Filtering p99 at {DECIDING_SEPARATION}° against texel bits"),
            "bits a texel of the filterable format",
            "filtering p99 (degrees)",
            false,
            true,
            &by_domain(&|e| {
                let f = e.filter_figure();
                let texel = e.filterable_storage()?;
                f.is_finite().then(|| (f64::from(texel.bits), f.max(1e-6)))
            }),
        )?,
    ];
    Ok(charts
        .into_iter()
        .map(|svg| format!("{svg}{legend}"))
        .collect())
}

/// Writes `files` into `dir` under the folder policy above. Returns how many files it
/// wrote.
pub fn write(dir: &Path, files: &Files) -> Result<usize> {
    let manifest = dir.join(MANIFEST);
    let listed: Vec<PathBuf> = match std::fs::read_to_string(&manifest) {
        Ok(t) => t.lines().skip(1).map(PathBuf::from).collect(),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            match std::fs::read_dir(dir) {
                Ok(mut entries) => {
                    if entries.next().is_some() {
                        bail!(
                            "{} is not empty and holds no earlier report ({MANIFEST}): name a new or empty folder",
                            dir.display()
                        );
                    }
                }
                Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
                Err(e) => {
                    return Err(e).with_context(|| format!("cannot read {}", dir.display()));
                }
            }
            Vec::new()
        }
        Err(e) => return Err(e).with_context(|| format!("cannot read {}", manifest.display())),
    };
    for rel in files.keys() {
        let path = dir.join(rel);
        if path.symlink_metadata().is_ok() && !listed.contains(rel) {
            bail!(
                "{} exists and an earlier report did not write it: nothing was written",
                path.display()
            );
        }
    }
    for (rel, bytes) in files {
        let path = dir.join(rel);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent)
                .with_context(|| format!("cannot create {}", parent.display()))?;
        }
        // Unchanged files are left as they are.
        if std::fs::read(&path).is_ok_and(|old| old == *bytes) {
            continue;
        }
        crate::support::atomic::write_atomic(&path, bytes)?;
    }
    let mut text = String::from("# Files written by `unitpack report`.\n");
    for rel in files.keys() {
        text.push_str(&format!("{}\n", rel.display()));
    }
    crate::support::atomic::write_atomic(&manifest, text.as_bytes())?;
    Ok(files.len())
}
