//! Normal-map texel layouts (fourth seed): a two-parameter hemisphere codec's parameters
//! stored in the 8-bit unorm channels of an RGBA8 texel, as block-compressed normal maps
//! hold them. The packed code is the texel as a `u32` (R in the lowest byte); each
//! parameter `p` is stored as `p·½ + ½`, whose code the wrapped codec decides exactly in
//! its unorm form ([`TexelCodec`]), so the packed encoders stay portable. The float
//! forms are what a shader sees: `encode_float` returns the texel's four channels (what a
//! render target stores), `decode_float` takes the fetched `vec4`.
//!
//! | layout | R | G | B | A | decoder reads |
//! |---|---|---|---|---|---|
//! | `rg` (BC5, RGTC, 3Dc) | x | y | 0 | 1 | R, G |
//! | `dxt5nm` (nvdxt) | 1 | y | 0 | x | A, G |
//! | `rxgb` (Doom 3) | 1 | y | z | x | A, G (B holds the input's z for readers of `.agb`) |
//! | `latc` (luminance–alpha) | y | y | y | x | A, G |
//! | `xra` | 1 | y | 0 | x | x = R·A, G (`encode_dxt1` writes x in R and A = 1) |
//!
//! Parameters are stored unorm as the hardware expects, so `p = 0` has no code: it
//! rounds up to 128 (`p = 1/255`), and invalid input encodes as `(128, 128)`.
//!
//! On the CPU a layout wraps the codec (its 16-bit form; the wrapped codec's own size
//! does not matter, the channels are always 8 bits):
//!
//! ```
//! use unitpack::api::{CpuCodec, Layout, Texel, Xy};
//!
//! let dxt5nm = Texel { inner: Xy::new(16).unwrap(), layout: Layout::Dxt5nm }.precise();
//! let t: u32 = dxt5nm.encode([0.6, 0.0, 0.8]);
//! assert_eq!(t.to_le_bytes(), [0xff, 0x80, 0x00, 0xcc]); // R = 1, G = y, B = 0, A = x
//! let n = dxt5nm.decode(t);
//! assert!((n[0] - 0.6).abs() < 4e-3 && (n[2] - 0.8).abs() < 4e-3);
//! ```

use crate::codecs::core::codec::{Codec, Params, above_horizon};
use crate::codecs::core::info::{Domain, OptDesc, OptKind, OptVal};
use crate::codecs::core::pipeline::codec_functions;
use crate::codecs::core::spec::{Spec, SpecError};
use crate::codecs::functions::function::Emitted;
use crate::codecs::functions::words::{Bits, Lanes, Lanes8};
use crate::codecs::toolkit::exact::{canonical_or_z, length2, unorm_sqrt_ratio};
use crate::codecs::toolkit::quant::{Quant, Quants};
use crate::model::avx2_lanes::F8;
use crate::model::deviant::Dev;
use crate::model::lanes::F4;
use crate::model::{Float, V2, V3, V4};

/// The storage of one channel.
pub const CHANNEL: Quant = Quant::Unorm(8);

/// Where a two-parameter codec's codes go in an RGBA8 texel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Layout {
    Rg,
    Dxt5nm,
    Rxgb,
    Latc,
    Xra,
}

