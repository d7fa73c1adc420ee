//! What a codec family says about itself: its description, how its sizes are spelled,
//! and its options (the [`Info`] of each `crate::codecs::core::spec::Family`).

use crate::codecs::core::error::SpecError;

/// Which directions a codec represents.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Domain {
    Sphere,
    /// The +Z hemisphere; input below the horizon is first projected onto it (`z ← max(z, 0)`).
    Hemisphere,
}

impl Domain {
    pub fn name(self) -> &'static str {
        match self {
            Domain::Sphere => "sphere",
            Domain::Hemisphere => "hemisphere",
        }
    }
}

/// How a family's bit sizes are written in a spec.
#[derive(Debug)]
pub enum Sizes {
    /// Total bit budgets after the name: `oct16`. A name that ends in a digit takes an
    /// underscore before its size (`cry3_16`), so every spelling reads back unambiguously.
    Total(&'static [u32]),
    /// Bits per component: `{prefix}{b}x{count}` (`snorm8x3`), total `b·count`.
    PerComponent {
        prefix: &'static str,
        count: u32,
        per: &'static [u32],
    },
    /// One configuration of this many bits, spelled by the name alone (`snorm11_11_10`,
    /// packing helpers).
    Fixed(u32),
    /// Bits per field after the name, as the format's own tool spells its quantization
    /// (`draco_oct10`: Draco's quantization bits), total `b·count`.
    PerField { count: u32, per: &'static [u32] },
}

/// One option a family takes: `key=value` in a spec, `_token` in an id.
#[derive(Debug)]
pub struct OptDesc {
    pub key: &'static str,
    pub help: &'static str,
    pub kind: OptKind,
}

#[derive(Debug)]
pub enum OptKind {
    /// One of the listed names; the first is the default. In an id the name alone stands
    /// for the option (`oct24_rgb8`), so names are unique within a family.
    Choice(&'static [&'static str]),
    /// A number in `min..=max`. In an id it is `{key}{value}` with `.` written `p` and
    /// `-` written `m` (`stereo_scaled16_scale2p5`), so ids stay identifiers.
    Number { default: f32, min: f32, max: f32 },
}

/// A parsed option value.
#[derive(Clone, Copy, Debug)]
pub enum OptVal {
    /// Index into the choice's names.
    Choice(usize),
    Number(f32),
}

impl PartialEq for OptVal {
    fn eq(&self, o: &OptVal) -> bool {
        match (self, o) {
            (OptVal::Choice(a), OptVal::Choice(b)) => a == b,
            (OptVal::Number(a), OptVal::Number(b)) => a.to_bits() == b.to_bits(),
            _ => false,
        }
    }
}
impl Eq for OptVal {}

impl OptDesc {
    pub fn default_value(&self) -> OptVal {
        match self.kind {
            OptKind::Choice(_) => OptVal::Choice(0),
            OptKind::Number { default, .. } => OptVal::Number(default),
        }
    }

    /// The value as written after `key=`.
    pub fn value_text(&self, v: OptVal) -> String {
        match (&self.kind, v) {
            (OptKind::Choice(names), OptVal::Choice(i)) => names[i].to_string(),
            (OptKind::Number { .. }, OptVal::Number(x)) => x.to_string(),
            _ => unreachable!("option value of the wrong kind"),
        }
    }

    /// The value as written in an id (`rgb8`, `scale2p5`).
    pub fn id_token(&self, v: OptVal) -> String {
        match self.kind {
            OptKind::Choice(_) => self.value_text(v),
            OptKind::Number { .. } => format!(
                "{}{}",
                self.key,
                self.value_text(v).replace('.', "p").replace('-', "m")
            ),
        }
    }

    /// Reads an id token back, if it is one of this option's.
    pub fn parse_id_token(&self, token: &str) -> Option<OptVal> {
        match self.kind {
            OptKind::Choice(names) => names.iter().position(|n| *n == token).map(OptVal::Choice),
            OptKind::Number { .. } => {
                let rest = token.strip_prefix(self.key)?;
                let text = rest.replace('p', ".").replace('m', "-");
                self.parse_value(&text).ok()
            }
        }
    }

    /// Parses `value` as written after `key=`, checking its range.
    pub fn parse_value(&self, value: &str) -> Result<OptVal, SpecError> {
        let bad = |why: String| SpecError::BadValue {
            key: self.key.to_string(),
            value: value.to_string(),
            why,
        };
        match self.kind {
            OptKind::Choice(names) => names
                .iter()
                .position(|n| *n == value)
                .map(OptVal::Choice)
                .ok_or_else(|| bad(format!("expected {}", names.join(" or ")))),
            OptKind::Number { min, max, .. } => {
                let x: f32 = value.parse().map_err(|_| bad("expected a number".into()))?;
                if (min..=max).contains(&x) {
                    Ok(OptVal::Number(x))
                } else {
                    Err(bad(format!("{} must lie in [{min}, {max}]", self.key)))
                }
            }
        }
    }

