//! Voxelyze's own validation cases (`test/tVoxelyze.h`, listed with their setups, expected
//! values and tolerances in `docs/voxelyze-model.md` §11), as tests of this engine.

use crate::{Dof, Material, VoxelId, World, WorldSettings, STANDARD_GRAVITY};
use glam::DVec3;

/// Voxelyze's test lattice: 1 mm voxels, no gravity, no floor.
fn world() -> World {
    World::new(WorldSettings {
        voxel_size: 1e-3,
        gravity: 0.0,
        floor: false,
        collisions: false,
    })
    .unwrap()
}

fn material(world: &mut World, internal: f64, global: f64) -> usize {
    world
        .add_material(Material {
            internal_damping: internal,
            global_damping: global,
            ..Material::voxelyze(1e6, 1e3)
        })
        .unwrap()
}

/// What a two-voxel case reads: a displacement or a rotation component.
#[derive(Clone, Copy)]
enum Read {
    T(usize),
    R(usize),
}

/// Voxelyze's `test2Vox`: voxel 1 fixed at the origin, voxel 2 one step along `dir` loaded with
/// `force` and `moment`, every DOF fixed except `free`; steps until 10 consecutive readings are
/// within 1e-5 of `expected` (relative); returns that step (1000 if never).
fn two_voxels(dir: [i32; 3], force: DVec3, moment: DVec3, free: &[Dof], read: Read, expected: f64) -> usize {
    let mut w = world();
    let m = material(&mut w, 1.0, 0.2);
    let a = w.add_voxel(m, [0, 0, 0]).unwrap();
    let b = w.add_voxel(m, dir).unwrap();
    w.set_fixed(a, &Dof::ALL, true);
    w.set_fixed(b, &Dof::ALL, true);
    w.set_fixed(b, free, false);
    w.set_external(b, force, moment);
    let dt = w.recommended_time_step();
    let mut run = 0;
    for k in 0..1000 {
        w.step(dt).unwrap();
        let data = match read {
            Read::T(i) => w.displacement(b)[i],
            Read::R(i) => w.rotation(b)[i],
        };
        let close = (data - expected).abs() < expected.abs() * 1e-5 || (data as f32) == (expected as f32);
        run = if close { run + 1 } else { 0 };
        if run == 10 {
            return k;
        }
    }
    1000
}

