//! The codecs unitpack knows, with what a user needs to choose one, and the spec syntax.
//!
//! A spec names one codec configuration: `NAME[BITS][p][:key=value,...]`, e.g. `oct24p`,
//! `hemioct16`, `snorm8x3`, `stereo_scaled16:scale=1.7777`, `oct24:layout=rgb8`,
//! `snorm12x2`. `p` selects the precise encoder.

use super::codec::Domain;
use super::stereo::{DEFAULT_SCALE, SCALE_RANGE};
use std::fmt;

/// A codec family as listed by `unitpack list`.
#[derive(Debug)]
pub struct CodecDesc {
    pub name: &'static str,
    pub title: &'static str,
    /// Allowed total bit budgets (empty for pure packing helpers).
    pub bits: &'static [u32],
    pub domain: Option<Domain>,
    pub precise: bool,
    pub source: &'static str,
    /// What zero, NaN, infinite and out-of-domain input encode to.
    pub edge_policy: &'static str,
    /// What the decoder returns (unit length or not).
    pub decode_note: &'static str,
    pub options: &'static str,
}

pub static CATALOGUE: &[CodecDesc] = &[
    CodecDesc {
        name: "oct",
        title: "octahedral, snorm×2",
        bits: &[16, 20, 22, 24, 32],
        domain: Some(Domain::Sphere),
        precise: true,
        source: "Cigolle et al. 2014 (JCGT survey) §3.1–3.3",
        edge_policy: "input need not be unit length; zero, NaN and infinite input encode as +Z",
        decode_note: "every code decodes to a unit vector (normalized as v / sqrt(v·v))",
        options: "layout=snorm (default) | layout=rgb8 (24 bits: the survey's unorm8×3 bytes)",
    },
    CodecDesc {
        name: "hemioct",
        title: "hemi-octahedral, snorm×2",
        bits: &[16, 24, 32],
        domain: Some(Domain::Hemisphere),
        precise: true,
        source: "Cigolle et al. 2014, Listing 6 and Table 3",
        edge_policy: "input below the horizon is projected onto it (z ← max(z, +0)); zero, NaN and infinite input encode as +Z",
        decode_note: "every code decodes to a unit vector with z ≥ 0",
        options: "",
    },
    CodecDesc {
        name: "snorm3",
        title: "components as snorm×3 (ids snorm8x3, snorm10x3, snorm16x3)",
        bits: &[24, 30, 48],
        domain: Some(Domain::Sphere),
        precise: false,
        source: "Cigolle et al. 2014 §2; Pranckevičius, baseline",
        edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z",
        decode_note: "decode re-normalizes; the all-zero code decodes as +Z",
        options: "",
    },
    CodecDesc {
        name: "spherical",
        title: "spherical coordinates (θ, φ), snorm×2",
        bits: &[16, 24, 32],
        domain: Some(Domain::Sphere),
        precise: true,
        source: "Cigolle et al. 2014 §2",
        edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z",
        decode_note: "decodes are unit length to within the trig approximations' error (about 2.5e-7)",
        options: "",
    },
    CodecDesc {
        name: "lambert",
        title: "Lambert azimuthal equal-area, unorm×2",
        bits: &[16, 24, 32],
        domain: Some(Domain::Sphere),
        precise: true,
        source: "Pranckevičius, Compact Normal Storage, method 6",
        edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z; -Z encodes as (1, 0.5)",
        decode_note: "every code decodes to a unit vector; codes outside the disk decode as -Z",
        options: "",
    },
    CodecDesc {
        name: "stereo_scaled",
        title: "scaled stereographic, unorm×2",
        bits: &[16, 24, 32],
        domain: Some(Domain::Sphere),
        precise: true,
        source: "Pranckevičius, Compact Normal Storage, method 7",
        edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z; directions beyond 2·atan(scale) from +Z clamp to the square's edge",
        decode_note: "every code decodes to a unit vector (up to rounding)",
        options: "scale=S (default 1.7777)",
    },
    CodecDesc {
        name: "xy",
        title: "x and y stored, z reconstructed, snorm×2",
        bits: &[16, 24, 32],
        domain: Some(Domain::Hemisphere),
        precise: true,
        source: "Pranckevičius method 1; Cigolle et al. XYOnly; NVIDIA normal-map notes",
        edge_policy: "input is normalized onto the +Z hemisphere first (z ← max(z, +0)); zero, NaN and infinite input encode as +Z",
        decode_note: "z = sqrt(1 - saturate(x²+y²)); codes outside the unit disk decode to (x, y, 0), longer than 1",
        options: "",
    },
    CodecDesc {
        name: "snorm12x2",
        title: "snorm12×2 ↔ unorm8×3 packing helpers, integer and float-only forms",
        bits: &[],
        domain: None,
        precise: false,
        source: "Cigolle et al. 2014 §3.3, Listings 4–5",
        edge_policy: "parameters are clamped to [-1, 1]",
        decode_note: "unpack returns values in [-1, 1]",
        options: "",
    },
];

