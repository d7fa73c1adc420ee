//! `convert-normal-map`: a tangent-space normal map between its conventional form (RGB8 or
//! RGB16, each component stored `n·½ + ½`) and a texel layout (`xy16:layout=dxt5nm`, …),
//! through the same CPU encoder and decoder the emitted shaders are verified against, so
//! a map converted here decodes in the shader to what `unitpack decode` prints.

use super::output;
use crate::api::Batch;
use crate::codecs::functions::function::Function;
use crate::codecs::{Spec, core::texel};
use crate::support::atomic::write_atomic_with;
use crate::support::png_file::{self, Picture};
use anyhow::{Context, Result, bail};
use indicatif::{ProgressBar, ProgressStyle};
use png::{BitDepth, ColorType};
use std::io::Write;
use std::path::Path;

/// Which way a map is converted.
pub enum Direction<'a> {
    /// Conventional map in, texels of the spec out (xra's DXT1 texel where set).
    To(&'a str, bool),
    /// Texels of the spec in, conventional map out, at 16 bits per channel (else 8).
    From(&'a str, bool),
}

/// Rows per step: the progress bar moves once per step, and a step is a batch for the
/// CPU encoder's four-lane evaluation.
const ROWS_PER_STEP: usize = 16;

/// Maps of at least this many texels show a progress bar (on a terminal).
const PROGRESS_TEXELS: usize = 1 << 20;

pub fn run(input: &Path, output: &Path, dir: Direction, force: bool) -> Result<()> {
    let to_stdout = output::is_stdout(output);
    if !to_stdout {
        check_output(input, output, force)?;
    }
    let spec_text = match dir {
        Direction::To(s, _) | Direction::From(s, _) => s,
    };
    let spec: Spec = spec_text.parse()?;
    if texel::layout(&spec).is_none() {
        bail!(
            "{spec} does not store a texel: write a texel layout, NAME16:layout=rg|dxt5nm|rxgb|latc|xra \
             (or the id, e.g. xy16_dxt5nm) with NAME one of xy, xy_stereo, hemioct, paraboloid, \
             paraboloid_square (p for the precise encoder)"
        );
    }
    let image = png_file::read(input)?;
    let png = match dir {
        Direction::To(_, dxt1) => {
            let name = if dxt1 { "encode_dxt1" } else { "encode" };
            let Some(encode) = spec
                .emitted()
                .functions
                .iter()
                .find(|f| f.name == name)
                .cloned()
            else {
                bail!("{spec} has one texel form; --dxt1 is for the xra layout");
            };
            encode_map(&image, &encode, input)?
        }
        Direction::From(_, sixteen) => decode_map(&image, &Batch::new(spec_text)?, input, sixteen)?,
    };
    if to_stdout {
        let mut out = output::stdout();
        return out
            .write_all(&png)
            .and_then(|()| out.flush())
            .context("cannot write to stdout");
    }
    Ok(write_atomic_with(output, &png, force)?)
}

/// Refuses an OUT that is not a `.png`, that is IN, or that exists (without `force`):
/// swapped arguments cannot destroy a map.
fn check_output(input: &Path, output: &Path, force: bool) -> Result<()> {
    if output
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        != Some("png".into())
    {
        bail!("{}: the output must be a .png file", output.display());
    }
    if same_file(input, output) {
        bail!(
            "{} is both the input and the output; write the converted map elsewhere",
            output.display()
        );
    }
    if output.exists() && !force {
        bail!(
            "{} exists; pass --force to replace it (IN and OUT may have been swapped)",
            output.display()
        );
    }
    Ok(())
}

/// Whether two paths name one existing file (the output would replace the input).
pub(super) fn same_file(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    }
}

/// The conventional map's vectors, row by row: `2c/M - 1` per component (the
/// encoder normalizes them), from 8- or 16-bit RGB; an alpha channel is not part of a
/// normal and is left out.
pub(super) fn conventional_vectors(image: &Picture, input: &Path) -> Result<Vec<[f32; 3]>> {
    let channels = match image.color {
        ColorType::Rgb => 3,
        ColorType::Rgba => 4,
        _ => bail!(
            "{} is {}: a normal map is RGB8 or RGB16 (each component n·½ + ½)",
            input.display(),
            image.kind()
        ),
    };
    let max = if image.depth == BitDepth::Sixteen {
        65535
    } else {
        255
    };
    let samples = image.samples();
    let pixels = || samples.chunks_exact(channels);
    if let Some(pattern) = texel_pattern(pixels(), max) {
        bail!(
            "{} looks like a map of texels, not a conventional normal map: {pattern}, so \
             its RGB are not normals; convert texels to a normal map with --from SPEC",
            input.display()
        );
    }
    let unit = |c: u32| (2.0 * f64::from(c) / f64::from(max) - 1.0) as f32;
    Ok(pixels()
        .map(|p| [unit(p[0]), unit(p[1]), unit(p[2])])
        .collect())
}

