//! Where a spec's code and float form are stored: formats real APIs have, each with what
//! it costs a texel or a vertex and whether a texture unit filters it.
//!
//! Derived from the spec, never restated: the packed code's width gives the integer
//! format that holds it, and the float form's fields (the `Quant`s its `decode_float`
//! reads) give the normalized or float format that holds them. A format *holds* a field
//! when its channel has at least the field's precision and sign (a unorm field in a snorm
//! channel needs one bit more); it holds it *exactly* when the channel's conversion
//! returns the field's own values (`c/M` of a b-bit unorm field survives a k-bit unorm
//! channel exactly when b divides k: `2^b - 1` divides `2^k - 1`). The float form's format
//! is the smallest format that holds its fields exactly, or else the smallest that holds
//! them at all — wider than the code (`eqdist16`'s unorm8, unorm7, unorm1 fields: no
//! 16-bit format has them, `rgba8unorm` does at 32 bits, rounding the unorm7 field's
//! values to its 8-bit channel). A texel layout's RGBA8 texel also names the
//! block-compressed formats the layout is made for.
//!
//! The table is the formats every one of WebGPU, Vulkan, Direct3D and OpenGL has, or the
//! vertex formats where a format has no texture form; [`Real::note`] says where an API
//! has a format only as an option.

use crate::codecs::core::spec::Spec;
use crate::codecs::core::texel::{self, Layout};
use crate::codecs::functions::function::{Emitted, Inputs, Role};
use crate::codecs::toolkit::quant::Quant;

/// What a format holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "cli", serde(rename_all = "snake_case"))]
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

/// One channel of a real format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "cli", serde(rename_all = "snake_case"))]
pub enum Channel {
    /// `k` bits, read as `c/(2^k - 1)`.
    Unorm(u32),
    /// `k` bits two's complement, read as `max(c/(2^(k-1) - 1), -1)`.
    Snorm(u32),
    /// IEEE binary16.
    Float16,
    /// IEEE binary32.
    Float32,
    /// `k` bits, read as the integer.
    Uint(u32),
    /// A block-compressed unorm channel: lossy, its precision the block's.
    Block,
}

impl Channel {
    /// Whether this channel holds `field` at its precision, and whether exactly.
    fn holds(self, field: Quant) -> Option<bool> {
        match (field, self) {
            (Quant::Unorm(b), Channel::Unorm(k)) if b <= k => Some(k % b == 0),
            (Quant::Unorm(b), Channel::Snorm(k)) if b < k => Some((k - 1) % b == 0),
            (Quant::Snorm(b), Channel::Snorm(k)) if b <= k => Some((k - 1) % (b - 1) == 0),
            (Quant::Half, Channel::Float16 | Channel::Float32) => Some(true),
            (Quant::Single, Channel::Float32) => Some(true),
            _ => None,
        }
    }

    /// The value a fetch of this channel returns after a render target stored `x`: the
    /// API's conversion to the channel (round to nearest, ties to even, after the clamp to
    /// its range, decided in f64), read back as the model reads a fetched field
    /// (`c·(1/M)` in f32, [`Quant::dequantize`]) so that a value a field already holds
    /// exactly comes back bit for bit.
    pub fn store(self, x: f32) -> f32 {
        let norm = |q: Quant, lo: f64| {
            // NaN stores as zero, as Direct3D's conversion rules say.
            let v = if x.is_nan() { 0.0 } else { f64::from(x) };
            let c = (v.clamp(lo, 1.0) * f64::from(q.max_code())).round_ties_even();
            q.dequantize(c as f32)
        };
        match self {
            Channel::Unorm(k) => norm(Quant::Unorm(k), 0.0),
            Channel::Snorm(k) => norm(Quant::Snorm(k), -1.0),
            Channel::Float16 => {
                use crate::codecs::toolkit::half::{half_bits, half_value};
                half_value::<f32>(half_bits(x))
            }
            Channel::Float32 | Channel::Uint(_) | Channel::Block => x,
        }
    }
}

