//! Survey Listings 4–5: the integer and float-only snorm12×2 ↔ unorm8×3 forms are equal,
//! bit for bit, on all 2^24 inputs each way (CPU model; the GPU run is in `verify`).

use unitpack::codecs::component::snorm12x2::{
    from_unorm8x3, from_unorm8x3_int, to_unorm8x3, to_unorm8x3_int,
};
use unitpack::model::{V2, V3};

#[test]
fn unpack_forms_agree_on_every_rgb8_texel() {
    for t in 0u32..1 << 24 {
        let u = V3::new(t & 255, (t >> 8) & 255, t >> 16)
            .to_array()
            .map(|b| b as f32 / 255.0);
        let u = V3::from_array(u);
        let (a, b) = (from_unorm8x3(u), from_unorm8x3_int(u));
        assert_eq!(
            (a.x.to_bits(), a.y.to_bits()),
            (b.x.to_bits(), b.y.to_bits()),
            "texel 0x{t:06x}: float form {a:?}, integer form {b:?}"
        );
    }
}

#[test]
fn pack_forms_agree_on_every_snorm12_pair() {
    let val = |c: i32| (c as f32 / 2047.0).max(-1.0);
    for x in -2048..2048 {
        for y in -2048..2048 {
            let f = V2::new(val(x), val(y));
            let (a, b) = (to_unorm8x3(f), to_unorm8x3_int(f));
            assert_eq!(
                a.to_array().map(f32::to_bits),
                b.to_array().map(f32::to_bits),
                "codes ({x}, {y})"
            );
        }
    }
}

#[test]
fn pack_then_unpack_is_identity_on_codes() {
    for x in (-2047..=2047).step_by(7) {
        for y in (-2047..=2047).step_by(5) {
            let f = V2::new(x as f32 / 2047.0, y as f32 / 2047.0);
            let u = to_unorm8x3_int(f)
                .to_array()
                .map(|b| (b * 255.0).round() / 255.0);
            let back = from_unorm8x3(V3::from_array(u));
            assert_eq!((back.x * 2047.0).round() as i32, x);
            assert_eq!((back.y * 2047.0).round() as i32, y);
        }
    }
}
