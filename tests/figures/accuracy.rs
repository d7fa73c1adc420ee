//! Survey Table 1 (Cigolle et al. 2014) reproduced with 2^20 seeded vectors (the survey's method, `src/measure/quality.rs`):
//! mean error within 2 %, max error within 5 % of the published figures. The rows we do
//! not match that way are asserted by what docs/design/survey.md's "Table 1 rows we do not
//! reproduce" says of them.

use unitpack::codecs::Spec;
use unitpack::measure::figures::{ErrorStats, VECTOR_SEED};
use unitpack::measure::quality::{angle_deg, component_mse};
use unitpack::support::sampling::random_unit_vectors;

const SAMPLES: usize = 1 << 20;

fn measured(spec: &str) -> ErrorStats {
    let s: Spec = spec.parse().unwrap();
    let st = crate::stats(&[s], SAMPLES)[0].expect("a codec spec");
    println!("{spec}: mean {:.5}°, max {:.5}°", st.mean, st.max);
    st
}

fn mean_matches(spec: &str, st: &ErrorStats, mean: f64) {
    assert!(
        (st.mean - mean).abs() <= 0.02 * mean,
        "{spec}: mean {:.5}° vs table {mean}°",
        st.mean
    );
}

fn max_matches(spec: &str, st: &ErrorStats, max: f64) {
    assert!(
        (st.max - max).abs() <= 0.05 * max,
        "{spec}: max {:.5}° vs table {max}°",
        st.max
    );
}

fn check(spec: &str, mean: f64, max: f64) {
    let st = measured(spec);
    mean_matches(spec, &st, mean);
    max_matches(spec, &st, max);
}

#[test]
fn oct16_matches_table_1() {
    check("oct16", 0.33709, 0.94424);
}
#[test]
fn oct16p_matches_table_1() {
    check("oct16p", 0.31485, 0.63575);
}
#[test]
fn oct24_matches_table_1() {
    check("oct24", 0.02091, 0.05874);
}
#[test]
fn oct24p_matches_table_1() {
    check("oct24p", 0.01953, 0.03928);
}
#[test]
fn oct32_matches_table_1() {
    check("oct32", 0.00131, 0.00370);
}
#[test]
fn oct32p_matches_table_1() {
    check("oct32p", 0.00122, 0.00246);
}

/// The rgb8 layout stores the same oct24 codes, so its error is oct24's.
#[test]
fn oct24_rgb8_layout_matches_oct24() {
    check("oct24p:layout=rgb8", 0.01953, 0.03928);
    check("oct24:layout=rgb8", 0.02091, 0.05874);
}

/// Table 3 (hemisphere codecs over the +Z hemisphere).
#[test]
fn hemioct_matches_table_3() {
    check("hemioct24", 0.01489, 0.03406);
    check("hemioct32", 0.00093, 0.00213);
}