/// One format of the table, in each API's spelling.
#[derive(Clone, Copy, Debug)]
pub struct Real {
    /// WebGPU's texture format, where WebGPU has one.
    pub texture: Option<&'static str>,
    /// WebGPU's vertex format, where there is one.
    pub vertex: Option<&'static str>,
    pub vulkan: &'static str,
    pub dxgi: Option<&'static str>,
    /// OpenGL's sized internal format.
    pub gl: Option<&'static str>,
    pub channels: &'static [Channel],
    /// Bits a texel (a block's bits over its 16 texels) or a vertex attribute costs.
    pub bits: u32,
    /// Whether every API that has it as a texture filters it linearly.
    pub filterable: bool,
    /// Where an API has it only as an option.
    pub note: Option<&'static str>,
}

const NORM16_NOTE: &str =
    "WebGPU only with the texture-formats-tier1 feature, OpenGL ES only with EXT_texture_norm16";

macro_rules! real {
    ($tex:expr, $vtx:expr, $vk:literal, $dx:expr, $gl:expr, [$($c:expr),*], $bits:literal, $filt:literal, $note:expr) => {
        Real {
            texture: $tex,
            vertex: $vtx,
            vulkan: $vk,
            dxgi: $dx,
            gl: $gl,
            channels: &[$($c),*],
            bits: $bits,
            filterable: $filt,
            note: $note,
        }
    };
}

use Channel::{Block as B, Float16 as H, Float32 as S, Snorm as Sn, Uint as U, Unorm as Un};

/// The normalized and float formats a float form may be stored in, in order of
/// preference among formats of the same size.
#[rustfmt::skip]
pub const FLOAT_FORMATS: &[Real] = &[
    real!(Some("r8unorm"), Some("unorm8"), "VK_FORMAT_R8_UNORM", Some("DXGI_FORMAT_R8_UNORM"), Some("GL_R8"), [Un(8)], 8, true, None),
    real!(Some("r8snorm"), Some("snorm8"), "VK_FORMAT_R8_SNORM", Some("DXGI_FORMAT_R8_SNORM"), Some("GL_R8_SNORM"), [Sn(8)], 8, true, None),
    real!(Some("rg8unorm"), Some("unorm8x2"), "VK_FORMAT_R8G8_UNORM", Some("DXGI_FORMAT_R8G8_UNORM"), Some("GL_RG8"), [Un(8), Un(8)], 16, true, None),
    real!(Some("rg8snorm"), Some("snorm8x2"), "VK_FORMAT_R8G8_SNORM", Some("DXGI_FORMAT_R8G8_SNORM"), Some("GL_RG8_SNORM"), [Sn(8), Sn(8)], 16, true, None),
    real!(Some("r16unorm"), Some("unorm16"), "VK_FORMAT_R16_UNORM", Some("DXGI_FORMAT_R16_UNORM"), Some("GL_R16"), [Un(16)], 16, true, Some(NORM16_NOTE)),
    real!(Some("r16snorm"), Some("snorm16"), "VK_FORMAT_R16_SNORM", Some("DXGI_FORMAT_R16_SNORM"), Some("GL_R16_SNORM"), [Sn(16)], 16, true, Some(NORM16_NOTE)),
    real!(Some("r16float"), Some("float16"), "VK_FORMAT_R16_SFLOAT", Some("DXGI_FORMAT_R16_FLOAT"), Some("GL_R16F"), [H], 16, true, None),
    real!(Some("rgba8unorm"), Some("unorm8x4"), "VK_FORMAT_R8G8B8A8_UNORM", Some("DXGI_FORMAT_R8G8B8A8_UNORM"), Some("GL_RGBA8"), [Un(8), Un(8), Un(8), Un(8)], 32, true, None),
    real!(Some("rgba8snorm"), Some("snorm8x4"), "VK_FORMAT_R8G8B8A8_SNORM", Some("DXGI_FORMAT_R8G8B8A8_SNORM"), Some("GL_RGBA8_SNORM"), [Sn(8), Sn(8), Sn(8), Sn(8)], 32, true, None),
    real!(Some("rgb10a2unorm"), Some("unorm10-10-10-2"), "VK_FORMAT_A2B10G10R10_UNORM_PACK32", Some("DXGI_FORMAT_R10G10B10A2_UNORM"), Some("GL_RGB10_A2"), [Un(10), Un(10), Un(10), Un(2)], 32, true, None),
    real!(Some("rg16unorm"), Some("unorm16x2"), "VK_FORMAT_R16G16_UNORM", Some("DXGI_FORMAT_R16G16_UNORM"), Some("GL_RG16"), [Un(16), Un(16)], 32, true, Some(NORM16_NOTE)),
    real!(Some("rg16snorm"), Some("snorm16x2"), "VK_FORMAT_R16G16_SNORM", Some("DXGI_FORMAT_R16G16_SNORM"), Some("GL_RG16_SNORM"), [Sn(16), Sn(16)], 32, true, Some(NORM16_NOTE)),
    real!(Some("rg16float"), Some("float16x2"), "VK_FORMAT_R16G16_SFLOAT", Some("DXGI_FORMAT_R16G16_FLOAT"), Some("GL_RG16F"), [H, H], 32, true, None),
    real!(Some("rgba16unorm"), Some("unorm16x4"), "VK_FORMAT_R16G16B16A16_UNORM", Some("DXGI_FORMAT_R16G16B16A16_UNORM"), Some("GL_RGBA16"), [Un(16), Un(16), Un(16), Un(16)], 64, true, Some(NORM16_NOTE)),
    real!(Some("rgba16snorm"), Some("snorm16x4"), "VK_FORMAT_R16G16B16A16_SNORM", Some("DXGI_FORMAT_R16G16B16A16_SNORM"), Some("GL_RGBA16_SNORM"), [Sn(16), Sn(16), Sn(16), Sn(16)], 64, true, Some(NORM16_NOTE)),
    real!(Some("rgba16float"), Some("float16x4"), "VK_FORMAT_R16G16B16A16_SFLOAT", Some("DXGI_FORMAT_R16G16B16A16_FLOAT"), Some("GL_RGBA16F"), [H, H, H, H], 64, true, None),
    real!(Some("rg32float"), Some("float32x2"), "VK_FORMAT_R32G32_SFLOAT", Some("DXGI_FORMAT_R32G32_FLOAT"), Some("GL_RG32F"), [S, S], 64, false, Some("filtered only where the API's optional float32 filtering is supported (WebGPU's float32-filterable feature)")),
    real!(None, Some("float32x3"), "VK_FORMAT_R32G32B32_SFLOAT", Some("DXGI_FORMAT_R32G32B32_FLOAT"), Some("GL_RGB32F"), [S, S, S], 96, false, Some(VERTEX_ONLY_NOTE)),
];

