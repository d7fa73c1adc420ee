//! Prints the generated includes' sizes and the first function of each, so a test can
//! check that the build script ran and wrote what it was asked for.

const FILES: [(&str, &str); 4] = [
    (
        "normals.wgsl",
        include_str!(concat!(env!("OUT_DIR"), "/normals.wgsl")),
    ),
    (
        "normals.glsl",
        include_str!(concat!(env!("OUT_DIR"), "/normals.glsl")),
    ),
    (
        "normals.hlsl",
        include_str!(concat!(env!("OUT_DIR"), "/normals.hlsl")),
    ),
    (
        "normals.h",
        include_str!(concat!(env!("OUT_DIR"), "/normals.h")),
    ),
];

fn main() {
    for (name, text) in FILES {
        let first = text
            .lines()
            .find(|l| l.contains("unitpack_oct24p_encode("))
            .unwrap_or("(no oct24p encoder)");
        println!("{name} {} bytes: {}", text.len(), first.trim());
    }
}
