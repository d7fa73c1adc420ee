//! Folding changes no operation: for every function of every spec, naga reads the folded
//! text the includes hold and the one-operation-per-statement text into the same
//! expression graph, in WGSL and in GLSL. Each returned value is reduced to a canonical
//! graph (hash-consed: an operation and the canonical ids of its operands), through `let`
//! bindings, local variables and the branches naga makes of GLSL's `?:`, so two texts
//! agree exactly when they compute the same operations on the same operands.

use naga::{Expression, Handle, Statement};
use std::collections::HashMap;
use unitpack::codecs::Spec;
use unitpack::emit::Lang;
use unitpack::emit::lang::printer::{Printed, Style, print_as};

/// Canonical ids of operation graphs, shared by the modules compared.
#[derive(Default)]
struct Interner {
    ids: HashMap<String, usize>,
}

impl Interner {
    fn id(&mut self, key: String) -> usize {
        let n = self.ids.len();
        *self.ids.entry(key).or_insert(n)
    }
}

/// One naga function's values: what each local variable holds, and call results.
struct Graph<'a> {
    module: &'a naga::Module,
    f: &'a naga::Function,
    /// The value last stored into each local variable, in program order.
    locals: HashMap<Handle<naga::LocalVariable>, Handle<Expression>>,
    /// Local variables assigned in the two branches of an `if`: `condition ? accept : reject`.
    chosen: HashMap<Handle<naga::LocalVariable>, [Handle<Expression>; 3]>,
    calls: HashMap<Handle<Expression>, (String, Vec<Handle<Expression>>)>,
    memo: HashMap<Handle<Expression>, usize>,
    ret: Option<Handle<Expression>>,
}

impl<'a> Graph<'a> {
    fn new(module: &'a naga::Module, f: &'a naga::Function) -> Self {
        let mut g = Graph {
            module,
            f,
            locals: HashMap::new(),
            chosen: HashMap::new(),
            calls: HashMap::new(),
            memo: HashMap::new(),
            ret: None,
        };
        for (h, v) in f.local_variables.iter() {
            if let Some(init) = v.init {
                g.locals.insert(h, init);
            }
        }
        g.walk(&f.body);
        g
    }

    fn local_of(&self, pointer: Handle<Expression>) -> Handle<naga::LocalVariable> {
        match self.f.expressions[pointer] {
            Expression::LocalVariable(l) => l,
            ref e => panic!("a store through {e:?}"),
        }
    }

    fn walk(&mut self, block: &naga::Block) {
        for s in block.iter() {
            match s {
                Statement::Emit(_) => {}
                Statement::Block(b) => self.walk(b),
                Statement::Store { pointer, value } => {
                    let l = self.local_of(*pointer);
                    self.locals.insert(l, *value);
                    self.chosen.remove(&l);
                }
                Statement::If {
                    condition,
                    accept,
                    reject,
                } => {
                    let stored =
                        |b: &naga::Block| -> Option<(Handle<Expression>, Handle<Expression>)> {
                            b.iter().find_map(|s| match s {
                                Statement::Store { pointer, value } => Some((*pointer, *value)),
                                _ => None,
                            })
                        };
                    let (Some((p, a)), Some((_, r))) = (stored(accept), stored(reject)) else {
                        panic!("an if that is not a ?:");
                    };
                    // A nested `?:` is an `if` inside a branch.
                    self.walk(accept);
                    self.walk(reject);
                    let l = self.local_of(p);
                    self.chosen.insert(l, [*condition, a, r]);
                }
                Statement::Call {
                    function,
                    arguments,
                    result,
                } => {
                    let name = self.module.functions[*function]
                        .name
                        .clone()
                        .unwrap_or_default();
                    if let Some(r) = result {
                        self.calls.insert(*r, (name, arguments.clone()));
                    }
                }
                Statement::Return { value } => self.ret = *value,
                other => panic!("unexpected statement {other:?}"),
            }
        }
    }

