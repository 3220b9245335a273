// Renders a Wavefront OBJ to a PNG without a GPU or a browser: an orthographic view, a z-buffer and
// flat shading, for reference pictures of single models (docs/cpfg/). Node.js only, no packages.
// usage: node tools/render_obj.js in.obj out.png [yawDeg] [pitchDeg] [size]
// e.g. sylva tree vlab/oofs/ext/10-manuals/ext/10-GettingStarted/ext/01-Lychnis --out lychnis.obj
//      node tools/render_obj.js lychnis.obj docs/cpfg/lychnis.png 30 15 700
const fs = require('fs'), zlib = require('zlib');
const [,, inp, out, yawD = '30', pitchD = '20', sizeS = '800'] = process.argv;
const W = +sizeS, H = +sizeS;
const text = fs.readFileSync(inp, 'utf8');
const V = []; const F = [];
for (const line of text.split('\n')) {
  if (line.startsWith('v ')) { const p = line.split(/\s+/); V.push([+p[1], +p[2], +p[3]]); }
  else if (line.startsWith('f ')) { const p = line.trim().split(/\s+/).slice(1).map(s => parseInt(s) - 1); for (let i = 1; i + 1 < p.length; i++) F.push([p[0], p[i], p[i + 1]]); }
}
const yaw = yawD * Math.PI / 180, pitch = pitchD * Math.PI / 180;
const rot = ([x, y, z]) => { const x1 = x * Math.cos(yaw) + z * Math.sin(yaw), z1 = -x * Math.sin(yaw) + z * Math.cos(yaw);
  const y2 = y * Math.cos(pitch) - z1 * Math.sin(pitch), z2 = y * Math.sin(pitch) + z1 * Math.cos(pitch); return [x1, y2, z2]; };
const R = V.map(rot);
let mn = [1e30, 1e30], mx = [-1e30, -1e30];
for (const p of R) for (let k = 0; k < 2; k++) { mn[k] = Math.min(mn[k], p[k]); mx[k] = Math.max(mx[k], p[k]); }
const s = 0.92 * Math.min(W / (mx[0] - mn[0]), H / (mx[1] - mn[1]));
const cx = (mn[0] + mx[0]) / 2, cy = (mn[1] + mx[1]) / 2;
const P = R.map(([x, y, z]) => [W / 2 + (x - cx) * s, H / 2 - (y - cy) * s, z]);
const zb = new Float32Array(W * H).fill(-1e30); const img = Buffer.alloc(W * H * 3, 235);
const L = [0.4, 0.8, 0.45]; const ln = Math.hypot(...L); L.forEach((v, i) => L[i] = v / ln);
for (const [a, b, c] of F) {
  const A = R[a], B = R[b], C = R[c];
  const u = [B[0] - A[0], B[1] - A[1], B[2] - A[2]], v = [C[0] - A[0], C[1] - A[1], C[2] - A[2]];
  const n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
  const nl = Math.hypot(...n) || 1; const shade = 0.25 + 0.75 * Math.abs((n[0] * L[0] + n[1] * L[1] + n[2] * L[2]) / nl);
  const pa = P[a], pb = P[b], pc = P[c];
  const x0 = Math.max(0, Math.floor(Math.min(pa[0], pb[0], pc[0]))), x1 = Math.min(W - 1, Math.ceil(Math.max(pa[0], pb[0], pc[0])));
  const y0 = Math.max(0, Math.floor(Math.min(pa[1], pb[1], pc[1]))), y1 = Math.min(H - 1, Math.ceil(Math.max(pa[1], pb[1], pc[1])));
  const d = (pb[1] - pc[1]) * (pa[0] - pc[0]) + (pc[0] - pb[0]) * (pa[1] - pc[1]); if (Math.abs(d) < 1e-12) continue;
  for (let y = y0; y <= y1; y++) for (let x = x0; x <= x1; x++) {
    const px = x + 0.5, py = y + 0.5;
    const w0 = ((pb[1] - pc[1]) * (px - pc[0]) + (pc[0] - pb[0]) * (py - pc[1])) / d;
    const w1 = ((pc[1] - pa[1]) * (px - pc[0]) + (pa[0] - pc[0]) * (py - pc[1])) / d;
    const w2 = 1 - w0 - w1; if (w0 < 0 || w1 < 0 || w2 < 0) continue;
    const z = w0 * pa[2] + w1 * pb[2] + w2 * pc[2]; const i = y * W + x;
    if (z > zb[i]) { zb[i] = z; img[i * 3] = 60 * shade + 20; img[i * 3 + 1] = 150 * shade + 30; img[i * 3 + 2] = 70 * shade + 20; }
  }
}
const crcT = []; for (let n = 0; n < 256; n++) { let c = n; for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1; crcT[n] = c >>> 0; }
const crc = (buf) => { let c = 0xffffffff; for (const b of buf) c = crcT[(c ^ b) & 255] ^ (c >>> 8); return (c ^ 0xffffffff) >>> 0; };
const chunk = (t, d) => { const l = Buffer.alloc(4); l.writeUInt32BE(d.length); const td = Buffer.concat([Buffer.from(t), d]); const c = Buffer.alloc(4); c.writeUInt32BE(crc(td)); return Buffer.concat([l, td, c]); };
const raw = Buffer.alloc(H * (W * 3 + 1)); for (let y = 0; y < H; y++) { raw[y * (W * 3 + 1)] = 0; img.copy(raw, y * (W * 3 + 1) + 1, y * W * 3, (y + 1) * W * 3); }
const ihdr = Buffer.alloc(13); ihdr.writeUInt32BE(W, 0); ihdr.writeUInt32BE(H, 4); ihdr[8] = 8; ihdr[9] = 2;
fs.writeFileSync(out, Buffer.concat([Buffer.from([137, 80, 78, 71, 13, 10, 26, 10]), chunk('IHDR', ihdr), chunk('IDAT', zlib.deflateSync(raw)), chunk('IEND', Buffer.alloc(0))]));
console.log(`${out}: ${F.length} triangles`);
