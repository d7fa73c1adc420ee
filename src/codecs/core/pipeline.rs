//! The encode/decode pipeline every codec shares, from its parameters to packed codes
//! and back, and the four functions of a codec spec traced and evaluated from it.

use crate::codecs::core::codec::{Codec, Params, dequantize, pack, unpack};
use crate::codecs::core::spec::Spec;
use crate::codecs::functions::decode_boxes::{fetched_range, field_codes};
use crate::codecs::functions::function::{
    BoxEval, Emitted, Enclose, Eval, Function, Inputs, LanesEval, Role, WordsMap,
};
use crate::codecs::functions::words::{
    Bits, Declared, Lanes, Lanes8, Tracer, chained, declared, generic_function, trace_declared,
    tracer,
};
use crate::model::Float;
use crate::model::V3;
use crate::model::avx2_lanes::F8;
use crate::model::deviant::Dev;
use crate::model::enclosure::Encl;
use crate::model::lanes::F4;
use crate::model::num::helper;
use std::sync::Arc;

/// The four functions of a codec spec (`decode_float`, `decode`, `encode_float`,
/// `encode`), each declared once ([`declared!`]): traced and evaluated by the same generic
/// code.
pub(crate) fn codec_functions<C: Codec + Clone + 'static>(spec: &Spec, c: C) -> Emitted
where
    C::P<f32>: Bits,
    C::C<f32>: Bits,
    C::P<Dev>: Bits,
    C::C<Dev>: Bits,
    C::P<F4>: Bits<Lanes>,
    C::C<F4>: Bits<Lanes>,
    C::P<F8>: Bits<Lanes8>,
    C::C<F8>: Bits<Lanes8>,
{
    let precise = spec.precise();
    // Decoders first, so that encoders calling them find them with their parameter names.
    let mut functions = codec_decoders(&c);
    if precise {
        functions.extend(precise_encoders(&c));
    } else {
        functions.extend([
            declared!(
                "encode_float",
                Role::EncodeFloat,
                Inputs::Vectors,
                ["v"],
                <F> [c] |v: V3<F>| encode_float(&c, false, v)
            ),
            declared!(
                "encode",
                Role::Encode,
                Inputs::Vectors,
                ["v"],
                <F> [c] |v: V3<F>| encode_packed(&c, false, v)
            ),
        ]);
        if let Some(name) = c.alternate() {
            functions.push(declared!(
                name,
                Role::Encode,
                Inputs::Vectors,
                ["v"],
                <F> [c] |v: V3<F>| encode_alternate(&c, false, v)
            ));
        }
    }
    let (module, functions) = trace_declared(functions);
    Emitted {
        module,
        functions,
        namespace: spec.id(),
        portable_encoder: if precise {
            C::EXACT_SEARCH
        } else {
            C::EXACT_ROUNDING
        },
        cpu: Vec::new(),
    }
}

/// A precise spec's `encode_float`, `encode` and alternate encoder: the search
/// ([`Codec::precise_codes`]) chained with the cheap step each makes of its codes
/// ([`chained`]), which is bit for bit [`encode_float`], [`encode_packed`] and
/// [`encode_alternate`] with `precise` set, the bodies they are traced by. The search,
/// the costliest body of the catalogue, is then compiled once per spec rather than once
/// per encoder, and `verify` runs it once for the three; the include defines it as
/// `encode_codes`, which the three call.
fn precise_encoders<C: Codec + Clone + 'static>(c: &C) -> Vec<Declared>
where
    C::P<f32>: Bits,
    C::C<f32>: Bits,
    C::P<Dev>: Bits,
    C::C<Dev>: Bits,
    C::P<F4>: Bits<Lanes>,
    C::C<F4>: Bits<Lanes>,
    C::P<F8>: Bits<Lanes8>,
    C::C<F8>: Bits<Lanes8>,
{
    let (search, traced_search) = declared!(
        "encode_codes",
        Role::Encode,
        Inputs::Vectors,
        ["v"],
        <F> [c] |v: V3<F>| c.precise_codes(v)
    )
    .unlisted();
    let step = |name, role, then: Function, trace: Tracer| {
        Declared::new(chained(name, role, Inputs::Vectors, &search, &then), trace)
    };
    let mut functions = vec![
        traced_search,
        step(
            "encode_float",
            Role::EncodeFloat,
            generic_function!(
                "dequantize",
                Role::EncodeFloat,
                Inputs::Vectors,
                <F> [c] |p: C::P<F>| dequantize(&c.quants(), p)
            ),
            tracer!(["v"], <F> [c] |v: V3<F>| encode_float(&c, true, v)),
        ),
        step(
            "encode",
            Role::Encode,
            generic_function!(
                "pack",
                Role::Encode,
                Inputs::Vectors,
                <F> [c] |p: C::P<F>| pack::<F, C::P<F>, C::C<F>>(&c.quants(), p)
            ),
            tracer!(["v"], <F> [c] |v: V3<F>| encode_packed(&c, true, v)),
        ),
    ];
    if let Some(name) = c.alternate() {
        functions.push(step(
            name,
            Role::Encode,
            generic_function!(
                "pack_alternate",
                Role::Encode,
                Inputs::Vectors,
                <F> [c] |p: C::P<F>| pack::<F, C::P<F>, C::C<F>>(&c.quants(), c.alternate_codes(p))
            ),
            tracer!(["v"], <F> [c] |v: V3<F>| encode_alternate(&c, true, v)),
        ));
    }
    functions
}

