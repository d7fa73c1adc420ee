//! What is wrong with a spec a user typed, or with a size or option a codec is asked for.

#[derive(Debug, thiserror::Error, PartialEq)]
pub enum SpecError {
    #[error("unknown codec '{given}'; did you mean {}? Valid codecs: {}", .nearest.join(" or "), .valid.join(", "))]
    UnknownCodec {
        given: String,
        nearest: Vec<String>,
        valid: Vec<String>,
    },
    #[error("{codec} has no {bits}-bit form; allowed sizes: {}", .allowed.join(", "))]
    InvalidBits {
        codec: &'static str,
        bits: String,
        allowed: Vec<String>,
    },
    #[error("{codec} needs a bit size, e.g. {codec}{}; allowed sizes: {}", .allowed[0], .allowed.join(", "))]
    MissingBits {
        codec: &'static str,
        allowed: Vec<String>,
    },
    #[error("'{given}' is not a form of {codec}; write one of: {}", .allowed.join(", "))]
    Spelling {
        codec: &'static str,
        given: String,
        allowed: Vec<String>,
    },
    #[error("'{given}': after {spelled} comes nothing, 'p' (precise), '_option' or ':key=value'")]
    Trailing { given: String, spelled: String },
    #[error("{spelled} has no precise encoder (drop the 'p')")]
    NoPrecise { spelled: String },
    #[error("{codec} takes no option '{key}'; options: {options}")]
    UnknownOption {
        codec: &'static str,
        key: String,
        options: String,
    },
    #[error("'{token}' in '{given}' is not an option of {codec}; options: {options}")]
    UnknownToken {
        codec: &'static str,
        given: String,
        token: String,
        options: String,
    },
    #[error("option {key} is given twice in '{given}'")]
    DuplicateOption { key: String, given: String },
    #[error("empty option in '{given}': write NAME:key=value[,key=value...] or no ':' at all")]
    EmptyOption { given: String },
    #[error("bad value '{value}' for {key}: {why}")]
    BadValue {
        key: String,
        value: String,
        why: String,
    },
    #[error("{0}")]
    Invalid(String),
}
