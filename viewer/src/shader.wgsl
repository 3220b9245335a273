// sylva viewer: instanced branches with TRS per instance, swaying in the wind; a sun with a
// shadow map, hemispheric ambient light, a sky gradient and distance fog.

struct Globals {
    view_proj: mat4x4<f32>,
    // The inverse of view_proj, for the sky's view rays.
    inverse_view_proj: mat4x4<f32>,
    light_view_proj: mat4x4<f32>,
    camera: vec4<f32>,
    // xyz: towards the sun (unit); w: 1 when the shadow map is in use.
    light: vec4<f32>,
    // Sky colour at the horizon (rgb); w unused.
    horizon: vec4<f32>,
    // Sky colour overhead (rgb); w unused.
    zenith: vec4<f32>,
    // x: fog density per metre; y, z: the lowest and highest terrain.
    fog: vec4<f32>,
    // xz: wind direction times strength (horizontal); w: time in seconds.
    wind: vec4<f32>,
    // x: the day of the year; y: 1 when the seasons are played; z: snow lying, 0 to 1.
    season: vec4<f32>,
};

struct Material {
    colour: vec4<f32>,
    id: vec4<f32>,
    // A deciduous leaf material's year: x the day it leafs out, y the day half its leaves
    // have fallen, z 1 (0: no year, the colour all year); its spring and autumn colours.
    season: vec4<f32>,
    spring: vec4<f32>,
    autumn: vec4<f32>,
};

@group(0) @binding(0) var<uniform> globals: Globals;
// Every material (the terrain's first); each vertex names its own. MATERIAL_COUNT is replaced
// by the world's number of materials when the shader is built.
@group(1) @binding(0) var<uniform> materials: array<Material, MATERIAL_COUNT>;
// The procedural textures, one layer each: every leaf shape, then every bark pattern, then
// the barks' normal maps in the same order; a material's colour.w is the colour layer plus
// one (0 for untextured materials, -1 for the terrain). Bark (from layer FIRST_BARK) tiles;
// leaf cards do not. FIRST_BARK and BARK_COUNT are replaced when the shader is built.
@group(2) @binding(0) var textures: texture_2d_array<f32>;
@group(2) @binding(1) var texture_sampler: sampler;
// The impostor atlases: each impostor's colour (rgb, coverage in a) then its normals (rgb, the
// share of leaves in a), in the layers 2k and 2k + 1.
@group(2) @binding(2) var impostor_atlases: texture_2d_array<f32>;
@group(3) @binding(0) var shadow_map: texture_depth_2d;
@group(3) @binding(1) var shadow_sampler: sampler_comparison;

const TAU: f32 = 6.2831853;
// Snow's colour: sylva_terrain::ground::SNOW.
const SNOW: vec3<f32> = vec3<f32>(0.85, 0.87, 0.90);

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    // Pivot (xyz, mesh space) and branch depth plus phase (w).
    @location(3) wind: vec4<f32>,
    @location(4) rotation: vec4<f32>,
    @location(5) translation_scale: vec4<f32>,
    @location(6) tint: vec4<f32>,
    // The tree's base (xyz, world) and phase (w).
    @location(7) tree: vec4<f32>,
    @location(8) material: u32,
};

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) tint: vec3<f32>,
    @location(4) @interpolate(flat) material: u32,
    // The placement's fade between levels of detail (see faded_out).
    @location(5) @interpolate(flat) fade: f32,
    // The share of an untextured crown (a far tree's proxy) the season leaves on the tree,
    // its pixels thinned by a dither; 1 for everything else.
    @location(6) @interpolate(flat) share: f32,
};

fn rotate(q: vec4<f32>, v: vec3<f32>) -> vec3<f32> {
    let t = 2.0 * cross(q.xyz, v);
    return v + q.w * t + cross(q.xyz, t);
}

// A 4 x 4 ordered dither threshold in (0, 1) at a pixel.
fn dither(pixel: vec2<f32>) -> f32 {
    let bayer = array<f32, 16>(0.0, 8.0, 2.0, 10.0, 12.0, 4.0, 14.0, 6.0, 3.0, 11.0, 1.0, 9.0, 15.0, 7.0, 13.0, 5.0);
    let p = vec2<u32>(pixel) % vec2<u32>(4u);
    return (bayer[p.y * 4u + p.x] + 0.5) / 16.0;
}

