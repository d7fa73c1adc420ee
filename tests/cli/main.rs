//! The `unitpack` binary end to end: every verb, every bad-input case, exit statuses and
//! the text a user relies on. Runs the built binary with std::process::Command.
//!
//! One test binary with a module per verb: every test binary links the whole library
//! (wgpu and naga included), so one link serves all of them.

mod choose;
mod choose_use;
mod common;
mod convert;
mod generate;
mod gltf;
mod help;
mod include;
mod list;
mod report;
mod sample;
mod spec;
mod stdout;
mod stream;
mod transcode;
mod verify;
