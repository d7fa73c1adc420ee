//! placeholder until the GPU harness lands