// Whether a placement fading between levels of detail leaves this pixel to the other level:
// 0 draws it whole; f > 0 (fading out) draws where the dither is at least f; -f (fading in)
// where it is below f, so the two levels of one tree share the pixels between them.
fn faded_out(pixel: vec2<f32>, fade: f32) -> bool {
    let d = dither(pixel);
    return (fade > 0.0 && d < fade) || (fade < 0.0 && d >= -fade);
}

fn is_terrain(material: Material) -> bool {
    return material.colour.w < -0.5;
}

// Whether the material is a leaf card's: its texture is one of the leaf shapes' layers.
fn is_card(material: Material) -> bool {
    let layer = i32(material.colour.w + 0.5) - 1;
    return layer >= 0 && layer < FIRST_BARK;
}

// How far the wind moves a world-space point: the whole tree bends about its base (more the
// higher the point), each branch sways about its pivot (more the longer its lever and the
// deeper the branch) and leaf cards flutter, each with its own phase. Every term reads
// either world-space geometry or the tree's own data, so instanced branches move as one tree.
fn sway(world: vec3<f32>, pivot: vec3<f32>, packed: f32, tree: vec4<f32>, still: bool) -> vec3<f32> {
    let strength = length(globals.wind.xz);
    if (strength < 1e-4 || still) {
        return vec3<f32>(0.0);
    }
    let dir = vec3<f32>(globals.wind.x, 0.0, globals.wind.z) / strength;
    let t = globals.wind.w;
    let depth = floor(packed);
    let phase = fract(packed) + tree.w;
    let height = max(world.y - tree.y, 0.0);
    let gust = 0.75 + 0.25 * sin(t * 0.7 + tree.w * TAU);
    let bend = 0.0009 * height * height * gust * (0.8 + 0.2 * sin(t * 1.3 + tree.w * TAU));
    let lever = length(world - pivot);
    let branch = 0.025 * lever * min(depth, 4.0) * sin(t * 2.1 + phase * TAU);
    let flutter = 0.02 * lever * step(3.5, depth) * sin(t * 7.0 + phase * 3.0 * TAU);
    return strength * (dir * (bend + branch) + vec3<f32>(0.0, branch * 0.3 + flutter, 0.0));
}

fn to_world(in: VertexIn) -> vec3<f32> {
    let s = in.translation_scale.w;
    let world = in.translation_scale.xyz + s * rotate(in.rotation, in.position);
    let pivot = in.translation_scale.xyz + s * rotate(in.rotation, in.wind.xyz);
    return world + sway(world, pivot, in.wind.w, in.tree, is_terrain(materials[in.material]));
}

// Each leaf card (a cluster of leaves) a little lighter or darker, warmer or cooler than its
// tree's colour, drawn from the card's own wind phase: sylva_forest::cluster_shade, repeated
// here, over its mean (the constant is replaced when the shader is built) so the species'
// colour holds on average.
fn cluster_shade(phase: f32) -> vec3<f32> {
    let light = 1.0 - 0.25 * fract(phase * 7.31);
    let warm = fract(phase * 13.7);
    return light * vec3<f32>(0.92 + 0.08 * warm, 1.0, 1.0 - 0.12 * warm) / CLUSTER_SHADE_MEAN;
}

// The seasons, as sylva_forest::Phenology::leaves has them (repeated here; the day
// constants are replaced when the shader is built): a deciduous species' share of its leaf
// cards on a day, their colour and size. A tree's day runs up to TREE_DAYS early or late
// by its phase (sylva_forest::tree_day).
struct LeafSeason {
    share: f32,
    colour: vec3<f32>,
    size: f32,
};

