//! The equi-angular cube map (EAC), beyond the survey: the direction's cube face and its
//! two equi-angular coordinates, numbered together as one index, so that no code is
//! spent on a face number's unused values or on a face's uneven split of bits.
//!
//! A `B`-bit code is the index `i = face·N² + t·N + s` of one of `6·N²` points, with
//! `N = ⌊√(2^B/6)⌋` points along each face edge: 104 at 16 bits (64,896 points; 640
//! codes unused), 1672 at 24 (16,773,504; 3,712 unused) and 26,754 at 32 (4,294,659,096;
//! 308,200 unused). Codes from `6·N²` up decode as code `6·N² - 1`. Faces are
//! [`faces`](crate::codecs::cube_maps::faces)' (+X, -X, +Y, -Y, +Z, -Z = 0–5). On a face, a
//! minor component over the major one's magnitude, `a`, is stored as the angle
//! `u = atan(a)/(π/4)` in `[-1, 1]` on `N` levels: `s = round((u + 1)/2·(N - 1))`. Equal
//! code steps are equal angles, which evens the point density between a face's centre and
//! its corners ([`warpedcube`](crate::codecs::cube_maps::warpedcube) takes the same warp
//! with the face in 3 bits of its own and the rest split between `s` and `t`: at 16 bits
//! 128 × 64 levels a face instead of 104 × 104).
//!
//! Layout: like [`sfib`](crate::codecs::angular::sfib)'s index, the low `B/2` bits in the
//! first field and the high `B/2` in the second (both unorm), so the packed word is `i`
//! ([`Halves`]).
//!
//! The encoder's angles come from the model's fixed-point arctangent
//! ([`fixed_trig::atan2_pi`]) and the index is formed in 32-bit integers, so every
//! implementation computes the same code. The decoder splits the index by integer
//! operations alone (comparisons with the faces' and the rows' first indices), so it too
//! is exact for every code whatever an implementation's rounding; only the direction's
//! trigonometry and normalization carry float error.

use crate::codecs::core::codec::Codec;
use crate::codecs::core::codec_family::CodecFamily;
use crate::codecs::core::info::{Domain, FloatForm, Info, Sizes};
use crate::codecs::core::pipeline::codec_functions;
use crate::codecs::core::spec::SpecError;
use crate::codecs::cube_maps::faces::{Face, placed};
use crate::codecs::toolkit::exact::canonical_or_z;
use crate::codecs::toolkit::fixed_trig;
use crate::codecs::toolkit::index::Halves;
use crate::codecs::toolkit::quant::Quants;
use crate::codecs::toolkit::trig::sincos_pi;
use crate::model::enclosure::Encl;
use crate::model::num::helper;
use crate::model::{Float, Lane, Uint, V2, V3};

pub static FAMILY: CodecFamily<Eac> = CodecFamily::new(
    Info {
        name: "eac",
        title: "equi-angular cube map: face and both coordinates in one index, face·N² + t·N + s",
        sizes: Sizes::Total(&[16, 24, 32]),
        domain: Some(Domain::Sphere),
        source: "the equi-angular cube map (a face's coordinates warped by atan(a)/(π/4)), beyond the survey",
        edge_policy: "input is normalized first; zero, NaN and infinite input encode as +Z; ties between components go to z, then y",
        decode_note: "every code decodes to a unit vector to within the trig approximations' error (about 2.5e-7); codes from 6·N² up (N = ⌊√(2^B/6)⌋) decode as code 6·N² - 1",
        float_form: FloatForm::Unfilterable {
            why: FloatForm::INDEX_SPLIT,
            seam: "at every face row: neighbouring rows' indices differ by N",
        },
        options: &[],
    },
    |bits| Eac { bits },
    codec_functions,
);

/// An equi-angular cube-map codec of `bits` bits.
#[derive(Clone, Copy, Debug)]
pub struct Eac {
    pub bits: u32,
}

impl Eac {
    /// The codec of the given total bit budget; an invalid size is an error listing the
    /// allowed ones.
    pub fn new(bits: u32) -> Result<Eac, SpecError> {
        FAMILY.codec(bits)
    }

    /// `N`, the points along each face edge: the largest with `6·N² ≤ 2^B`.
    pub fn side(&self) -> u32 {
        let codes = 1u64 << self.bits;
        let mut n = ((codes / 6) as f64).sqrt() as u64;
        while 6 * (n + 1) * (n + 1) <= codes {
            n += 1;
        }
        while 6 * n * n > codes {
            n -= 1;
        }
        n as u32
    }

    /// How many codes are points: `6·N²`.
    pub fn points(&self) -> u64 {
        6 * u64::from(self.side()).pow(2)
    }

    fn halves(&self) -> Halves {
        Halves { bits: self.bits }
    }