impl CodecDesc {
    pub fn allowed_bits(&self) -> Vec<String> {
        self.bits.iter().map(|b| b.to_string()).collect()
    }
    /// `bits` as one of this codec's sizes, or the error listing the allowed ones.
    pub fn check_bits(&self, bits: &str) -> Result<u32, SpecError> {
        match bits.parse::<u32>() {
            Ok(b) if self.bits.contains(&b) => Ok(b),
            _ => Err(SpecError::InvalidBits {
                codec: self.name,
                bits: bits.to_string(),
                allowed: self.allowed_bits(),
            }),
        }
    }
}

/// Storage layout of oct24.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Layout {
    Snorm,
    Rgb8,
}

/// One parsed spec.
#[derive(Clone, Debug)]
pub struct Spec {
    pub codec: &'static CodecDesc,
    pub bits: u32,
    pub precise: bool,
    pub layout: Layout,
    pub scale: f32,
}

#[derive(Debug, thiserror::Error, PartialEq)]
pub enum SpecError {
    #[error("unknown codec '{given}'; did you mean {}? Valid codecs: {}", .nearest.join(" or "), .valid.join(", "))]
    UnknownCodec {
        given: String,
        nearest: Vec<String>,
        valid: Vec<String>,
    },
    #[error("{codec} has no {bits}-bit form; allowed sizes: {}", fmt_list(.allowed))]
    InvalidBits {
        codec: &'static str,
        bits: String,
        allowed: Vec<String>,
    },
    #[error("{codec} needs a bit size, e.g. {codec}{}; allowed sizes: {}", .allowed[0], fmt_list(.allowed))]
    MissingBits {
        codec: &'static str,
        allowed: Vec<String>,
    },
    #[error(
        "snorm3 is spelled by component size: snorm8x3, snorm10x3 or snorm16x3 (got '{given}')"
    )]
    Snorm3Size { given: String },
    #[error("{codec} has no precise encoder")]
    NoPrecise { codec: &'static str },
    #[error("{codec} takes no option '{key}'; options: {options}")]
    UnknownOption {
        codec: &'static str,
        key: String,
        options: &'static str,
    },
    #[error("bad value '{value}' for {key}: {why}")]
    BadValue {
        key: String,
        value: String,
        why: &'static str,
    },
}

fn fmt_list(v: &[String]) -> String {
    v.join(", ")
}

fn snorm3_id(bits: u32) -> String {
    format!("snorm{}x3", bits / 3)
}

impl Spec {
    /// Every spec the catalogue holds with default options: what `generate` writes.
    pub fn all() -> Vec<Spec> {
        let mut out = Vec::new();
        for c in CATALOGUE {
            if c.bits.is_empty() {
                out.push(Spec::new(c, 0, false));
            }
            for &b in c.bits {
                out.push(Spec::new(c, b, false));
                if c.precise {
                    out.push(Spec::new(c, b, true));
                }
                if c.name == "oct" && b == 24 {
                    for precise in [false, true] {
                        out.push(Spec {
                            layout: Layout::Rgb8,
                            ..Spec::new(c, b, precise)
                        });
                    }
                }
            }
        }
        out
    }

    fn new(codec: &'static CodecDesc, bits: u32, precise: bool) -> Spec {
        Spec {
            codec,
            bits,
            precise,
            layout: Layout::Snorm,
            scale: DEFAULT_SCALE,
        }
    }

    /// The identifier used in file and function names, e.g. `oct24p_rgb8`,
    /// `stereo_scaled16_scale2` (a non-default scale is part of the name, so two scales
    /// can share one include).
    pub fn id(&self) -> String {
        let scale = if self.scale_is_set() {
            format!("_scale{}", self.scale.to_string().replace(['.', '-'], "_"))
        } else {
            String::new()
        };
        format!("{}{scale}", self.base_id())
    }

    fn scale_is_set(&self) -> bool {
        self.codec.name == "stereo_scaled" && self.scale != DEFAULT_SCALE
    }

    /// The id without options.
    fn base_id(&self) -> String {
        let base = match self.codec.name {
            "snorm3" => snorm3_id(self.bits),
            "snorm12x2" => "snorm12x2".to_string(),
            n => format!("{n}{}", self.bits),
        };
        let p = if self.precise { "p" } else { "" };
        let layout = if self.layout == Layout::Rgb8 {
            "_rgb8"
        } else {
            ""
        };
        format!("{base}{p}{layout}")
    }

    /// The id plus any non-default option, for display.
    pub fn display_name(&self) -> String {
        let mut s = self.base_id();
        if self.scale_is_set() {
            s.push_str(&format!(":scale={}", self.scale));
        }
        s
    }
}

impl PartialEq for Spec {
    fn eq(&self, o: &Spec) -> bool {
        std::ptr::eq(self.codec, o.codec)
            && (self.bits, self.precise, self.layout, self.scale)
                == (o.bits, o.precise, o.layout, o.scale)
    }
}

impl fmt::Display for Spec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.display_name())
    }
}

