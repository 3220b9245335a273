// Pictures by role, to compare levels with full detail: every material drawn flat by what
// it shows (leaves and impostor cards green, bark red, terrain blue, over a white sky), a
// leaf card keeping its texture's alpha test through the client's own mipmaps; and the
// share of the picture each role covers.
import { Color, MeshBasicMaterial } from 'three';

/** The flat material of `material`'s role. */
export function flatten(material) {
  const name = material.name || '';
  const leaves = name.endsWith('leaves') || name.endsWith('impostor');
  const colour = leaves ? 0x00ff00 : name.endsWith('bark') ? 0xff0000 : 0x0000ff;
  return new MeshBasicMaterial({
    color: colour,
    map: leaves ? material.map : null,
    alphaTest: material.alphaTest,
    side: material.side,
  });
}

/** Draws every mesh under `root` by role, over a white sky without fog. */
export function byRole(scene, root) {
  scene.background = new Color(0xffffff);
  scene.fog = null;
  const flat = new Map();
  root.traverse((o) => {
    if (!o.material) return;
    if (!flat.has(o.material)) flat.set(o.material, flatten(o.material));
    o.material = flat.get(o.material);
  });
}

/** Shares of the picture (percent) by dominant channel, and foliage over the ground seen. */
export function coverage(renderer, width, height) {
  const gl = renderer.getContext();
  const pixels = new Uint8Array(width * height * 4);
  gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
  const counts = { leaves: 0, bark: 0, terrain: 0, sky: 0 };
  for (let i = 0; i < pixels.length; i += 4) {
    const [r, g, b] = [pixels[i], pixels[i + 1], pixels[i + 2]];
    if (Math.max(r, g, b) - Math.min(r, g, b) < 40) counts.sky += 1;
    else if (g >= r && g >= b) counts.leaves += 1;
    else if (r >= b) counts.bark += 1;
    else counts.terrain += 1;
  }
  const n = width * height;
  const ground = n - counts.sky;
  const out = Object.fromEntries(Object.entries(counts).map(([k, v]) => [k, 100 * v / n]));
  out.foliage = ground > 0 ? 100 * counts.leaves / ground : 0;
  return out;
}