fn ramp(x: f32) -> f32 {
    let t = clamp(x, 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

fn leaf_season(m: Material, tree_phase: f32) -> LeafSeason {
    var out: LeafSeason;
    out.share = 1.0;
    out.colour = m.colour.rgb;
    out.size = 1.0;
    if (globals.season.y < 0.5 || m.season.z < 0.5) {
        return out;
    }
    let shifted = globals.season.x + (2.0 * clamp(tree_phase, 0.0, 1.0) - 1.0) * TREE_DAYS;
    let day = shifted - 1.0 - floor((shifted - 1.0) / 365.0) * 365.0 + 1.0;
    let since = day - m.season.x;
    let flush = ramp(since / FLUSH_DAYS);
    let fall = 1.0 - ramp((day - (m.season.y - 0.5 * FALL_DAYS)) / FALL_DAYS);
    out.share = select(min(flush, fall), 0.0, day < m.season.x);
    let green = ramp(since / GREEN_DAYS);
    let turn = ramp((day - (m.season.y - 5.0 - TURN_DAYS)) / TURN_DAYS);
    out.colour = mix(mix(m.spring.rgb, m.colour.rgb, green), m.autumn.rgb, turn);
    out.size = 0.4 + 0.6 * ramp(since / (FLUSH_DAYS + 15.0));
    return out;
}

// A vertex of a leaf card as the season has it, in mesh space: grown from the card's base
// (its wind pivot) to the season's size; other vertices as they are.
fn grown_position(in: VertexIn, season: LeafSeason, card: bool) -> vec3<f32> {
    return in.wind.xyz + (in.position - in.wind.xyz) * select(1.0, season.size, card);
}

// Whether a leaf card is off the tree: its order in the year (its wind phase) is not below
// its species' share that day. Its corners are then put behind the far plane.
fn fallen(in: VertexIn, season: LeafSeason, card: bool) -> bool {
    return card && fract(in.wind.w) >= season.share;
}

const FALLEN_CLIP: vec4<f32> = vec4<f32>(0.0, 0.0, 2.0, 1.0);

// The factor that turns a material's own colour into the season's.
fn turned(season: LeafSeason, material: Material) -> vec3<f32> {
    return season.colour / max(material.colour.rgb, vec3<f32>(1e-4));
}

// `albedo` under the snow lying that day where the surface catches it (0 to 1: how far it
// faces up), as sylva_forest::vertex_phenology's snow catch.
fn snowed(albedo: vec3<f32>, catch_snow: f32) -> vec3<f32> {
    return mix(albedo, SNOW, globals.season.z * smoothstep(0.2, 0.7, catch_snow) * 0.85);
}

@vertex
fn vs_main(in: VertexIn) -> VertexOut {
    var out: VertexOut;
    let material = materials[in.material];
    let card = is_card(material);
    let season = leaf_season(material, in.tree.w);
    var grown = in;
    grown.position = grown_position(in, season, card);
    let world = to_world(grown);
    out.clip = select(globals.view_proj * vec4<f32>(world, 1.0), FALLEN_CLIP, fallen(in, season, card));
    out.world = world;
    out.normal = rotate(in.rotation, in.normal);
    out.uv = in.uv;
    // The day's colour over the species' own, so the material's colour turns into it; a
    // proxy's untextured crown turns too, and thins as its cards would.
    let shade = select(vec3<f32>(1.0), cluster_shade(fract(in.wind.w)), card);
    out.tint = in.tint.rgb * shade * turned(season, material);
    out.share = select(1.0, season.share, !card && material.season.z > 0.5);
    out.material = in.material;
    out.fade = in.tint.w;
    return out;
}

struct Texel {
    colour: vec3<f32>,
    // Tangent-space normal from the bark's normal map; (0, 0, 1) elsewhere.
    normal: vec3<f32>,
    alpha: f32,
};

// The material's texture (leaf card or bark) with the bark's normal map, or white for
// untextured materials. Sampled in uniform control flow; callers discard clear texels.
fn texel(uv: vec2<f32>, material: Material) -> Texel {
    let layer = i32(material.colour.w + 0.5) - 1;
    let bark = layer >= FIRST_BARK;
    let tiled = select(uv, fract(uv), bark);
    let sampled = textureSample(textures, texture_sampler, tiled, max(layer, 0));
    let normal = textureSample(textures, texture_sampler, tiled, select(0, layer + BARK_COUNT, bark));
    var out: Texel;
    out.colour = select(vec3<f32>(1.0), sampled.rgb, layer >= 0);
    out.alpha = select(1.0, sampled.a, layer >= 0);
    // Normal maps are uploaded sRGB-encoded, so sampling returns their plain values.
    out.normal = select(vec3<f32>(0.0, 0.0, 1.0), normal.rgb * 2.0 - 1.0, bark);
    return out;
}

// Ground colour by slope and altitude: the palette of sylva_terrain::ground, repeated here.
fn ground(normal: vec3<f32>, height: f32) -> vec3<f32> {
    let grass = vec3<f32>(0.20, 0.30, 0.09);
    let soil = vec3<f32>(0.30, 0.23, 0.14);
    let rock = vec3<f32>(0.36, 0.35, 0.33);
    let slope = 1.0 - clamp(normal.y, 0.0, 1.0);
    let soil_w = smoothstep(0.08, 0.25, slope);
    let rock_w = smoothstep(0.25, 0.45, slope);
    let snow_w = smoothstep(0.80, 0.90, height) * (1.0 - rock_w);
    return mix(mix(mix(grass, soil, soil_w), rock, rock_w), SNOW, snow_w);
}

// Value noise on a unit lattice, from a hash of the corners: the ground's fine detail.
fn hash2(p: vec2<f32>) -> f32 {
    return fract(sin(dot(p, vec2<f32>(127.1, 311.7))) * 43758.5453);
}

fn noise(p: vec2<f32>) -> f32 {
    let i = floor(p);
    let f = fract(p);
    let u = f * f * (3.0 - 2.0 * f);
    let a = hash2(i);
    let b = hash2(i + vec2<f32>(1.0, 0.0));
    let c = hash2(i + vec2<f32>(0.0, 1.0));
    let d = hash2(i + vec2<f32>(1.0, 1.0));
    return mix(mix(a, b, u.x), mix(c, d, u.x), u.y);
}

// Patches of lighter and darker ground at metre and ten-metre scales, so that the ground
// does not read as one flat colour up close.
fn ground_detail(xz: vec2<f32>) -> f32 {
    return 0.78 + 0.28 * noise(xz * 0.9) + 0.16 * noise(xz * 0.11);
}

// The sky seen along `dir`: horizon colour low down, zenith colour overhead, a glow around the
// sun.
fn sky(dir: vec3<f32>) -> vec3<f32> {
    let up = clamp(dir.y, 0.0, 1.0);
    let base = mix(globals.horizon.rgb, globals.zenith.rgb, pow(up, 0.6));
    let sun = pow(max(dot(dir, globals.light.xyz), 0.0), 64.0);
    return base + vec3<f32>(1.0, 0.9, 0.7) * sun * 0.5;
}

// 1 where the sun reaches `world`, 0 in shadow, from a 3 x 3 percentage-closer filter; lit
// outside the shadow map's box.
fn sunlit(world: vec3<f32>, normal: vec3<f32>) -> f32 {
    if (globals.light.w < 0.5) {
        return 1.0;
    }
    // Offset along the normal against acne on surfaces that face away from the sun.
    let p = globals.light_view_proj * vec4<f32>(world + normal * 0.08, 1.0);
    let uv = vec2<f32>(p.x * 0.5 + 0.5, 0.5 - p.y * 0.5);
    if (any(uv < vec2<f32>(0.0)) || any(uv > vec2<f32>(1.0)) || p.z > 1.0) {
        return 1.0;
    }
    let texel_size = 1.0 / vec2<f32>(textureDimensions(shadow_map));
    var lit = 0.0;
    for (var i = -1; i <= 1; i++) {
        for (var j = -1; j <= 1; j++) {
            let offset = vec2<f32>(f32(i), f32(j)) * texel_size;
            lit += textureSampleCompareLevel(shadow_map, shadow_sampler, uv + offset, p.z - 0.0015);
        }
    }
    return lit / 9.0;
}

// A normal from the tangent-space `mapped` normal around the surface normal `n`, with the
// tangent frame taken from screen-space derivatives of position and uv (no tangents needed).
fn perturb(n: vec3<f32>, mapped: vec3<f32>, dp_dx: vec3<f32>, dp_dy: vec3<f32>, duv_dx: vec2<f32>, duv_dy: vec2<f32>) -> vec3<f32> {
    let dp2perp = cross(dp_dy, n);
    let dp1perp = cross(n, dp_dx);
    let t = dp2perp * duv_dx.x + dp1perp * duv_dy.x;
    let b = dp2perp * duv_dx.y + dp1perp * duv_dy.y;
    let scale = inverseSqrt(max(max(dot(t, t), dot(b, b)), 1e-20));
    // The map's green points up the image, towards smaller v.
    let perturbed = t * scale * mapped.x - b * scale * mapped.y + n * mapped.z;
    return normalize(select(n, perturbed, all(perturbed == perturbed)));
}

@fragment
fn fs_main(in: VertexOut, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    // Derivatives first, in uniform control flow.
    let dp_dx = dpdx(in.world);
    let dp_dy = dpdy(in.world);
    let duv_dx = dpdx(in.uv);
    let duv_dy = dpdy(in.uv);
    let material = materials[in.material];
    let tex = texel(in.uv, material);
    if (tex.alpha < 0.5 || faded_out(in.clip.xy, in.fade) || dither(in.clip.xy) >= in.share) {
        discard;
    }
    var albedo = material.colour.rgb * tex.colour * in.tint;
    if (is_terrain(material)) {
        let height = (in.world.y - globals.fog.y) / max(globals.fog.z - globals.fog.y, 1e-3);
        albedo = ground(normalize(in.normal), clamp(height, 0.0, 1.0)) * ground_detail(in.world.xz);
    }
    // Snow lies on what faces up (a card, seen from either side, either way): the
    // exports' snow catch (sylva_forest::vertex_phenology) times the snow that day.
    let up = normalize(in.normal).y;
    albedo = snowed(albedo, select(max(up, 0.0), abs(up), is_card(material)));
    var n = normalize(in.normal);
    if (!front) {
        n = -n;
    }
    n = perturb(n, tex.normal, dp_dx, dp_dy, duv_dx, duv_dy);
    // Leaf cards pass some light through: their back faces glow a little.
    let translucent = select(0.0, 0.35, is_card(material));
    return vec4<f32>(lit(in.world, n, albedo, translucent), 1.0);
}

// A surface at `world` of normal `n` and colour `albedo` in the sun (`translucent`: how much
// light comes through from behind), the sky and the fog.
fn lit(world: vec3<f32>, n: vec3<f32>, albedo: vec3<f32>, translucent: f32) -> vec3<f32> {
    let l = globals.light.xyz;
    let facing = dot(n, l);
    let diffuse = max(facing, 0.0) + translucent * max(-facing, 0.0);
    let shadow = sunlit(world, n);
    // Hemispheric ambient: sky light from above, light bounced off the ground from below.
    let bounce = vec3<f32>(0.20, 0.22, 0.12);
    let ambient = mix(bounce, globals.zenith.rgb, n.y * 0.5 + 0.5) * 0.55;
    let sun_colour = vec3<f32>(1.0, 0.95, 0.85);
    let shaded = albedo * (ambient + sun_colour * diffuse * shadow * 0.9);
    let to_eye = world - globals.camera.xyz;
    let fog = 1.0 - exp(-length(to_eye) * globals.fog.x);
    let haze = sky(normalize(vec3<f32>(to_eye.x, 0.0, to_eye.z) + vec3<f32>(0.0, 0.05, 0.0)));
    return mix(shaded, haze, clamp(fog, 0.0, 1.0));
}

// Flat material ids, for tests that count what covers the picture.
@fragment
fn fs_id(in: VertexOut) -> @location(0) vec4<f32> {
    // Clear parts of leaf cards are no leaf.
    let material = materials[in.material];
    if (texel(in.uv, material).alpha < 0.5 || faded_out(in.clip.xy, in.fade) || dither(in.clip.xy) >= in.share) {
        discard;
    }
    return material.id;
}

// The shadow map: depth from the sun, leaf cards cut by their alpha like in the main pass.
struct ShadowOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) uv: vec2<f32>,
    @location(1) @interpolate(flat) material: u32,
    @location(2) @interpolate(flat) fade: f32,
};