/// Table 1 rows for the other surveyed codecs implemented here.
#[test]
fn spherical_and_snorm_match_table_1() {
    check("spherical16", 0.35527, 0.78685);
    check("spherical24", 0.02209, 0.04906);
    check("snorm8x3", 0.17015, 0.38588);
}
/// The fast latlong is a lat-long grid of `2^h` rings by `2^h - 1` azimuths (the reading
/// of the survey's rows that `src/codecs/latlong.rs` explains). At 32 bits the table's
/// max is marked ± (lower with float64 intermediates); ours is the quantization's own.
#[test]
fn latlong_matches_table_1() {
    check("latlong16", 0.35560, 0.78846);
    check("latlong24", 0.02211, 0.04907);
    let st = measured("latlong32");
    mean_matches("latlong32", &st, 0.00138);
    assert!(st.max < 0.00324, "latlong32: {st:?}");
}
/// Table 1's CrytekBFN24 row (0.04027° / 4.78260°) is not reproduced by any reading of
/// Crytek's table we tried (docs/design/survey.md, "Table 1 rows we do not reproduce"). Ours follows the
/// generator of Crytek's shipped 512×512 table, read at the nearest texel: the fitted
/// lengths cut plain RGB8's mean error to a third (`unorm3`, the same bytes without
/// them) and keep its max, but stay above the precise search's (`snorm8x3p`), which
/// searches every length instead of reading one.
#[test]
fn crytek_bfn_cuts_plain_rgb8s_error_but_is_not_table_1() {
    let st = measured("crytek_bfn24");
    let plain = measured("unorm3");
    let search = measured("snorm8x3p");
    assert!(st.mean < 0.35 * plain.mean, "{st:?} vs unorm3 {plain:?}");
    assert!(st.mean > search.mean, "{st:?} vs snorm8x3p {search:?}");
    assert!(st.max < plain.max, "{st:?} vs unorm3 {plain:?}");
}
/// latlongD: Smith et al.'s rings with the table decoder. At 32 bits the table's max is
/// marked ± (float32 intermediates); our sample max is the rings' `ε` (0.00219148°, every
/// patch point's distance to its centre) plus the encoder's angle grid and the decoder's
/// float error (about 2·10^-5°).
#[test]
fn latlongd_matches_table_1() {
    check("latlongd16", 0.30351, 0.56178);
    check("latlongd24", 0.01895, 0.03504);
    let st = measured("latlongd32");
    mean_matches("latlongd32", &st, 0.00119);
    assert!(st.max < 0.00222, "latlongd32: {st:?}");
}
#[test]
fn more_spherical_sizes_match_table_1() {
    check("spherical20", 0.08847, 0.19632);
    check("spherical22", 0.04423, 0.09809);
}
/// The table's 0.00957° max is float32 error in its atan2/acos; ours (about 0.00307°) is
/// the quantization's own.
#[test]
fn spherical32_matches_table_1_with_a_lower_max() {
    let st = measured("spherical32");
    mean_matches("spherical32", &st, 0.00138);
    assert!(st.max < 0.0031, "spherical32: max {:.5}°", st.max);
}

/// The portable encoders decide spherical's angles in fixed point; on the same sample,
/// codes rounded exactly from f64 angles (decoded by the same decoder) reach the same
/// max to within 0.05 % (0.00306500° against our 0.00306636°), and the same mean.
#[test]
fn spherical32_is_as_good_as_exact_rounding() {
    use std::f64::consts::PI;
    use unitpack::api::{CpuCodec, Spherical};
    let c = Spherical::new(32).unwrap().fast();
    let m = 32767.0;
    let field = |x: f64| (x.round() as i32 as u32) & 0xffff;
    let (mut sum, mut max) = (0.0, 0f64);
    for v in random_unit_vectors(VECTOR_SEED, SAMPLES, false) {
        let n = v.map(f64::from);
        let theta = n[0].hypot(n[1]).atan2(n[2]) / PI * 2.0 - 1.0;
        let phi = n[1].atan2(n[0]) / PI;
        let a = angle_deg(v, c.decode(field(theta * m) | field(phi * m) << 16));
        sum += a;
        max = max.max(a);
    }
    let ours = measured("spherical32");
    let mean = sum / SAMPLES as f64;
    println!("exact rounding: mean {mean:.5}°, max {max:.8}°");
    assert!(ours.max < max * 1.0005, "{ours:?} vs exact {max}");
    assert!(
        (ours.mean / mean - 1.0).abs() < 1e-4,
        "{ours:?} vs exact {mean}"
    );
}
#[test]
fn more_snorm_layouts_match_table_1() {
    check("snorm5x3", 1.45262, 3.26743);
    check("snorm11_11_10", 0.02937, 0.06776);
    check("snorm16x3", 0.00066, 0.00149);
}
/// Table 1's snorm×3P rows are Crytek's table of best lengths, read at its four nearest
/// texels; ours searches the scales themselves (every one above M/2 at snorm8, the top
/// 64 at snorm16), and so lands below both rows.
/// At snorm8 the mean is 3.7 % and the max 10 % below the table; at snorm16, where the
/// table barely improves on plain rounding (0.00060° against 0.00066°), the mean is a
/// sixth of it.
#[test]
fn snorm_best_fit_is_below_table_1() {
    let st = measured("snorm8x3p");
    assert!(
        st.mean < 0.03164 && st.mean > 0.9 * 0.03164,
        "snorm8x3p: {st:?}"
    );
    assert!(
        st.max < 0.33443 && st.max > 0.85 * 0.33443,
        "snorm8x3p: {st:?}"
    );
    let st = measured("snorm16x3p");
    assert!(st.mean < 0.00060 / 5.0, "snorm16x3p: {st:?}");
    assert!(st.max < 0.00149, "snorm16x3p: {st:?}");
}
/// The table's mean (0.04708°) does not fit its own neighbours: snorm×3's mean scales
/// with the step `1/M`, and snorm5x3, snorm8x3 and snorm11_11_10 match the table, which
/// puts snorm10x3 at 0.170° · 127/511 = 0.0423°, what we measure. The max matches.
#[test]
fn snorm10x3_matches_table_1_max_and_the_step_scaling_of_its_mean() {
    let st = measured("snorm10x3");
    max_matches("snorm10x3", &st, 0.09598);
    let scaled = 0.17015 * 127.0 / 511.0;
    mean_matches("snorm10x3 (scaled from snorm8x3)", &st, scaled);
}
#[test]
fn oct20_and_oct22_match_table_1() {
    check("oct20", 0.08380, 0.23467);
    check("oct20p", 0.07829, 0.15722);
    check("oct22", 0.04180, 0.11734);
}
/// The extracted row reads `oct22P 24 0.02372 0.08093±`: a 22-bit codec listed at 24
/// bits with a mean below oct24's own neighbours', so its mean is not usable. Its max is
/// marked ±: ours may be lower. The mean must lie below oct22's (the precise search never
/// picks a worse code than rounding).
#[test]
fn oct22p_matches_table_1_max() {
    let st = measured("oct22p");
    assert!(st.max <= 1.05 * 0.08093, "oct22p: max {:.5}°", st.max);
    assert!(st.mean < 0.04180, "oct22p: mean {:.5}°", st.mean);
}

