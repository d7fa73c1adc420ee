//! The second seed's detail combine (`CombineParaboloidNormalWithPD`, from the comments
//! under "Improved Normal-map Distributions"): a primary normal map stored as
//! [`crate::codecs::azimuthal::paraboloid`] points, a detail map stored as partial derivatives, combined
//! per texel without decoding the primary to a unit vector first. The detail's slopes
//! are scaled by the primary's height `nz` before they are added, so detail fades
//! towards the horizon, where the paraboloid's precision is spent.
//!
//! Written as the seed writes it, `nz = saturate(1 - x·x - y·y)` (two differences, not
//! the decoder's `1 - saturate(p·p)`), so the emitted code is the one the seed's users
//! know; with `pd = 0` it is the paraboloid decode up to that rounding.

use crate::codecs::core::info::{Info, Sizes, FloatForm};
use crate::codecs::core::spec::{Family, Tracing};
use crate::codecs::functions::function::{Emitted, Inputs, Role};
use crate::codecs::functions::words::{declared, trace_declared};
use crate::codecs::toolkit::quant::Quant;
use crate::codecs::core::spec::Spec;
use crate::model::{Float, V2, V3};

pub static FAMILY: ParaboloidPdFamily = ParaboloidPdFamily;

pub struct ParaboloidPdFamily;

static INFO: Info = Info {
    name: "paraboloid_pd",
    title: "combine a paraboloid normal with a partial-derivative detail normal",
    sizes: Sizes::Fixed(0),
    domain: None,
    source: "Improved Normal-map Distributions (Insomniac), CombineParaboloidNormalWithPD",
    edge_policy: "any finite input; the paraboloid point may lie outside the unit disk (its height is then 0)",
    decode_note: "a unit vector (up to rounding) for any finite input",
    float_form: FloatForm::Absent,
    options: &[],
};

/// The emitted function's name.
const NAME: &str = "combine_paraboloid_pd";

impl Family for ParaboloidPdFamily {
    fn info(&self) -> &Info {
        &INFO
    }
    fn precise(&self) -> bool {
        // A combination of two paraboloid fields, with no encoder of its own to search.
        false
    }
    fn emitted(&self, _spec: &Spec, _: Tracing) -> Emitted {
        // A primary paraboloid point and a detail's slopes as snorm8 fetches return them.
        let inputs = Inputs::FloatCodes(vec![Quant::Snorm(8); 4]);
        let (module, functions) = trace_declared(vec![declared!(
            NAME,
            Role::Combine,
            inputs,
            ["pn", "pd"],
            <F> [] |pd: (V2<F>, V2<F>)| combine(pd.0, pd.1)
        )]);
        Emitted {
            module,
            functions,
            namespace: String::new(),
            portable_encoder: false,
            cpu: Vec::new(),
        }
    }
    fn helper_doc(&self, name: &str) -> Option<String> {
        (name == NAME).then(|| {
            "The second seed's CombineParaboloidNormalWithPD: `pn` a paraboloid point (the float \
             form of paraboloid's parameters), `pd` a detail normal's partial derivatives; \
             returns normalize(pn - pd·nz, nz) with nz = saturate(1 - pn.x² - pn.y²), a unit \
             vector for any finite input. Other implementations: within the rounding that \
             division, square root and contraction allow (measured by unitpack verify \
             --portable, not proven)."
                .into()
        })
    }
}

/// `normalize(pd·(-nz) + pn, nz)`, `nz = saturate(1 - pn.x·pn.x - pn.y·pn.y)`: outside
/// the disk `nz = 0` and `pn` itself (at least 1 long) is the direction, so the length
/// is never zero.
#[inline(always)]
pub fn combine<F: Float>(pn: V2<F>, pd: V2<F>) -> V3<F> {
    let h = F::c(1.0) - pn.x * pn.x - pn.y * pn.y;
    let nz = h.clamped(F::c(0.0), F::c(1.0)).named("nz");
    let n = V3::from_xy(pd * (-nz) + pn, nz).named("combined");
    n / n.length_squared().sqrt()
}

/// [`combine`] on the CPU: the same bits as the emitted `combine_paraboloid_pd`.
pub fn combine_paraboloid_pd(pn: [f32; 2], pd: [f32; 2]) -> [f32; 3] {
    combine(V2::new(pn[0], pn[1]), V2::new(pd[0], pd[1])).to_array()
}