/// The integer formats a packed code is stored in, smallest first.
#[rustfmt::skip]
const CODE_FORMATS: &[Real] = &[
    real!(Some("r8uint"), Some("uint8"), "VK_FORMAT_R8_UINT", Some("DXGI_FORMAT_R8_UINT"), Some("GL_R8UI"), [U(8)], 8, false, None),
    real!(Some("r16uint"), Some("uint16"), "VK_FORMAT_R16_UINT", Some("DXGI_FORMAT_R16_UINT"), Some("GL_R16UI"), [U(16)], 16, false, None),
    real!(Some("r32uint"), Some("uint32"), "VK_FORMAT_R32_UINT", Some("DXGI_FORMAT_R32_UINT"), Some("GL_R32UI"), [U(32)], 32, false, None),
    real!(Some("rg32uint"), Some("uint32x2"), "VK_FORMAT_R32G32_UINT", Some("DXGI_FORMAT_R32G32_UINT"), Some("GL_RG32UI"), [U(32), U(32)], 64, false, None),
    real!(None, Some("uint32x3"), "VK_FORMAT_R32G32B32_UINT", Some("DXGI_FORMAT_R32G32B32_UINT"), Some("GL_RGB32UI"), [U(32), U(32), U(32)], 96, false, Some(VERTEX_ONLY_NOTE)),
];

const VERTEX_ONLY_NOTE: &str = "a vertex format: no WebGPU texture has three 32-bit channels";
const BC_NOTE: &str = "WebGPU only with the texture-compression-bc feature";

