//! Specs: one codec configuration, and the grammar users type.
//!
//! ```text
//! spec   = head ["p"] {"_" token} [":" option {"," option}]
//! head   = name bits            (oct16, hemioct24; a name ending in a digit: cry3_16)
//!        | prefix bits "x" n    (snorm8x3: bits per component)
//!        | name                 (fixed forms: snorm12x2)
//! option = key "=" value        (oct24:layout=rgb8, stereo_scaled16:scale=2.5)
//! token  = choice | key number  (oct24_rgb8, stereo_scaled16_scale2p5: "." as "p", "-" as "m")
//! ```
//!
//! `p` selects the precise encoder. Case does not matter. Every id (file and function
//! name) is itself a spec, and [`Spec`]'s `Display` writes the `key=value` form; both read
//! back as the same spec. An option may be given once, and an option list must not be empty.

pub use crate::codecs::core::error::SpecError;
use crate::codecs::core::info::{FloatForm, Info, OptDesc, OptKind, OptVal};
use crate::codecs::functions::function::Emitted;
use std::collections::BTreeMap;
use std::fmt;
use std::hash::{Hash, Hasher};
use std::sync::{Arc, Mutex, OnceLock};

/// One parsed spec: a family, a size, the encoder, and every option's value.
#[derive(Clone)]
pub struct Spec {
    family: &'static dyn Family,
    bits: u32,
    precise: bool,
    /// One value per option of the family, in the family's order (defaults included).
    opts: Vec<OptVal>,
}

impl Spec {
    /// The spec of `family` at `bits` with default options.
    pub fn new(family: &'static dyn Family, bits: u32, precise: bool) -> Spec {
        Spec {
            family,
            bits,
            precise,
            opts: family
                .info()
                .options
                .iter()
                .map(|o| o.default_value())
                .collect(),
        }
    }

    /// Every spec `generate` writes of `families`: each size of each family with default
    /// options (fast and precise), plus each family's variants.
    pub fn all_in(families: Families) -> Vec<Spec> {
        let mut out = Vec::new();
        for &f in families {
            let info = f.info();
            for (_, bits) in info.spellings() {
                out.push(Spec::new(f, bits, false));
                if f.precise() {
                    out.push(Spec::new(f, bits, true));
                }
            }
            for v in f.variants() {
                let s = Spec::parse_in(families, v).expect("a family's variants parse");
                let precise = Spec {
                    precise: true,
                    ..s.clone()
                };
                // With the precise encoder too where the family offers it for the variant
                // (the lean tier has none).
                let with_precise = f.precise() && f.validate(&precise).is_ok();
                out.push(s.fast());
                if with_precise {
                    out.push(precise);
                }
            }
        }
        out
    }