impl Layout {
    /// The layout option's values; the first, `snorm`, is the codec's own packing.
    pub const CHOICES: &'static [&'static str] = &["snorm", "rg", "dxt5nm", "rxgb", "latc", "xra"];
    pub const HELP: &'static str = "the 16-bit form's two parameters as unorm8 p·½+½ in an RGBA8 texel (the code is the texel as a u32, R lowest; the float forms take and return the fetched vec4): rg = BC5/RGTC (x R, y G), dxt5nm = nvdxt (x A, y G, R = 1), rxgb = Doom 3 (x A, y G, the input's z B, R = 1), latc = luminance-alpha (x A, y in R, G and B), xra = x read as R·A (encode: x A, R = 1 for DXT5; encode_dxt1: x R, A = 1 for DXT1)";

    /// The layout of a `layout=` choice index (`None` for the default, `snorm`).
    pub fn from_choice(i: usize) -> Option<Layout> {
        [
            Layout::Rg,
            Layout::Dxt5nm,
            Layout::Rxgb,
            Layout::Latc,
            Layout::Xra,
        ]
        .get(i.checked_sub(1)?)
        .copied()
    }

    /// The texel of the parameters' channel values `x`, `y` (codes, or values in
    /// `[0, 1]`), `z` (rxgb's blue) and the value of a full channel, `one`.
    #[inline(always)]
    fn texel<F: Float>(self, x: F, y: F, z: F, one: F) -> V4<F> {
        let zero = F::c(0.0);
        let t = match self {
            Layout::Rg => [x, y, zero, one],
            Layout::Dxt5nm | Layout::Xra => [one, y, zero, x],
            Layout::Rxgb => [one, y, z, x],
            Layout::Latc => [y, y, y, x],
        };
        V4::from_array(F::fuse(t))
    }

    /// The parameters' channels of a fetched texel.
    #[inline(always)]
    fn read<F: Float>(self, t: V4<F>) -> V2<F> {
        let x = match self {
            Layout::Rg => t.x,
            Layout::Dxt5nm | Layout::Rxgb | Layout::Latc => t.w,
            Layout::Xra => t.x * t.w,
        };
        let y = t.y;
        V2::from_array(F::fuse([x, y]))
    }

    /// The channels, for doc comments (`x`, `y` the parameters).
    pub fn channels(self) -> &'static str {
        match self {
            Layout::Rg => "R = x, G = y, B = 0, A = 255",
            Layout::Dxt5nm | Layout::Xra => "R = 255, G = y, B = 0, A = x",
            Layout::Rxgb => "R = 255, G = y, B = the input's z (z·½ + ½), A = x",
            Layout::Latc => "R = G = B = y, A = x",
        }
    }

    /// What the decoder reads, for doc comments.
    pub fn reads(self) -> &'static str {
        match self {
            Layout::Rg => "x from R, y from G",
            Layout::Dxt5nm | Layout::Rxgb | Layout::Latc => "x from A, y from G",
            Layout::Xra => "x = R·A (a DXT1 texel has A = 1, a DXT5 one R = 1), y from G",
        }
    }

    /// The channels the decoder does not read (their values cannot change a decode).
    pub fn unread(self) -> &'static [usize] {
        match self {
            Layout::Rg => &[2, 3],
            Layout::Dxt5nm | Layout::Rxgb | Layout::Latc => &[0, 2],
            Layout::Xra => &[2],
        }
    }
}

/// The `layout` option of a two-parameter hemisphere family.
pub const OPTION: OptDesc = OptDesc {
    key: "layout",
    help: Layout::HELP,
    kind: OptKind::Choice(Layout::CHOICES),
};

/// The texel layout a spec asks for (`None`: the codec's own packing, or a family
/// without this option — oct's `layout` is another one).
pub fn layout(spec: &Spec) -> Option<Layout> {
    let i = spec.info().option_index(OPTION.key)?;
    match (&spec.info().options[i].kind, spec.option(&OPTION)?) {
        (OptKind::Choice(c), OptVal::Choice(chosen)) if *c == Layout::CHOICES => {
            Layout::from_choice(chosen)
        }
        _ => None,
    }
}

/// A texel holds two 8-bit parameters: the family's 16-bit form.
pub fn validate(spec: &Spec) -> Result<(), SpecError> {
    let Some(OptVal::Choice(chosen)) = spec.option(&OPTION) else {
        return Ok(());
    };
    if chosen > 0 && spec.bits() != 16 {
        return Err(SpecError::BadValue {
            key: OPTION.key.into(),
            value: Layout::CHOICES[chosen].into(),
            why: format!(
                "a texel layout holds the 16-bit form only ({}16)",
                spec.info().name
            ),
        });
    }
    Ok(())
}

/// The functions of a spec of a family with the texel layouts: its codec in the layout
/// the spec asks for, or in its own packing.
pub(crate) fn functions<C: TexelCodec>(spec: &Spec, c: C) -> Emitted
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
    match layout(spec) {
        Some(layout) => codec_functions(spec, Texel { inner: c, layout }),
        None => codec_functions(spec, c),
    }
}

/// `generate`'s variants of a family: its 16-bit form in every layout, then any others.
macro_rules! texel_variants {
    ($name:literal $(, $more:literal)*) => {
        &[
            concat!($name, "16:layout=rg"),
            concat!($name, "16:layout=dxt5nm"),
            concat!($name, "16:layout=rxgb"),
            concat!($name, "16:layout=latc"),
            concat!($name, "16:layout=xra"),
            $($more,)*
        ]
    };
}
pub(crate) use texel_variants;