/// float32x3 has no Table 1 row (the survey measures against float32×3 itself). Its
/// error is bounded by construction: the input on a grid of 2^-21 of its largest
/// component's binade (at most √3·2^-22 rad), then each component rounded to the 2^-24
/// grid (at most √3·2^-25 rad): 2.7·10⁻⁵° in all.
#[test]
fn float32x3_is_within_its_grids() {
    let st = measured("float32x3");
    let bound = 3f64.sqrt() * (2f64.powi(-22) + 2f64.powi(-25));
    assert!(
        st.max <= bound.to_degrees(),
        "float32x3: max {:.7}°",
        st.max
    );
    assert!(
        st.mean > 0.0 && st.mean < st.max,
        "float32x3: mean {:.7}°",
        st.mean
    );
}

/// The table's float16×3 row (0.00635° / 0.02635°) is a conversion that truncates:
/// rounding each component of the same vectors toward zero on the f16 grid (computed
/// here from the format's definition) reproduces its mean. float16x3 rounds to nearest,
/// ties to even, as IEEE 754 and every RGBA16_FLOAT render target do, and is better on
/// both counts.
#[test]
fn float16x3_rounds_to_nearest_where_the_table_truncated() {
    let st = measured("float16x3");
    assert!(st.mean < 0.97 * 0.00635, "float16x3: mean {:.5}°", st.mean);
    assert!(st.max < 0.95 * 0.02635, "float16x3: max {:.5}°", st.max);
    let toward_zero = |x: f32| {
        let a = f64::from(x).abs();
        let spacing = 2f64.powf(a.log2().floor().max(-14.0) - 10.0);
        ((a / spacing).floor() * spacing).copysign(f64::from(x)) as f32
    };
    let vs = random_unit_vectors(VECTOR_SEED, SAMPLES, false);
    let (mut sum, mut max, mut squares) = (0.0, 0f64, 0.0);
    for v in &vs {
        let t = v.map(toward_zero);
        let a = angle_deg(*v, t);
        sum += a;
        max = max.max(a);
        squares += component_mse(*v, t);
    }
    let truncated = ErrorStats {
        mean: sum / SAMPLES as f64,
        max,
        mse: squares / SAMPLES as f64,
        samples: SAMPLES,
    };
    println!(
        "truncating: mean {:.5}°, max {:.5}°",
        truncated.mean, truncated.max
    );
    mean_matches("float16x3 truncating", &truncated, 0.00635);
    assert!(
        truncated.max <= 0.02635,
        "truncating: max {:.5}°",
        truncated.max
    );
}

