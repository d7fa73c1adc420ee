use unitpack::cli::grammar::*;

#[test]
fn codes() {
    assert_eq!(parse_code("123", 16), Ok(123));
    assert_eq!(parse_code(" 0x7F\t", 16), Ok(0x7f));
    assert_eq!(parse_code("0X00ff", 16), Ok(0xff));
    assert_eq!(parse_code("007", 16), Ok(7));
    for bad in [
        "0b101", "+ff", "0x+ff", "-1", "ff", "0x", "", "1_0", "0o7", "1 2",
    ] {
        assert_eq!(parse_code(bad, 16), Err(LineError::NotACode), "{bad:?}");
    }
    assert_eq!(parse_code("0xffff", 16), Ok(0xffff));
    assert_eq!(
        parse_code("0x1ffff", 16),
        Err(LineError::TooWide { bits: 16 })
    );
    assert_eq!(
        parse_code("65536", 16),
        Err(LineError::TooWide { bits: 16 })
    );
    assert_eq!(
        parse_code("0x1000000", 24),
        Err(LineError::TooWide { bits: 24 })
    );
    assert_eq!(parse_code("0xffffffffffff", 48), Ok(0xffff_ffff_ffff));
    assert_eq!(
        parse_code("0x1000000000000", 48),
        Err(LineError::TooWide { bits: 48 })
    );
    assert_eq!(
        parse_code("99999999999999999999999", 48),
        Err(LineError::TooWide { bits: 48 })
    );
}

#[test]
fn vectors() {
    assert_eq!(parse_vector(" 1\t-0.5 .5 "), Ok([1.0, -0.5, 0.5]));
    assert_eq!(parse_vector("1 2"), Err(LineError::Count(2)));
    assert_eq!(parse_vector("1 2 3 4"), Err(LineError::Count(4)));
    assert_eq!(
        parse_vector("1e39 0 0"),
        Err(LineError::OutOfRange("1e39".into()))
    );
    assert!(parse_vector("inf -inf nan").is_ok());
    assert_eq!(
        parse_vector("a 0 0"),
        Err(LineError::NotANumber("a".into()))
    );
}

#[test]
fn quotes_are_cut() {
    assert_eq!(quote("1 2"), "\"1 2\"");
    let long = "é".repeat(1000);
    let q = quote(&long);
    assert!(q.chars().count() < QUOTE_CHARS + 20, "{q}");
    assert!(q.ends_with("(2000 bytes)"), "{q}");
}