/// A two-voxel case: load force and moment, free DOFs, what is read, expected value, step limit.
type Case = (DVec3, DVec3, &'static [Dof], Read, f64, usize);
/// The same with the direction of the second voxel.
type DirectedCase = ([i32; 3], DVec3, DVec3, &'static [Dof], Read, f64, usize);

/// Runs every two-voxel case and checks each reaches its value within its step limit.
fn assert_reached_in_time(cases: impl IntoIterator<Item = DirectedCase>) {
    for (i, (dir, f, m, free, read, expected, limit)) in cases.into_iter().enumerate() {
        let k = two_voxels(dir, f, m, free, read, expected);
        assert!(k < limit, "case {i} {dir:?}: {k} steps (limit {limit})");
    }
}

const F: f64 = 1e-3;
const M: f64 = 1e-9;

#[test]
fn a_single_bond_deflects_as_a_beam_axially_transversely_and_in_torsion() {
    let x = [1, 0, 0];
    let cases: [Case; 8] = [
        (DVec3::new(F, 0.0, 0.0), DVec3::ZERO, &[Dof::Tx], Read::T(0), 1e-6, 150),
        (
            DVec3::new(-F, 0.0, 0.0),
            DVec3::ZERO,
            &[Dof::Tx],
            Read::T(0),
            -1e-6,
            150,
        ),
        (DVec3::new(0.0, F, 0.0), DVec3::ZERO, &[Dof::Ty], Read::T(1), 1e-6, 150),
        (
            DVec3::new(0.0, 0.0, -F),
            DVec3::ZERO,
            &[Dof::Tz],
            Read::T(2),
            -1e-6,
            150,
        ),
        (
            DVec3::ZERO,
            DVec3::new(M, 0.0, 0.0),
            &[Dof::Rx],
            Read::R(0),
            1.2e-5,
            200,
        ),
        (DVec3::ZERO, DVec3::new(0.0, M, 0.0), &[Dof::Ry], Read::R(1), 3e-6, 200),
        (
            DVec3::ZERO,
            DVec3::new(0.0, 0.0, -M),
            &[Dof::Rz],
            Read::R(2),
            -3e-6,
            200,
        ),
        (
            DVec3::ZERO,
            DVec3::new(M, 0.0, 0.0),
            &[Dof::Tx, Dof::Rx],
            Read::R(0),
            1.2e-5,
            200,
        ),
    ];
    assert_reached_in_time(cases.into_iter().map(|c| (x, c.0, c.1, c.2, c.3, c.4, c.5)));
}

#[test]
fn end_loads_give_the_cantilever_slopes_and_deflections() {
    let x = [1, 0, 0];
    // an end moment bends the free end down by M L² / (2 E I); an end force turns it by F L² / (2 E I)
    let cases: [Case; 4] = [
        (
            DVec3::ZERO,
            DVec3::new(0.0, M, 0.0),
            &[Dof::Tz, Dof::Ry],
            Read::T(2),
            -6e-9,
            300,
        ),
        (
            DVec3::ZERO,
            DVec3::new(0.0, 0.0, M),
            &[Dof::Ty, Dof::Rz],
            Read::T(1),
            6e-9,
            300,
        ),
        (
            DVec3::new(0.0, F, 0.0),
            DVec3::ZERO,
            &[Dof::Ty, Dof::Rz],
            Read::R(2),
            6e-3,
            300,
        ),
        (
            DVec3::new(0.0, 0.0, F),
            DVec3::ZERO,
            &[Dof::Tz, Dof::Ry],
            Read::R(1),
            -6e-3,
            300,
        ),
    ];
    assert_reached_in_time(cases.into_iter().map(|c| (x, c.0, c.1, c.2, c.3, c.4, c.5)));
    // torsion gives no axial motion
    assert!(
        two_voxels(
            x,
            DVec3::ZERO,
            DVec3::new(M, 0.0, 0.0),
            &[Dof::Tx, Dof::Rx],
            Read::T(0),
            0.0
        ) < 10
    );
}

#[test]
fn links_along_every_axis_and_direction_behave_alike() {
    // a force along the link is axial, across it transverse: both 1e-6 m; a moment along the
    // link is torsion (1.2e-5 rad), across it bending (3e-6 rad)
    let cases: [DirectedCase; 8] = [
        (
            [-1, 0, 0],
            DVec3::new(F, 0.0, 0.0),
            DVec3::ZERO,
            &[Dof::Tx],
            Read::T(0),
            1e-6,
            150,
        ),
        (
            [0, 1, 0],
            DVec3::new(F, 0.0, 0.0),
            DVec3::ZERO,
            &[Dof::Tx],
            Read::T(0),
            1e-6,
            150,
        ),
        (
            [0, -1, 0],
            DVec3::new(0.0, F, 0.0),
            DVec3::ZERO,
            &[Dof::Ty],
            Read::T(1),
            1e-6,
            150,
        ),
        (
            [0, 0, 1],
            DVec3::new(0.0, 0.0, F),
            DVec3::ZERO,
            &[Dof::Tz],
            Read::T(2),
            1e-6,
            150,
        ),
        (
            [0, 1, 0],
            DVec3::ZERO,
            DVec3::new(0.0, M, 0.0),
            &[Dof::Ry],
            Read::R(1),
            1.2e-5,
            200,
        ),
        (
            [0, 1, 0],
            DVec3::ZERO,
            DVec3::new(M, 0.0, 0.0),
            &[Dof::Rx],
            Read::R(0),
            3e-6,
            200,
        ),
        (
            [0, 0, -1],
            DVec3::ZERO,
            DVec3::new(0.0, 0.0, M),
            &[Dof::Rz],
            Read::R(2),
            1.2e-5,
            200,
        ),
        (
            [0, 0, -1],
            DVec3::ZERO,
            DVec3::new(M, 0.0, 0.0),
            &[Dof::Rx],
            Read::R(0),
            3e-6,
            100,
        ),
    ];
    assert_reached_in_time(cases);
}

/// A line of voxels along x, the first fixed; returns the world and the voxels.
fn line(n: i32, moduli: &dyn Fn(i32) -> f64, internal: f64, global: f64) -> (World, Vec<VoxelId>) {
    let mut w = world();
    let mut ids = Vec::new();
    for i in 0..n {
        let m = w
            .add_material(Material {
                internal_damping: internal,
                global_damping: global,
                ..Material::voxelyze(moduli(i), 1e3)
            })
            .unwrap();
        ids.push(w.add_voxel(m, [i, 0, 0]).unwrap());
    }
    w.set_fixed(ids[0], &Dof::ALL, true);
    (w, ids)
}

fn run(w: &mut World, steps: usize) {
    let dt = w.recommended_time_step();
    for _ in 0..steps {
        w.step(dt).unwrap();
    }
}

/// globalDamping (b): a two-voxel cantilever under (1e-6, 1e-6, 1e-6) N deflects F L³ / (3 E I)
/// = 4e-9 m sideways after 300 steps.
#[test]
fn a_cantilever_tip_deflects_f_l3_over_3_e_i() {
    let (mut w, ids) = line(2, &|_| 1e6, 0.0, 0.25);
    w.set_external(ids[1], DVec3::splat(1e-6), DVec3::ZERO);
    run(&mut w, 300);
    let y = w.displacement(ids[1]).y;
    assert!((y - 4e-9).abs() < 4e-9 * 1e-6, "{y:e}");
}

/// doubleBondCantilever: three voxels, the tip guided, ±5e-6 N: axial ±1e-8 m within 200 steps,
/// transverse ±1.6e-7 m = F (2L)³ / (3 E I) within 500 (relative 1e-4, 10 readings in a row).
#[test]
fn a_two_link_cantilever_is_exact_for_an_end_load() {
    for (axis, expected, limit) in [(0, 1e-8, 200), (1, 1.6e-7, 500), (2, 1.6e-7, 500)] {
        for sign in [1.0, -1.0] {
            let (mut w, ids) = line(3, &|_| 1e6, 1.0, 0.1);
            let tip = ids[2];
            let free = match axis {
                0 => vec![Dof::Tx],
                1 => vec![Dof::Ty, Dof::Rz],
                _ => vec![Dof::Tz, Dof::Ry],
            };
            w.set_fixed(tip, &Dof::ALL, true);
            w.set_fixed(tip, &free, false);
            let mut f = DVec3::ZERO;
            f[axis] = sign * 5e-6;
            w.set_external(tip, f, DVec3::ZERO);
            let dt = w.recommended_time_step();
            let (mut streak, mut reached) = (0, None);
            for k in 0..3000 {
                w.step(dt).unwrap();
                let d = w.displacement(tip)[axis];
                streak = if (d - sign * expected).abs() < expected * 1e-4 {
                    streak + 1
                } else {
                    0
                };
                if streak == 10 {
                    reached = Some(k);
                    break;
                }
            }
            assert!(
                reached.is_some_and(|k| k < limit),
                "axis {axis} sign {sign}: {reached:?}"
            );
        }
    }
}

/// freqency: an undamped two-voxel spring vibrates with period 2π / √(k/m) = 1.98692e-4 s
/// (within 1/1000), stepped at a tenth of the recommended step.
#[test]
fn the_axial_natural_period_is_two_pi_over_omega() {
    let (mut w, ids) = line(2, &|_| 1e6, 0.0, 0.0);
    let b = ids[1];
    w.set_fixed(b, &Dof::ALL, true);
    w.set_fixed(b, &[Dof::Tx], false);
    w.set_external(b, DVec3::new(1e-3, 0.0, 0.0), DVec3::ZERO);
    let dt = w.recommended_time_step() / 10.0;
    let mut samples = Vec::new();
    for _ in 0..1000 {
        w.step(dt).unwrap();
        samples.push(w.position(b).x - 0.001001);
    }
    let crossings: Vec<f64> = samples
        .windows(2)
        .enumerate()
        .filter(|(_, s)| (s[0] < 0.0) != (s[1] < 0.0))
        .map(|(k, s)| (k as f64 + s[0] / (s[0] - s[1])) * dt)
        .collect();
    assert!(crossings.len() > 4, "{} crossings", crossings.len());
    let period = 2.0 * (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64;
    let expected = 2.0 * std::f64::consts::PI / 1e9f64.sqrt();
    assert!(
        (period - expected).abs() < expected / 1000.0,
        "{period:e} vs {expected:e}"
    );
}

/// multiSimple: four voxels of alternating E 1e6 / 1e9; three mixed links in series stretch
/// 1.5015e-6 m under 1e-3 N after 800 steps.
#[test]
fn links_of_two_materials_take_the_harmonic_mean_modulus() {
    let (mut w, ids) = line(4, &|i| if i % 2 == 0 { 1e6 } else { 1e9 }, 0.01, 0.03);
    w.set_external(ids[3], DVec3::new(1e-3, 0.0, 0.0), DVec3::ZERO);
    run(&mut w, 800);
    let x = w.displacement(ids[3]).x;
    assert!((x - 1.5015e-6).abs() < 1.5015e-6 * 1e-6, "{x:e}");
}

/// internalDamping: a voxel held by six fixed face neighbours under 1e-6 N per axis settles at
/// 1e-9 / 6 m along y in 100 steps (stiffness 6000 N/m per axis).
#[test]
fn a_voxel_among_six_fixed_neighbours_is_six_times_as_stiff() {
    let mut w = world();
    let m = material(&mut w, 1.0, 0.0);
    let centre = w.add_voxel(m, [0, 0, 0]).unwrap();
    for d in [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]] {
        let v = w.add_voxel(m, d).unwrap();
        w.set_fixed(v, &Dof::ALL, true);
    }
    w.set_external(centre, DVec3::splat(1e-6), DVec3::ZERO);
    run(&mut w, 100);
    let y = w.displacement(centre).y;
    assert!((y - 1e-9 / 6.0).abs() < 1e-9 / 6.0 * 1e-6, "{y:e}");
}

/// temperature: a bimetal strip (a row that expands 5 % over a stiff inert row, both clamped
/// at x = 0) bends its tip up 2.55e-5 m in 500 steps, and down 2.591e-5 m when cooled
/// (Voxelyze's tolerance 1e-8 m).
#[test]
fn a_bimetal_strip_bends_toward_the_inert_layer() {
    for (temperature, expected) in [(5.0, 2.55e-5), (-5.0, -2.591e-5)] {
        let mut w = world();
        let hot = w
            .add_material(Material {
                cte: 0.01,
                global_damping: 0.15,
                ..Material::voxelyze(1e6, 1e3)
            })
            .unwrap();
        let inert = w
            .add_material(Material {
                global_damping: 0.15,
                ..Material::voxelyze(1e7, 1e3)
            })
            .unwrap();
        let mut bottom = Vec::new();
        for x in 0..3 {
            bottom.push(w.add_voxel(hot, [x, 0, 0]).unwrap());
            let top = w.add_voxel(inert, [x, 0, 1]).unwrap();
            if x == 0 {
                w.set_fixed(top, &Dof::ALL, true);
            }
        }
        w.set_fixed(bottom[0], &Dof::ALL, true);
        for &v in &bottom {
            w.set_temperature(v, temperature);
        }
        run(&mut w, 500);
        let z = w.displacement(bottom[2]).z;
        assert!((z - expected).abs() < 1e-8, "T {temperature}: {z:e} vs {expected:e}");
    }
}

/// largeDeformationDamping: a 0.2 N oblique tip load, far past small angles, settles the tip at
/// z = 9.5587e-4 m after 200 steps (±1e-7).
#[test]
fn a_large_deflection_goes_through_the_large_angle_mode() {
    let (mut w, ids) = line(2, &|_| 1e6, 1.0, 0.2);
    w.set_external(ids[1], DVec3::new(-0.2, 0.0, 0.2), DVec3::ZERO);
    run(&mut w, 200);
    let z = w.position(ids[1]).z;
    assert!((z - 9.5587e-4).abs() < 1e-7, "{z:e}");
}

/// One voxel on the floor with gravity (μs 1, μk 0.1, global damping 1): after settling, a
/// horizontal force of c·N holds it still for c below μs·(g multiple) and moves it above.
#[test]
fn static_friction_holds_below_mu_n_and_slips_above() {
    for (g, mu, c, moves) in [
        (1.0, 1.0, 0.9, false),
        (1.0, 1.0, 1.1, true),
        (2.0, 1.0, 1.9, false),
        (2.0, 1.0, 2.1, true),
        (1.0, 2.0, 1.9, false),
        (1.0, 2.0, 2.1, true),
    ] {
        let mut w = World::new(WorldSettings {
            voxel_size: 1e-3,
            gravity: g * STANDARD_GRAVITY,
            floor: true,
            collisions: false,
        })
        .unwrap();
        let m = w
            .add_material(Material {
                static_friction: mu,
                kinetic_friction: 0.1,
                global_damping: 1.0,
                ..Material::voxelyze(1e6, 1e3)
            })
            .unwrap();
        let v = w.add_voxel(m, [0, 0, 0]).unwrap();
        run(&mut w, 50);
        let n0 = 1e3 * 1e-9 * STANDARD_GRAVITY;
        w.set_external(v, DVec3::new(c * n0, 0.0, 0.0), DVec3::ZERO);
        run(&mut w, 10);
        let x = w.displacement(v).x;
        assert_eq!(x != 0.0, moves, "g {g} μs {mu} c {c}: x {x:e}");
    }
}

/// kineticFriction: sliding under 2N with μk 0.1 turns the work of the net force into kinetic
/// energy (within 2e-16 J over 10 steps).
#[test]
fn kinetic_friction_work_balances_kinetic_energy() {
    let mut w = World::new(WorldSettings {
        voxel_size: 1e-3,
        gravity: STANDARD_GRAVITY,
        floor: true,
        collisions: false,
    })
    .unwrap();
    let settle = w
        .add_material(Material {
            static_friction: 1.0,
            kinetic_friction: 0.1,
            global_damping: 1.0,
            ..Material::voxelyze(1e6, 1e3)
        })
        .unwrap();
    let v = w.add_voxel(settle, [0, 0, 0]).unwrap();
    run(&mut w, 50);
    // Voxelyze lowers the global damping to 1e-4 for the sliding phase
    let mut sliding = w.clone();
    sliding.materials[settle].global_damping = 1e-4;
    let n0 = 1e3 * 1e-9 * STANDARD_GRAVITY;
    sliding.set_external(v, DVec3::new(2.0 * n0, 0.0, 0.0), DVec3::ZERO);
    let dt = sliding.recommended_time_step();
    let mut energy = 0.0;
    let mut last = 0.0;
    for step in 0..10 {
        let x0 = sliding.position(v).x;
        sliding.step(dt).unwrap();
        last = sliding.position(v).x - x0;
        let weight = if step == 9 { 0.5 } else { 1.0 };
        energy += weight * (2.0 * n0 - 0.1 * n0) * last;
    }
    let speed = last / dt;
    let kinetic = 0.5 * 1e-6 * speed * speed;
    assert!((energy - kinetic).abs() < 2e-16, "{energy:e} vs {kinetic:e}");
}

/// A voxel dropped from 2 mm comes to rest on the floor and stays where it landed.
#[test]
fn a_dropped_voxel_comes_to_rest_without_drift() {
    let mut w = World::new(WorldSettings {
        voxel_size: 0.01,
        gravity: STANDARD_GRAVITY,
        floor: true,
        collisions: true,
    })
    .unwrap();
    let m = w.add_material(Material::affordance()).unwrap();
    let v = w.add_voxel(m, [0, 0, 0]).unwrap();
    w.set_position(v, DVec3::new(0.0, 0.0, 0.002));
    let dt = 0.95 * w.recommended_time_step();
    for _ in 0..40_000 {
        w.step(dt).unwrap();
    }
    let p = w.position(v);
    let rest = 1e-5 * STANDARD_GRAVITY / (2.0 * 1e4 * 0.01);
    assert!((p.z + rest).abs() < 1e-8, "z {:e} vs {:e}", p.z, -rest);
    assert_eq!((p.x, p.y), (0.0, 0.0));
    assert!(w.velocity(v).length() < 1e-6);
}

/// Numbers uniform in [0, 1) from `seed` (a 64-bit LCG's high bits): the tests' random bodies,
/// loads and bends.
#[cfg(test)]
pub(crate) fn uniform(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The piece connected to the first filled cell of a random fill (`fill`: each cell's chance,
/// drawn from `next`) of a side³ box: a random connected body.
pub(crate) fn random_piece(next: &mut impl FnMut() -> f64, side: i32, fill: f64) -> Vec<[i32; 3]> {
    let mut cells = Vec::new();
    for x in 0..side {
        for y in 0..side {
            for z in 0..side {
                if next() < fill {
                    cells.push([x, y, z]);
                }
            }
        }
    }
    if cells.is_empty() {
        cells.push([0, 0, 0]);
    }
    let mut keep = vec![cells[0]];
    let mut i = 0;
    while i < keep.len() {
        let c = keep[i];
        for d in [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]] {
            let n = [c[0] + d[0], c[1] + d[1], c[2] + d[2]];
            if cells.contains(&n) && !keep.contains(&n) {
                keep.push(n);
            }
        }
        i += 1;
    }
    keep
}

/// Random connected bodies of the affordance material, up to 6 × 6 × 6, collisions on, on the
/// floor under random thermal actuation (every voxel's temperature redrawn in ±14.4714 every
/// 0.05 s) for 0.3 s: every step succeeds and every state stays finite. (The 5 s campaign over 24
/// bodies is `--example robustness3d`.)
#[test]
fn random_bodies_under_random_actuation_stay_finite() {
    let mut next = uniform(0x5EED);
    for body in 0..5 {
        let keep = random_piece(&mut next, 2 + body, 0.6);
        let mut w = World::new(WorldSettings::default()).unwrap();
        let m = w.add_material(Material::affordance()).unwrap();
        let ids: Vec<VoxelId> = keep.iter().map(|&c| w.add_voxel(m, c).unwrap()).collect();
        let dt = 0.95 * w.recommended_time_step();
        let per_draw = (0.05 / dt) as usize;
        for step in 0..(0.3 / dt) as usize {
            if step % per_draw == 0 {
                for &v in &ids {
                    w.set_temperature(v, 14.4714 * (2.0 * next() - 1.0));
                }
            }
            w.step(dt)
                .unwrap_or_else(|e| panic!("body {body} ({} voxels), step {step}: {e}", ids.len()));
        }
        for &v in &ids {
            let (p, q) = (w.position(v), w.orientation(v));
            assert!(
                p.is_finite() && q.is_finite() && w.velocity(v).is_finite(),
                "body {body}"
            );
            assert!(p.z > -0.01, "body {body}: a voxel sank through the floor to {p}");
        }
    }
}

/// A free voxel dropped onto a fixed one (a wall voxel, not linked to it: one empty cell between
/// them) comes to rest on it, centres 1.25 s apart less the sag m g / k of the contact spring;
/// without collisions it falls past.
#[test]
fn a_voxel_dropped_on_a_fixed_voxel_rests_on_it() {
    let drop = |collisions: bool| {
        let mut w = World::new(WorldSettings {
            floor: false,
            collisions,
            ..WorldSettings::default()
        })
        .unwrap();
        let m = w
            .add_material(Material {
                collision_damping: 1.0,
                ..Material::affordance()
            })
            .unwrap();
        let wall = w.add_voxel(m, [0, 0, 0]).unwrap();
        w.set_fixed(wall, &Dof::ALL, true);
        let v = w.add_voxel(m, [0, 0, 2]).unwrap();
        let dt = 0.95 * w.recommended_time_step();
        for _ in 0..(1.0 / dt) as usize {
            w.step(dt).unwrap();
        }
        (w.position(v), w.velocity(v), w.mass(v), w.touches_voxel(v))
    };
    let (p, v, mass, touching) = drop(true);
    let s = 0.01;
    let k = 2.0 * 1e4 * s;
    let expected = 1.25 * s - mass * STANDARD_GRAVITY / k;
    assert!((p.z - expected).abs() < 1e-6 * s, "z {} vs {expected}", p.z);
    assert!(v.length() < 1e-6, "{v}");
    assert!(touching);
    let (p, _, _, touching) = drop(false);
    assert!(p.z < -s, "without collisions it falls past: {}", p.z);
    assert!(!touching);
}

/// Stepped far beyond its stable time step, a body diverges: the step that finds it says so
/// (`Diverged`), and no step before it returned a non-finite state.
#[test]
fn an_unstable_step_is_an_error_never_a_nan_state() {
    let mut w = World::new(WorldSettings::default()).unwrap();
    let m = w.add_material(Material::affordance()).unwrap();
    let ids: Vec<VoxelId> = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [1, 1, 1]]
        .iter()
        .map(|&c| w.add_voxel(m, c).unwrap())
        .collect();
    w.set_temperature(ids[3], 14.4714);
    let dt = 5.0 * w.recommended_time_step();
    let mut failed = None;
    for step in 0..100_000 {
        match w.step(dt) {
            Ok(()) => assert!(
                ids.iter()
                    .all(|&v| w.position(v).is_finite() && w.orientation(v).is_finite()),
                "step {step} returned a non-finite state"
            ),
            Err(e) => {
                failed = Some(e);
                break;
            }
        }
    }
    assert!(
        matches!(failed, Some(crate::Physics3dError::Diverged { .. })),
        "{failed:?}"
    );
}
