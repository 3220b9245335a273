// How far the wind moves a world-space point of a branch (sylva's viewer sways the same way):
// each branch about its pivot, more the longer its lever and the deeper the branch, and leaf
// cards flutter; `packed` is the vertex's depth plus phase, `tag` the placement's phase in
// 1/65536ths. The wind (direction times strength, and the time) is the material's.
#define_import_path sylva::sway

struct Wind {
    // xz: direction times strength; w: time in seconds.
    wind: vec4<f32>,
};
@group(#{MATERIAL_BIND_GROUP}) @binding(100) var<uniform> sylva_wind: Wind;

const TAU: f32 = 6.2831853;

fn sway(world: vec3<f32>, pivot: vec3<f32>, packed: f32, tag: u32) -> vec3<f32> {
    let strength = length(sylva_wind.wind.xz);
    if (strength < 1e-4) {
        return vec3<f32>(0.0);
    }
    let dir = vec3<f32>(sylva_wind.wind.x, 0.0, sylva_wind.wind.z) / strength;
    let t = sylva_wind.wind.w;
    let depth = floor(packed);
    let phase = fract(packed) + f32(tag) / 65536.0;
    let lever = length(world - pivot);
    let branch = 0.025 * lever * min(depth, 4.0) * sin(t * 2.1 + phase * TAU);
    let flutter = 0.02 * lever * step(3.5, depth) * sin(t * 7.0 + phase * 3.0 * TAU);
    return strength * (dir * branch + vec3<f32>(0.0, branch * 0.3 + flutter, 0.0));
}
