// Writes scenes/bunny.obj from the npm package `bunny` (Mikola Lysenko's packaging of the Stanford
// bunny, public domain; the scan is from the Stanford 3D Scanning Repository,
// http://graphics.stanford.edu/data/3Dscanrep/). Run once; the OBJ is committed:
//   (cd /tmp && npm install bunny) && node tools/bunny_to_obj.mjs /tmp/node_modules/bunny scenes/bunny.obj
// The faces are wound so that their fronts face out, and each vertex gets the area-weighted mean of
// its faces' normals, for smooth shading.
import { createRequire } from "module";
import { writeFileSync } from "fs";
import { resolve } from "path";

const [packageDir, output] = process.argv.slice(2);
if (!packageDir || !output) {
  console.error("usage: node tools/bunny_to_obj.mjs <bunny package folder> <output.obj>");
  process.exit(2);
}
const { positions, cells } = createRequire(import.meta.url)(resolve(packageDir));

const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];

// Outward winding: the signed volume the faces enclose is positive.
let volume = 0;
for (const [i, j, k] of cells) volume += dot(positions[i], cross(positions[j], positions[k])) / 6;
const faces = volume >= 0 ? cells : cells.map(([i, j, k]) => [i, k, j]);

const normals = positions.map(() => [0, 0, 0]);
for (const [i, j, k] of faces) {
  const n = cross(sub(positions[j], positions[i]), sub(positions[k], positions[i]));  // twice the area
  for (const v of [i, j, k]) for (let c = 0; c < 3; c++) normals[v][c] += n[c];
}

const fmt = (x) => Number(x.toFixed(6)).toString();
const lines = [
  "# The Stanford bunny (Stanford 3D Scanning Repository, http://graphics.stanford.edu/data/3Dscanrep/),",
  "# from the npm package bunny 1.0.1 (public domain), by tools/bunny_to_obj.mjs.",
  `# ${positions.length} vertices, ${faces.length} triangles, wound outwards, with vertex normals.`,
];
for (const p of positions) lines.push(`v ${p.map(fmt).join(" ")}`);
for (const n of normals) {
  const l = Math.hypot(...n) || 1;
  lines.push(`vn ${n.map((x) => fmt(x / l)).join(" ")}`);
}
for (const f of faces) lines.push(`f ${f.map((v) => `${v + 1}//${v + 1}`).join(" ")}`);
writeFileSync(output, lines.join("\n") + "\n");
console.log(`${output}: ${positions.length} vertices, ${faces.length} triangles (signed volume ${volume.toFixed(3)})`);