    /// Face, row and column of index `i`, as exact integers in floats. Only integer
    /// operations decide them (comparisons with the faces' first indices, the row bit by
    /// bit from the top, each bit kept where `i` reaches that row's first index), so they
    /// are the same on every implementation by construction, which the decoders' bound,
    /// proven over face, row and column ([`Codec::proof_parts`]), takes as given. A
    /// quotient estimated in floats and corrected by comparisons would be as exact and
    /// cheaper, but exact by an argument about the estimate's error, not by construction.
    #[inline(always)]
    fn split<F: Float>(&self, i: F::U) -> (F, F, F) {
        let n = self.side();
        let per_face = n * n;
        let last = F::U::c(6 * per_face - 1);
        let i = F::U::sel(i.lt(last), i, last).named("i");
        // The face: how many of faces 1–5's first indices `i` reaches.
        let mut face = F::c(0.0);
        for k in 1..6 {
            face = face + F::sel(i.lt(F::U::c(k * per_face)), F::c(0.0), F::c(1.0));
        }
        let face = face.named("face");
        let r = i.wrapping_sub(face.to_u().wrapping_mul(F::U::c(per_face))).named("r");
        let mut row = F::U::c(0);
        for bit in (0..u32::BITS - (n - 1).leading_zeros()).rev() {
            let next = row + F::U::c(1 << bit);
            row = F::U::sel(r.lt(next.wrapping_mul(F::U::c(n))), row, next);
        }
        let row = row.named("row");
        let column = r.wrapping_sub(row.wrapping_mul(F::U::c(n))).named("column");
        // Both below N, so below 2^24: converted exactly.
        (face, row.to_f(), column.to_f())
    }

    /// The direction of index `i`: [`Eac::on_face`] of its face, row and column.
    #[inline(always)]
    fn index_direction<F: Float>(&self, i: F::U) -> V3<F> {
        let (face, t, s) = self.split(i);
        self.on_face(face, t, s)
    }

    /// The point of row `t` and column `s` on face `face`: the face point
    /// `(tan α, tan β, 1)` scaled by `cos α·cos β` (so no quotient is needed), normalized
    /// and placed on its face.
    #[inline(always)]
    fn on_face<F: Float>(&self, face: F, t: F, s: F) -> V3<F> {
        // A level `c` of `0..=N-1` is the angle `(2c/(N-1) - 1)·π/4`, in half turns.
        let k = 0.5 / f64::from(self.side() - 1);
        let quarter = |c: F| c * F::c(k as f32) - F::c(0.25);
        let cs = helper!(sincos_pi(quarter(s))).named("cs");
        let ct = helper!(sincos_pi(quarter(t))).named("ct");
        let d = V3::new(cs.x * ct.y, ct.x * cs.y, cs.y * ct.y).named("d");
        let u = (d / d.length_squared().sqrt()).named("u");
        placed(face, 1.0, u.z, u.x, u.y)
    }
}

impl Codec for Eac {
    type P<F: Float> = V2<F>;
    type C<F: Float> = F::U;
    #[inline]
    fn quants(&self) -> Quants {
        self.halves().quants()
    }
    fn domain(&self) -> Domain {
        Domain::Sphere
    }
    /// The index's two fields as a texture fetch returns them (`c/M`).
    #[inline(always)]
    fn params<F: Float>(&self, v: V3<F>) -> V2<F> {
        self.halves().fetched(self.round_codes(v))
    }
    /// The fields re-quantized (`round(p·M)`, exact for a fetched `c/M`), then the point
    /// of their index.
    #[inline(always)]
    fn direction<F: Float>(&self, p: V2<F>) -> V3<F> {
        self.decode_codes(self.halves().codes(p))
    }
    /// Face, row and column, which [`Eac::split`] computes by integer operations alone.
    fn proof_parts(&self) -> Option<Vec<(i64, i64)>> {
        let last = i64::from(self.side() - 1);
        Some(vec![(0, 5), (0, last), (0, last)])
    }
    fn parts_direction(&self, parts: &[Encl]) -> V3<Encl> {
        self.on_face(parts[0], parts[1], parts[2])
    }
    #[inline(always)]
    fn decode_codes<F: Float>(&self, codes: V2<F>) -> V3<F> {
        self.index_direction(self.halves().index(codes).named("i"))
    }
    /// The face of the canonical input, each coordinate's angle `atan2(n, major)/π` in
    /// units of `2^-23` ([`fixed_trig::atan2_pi`]) times 4 put on the `N` levels
    /// ([`fixed_trig::angle_level`]), and the index formed in 32-bit integers.
    const EXACT_ROUNDING: bool = true;
    #[inline(always)]
    fn round_codes<F: Float>(&self, v: V3<F>) -> V2<F> {
        let f = Face::of(canonical_or_z(v).0);
        let n = self.side();
        let level = |x: F| {
            let a = fixed_trig::atan2_pi(x, f.major);
            fixed_trig::angle_level((n - 1) as f32, a * F::c(4.0), 0.5).to_u()
        };
        let (s, t) = (level(f.s), level(f.t));
        let n = F::U::c(n);
        let i = (f.number.to_u().wrapping_mul(n) + t).wrapping_mul(n) + s;
        self.halves().fields(i.named("i"))
    }
}