    /// `layout=snorm (default) | rgb8: help`, for `list` and errors.
    pub fn usage(&self) -> String {
        let values = match &self.kind {
            OptKind::Choice(names) => {
                let mut v: Vec<String> = names.iter().map(|n| n.to_string()).collect();
                v[0].push_str(" (default)");
                v.join(" | ")
            }
            OptKind::Number { default, min, max } => {
                format!("a number in [{min}, {max}], default {default}")
            }
        };
        format!("{}={values}: {}", self.key, self.help)
    }
}

/// Everything a user needs to choose a codec, as `list` shows it and doc comments quote it.
#[derive(Debug)]
pub struct Info {
    pub name: &'static str,
    pub title: &'static str,
    pub sizes: Sizes,
    /// `None` for packing helpers, which are not codecs and have no encode/decode.
    pub domain: Option<Domain>,
    pub source: &'static str,
    /// What zero, NaN, infinite and out-of-domain input encode to.
    pub edge_policy: &'static str,
    /// What the decoder returns (unit length or not).
    pub decode_note: &'static str,
    /// What a texture unit's filter or a resolve may do with the float form.
    pub float_form: FloatForm,
    pub options: &'static [OptDesc],
}

/// What linear filtering and multisample resolves may do with a family's float form
/// (`decode_float`'s input, as a texture stores it): `choose --filterable` and the
/// report's filtering lines read it. Every family states it, so a new family cannot fall
/// back on someone else's answer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FloatForm {
    /// Continuous parameters, which a filter mixes into a direction between its
    /// neighbours' except at `seam` (where on the sphere the parameters jump).
    Continuous { seam: &'static str },
    /// Parameters a filter must not mix, `why` (an index split into channels); they jump
    /// at `seam`.
    Unfilterable {
        why: &'static str,
        seam: &'static str,
    },
    /// No texel of directions: packing helpers and tangent frames.
    Absent,
}

impl FloatForm {
    /// Why an index code's float form does not filter.
    pub const INDEX_SPLIT: &str = "its float form holds a point's index, split into channels";
    /// Where the parameters jump, if there is a float form.
    pub fn seam(self) -> Option<&'static str> {
        match self {
            FloatForm::Continuous { seam } | FloatForm::Unfilterable { seam, .. } => Some(seam),
            FloatForm::Absent => None,
        }
    }
    /// Why a filter must not mix the float form, if it must not.
    pub fn unfilterable(self) -> Option<&'static str> {
        match self {
            FloatForm::Unfilterable { why, .. } => Some(why),
            FloatForm::Continuous { .. } | FloatForm::Absent => None,
        }
    }
}

/// The seams that several families' maps share ([`FloatForm::Continuous`]).
pub mod seam {
    /// Octahedral maps of the sphere.
    pub const OCTAHEDRAL_FOLD: &str =
        "the octahedral fold, where the lower hemisphere's triangles meet at the square's edges";
    /// Hemisphere maps with a bit for the sign of z.
    pub const HEMISPHERE_BIT: &str = "the equator, where the hemisphere bit flips";
    /// Azimuth and polar angle (or z).
    pub const AZIMUTH_WRAP: &str = "the azimuth's wrap at ±180° and the poles";
    /// Cube maps.
    pub const CUBE_FACES: &str = "the cube's face boundaries, where the face index changes";
    /// Sphere-to-disk maps that send -Z to the disk's rim (Lambert's and its kin).
    pub const RIM_IS_MINUS_Z: &str = "around -Z, which the disk's whole rim stands for";
    /// Maps of the +Z hemisphere alone.
    pub const NONE_IN_HEMISPHERE: &str =
        "nowhere inside the hemisphere: the parameters are continuous up to its rim";
    /// Components stored one by one.
    pub const NONE_PER_COMPONENT: &str = "nowhere: each component is continuous";
}

impl Info {
    /// Every size as a user spells it, with its total bit budget.
    pub fn spellings(&self) -> Vec<(String, u32)> {
        match &self.sizes {
            Sizes::Total(bits) => {
                let sep = if self.name.ends_with(|c: char| c.is_ascii_digit()) {
                    "_"
                } else {
                    ""
                };
                bits.iter()
                    .map(|b| (format!("{}{sep}{b}", self.name), *b))
                    .collect()
            }
            Sizes::PerComponent { prefix, count, per } => per
                .iter()
                .map(|b| (format!("{prefix}{b}x{count}"), b * count))
                .collect(),
            Sizes::Fixed(bits) => vec![(self.name.to_string(), *bits)],
            Sizes::PerField { count, per } => per
                .iter()
                .map(|b| (format!("{}{b}", self.name), b * count))
                .collect(),
        }
    }

    /// The allowed total bit budgets.
    pub fn total_bits(&self) -> Vec<u32> {
        self.spellings().into_iter().map(|s| s.1).collect()
    }

    /// `bits` if it is one of this family's sizes, else the error listing them.
    pub fn check_bits(&self, bits: u32) -> Result<u32, SpecError> {
        if self.total_bits().contains(&bits) && bits > 0 {
            Ok(bits)
        } else {
            Err(SpecError::InvalidBits {
                codec: self.name,
                bits: bits.to_string(),
                allowed: self.total_bits().iter().map(|b| b.to_string()).collect(),
            })
        }
    }

    /// Index of the option called `key`.
    pub fn option_index(&self, key: &str) -> Option<usize> {
        self.options.iter().position(|o| o.key == key)
    }
}
