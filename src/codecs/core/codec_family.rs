//! The common family: one codec type whose codec follows from the spec's total bits.
//! A family file then holds its [`Info`], how a size becomes a codec, how the codec's
//! functions are emitted (its own packing, or also the texel layouts), and the docs of
//! its helpers, in one `static`; everything else a [`Family`] says follows from these.
//! Families whose sizes pick different codec types (`oct`, `snorm3`, `float3`) or that
//! are no codec at all (lookup tables, `paraboloid_pd`) implement [`Family`] by hand.

use crate::codecs::core::codec::Codec;
use crate::codecs::core::info::Info;
use crate::codecs::core::spec::{Family, Spec, SpecError, Tracing};
use crate::codecs::functions::function::Emitted;

/// A [`Family`] of one codec type `C`.
pub struct CodecFamily<C> {
    pub info: Info,
    /// The codec of a valid total size, its options at their defaults.
    sized: fn(u32) -> C,
    /// The sized codec with the spec's options that change it (meshopt's K, a scale, a
    /// decoder form), read by key ([`Spec::choice_of`], [`Spec::number_of`]).
    configure: fn(&Spec, C) -> C,
    /// Traces and lists the spec's functions for its codec (`codec_functions`, or
    /// `texel::functions` for a family with the texel layouts).
    emit: fn(&Spec, C) -> Emitted,
    validate: fn(&Spec) -> Result<(), SpecError>,
    variants: &'static [&'static str],
    helper_doc: fn(&str) -> Option<String>,
    engine: Option<&'static str>,
}

impl<C> CodecFamily<C> {
    /// A family without options and without helper docs.
    pub const fn new(info: Info, sized: fn(u32) -> C, emit: fn(&Spec, C) -> Emitted) -> Self {
        CodecFamily {
            info,
            sized,
            configure: |_, c| c,
            emit,
            validate: |_| Ok(()),
            variants: &[],
            helper_doc: |_| None,
            engine: None,
        }
    }

    /// With the options that change the codec applied to it ([`CodecFamily::codec_of`]).
    pub const fn with_options(self, configure: fn(&Spec, C) -> C) -> Self {
        CodecFamily { configure, ..self }
    }

    /// With the check that combines the options with the size ([`Family::validate`]).
    pub const fn with_validate(self, validate: fn(&Spec) -> Result<(), SpecError>) -> Self {
        CodecFamily { validate, ..self }
    }

    /// With the specs `generate` writes besides the defaults ([`Family::variants`]).
    pub const fn with_variants(self, variants: &'static [&'static str]) -> Self {
        CodecFamily { variants, ..self }
    }

    /// With doc comments for the helper functions the codec defines
    /// ([`Family::helper_doc`]).
    pub const fn with_helper_doc(self, helper_doc: fn(&str) -> Option<String>) -> Self {
        CodecFamily { helper_doc, ..self }
    }

    /// An engine format: the engine whose bits it reproduces ([`Family::engine`]).
    pub const fn with_engine(self, engine: &'static str) -> Self {
        CodecFamily {
            engine: Some(engine),
            ..self
        }
    }

    /// The codec of `bits` total bits; an invalid size is an error listing the allowed ones.
    pub fn codec(&self, bits: u32) -> Result<C, SpecError> {
        self.info.check_bits(bits).map(self.sized)
    }

    /// The codec a spec of this family names: its size and its options.
    pub fn codec_of(&self, spec: &Spec) -> C {
        (self.configure)(spec, (self.sized)(spec.bits()))
    }
}

impl<C: Codec + 'static> Family for CodecFamily<C> {
    fn info(&self) -> &Info {
        &self.info
    }
    /// The codec's own: offered where its search is exact.
    fn precise(&self) -> bool {
        C::EXACT_SEARCH
    }
    fn validate(&self, spec: &Spec) -> Result<(), SpecError> {
        (self.validate)(spec)
    }
    fn variants(&self) -> &'static [&'static str] {
        self.variants
    }
    fn emitted(&self, spec: &Spec, _: Tracing) -> Emitted {
        (self.emit)(spec, self.codec_of(spec))
    }
    fn helper_doc(&self, name: &str) -> Option<String> {
        (self.helper_doc)(name)
    }
    fn engine(&self, _spec: &Spec) -> Option<&'static str> {
        self.engine
    }
}
