//! The filtering figures (`src/choice/filtering.rs`) on cases whose answer is known
//! without the code under test: a float form that stores the vector itself, a projection
//! that is smooth away from its rim, and the octahedral fold.

use unitpack::Spec;
use unitpack::choice::filtering::{self, Filtering, errors};
use unitpack::codecs::core::storage::{self, Format};
use unitpack::codecs::functions::function::{Emitted, Function, Role};

fn emitted(spec: &str) -> std::sync::Arc<Emitted> {
    spec.parse::<Spec>().unwrap().emitted()
}

/// The format the spec's float form is stored in.
fn stored_in(spec: &str) -> Format {
    let s: Spec = spec.parse().unwrap();
    let formats = storage::formats(&s, &s.emitted());
    storage::float_form_storage(&formats)
        .expect("a float-form format")
        .clone()
}

fn float_form(e: &Emitted) -> (&Function, &Function) {
    (
        e.cpu_function(Role::EncodeFloat).unwrap(),
        e.cpu_function(Role::DecodeFloat).unwrap(),
    )
}

fn unit(v: [f64; 3]) -> [f32; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|x| (x / l) as f32)
}

/// The error of filtering `a` and `b` with weights `1 - w`, `w`.
fn pair(spec: &str, a: [f64; 3], b: [f64; 3], w: f64) -> f64 {
    let e = emitted(spec);
    let (enc, dec) = float_form(&e);
    let decode = |p: &[u32], o: &mut [u32]| dec.eval_many(p, o);
    let format = stored_in(spec);
    errors(enc, &format, &decode, 2, &[unit(a), unit(b)], &[1.0 - w, w])[0]
}

