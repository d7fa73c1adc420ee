//! Emission: traced functions and their measured figures ([`Measured`]) → WGSL, GLSL,
//! HLSL or C text. Emission only prints: every figure a comment quotes was measured
//! before (`crate::measure`). [`printer`] walks each traced function once; each language's module in [`lang`] owns its syntax, its askama
//! file template (in `templates/`) and its verification kernel; [`docs`] writes the doc
//! comments.

pub mod docs;
pub mod lang;

use crate::measure::figures::Measured;
use lang::printer::Printed;
use lang::{Backend, FileOptions, FnView, SpecView, Wrapper, layout, printer};
use std::fmt;

/// A target language.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Lang {
    Wgsl,
    Glsl,
    Hlsl,
    /// C99, also valid C++: headers for CPU asset pipelines.
    C,
}

impl Lang {
    pub const ALL: [Lang; 4] = [Lang::Wgsl, Lang::Glsl, Lang::Hlsl, Lang::C];
    /// The language's name: `--lang` value and the folder `generate` writes into.
    pub fn name(self) -> &'static str {
        match self {
            Lang::Wgsl => "wgsl",
            Lang::Glsl => "glsl",
            Lang::Hlsl => "hlsl",
            Lang::C => "c",
        }
    }
    /// The file extension of an include.
    pub fn ext(self) -> &'static str {
        match self {
            Lang::C => "h",
            other => other.name(),
        }
    }
    /// The language's syntax and templates, with names built from `prefix`.
    pub fn backend(self, prefix: &str) -> Box<dyn Backend> {
        match self {
            Lang::Wgsl => Box::new(lang::wgsl::Wgsl),
            Lang::Glsl => Box::new(lang::glsl::Glsl::new(prefix)),
            Lang::Hlsl => Box::new(lang::hlsl::Hlsl::new(prefix)),
            Lang::C => Box::new(lang::c::C::new(prefix)),
        }
    }
}