    pub fn family(&self) -> &'static dyn Family {
        self.family
    }
    pub fn info(&self) -> &Info {
        self.family.info()
    }
    /// Total bit budget (0 for fixed helper forms).
    pub fn bits(&self) -> u32 {
        self.bits
    }
    pub fn precise(&self) -> bool {
        self.precise
    }
    /// The same spec with the fast encoder: what a precise spec's decoders and lookup
    /// tables are.
    pub fn fast(&self) -> Spec {
        Spec {
            precise: false,
            ..self.clone()
        }
    }
    /// The value the spec gives option `opt`, found by its key: `None` where the family
    /// has no such option (shared options such as `layout` or `guarantee` are read by code
    /// that serves many families). Options are read by key, never by position, so that a
    /// family may reorder or add options without its readers changing.
    pub fn option(&self, opt: &OptDesc) -> Option<OptVal> {
        let i = self.info().option_index(opt.key)?;
        Some(self.opts[i])
    }
    /// The index of the chosen name of the family's own choice option `opt`.
    pub fn choice_of(&self, opt: &OptDesc) -> usize {
        match self.option(opt) {
            Some(OptVal::Choice(c)) => c,
            other => panic!(
                "{} has no choice option {} ({other:?})",
                self.info().name,
                opt.key
            ),
        }
    }
    /// Whether the spec chose `name` for the family's own choice option `opt` (a name the
    /// option does not list is a mistake in the family's code, and panics saying so).
    pub fn chose(&self, opt: &OptDesc, name: &str) -> bool {
        let OptKind::Choice(names) = opt.kind else {
            panic!("{}: option {} is no choice", self.info().name, opt.key)
        };
        let at = names.iter().position(|n| *n == name);
        let at = at.unwrap_or_else(|| {
            panic!(
                "{}: option {} has no choice {name}",
                self.info().name,
                opt.key
            )
        });
        self.choice_of(opt) == at
    }
    /// The value of the family's own number option `opt`.
    pub fn number_of(&self, opt: &OptDesc) -> f32 {
        match self.option(opt) {
            Some(OptVal::Number(x)) => x,
            other => panic!(
                "{} has no number option {} ({other:?})",
                self.info().name,
                opt.key
            ),
        }
    }

    /// The spec's traced functions, traced once per process: every caller (emission,
    /// the figures, `verify`, the CPU batches) shares one trace. Only this method can ask
    /// a family to trace ([`Tracing`] has no other maker).
    pub fn emitted(&self) -> Arc<Emitted> {
        static TRACED: Mutex<BTreeMap<String, Arc<OnceLock<Arc<Emitted>>>>> =
            Mutex::new(BTreeMap::new());
        let cell = {
            let mut traced = TRACED.lock().unwrap_or_else(|e| e.into_inner());
            traced.entry(self.id()).or_default().clone()
        };
        cell.get_or_init(|| {
            let mut counts = TRACE_COUNTS.lock().unwrap_or_else(|e| e.into_inner());
            *counts.entry(self.id()).or_default() += 1;
            drop(counts);
            Arc::new(self.traced())
        })
        .clone()
    }

    /// The family's trace of this spec. A rule the trace breaks (a tracer's assertion, a
    /// codec's own check) panics again, naming the spec, its family and the functions
    /// being defined, which the first message need not know.
    fn traced(&self) -> Emitted {
        let run = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            self.family.emitted(self, Tracing(()))
        }));
        run.unwrap_or_else(|p| {
            let message = p
                .downcast_ref::<String>()
                .map(String::as_str)
                .or_else(|| p.downcast_ref::<&str>().copied())
                .unwrap_or("(a panic without a message)");
            let at = crate::model::trace::take_defining();
            let at = if at.is_empty() {
                String::new()
            } else {
                format!(", in {}", at.join(" → "))
            };
            panic!(
                "tracing {self} (family {}){at}: {message}",
                self.info().name
            )
        })
    }

    /// How many times this process has traced the spec `id`: at most once, whatever
    /// asked for it (tests/internals hold every path to it).
    pub fn traces(id: &str) -> usize {
        let counts = TRACE_COUNTS.lock().unwrap_or_else(|e| e.into_inner());
        counts.get(id).copied().unwrap_or(0)
    }

    fn head(&self) -> String {
        let info = self.info();
        let spelled = info
            .spellings()
            .into_iter()
            .find(|s| s.1 == self.bits)
            .map(|s| s.0)
            .expect("a spec's size is one of its family's");
        format!("{spelled}{}", if self.precise { "p" } else { "" })
    }

    /// Options that differ from their default, with their descriptions.
    fn set_options(
        &self,
    ) -> impl Iterator<Item = (&'static crate::codecs::core::info::OptDesc, OptVal)> + '_ {
        self.info()
            .options
            .iter()
            .zip(&self.opts)
            .filter(|(d, v)| d.default_value() != **v)
            .map(|(d, v)| (d, *v))
    }

    /// The identifier used in file and function names: `oct24p_rgb8`,
    /// `stereo_scaled16_scale2`. It is a spec too: it parses back to this spec.
    pub fn id(&self) -> String {
        let mut s = self.head();
        for (d, v) in self.set_options() {
            s.push('_');
            s.push_str(&d.id_token(v));
        }
        s
    }
}

impl PartialEq for Spec {
    fn eq(&self, o: &Spec) -> bool {
        std::ptr::addr_eq(self.family, o.family)
            && (self.bits, self.precise) == (o.bits, o.precise)
            && self.opts == o.opts
    }
}
impl Eq for Spec {}

impl Hash for Spec {
    fn hash<H: Hasher>(&self, h: &mut H) {
        self.id().hash(h);
    }
}

/// `oct24p`, `oct24:layout=rgb8`, `stereo_scaled16:scale=2`.
impl fmt::Display for Spec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.head())?;
        for (i, (d, v)) in self.set_options().enumerate() {
            let sep = if i == 0 { ':' } else { ',' };
            write!(f, "{sep}{}={}", d.key, d.value_text(v))?;
        }
        Ok(())
    }
}

