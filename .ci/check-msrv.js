// Checks the workspace's declared minimum Rust version against its dependencies: every
// package the library crates build on must declare a rust-version at or below ours (a
// dependency that needs a newer compiler makes our declaration false). Only one toolchain
// can be installed where CI runs, so this and clippy's incompatible_msrv lint (which flags std
// APIs newer than rust-version) stand in for building with the old compiler.
// usage: cargo metadata --locked --format-version 1 | node .ci/check-msrv.js
const meta = JSON.parse(require('fs').readFileSync(0, 'utf8'));
const parse = (v) => v.split('.').map(Number).concat([0, 0]).slice(0, 3);
const newer = (a, b) => {
  for (let i = 0; i < 3; i++) if (a[i] !== b[i]) return a[i] > b[i];
  return false;
};
const members = new Set(meta.workspace_members);
const ours = meta.packages.find((p) => members.has(p.id) && p.name === 'sylva').rust_version;
const msrv = parse(ours);
// Dependencies of the library crates only: the viewer, benches and examples may need more.
const nodes = new Map(meta.resolve.nodes.map((n) => [n.id, n]));
const library = meta.packages.filter((p) => members.has(p.id) && p.name !== 'sylva-viewer');
const seen = new Set();
const stack = library.map((p) => p.id);
while (stack.length) {
  const id = stack.pop();
  if (seen.has(id)) continue;
  seen.add(id);
  for (const d of nodes.get(id).deps) {
    if (d.dep_kinds.some((k) => k.kind === null)) stack.push(d.pkg);
  }
}
const bad = meta.packages.filter((p) => seen.has(p.id) && p.rust_version && newer(parse(p.rust_version), msrv));
for (const p of bad) console.log(`  ${p.name} ${p.version} needs Rust ${p.rust_version}`);
// Every member declares ours, but the viewer: an application, not published, whose egui
// needs a newer compiler; it may declare a newer one, never an older.
const undeclared = meta.packages.filter((p) => members.has(p.id) && (p.name === 'sylva-viewer'
  ? newer(msrv, parse(p.rust_version || '0'))
  : p.rust_version !== ours));
for (const p of undeclared) console.log(`  workspace member ${p.name} declares ${p.rust_version}, not ${ours}`);
console.log(`rust-version ${ours}: ${seen.size} library packages checked, ${bad.length + undeclared.length} problems`);
process.exit(bad.length + undeclared.length ? 1 : 0);
