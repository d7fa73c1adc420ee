//! The storage formats a spec's code or float form is written to, by their API names.
//!
//! Derived from the spec, never restated: the packed code's width gives the integer
//! formats that hold it, and the float form's fields (the `Quant`s its `decode_float`
//! reads, as a texture fetch or vertex fetch delivers them) give the normalized or float
//! format whose conversion is exactly the field's (`Snorm(b)`: `max(c/M, -1)`, which is
//! what every API's snorm conversion computes; `Unorm(b)`: `c/M`). A float form whose
//! fields have no format of their own (two snorm12 fields, say) is written through its
//! packed code only. A texel layout's RGBA8 texel also names the block-compressed
//! formats the layout is made for.

use crate::codecs::Spec;
use crate::codecs::functions::function::{Emitted, Inputs, Role};
use crate::codecs::toolkit::quant::Quant;
use serde::{Deserialize, Serialize};

/// What a format holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Holds {
    /// The packed code, as unsigned integer words.
    Code,
    /// The float form: what `encode_float` writes and `decode_float` reads.
    FloatForm,
}

impl Holds {
    pub fn name(self) -> &'static str {
        match self {
            Holds::Code => "code",
            Holds::FloatForm => "float form",
        }
    }
}

/// One format, in each API's spelling.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Format {
    /// WebGPU's texture format (`rg8snorm`), where WebGPU has one.
    pub texture: Option<String>,
    /// WebGPU's vertex format (`snorm8x2`), where there is one.
    pub vertex: Option<String>,
    /// Vulkan's `VkFormat`.
    pub vulkan: String,
    /// Direct3D's `DXGI_FORMAT`, where there is one.
    pub dxgi: Option<String>,
    pub holds: Holds,
    /// Channels the spec leaves unused (an RGB float form in an RGBA format), for the
    /// reader.
    pub unused_channels: u32,
}

impl Format {
    /// The name it is listed by: WebGPU's texture name, else its vertex name, else
    /// Vulkan's.
    pub fn name(&self) -> &str {
        self.texture
            .as_deref()
            .or(self.vertex.as_deref())
            .unwrap_or(&self.vulkan)
    }

    /// Every spelling: WebGPU texture and vertex, Vulkan, DXGI.
    pub fn spellings(&self) -> Vec<&str> {
        [
            self.texture.as_deref(),
            self.vertex.as_deref(),
            Some(self.vulkan.as_str()),
            self.dxgi.as_deref(),
        ]
        .into_iter()
        .flatten()
        .collect()
    }

    /// Whether a user's `--format` names this format: any spelling, case ignored, with
    /// or without Vulkan's `VK_FORMAT_` and DXGI's `DXGI_FORMAT_` prefix.
    pub fn matches(&self, query: &str) -> bool {
        let q = query.trim().to_ascii_uppercase();
        self.spellings().iter().any(|s| {
            let s = s.to_ascii_uppercase();
            s == q
                || s.strip_prefix("VK_FORMAT_") == Some(q.as_str())
                || s.strip_prefix("DXGI_FORMAT_") == Some(q.as_str())
        })
    }
}

/// A row of the format table: texture, vertex, Vulkan, DXGI.
type Row = (
    Option<&'static str>,
    Option<&'static str>,
    &'static str,
    Option<&'static str>,
);

/// The formats of `n` channels of one field type: (channels the format has, its row).
fn uniform_fields(q: Quant, n: usize) -> Option<(usize, Row)> {
    use Quant::*;
    let row: Row = match (q, n) {
        (Snorm(8), 2) => (
            Some("rg8snorm"),
            Some("snorm8x2"),
            "VK_FORMAT_R8G8_SNORM",
            Some("DXGI_FORMAT_R8G8_SNORM"),
        ),
        (Snorm(8), 3 | 4) => (
            Some("rgba8snorm"),
            Some("snorm8x4"),
            "VK_FORMAT_R8G8B8A8_SNORM",
            Some("DXGI_FORMAT_R8G8B8A8_SNORM"),
        ),
        (Unorm(8), 2) => (
            Some("rg8unorm"),
            Some("unorm8x2"),
            "VK_FORMAT_R8G8_UNORM",
            Some("DXGI_FORMAT_R8G8_UNORM"),
        ),
        (Unorm(8), 3 | 4) => (
            Some("rgba8unorm"),
            Some("unorm8x4"),
            "VK_FORMAT_R8G8B8A8_UNORM",
            Some("DXGI_FORMAT_R8G8B8A8_UNORM"),
        ),
        (Snorm(16), 2) => (
            Some("rg16snorm"),
            Some("snorm16x2"),
            "VK_FORMAT_R16G16_SNORM",
            Some("DXGI_FORMAT_R16G16_SNORM"),
        ),
        (Snorm(16), 3 | 4) => (
            Some("rgba16snorm"),
            Some("snorm16x4"),
            "VK_FORMAT_R16G16B16A16_SNORM",
            Some("DXGI_FORMAT_R16G16B16A16_SNORM"),
        ),
        (Unorm(16), 2) => (
            Some("rg16unorm"),
            Some("unorm16x2"),
            "VK_FORMAT_R16G16_UNORM",
            Some("DXGI_FORMAT_R16G16_UNORM"),
        ),
        (Unorm(16), 3 | 4) => (
            Some("rgba16unorm"),
            Some("unorm16x4"),
            "VK_FORMAT_R16G16B16A16_UNORM",
            Some("DXGI_FORMAT_R16G16B16A16_UNORM"),
        ),
        (Half, 2) => (
            Some("rg16float"),
            Some("float16x2"),
            "VK_FORMAT_R16G16_SFLOAT",
            Some("DXGI_FORMAT_R16G16_FLOAT"),
        ),
        (Half, 3 | 4) => (
            Some("rgba16float"),
            Some("float16x4"),
            "VK_FORMAT_R16G16B16A16_SFLOAT",
            Some("DXGI_FORMAT_R16G16B16A16_FLOAT"),
        ),
        (Single, 2) => (
            Some("rg32float"),
            Some("float32x2"),
            "VK_FORMAT_R32G32_SFLOAT",
            Some("DXGI_FORMAT_R32G32_FLOAT"),
        ),
        (Single, 3) => (
            None,
            Some("float32x3"),
            "VK_FORMAT_R32G32B32_SFLOAT",
            Some("DXGI_FORMAT_R32G32B32_FLOAT"),
        ),
        _ => return None,
    };
    let channels = if n == 3 && row.0.is_some() { 4 } else { n };
    Some((channels, row))
}