impl fmt::Debug for Spec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Spec({self})")
    }
}

/// Every spelling a user can type of `families`, for suggestions and `list`.
pub fn valid_names_in(families: Families) -> Vec<String> {
    let mut v = Vec::new();
    for f in families {
        let info = f.info();
        match info.sizes {
            crate::codecs::core::info::Sizes::Total(_)
            | crate::codecs::core::info::Sizes::PerField { .. } => v.push(info.name.to_string()),
            _ => v.extend(info.spellings().into_iter().map(|s| s.0)),
        }
    }
    v
}

fn options_text(info: &Info) -> String {
    if info.options.is_empty() {
        "none".to_string()
    } else {
        info.options
            .iter()
            .map(|o| o.usage())
            .collect::<Vec<_>>()
            .join("; ")
    }
}

impl Spec {
    /// Parses what a user types against `families` (the registry hands its own:
    /// `"oct24p".parse::<Spec>()`).
    pub fn parse_in(families: Families, given: &str) -> Result<Spec, SpecError> {
        let lower = given.trim().to_ascii_lowercase();
        let (head, opts) = match lower.split_once(':') {
            Some((h, o)) => (h, Some(o)),
            None => (lower.as_str(), None),
        };
        let (family, bits, rest) = match_head(families, head)?;
        let info = family.info();
        let (precise, tokens) = match rest.strip_prefix('p') {
            Some(r) if r.is_empty() || r.starts_with('_') => (true, r),
            _ => (false, rest),
        };
        let spelled = &head[..head.len() - rest.len()];
        if precise && !family.precise() {
            return Err(SpecError::NoPrecise {
                spelled: spelled.to_string(),
            });
        }
        let mut spec = Spec::new(family, bits, precise);
        let mut given_keys: Vec<&'static str> = Vec::new();
        let mut set = |i: usize, v: OptVal, spec: &mut Spec| {
            let key = info.options[i].key;
            if given_keys.contains(&key) {
                return Err(SpecError::DuplicateOption {
                    key: key.to_string(),
                    given: given.to_string(),
                });
            }
            given_keys.push(key);
            spec.opts[i] = v;
            Ok(())
        };
        for token in tokens.split('_').skip(1) {
            let found = info
                .options
                .iter()
                .enumerate()
                .find_map(|(i, d)| d.parse_id_token(token).map(|v| (i, v)));
            let Some((i, v)) = found else {
                return Err(SpecError::UnknownToken {
                    codec: info.name,
                    given: given.to_string(),
                    token: token.to_string(),
                    options: options_text(info),
                });
            };
            set(i, v, &mut spec)?;
        }
        if let Some(opts) = opts {
            for kv in opts.split(',') {
                let (k, v) = kv.split_once('=').unwrap_or((kv, ""));
                let (k, v) = (k.trim(), v.trim());
                if k.is_empty() {
                    return Err(SpecError::EmptyOption {
                        given: given.to_string(),
                    });
                }
                let Some(i) = info.option_index(k) else {
                    return Err(SpecError::UnknownOption {
                        codec: info.name,
                        key: k.to_string(),
                        options: options_text(info),
                    });
                };
                let v = info.options[i].parse_value(v)?;
                set(i, v, &mut spec)?;
            }
        }
        family.validate(&spec)?;
        Ok(spec)
    }
}