@vertex
fn vs_shadow(in: VertexIn) -> ShadowOut {
    var out: ShadowOut;
    let material = materials[in.material];
    let card = is_card(material);
    let season = leaf_season(material, in.tree.w);
    var grown = in;
    grown.position = grown_position(in, season, card);
    let clip = globals.light_view_proj * vec4<f32>(to_world(grown), 1.0);
    out.clip = select(clip, FALLEN_CLIP, fallen(in, season, card));
    out.uv = in.uv;
    out.material = in.material;
    out.fade = in.tint.w;
    return out;
}

@fragment
fn fs_shadow(in: ShadowOut) {
    if (texel(in.uv, materials[in.material]).alpha < 0.5 || faded_out(in.clip.xy, in.fade)) {
        discard;
    }
}

// The sky: one triangle over the whole screen at the far plane, coloured along each view ray.
struct SkyOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) ndc: vec2<f32>,
};

@vertex
fn vs_sky(@builtin(vertex_index) i: u32) -> SkyOut {
    let ndc = vec2<f32>(f32(i / 2u) * 4.0 - 1.0, f32(i % 2u) * 4.0 - 1.0);
    var out: SkyOut;
    out.clip = vec4<f32>(ndc, 1.0, 1.0);
    out.ndc = ndc;
    return out;
}