#[test]
fn a_float_form_that_stores_the_vector_filters_as_the_reference_does() {
    // float32x3's float form is the vector: the filter is the reference's lerp, and only
    // f32 rounding separates the two.
    let e = pair("float32x3", [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 0.5);
    assert!(e < 1e-3, "{e}");
}

#[test]
fn xy_filters_with_small_error_away_from_the_rim() {
    // Near +Z, xy's (x, y) are nearly linear in the direction: two neighbours 5° apart
    // filter to within a few thousandths of a degree of the renormalized lerp.
    let e = pair("xy32", [0.05, 0.0, 1.0], [0.05 + 0.0875, 0.0, 1.0], 0.5);
    assert!(e < 0.01, "near the pole: {e}");
    // Near the rim z = sqrt(1 - x² - y²) is steep, and the same separation errs more.
    let rim = pair("xy32", [1.0, 0.0, 0.1], [1.0, 0.0875, 0.1], 0.5);
    assert!(rim > 10.0 * e, "near the rim {rim} vs near the pole {e}");
}

#[test]
fn the_octahedral_fold_makes_pairs_across_it_err_by_tens_of_degrees() {
    // Below the equator, x = 0 is an edge of the unfolded square: its two sides are at
    // opposite edges, and their lerp decodes far from both.
    let across = pair("oct32", [0.02, 0.3, -0.95], [-0.02, 0.3, -0.95], 0.5);
    assert!(across > 10.0, "across the fold: {across}");
    // Inside one face of the octahedron the map is a central projection onto the face's
    // plane, which keeps great circles straight: the filtered texel stays on the arc
    // between the two, near the renormalized lerp.
    let inside = pair("oct32", [0.2, 0.3, 0.93], [0.24, 0.3, 0.92], 0.5);
    assert!(inside < 0.05, "inside a face: {inside}");
}

fn measured(spec: &str) -> Filtering {
    let s: Spec = spec.parse().unwrap();
    filtering::measure(&s.emitted(), &stored_in(spec), s.info().domain.unwrap()).unwrap()
}

#[test]
fn the_sample_figures_are_seeded_and_show_the_seams() {
    let oct = measured("oct16");
    assert_eq!(oct, measured("oct16"), "the same seed, the same figures");
    // Pairs 1° apart that straddle the fold are a few in a thousand.
    let near = &oct.lerp[0];
    assert_eq!(near.separation, 1.0);
    assert!(near.over_1deg > 0.0 && near.over_1deg < 0.05, "{near:?}");
    assert!(near.max > 10.0, "{near:?}");
    // hemioct has no fold inside its domain.
    let hemi = measured("hemioct16");
    assert_eq!(hemi.lerp[0].over_1deg, 0.0, "{:?}", hemi.lerp[0]);
    // Every case has its separation, and its figures are in order. (The mean may exceed
    // the 99th percentile: the few pairs across the fold err by tens of degrees.)
    for (s, sep) in oct.lerp.iter().zip(filtering::SEPARATIONS) {
        assert_eq!(s.separation, sep);
        assert!(s.mean <= s.max && s.p99 <= s.max && s.max <= 180.0, "{s:?}");
    }
}

/// A float form decoded through a lookup table is filtered as a shader reads it: the
/// filtered texel's nearest code, through the table. Its azimuth wraps at ±180°.
#[test]
fn every_codec_with_a_float_form_has_filtering_figures() {
    let lut = measured("spherical_lut16");
    assert!(lut.lerp[0].mean < 1.0, "{:?}", lut.lerp[0]);
    assert!(
        lut.lerp[0].max > 90.0,
        "the wrap at ±180°: {:?}",
        lut.lerp[0]
    );
    // The compiled-in catalogue (held fresh by tests/figures/tables.rs) has them for
    // every codec: every one has a float form.
    let catalogue = unitpack::choice::catalogue::Catalogue::load();
    assert_eq!(
        catalogue.specs.len(),
        unitpack::report::doc_tables::codec_specs().len()
    );
    for e in &catalogue.specs {
        assert!(e.filtering.is_some(), "{} has no filtering figures", e.spec);
    }
    assert_eq!(
        catalogue.get("spherical_lut16").unwrap().filtering.as_ref(),
        Some(&lut)
    );
}

#[test]
fn index_codes_are_labelled_not_filterable() {
    for spec in ["sfib16", "latlong16", "latlongd24", "oct24:layout=rgb8"] {
        let s: Spec = spec.parse().unwrap();
        assert!(s.family().float_form(&s).unfilterable().is_some(), "{spec}");
    }
    for spec in ["oct16", "xy16", "hemioct16p:layout=rg"] {
        let s: Spec = spec.parse().unwrap();
        assert!(s.family().float_form(&s).unfilterable().is_none(), "{spec}");
    }
}

/// Every family states its float form: a codec of directions has one, with a seam in
/// words (where its parameters jump, or that they do not); packing helpers and tangent
/// frames have none that a texture filters.
#[test]
fn every_family_states_its_float_form() {
    use unitpack::codecs::core::info::FloatForm;
    for f in unitpack::codecs::FAMILIES {
        let info = f.info();
        let form = info.float_form;
        if info.domain.is_some() && !f.frames() {
            let seam = form
                .seam()
                .unwrap_or_else(|| panic!("{}: no float form", info.name));
            assert!(seam.len() > 10, "{}: {seam:?}", info.name);
        } else {
            assert_eq!(form, FloatForm::Absent, "{}", info.name);
        }
    }
}

/// A codec spec the compiled-in catalogue lacks (a family added since the catalogue was
/// last written) is named, for `list` to say so, rather than left out without a word; the
/// catalogue as built lacks none.
#[test]
fn a_spec_missing_from_the_catalogue_is_named() {
    use unitpack::choice::catalogue::Catalogue;
    use unitpack::codecs::Spec;
    let all = Spec::all();
    let mut c = Catalogue::load();
    assert_eq!(c.missing(&all), Vec::<String>::new());
    c.specs
        .retain(|e| e.spec != "oct16" && e.spec != "eqdist24p");
    assert_eq!(c.missing(&all), ["oct16", "eqdist24p"]);
}
