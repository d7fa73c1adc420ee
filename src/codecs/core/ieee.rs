//! The lean tier, `guarantee=ieee`: a codec's encoders in the plain arithmetic of its
//! source, for a user who runs only where `+ - * /` and `sqrt` round correctly to nearest,
//! denormals are kept and nothing is contracted (lavapipe, C with `-ffp-contract=off`,
//! the CPU), or who does not need the same codes everywhere.
//!
//! The default tier (`guarantee=portable`) decides every code with exact comparisons
//! ([`crate::codecs::toolkit::exact`], [`crate::codecs::toolkit::lattice`]) and scales
//! tiny and huge input into range, so that the code survives every liberty the APIs
//! allow; that costs instructions (oct16's packed encoder: 56, its octahedral core 20).
//! Here the fast encoder rounds the parameters ([`Codec::round_codes`]' default) of the
//! codec's [`Codec::ieee_params`]; there is no lean precise encoder ([`validate`]).
//! Decoders are the default tier's, unchanged. Zero, NaN and infinite input encode as +Z,
//! as in the default tier; finite input so large or so small that its norm overflows or underflows in plain
//! arithmetic gets a defined code, which need not be its direction's (the default tier
//! scales such input into range first).

use crate::codecs::core::codec::{Codec, Params, quantize};
use crate::codecs::core::info::{Domain, OptDesc, OptKind, OptVal};
use crate::codecs::core::pipeline::codec_functions;
use crate::codecs::core::spec::{Spec, SpecError};
use crate::codecs::functions::function::Emitted;
use crate::codecs::functions::words::{Bits, Lanes, Lanes8};
use crate::codecs::toolkit::quant::Quants;
use crate::model::avx2_lanes::F8;
use crate::model::deviant::Dev;
use crate::model::lanes::F4;
use crate::model::num::helper;
use crate::model::{Float, V3};

/// The `guarantee` option of a family with a lean tier.
pub const OPTION: OptDesc = OptDesc {
    key: "guarantee",
    help: "portable: the same codes on every implementation the include's header names; ieee: the lean arithmetic of the source, not portable: bit-exact only where + - * / sqrt round correctly, denormals are kept and nothing is contracted (lavapipe, C with -ffp-contract=off, the CPU)",
    kind: OptKind::Choice(&["portable", "ieee"]),
};

/// The `guarantee` option of an engine format ([`crate::codecs::engine`]): its encoder is
/// the engine's own arithmetic, so the lean tier is its only one.
pub const ENGINE_OPTION: OptDesc = OptDesc {
    key: "guarantee",
    help: "ieee (the only tier): the engine's own encoder arithmetic, bit-exact where + - * / sqrt round correctly, denormals are kept and nothing is contracted (the CPU, lavapipe, C with -ffp-contract=off), as where the engine itself encodes",
    kind: OptKind::Choice(&["ieee"]),
};

/// Whether the spec asks for the lean tier. An engine's format always does, whether its
/// family offers the `guarantee` option ([`ENGINE_OPTION`]) or, where the family's other
/// sizes are not an engine's (`qtangent32` beside Filament's `qtangent64`), not.
pub fn asked(spec: &Spec) -> bool {
    let info = spec.info();
    spec.family().engine(spec).is_some()
        || info.option_index(OPTION.key).is_some_and(|i| {
            matches!(
                (&info.options[i].kind, spec.option(&OPTION)),
                (OptKind::Choice(names), Some(OptVal::Choice(c))) if names[c] == "ieee"
            )
        })
}

/// The lean tier is the fast encoder's, in a codec's own packing: the precise search
/// runs where its cost does not matter (offline, at asset time), so it keeps the portable
/// form, and a texel layout's channels are decided in the default tier only.
pub fn validate(spec: &Spec, layout: bool) -> Result<(), SpecError> {
    let why = if !asked(spec) {
        return Ok(());
    } else if layout {
        "the ieee tier covers the codec's own packing, not a texel layout"
    } else if spec.precise() {
        "the ieee tier is the fast encoder's: the precise search (p) runs offline, where \
         its portable form costs nothing at run time"
    } else {
        return Ok(());
    };
    Err(SpecError::BadValue {
        key: OPTION.key.into(),
        value: "ieee".into(),
        why: why.into(),
    })
}

/// A codec in the lean tier.
#[derive(Clone, Copy, Debug)]
pub struct Ieee<C>(pub C);

impl<C: Codec> Codec for Ieee<C> {
    type P<F: Float> = C::P<F>;
    type C<F: Float> = C::C<F>;
    #[inline]
    fn quants(&self) -> Quants {
        self.0.quants()
    }
    fn domain(&self) -> Domain {
        self.0.domain()
    }
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> C::P<F> {
        self.0.ieee_params(v)
    }
    #[inline(always)]
    fn direction<F: Float>(&self, p: C::P<F>) -> V3<F> {
        self.0.direction(p)
    }
    #[inline(always)]
    fn decode_codes<F: Float>(&self, codes: C::P<F>) -> V3<F> {
        self.0.decode_codes(codes)
    }
    fn whole_field(&self) -> Option<usize> {
        self.0.whole_field()
    }
    fn unread_fields(&self) -> &'static [usize] {
        self.0.unread_fields()
    }
    /// The default rounding of the parameters, without the clamp where the codec's
    /// [`Codec::IEEE_IN_RANGE`] says they cannot leave the range.
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> C::P<F> {
        let p = helper!("encode_float" => self.params(v));
        let q = self.quants();
        let codes = if C::IEEE_IN_RANGE {
            C::P::<F>::build(
                #[inline(always)]
                |i| q[i].quantize_in_range(p.lane(i)),
            )
        } else {
            quantize(&q, p)
        };
        codes.named_p("codes")
    }
}

/// The functions of a spec of a family with a lean tier: `default` (the family's own
/// emission) unless the spec asks for `guarantee=ieee`.
pub(crate) fn functions<C: Codec + Clone + 'static>(
    spec: &Spec,
    c: C,
    default: fn(&Spec, C) -> Emitted,
) -> Emitted
where
    C::P<f32>: Bits,
    C::C<f32>: Bits,
    C::P<Dev>: Bits,
    C::C<Dev>: Bits,
    C::P<F4>: Bits<Lanes>,
    C::C<F4>: Bits<Lanes>,
    C::P<F8>: Bits<Lanes8>,
    C::C<F8>: Bits<Lanes8>,
{
    if asked(spec) {
        codec_functions(spec, Ieee(c))
    } else {
        default(spec, c)
    }
}
