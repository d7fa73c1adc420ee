//! Emission: traced functions → WGSL, GLSL or HLSL text. [`printer`] writes function
//! bodies; the askama templates in `templates/` own everything around them (header,
//! include guards, doc comments, signatures); [`docs`] writes the doc comments.

pub mod docs;
pub mod printer;

use crate::codecs::Spec;
use crate::quality::ErrorStats;
use askama::Template;
use std::fmt;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, clap::ValueEnum)]
pub enum Lang {
    Wgsl,
    Glsl,
    Hlsl,
}

impl Lang {
    pub const ALL: [Lang; 3] = [Lang::Wgsl, Lang::Glsl, Lang::Hlsl];
    pub fn ext(self) -> &'static str {
        match self {
            Lang::Wgsl => "wgsl",
            Lang::Glsl => "glsl",
            Lang::Hlsl => "hlsl",
        }
    }
}

impl fmt::Display for Lang {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.ext())
    }
}

/// The default name prefix: WGSL has no preprocessor, so names must not clash.
pub const DEFAULT_PREFIX: &str = "unitpack_";

pub struct FnView {
    pub doc: Vec<String>,
    pub name: String,
    pub params: Vec<(String, String)>,
    pub ret_ty: String,
    pub body: Vec<String>,
}

pub struct SpecView {
    pub guard: String,
    pub title: String,
    pub functions: Vec<FnView>,
}

#[derive(Template)]
#[template(path = "wgsl.txt", escape = "none")]
struct WgslFile<'a> {
    header: &'a [String],
    specs: &'a [SpecView],
}

#[derive(Template)]
#[template(path = "glsl.txt", escape = "none")]
struct GlslFile<'a> {
    header: &'a [String],
    specs: &'a [SpecView],
    precise_macro: String,
}

#[derive(Template)]
#[template(path = "hlsl.txt", escape = "none")]
struct HlslFile<'a> {
    header: &'a [String],
    specs: &'a [SpecView],
    select_macro: String,
}

/// One spec's functions in `lang`, named `{prefix}{namespace}_{name}`.
pub fn spec_view(spec: &Spec, lang: Lang, prefix: &str, stats: Option<ErrorStats>) -> SpecView {
    let e = spec.emitted();
    let ns = if e.namespace.is_empty() {
        String::new()
    } else {
        format!("{}_", e.namespace)
    };
    let full = |local: &str| format!("{prefix}{ns}{local}");
    let functions = e
        .module
        .funcs
        .iter()
        .map(|f| {
            let p = printer::print(lang, f, prefix, &full);
            let public = e.functions.iter().find(|pf| pf.name == f.name);
            FnView {
                doc: docs::function_doc(spec, &e, &p, public.map(|pf| pf.role), &f.name, stats),
                name: p.name,
                params: p.params,
                ret_ty: p.ret_ty,
                body: p.body,
            }
        })
        .collect();
    SpecView {
        guard: format!("{}{}_{}", prefix, spec.id(), lang.ext()).to_ascii_uppercase(),
        title: docs::spec_title(spec),
        functions,
    }
}

/// A complete include file for the given specs.
pub fn render(
    specs: &[(Spec, Option<ErrorStats>)],
    lang: Lang,
    prefix: &str,
    command: &str,
) -> String {
    let views: Vec<SpecView> = specs
        .iter()
        .map(|(s, st)| spec_view(s, lang, prefix, *st))
        .collect();
    let header = docs::file_header(command);
    let r = match lang {
        Lang::Wgsl => WgslFile {
            header: &header,
            specs: &views,
        }
        .render(),
        Lang::Glsl => GlslFile {
            header: &header,
            specs: &views,
            precise_macro: printer::precise_macro(prefix),
        }
        .render(),
        Lang::Hlsl => HlslFile {
            header: &header,
            specs: &views,
            select_macro: printer::select_macro(prefix),
        }
        .render(),
    };
    let mut s = r.expect("templates render");
    if !s.ends_with('\n') {
        s.push('\n');
    }
    s
}

/// Checks that a prefix makes valid identifiers in all three languages.
pub fn validate_prefix(p: &str) -> Result<(), String> {
    let ok = p.chars().next().is_none_or(|c| c.is_ascii_alphabetic())
        && p.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
        && !p.contains("__")
        && !p.to_ascii_lowercase().starts_with("gl_");
    if ok {
        Ok(())
    } else {
        Err(format!(
            "invalid prefix '{p}': use ASCII letters, digits and single underscores, starting with a letter (GLSL reserves '__' and 'gl_')"
        ))
    }
}