@fragment
fn fs_sky(in: SkyOut) -> @location(0) vec4<f32> {
    let far = globals.inverse_view_proj * vec4<f32>(in.ndc, 1.0, 1.0);
    let dir = normalize(far.xyz / far.w - globals.camera.xyz);
    return vec4<f32>(sky(dir), 1.0);
}

// Impostors: a card per far tree, turned to face the camera, showing the tree's atlas views
// nearest the direction it is seen from (sylva_export::lod::Impostor: hemi-octahedral views
// on an N x N lattice, view (i, j) looking from the lattice point (i, j) / (N - 1), in
// column i, row j of the atlas), blended by their distance on the lattice.
struct ImpostorOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) @interpolate(flat) centre: vec3<f32>,
    @location(2) @interpolate(flat) tint: vec3<f32>,
    @location(3) @interpolate(flat) material: u32,
    // Atlas number, views per side, the sphere's radius in the world, the bark material.
    @location(4) @interpolate(flat) atlas: vec4<f32>,
    @location(5) @interpolate(flat) rotation: vec4<f32>,
    @location(6) @interpolate(flat) fade: f32,
    // The tree's phase, which moves its day in the year.
    @location(7) @interpolate(flat) phase: f32,
};

// A view's picture axes, as sylva_export::lod::OrthoView::axes: right horizontal, up the rest.
fn view_right(toward: vec3<f32>) -> vec3<f32> {
    let r = cross(vec3<f32>(0.0, 1.0, 0.0), toward);
    return select(vec3<f32>(1.0, 0.0, 0.0), normalize(r), dot(r, r) > 1e-8);
}