/// A codec's `decode_float` and `decode`, with the enclosures their bounds are proven
/// by: what a spec whose encoders are its own (a table codec) shares with the codec
/// whose texels it writes.
pub(crate) fn codec_decoders<C: Codec + Clone + 'static>(c: &C) -> Vec<Declared>
where
    C::P<f32>: Bits,
    C::C<f32>: Bits,
    C::P<Dev>: Bits,
    C::C<Dev>: Bits,
    C::P<F4>: Bits<Lanes>,
    C::C<F4>: Bits<Lanes>,
    C::P<F8>: Bits<Lanes8>,
    C::C<F8>: Bits<Lanes8>,
{
    let q = c.quants();
    let fetch_box = {
        let c = c.clone();
        move |r: &[(i64, i64)]| {
            let p = C::P::<Encl>::build(
                #[inline(always)]
                |i| fetched_range(q[i], r[i]),
            );
            c.direction(p).to_array().to_vec()
        }
    };
    let field_box = {
        let c = c.clone();
        move |r: &[(i64, i64)]| {
            let codes = C::P::<Encl>::build(
                #[inline(always)]
                |i| field_codes(q[i], r[i]),
            );
            c.decode_codes(codes).to_array().to_vec()
        }
    };
    let c = c.clone();
    let mut functions = vec![
        declared!(
            "decode_float",
            Role::DecodeFloat,
            Inputs::FloatCodes(q.to_vec()),
            ["params"],
            <F> [c] |p: C::P<F>| c.direction(p)
        ),
        declared!(
            "decode",
            Role::Decode,
            Inputs::Codes(q.to_vec()),
            ["code"],
            <F> [c] |code: C::C<F>| decode_packed(&c, code)
        ),
    ];
    let whole_field = c.whole_field();
    let unread = c.unread_fields();
    let fixed = c.fixed_fields();
    if let Some(parts) = c.proof_parts() {
        // Both decoders reach the parts exactly (the float form re-quantizes each fetched
        // `c/M` exactly, and the split is integer operations): one proof over the parts
        // covers every code of each.
        let eval: BoxEval = Arc::new(move |r: &[(i64, i64)]| {
            let p: Vec<Encl> = r
                .iter()
                .map(|&(a, b)| Encl::range(a as f64, b as f64, 1.0))
                .collect();
            c.parts_direction(&p).to_array().to_vec()
        });
        for f in &mut functions {
            f.function_mut().enclose = Some(Enclose {
                eval: eval.clone(),
                whole_field: None,
                unread: &[],
                fixed: Vec::new(),
                budget: None,
                parts: Some(parts.clone()),
            });
        }
        return functions;
    }
    functions[0].function_mut().enclose = Some(Enclose {
        eval: Arc::new(fetch_box),
        whole_field,
        unread,
        fixed: fixed.clone(),
        budget: None,
        parts: None,
    });
    functions[1].function_mut().enclose = Some(Enclose {
        eval: Arc::new(field_box),
        whole_field,
        unread,
        fixed,
        budget: None,
        parts: None,
    });
    functions
}

/// How [`through_table`] chains two lane evaluations around a lookup.
struct Chain {
    iw: usize,
    mid: usize,
    second_in: usize,
    keep_input: bool,
    lookup: WordsMap,
}

