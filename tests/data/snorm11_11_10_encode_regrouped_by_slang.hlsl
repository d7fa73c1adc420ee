// tests/verify_gpu.rs: snorm11_11_10's include as it was when its exact rounding squared
// |n|·M, a product by a constant, which Slang's SPIR-V optimizer regroups (see that test).
// Every function computes bit for bit what unitpack's Rust model computes on any
// implementation with correctly rounded + - * / sqrt that keeps denormals and does not
// fuse multiply-adds (verified on Mesa lavapipe). It uses no fma, no builtin trig and no
// pack builtins.
// HLSL, Shader Model 5.0 and later, HLSL 2018 and 2021, and Slang. Under Slang, compile
// to SPIR-V with -emit-spirv-via-glsl: Slang's direct SPIR-V output drops `precise`
// (no NoContraction), so drivers may fuse a*b + c there.

// Lane-wise select: HLSL 2021 requires select() for vector conditions and Slang deprecates
// a vector ?: (it reports __HLSL_VERSION 2018); earlier HLSL has only the lane-wise ?:.
#ifndef UNITPACK_SELECT
#if defined(__SLANG_COMPILER__) || (defined(__HLSL_VERSION) && __HLSL_VERSION >= 2021)
#define UNITPACK_SELECT(c, t, f) select(c, t, f)
#else
#define UNITPACK_SELECT(c, t, f) ((c) ? (t) : (f))
#endif
#endif

// ---- snorm11_11_10: components as snorm 11, 11 and 10 bits in one word (x lowest), 32 bits ----
#ifndef UNITPACK_SNORM11_11_10_HLSL
#define UNITPACK_SNORM11_11_10_HLSL

// unitpack_snorm11_11_10_decode_float: snorm11_11_10 (components as snorm 11, 11 and 10 bits in one word (x lowest), 32 bits, sphere), decoder, float form.
// In: parameters in [-1, 1], as a snorm11, snorm11, snorm10 fetch returns them.
// Out: decode re-normalizes; the all-zero code decodes as +Z.
// Portable within a bound: on every implementation that rounds + - * to nearest and keeps the order of operations (HLSL as emitted, GLSL with its statements made precise as the include's header says, C without fast math, Metal with fast math off), whatever latitude it takes with division and square root, contraction of a*b + c, denormals and signs of zero, each output component is within 23·2^-24 (1.37e-6) of what this function computes here, for every code: a bound proven by interval evaluation (unitpack verify --portable prints it). Not where a compiler may reassociate (WGSL, GLSL without precise), on hardware that truncates, or under fast math or excess precision.
// Source: Cigolle et al. 2014 §2 and Table 1.
// Round-trip error (encode, store, decode) over a sample of 65536 seeded unit vectors (seed 0x756e69747061636b5f766563746f7273): mean 0.02938°, sample max 0.06674° (not a bound); MSE of the components of n - n' 1.063e-7, PSNR 69.73 dB.
float3 unitpack_snorm11_11_10_decode_float(float3 params) {
    precise float3 t1 = params * params;
    precise float t2 = t1.x + t1.y;
    precise float len2 = t2 + t1.z;
    bool t3 = len2 > 0.0;
    precise float t4 = t3 ? len2 : 1.0;
    precise float t5 = sqrt(t4);
    precise float3 t6 = params / t5;
    precise float3 t7 = t3 ? t6 : float3(0.0, 0.0, 1.0);
    return t7;
}