fn hemi_octahedral_uv(d: vec3<f32>) -> vec2<f32> {
    let s = max(abs(d.x) + abs(d.y) + abs(d.z), 1e-12);
    let p = d.x / s;
    let q = d.z / s;
    return vec2<f32>(0.5 * (p + q) + 0.5, 0.5 * (p - q) + 0.5);
}

fn hemi_octahedral_direction(uv: vec2<f32>) -> vec3<f32> {
    let a = 2.0 * uv.x - 1.0;
    let b = 2.0 * uv.y - 1.0;
    let p = 0.5 * (a + b);
    let q = 0.5 * (a - b);
    let y = max(1.0 - abs(p) - abs(q), 0.0);
    return normalize(vec3<f32>(p, y, q));
}

@vertex
fn vs_impostor(in: VertexIn) -> ImpostorOut {
    var out: ImpostorOut;
    let s = in.translation_scale.w;
    // The card's vertices carry the atlas' sphere: its centre in `normal`, its radius in wind.z.
    let centre = in.translation_scale.xyz + s * rotate(in.rotation, in.normal);
    let radius = in.wind.z * s;
    let toward = normalize(globals.camera.xyz - centre);
    let right = view_right(toward);
    let up = cross(toward, right);
    let world = centre + (right * in.position.x + up * in.position.y) * radius;
    out.clip = globals.view_proj * vec4<f32>(world, 1.0);
    out.world = world;
    out.centre = centre;
    out.tint = in.tint.rgb;
    out.material = in.material;
    out.atlas = vec4<f32>(in.wind.x, in.wind.y, radius, in.wind.w);
    out.rotation = in.rotation;
    out.fade = in.tint.w;
    out.phase = in.tree.w;
    return out;
}