impl fmt::Display for Lang {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for Lang {
    type Err = String;
    fn from_str(s: &str) -> Result<Lang, String> {
        Lang::ALL
            .into_iter()
            .find(|l| l.name().eq_ignore_ascii_case(s.trim()))
            .ok_or_else(|| format!("unknown language '{s}'; languages: wgsl, glsl, hlsl, c"))
    }
}

/// The default name prefix: WGSL has no preprocessor, so names must not clash.
pub const DEFAULT_PREFIX: &str = "unitpack_";

/// One spec's functions in `lang`, named `{prefix}{namespace}_{name}`, or by their own
/// names alone where not `namespaced` (a WESL module, whose path names the spec).
pub fn spec_view(
    m: &Measured,
    lang: Lang,
    backend: &dyn Backend,
    prefix: &str,
    namespaced: bool,
) -> SpecView {
    let (spec, e) = (&m.spec, &*m.emitted);
    let ns = if e.namespace.is_empty() || !namespaced {
        String::new()
    } else {
        format!("{}_", e.namespace)
    };
    let public = |local: &str| format!("{prefix}{ns}{local}");
    let defined = |local: &str| backend.impl_name(&public(local));
    let functions = e
        .module
        .funcs
        .iter()
        .map(|f| {
            let p = printer::print(backend, f, &defined);
            let role = e
                .functions
                .iter()
                .find(|pf| pf.name == f.name)
                .map(|pf| pf.role);
            let returns = lang::Returns::of(f, &public(""));
            let wrapper = role
                .and_then(|_| backend.public_abi(&public(&f.name), &p.name, &f.params, &returns))
                .map(|(signature, body)| Wrapper {
                    name: public(&f.name),
                    signature,
                    body,
                });
            // Doc comments speak of the public name.
            let shown = Printed {
                name: public(&f.name),
                ..p
            };
            let doc = docs::function_doc(spec, e, &m.figures, &shown, role, &f.name);
            FnView {
                doc,
                name: defined(&f.name),
                params: shown.params,
                ret_ty: shown.ret_ty,
                body: shown.body,
                wrapper,
            }
        })
        .collect();
    let types = struct_defs(backend, &e.module.funcs, &defined);
    SpecView {
        guard: format!("{}{}_{}", prefix, spec.id(), lang.ext()).to_ascii_uppercase(),
        title: docs::spec_title(spec),
        doc: docs::spec_doc(spec, &m.figures),
        portable: docs::has_portable(spec, e, &m.figures),
        types,
        functions,
    }
}

/// The definitions of the structs `funcs` return (each once, in order of first use),
/// named as `defined` names a local name.
pub fn struct_defs(
    backend: &dyn Backend,
    funcs: &[crate::model::trace::Func],
    defined: &dyn Fn(&str) -> String,
) -> Vec<String> {
    let mut types: Vec<String> = Vec::new();
    for f in funcs {
        if let Some(shape) = f.shape {
            let fields: Vec<_> = shape
                .fields
                .iter()
                .copied()
                .zip(f.ret_tys.iter().copied())
                .collect();
            let def = backend.struct_def(&defined(shape.name), &fields);
            if !types.contains(&def) {
                types.push(def);
            }
        }
    }
    types
}

/// A complete include file for the given specs.
pub fn render(specs: &[Measured], lang: Lang, prefix: &str, command: &str) -> String {
    render_with(specs, lang, prefix, command, None)
}

/// [`render`], with a WGSL `#define_import_path` when `import_path` is given.
pub fn render_with(
    specs: &[Measured],
    lang: Lang,
    prefix: &str,
    command: &str,
    import_path: Option<&str>,
) -> String {
    let backend = lang.backend(prefix);
    let views: Vec<SpecView> = specs
        .iter()
        .map(|m| spec_view(m, lang, backend.as_ref(), prefix, true))
        .collect();
    let errors = specs.iter().any(|m| m.figures.errors.is_some());
    file(
        backend.as_ref(),
        views,
        errors,
        command,
        prefix,
        import_path,
    )
}

/// One spec's WGSL include as a WESL module (`unitpack/oct16.wesl`, imported as
/// `unitpack::oct16`): the same functions, text and comments, each named by its own name
/// alone (`encode`, `decode_float`), since the module path names the spec and WESL's
/// linker gives every imported declaration a name of its own.
pub fn render_wesl(m: &Measured, command: &str) -> String {
    let backend = Lang::Wgsl.backend("");
    let views = vec![spec_view(m, Lang::Wgsl, backend.as_ref(), "", false)];
    let errors = m.figures.errors.is_some();
    file(backend.as_ref(), views, errors, command, "", None)
}

/// The whole file of `views`: shared paragraphs referred back, the header, the template,
/// lines wrapped.
fn file(
    backend: &dyn Backend,
    mut views: Vec<SpecView>,
    errors: bool,
    command: &str,
    prefix: &str,
    import_path: Option<&str>,
) -> String {
    refer_back(&mut views);
    let header = docs::file_header(command, views.iter().any(|v| v.portable), errors);
    let mut s = backend.render(
        &views,
        &FileOptions {
            header: &header,
            prefix,
            import_path,
        },
    );
    if !s.ends_with('\n') {
        s.push('\n');
    }
    layout::wrap(&s)
}

/// A long paragraph a function's comment shares with an earlier function's (the edge
/// policy of a spec's encoders, say) is written once: the later comment refers back to
/// the first, so that a reader meets each long paragraph once per file.
fn refer_back(views: &mut [SpecView]) {
    const LONG: usize = 200;
    let mut first: std::collections::HashMap<String, String> = Default::default();
    for f in views.iter_mut().flat_map(|v| &mut v.functions) {
        let public = f.wrapper.as_ref().map_or(&f.name, |w| &w.name).clone();
        for d in &mut f.doc {
            if d.chars().count() <= LONG {
                continue;
            }
            match first.get(d.as_str()) {
                Some(earlier) => {
                    *d = match d.split_once(": ") {
                        Some((label, _)) => format!("{label}: as for {earlier}."),
                        None => format!("As for {earlier}."),
                    };
                }
                None => {
                    first.insert(d.clone(), public.clone());
                }
            }
        }
    }
}

/// Checks that a prefix makes valid identifiers in every language.
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
