// gltf-transform's quantize() on the vectors read from stdin: little-endian f32 items of
// 3 (NORMAL) or 4 (TANGENT) components in, the quantized accessor's integers out
// (Int8 or Int16, little-endian), as tests/families/gltf.rs compares them.
// Usage: node quantize.mjs BITS NORMAL|TANGENT < floats > integers
import { Document } from '@gltf-transform/core';
import { quantize } from '@gltf-transform/functions';

const bits = Number(process.argv[2]);
const semantic = process.argv[3];
const size = semantic === 'TANGENT' ? 4 : 3;
const chunks = [];
for await (const chunk of process.stdin) chunks.push(chunk);
const bytes = Buffer.concat(chunks);
const values = new Float32Array(bytes.byteLength / 4);
new Uint8Array(values.buffer).set(bytes);

const doc = new Document();
const buffer = doc.createBuffer();
const type = size === 4 ? 'VEC4' : 'VEC3';
const vectors = doc.createAccessor().setType(type).setArray(values).setBuffer(buffer);
const count = values.length / size;
const position = doc.createAccessor().setType('VEC3').setArray(new Float32Array(count * 3)).setBuffer(buffer);
const prim = doc.createPrimitive().setAttribute('POSITION', position).setAttribute(semantic, vectors);
doc.createMesh().addPrimitive(prim);
await doc.transform(quantize({ pattern: new RegExp(`^${semantic}$`), quantizeNormal: bits, cleanup: false }));
const out = prim.getAttribute(semantic).getArray();
process.stdout.write(Buffer.from(out.buffer, out.byteOffset, out.byteLength));