// unitpack_snorm11_11_10_decode: snorm11_11_10 (components as snorm 11, 11 and 10 bits in one word (x lowest), 32 bits, sphere), decoder.
// In: a packed code (bits 0–10: p0 snorm11 (two's complement), bits 11–21: p1 snorm11 (two's complement), bits 22–31: p2 snorm10 (two's complement)); other bits are ignored.
// Out: decode re-normalizes; the all-zero code decodes as +Z.
// Portable within a bound: on every implementation that rounds + - * to nearest and keeps the order of operations (HLSL as emitted, GLSL with its statements made precise as the include's header says, C without fast math, Metal with fast math off), whatever latitude it takes with division and square root, contraction of a*b + c, denormals and signs of zero, each output component is within 23·2^-24 (1.37e-6) of what this function computes here, for every code: a bound proven by interval evaluation (unitpack verify --portable prints it). Not where a compiler may reassociate (WGSL, GLSL without precise), on hardware that truncates, or under fast math or excess precision.
// Source: Cigolle et al. 2014 §2 and Table 1.
// Round-trip error (encode, store, decode) over a sample of 65536 seeded unit vectors (seed 0x756e69747061636b5f766563746f7273): mean 0.02938°, sample max 0.06674° (not a bound); MSE of the components of n - n' 1.063e-7, PSNR 69.73 dB.
float3 unitpack_snorm11_11_10_decode(uint code) {
    uint t1 = code & 2047u;
    uint t2 = code >> 11u;
    uint t3 = t2 & 2047u;
    uint t4 = code >> 22u;
    uint3 t5 = uint3(t1, t3, t4);
    precise float3 t6 = float3(t5);
    bool3 t7 = t6 > float3(1023.0, 1023.0, 511.0);
    precise float3 t8 = t6 - float3(2048.0, 2048.0, 1024.0);
    precise float3 t9 = UNITPACK_SELECT(t7, t8, t6);
    precise float3 t10 = t9 * float3(0.0009775171, 0.0009775171, 0.0019569471);
    bool3 t11 = t10 >= float3(-1.0, -1.0, -1.0);
    precise float3 params = UNITPACK_SELECT(t11, t10, float3(-1.0, -1.0, -1.0));
    precise float3 t12 = unitpack_snorm11_11_10_decode_float(params);
    return t12;
}

// unitpack_snorm11_11_10_encode_float: snorm11_11_10 (components as snorm 11, 11 and 10 bits in one word (x lowest), 32 bits, sphere), fast encoder, float form.
// In: any vector; input is normalized first; zero, NaN and infinite input encode as +Z.
// Out: parameters in [-1, 1], unquantized, for a snorm11, snorm11, snorm10 render target or vertex format to round.
// Not bit-portable: other implementations may return other floats here (unitpack verify --portable measures how far); the packed encoder is the portable form.
// Source: Cigolle et al. 2014 §2 and Table 1.
// Round-trip error (encode, store, decode) over a sample of 65536 seeded unit vectors (seed 0x756e69747061636b5f766563746f7273): mean 0.02938°, sample max 0.06674° (not a bound); MSE of the components of n - n' 1.063e-7, PSNR 69.73 dB.
float3 unitpack_snorm11_11_10_encode_float(float3 v) {
    precise float3 t1 = abs(v);
    bool t2 = t1.x >= t1.y;
    precise float t3 = t2 ? t1.x : t1.y;
    bool t4 = t3 >= t1.z;
    precise float largest = t4 ? t3 : t1.z;
    bool t5 = largest > 0.0;
    bool t6 = largest <= 3.4028235e38;
    bool t7 = t5 && t6;
    precise float t8 = t7 ? largest : 1.0;
    precise float3 scaled = v / t8;
    precise float3 t9 = scaled * scaled;
    precise float t10 = t9.x + t9.y;
    precise float len2 = t10 + t9.z;
    bool t11 = len2 >= 1.0;
    bool t12 = t7 && t11;
    precise float t13 = sqrt(len2);
    precise float3 t14 = scaled / t13;
    precise float3 t15 = t12 ? t14 : float3(0.0, 0.0, 1.0);
    return t15;
}

