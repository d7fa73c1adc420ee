#![doc = include_str!("../README.md")]

pub mod api;
#[cfg(feature = "cli")]
pub mod cli;
pub mod codecs;
pub mod emit;
pub mod model;
pub mod quality;
#[cfg(feature = "verify")]
pub mod verify;
