//! The gathering checked against a placement-by-placement reference, at any thread count,
//! copied and picked from the pool.

use super::*;
use crate::cull::Volume;
use crate::geometry::{MESH_LEVELS, lod_chain, world_sphere};
use crate::shadow::{SHADOW_TEXEL, light_view_proj};
use crate::world::SceneOptions;
use proptest::prelude::*;
use std::sync::{Mutex, OnceLock, PoisonError};
use sylva::terrain::glam::Vec3;
use sylva::terrain::glam::camera::rh::{proj::directx, view};

/// Runs `f` on a small world with its cells streamed around its middle, built once for
/// every test (a scene is not shared between threads, so it sits behind a lock).
fn with_scene<R>(f: impl FnOnce(&Scene) -> R) -> R {
    static SCENE: OnceLock<Mutex<Scene>> = OnceLock::new();
    let scene = SCENE.get_or_init(|| {
        let mut scene = Scene::build(SceneOptions::small(6, 300.0)).expect("scene builds");
        let middle = Vec3::new(150.0, 40.0, 150.0);
        scene.stream(middle, false, true).expect("cells stream");
        Mutex::new(scene)
    });
    f(&scene.lock().unwrap_or_else(PoisonError::into_inner))
}

/// The sights of a frame seen from `eye` looking along `forward`: the camera's, and the
/// sun's as the renderer makes it.
fn sights(eye: Vec3, forward: Vec3) -> Vec<Sight> {
    let proj = directx::perspective(55f32.to_radians(), 16.0 / 9.0, 0.2, 2000.0);
    let camera = proj * view::look_to_mat4(eye, forward, Vec3::Y);
    let sun = Vec3::new(0.45, 0.75, 0.35).normalize();
    vec![
        Sight {
            volume: Volume::of(&camera),
            eye,
            pixels_per_radian: 720.0 / 55f32.to_radians(),
        },
        Sight {
            volume: Volume::of(&light_view_proj(eye, forward, sun)),
            eye: eye + sun * 1e4,
            pixels_per_radian: 1e4 / SHADOW_TEXEL,
        },
    ]
}

fn lod_view(eye: Vec3) -> LodView {
    let chain = lod_chain();
    LodView {
        eye,
        pixels_per_radian: 720.0 / 55f32.to_radians(),
        pixel_error: chain.pixel_error,
        fade: chain.fade,
    }
}

/// Each slot's placements as bytes, per sight: what the GPU is given.
type Slots = Vec<Vec<Vec<u8>>>;

/// The placements each sight sees, slot by slot, found one placement at a time: every
/// group of every fine cell, then the impostors of fine and coarse cells, with no
/// placement passed over unless it is tested.
fn reference(scene: &Scene, sights: &[Sight], lod: Option<LodView>) -> Slots {
    let world = &scene.world;
    let with_fade = |i: &InstanceRaw, fade: f32| {
        let mut out = *i;
        out.tint[3] = fade;
        out
    };
    let seen = |sight: &Sight, i: &InstanceRaw, sphere| {
        let (centre, radius) = world_sphere(i, sphere);
        sight.volume.touches(centre, radius)
            && radius >= sight.min_ratio() * centre.distance(sight.eye)
    };
    let mut out = Vec::new();
    for sight in sights {
        let mut slots = vec![Vec::new(); world.slots()];
        let cells = |level| scene.cells.drawn().filter(move |(k, _)| k.level == level);
        for (k, group) in world.groups.iter().enumerate() {
            let errors = &world.lods[group.variant].errors;
            for (_, cell) in cells(Level::Fine) {
                for i in cell.placements.run(k) {
                    if !seen(sight, i, group.sphere) {
                        continue;
                    }
                    let Some(lod) = lod else {
                        slots[k * MESH_LEVELS].push(*i);
                        continue;
                    };
                    for (level, fade) in lod.levels(i.base(), errors).into_iter().flatten() {
                        if level < MESH_LEVELS {
                            slots[k * MESH_LEVELS + level].push(with_fade(i, fade));
                        }
                    }
                }
            }
        }
        for (k, proxy) in world.proxies.iter().enumerate() {
            let slot = &mut slots[world.groups.len() * MESH_LEVELS + k];
            if let Some(lod) = lod {
                for (_, cell) in cells(Level::Fine) {
                    for i in cell.proxies.run(k) {
                        let levels = lod.levels(i.base(), &world.lods[k].errors);
                        for (level, fade) in levels.into_iter().flatten() {
                            if level == MESH_LEVELS && seen(sight, i, proxy.sphere) {
                                slot.push(with_fade(i, fade));
                            }
                        }
                    }
                }
            }
            for (_, cell) in cells(Level::Coarse) {
                slot.extend(
                    cell.proxies
                        .run(k)
                        .iter()
                        .filter(|i| seen(sight, i, proxy.sphere)),
                );
            }
        }
        out.push(
            slots
                .iter()
                .map(|s| bytemuck::cast_slice(s).to_vec())
                .collect(),
        );
    }
    out
}

