//! What a user asks `choose`: the constraints ([`Query`]), the use the normals are for
//! ([`Use`]), and the answer when nothing meets them ([`Empty`]).

/// What the normals are for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Use {
    /// A deferred renderer's G-buffer: encoded per pixel every frame on the GPU, decoded
    /// per pixel by the lighting passes; filterable (read through a filter or an MSAA
    /// resolve) unless --no-filter.
    Gbuffer,
    /// Vertex normals: encoded offline on the CPU, decoded per vertex from a vertex
    /// attribute.
    Vertex,
    /// Stored data (an asset file, a network message): encoded and decoded on the CPU
    /// or once; only the error counts.
    Asset,
    /// A tangent-space normal map: encoded offline into a filtered, mipmapped texture,
    /// decoded per pixel; hemisphere codecs allowed.
    NormalMap,
    /// A whole tangent frame (normal, tangent, handedness) in a vertex attribute: encoded
    /// offline, decoded per vertex.
    Frame,
}

impl Use {
    /// Every profile, in the order the README lists them.
    pub const ALL: [Use; 5] = [
        Use::Gbuffer,
        Use::Vertex,
        Use::Asset,
        Use::NormalMap,
        Use::Frame,
    ];

    /// The name a user types.
    pub fn name(self) -> &'static str {
        match self {
            Use::Gbuffer => "gbuffer",
            Use::Vertex => "vertex",
            Use::Asset => "asset",
            Use::NormalMap => "normal-map",
            Use::Frame => "frame",
        }
    }

    /// The use in a few words, as the README's table names it.
    pub fn label(self, filtered: bool) -> &'static str {
        match (self, filtered) {
            (Use::Gbuffer, true) => "G-buffer, filtered or resolved",
            (Use::Gbuffer, false) => "G-buffer, read texel by texel",
            (Use::Vertex, _) => "vertex normals",
            (Use::Asset, _) => "stored normals, error only",
            (Use::NormalMap, _) => "tangent-space normal map",
            (Use::Frame, _) => "tangent frames",
        }
    }

    /// Where the vectors are encoded and decoded, in words.
    pub fn what(self, filtered: bool) -> &'static str {
        match (self, filtered) {
            (Use::Gbuffer, true) => {
                "G-buffer normals, filtered or MSAA-resolved: encoded and decoded per pixel"
            }
            (Use::Gbuffer, false) => {
                "G-buffer normals, read texel by texel: encoded and decoded per pixel"
            }
            (Use::Vertex, _) => "vertex normals: encoded offline, decoded per vertex",
            (Use::Asset, _) => "stored normals: error only",
            (Use::NormalMap, _) => "tangent-space normal maps: filtered, decoded per pixel",
            (Use::Frame, _) => "tangent frames: encoded offline, decoded per vertex",
        }
    }

    /// Whether the profile reads its storage through a filter.
    pub fn filters(self, query: &Query) -> bool {
        match self {
            Use::Gbuffer => !query.no_filter,
            Use::NormalMap => true,
            Use::Vertex | Use::Asset | Use::Frame => false,
        }
    }

    /// The domain the profile implies where `--domain` is not given.
    pub fn domain(self) -> Option<&'static str> {
        match self {
            Use::Gbuffer | Use::Vertex | Use::Asset => Some("sphere"),
            Use::NormalMap | Use::Frame => None,
        }
    }
}

/// A user's constraints, as `choose` takes them.
#[derive(Clone, Debug, Default, PartialEq, clap::Args)]
pub struct Query {
    /// What the normals are for: rank by that use's score (docs/design/choosing.md),
    /// with the constraints it implies; constraints given too still apply.
    #[arg(long = "use", value_enum, value_name = "USE")]
    pub use_case: Option<Use>,
    /// With --use gbuffer: the G-buffer is read texel by texel, never filtered or
    /// resolved, so the code may be stored in an integer format.
    #[arg(long)]
    pub no_filter: bool,
    /// Total bits of the packed code; with `--filterable`, bits a texel of the float
    /// form's filterable format costs (which may be wider than the code); with `--use`,
    /// the most a texel, vertex or record of the storage may cost.
    #[arg(long, value_name = "N")]
    pub bits: Option<u32>,
    /// A storage format the code or float form is written to, in any API's spelling:
    /// rg8snorm, snorm16x2, VK_FORMAT_R16G16_UNORM, DXGI_FORMAT_R8G8_UNORM, bc5-rg-unorm.
    #[arg(long, value_name = "F")]
    pub format: Option<String>,
    /// The codec's domain (`frame`: the tangent-frame specs, as `--use frame`).
    #[arg(long, value_parser = ["sphere", "hemisphere", "frame"])]
    pub domain: Option<String>,
    /// Only specs whose float form is stored in a format texture units filter and
    /// survives linear filtering and four-sample resolves there: the 99th percentile of
    /// the filtering error at 5° apart at most DEG degrees.
    #[arg(
        long,
        value_name = "DEG",
        num_args = 0..=1,
        default_missing_value = "1"
    )]
    pub filterable: Option<f64>,
    /// At most N ALU instructions in the packed encoder (with --use: in the encoder its
    /// storage runs).
    #[arg(long, value_name = "N")]
    pub max_encode_alu: Option<u32>,
    /// At most N ALU instructions in the packed decoder (with --use: in the decoder its
    /// storage runs).
    #[arg(long, value_name = "N")]
    pub max_decode_alu: Option<u32>,
    /// Only packed encoders that give the same code on every conformant GPU (with --use:
    /// only the packed code is stored, never the float form).
    #[arg(long)]
    pub portable: bool,
}

/// Nothing met the constraints.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("no spec meets {constraint}; {before}")]
pub struct Empty {
    /// The constraint that emptied the list, as typed (`--bits 17`).
    pub constraint: String,
    /// What was left before it.
    pub before: String,
}
