//! Ports of engines' normal and tangent-frame codecs, the oracles of the engine formats
//! (`src/codecs/engine`). Each cites the upstream file and commit it follows; each is
//! written here, independently of the model it checks.

pub mod bevy;
pub mod draco;
pub mod filament;
pub mod gltf_transform;
pub mod godot;
pub mod meshopt;
pub mod unity;