/// A layout holding every cell `scene` draws, and what the GPU's pool holds by it.
fn pool_of(scene: &Scene) -> (Layout, Vec<InstanceRaw>) {
    let cells: Vec<&Cell> = scene.cells.drawn().map(|(_, c)| c).collect();
    let total: usize = cells
        .iter()
        .map(|c| c.placements.len() + c.proxies.len())
        .sum();
    let mut layout = Layout::with_capacity(total as u32);
    layout.hold(&cells).expect("every cell fits");
    let mut image = vec![InstanceRaw::zeroed(); total];
    for cell in cells {
        let [a, b] = layout.base(cell).expect("held").map(|b| b as usize);
        let (placements, proxies) = (&cell.placements.instances, &cell.proxies.instances);
        image[a..a + placements.len()].copy_from_slice(placements);
        image[b..b + proxies.len()].copy_from_slice(proxies);
    }
    (layout, image)
}

/// What `gathered` holds for each sight, in the reference's shape: its copies, or its
/// picks from `image`, the pool.
fn slots_of(gathered: &Gathered, scene: &Scene, sights: usize, image: &[InstanceRaw]) -> Slots {
    let picked: Vec<InstanceRaw> = (gathered.picks.iter())
        .map(|&[i, fade]| {
            let mut out = image[i as usize];
            out.tint[3] = f32::from_bits(fade);
            out
        })
        .collect();
    let placements = if gathered.picks.is_empty() {
        &gathered.visible
    } else {
        &picked
    };
    (0..sights)
        .map(|s| {
            let mut slots = vec![Vec::new(); scene.world.slots()];
            for r in gathered.ranges(s) {
                let placements = &placements[r.first as usize..(r.first + r.count) as usize];
                slots[r.slot as usize] = bytemuck::cast_slice(placements).to_vec();
            }
            slots
        })
        .collect()
}

fn gather_with(
    threads: usize,
    gathered: &mut Gathered,
    sights: &[Sight],
    lod: Option<LodView>,
    layout: Option<&Layout>,
) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a pool");
    with_scene(|scene| {
        let (world, drawn): (&World, _) = (&scene.world, drawn(scene));
        pool.install(|| gathered.gather_cells(world, &drawn, (sights, lod), layout));
    });
}

#[test]
fn a_frame_gathers_the_same_placements_on_one_thread_as_on_four_and_copied_as_picked() {
    let eye = Vec3::new(120.0, 45.0, 130.0);
    let sights = sights(eye, Vec3::new(1.0, -0.2, 0.6).normalize());
    let (layout, image) = with_scene(pool_of);
    let lod = Some(lod_view(eye));
    let mut gathered: [Gathered; 4] = Default::default();
    gather_with(1, &mut gathered[0], &sights, lod, Some(&layout));
    gather_with(4, &mut gathered[1], &sights, lod, Some(&layout));
    gather_with(1, &mut gathered[2], &sights, lod, None);
    gather_with(4, &mut gathered[3], &sights, lod, None);
    assert!(
        !gathered[0].picks.is_empty(),
        "the view sees some of the forest"
    );
    assert!(gathered[0].visible.is_empty() && gathered[2].picks.is_empty());
    assert_eq!(gathered[0].picks, gathered[1].picks);
    assert_eq!(
        bytemuck::cast_slice::<_, u8>(&gathered[2].visible),
        bytemuck::cast_slice::<_, u8>(&gathered[3].visible)
    );
    with_scene(|scene| {
        let slots = gathered.each_ref().map(|g| slots_of(g, scene, 2, &image));
        assert!(slots.iter().all(|s| *s == slots[0]));
    });
}

