// sylva viewer: instanced branches with TRS per instance, Lambert plus ambient, distance fog.

struct Globals {
    view_proj: mat4x4<f32>,
    camera: vec4<f32>,
    light: vec4<f32>,
    sky: vec4<f32>,
    fog: vec4<f32>,
};

struct Material {
    colour: vec4<f32>,
    id: vec4<f32>,
};

@group(0) @binding(0) var<uniform> globals: Globals;
@group(1) @binding(0) var<uniform> material: Material;
// The procedural textures, one layer each: broadleaf, needles, furrowed and smooth bark;
// material.colour.w is the layer plus one, 0 for untextured materials. Bark (layers 2 and 3)
// tiles; leaf cards do not.
@group(2) @binding(0) var textures: texture_2d_array<f32>;
@group(2) @binding(1) var texture_sampler: sampler;

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) rotation: vec4<f32>,
    @location(4) translation_scale: vec4<f32>,
    @location(5) tint: vec4<f32>,
};

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) tint: vec3<f32>,
};

fn rotate(q: vec4<f32>, v: vec3<f32>) -> vec3<f32> {
    let t = 2.0 * cross(q.xyz, v);
    return v + q.w * t + cross(q.xyz, t);
}

@vertex
fn vs_main(in: VertexIn) -> VertexOut {
    var out: VertexOut;
    let world = in.translation_scale.xyz + in.translation_scale.w * rotate(in.rotation, in.position);
    out.clip = globals.view_proj * vec4<f32>(world, 1.0);
    out.world = world;
    out.normal = rotate(in.rotation, in.normal);
    out.uv = in.uv;
    out.tint = in.tint.rgb;
    return out;
}

// The material's texture colour (leaf card or bark), or white for untextured materials;
// discards where a leaf card is clear (alpha-tested foliage).
fn texel(uv: vec2<f32>) -> vec3<f32> {
    let layer = i32(material.colour.w + 0.5) - 1;
    let tiled = select(uv, fract(uv), layer >= 2);
    // Sampled in uniform control flow; the layer is clamped for untextured materials.
    let sampled = textureSample(textures, texture_sampler, tiled, max(layer, 0));
    if (layer < 0) {
        return vec3<f32>(1.0);
    }
    if (sampled.a < 0.5) {
        discard;
    }
    return sampled.rgb;
}

// Ground colour by slope and altitude: the palette of sylva_terrain::ground, repeated here.
fn ground(normal: vec3<f32>, height: f32) -> vec3<f32> {
    let grass = vec3<f32>(0.20, 0.30, 0.09);
    let soil = vec3<f32>(0.30, 0.23, 0.14);
    let rock = vec3<f32>(0.36, 0.35, 0.33);
    let snow_colour = vec3<f32>(0.85, 0.87, 0.90);
    let slope = 1.0 - clamp(normal.y, 0.0, 1.0);
    let soil_w = smoothstep(0.08, 0.25, slope);
    let rock_w = smoothstep(0.25, 0.45, slope);
    let snow_w = smoothstep(0.80, 0.90, height) * (1.0 - rock_w);
    return mix(mix(mix(grass, soil, soil_w), rock, rock_w), snow_colour, snow_w);
}

@fragment
fn fs_main(in: VertexOut, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    var albedo = material.colour.rgb * texel(in.uv) * in.tint;
    if (material.colour.w < -0.5) {
        // fog.yz: the lowest and highest terrain.
        let height = (in.world.y - globals.fog.y) / max(globals.fog.z - globals.fog.y, 1e-3);
        albedo = ground(normalize(in.normal), clamp(height, 0.0, 1.0));
    }
    var n = normalize(in.normal);
    if (!front) {
        n = -n;
    }
    let diffuse = max(dot(n, globals.light.xyz), 0.0);
    let lit = albedo * (0.35 + 0.65 * diffuse);
    let fog = 1.0 - exp(-distance(in.world, globals.camera.xyz) * globals.fog.x);
    return vec4<f32>(mix(lit, globals.sky.rgb, clamp(fog, 0.0, 1.0)), 1.0);
}

// Flat material ids, for tests that count what covers the picture.
@fragment
fn fs_id(in: VertexOut) -> @location(0) vec4<f32> {
    // Clear parts of leaf cards are no leaf: texel() discards them.
    _ = texel(in.uv);
    return material.id;
}
