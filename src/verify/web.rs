//! `unitpack verify --web DIR`: a page that verifies the catalogue's WGSL through WebGPU on
//! whatever GPU the visitor's browser has (Metal on a Mac, D3D12 on Windows, Vulkan on
//! Linux and Android), where no machine of ours can. One self-contained file, `index.html`:
//! the job runner of the browser paths ([`super::browser::RUNNER_JS`]), each spec's WGSL
//! kernel, each function's inputs and what the model computes for them, nothing fetched
//! from elsewhere.
//!
//! To keep the page small, a function takes [`WEB_ITEMS`] items (every edge item first,
//! then a seeded spread, as the sampled paths do). Packed outputs carry two hashes of the
//! model's words and the first [`HEAD_ITEMS`] items' words, which locate a mismatch there;
//! float outputs carry every word, so that the page can give the largest difference and
//! hold it against the function's proven bound where it has one.

use super::{GL_ITEMS, expected, owners, picks};
use crate::codecs::Spec;
use crate::codecs::functions::function::Function;
use crate::emit::{DEFAULT_PREFIX, Lang, render};
use crate::model::Kind;
use anyhow::{Context, Result};
use base64::Engine;
use std::path::Path as FsPath;

/// Items of each function the page runs.
pub const WEB_ITEMS: usize = GL_ITEMS / 64;

/// Items of each packed function whose expected words the page carries in full.
pub const HEAD_ITEMS: usize = 256;

const PAGE_JS: &str = include_str!("web/page.js");

/// The two hashes of a function's output words the page recomputes (`page.js`): FNV-1a
/// over the words, and a multiply-rotate mix; 64 bits between them.
pub fn hashes(words: &[u32]) -> [u32; 2] {
    let (mut a, mut b) = (0x811c_9dc5u32, 0x9e37_79b9u32);
    for &w in words {
        a = (a ^ w).wrapping_mul(0x0100_0193);
        b = (b ^ w).wrapping_mul(0x5bd1_e995).rotate_left(13);
    }
    [a, b]
}

fn b64(words: &[u32]) -> String {
    let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).collect();
    base64::engine::general_purpose::STANDARD.encode(bytes)
}

/// One function's entry in the page's data.
fn function_json(
    module: &crate::model::trace::Module,
    f: &Function,
    selector: usize,
    params_float: bool,
    out_float: bool,
    lean: bool,
) -> serde_json::Value {
    let all = super::inputs::generate(&f.inputs, f.in_words);
    let mut input = Vec::new();
    for k in picks(all.len() / f.in_words, WEB_ITEMS) {
        input.extend_from_slice(&all[k * f.in_words..][..f.in_words]);
    }
    let want = expected(f, &input);
    let bound = crate::measure::decode_bound::cached(module, f)
        .map(|b| b.units * crate::measure::figures::UNIT)
        .filter(|_| out_float);
    let head = (HEAD_ITEMS * f.out_words).min(want.len());
    serde_json::json!({
        "name": f.name,
        "selector": selector,
        "in_words": f.in_words,
        "out_words": f.out_words,
        "input_float": params_float,
        "output_float": out_float,
        "bound": bound,
        "lean": lean,
        "input": b64(&input),
        "expected": if out_float { serde_json::Value::String(b64(&want)) } else { serde_json::Value::Null },
        "head": b64(&want[..head]),
        "hashes": hashes(&want),
    })
}