/// How a map's channels show that it holds the texels of a two-parameter layout (what
/// `--to` writes) rather than `n·½ + ½`, if they do: no map of normals has these in every
/// texel, since each would make every normal point into the surface (B = 0), lie along
/// +X (R = 1) or along the diagonal (R = G = B). The alpha channel, where dxt5nm, rxgb,
/// latc and xra keep x, is not read as part of a normal, so without this check such a map
/// would convert without a word into nonsense.
fn texel_pattern<'a>(
    mut pixels: impl Iterator<Item = &'a [u32]> + Clone,
    max: u32,
) -> Option<&'static str> {
    // An empty map shows no pattern (`all` would hold for each).
    pixels.clone().next()?;
    if pixels.clone().all(|p| p[2] == 0) {
        Some(
            "B = 0 in every texel (a normal pointing into the surface), as the rg, dxt5nm and xra layouts store texels",
        )
    } else if pixels.clone().all(|p| p[0] == max) {
        Some("R = 1 in every texel (a normal along +X), as the rxgb layout stores texels")
    } else if pixels.all(|p| p[0] == p[1] && p[1] == p[2]) {
        Some("R = G = B in every texel, as the latc layout stores texels")
    } else {
        None
    }
}

fn encode_map(image: &Picture, encode: &Function, input: &Path) -> Result<Vec<u8>> {
    let vectors = conventional_vectors(image, input)?;
    let (w, h) = (image.width, image.height);
    let mut texels = vec![0u32; vectors.len()];
    let step = ROWS_PER_STEP * w as usize;
    let bar = progress(vectors.len(), "encoding");
    for (v, t) in vectors
        .chunks(step.max(1))
        .zip(texels.chunks_mut(step.max(1)))
    {
        encode.eval_many(bytemuck::cast_slice(v), t);
        bar.inc(v.len() as u64);
    }
    bar.finish_and_clear();
    let bytes: Vec<u8> = texels.iter().flat_map(|t| t.to_le_bytes()).collect();
    png_file::encode(w, h, ColorType::Rgba, BitDepth::Eight, &bytes)
}

fn decode_map(image: &Picture, batch: &Batch, input: &Path, sixteen: bool) -> Result<Vec<u8>> {
    if (image.color, image.depth) != (ColorType::Rgba, BitDepth::Eight) {
        bail!(
            "{} is {}: a map of texels is RGBA8 (the layout's four channels)",
            input.display(),
            image.kind()
        );
    }
    let (w, h) = (image.width, image.height);
    let codes: Vec<u32> = image
        .data
        .chunks_exact(4)
        .map(|p| u32::from_le_bytes([p[0], p[1], p[2], p[3]]))
        .collect();
    let mut vectors = vec![[0f32; 3]; codes.len()];
    let step = (ROWS_PER_STEP * w as usize).max(1);
    let bar = progress(codes.len(), "decoding");
    for (c, v) in codes.chunks(step).zip(vectors.chunks_mut(step)) {
        batch.decode(c, v);
        bar.inc(c.len() as u64);
    }
    bar.finish_and_clear();
    // n·½ + ½, rounded to the nearest code (a decoded component is within [-1, 1] up to
    // rounding; xy's decoders can return vectors longer than 1 outside the unit disk).
    let code = |x: f32, m: f64| ((f64::from(x) * 0.5 + 0.5).clamp(0.0, 1.0) * m).round();
    let components = vectors.iter().flatten();
    if sixteen {
        let data: Vec<u8> = components
            .flat_map(|&x| (code(x, 65535.0) as u16).to_be_bytes())
            .collect();
        png_file::encode(w, h, ColorType::Rgb, BitDepth::Sixteen, &data)
    } else {
        let data: Vec<u8> = components.map(|&x| code(x, 255.0) as u8).collect();
        png_file::encode(w, h, ColorType::Rgb, BitDepth::Eight, &data)
    }
}

/// A progress bar on stderr for large maps (hidden where stderr is not a terminal).
fn progress(texels: usize, what: &'static str) -> ProgressBar {
    if texels < PROGRESS_TEXELS {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(texels as u64);
    bar.set_style(
        ProgressStyle::with_template("{msg} {wide_bar} {pos}/{len} texels")
            .expect("a valid template"),
    );
    bar.set_message(what);
    bar
}