/// The family and size `head` starts with, and what follows them (`p`, `_tokens`).
/// The longest spelling wins; what follows it must be nothing, `p`, or `_`-separated.
fn match_head(
    families: Families,
    head: &str,
) -> Result<(&'static dyn Family, u32, &str), SpecError> {
    let mut best: Option<(&'static dyn Family, u32, usize)> = None;
    for &f in families {
        for (spelled, bits) in f.info().spellings() {
            let Some(rest) = head.strip_prefix(spelled.as_str()) else {
                continue;
            };
            let fits =
                rest.is_empty() || rest == "p" || rest.starts_with('_') || rest.starts_with("p_");
            if fits && best.is_none_or(|b| spelled.len() > b.2) {
                best = Some((f, bits, spelled.len()));
            }
        }
    }
    if let Some((f, bits, len)) = best {
        return Ok((f, bits, &head[len..]));
    }
    Err(diagnose(families, head))
}

/// Why `head` names no spec: a known name with a wrong or missing size, or an unknown name.
fn diagnose(families: Families, head: &str) -> SpecError {
    use crate::codecs::core::info::Sizes;
    let mut named: Option<(&'static Info, &str)> = None;
    for f in families {
        let info = f.info();
        let stem = match info.sizes {
            Sizes::PerComponent { prefix, .. } => prefix,
            _ => info.name,
        };
        if head.starts_with(stem) && named.is_none_or(|n| stem.len() > n.1.len()) {
            named = Some((info, stem));
        }
    }
    let Some((info, stem)) = named else {
        return unknown_codec(families, head);
    };
    if !matches!(info.sizes, Sizes::Total(_) | Sizes::PerField { .. }) {
        return SpecError::Spelling {
            codec: info.name,
            given: head.to_string(),
            allowed: info.spellings().into_iter().map(|s| s.0).collect(),
        };
    }
    let allowed: Vec<String> = match info.sizes {
        Sizes::PerField { per, .. } => per.iter().map(|b| b.to_string()).collect(),
        _ => info.total_bits().iter().map(|b| b.to_string()).collect(),
    };
    let rest = &head[stem.len()..];
    let rest = rest.strip_prefix('_').unwrap_or(rest);
    let digits: String = rest.chars().take_while(|c| c.is_ascii_digit()).collect();
    if let Some((spelled, _)) = info
        .spellings()
        .into_iter()
        .find(|s| head.starts_with(s.0.as_str()))
    {
        SpecError::Trailing {
            given: head.to_string(),
            spelled,
        }
    } else if !digits.is_empty() {
        SpecError::InvalidBits {
            codec: info.name,
            bits: digits,
            allowed,
        }
    } else if rest.is_empty() || rest == "p" {
        SpecError::MissingBits {
            codec: info.name,
            allowed,
        }
    } else {
        unknown_codec(families, head)
    }
}

/// Suggestions: names sharing a prefix with what was typed first, then by edit distance.
/// Where a size was typed, whole spellings with their sizes are suggested (`octt16` →
/// `oct16`, `meshopt16` → `meshopt_oct16`), `p` kept where the family has a precise form.
fn unknown_codec(families: Families, given: &str) -> SpecError {
    let name: String = given.chars().take_while(|c| !c.is_ascii_digit()).collect();
    let related =
        |v: &str| v.starts_with(name.as_str()) || (!name.is_empty() && name.starts_with(v));
    let key = |v: &String| (!related(v), strsim::levenshtein(&name, v));
    let mut valid = valid_names_in(families);
    valid.sort_by_key(|v| (key(v), v.clone()));
    let nearest = if name.len() < given.len() {
        let precise = given.ends_with('p');
        let sized = given.strip_suffix('p').unwrap_or(given);
        // Each spelling with a size, and whether its family has a precise form.
        let mut spellings: Vec<(String, bool)> = families
            .iter()
            .flat_map(|f| {
                let p = f.precise();
                f.info().spellings().into_iter().map(move |(s, _)| (s, p))
            })
            .collect();
        let key = |(v, _): &(String, bool)| (!related(v), strsim::levenshtein(sized, v));
        spellings.sort_by_key(|v| (key(v), v.0.clone()));
        let best = key(&spellings[0]);
        spellings
            .iter()
            .take_while(|v| key(v) == best)
            .map(|(v, p)| {
                if precise && *p {
                    format!("{v}p")
                } else {
                    v.clone()
                }
            })
            .collect()
    } else {
        let best = key(&valid[0]);
        valid
            .iter()
            .take_while(|v| key(v) == best)
            .cloned()
            .collect()
    };
    SpecError::UnknownCodec {
        given: given.to_string(),
        nearest,
        valid,
    }
}

/// A codec family in the registry. Everything about it lives in its own file; nothing
/// outside that file names it.
/// Traces so far by spec id ([`Spec::traces`]).
static TRACE_COUNTS: Mutex<BTreeMap<String, usize>> = Mutex::new(BTreeMap::new());

/// Leave to trace a spec: [`Spec::emitted`] alone makes one, so that no path can trace
/// a spec again behind its memo. A family may hand it on to the families it is made of.
#[derive(Clone, Copy)]
pub struct Tracing(());

/// A registry of families, in `list` order: the parser reads the one it is handed
/// (`crate::codecs::FAMILIES`), never a global of its own.
pub type Families = &'static [&'static dyn Family];

pub trait Family: Sync + 'static {
    fn info(&self) -> &Info;
    /// Whether the precise (`p`) encoder is offered. A codec family returns its codec's
    /// `Codec::EXACT_SEARCH` (offered only where the search is decided in exact
    /// arithmetic, so the precise packed encoder is portable); a family that has no such
    /// codec, or whose search does not fit its layout (`snorm11_11_10`), returns a
    /// literal with its reason beside it.
    fn precise(&self) -> bool;
    /// Checks that combine the size and options (each option's own range is checked by
    /// the parser).
    fn validate(&self, _spec: &Spec) -> Result<(), SpecError> {
        Ok(())
    }
    /// Specs `generate` writes besides every size with default options (with and without
    /// the precise encoder), written as spec strings.
    fn variants(&self) -> &'static [&'static str] {
        &[]
    }
    /// Traces the spec and lists its public functions (called by [`Spec::emitted`] alone).
    fn emitted(&self, spec: &Spec, tracing: Tracing) -> Emitted;
    /// The lookup tables the spec's shader functions read, which `generate` writes
    /// beside the includes.
    fn tables(&self, _spec: &Spec) -> Vec<Table> {
        Vec::new()
    }
    /// What a function's doc comment says of its input and output, where the family's
    /// functions are not the standard four (a lookup-table codec's pieces).
    fn function_doc(&self, _spec: &Spec, _name: &str) -> Option<Vec<String>> {
        None
    }
    /// The doc comment of a helper function this family defines, if it has one.
    fn helper_doc(&self, _name: &str) -> Option<String> {
        None
    }
    /// The engine whose stored bits an engine format reproduces ([`crate::codecs::engine`]):
    /// its degenerate input and its rounding are that engine's, not the catalogue's
    /// conventions.
    fn engine(&self, _spec: &Spec) -> Option<&'static str> {
        None
    }
    /// Whether the encoders take the input as it is rather than its direction: glTF's
    /// quantization clamps each component and normalizes nothing, as gltf-transform does.
    /// The catalogue's conventions for non-unit and degenerate input (normalized first;
    /// zero, NaN and infinite input as +Z) do not apply; the family's edge policy says
    /// what does, and its own tests hold it.
    fn keeps_length(&self) -> bool {
        false
    }
    /// Whether the family codes tangent frames ([`crate::codecs::frames`]): its encoders
    /// take a normal and a tangent, its decoders return the struct `frame`, and the
    /// normal codecs' error statistics, bounds and choices do not apply.
    fn frames(&self) -> bool {
        false
    }
    /// Whether the family's arithmetic (an engine's, in the lean tier) sums products at
    /// every step, which a compiler free to contract fuses: OpenGL's GLSL compiler without
    /// `precise` ([`crate::verify::Path::contracts`]). There its
    /// outputs are measured, not held; the lean tier promises nothing where operations are
    /// contracted. Filament's frame arithmetic (cross products, `extractQuat`) does;
    /// every other family's outputs are held there too.
    fn contracted(&self, _spec: &Spec) -> bool {
        false
    }
    /// What a filter or a resolve may do with the spec's float form: the family's
    /// [`Info::float_form`], unless an option changes how the texel holds it.
    fn float_form(&self, _spec: &Spec) -> FloatForm {
        self.info().float_form
    }
    /// What the family's encoders take, as `list` and the docs name it: its domain
    /// (`sphere`, `hemisphere`), `frame`, or nothing for packing helpers.
    fn takes(&self) -> Option<&'static str> {
        if self.frames() {
            Some("frame")
        } else {
            self.info().domain.map(|d| d.name())
        }
    }
}

/// A lookup table a spec's functions read: `width × height` texels of `channels`
/// elements each (unorm8 bytes, or little-endian 32-bit words), row after row (the
/// texel's y), as it is uploaded.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Table {
    /// File name without extension (`spherical_lut16_atan`).
    pub stem: String,
    pub width: u32,
    pub height: u32,
    /// 1 (R8, R32UI), 2 (RG32UI) or 4 (RGBA8).
    pub channels: u8,
    pub format: TableFormat,
    pub bytes: Vec<u8>,
}

/// A table's element type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TableFormat {
    /// unorm8 channels: a texture, also written as a PNG.
    Unorm8,
    /// 32-bit unsigned integers, little-endian: a buffer or an integer texture, written
    /// as raw bytes only.
    Uint32,
}