/// The page for `specs`, with each spec's WGSL include passed through `include` first (the
/// suite perturbs one there to see the page catch it).
pub fn page(specs: &[Spec], include: impl Fn(&Spec, String) -> String + Sync) -> String {
    let emitted: Vec<_> = specs.iter().map(|s| s.emitted()).collect();
    let owners = owners(specs, &emitted);
    let entries: Vec<serde_json::Value> =
        crate::support::par::map(&(0..specs.len()).collect::<Vec<_>>(), |&i| {
            let (spec, e) = (&specs[i], &emitted[i]);
            let ns = if e.namespace.is_empty() {
                String::new()
            } else {
                format!("{}_", e.namespace)
            };
            let prefix = format!("{DEFAULT_PREFIX}{ns}");
            let own: Vec<&Function> = e
                .functions
                .iter()
                .zip(&owners[i])
                .filter(|(_, o)| o.is_none())
                .map(|(f, _)| f)
                .collect();
            let names: Vec<String> = own.iter().map(|f| format!("{prefix}{}", f.name)).collect();
            let funcs: Vec<crate::emit::lang::KernelFn> = own
                .iter()
                .zip(&names)
                .map(|(f, name)| {
                    let (params, ret) =
                        super::func_types(e.module.func(f.name).expect("traced"), &prefix);
                    (name.as_str(), params, ret)
                })
                .collect();
            let text = render(
                &[crate::measure::measured(spec, None)],
                Lang::Wgsl,
                DEFAULT_PREFIX,
                "unitpack verify --web",
            );
            let text = include(spec, text);
            let kernel = Lang::Wgsl.backend(DEFAULT_PREFIX).kernel(&text, &funcs);
            let functions: Vec<serde_json::Value> = own
                .iter()
                .zip(&funcs)
                .enumerate()
                .map(|(k, (f, (_, params, ret)))| {
                    let params_float = params.iter().all(|t| t.kind == Kind::F32);
                    function_json(
                        &e.module,
                        f,
                        k,
                        params_float,
                        ret.kind() == Kind::F32,
                        crate::codecs::core::ieee::asked(spec),
                    )
                })
                .collect();
            serde_json::json!({ "spec": spec.to_string(), "wgsl": kernel, "functions": functions })
        });
    let data = serde_json::json!({
        "generator": format!("unitpack {}", env!("CARGO_PKG_VERSION")),
        "items": WEB_ITEMS,
        "head_items": HEAD_ITEMS,
        "specs": entries,
    });
    // `</` would end the script element early; JSON allows `<\/`.
    let data = data.to_string().replace("</", "<\\/");
    format!(
        "<!doctype html>
<html lang=\"en\">
<head>
<meta charset=\"utf-8\">
<title>unitpack: verify on this GPU</title>
<style>
body {{ font: 14px system-ui, sans-serif; margin: 2em; max-width: 70em; }}
table {{ border-collapse: collapse; }}
td, th {{ padding: 0.2em 0.8em; text-align: left; border-bottom: 1px solid #ddd; vertical-align: top; }}
.pass {{ color: #060; }} .fail {{ color: #b00; font-weight: bold; }} .measured {{ color: #a60; }}
code, pre {{ font: 12px ui-monospace, monospace; }}
</style>
</head>
<body>
<h1>unitpack: verify on this GPU</h1>
<p>Runs every function's WGSL through this browser's WebGPU and compares the raw bits with
unitpack's model, {WEB_ITEMS} items per function. Nothing is sent anywhere.</p>
<p id=\"adapter\">Starting…</p>
<p><button id=\"save\" disabled>Save the result as JSON</button> <span id=\"summary\"></span></p>
<table><thead><tr><th>spec</th><th>function</th><th>result</th><th>details</th></tr></thead>
<tbody id=\"rows\"></tbody></table>
<script type=\"application/json\" id=\"unitpack-data\">{data}</script>
<script>
{runner}
</script>
<script>
{PAGE_JS}
</script>
</body>
</html>
",
        runner = super::browser::RUNNER_JS,
    )
}

/// Writes the page for `specs` to `dir/index.html` (atomically; `dir` is created if
/// missing) and returns its path.
pub fn write(dir: &FsPath, specs: &[Spec]) -> Result<std::path::PathBuf> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let path = dir.join("index.html");
    crate::support::atomic::write_atomic(&path, page(specs, |_, t| t).as_bytes())
        .with_context(|| format!("writing {}", path.display()))?;
    Ok(path)
}
