// Rebuilds a csgray part's CSG tree (bench/csg_to_manifold) with Manifold and writes its mesh as a
// binary STL, for bench/peer_export.sh and bench/export_sweep.sh. Leaves: hulls, meshes and
// untwisted linear extrusions (Manifold.extrude of the outline's contours).
//   node export.mjs TREE.json OUT.stl
// Prints one JSON line: the seconds from the first leaf to the final mesh (Manifold evaluates
// its booleans lazily, so that is leaves, booleans and getMesh together), and the triangles and
// vertices of the result. WebAssembly, one thread.
import { readFileSync, writeFileSync } from 'node:fs';
import Module from 'manifold-3d';

const [treeFile, outFile] = process.argv.slice(2);
if (!treeFile || !outFile) {
  console.error('usage: node export.mjs TREE.json OUT.stl');
  process.exit(2);
}
const wasm = await Module();
wasm.setup();
const { Manifold, Mesh, CrossSection } = wasm;

const tree = JSON.parse(readFileSync(treeFile, 'utf8'));

function triples(flat) {
  const out = [];
  for (let i = 0; i < flat.length; i += 3) out.push([flat[i], flat[i + 1], flat[i + 2]]);
  return out;
}

function build(node) {
  if (node.empty) return new Manifold(new Mesh({ numProp: 3, vertProperties: new Float32Array(), triVerts: new Uint32Array() }));
  if (node.hull) return Manifold.hull(triples(node.hull));
  if (node.extrude) {
    // An untwisted linear_extrude: its contours as [x, y] pairs, extruded from z = 0 and placed
    // by the leaf's matrix (column-major, bottom at its z0).
    const e = node.extrude;
    const contours = e.contours.map((flat) => {
      const out = [];
      for (let i = 0; i < flat.length; i += 2) out.push([flat[i], flat[i + 1]]);
      return out;
    });
    const section = new CrossSection(contours, e.rule);
    return Manifold.extrude(section, e.height, 0, 0, e.scale).transform(node.m);
  }
  if (node.mesh) {
    const mesh = new Mesh({
      numProp: 3,
      vertProperties: new Float32Array(node.mesh.v),
      triVerts: new Uint32Array(node.mesh.t),
    });
    mesh.merge();
    return new Manifold(mesh);
  }
  const a = build(node.a), b = build(node.b);
  if (node.op === 'union') return a.add(b);
  if (node.op === 'intersection') return a.intersect(b);
  return a.subtract(b);
}

const start = performance.now();
const result = build(tree);
const mesh = result.getMesh();
const seconds = (performance.now() - start) / 1000;

// Binary STL: an 80-byte header, the count, then 50 bytes per facet.
const numTri = mesh.triVerts.length / 3, stride = mesh.numProp;
const bytes = Buffer.alloc(84 + 50 * numTri);
bytes.write('manifold-3d via csgray bench/manifold/export.mjs', 0);
bytes.writeUInt32LE(numTri, 80);
for (let t = 0; t < numTri; ++t) {
  const base = 84 + 50 * t;
  const p = [0, 1, 2].map((k) => {
    const v = mesh.triVerts[3 * t + k];
    return [mesh.vertProperties[stride * v], mesh.vertProperties[stride * v + 1], mesh.vertProperties[stride * v + 2]];
  });
  const u = [p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]];
  const w = [p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]];
  const n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]];
  const length = Math.hypot(n[0], n[1], n[2]) || 1;
  [n[0] / length, n[1] / length, n[2] / length, ...p.flat()].forEach((x, i) => bytes.writeFloatLE(x, base + 4 * i));
}
writeFileSync(outFile, bytes);
console.log(JSON.stringify({ seconds, triangles: numTri, vertices: mesh.vertProperties.length / stride }));
