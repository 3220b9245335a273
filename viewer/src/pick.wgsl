// Copies the placements a frame draws out of the pool of the cells' placements into the
// frame's instance buffer, slot by slot as the draws read them, each with its fade.

struct Instance {
    rotation: vec4<f32>,
    translation_scale: vec4<f32>,
    tint: vec4<f32>,
    tree: vec4<f32>,
}

@group(0) @binding(0) var<storage, read> pool: array<Instance>;
// Each placement drawn: its slot in the pool, and its fade's bits.
@group(0) @binding(1) var<storage, read> picks: array<vec2<u32>>;
@group(0) @binding(2) var<storage, read_write> drawn: array<Instance>;

// Workgroups along x before the next row of them (the dispatch is two-dimensional when a
// frame draws more than 65535 workgroups' worth).
const ROW: u32 = 65535u;

@compute @workgroup_size(64)
fn pick(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x + id.y * ROW * 64u;
    if i >= arrayLength(&picks) {
        return;
    }
    let p = picks[i];
    var instance = pool[p.x];
    instance.tint.w = bitcast<f32>(p.y);
    drawn[i] = instance;
}