// The nearest integer codes (as floats; bytes of them for the rgb8 layout), each decided by comparing correctly rounded products, never a quotient or a root, so division and square root error, contraction, denormal flushing and lost signs of zero cannot change them.
float3 unitpack_snorm11_11_10_round_codes(float3 a0) {
    precise float3 t1 = abs(a0);
    bool3 t2 = t1 < float3(1.1754944e-38, 1.1754944e-38, 1.1754944e-38);
    precise float3 normal = UNITPACK_SELECT(t2, float3(0.0, 0.0, 0.0), a0);
    precise float3 t3 = abs(normal);
    bool t4 = t3.x >= t3.y;
    precise float t5 = t4 ? t3.x : t3.y;
    bool t6 = t5 >= t3.z;
    precise float largest = t6 ? t5 : t3.z;
    uint t7 = asuint(largest);
    uint t8 = t7 & 2139095040u;
    uint t9 = 2139095040u - t8;
    precise float scale = asfloat(t9);
    precise float3 scaled = normal * scale;
    precise float3 t10 = abs(scaled);
    precise float t11 = t10.x + t10.y;
    precise float sum = t11 + t10.z;
    bool t12 = sum >= 2.0;
    bool t13 = sum < 16.0;
    bool t14 = t12 && t13;
    precise float3 t15 = abs(scaled);
    bool3 t16 = t15 < float3(1.8189894e-12, 1.8189894e-12, 1.8189894e-12);
    precise float3 w = UNITPACK_SELECT(t16, float3(0.0, 0.0, 0.0), scaled);
    uint t17 = asuint(w.x);
    uint t18 = t17 & 4294963200u;
    precise float t19 = asfloat(t18);
    precise float t20 = w.x - t19;
    precise float t21 = t19 * t19;
    precise float t22 = t19 + t19;
    precise float t23 = t22 * t20;
    precise float t24 = t20 * t20;
    uint t25 = asuint(w.y);
    uint t26 = t25 & 4294963200u;
    precise float t27 = asfloat(t26);
    precise float t28 = w.y - t27;
    precise float t29 = t27 * t27;
    precise float t30 = t27 + t27;
    precise float t31 = t30 * t28;
    precise float t32 = t28 * t28;
    uint t33 = asuint(w.z);
    uint t34 = t33 & 4294963200u;
    precise float t35 = asfloat(t34);
    precise float t36 = w.z - t35;
    precise float t37 = t35 * t35;
    precise float t38 = t35 + t35;
    precise float t39 = t38 * t36;
    precise float t40 = t36 * t36;
    precise float t41 = t21 + t29;
    precise float t42 = t41 + t37;
    precise float t43 = t23 + t31;
    precise float t44 = t43 + t39;
    precise float t45 = t24 + t32;
    precise float t46 = t45 + t40;
    precise float t47 = t42 + t44;
    precise float len2 = t47 + t46;
    precise float t48 = abs(w.x);
    precise float t49 = sqrt(len2);
    precise float t50 = t48 / t49;
    precise float t51 = t50 * 1023.0;
    precise float t52 = round(t51);
    precise float t53 = t48 * 1023.0;
    precise float t54 = t53 * t53;
    precise float t55 = t52 - 0.5;
    bool t56 = t52 > 0.0;
    precise float t57 = t55 * t55;
    precise float t58 = t57 * len2;
    bool t59 = t54 < t58;
    bool t60 = t56 && t59;
    precise float t61 = abs(w.y);
    precise float t62 = sqrt(len2);
    precise float t63 = t61 / t62;
    precise float t64 = t63 * 1023.0;
    precise float t65 = round(t64);
    precise float t66 = t61 * 1023.0;
    precise float t67 = t66 * t66;
    precise float t68 = t65 - 0.5;
    bool t69 = t65 > 0.0;
    precise float t70 = t68 * t68;
    precise float t71 = t70 * len2;
    bool t72 = t67 < t71;
    bool t73 = t69 && t72;
    precise float t74 = abs(w.z);
    precise float t75 = sqrt(len2);
    precise float t76 = t74 / t75;
    precise float t77 = t76 * 511.0;
    precise float t78 = round(t77);
    precise float t79 = t74 * 511.0;
    precise float t80 = t79 * t79;
    precise float t81 = t78 - 0.5;
    bool t82 = t78 > 0.0;
    precise float t83 = t81 * t81;
    precise float t84 = t83 * len2;
    bool t85 = t80 < t84;
    bool t86 = t82 && t85;
    bool3 t87 = w < float3(0.0, 0.0, 0.0);
    precise float3 t88 = abs(w);
    precise float3 t89 = float3(len2, len2, len2);
    precise float3 t90 = sqrt(t89);
    precise float3 t91 = t88 / t90;
    precise float3 t92 = t91 * float3(1023.0, 1023.0, 511.0);
    precise float3 t93 = round(t92);
    precise float3 t94 = t88 * float3(1023.0, 1023.0, 511.0);
    precise float3 t95 = t94 * t94;
    precise float3 t96 = t93 + 0.5;
    precise float3 t97 = t96 * t96;
    precise float3 t98 = t97 * len2;
    bool3 t99 = t95 >= t98;
    bool3 t100 = bool3(t60, t73, t86);
    precise float3 t101 = UNITPACK_SELECT(t100, float3(-1.0, -1.0, -1.0), float3(0.0, 0.0, 0.0));
    precise float3 t102 = UNITPACK_SELECT(t99, float3(1.0, 1.0, 1.0), t101);
    precise float3 t103 = t93 + t102;
    bool3 t104 = t103 >= float3(0.0, 0.0, 0.0);
    precise float3 t105 = UNITPACK_SELECT(t104, t103, float3(0.0, 0.0, 0.0));
    bool3 t106 = t105 <= float3(1023.0, 1023.0, 511.0);
    precise float3 t107 = UNITPACK_SELECT(t106, t105, float3(1023.0, 1023.0, 511.0));
    precise float3 t108 = -t107;
    precise float3 t109 = UNITPACK_SELECT(t87, t108, t107);
    precise float3 t110 = t14 ? t109 : float3(0.0, 0.0, 511.0);
    return t110;
}

