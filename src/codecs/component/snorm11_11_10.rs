//! snorm11_11_10 (survey Table 1): [`Snorm3`] with x and y in 11 bits and z in 10, the
//! three fields of one 32-bit word, x in the lowest bits (bits 0–10 x, 11–21 y, 22–31 z).

use crate::codecs::core::info::Domain;
use crate::codecs::core::info::{Info, Sizes, FloatForm, seam};
use crate::codecs::core::spec::{Family, Tracing};
use crate::codecs::functions::function::Emitted;
use crate::codecs::core::pipeline::codec_functions;
use crate::codecs::component::snorm3::Snorm3;
use crate::codecs::core::spec::Spec;

pub static FAMILY: Snorm111110Family = Snorm111110Family;

pub struct Snorm111110Family;

static INFO: Info = Info {
    name: "snorm11_11_10",
    title: "components as snorm 11, 11 and 10 bits in one word (x lowest)",
    sizes: Sizes::Fixed(32),
    domain: Some(Domain::Sphere),
    source: "Cigolle et al. 2014 §2 and Table 1",
    edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z",
    decode_note: "decode re-normalizes; the all-zero code decodes as +Z",
    float_form: FloatForm::Continuous { seam: seam::NONE_PER_COMPONENT },
    options: &[],
};

impl Family for Snorm111110Family {
    fn info(&self) -> &Info {
        &INFO
    }
    fn precise(&self) -> bool {
        // Snorm3's precise search is not made for fields of unequal sizes: on 11, 11 and
        // 10 bits it picks codes far from the input (tests/figures/cover.rs finds one 19°
        // beyond reach), so this layout offers the fast encoder only.
        false
    }
    fn emitted(&self, spec: &Spec, _: Tracing) -> Emitted {
        codec_functions(spec, Snorm3::snorm11_11_10())
    }
}
