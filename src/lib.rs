#![doc = include_str!("../README.md")]

pub mod api;
pub mod cli;
pub mod codecs;
pub mod emit;
pub mod model;
pub mod quality;
pub mod verify;