/// A layout holds exactly the cells it is given: each in room of its own, all of them
/// again (in the same room) when asked again, none when they do not fit, and the room
/// of a cell no longer drawn is given back.
#[test]
fn a_layout_holds_the_cells_drawn_in_room_of_their_own() {
    with_scene(|scene| {
        let cells: Vec<&Cell> = scene.cells.drawn().map(|(_, c)| c).collect();
        let len = |c: &Cell| (c.placements.len() + c.proxies.len()) as u32;
        let total: u32 = cells.iter().map(|c| len(c)).sum();
        assert!(cells.len() > 2 && total > 0);
        let mut small = Layout::with_capacity(total - 1);
        assert_eq!(small.hold(&cells), Err(u64::from(total)));
        assert!(cells.iter().all(|c| small.base(c).is_none()));

        let mut layout = Layout::with_capacity(total);
        let placed = layout.hold(&cells).expect("they fit");
        assert_eq!(placed.len(), cells.len());
        let mut spans: Vec<(u32, u32)> = (cells.iter())
            .filter(|c| len(c) > 0)
            .map(|c| {
                let [a, b] = layout.base(c).expect("held");
                assert_eq!(b - a, c.placements.len() as u32);
                (a, a + len(c))
            })
            .collect();
        spans.sort_unstable();
        assert!(spans.windows(2).all(|w| w[0].1 <= w[1].0), "{spans:?}");
        assert!(spans.last().is_some_and(|s| s.1 <= total));

        let bases: Vec<_> = cells.iter().map(|c| layout.base(c)).collect();
        assert_eq!(layout.hold(&cells), Ok(Vec::new()), "nothing new to upload");
        let again: Vec<_> = cells.iter().map(|c| layout.base(c)).collect();
        assert_eq!(bases, again);

        // Without the first cell, its room is free for it to come back to.
        let first = cells[0];
        assert_eq!(layout.hold(&cells[1..]), Ok(Vec::new()));
        assert_eq!(layout.base(first), None);
        assert_eq!(layout.hold(&cells).map(|p| p.len()), Ok(1));
    });
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    /// Passing over whole runs and cells, and gathering cells on every core, give the
    /// placements a test of every placement gives, in the same order, from any view,
    /// with and without levels of detail; and a gathering that reuses the last frame's
    /// buffers and picks from the pool gives the same as a fresh one that copies.
    #[test]
    fn gathering_matches_a_placement_by_placement_reference(
        x in 0.0f32..300.0,
        z in 0.0f32..300.0,
        height in 2.0f32..120.0,
        yaw in 0.0f32..std::f32::consts::TAU,
        pitch in -1.2f32..0.3,
        lod in any::<bool>(),
    ) {
        // One gathering kept across cases, as the renderer keeps it across frames.
        static KEPT: Mutex<Option<Gathered>> = Mutex::new(None);
        let eye = Vec3::new(x, height, z);
        let forward = Vec3::new(yaw.cos() * pitch.cos(), pitch.sin(), yaw.sin() * pitch.cos());
        let sights = sights(eye, forward);
        let lod = lod.then(|| lod_view(eye));
        let mut kept = KEPT.lock().unwrap_or_else(PoisonError::into_inner);
        let gathered = kept.get_or_insert_with(Gathered::default);
        let (kept, expected, fresh) = with_scene(|scene| {
            // The kept one picks from the pool, the fresh one copies.
            let (layout, image) = pool_of(scene);
            gathered.gather(scene, (&sights, lod), Some(&layout));
            let mut fresh = Gathered::default();
            fresh.gather(scene, (&sights[..1], lod), None);
            (
                slots_of(gathered, scene, 2, &image),
                reference(scene, &sights, lod),
                slots_of(&fresh, scene, 1, &image),
            )
        });
        prop_assert_eq!(&kept, &expected);
        prop_assert_eq!(&fresh[..], &expected[..1]);
    }
}
