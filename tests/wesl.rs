//! The WESL modules `generate` writes (`generated/wesl/<id>.wesl`, the module
//! `unitpack::<id>` of a package): each is its spec's WGSL include with the functions
//! named by their own names, every one links with the `wesl` crate into WGSL that naga
//! validates, every one links with npm's JavaScript `wesl` linker as well, and a package
//! importing two of them runs on lavapipe bit for bit as the model computes.

use unitpack::codecs::Spec;
use unitpack::emit::lang::{KernelFn, Returns};
use unitpack::emit::{DEFAULT_PREFIX, Lang, render};
use unitpack::measure::measured;
use unitpack::model::trace::Ty;
use unitpack::verify::gpu::{Gpu, Shader};
use unitpack::verify::tools::naga_wgsl;
use unitpack::verify::{expected, func_types, inputs};
use wesl::{CompileOptions, VirtualResolver, Wesl};

fn module_text(spec: &Spec) -> String {
    let path = format!(
        "{}/generated/wesl/{}.wesl",
        env!("CARGO_MANIFEST_DIR"),
        spec.id()
    );
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// The code of a file as tokens, comments and white space left out: identifiers, numbers
/// (with their suffixes) and single punctuation characters.
fn tokens(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    for line in text.lines().filter(|l| !l.trim_start().starts_with("//")) {
        let mut chars = line.chars().peekable();
        while let Some(c) = chars.next() {
            if c.is_whitespace() {
                continue;
            }
            let mut t = c.to_string();
            if c.is_alphanumeric() || c == '_' {
                while let Some(&d) = chars.peek() {
                    if !(d.is_alphanumeric() || d == '_' || (c.is_ascii_digit() && d == '.')) {
                        break;
                    }
                    t.push(d);
                    chars.next();
                }
            }
            out.push(t);
        }
    }
    out
}

/// Whether two texts are the same code up to names: token for token, where the
/// identifiers that differ are renamed consistently both ways, each one a prefixed name
/// of the WGSL include (`unitpack_oct16_round_codes` → `round_codes`) or a local the
/// printer numbered because its name is now a function's (`round_codes` →
/// `round_codes2`). Builtins, keywords and literals are the same.
fn same_up_to_names(wgsl: &str, wesl: &str) -> Result<(), String> {
    let (a, b) = (tokens(wgsl), tokens(wesl));
    if a.len() != b.len() {
        return Err(format!("{} tokens against {}", a.len(), b.len()));
    }
    let mut forth = std::collections::HashMap::new();
    let mut back = std::collections::HashMap::new();
    let ident = |t: &str| t.starts_with(|c: char| c.is_alphabetic() || c == '_');
    for (k, (x, y)) in a.iter().zip(&b).enumerate() {
        if x == y && !ident(x) {
            continue;
        }
        let numbered = y.strip_prefix(x.as_str()).is_some_and(|n| {
            !n.is_empty()
                && n.trim_start_matches('_')
                    .chars()
                    .all(|c| c.is_ascii_digit())
        });
        let renamed = ident(x) && ident(y) && (x == y || x.starts_with(DEFAULT_PREFIX) || numbered);
        let consistent = *forth.entry(x).or_insert(y) == y && *back.entry(y).or_insert(x) == x;
        if !(renamed && consistent) {
            return Err(format!("token {k}: {x:?} against {y:?}"));
        }
    }
    Ok(())
}

/// A spec's functions as a root module calls them: the name of the root's wrapper
/// (`call_oct16__encode`, which no name the linker gives an imported declaration can
/// be), the function's own name, its parameter types and result.
fn functions(spec: &Spec) -> Vec<(String, String, Vec<Ty>, Returns)> {
    let e = spec.emitted();
    e.functions
        .iter()
        .map(|f| {
            let (params, ret) = func_types(e.module.func(f.name).expect("traced"), "");
            (
                format!("call_{}__{}", spec.id(), f.name),
                f.name.to_string(),
                params,
                ret,
            )
        })
        .collect()
}

/// A root that imports `specs`' modules and wraps each function of theirs, calling it
/// through the module path, linked with the `wesl` crate.
fn link(specs: &[Spec]) -> String {
    let wgsl = Lang::Wgsl.backend(DEFAULT_PREFIX);
    let mut resolver = VirtualResolver::new();
    let mut root = String::new();
    let mut wrappers = String::new();
    for spec in specs {
        let id = spec.id();
        resolver.add_module(
            format!("unitpack::{id}").parse().expect("module path"),
            module_text(spec).into(),
        );
        root.push_str(&format!("import unitpack::{id};\n"));
        for (name, own, params, ret) in functions(spec) {
            let args: Vec<String> = (0..params.len()).map(|i| format!("a{i}")).collect();
            let declared: Vec<String> = params
                .iter()
                .zip(&args)
                .map(|(t, a)| format!("{a}: {}", wgsl.ty(*t)))
                .collect();
            wrappers.push_str(&format!(
                "fn {name}({}) -> {} {{ return {id}::{own}({}); }}\n",
                declared.join(", "),
                // A struct is the module's: named through its path.
                match &ret.name {
                    Some(name) => format!("{id}::{name}"),
                    None => ret.ty(wgsl.as_ref()),
                },
                args.join(", ")
            ));
        }
    }
    root.push_str(&wrappers);
    resolver.add_module("package::main".parse().expect("root path"), root.into());
    let mut compiler = Wesl::new("").set_custom_resolver(resolver);
    compiler.set_options(CompileOptions {
        keep_root: true,
        ..Default::default()
    });
    compiler
        .compile(&"package::main".parse().expect("root path"))
        .unwrap_or_else(|e| panic!("{specs:?}: {e}"))
        .to_string()
}

/// Every module is its WGSL include with `unitpack_<spec>_` dropped from the names: the
/// same code up to names, which `verify` runs on every path.
#[test]
fn each_module_is_its_wgsl_include_renamed() {
    for spec in Spec::all() {
        let wgsl = render(&[measured(&spec, None)], Lang::Wgsl, DEFAULT_PREFIX, "x");
        let module = module_text(&spec);
        assert!(!module.contains(DEFAULT_PREFIX), "{spec}: a prefixed name");
        // The wesl crate reads a hexadecimal float's exponent wrongly (as a power of 16).
        let hex_float = tokens(&module)
            .into_iter()
            .find(|t| t.starts_with("0x") && t.contains(['.', 'p']));
        assert_eq!(hex_float, None, "{spec}: a hexadecimal float literal");
        same_up_to_names(&wgsl, &module).unwrap_or_else(|e| panic!("{spec}: {e}"));
    }
}

/// Every module links alone (its functions all kept by the root's calls) into WGSL
/// that naga validates and Tint compiles (WebGPU in headless Chromium).
#[test]
fn every_module_links_and_validates() {
    use unitpack::verify::browser::{Api, Browser};
    let browser = Browser::start().unwrap_or_else(|e| panic!("{e:#}"));
    for spec in Spec::all() {
        let linked = link(std::slice::from_ref(&spec));
        naga_wgsl(&linked).unwrap_or_else(|e| panic!("{spec}: {e:#}\n{linked}"));
        // Chrome's WGSL compiler is stricter than naga (an out-of-range literal is an error).
        browser
            .compile(Api::WebGpu, &linked)
            .unwrap_or_else(|e| panic!("{spec}: Tint: {e:#}\n{linked}"));
    }
}

/// npm's `wesl` linker (`tools/wesl-js`, pinned by its lockfile) on `files`, through
/// `tools/wesl-js/link.mjs`: each file and its error, if it did not link.
fn javascript_links(files: &[std::path::PathBuf]) -> Vec<(String, Option<String>)> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tools/wesl-js");
    assert!(
        dir.join("node_modules/wesl/package.json").exists(),
        "npm's wesl linker is not installed: run `npm ci --prefix tools/wesl-js` \
         (Node.js and npm: the Debian packages `nodejs` and `npm`)"
    );
    let out = std::process::Command::new("node")
        .arg(dir.join("link.mjs"))
        .args(files)
        .output()
        .unwrap_or_else(|e| panic!("running `node` (the Debian package `nodejs`): {e}"));
    assert!(
        out.status.success(),
        "link.mjs failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout)
        .expect("UTF-8")
        .lines()
        .map(|line| {
            let v: serde_json::Value = serde_json::from_str(line).expect("a JSON line");
            let file = v["file"].as_str().expect("file").to_string();
            (file, v["error"].as_str().map(str::to_string))
        })
        .collect()
}

/// Every generated module links with the JavaScript WESL linker a web application
/// uses, whose template-list discovery is not WGSL's (`less_than_as_greater` in
/// `src/emit/lang`); the module written before that rule fails there.
#[test]
fn every_module_links_with_the_javascript_linker() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files: Vec<_> = std::fs::read_dir(root.join("generated/wesl"))
        .expect("generated/wesl")
        .map(|e| e.expect("an entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "wesl"))
        .collect();
    files.sort();
    assert!(files.len() >= Spec::all().len(), "{} modules", files.len());
    let results = javascript_links(&files);
    assert_eq!(results.len(), files.len(), "one result per module");
    let failed: Vec<String> = results
        .iter()
        .filter_map(|(f, e)| e.as_ref().map(|e| format!("{f}: {e}")))
        .collect();
    assert!(
        failed.is_empty(),
        "{} of {} modules do not link with npm's wesl:\n{}",
        failed.len(),
        files.len(),
        failed.join("\n")
    );
    // `t5 < vec2<f32>(0.0f)` in a select followed by a `>=`: read as a template there.
    let old = root.join("tests/data/cry3_16_before_the_js_linker_fix.wesl");
    let results = javascript_links(&[old]);
    let error = results[0]
        .1
        .as_deref()
        .expect("the old module fails to link");
    assert!(error.contains("template"), "{error}");
}

/// A package importing two modules (oct16, and float16x3 with its two-word codes and
/// integer vector selects) links to WGSL whose every function gives the model's bits on
/// every verify input, run on lavapipe through naga.
#[test]
fn two_linked_modules_run_bit_exact() {
    let specs: Vec<Spec> = ["oct16", "float16x3"]
        .iter()
        .map(|s| s.parse().unwrap())
        .collect();
    let linked = link(&specs);
    naga_wgsl(&linked).unwrap_or_else(|e| panic!("{e:#}\n{linked}"));
    let mut funcs: Vec<(String, Vec<Ty>, Returns)> = Vec::new();
    let mut models = Vec::new();
    for spec in &specs {
        let e = spec.emitted();
        for ((name, _, params, ret), f) in
            functions(spec).into_iter().zip(e.functions.iter().cloned())
        {
            funcs.push((name, params, ret));
            models.push((spec.to_string(), f));
        }
    }
    let kernel_fns: Vec<KernelFn> = funcs
        .iter()
        .map(|(n, p, r)| (n.as_str(), p.clone(), r.clone()))
        .collect();
    let kernel = Lang::Wgsl
        .backend(DEFAULT_PREFIX)
        .kernel(&linked, &kernel_fns);
    let gpu = Gpu::shared().expect("lavapipe (Debian package mesa-vulkan-drivers)");
    let selecting = gpu
        .selecting(&Shader::Wgsl(&kernel))
        .unwrap_or_else(|e| panic!("{e:#}"));
    for (index, (spec, f)) in (0u32..).zip(&models) {
        let input = inputs::generate(&f.inputs, f.in_words);
        let want = expected(f, &input);
        let mut got = Vec::with_capacity(want.len());
        gpu.run_selected(
            &selecting,
            index,
            &input,
            f.in_words,
            f.out_words,
            &mut |w| got.extend_from_slice(w),
        )
        .unwrap_or_else(|e| panic!("{spec} {}: {e:#}", f.name));
        assert_eq!(got.len(), want.len(), "{spec} {}", f.name);
        if let Some(k) = (0..want.len()).find(|&k| got[k] != want[k]) {
            let item = k / f.out_words;
            panic!(
                "{spec} {}: item {item} (input {:08x?}) gives {:08x?}, the model {:08x?}",
                f.name,
                &input[item * f.in_words..][..f.in_words],
                &got[item * f.out_words..][..f.out_words],
                &want[item * f.out_words..][..f.out_words],
            );
        }
    }
}

/// The README's two WESL imports link against the generated oct16 module: as the module
/// `unitpack::oct16` of a package `unitpack`, and as `package::unitpack::oct16` inside the
/// user's own package; naga validates each result.
#[test]
fn the_readme_imports_link() {
    let readme = std::fs::read_to_string(format!("{}/README.md", env!("CARGO_MANIFEST_DIR")))
        .expect("README.md");
    let oct16: Spec = "oct16".parse().unwrap();
    for (import, path) in [
        ("import unitpack::oct16::", "unitpack::oct16"),
        (
            "import package::unitpack::oct16::",
            "package::unitpack::oct16",
        ),
    ] {
        let statement = readme
            .split('`')
            .find(|s| s.starts_with(import))
            .unwrap_or_else(|| panic!("the README has no `{import}…`"));
        let root = format!(
            "{statement}\nfn reencode(code: u32, model: mat4x4<f32>) -> u32 {{\n    \
             return encode((model * vec4<f32>(decode(code), 0.0)).xyz);\n}}\n"
        );
        let mut resolver = VirtualResolver::new();
        resolver.add_module(path.parse().unwrap(), module_text(&oct16).into());
        resolver.add_module("package::main".parse().unwrap(), root.into());
        let mut compiler = Wesl::new("").set_custom_resolver(resolver);
        compiler.set_options(CompileOptions {
            keep_root: true,
            ..Default::default()
        });
        let linked = compiler
            .compile(&"package::main".parse().unwrap())
            .unwrap_or_else(|e| panic!("{path}: {e}"))
            .to_string();
        assert!(linked.contains("fn reencode("), "{linked}");
        naga_wgsl(&linked).unwrap_or_else(|e| panic!("{path}: {e:#}\n{linked}"));
    }
}