struct ImpostorTexel {
    colour: vec3<f32>,
    alpha: f32,
    normal: vec3<f32>,
    leaf: f32,
};

// What the impostor shows at this fragment: the four lattice views around the direction the
// tree is seen from, each sampled where the fragment's point falls in its picture.
fn impostor_texel(in: ImpostorOut) -> ImpostorTexel {
    let q = in.rotation;
    let inverse = vec4<f32>(-q.xyz, q.w);
    let toward = rotate(inverse, normalize(globals.camera.xyz - in.centre));
    let point = rotate(inverse, in.world - in.centre) / max(in.atlas.z, 1e-6);
    let n = in.atlas.y;
    let last = n - 1.0;
    let g = hemi_octahedral_uv(toward) * last;
    let base = clamp(floor(g), vec2<f32>(0.0), vec2<f32>(last - 1.0));
    let f = clamp(g - base, vec2<f32>(0.0), vec2<f32>(1.0));
    let layer = i32(in.atlas.x + 0.5) * 2;
    var colour = vec3<f32>(0.0);
    var alpha = 0.0;
    var normal = vec3<f32>(0.0);
    var leaf = 0.0;
    for (var k = 0u; k < 4u; k++) {
        let corner = vec2<f32>(f32(k & 1u), f32(k >> 1u));
        let weights = mix(vec2<f32>(1.0) - f, f, corner);
        let w = weights.x * weights.y;
        let cell = base + corner;
        let d = hemi_octahedral_direction(cell / last);
        let right = view_right(d);
        let up = cross(d, right);
        let in_view = clamp(vec2<f32>(dot(point, right), -dot(point, up)) * 0.5 + 0.5, vec2<f32>(0.002), vec2<f32>(0.998));
        let uv = (cell + in_view) / n;
        let c = textureSampleLevel(impostor_atlases, texture_sampler, uv, layer, 0.0);
        let m = textureSampleLevel(impostor_atlases, texture_sampler, uv, layer + 1, 0.0);
        colour += w * c.a * c.rgb;
        alpha += w * c.a;
        normal += w * c.a * (m.rgb * 2.0 - 1.0);
        leaf += w * c.a * m.a;
    }
    var out: ImpostorTexel;
    out.colour = colour / max(alpha, 1e-4);
    out.alpha = alpha;
    out.normal = rotate(q, normalize(normal + vec3<f32>(0.0, 1e-4, 0.0)));
    out.leaf = leaf / max(alpha, 1e-4);
    return out;
}

@fragment
fn fs_impostor(in: ImpostorOut) -> @location(0) vec4<f32> {
    let t = impostor_texel(in);
    // Leaf texels go as the species' share of cards falls (by a dither, so a crown thins
    // evenly), and what stays turns to the day's colour.
    let material = materials[in.material];
    let season = leaf_season(material, in.phase);
    let bare = t.leaf >= 0.5 && dither(in.clip.xy) >= season.share;
    if (t.alpha < 0.5 || faded_out(in.clip.xy, in.fade) || bare) {
        discard;
    }
    let albedo = snowed(t.colour * in.tint * mix(vec3<f32>(1.0), turned(season, material), t.leaf), t.normal.y);
    return vec4<f32>(lit(in.world, t.normal, albedo, 0.35 * t.leaf), 1.0);
}

@fragment
fn fs_impostor_id(in: ImpostorOut) -> @location(0) vec4<f32> {
    let t = impostor_texel(in);
    let bare = t.leaf >= 0.5 && dither(in.clip.xy) >= leaf_season(materials[in.material], in.phase).share;
    if (t.alpha < 0.5 || faded_out(in.clip.xy, in.fade) || bare) {
        discard;
    }
    let bark = materials[u32(in.atlas.w + 0.5)];
    return select(bark.id, materials[in.material].id, t.leaf >= 0.5);
}
