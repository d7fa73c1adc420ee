//! What every cube-map codec shares: the face a direction lies on, with its coordinates'
//! numerators and divisor ([`Face`]), and the direction placed back on a face
//! ([`placed`]). Faces are numbered like a cube map's layers, `2·axis + (major < 0)`:
//! +X, -X, +Y, -Y, +Z, -Z = 0–5; on the face of axis `a` the coordinates are the next two
//! components in cyclic order (+X: `(y, z)`, +Y: `(z, x)`, +Z: `(x, y)`). Ties between
//! components go to z, then y.

use crate::model::{Bool, Float, V3};

/// Which face a canonical vector lies on, and its coordinates' numerators and divisor.
pub(crate) struct Face<F: Float> {
    /// `2·axis + (major < 0)`.
    pub number: F,
    /// The next two components in cyclic order, and the major one's magnitude.
    pub s: F,
    pub t: F,
    pub major: F,
}

impl<F: Float> Face<F> {
    /// From a canonical vector (whose largest component is at least 2, so never 0).
    #[inline(always)]
    pub(crate) fn of(w: V3<F>) -> Self {
        let a = w.abs();
        let z = a.z.ge(a.x).and(a.z.ge(a.y));
        let y = a.y.ge(a.x);
        let pick = { #[inline(always)] |zv: F, yv: F, xv: F| F::sel(z, zv, F::sel(y, yv, xv)) };
        let major = pick(w.z, w.y, w.x).named("major");
        let axis2 = pick(F::c(4.0), F::c(2.0), F::c(0.0));
        let number = (axis2 + F::sel(major.lt(F::c(0.0)), F::c(1.0), F::c(0.0))).named("face");
        Face {
            number,
            s: pick(w.x, w.z, w.y).named("s"),
            t: pick(w.y, w.x, w.z).named("t"),
            major: major.abs(),
        }
    }
}

/// The vector with major component `m` on face `f·unit` (`f` the face number 0–7 times
/// `unit`) and coordinates `(s, t)` on it, placed by the face's axis and sign. The face
/// is read by comparisons with half-way thresholds, so the decoder never scales its
/// dequantized `face/7` back by a literal (which a driver would fold into the
/// dequantization's own product).
#[inline(always)]
pub(crate) fn placed<F: Float>(f: F, unit: f64, m: F, s: F, t: F) -> V3<F> {
    let at = { #[inline(always)] |k: f64| F::c((k * unit) as f32) };
    let on_z = f.ge(at(3.5));
    let on_y = f.ge(at(1.5));
    let within = F::sel(on_z, f - at(4.0), F::sel(on_y, f - at(2.0), f));
    let within = F::sel(within.ge(at(1.5)), within - at(2.0), within);
    let m = F::sel(within.gt(at(0.5)), -m, m);
    let pick = { #[inline(always)] |zv: F, yv: F, xv: F| F::sel(on_z, zv, F::sel(on_y, yv, xv)) };
    V3::new(pick(s, t, m), pick(t, m, s), pick(m, s, t))
}