/// The stereographic hemisphere codec (1 + ⌈(B-1)/2⌉ + ⌊(B-1)/2⌋ bits, unorm).
#[test]
fn stereo_matches_table_1() {
    check("stereo16", 0.40140, 1.00318);
    check("stereo20", 0.09980, 0.24779);
    check("stereo22", 0.04979, 0.12437);
    check("stereo24", 0.02490, 0.06230);
}
/// The table marks stereo32's max (0.00547°) ±, lower with float64 intermediates: ours is
/// the quantization's own (about 0.0039°).
#[test]
fn stereo32_matches_table_1_with_a_lower_max() {
    let st = measured("stereo32");
    mean_matches("stereo32", &st, 0.00155);
    assert!(st.max < 0.0040, "stereo32: max {:.5}°", st.max);
}

/// The Lambert equal-area hemisphere codec (the same layout as stereo).
#[test]
fn eqarea_matches_table_1() {
    check("eqarea16", 0.38716, 0.96092);
    check("eqarea20", 0.09627, 0.24355);
    check("eqarea22", 0.04806, 0.11915);
    check("eqarea24", 0.02402, 0.06067);
    check("eqarea32", 0.00150, 0.00383);
}

/// The azimuthal equidistant hemisphere codec (the same layout as stereo).
#[test]
fn eqdist_matches_table_1() {
    check("eqdist16", 0.38452, 0.78944);
    check("eqdist20", 0.09541, 0.19667);
    check("eqdist22", 0.04768, 0.09809);
    check("eqdist24", 0.02387, 0.04899);
    check("eqdist32", 0.00149, 0.00307);
}

/// The stereographic disk mapped onto the square by the concentric map (the disk
/// codecs' layout).
#[test]
fn stereo_concentric_matches_table_1() {
    check("stereo_concentric16", 0.37364, 1.29985);
    check("stereo_concentric20", 0.09290, 0.32722);
    check("stereo_concentric22", 0.04642, 0.16228);
    check("stereo_concentric32", 0.00146, 0.00522);
}
/// stereo+concentric24's max (0.09398°) is out of line with every neighbour: from 22 to 24
/// bits the table's other disk rows halve their max (0.51×, 0.50×, 0.49×, 0.51× for
/// eqarea+concentric, eqdist+concentric, eqarea, eqdist), this row falls only to 0.58×.
/// Ours halves like the others (0.0842°); the mean matches.
#[test]
fn stereo_concentric24_matches_table_1_with_a_lower_max() {
    let st = measured("stereo_concentric24");
    mean_matches("stereo_concentric24", &st, 0.02319);
    assert!(st.max < 0.0860, "stereo_concentric24: max {:.5}°", st.max);
}

/// The equal-area disk mapped onto the square by the concentric map.
#[test]
fn eqarea_concentric_matches_table_1() {
    check("eqarea_concentric16", 0.36584, 1.00697);
    check("eqarea_concentric20", 0.09096, 0.24671);
    check("eqarea_concentric22", 0.04545, 0.12304);
    check("eqarea_concentric24", 0.02273, 0.06265);
    check("eqarea_concentric32", 0.00142, 0.00391);
}

/// The equidistant disk mapped onto the square by the concentric map.
#[test]
fn eqdist_concentric_matches_table_1() {
    check("eqdist_concentric16", 0.36114, 1.05603);
    check("eqdist_concentric20", 0.08975, 0.25856);
    check("eqdist_concentric22", 0.04484, 0.12983);
    check("eqdist_concentric24", 0.02241, 0.06548);
    check("eqdist_concentric32", 0.00141, 0.00409);
}

/// The equal-area disk mapped onto the square by the elliptical grid map (the disk
/// codecs' layout). The 32-bit max is marked ± (float32 intermediates: the survey's
/// inverse map cancels near `x = 0`); ours, decided exactly, is the quantization's own,
/// below the plain disk codec's.
#[test]
fn eqarea_ellipse_matches_table_1() {
    check("eqarea_ellipse16", 0.35217, 0.90617);
    check("eqarea_ellipse20", 0.08758, 0.22567);
    check("eqarea_ellipse22", 0.04374, 0.11238);
    check("eqarea_ellipse24", 0.02185, 0.05615);
    let st = measured("eqarea_ellipse32");
    mean_matches("eqarea_ellipse32", &st, 0.00137);
    assert!(st.max < 0.0038, "eqarea_ellipse32: max {:.5}°", st.max);
}

