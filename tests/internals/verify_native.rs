use unitpack::model::Kind;
use unitpack::model::trace::Ty;
use unitpack::verify::native::{Compiler, compile};

/// The loaded driver runs a function over every item in place, and refuses an index it
/// lacks and buffers sized for other widths before touching them.
#[test]
fn driver_runs_in_process_and_refuses_other_widths() {
    let u32_ty = Ty {
        kind: Kind::U32,
        lanes: 1,
    };
    let include =
        "#include <stdint.h>\nstatic inline uint32_t twice(uint32_t x) { return 2u * x; }\n";
    let source = unitpack::emit::lang::c::driver(include, &[("twice", vec![u32_ty], u32_ty)]);
    for compiler in [Compiler::C, Compiler::Cpp] {
        let program = compile(compiler, &source).expect("the driver compiles");
        let input: Vec<u32> = (0..10_000).collect();
        let out = program.run(0, &input, 1, 1).expect("runs");
        assert_eq!(out, input.iter().map(|x| 2 * x).collect::<Vec<_>>());
        let e = program.run(1, &input, 1, 1).unwrap_err().to_string();
        assert!(e.contains("no function 1"), "{e}");
        let e = program.run(0, &input, 1, 3).unwrap_err().to_string();
        assert!(e.contains("does not take 1 words to 3"), "{e}");
        assert!(program.run(0, &input[..3], 2, 1).is_err(), "half an item");
    }
}
