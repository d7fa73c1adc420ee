//! What every room leans on and none is about: files replaced atomically ([`atomic`]),
//! PNG files ([`png_file`]), work spread over threads ([`par`]), process-wide tables of
//! results worth computing once ([`memo`]) and seeded unit vectors ([`sampling`]). Nothing
//! here names another module of the crate.

pub mod atomic;
pub(crate) mod memo;
pub mod par;
#[cfg(feature = "cli")]
pub(crate) mod png_file;
pub mod sampling;
