// OBJ -> a non-indexed triangle list in the file's face order (as ShadeLab draws it): positions
// and normals, 3 floats per corner. Polygons become fans; a corner with no normal (or a zero one)
// takes the area-weighted normal of its position, as the server's reader does
// (server/scene/obj_reader.h); the others keep the file's.
export function parseObj(text) {
  const v = [], vn = [];
  const pos = [], nrm = [];
  let missingNormals = false;
  const index = (token, list) => {
    const i = parseInt(token, 10);
    return i < 0 ? list.length / 3 + i : i - 1;
  };
  for (const raw of text.split("\n")) {
    const line = raw.trim();
    if (line.startsWith("v ")) v.push(...line.slice(2).trim().split(/\s+/).slice(0, 3).map(Number));
    else if (line.startsWith("vn ")) vn.push(...line.slice(3).trim().split(/\s+/).slice(0, 3).map(Number));
    else if (line.startsWith("f ")) {
      const corners = line.slice(2).trim().split(/\s+/).map((c) => c.split("/"));
      for (let k = 1; k + 1 < corners.length; ++k) {
        for (const c of [corners[0], corners[k], corners[k + 1]]) {
          const p = index(c[0], v);
          pos.push(v[3 * p], v[3 * p + 1], v[3 * p + 2]);
          if (c[2]) {
            const n = index(c[2], vn);
            nrm.push(vn[3 * n], vn[3 * n + 1], vn[3 * n + 2]);
          } else {
            missingNormals = true;
            nrm.push(0, 0, 0);
          }
        }
      }
    }
  }
  if (missingNormals) smoothNormals(pos, nrm);
  return { positions: new Float32Array(pos), normals: new Float32Array(nrm), triangles: pos.length / 9 };
}

function smoothNormals(pos, nrm) {
  const sums = new Map();
  const key = (i) => `${pos[i]},${pos[i + 1]},${pos[i + 2]}`;
  for (let t = 0; t < pos.length; t += 9) {
    const e1 = [pos[t + 3] - pos[t], pos[t + 4] - pos[t + 1], pos[t + 5] - pos[t + 2]];
    const e2 = [pos[t + 6] - pos[t], pos[t + 7] - pos[t + 1], pos[t + 8] - pos[t + 2]];
    const f = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
    for (let k = 0; k < 9; k += 3) {
      const s = sums.get(key(t + k)) ?? [0, 0, 0];
      sums.set(key(t + k), [s[0] + f[0], s[1] + f[1], s[2] + f[2]]);
    }
  }
  for (let i = 0; i < pos.length; i += 3) {
    const s = sums.get(key(i));
    const len = Math.hypot(s[0], s[1], s[2]);
    const missing = nrm[i] === 0 && nrm[i + 1] === 0 && nrm[i + 2] === 0;
    if (missing && len > 0) [nrm[i], nrm[i + 1], nrm[i + 2]] = [s[0] / len, s[1] / len, s[2] / len];
  }
}
