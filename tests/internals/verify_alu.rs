use unitpack::codecs::Spec;
use unitpack::verify::alu::*;

#[test]
fn counts_the_alu_opcodes_of_main_only() {
    let dis = "OpEntryPoint GLCompute %main \"main\"\n\
               %f = OpFunction %v None %t\n%1 = OpFAdd %float %a %b\nOpFunctionEnd\n\
               %main = OpFunction %void None %fn\n%2 = OpLoad %float %p\n\
               %3 = OpFMul %float %2 %2\n%4 = OpSelect %float %c %3 %2\n\
               OpStore %q %4\nOpReturn\nOpFunctionEnd\n";
    assert_eq!(count_main(dis).unwrap(), 2);
}

/// The counts the README's "What portability costs" table gives for oct16, measured
/// by the same method outside the crate.
#[test]
fn oct16_counts_as_measured_by_hand() {
    let spec: Spec = "oct16".parse().unwrap();
    let got: Vec<u32> = ["encode", "encode_float", "decode", "decode_float"]
        .iter()
        .map(|f| count(&spec, f).unwrap())
        .collect();
    assert_eq!(got, [56, 23, 24, 15]);
}