/// The equidistant disk mapped onto the square by the elliptical grid map; the 24- and
/// 32-bit maxes are marked ±, and ours are the plain eqdist codec's (0.0490°, 0.0031°).
#[test]
fn eqdist_ellipse_matches_table_1() {
    check("eqdist_ellipse16", 0.35663, 0.79669);
    check("eqdist_ellipse20", 0.08851, 0.19633);
    check("eqdist_ellipse22", 0.04418, 0.10132);
    let st = measured("eqdist_ellipse24");
    mean_matches("eqdist_ellipse24", &st, 0.02208);
    assert!(st.max < 0.0500, "eqdist_ellipse24: max {:.5}°", st.max);
    let st = measured("eqdist_ellipse32");
    mean_matches("eqdist_ellipse32", &st, 0.00138);
    assert!(st.max < 0.0032, "eqdist_ellipse32: max {:.5}°", st.max);
}

/// The stereographic disk mapped onto the square by the elliptical grid map. The table's
/// maxes from 20 bits up exceed its own plain stereo rows' (the survey: the elliptical
/// compositions "exhibit significantly greater worst-case error at float32 intermediate
/// precision"); at 16 bits, where quantization dominates, its stereo+ellipse max equals
/// its stereo max (1.00318°). The map is the identity on the axes, where stereo's worst
/// cells lie, and ours, decided exactly, keep stereo's max at every size: asserted
/// against the table's stereo rows. The 24-bit row is garbled in the extraction
/// (`stereo+ellipse24 24 24 0.02319 0.08303 0.08093±` beside `oct22P 24 0.02372
/// 0.08093±`); its mean is the 0.02372 extracted into oct22P's row (oct22P's own mean
/// lies between oct22's and oct24's, see `oct22p_matches_table_1_max`).
#[test]
fn stereo_ellipse_matches_table_1_with_stereo_maxes() {
    check("stereo_ellipse16", 0.38233, 1.00318);
    for (spec, mean, stereo_max) in [
        ("stereo_ellipse20", 0.09494, 0.24779),
        ("stereo_ellipse22", 0.04746, 0.12437),
        ("stereo_ellipse24", 0.02372, 0.06230),
    ] {
        let st = measured(spec);
        mean_matches(spec, &st, mean);
        max_matches(spec, &st, stereo_max);
    }
    let st = measured("stereo_ellipse32");
    mean_matches("stereo_ellipse32", &st, 0.00149);
    assert!(st.max < 0.0040, "stereo_ellipse32: max {:.5}°", st.max);
}

/// cube and warpedcube have no Table 1 rows (docs/codecs.md publishes ours). The warp
/// exists to even the point density, so it must lower both the mean and the max at every
/// size. cube spends 3 bits on six faces (log2 6 ≈ 2.6 needed) and oversamples the
/// corners, so it trails oct of the same size, but by less than 1.5× in the mean.
#[test]
fn warpedcube_beats_cube_at_every_size() {
    for bits in [16, 24, 32] {
        let plain = measured(&format!("cube{bits}"));
        let warped = measured(&format!("warpedcube{bits}"));
        assert!(
            warped.mean < plain.mean,
            "{bits}: mean {warped:?} vs {plain:?}"
        );
        assert!(
            warped.max < plain.max,
            "{bits}: max {warped:?} vs {plain:?}"
        );
        let oct = measured(&format!("oct{bits}"));
        assert!(
            plain.mean < 1.5 * oct.mean,
            "{bits}: cube mean {plain:?} vs oct {oct:?}"
        );
    }
}

/// The fourth seed offers the stereographic projection as the alternative to storing x
/// and y: it keeps the points dense at the horizon, so at every size its max error is
/// a small fraction of xy's and its mean lower.
#[test]
fn xy_stereo_beats_xy_at_every_size() {
    for bits in [16, 24, 32] {
        let xy = measured(&format!("xy{bits}"));
        let stereo = measured(&format!("xy_stereo{bits}"));
        assert!(stereo.mean < xy.mean, "{bits}: {stereo:?} vs {xy:?}");
        assert!(stereo.max < 0.2 * xy.max, "{bits}: {stereo:?} vs {xy:?}");
    }
}