// unitpack_snorm11_11_10_encode: snorm11_11_10 (components as snorm 11, 11 and 10 bits in one word (x lowest), 32 bits, sphere), fast encoder.
// In: any vector; input is normalized first; zero, NaN and infinite input encode as +Z.
// Out: the packed code, uint (bits 0–10: p0 snorm11 (two's complement), bits 11–21: p1 snorm11 (two's complement), bits 22–31: p2 snorm10 (two's complement)).
// Portable: the same code on every implementation that rounds + - * to nearest and keeps the order of operations (HLSL as emitted, GLSL with its statements made precise as the include's header says, C without fast math, Metal with fast math off), whatever latitude it takes with division and square root (within their ULP bounds), contraction of a*b + c, denormals and signs of zero; denormal input components count as zero. Not where a compiler may reassociate (WGSL, GLSL without precise), on hardware that truncates, or under fast math or excess precision.
// Source: Cigolle et al. 2014 §2 and Table 1.
// Round-trip error (encode, store, decode) over a sample of 65536 seeded unit vectors (seed 0x756e69747061636b5f766563746f7273): mean 0.02938°, sample max 0.06674° (not a bound); MSE of the components of n - n' 1.063e-7, PSNR 69.73 dB.
uint unitpack_snorm11_11_10_encode(float3 v) {
    precise float3 t1 = unitpack_snorm11_11_10_round_codes(v);
    precise float t2 = t1.x + 2048.0;
    uint t3 = uint(t2);
    uint t4 = t3 & 2047u;
    precise float t5 = t1.y + 2048.0;
    uint t6 = uint(t5);
    uint t7 = t6 << 11u;
    uint t8 = t7 & 4192256u;
    uint t9 = t4 | t8;
    precise float t10 = t1.z + 1024.0;
    uint t11 = uint(t10);
    uint t12 = t11 << 22u;
    uint t13 = t9 | t12;
    return t13;
}

#endif // UNITPACK_SNORM11_11_10_HLSL
