//! The CPU library for asset pipelines: the same `f32` model the emitted shaders are
//! verified against, so codes encoded here are the codes the shader encoder writes, and
//! the shader decoder turns them into the same vectors as [`Encoder::decode`] — exactly,
//! on implementations with correctly rounded arithmetic that keep denormals and do not
//! fuse multiply-adds (verified on lavapipe; see the README on real GPUs).
//!
//! ```
//! use unitpack::api::{CpuCodec, Oct};
//!
//! let oct = Oct::new(24).unwrap().precise();
//! let code: u32 = oct.encode([0.0, 0.6, 0.8]);
//! let v = oct.decode(code);
//! assert!((v[1] - 0.6).abs() < 1e-3 && (v[2] - 0.8).abs() < 1e-3);
//!
//! // Batches over slices, e.g. a mesh's normals into an RG16_SNORM-style buffer.
//! let normals = vec![[0.0, 0.0, 1.0]; 4];
//! let mut codes = vec![0u32; 4];
//! Oct::new(32).unwrap().fast().encode_slice(&normals, &mut codes);
//! assert!(codes.iter().all(|&c| c == codes[0]));
//! ```

use crate::codecs::SpecError;
use crate::codecs::codec::Codec;
use crate::codecs::functions::{decode_packed, encode_packed};
pub use crate::codecs::hemioct::HemiOct;
pub use crate::codecs::lambert::Lambert;
pub use crate::codecs::oct::Oct;
pub use crate::codecs::spherical::Spherical;
pub use crate::codecs::stereo::StereoScaled;
pub use crate::codecs::xy::Xy;
use crate::model::V3;

/// A codec with its encoder chosen (fast: nearest codes; precise: the survey's "P" search).
#[derive(Clone, Copy, Debug)]
pub struct Encoder<C> {
    pub codec: C,
    pub precise: bool,
}

/// Encoders and decoders on the CPU, for every codec.
pub trait CpuCodec: Codec + Sized {
    /// The nearest-code encoder.
    fn fast(self) -> Encoder<Self> {
        Encoder {
            codec: self,
            precise: false,
        }
    }
    /// The precise encoder: the candidate code whose decode is nearest the input.
    fn precise(self) -> Encoder<Self> {
        Encoder {
            codec: self,
            precise: true,
        }
    }
}
impl<C: Codec> CpuCodec for C {}

impl<C: Codec> Encoder<C> {
    /// The packed code of `v` (any vector; see the codec's zero/NaN policy).
    #[inline]
    pub fn encode(&self, v: [f32; 3]) -> C::C<f32> {
        encode_packed(&self.codec, self.precise, V3::from_array(v))
    }
    /// The direction a packed code stands for.
    #[inline]
    pub fn decode(&self, code: C::C<f32>) -> [f32; 3] {
        decode_packed(&self.codec, code).to_array()
    }
    /// Encodes `input` into `out` (same length).
    pub fn encode_slice(&self, input: &[[f32; 3]], out: &mut [C::C<f32>]) {
        assert_eq!(
            input.len(),
            out.len(),
            "encode_slice: input and output lengths differ"
        );
        for (o, v) in out.iter_mut().zip(input) {
            *o = self.encode(*v);
        }
    }
    /// Decodes `input` into `out` (same length).
    pub fn decode_slice(&self, input: &[C::C<f32>], out: &mut [[f32; 3]]) {
        assert_eq!(
            input.len(),
            out.len(),
            "decode_slice: input and output lengths differ"
        );
        for (o, c) in out.iter_mut().zip(input) {
            *o = self.decode(*c);
        }
    }
}

fn checked(name: &'static str, bits: u32) -> Result<u32, SpecError> {
    crate::codecs::catalogue::desc(name).check_bits(&bits.to_string())
}

macro_rules! constructor {
    ($T:ident, $name:literal) => {
        impl $T {
            /// A codec with the given total bit budget; an invalid size is an error listing
            /// the allowed ones.
            pub fn new(bits: u32) -> Result<$T, SpecError> {
                Ok($T {
                    bits: checked($name, bits)?,
                })
            }
        }
    };
}
constructor!(Oct, "oct");
constructor!(HemiOct, "hemioct");
constructor!(Spherical, "spherical");
constructor!(Lambert, "lambert");
constructor!(Xy, "xy");

impl StereoScaled {
    /// Scaled stereographic with the seed's default scale (1.7777); see [`StereoScaled::with_scale`].
    pub fn new(bits: u32) -> Result<StereoScaled, SpecError> {
        Ok(StereoScaled {
            bits: checked("stereo_scaled", bits)?,
            scale: crate::codecs::stereo::DEFAULT_SCALE,
        })
    }
    /// The same codec with another scale; see [`crate::codecs::stereo::SCALE_RANGE`].
    pub fn with_scale(self, scale: f32) -> Result<StereoScaled, SpecError> {
        if crate::codecs::stereo::SCALE_RANGE.contains(&scale) {
            Ok(StereoScaled { scale, ..self })
        } else {
            Err(SpecError::BadValue {
                key: "scale".into(),
                value: scale.to_string(),
                why: "scale must lie in [0.001, 1000]",
            })
        }
    }
}
