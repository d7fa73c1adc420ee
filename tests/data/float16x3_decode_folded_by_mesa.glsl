// float16x3's decoders as unitpack emitted them before they decided NaN and infinity on
// the bits: their float comparisons are what Mesa's GLSL compiler folds without precise
// (tests/verify_gl.rs).
#ifndef UNITPACK_PRECISE
#define UNITPACK_PRECISE
#endif
vec3 unitpack_float16x3_decode_float(vec3 params) {
    UNITPACK_PRECISE float t1 = abs(params.x);
    bool t2 = t1 <= 3.4028235e38;
    UNITPACK_PRECISE float t3 = abs(params.y);
    bool t4 = t3 <= 3.4028235e38;
    bool t5 = t2 && t4;
    UNITPACK_PRECISE float t6 = abs(params.z);
    bool t7 = t6 <= 3.4028235e38;
    bool t8 = t5 && t7;
    UNITPACK_PRECISE float t9 = abs(params.x);
    bool t10 = t9 > 0.0;
    UNITPACK_PRECISE float t11 = abs(params.y);
    bool t12 = t11 > 0.0;
    bool t13 = t10 || t12;
    UNITPACK_PRECISE float t14 = abs(params.z);
    bool t15 = t14 > 0.0;
    bool t16 = t13 || t15;
    bool t17 = t8 && t16;
    UNITPACK_PRECISE vec3 t18 = t17 ? params : vec3(0.0, 0.0, 1.0);
    return t18;
}

vec3 unitpack_float16x3_decode(uvec2 code) {
    uint t1 = code.x & 65535u;
    uint t2 = t1 & 32768u;
    uint t3 = t2 << 16u;
    uint t4 = t1 & 32767u;
    uint t5 = t4 << 13u;
    uint t6 = code.x >> 16u;
    uint t7 = t6 & 32768u;
    uint t8 = t7 << 16u;
    uint t9 = t6 & 32767u;
    uint t10 = t9 << 13u;
    uint t11 = code.y & 65535u;
    uint t12 = t11 & 32768u;
    uint t13 = t12 << 16u;
    uint t14 = t11 & 32767u;
    uint t15 = t14 << 13u;
    uvec3 t16 = uvec3(t1, t6, t11);
    uvec3 t17 = t16 & uvec3(32767u);
    bvec3 t18 = lessThan(t17, uvec3(31744u));
    bvec3 t19 = lessThan(t17, uvec3(1024u));
    UNITPACK_PRECISE vec3 t20 = vec3(t17);
    UNITPACK_PRECISE vec3 t21 = t20 * 5.9604645e-8;
    uvec3 t22 = floatBitsToUint(t21);
    uvec3 t23 = uvec3(t5, t10, t15);
    uvec3 t24 = t23 + 939524096u;
    uvec3 t25 = uvec3(t19.x ? t22.x : t24.x, t19.y ? t22.y : t24.y, t19.z ? t22.z : t24.z);
    uvec3 t26 = t23 | uvec3(2139095040u);
    uvec3 t27 = uvec3(t18.x ? t25.x : t26.x, t18.y ? t25.y : t26.y, t18.z ? t25.z : t26.z);
    uvec3 t28 = uvec3(t3, t8, t13);
    uvec3 t29 = t27 | t28;
    UNITPACK_PRECISE vec3 params = uintBitsToFloat(t29);
    UNITPACK_PRECISE vec3 t30 = unitpack_float16x3_decode_float(params);
    return t30;
}