#[rustfmt::skip]
const BC1: Real = real!(Some("bc1-rgba-unorm"), None, "VK_FORMAT_BC1_RGBA_UNORM_BLOCK", Some("DXGI_FORMAT_BC1_UNORM"), Some("GL_COMPRESSED_RGBA_S3TC_DXT1_EXT"), [B, B, B, B], 4, true, Some(BC_NOTE));
#[rustfmt::skip]
const BC3: Real = real!(Some("bc3-rgba-unorm"), None, "VK_FORMAT_BC3_UNORM_BLOCK", Some("DXGI_FORMAT_BC3_UNORM"), Some("GL_COMPRESSED_RGBA_S3TC_DXT5_EXT"), [B, B, B, B], 8, true, Some(BC_NOTE));
#[rustfmt::skip]
const BC5: Real = real!(Some("bc5-rg-unorm"), None, "VK_FORMAT_BC5_UNORM_BLOCK", Some("DXGI_FORMAT_BC5_UNORM"), Some("GL_COMPRESSED_RG_RGTC2"), [B, B], 8, true, Some(BC_NOTE));

/// One format a spec is stored in, in each API's spelling.
#[derive(Clone, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(serde::Serialize, serde::Deserialize))]
pub struct Format {
    /// WebGPU's texture format (`rg8snorm`), where WebGPU has one.
    pub texture: Option<String>,
    /// WebGPU's vertex format (`snorm8x2`), where there is one.
    pub vertex: Option<String>,
    /// Vulkan's `VkFormat`.
    pub vulkan: String,
    /// Direct3D's `DXGI_FORMAT`, where there is one.
    pub dxgi: Option<String>,
    /// OpenGL's sized internal format.
    pub gl: Option<String>,
    pub holds: Holds,
    /// Bits a texel or vertex attribute of it costs.
    pub bits: u32,
    /// Whether a texture unit filters it (and a resolve averages it) in every API.
    pub filterable: bool,
    /// Whether it stores the values the spec writes exactly; `false`: its channels are
    /// wider than the fields and round their values (or, for a block format, compress
    /// them).
    pub exact: bool,
    /// Channels the spec leaves unused (an RGB float form in an RGBA format), for the
    /// reader.
    pub unused_channels: u32,
    /// The channels, in order: what a render target of it stores.
    pub channels: Vec<Channel>,
    /// Where an API has it only as an option.
    pub note: Option<String>,
}

impl Format {
    fn new(r: &Real, holds: Holds, exact: bool, used: usize) -> Format {
        Format {
            texture: r.texture.map(str::to_string),
            vertex: r.vertex.map(str::to_string),
            vulkan: r.vulkan.to_string(),
            dxgi: r.dxgi.map(str::to_string),
            gl: r.gl.map(str::to_string),
            holds,
            bits: r.bits,
            filterable: r.filterable,
            exact,
            unused_channels: (r.channels.len().saturating_sub(used)) as u32,
            channels: r.channels.to_vec(),
            note: r.note.map(str::to_string),
        }
    }

    /// The name it is listed by: WebGPU's texture name, else its vertex name, else
    /// Vulkan's.
    pub fn name(&self) -> &str {
        self.texture
            .as_deref()
            .or(self.vertex.as_deref())
            .unwrap_or(&self.vulkan)
    }

    /// Whether a render target can be of it (a shader writes it): every format but the
    /// block-compressed ones, which only an offline compressor writes.
    pub fn renderable(&self) -> bool {
        !self.block()
    }

    /// Whether it is block-compressed (lossy: what it stores is not what was written).
    pub fn block(&self) -> bool {
        self.channels.contains(&Channel::Block)
    }

    /// Where a render target of it is not in every API's core: snorm colour attachments
    /// (D3D and desktop GL have them; Vulkan does not require them).
    pub fn render_note(&self) -> Option<&'static str> {
        self.channels
            .iter()
            .any(|c| matches!(c, Channel::Snorm(_)))
            .then_some(
                "a snorm render target needs WebGPU's texture-formats-tier1, OpenGL ES's \
                 EXT_render_snorm, and a Vulkan device that lists it as a colour attachment",
            )
    }

    /// `rg8snorm (16 bits)`, as `list`, `choose` and the report print it.
    pub fn label(&self) -> String {
        format!("{} ({} bits)", self.name(), self.bits)
    }

    /// Every spelling: WebGPU texture and vertex, Vulkan, DXGI, OpenGL.
    pub fn spellings(&self) -> Vec<&str> {
        [
            self.texture.as_deref(),
            self.vertex.as_deref(),
            Some(self.vulkan.as_str()),
            self.dxgi.as_deref(),
            self.gl.as_deref(),
        ]
        .into_iter()
        .flatten()
        .collect()
    }

    /// Whether a user's `--format` names this format: any spelling, case ignored, with
    /// or without Vulkan's `VK_FORMAT_`, DXGI's `DXGI_FORMAT_` and OpenGL's `GL_` prefix.
    pub fn matches(&self, query: &str) -> bool {
        let q = query.trim().to_ascii_uppercase();
        self.spellings().iter().any(|s| {
            let s = s.to_ascii_uppercase();
            s == q
                || ["VK_FORMAT_", "DXGI_FORMAT_", "GL_"]
                    .iter()
                    .any(|p| s.strip_prefix(p) == Some(q.as_str()))
        })
    }

    /// What a render target of this format stores for the float form's values `p` (one
    /// per field, in channel order).
    pub fn store(&self, p: &mut [f32]) {
        for (x, c) in p.iter_mut().zip(&self.channels) {
            *x = c.store(*x);
        }
    }
}