impl Chain {
    /// `a` on the items, the lookup item by item, then `b`: each part on its lanes.
    fn chain(&self, a: &LanesEval, b: &LanesEval) -> LanesEval {
        let (a, b, lookup) = (a.clone(), b.clone(), self.lookup.clone());
        let Chain {
            iw,
            mid,
            second_in,
            keep_input,
            ..
        } = *self;
        Arc::new(move |i: &[u32], o: &mut [u32]| {
            let n = i.len() / iw;
            let mut t = vec![0u32; n * mid];
            a(i, &mut t);
            let mut arg = Vec::with_capacity(n * second_in);
            for (item, t) in i.chunks_exact(iw).zip(t.chunks_exact(mid)) {
                if keep_input {
                    arg.extend_from_slice(item);
                }
                arg.extend(lookup(t));
            }
            assert_eq!(arg.len(), n * second_in, "the lookup's words");
            b(&arg, o)
        })
    }
}

/// A CPU-only function through a table in memory: `first`, then `lookup` of its
/// output words (one item's), then `second` on the lookup's words, after the item's own
/// input words where `keep_input`. Each evaluation (`f32`, [`Dev`], four lanes) chains
/// the parts' own, so it is bit for bit the emitted functions around a fetch that
/// returns what `lookup` does.
pub fn through_table(
    name: &'static str,
    role: Role,
    inputs: Inputs,
    first: &Function,
    lookup: WordsMap,
    second: &Function,
    keep_input: bool,
) -> Function {
    let (iw, mid) = (first.in_words, first.out_words);
    let kept = if keep_input { iw } else { 0 };
    assert!(
        second.in_words > kept,
        "{name}: {} takes {} words, fewer than the kept input and a lookup",
        second.name,
        second.in_words
    );
    let want = second.in_words;
    let chain = |a: &Eval, b: &Eval| -> Eval {
        let (a, b, lookup) = (a.clone(), b.clone(), lookup.clone());
        Arc::new(move |i: &[u32], o: &mut [u32]| {
            let mut t = vec![0u32; mid];
            a(i, &mut t);
            // A caller's item may sit in a longer buffer: keep its own words only.
            let mut arg = if keep_input {
                i[..iw].to_vec()
            } else {
                Vec::new()
            };
            arg.extend(lookup(&t));
            assert_eq!(arg.len(), want, "the lookup's words and the kept input");
            b(&arg, o)
        })
    };
    let lanes = Chain {
        iw,
        mid,
        second_in: second.in_words,
        keep_input,
        lookup: lookup.clone(),
    };
    Function {
        name,
        role,
        inputs,
        in_words: iw,
        out_words: second.out_words,
        eval: chain(&first.eval, &second.eval),
        eval_dev: chain(&first.eval_dev, &second.eval_dev),
        eval_lanes: lanes.chain(&first.eval_lanes, &second.eval_lanes),
        eval_lanes8: lanes.chain(&first.eval_lanes8, &second.eval_lanes8),
        enclose: None,
        parts: vec![first.name, second.name],
        stages: None,
    }
}

/// The packed decoder: unpack, then [`Codec::decode_codes`].
#[inline(always)]
pub fn decode_packed<F: Float, C: Codec>(c: &C, code: C::C<F>) -> V3<F> {
    c.decode_codes(unpack(&c.quants(), code))
}

/// Integer codes of an encoder: the precise search (through the `encode_codes` helper),
/// or the nearest codes of the `encode_float` helper's parameters.
#[inline(always)]
fn codes_of<F: Float, C: Codec>(c: &C, precise: bool, v: V3<F>) -> C::P<F> {
    if precise {
        helper!("encode_codes" => c.precise_codes(v))
    } else if C::EXACT_ROUNDING {
        helper!(c.round_codes(v))
    } else {
        c.round_codes(v)
    }
}

/// The packed encoder.
#[inline(always)]
pub fn encode_packed<F: Float, C: Codec>(c: &C, precise: bool, v: V3<F>) -> C::C<F> {
    pack(&c.quants(), codes_of(c, precise, v))
}

/// The packed [`Codec::alternate`] encoder.
#[inline(always)]
pub fn encode_alternate<F: Float, C: Codec>(c: &C, precise: bool, v: V3<F>) -> C::C<F> {
    pack(&c.quants(), c.alternate_codes(codes_of(c, precise, v)))
}

/// Float-form encoder output: the exact parameters for the hardware to round (fast), or
/// the chosen codes' values (precise), which the hardware's rounding keeps.
#[inline(always)]
pub fn encode_float<F: Float, C: Codec>(c: &C, precise: bool, v: V3<F>) -> C::P<F> {
    if precise {
        dequantize(&c.quants(), helper!("encode_codes" => c.precise_codes(v)))
    } else {
        c.params(v)
    }
}