/// Every spelling a user can type for a codec name, for suggestions.
fn valid_names() -> Vec<String> {
    let mut v: Vec<String> = CATALOGUE
        .iter()
        .filter(|c| c.name != "snorm3")
        .map(|c| c.name.to_string())
        .collect();
    v.extend(["snorm8x3", "snorm10x3", "snorm16x3"].map(String::from));
    v
}

impl std::str::FromStr for Spec {
    type Err = SpecError;
    fn from_str(s: &str) -> Result<Spec, SpecError> {
        let (head, opts) = match s.split_once(':') {
            Some((h, o)) => (h, Some(o)),
            None => (s, None),
        };
        let head_lc = head.to_ascii_lowercase();
        let mut spec = parse_head(&head_lc)?;
        let opts = opts.map(str::to_ascii_lowercase);
        for kv in opts
            .iter()
            .flat_map(|o| o.split(','))
            .filter(|kv| !kv.is_empty())
        {
            let (k, v) = kv.split_once('=').unwrap_or((kv, ""));
            let unknown = || SpecError::UnknownOption {
                codec: spec.codec.name,
                key: k.to_string(),
                options: if spec.codec.options.is_empty() {
                    "none"
                } else {
                    spec.codec.options
                },
            };
            match (spec.codec.name, k) {
                ("stereo_scaled", "scale") => {
                    let x: f32 = v.parse().map_err(|_| SpecError::BadValue {
                        key: k.into(),
                        value: v.into(),
                        why: "expected a number",
                    })?;
                    if !SCALE_RANGE.contains(&x) {
                        return Err(SpecError::BadValue {
                            key: k.into(),
                            value: v.into(),
                            why: "scale must lie in [0.001, 1000]",
                        });
                    }
                    spec.scale = x;
                }
                ("oct", "layout") => {
                    spec.layout = match v {
                        "snorm" => Layout::Snorm,
                        "rgb8" if spec.bits == 24 => Layout::Rgb8,
                        "rgb8" => {
                            return Err(SpecError::BadValue {
                                key: k.into(),
                                value: v.into(),
                                why: "the rgb8 layout holds oct24 only",
                            });
                        }
                        _ => {
                            return Err(SpecError::BadValue {
                                key: k.into(),
                                value: v.into(),
                                why: "expected snorm or rgb8",
                            });
                        }
                    }
                }
                _ => return Err(unknown()),
            }
        }
        Ok(spec)
    }
}

fn parse_head(head: &str) -> Result<Spec, SpecError> {
    let (body, precise) = match head.strip_suffix('p') {
        Some(b) if b.ends_with(|c: char| c.is_ascii_digit()) => (b, true),
        _ => (head, false),
    };
    // snorm3 is spelled by component size, as in the survey: snorm8x3.
    if body == "snorm3" || (body.starts_with("snorm") && body.ends_with("x3")) {
        let c = desc("snorm3");
        let per = body
            .strip_prefix("snorm")
            .and_then(|r| r.strip_suffix("x3"));
        return match per.and_then(|b| b.parse::<u32>().ok()) {
            Some(n) if c.bits.contains(&(n * 3)) && !precise => Ok(Spec::new(c, n * 3, false)),
            Some(n) if c.bits.contains(&(n * 3)) => Err(SpecError::NoPrecise { codec: c.name }),
            _ => Err(SpecError::Snorm3Size {
                given: head.to_string(),
            }),
        };
    }
    if body == "snorm12x2" {
        let c = desc("snorm12x2");
        return if precise {
            Err(SpecError::NoPrecise { codec: c.name })
        } else {
            Ok(Spec::new(c, 0, false))
        };
    }
    let name_end = body
        .find(|c: char| c.is_ascii_digit())
        .unwrap_or(body.len());
    let (name, digits) = body.split_at(name_end);
    let Some(c) = CATALOGUE
        .iter()
        .find(|c| c.name == name && !c.bits.is_empty())
    else {
        return Err(unknown_codec(head));
    };
    if digits.is_empty() {
        return Err(SpecError::MissingBits {
            codec: c.name,
            allowed: c.allowed_bits(),
        });
    }
    let bits = c.check_bits(digits)?;
    if precise && !c.precise {
        return Err(SpecError::NoPrecise { codec: c.name });
    }
    Ok(Spec::new(c, bits, precise))
}

/// Suggestions: names sharing a prefix with what was typed first, then by edit distance.
fn unknown_codec(given: &str) -> SpecError {
    let name: String = given.chars().take_while(|c| !c.is_ascii_digit()).collect();
    let key = |v: &String| {
        let related =
            v.starts_with(name.as_str()) || (!name.is_empty() && name.starts_with(v.as_str()));
        (!related, strsim::levenshtein(&name, v))
    };
    let mut valid = valid_names();
    valid.sort_by_key(|v| (key(v), v.clone()));
    let best = key(&valid[0]);
    let nearest = valid
        .iter()
        .take_while(|v| key(v) == best)
        .cloned()
        .collect();
    SpecError::UnknownCodec {
        given: given.to_string(),
        nearest,
        valid,
    }
}

pub fn desc(name: &str) -> &'static CodecDesc {
    CATALOGUE
        .iter()
        .find(|c| c.name == name)
        .expect("catalogue name")
}