/// The float form's format: the smallest that holds `fields` exactly, else the smallest
/// that holds them at all (ties: the least precision to spare, then table order).
pub fn float_form_format(fields: &[Quant]) -> Option<(&'static Real, bool)> {
    let fits = |r: &Real| -> Option<(bool, u32)> {
        if r.channels.len() < fields.len() {
            return None;
        }
        let mut exact = true;
        let mut spare = 0;
        for (f, c) in fields.iter().zip(r.channels) {
            exact &= c.holds(*f)?;
            if let Channel::Unorm(k) | Channel::Snorm(k) = c {
                spare += k - f.bits().min(*k);
            }
        }
        Some((exact, spare))
    };
    let best = |want_exact: bool| {
        FLOAT_FORMATS
            .iter()
            .filter_map(|r| fits(r).map(|(exact, spare)| (r, exact, spare)))
            .filter(|(_, exact, _)| *exact || !want_exact)
            .min_by_key(|(r, _, spare)| (r.bits, *spare))
            .map(|(r, exact, _)| (r, exact))
    };
    best(true).or_else(|| best(false))
}

/// The integer format of a code of `bits` in `words` 32-bit words.
fn code_format(bits: u32, words: usize) -> &'static Real {
    match (words, bits) {
        (1, 0..=8) => &CODE_FORMATS[0],
        (1, 9..=16) => &CODE_FORMATS[1],
        (1, _) => &CODE_FORMATS[2],
        (2, _) => &CODE_FORMATS[3],
        _ => &CODE_FORMATS[4],
    }
}

/// The block-compressed formats a texel layout is made for.
fn block_formats(layout: Layout) -> &'static [Real] {
    match layout {
        Layout::Rg => &[BC5],
        Layout::Dxt5nm | Layout::Rxgb => &[BC3],
        Layout::Xra => &[BC1, BC3],
        // Luminance–alpha: BC5's two channels sampled through an LA swizzle.
        Layout::Latc => &[BC5],
    }
}

/// The fields `decode_float` reads, where they are a float form's fields.
pub fn float_fields(e: &Emitted) -> Option<&[Quant]> {
    e.functions
        .iter()
        .find(|f| f.role == Role::DecodeFloat)
        .and_then(|f| match &f.inputs {
            Inputs::FloatCodes(q) => Some(q.as_slice()),
            _ => None,
        })
}

/// Every format `spec`'s code and float form are stored in ([`Emitted`] is the spec's
/// traced functions): the code's first, then the float form's, then a texel layout's
/// block formats.
pub fn formats(spec: &Spec, e: &Emitted) -> Vec<Format> {
    let mut out = Vec::new();
    if let Some(enc) = e.functions.iter().find(|f| f.role == Role::Encode) {
        let r = code_format(spec.bits(), enc.out_words);
        out.push(Format::new(r, Holds::Code, true, enc.out_words));
    }
    if let Some(q) = float_fields(e)
        && let Some((r, exact)) = float_form_format(q)
    {
        out.push(Format::new(r, Holds::FloatForm, exact, q.len()));
        if let Some(l) = texel::layout(spec) {
            for r in block_formats(l) {
                out.push(Format::new(r, Holds::FloatForm, false, 0));
            }
        }
    }
    out
}

/// The float form's own format (not a block format): what its filtering is measured on.
pub fn float_form_storage(formats: &[Format]) -> Option<&Format> {
    formats
        .iter()
        .find(|f| f.holds == Holds::FloatForm && !f.channels.contains(&Channel::Block))
}
