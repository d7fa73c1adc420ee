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
    let source = unitpack::emit::lang::c::driver(
        include,
        &[(
            "twice",
            vec![u32_ty],
            unitpack::emit::lang::Returns::one(u32_ty),
        )],
    );
    for compiler in [Compiler::C, Compiler::Cpp] {
        let program = compile(compiler, &source).expect("the driver compiles");
        let input: Vec<u32> = (0..10_000).collect();
        let mut out = vec![0u32; 10_000];
        program.run(0, &input, 1, 1, &mut out).expect("runs");
        assert_eq!(out, input.iter().map(|x| 2 * x).collect::<Vec<_>>());
        let e = program
            .run(1, &input, 1, 1, &mut out)
            .unwrap_err()
            .to_string();
        assert!(e.contains("no function 1"), "{e}");
        let mut wide = vec![0u32; 30_000];
        let e = program
            .run(0, &input, 1, 3, &mut wide)
            .unwrap_err()
            .to_string();
        assert!(e.contains("does not take 1 words to 3"), "{e}");
        let e = program
            .run(0, &input, 1, 3, &mut out)
            .unwrap_err()
            .to_string();
        assert!(e.contains("room for 10000 output words"), "{e}");
        assert!(
            program.run(0, &input[..3], 2, 1, &mut out).is_err(),
            "half an item"
        );
    }
}
