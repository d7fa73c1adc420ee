//! A code that is one index `i` of a point set, its low half in the first field and its
//! high half in the second (both unorm), so that the packed word is `i` itself
//! (`angular::sfib`'s spiral points, `cube_maps::eac`'s faces): the fields, the index of
//! their codes, and the float form a fetch of them returns.

use crate::codecs::toolkit::quant::{Quant, Quants};
use crate::model::{Float, Uint, V2};

/// The two halves of a `bits`-bit index.
#[derive(Clone, Copy, Debug)]
pub struct Halves {
    pub bits: u32,
}

impl Halves {
    /// Two unorm fields of `bits / 2` bits each.
    pub fn quants(self) -> Quants {
        Quants::new(&[Quant::Unorm(self.bits / 2); 2])
    }

    /// The two fields' codes of index `i`: its low and its high half.
    #[inline(always)]
    pub fn fields<F: Float>(self, i: F::U) -> V2<F> {
        let h = self.bits / 2;
        V2::new((i & F::U::c((1 << h) - 1)).to_f(), i.shr(h).to_f())
    }

    /// The index of the two fields' codes (a sum, not an or: the same bits, and an
    /// interval evaluation keeps a single code a single index).
    #[inline(always)]
    pub fn index<F: Float>(self, codes: V2<F>) -> F::U {
        codes.x.to_u() + codes.y.to_u().shl(self.bits / 2)
    }

    /// The fields' codes as a texture fetch returns them, `c/M`: the float form.
    #[inline(always)]
    pub fn fetched<F: Float>(self, codes: V2<F>) -> V2<F> {
        codes * F::c(1.0 / self.max_code())
    }

    /// The codes of a fetched float form, re-quantized (`round(p·M)`, exact for a
    /// fetched `c/M`).
    #[inline(always)]
    pub fn codes<F: Float>(self, p: V2<F>) -> V2<F> {
        (p * F::c(self.max_code())).round()
    }

    fn max_code(self) -> f32 {
        Quant::Unorm(self.bits / 2).max_code()
    }
}
