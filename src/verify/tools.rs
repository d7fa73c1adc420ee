//! placeholder until the tool wrappers land
