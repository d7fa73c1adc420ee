use unitpack::codecs::functions::function::Role;
use unitpack::measure::portability::*;
use unitpack::model::deviant::{Class, Mode};

fn row(class: Class, changed: usize) -> Row {
    Row {
        spec: "oct16".into(),
        function: "encode",
        role: Role::Encode,
        class: class.into(),
        items: 10,
        changed,
        by_mode: vec![changed],
        max_ulp: None,
        max_dev: None,
        bound: None,
        bound_at: None,
        example: None,
        promised: true,
    }
}

/// Every encoder the catalogue promises is portable, so the failing verdict (`verify
/// --portable` exits 1 on it) is exercised here on a report with a changed code.
#[test]
fn a_code_changed_under_a_guaranteed_class_fails_the_report() {
    let report = |rows| PortabilityReport {
        classes: vec![Class::Div.into(), Class::Excess.into()],
        modes: vec![Mode::Lowest],
        rows,
    };
    let failing = report(vec![row(Class::Div, 3), row(Class::Excess, 0)]);
    assert!(!failing.packed_encoders_portable());
    let table = failing.table();
    assert!(table.contains("3!"), "{table}");
    assert!(table.contains("failures: 1"), "{table}");
    assert!(failing.json().contains("\"fails\":true"));
    // Outside the guarantee a change is reported, not failed.
    let outside = report(vec![row(Class::Div, 0), row(Class::Excess, 2)]);
    assert!(outside.packed_encoders_portable());
    assert!(outside.table().contains("2x"));
    // An encoder documented not portable (the lean tier) is measured, not failed.
    let lean = report(vec![
        Row {
            promised: false,
            ..row(Class::Div, 5)
        },
        row(Class::Excess, 0),
    ]);
    assert!(lean.packed_encoders_portable());
    assert!(lean.guarantees_hold());
    assert!(lean.table().contains("5~"), "{}", lean.table());
    assert!(lean.json().contains("\"fails\":false,\"promised\":false"));
}