/// The integer formats of a code of `bits` in `words` 32-bit words.
fn code_formats(bits: u32, words: usize) -> Vec<Row> {
    match (words, bits) {
        (1, 0..=8) => vec![(
            Some("r8uint"),
            Some("uint8"),
            "VK_FORMAT_R8_UINT",
            Some("DXGI_FORMAT_R8_UINT"),
        )],
        (1, 9..=16) => vec![(
            Some("r16uint"),
            Some("uint16"),
            "VK_FORMAT_R16_UINT",
            Some("DXGI_FORMAT_R16_UINT"),
        )],
        (1, _) => vec![(
            Some("r32uint"),
            Some("uint32"),
            "VK_FORMAT_R32_UINT",
            Some("DXGI_FORMAT_R32_UINT"),
        )],
        (2, _) => vec![(
            Some("rg32uint"),
            Some("uint32x2"),
            "VK_FORMAT_R32G32_UINT",
            Some("DXGI_FORMAT_R32G32_UINT"),
        )],
        _ => vec![(
            None,
            Some("uint32x3"),
            "VK_FORMAT_R32G32B32_UINT",
            Some("DXGI_FORMAT_R32G32B32_UINT"),
        )],
    }
}

/// The block-compressed formats a texel layout (`layout=` option) is made for.
fn block_formats(layout: &str) -> Vec<Row> {
    let bc1 = (
        Some("bc1-rgba-unorm"),
        None,
        "VK_FORMAT_BC1_RGBA_UNORM_BLOCK",
        Some("DXGI_FORMAT_BC1_UNORM"),
    );
    let bc3 = (
        Some("bc3-rgba-unorm"),
        None,
        "VK_FORMAT_BC3_UNORM_BLOCK",
        Some("DXGI_FORMAT_BC3_UNORM"),
    );
    let bc5 = (
        Some("bc5-rg-unorm"),
        None,
        "VK_FORMAT_BC5_UNORM_BLOCK",
        Some("DXGI_FORMAT_BC5_UNORM"),
    );
    match layout {
        "rg" => vec![bc5],
        "dxt5nm" | "rxgb" => vec![bc3],
        "xra" => vec![bc1, bc3],
        // Luminance–alpha: BC5's two channels sampled through an LA swizzle.
        "latc" => vec![bc5],
        _ => vec![],
    }
}

/// The `layout=` option's value of a spec, if it has one.
fn layout(spec: &Spec) -> Option<String> {
    let text = spec.to_string();
    let (_, options) = text.split_once(':')?;
    options
        .split(',')
        .find_map(|o| o.strip_prefix("layout="))
        .map(str::to_string)
}

/// Every format `spec`'s code and float form are written to ([`Emitted`] is the spec's
/// traced functions): the code's first, then the float form's.
pub fn formats(spec: &Spec, e: &Emitted) -> Vec<Format> {
    let make = |(texture, vertex, vulkan, dxgi): Row, holds, unused| Format {
        texture: texture.map(str::to_string),
        vertex: vertex.map(str::to_string),
        vulkan: vulkan.to_string(),
        dxgi: dxgi.map(str::to_string),
        holds,
        unused_channels: unused,
    };
    let mut out = Vec::new();
    if let Some(enc) = e.functions.iter().find(|f| f.role == Role::Encode) {
        for row in code_formats(spec.bits(), enc.out_words) {
            out.push(make(row, Holds::Code, 0));
        }
    }
    let float_fields = e
        .functions
        .iter()
        .find(|f| f.role == Role::DecodeFloat)
        .and_then(|f| match &f.inputs {
            Inputs::FloatCodes(q) => Some(q.clone()),
            _ => None,
        });
    if let Some(q) = float_fields
        && let Some(first) = q.first()
        && q.iter().all(|f| f == first)
        && let Some((channels, row)) = uniform_fields(*first, q.len())
    {
        out.push(make(row, Holds::FloatForm, (channels - q.len()) as u32));
        if let Some(l) = layout(spec) {
            for row in block_formats(&l) {
                out.push(make(row, Holds::FloatForm, 0));
            }
        }
    }
    out
}