    /// The canonical id of the value of `h`.
    fn canon(&mut self, h: Handle<Expression>, ids: &mut Interner) -> usize {
        if let Some(&id) = self.memo.get(&h) {
            return id;
        }
        let key = match &self.f.expressions[h] {
            Expression::Load { pointer } => {
                let id = self.canon(*pointer, ids);
                self.memo.insert(h, id);
                return id;
            }
            Expression::LocalVariable(l) => {
                let id = if let Some([c, a, r]) = self.chosen.get(l).copied() {
                    let k = format!(
                        "select({},{},{})",
                        self.canon(c, ids),
                        self.canon(a, ids),
                        self.canon(r, ids)
                    );
                    ids.id(k)
                } else {
                    let v = *self.locals.get(l).unwrap_or_else(|| {
                        panic!(
                            "{:?} is read but never stored\n{:#?}",
                            self.f.local_variables[*l], self.f.body
                        )
                    });
                    self.canon(v, ids)
                };
                self.memo.insert(h, id);
                return id;
            }
            Expression::Literal(l) => format!("lit {l:?}"),
            Expression::Constant(c) => {
                let init = self.module.constants[*c].init;
                format!("const {:?}", self.module.global_expressions[init])
            }
            Expression::ZeroValue(t) => format!("zero {:?}", self.module.types[*t].inner),
            Expression::FunctionArgument(i) => format!("arg {i}"),
            Expression::Compose { ty, components } => {
                let c: Vec<usize> = components.iter().map(|c| self.canon(*c, ids)).collect();
                format!("compose {:?} {c:?}", self.module.types[*ty].inner)
            }
            Expression::Splat { size, value } => {
                format!("splat {size:?} {}", self.canon(*value, ids))
            }
            Expression::Swizzle {
                size,
                vector,
                pattern,
            } => format!(
                "swizzle {:?} {}",
                &pattern[..*size as usize],
                self.canon(*vector, ids)
            ),
            Expression::AccessIndex { base, index } => {
                format!("index {index} {}", self.canon(*base, ids))
            }
            Expression::Unary { op, expr } => format!("{op:?} {}", self.canon(*expr, ids)),
            Expression::Binary { op, left, right } => {
                format!(
                    "{op:?} {} {}",
                    self.canon(*left, ids),
                    self.canon(*right, ids)
                )
            }
            Expression::Select {
                condition,
                accept,
                reject,
            } => format!(
                "select({},{},{})",
                self.canon(*condition, ids),
                self.canon(*accept, ids),
                self.canon(*reject, ids)
            ),
            Expression::Relational { fun, argument } => {
                format!("{fun:?} {}", self.canon(*argument, ids))
            }
            Expression::Math {
                fun,
                arg,
                arg1,
                arg2,
                arg3,
            } => {
                let rest: Vec<usize> = [arg1, arg2, arg3]
                    .into_iter()
                    .flatten()
                    .map(|a| self.canon(*a, ids))
                    .collect();
                format!("{fun:?} {} {rest:?}", self.canon(*arg, ids))
            }
            Expression::As {
                expr,
                kind,
                convert,
            } => format!("as {kind:?} {convert:?} {}", self.canon(*expr, ids)),
            Expression::CallResult(_) => {
                let (name, args) = self.calls[&h].clone();
                let a: Vec<usize> = args.iter().map(|a| self.canon(*a, ids)).collect();
                format!("call {name} {a:?}")
            }
            other => panic!("unexpected expression {other:?}"),
        };
        let id = ids.id(key);
        self.memo.insert(h, id);
        id
    }
}

/// A spec's functions printed in `style`, as a module naga reads.
fn source(spec: &Spec, lang: Lang, style: Style) -> String {
    let e = spec.emitted();
    let backend = lang.backend("");
    let name = |local: &str| format!("f_{local}");
    let mut s = match lang {
        Lang::Glsl => "#version 450\n#define UNITPACK_PRECISE\n".to_string(),
        _ => String::new(),
    };
    for def in unitpack::emit::struct_defs(backend.as_ref(), &e.module.funcs, &name) {
        s += &format!("{def}\n");
    }
    for f in &e.module.funcs {
        let p: Printed = print_as(backend.as_ref(), f, &name, style);
        let body = p.body.join("\n    ");
        match lang {
            Lang::Wgsl => {
                let params: Vec<String> =
                    p.params.iter().map(|(n, t)| format!("{n}: {t}")).collect();
                s += &format!(
                    "fn {}({}) -> {} {{\n    {body}\n}}\n",
                    p.name,
                    params.join(", "),
                    p.ret_ty
                );
            }
            _ => {
                let params: Vec<String> =
                    p.params.iter().map(|(n, t)| format!("{t} {n}")).collect();
                s += &format!(
                    "{} {}({}) {{\n    {body}\n}}\n",
                    p.ret_ty,
                    p.name,
                    params.join(", ")
                );
            }
        }
    }
    if lang == Lang::Glsl {
        s += "layout(local_size_x = 1) in;\nvoid main() {}\n";
    }
    s
}

fn parse(src: &str, lang: Lang) -> naga::Module {
    match lang {
        Lang::Wgsl => naga::front::wgsl::parse_str(src)
            .unwrap_or_else(|e| panic!("{}\n{src}", e.emit_to_string(src))),
        _ => naga::front::glsl::Frontend::default()
            .parse(
                &naga::front::glsl::Options::from(naga::ShaderStage::Compute),
                src,
            )
            .unwrap_or_else(|e| panic!("{}\n{src}", e.emit_to_string(src))),
    }
}

/// Each function's returned value as a canonical id.
fn returns(m: &naga::Module, ids: &mut Interner) -> Vec<(String, usize)> {
    m.functions
        .iter()
        .filter(|(_, f)| f.name.as_deref().is_some_and(|n| n.starts_with("f_")))
        .map(|(_, f)| {
            let mut g = Graph::new(m, f);
            let ret = g.ret.expect("every function returns a value");
            (f.name.clone().unwrap_or_default(), g.canon(ret, ids))
        })
        .collect()
}

#[test]
fn folding_changes_no_operation_in_any_function() {
    let mut folded_lets = 0;
    for spec in Spec::all() {
        for lang in [Lang::Wgsl, Lang::Glsl] {
            let folded = source(&spec, lang, Style::Folded);
            let flat = source(&spec, lang, Style::OneOperationPerStatement);
            let mut ids = Interner::default();
            let a = returns(&parse(&folded, lang), &mut ids);
            let b = returns(&parse(&flat, lang), &mut ids);
            assert_eq!(
                a, b,
                "{spec} in {lang}: folded\n{folded}\none operation per statement\n{flat}"
            );
            folded_lets += flat.matches(" = ").count() - folded.matches(" = ").count();
        }
    }
    // The comparison is not vacuous: folding did fold.
    assert!(folded_lets > 10_000, "{folded_lets} statements folded");
}