/// The first seed's baseline unorm3 stores 255 steps per component where snorm8x3 stores
/// 254: the same method on a grid finer by 1/254, so its mean error is lower by about
/// that much, not more.
#[test]
fn unorm3_is_snorm8x3_on_a_finer_grid() {
    let unorm = measured("unorm3");
    let snorm = measured("snorm8x3");
    assert!(unorm.mean < snorm.mean, "{unorm:?} vs {snorm:?}");
    assert!(unorm.mean > 0.99 * snorm.mean, "{unorm:?} vs {snorm:?}");
}

/// The second seed's point: the inverted paraboloid spends the texels xy wastes on the
/// centre near the horizon instead, so at every size its mean is lower than xy's and
/// its max a small fraction of it, fast and precise.
#[test]
fn paraboloid_beats_xy_at_every_size() {
    for bits in [16, 24, 32] {
        for p in ["", "p"] {
            let xy = measured(&format!("xy{bits}{p}"));
            let par = measured(&format!("paraboloid{bits}{p}"));
            assert!(par.mean < 0.7 * xy.mean, "{bits}{p}: {par:?} vs {xy:?}");
            assert!(par.max < 0.2 * xy.max, "{bits}{p}: {par:?} vs {xy:?}");
        }
    }
}

/// The seed's extension: the dual paraboloid spends the corners of the square that the
/// paraboloid leaves outside its disk, so at every size its mean is lower by more than
/// 5 %, fast and precise. The fast sample max is lower too; the precise one stays within
/// 2 % of the paraboloid's (measured: 0.4 % above at 16 and 0.1 % at 24 bits).
#[test]
fn paraboloid_square_beats_paraboloid_at_every_size() {
    for bits in [16, 24, 32] {
        for p in ["", "p"] {
            let par = measured(&format!("paraboloid{bits}{p}"));
            let sq = measured(&format!("paraboloid_square{bits}{p}"));
            assert!(sq.mean < 0.95 * par.mean, "{bits}{p}: {sq:?} vs {par:?}");
            let max_ratio = if p.is_empty() { 1.0 } else { 1.02 };
            assert!(sq.max < max_ratio * par.max, "{bits}{p}: {sq:?} vs {par:?}");
        }
    }
}

/// The first seed's metric on its own baseline: storing each component of `n` as unorm8
/// leaves an error uniform over one step of `2/255`, whose mean square is
/// `(2/255)²/12` = 5.13e-6 per component (the seed, which did not renormalize, measured
/// 0.0000054 on its scene). unorm3's decoder renormalizes, which removes the error along
/// `n`, a third of it on average over directions: `(2/3)·(2/255)²/12` = 3.42e-6, a PSNR of
/// 54.66 dB.
#[test]
fn unorm3_mse_is_the_uniform_quantization_error_off_the_normal() {
    let st = measured("unorm3");
    let expected = 2.0 / 3.0 * (2.0f64 / 255.0).powi(2) / 12.0;
    assert!(
        (st.mse / expected - 1.0).abs() < 0.02,
        "unorm3: MSE {:e} vs {expected:e}",
        st.mse
    );
    assert!(
        (st.psnr() - 54.66).abs() < 0.1,
        "unorm3: PSNR {}",
        st.psnr()
    );
}

/// The spherical Fibonacci sets (beyond the survey's table) against the physical limit for
/// `N = 2^b` codes (DESIGN §5, the hexagonal estimate of the covering radius,
/// `acos(1 - 2/N)·1.0996` for the max and 0.61 of that for the mean): the mean within 2 %
/// of it at every size, the sample max within 20 % (the spiral's largest holes are in the
/// polar caps, docs/design/families.md "Spherical Fibonacci").
#[test]
fn sfib_is_near_the_covering_limit() {
    for bits in [16, 24, 32] {
        let st = measured(&format!("sfib{bits}"));
        let max = (1.0 - 2.0 / 2f64.powi(bits)).acos().to_degrees() * 1.0996;
        let mean = 0.61 * max;
        assert!(
            st.mean <= 1.02 * mean,
            "sfib{bits}: mean {:.5}° vs limit {mean:.5}°",
            st.mean
        );
        assert!(
            st.max <= 1.2 * max,
            "sfib{bits}: max {:.5}° vs limit {max:.5}°",
            st.max
        );
    }
}