/// A two-parameter hemisphere codec whose exact encoders decide codes in any field: its
/// own snorm one, or a texel channel ([`CHANNEL`]), each parameter then stored as
/// `p·½ + ½`. Its `Codec` methods are these with its own field.
pub trait TexelCodec: Codec + Clone + 'static {
    /// [`Codec::params`], as a pair.
    fn params2<F: Float>(&self, v: V3<F>) -> V2<F>;
    /// [`Codec::direction`] of a pair.
    fn direction2<F: Float>(&self, p: V2<F>) -> V3<F>;
    /// [`Codec::round_codes`] in the field `q`.
    fn round_in<F: Float>(&self, q: Quant, v: V3<F>) -> V2<F>;
    /// [`Codec::precise_codes`] in the field `q`.
    fn precise_in<F: Float>(&self, q: Quant, v: V3<F>) -> V2<F>;
}

/// A codec's 16-bit form in an RGBA8 texel.
#[derive(Clone, Copy, Debug)]
pub struct Texel<C> {
    pub inner: C,
    pub layout: Layout,
}

impl<C: TexelCodec> Texel<C> {
    /// The texel of the codes `c` and, for rxgb, the input's `z` as a code.
    #[inline(always)]
    fn codes<F: Float>(&self, c: V2<F>, v: V3<F>) -> V4<F> {
        let z = if self.layout == Layout::Rxgb {
            z_code(v)
        } else {
            F::c(0.0)
        };
        self.layout.texel(c.x, c.y, z, F::c(CHANNEL.max_code()))
    }
}

/// The unorm8 code of `z·½ + ½` of the input's unit direction on the hemisphere, decided
/// exactly ([`unorm_sqrt_ratio`]); input without a direction there stands in as +Z (255).
#[inline(always)]
fn z_code<F: Float>(v: V3<F>) -> F {
    let (w, _) = canonical_or_z(v);
    let (h, _) = canonical_or_z(above_horizon(w));
    let s = length2(h);
    unorm_sqrt_ratio(CHANNEL, h.z, s, s.sqrt(), 0.5)
}

impl<C: TexelCodec> Codec for Texel<C> {
    type P<F: Float> = V4<F>;
    type C<F: Float> = F::U;
    #[inline]
    fn quants(&self) -> Quants {
        Quants::new(&[CHANNEL; 4])
    }
    fn domain(&self) -> Domain {
        Domain::Hemisphere
    }
    /// The texel a render target should hold: `p·½ + ½` of the codec's parameters,
    /// rxgb's blue `z·½ + ½` of the input's direction, full channels 1.
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V4<F> {
        let half = {
            #[inline(always)]
            |x: F| F::c(0.5) + x * F::c(0.5)
        };
        let p = self.inner.params2(v).named("p");
        let z = if self.layout == Layout::Rxgb {
            half(self.inner.target(v).z)
        } else {
            F::c(0.0)
        };
        self.layout.texel(half(p.x), half(p.y), z, F::c(1.0))
    }
    /// The parameters `2t - 1` of the texel's channels (`t·2` is exact, so a fused
    /// multiply-add computes the same), then the codec's decode.
    #[inline(always)]
    fn direction<F: Float>(&self, t: V4<F>) -> V3<F> {
        let p = self
            .layout
            .read(t)
            .map(
                #[inline(always)]
                |x| x * F::c(2.0) - F::c(1.0),
            )
            .named("p");
        self.inner.direction2(p)
    }
    fn unread_fields(&self) -> &'static [usize] {
        self.layout.unread()
    }
    const EXACT_ROUNDING: bool = C::EXACT_ROUNDING;
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V4<F> {
        let c = self.inner.round_in(CHANNEL, v).named("c");
        self.codes(c, v)
    }
    const EXACT_SEARCH: bool = C::EXACT_SEARCH;
    #[inline(always)]
    fn precise_codes<F: Float>(&self, v: V3<F>) -> V4<F> {
        let c = self.inner.precise_in(CHANNEL, v).named("c");
        self.codes(c, v)
    }
    fn alternate(&self) -> Option<&'static str> {
        (self.layout == Layout::Xra).then_some("encode_dxt1")
    }
    /// xra's DXT1 texel: x in R and A = 1, the DXT5 texel with R and A swapped.
    #[inline(always)]
    fn alternate_codes<F: Float>(&self, c: V4<F>) -> V4<F> {
        V4::build(
            #[inline(always)]
            |i| c.lane([3, 1, 2, 0][i]),
        )
    }
}
