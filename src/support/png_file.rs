//! PNG files in and out through the `png` crate: the normal maps `convert-normal-map`
//! reads and writes and the tables `generate` writes. Only 8- and 16-bit samples are
//! wanted; palettes and lower depths are expanded to 8 bits on reading.

use anyhow::{Context, Result};
use png::{BitDepth, ColorType};
use std::io::BufReader;
use std::path::Path;

/// A decoded image: samples row by row, 16-bit samples big-endian (as PNG stores them).
pub struct Picture {
    pub width: u32,
    pub height: u32,
    pub color: ColorType,
    pub depth: BitDepth,
    pub data: Vec<u8>,
}

impl Picture {
    /// What the image is, as error messages name it: `RGB8`, `L16`, `RGBA8`, … (the
    /// spelling of the help text and of texture formats, not the `png` crate's `Rgb`).
    pub fn kind(&self) -> String {
        let channels = match self.color {
            ColorType::Grayscale => "L",
            ColorType::GrayscaleAlpha => "LA",
            ColorType::Rgb => "RGB",
            ColorType::Rgba => "RGBA",
            ColorType::Indexed => "indexed ",
        };
        format!("{channels}{}", self.depth as u8)
    }

    /// Each sample as an integer, row by row (16-bit samples read big-endian).
    pub fn samples(&self) -> Vec<u32> {
        match self.depth {
            BitDepth::Sixteen => self
                .data
                .chunks_exact(2)
                .map(|b| u32::from(u16::from_be_bytes([b[0], b[1]])))
                .collect(),
            _ => self.data.iter().map(|&b| u32::from(b)).collect(),
        }
    }
}

/// Reads the PNG at `path`, expanding palettes and sub-byte depths to 8 bits.
pub fn read(path: &Path) -> Result<Picture> {
    let file =
        std::fs::File::open(path).with_context(|| format!("cannot read {}", path.display()))?;
    let mut decoder = png::Decoder::new(BufReader::new(file));
    decoder.set_transformations(png::Transformations::EXPAND);
    let undecodable = || format!("cannot decode {} as a PNG image", path.display());
    let mut reader = decoder.read_info().with_context(undecodable)?;
    let size = reader.output_buffer_size().with_context(undecodable)?;
    let mut data = vec![0; size];
    let info = reader.next_frame(&mut data).with_context(undecodable)?;
    data.truncate(info.buffer_size());
    Ok(Picture {
        width: info.width,
        height: info.height,
        color: info.color_type,
        depth: info.bit_depth,
        data,
    })
}

/// `data` (row by row, 16-bit samples big-endian) as PNG bytes: fast deflate and the
/// adaptive filter, fixed settings so that the same pixels give the same bytes.
pub fn encode(
    width: u32,
    height: u32,
    color: ColorType,
    depth: BitDepth,
    data: &[u8],
) -> Result<Vec<u8>> {
    let mut out = Vec::new();
    let mut encoder = png::Encoder::new(&mut out, width, height);
    encoder.set_color(color);
    encoder.set_depth(depth);
    encoder.set_compression(png::Compression::Fast);
    encoder.set_filter(png::Filter::Adaptive);
    let mut writer = encoder.write_header().context("cannot encode the PNG")?;
    writer
        .write_image_data(data)
        .context("cannot encode the PNG")?;
    writer.finish().context("cannot encode the PNG")?;
    Ok(out)
}
