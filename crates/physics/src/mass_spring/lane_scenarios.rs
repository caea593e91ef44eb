//! Whole-world tests of [`MassSpringLanes`]: every lane against the same world stepped alone, bit
//! for bit, through contacts, the ground, tight limits, refused targets, failures and refills.

use super::scenarios::grid;
use super::*;

/// Terrain, an actuated soft block on it, and an actuated rigid block (tight limits) beside it,
/// on the ground when `settings` has one; with the soft and the rigid block's points and the
/// terrain's.
fn scene(settings: MassSpringSettings) -> (MassSpringWorld, Vec<PointId>, Vec<PointId>, Vec<PointId>) {
    let mut b = MassSpringBuilder::new(settings);
    let terrain = grid(&mut b, (0.0, 0.0), (5, 1), true, true, false);
    let soft = grid(&mut b, (0.05, 0.11), (3, 2), false, false, true);
    let rigid = grid(&mut b, (0.55, 0.0), (2, 2), true, false, true);
    for cell in soft.sides.chunks(4).chain(rigid.sides.chunks(4)) {
        b.add_actuator(cell);
    }
    (b.build().unwrap(), soft.points, rigid.points, terrain.points)
}

/// Lane `lane`'s targets at `step`: a square wave of its own phase and period per actuator.
fn gait(lane: usize, step: usize, actuators: usize) -> Vec<f64> {
    (0..actuators)
        .map(|i| match (step + 3 * i + 5 * lane) % (8 + 2 * lane) < 4 + lane {
            true => 1.6,
            false => 0.6,
        })
        .collect()
}

/// Every position, velocity and rest length of two worlds as bits.
fn bits(w: &MassSpringWorld) -> Vec<u64> {
    let parts = [
        w.positions_x(),
        w.positions_y(),
        w.velocities_x(),
        w.velocities_y(),
        w.rest_lengths(),
    ];
    parts.iter().flat_map(|p| p.iter().map(|v| v.to_bits())).collect()
}

/// Steps `laned` (the worlds stepped in lanes) and `alone` (the same worlds stepped alone) with
/// the lanes' gaits for `steps` steps, world `bad` given an infinite target at step 10; every
/// report and every state must agree bit for bit. A world that fails is not stepped again. Returns
/// the step at which each world failed, and its contacts.
fn step_both(
    lanes: &mut MassSpringLanes,
    laned: &mut [MassSpringWorld],
    alone: &mut [MassSpringWorld],
    steps: usize,
    bad: usize,
) -> (Vec<Option<usize>>, Vec<usize>) {
    let actuators = alone[0].actuator_count();
    let (mut failed, mut contacts) = (vec![None; LANES], vec![0; LANES]);
    for step in 0..steps {
        let mut targets: Vec<Vec<f64>> = (0..LANES).map(|l| gait(l, step, actuators)).collect();
        if step == 10 {
            targets[bad][1] = f64::INFINITY;
        }
        let live: Vec<usize> = (0..LANES).filter(|&l| failed[l].is_none()).collect();
        let mut worlds: Vec<&mut MassSpringWorld> = laned
            .iter_mut()
            .enumerate()
            .filter(|(l, _)| failed[*l].is_none())
            .map(|(_, w)| w)
            .collect();
        let lists: Vec<&[f64]> = live.iter().map(|&l| targets[l].as_slice()).collect();
        let out = lanes.step(&mut worlds, &lists).unwrap();
        assert!(out[live.len()..].iter().all(Option::is_none), "lanes without a world");
        for (k, &l) in live.iter().enumerate() {
            let result = alone[l].step(&targets[l]);
            assert_eq!(out[k].as_ref(), Some(&result), "world {l}, step {step}");
            assert!(bits(&laned[l]) == bits(&alone[l]), "world {l}, step {step}: state");
            assert_eq!(laned[l].substeps_done(), alone[l].substeps_done());
            contacts[l] += result.as_ref().map_or(0, |r| r.contacts);
            if matches!(
                result,
                Err(MassSpringError::NonFinite { .. } | MassSpringError::SelfOverlap { .. })
            ) {
                failed[l] = Some(step);
            }
        }
    }
    (failed, contacts)
}

#[test]
fn every_lane_has_the_bits_of_its_world_stepped_alone() {
    for settings in [
        MassSpringSettings::evogym(),
        MassSpringSettings {
            ground: None,
            ..MassSpringSettings::evogym()
        },
    ] {
        let (start, soft, rigid, terrain) = scene(settings);
        let mut alone: Vec<MassSpringWorld> = (0..4).map(|_| start.clone()).collect();
        // worlds start apart: the rigid block of world 1 thrown at the soft one, world 3's soft
        // block squeezed into a corner of itself (it folds: self-overlap)
        for &p in &rigid {
            alone[1].set_velocity(p, -3.0, 0.5);
        }
        for (i, &p) in soft.iter().enumerate() {
            alone[3].set_position(p, 0.1 + 0.001 * (i % 4) as f64, 0.15 + 0.001 * (i / 4) as f64);
        }
        let mut laned = alone.clone();
        let mut lanes = MassSpringLanes::new(&start);
        let (failed, contacts) = step_both(&mut lanes, &mut laned, &mut alone, 120, 2);
        assert!(failed[3].is_some(), "world 3 fails: {failed:?}");
        assert!(failed[..3].iter().all(Option::is_none), "{failed:?}");
        assert!(contacts[..3].iter().all(|&c| c > 0), "contacts: {contacts:?}");
        // the failed world's lane refilled with a fresh episode: it steps as a fresh world alone,
        // also when the new world's terrain was moved by hand (two of its top points raised into
        // the soft block), which the lane must load instead of the terrain it held
        (laned[3], alone[3]) = (start.clone(), start.clone());
        step_both(&mut lanes, &mut laned, &mut alone, 40, 0);
        let mut raised = start.clone();
        for &p in &terrain[7..9] {
            raised.set_position(p, raised.positions_x()[p.index()], 0.14);
        }
        (laned[3], alone[3]) = (raised.clone(), raised);
        let (_, contacts) = step_both(&mut lanes, &mut laned, &mut alone, 40, 0);
        assert!(contacts[3] > 0);
    }
}

#[test]
fn lanes_refuse_worlds_of_another_shape_and_too_many_worlds() {
    let mut a = scene(MassSpringSettings::evogym()).0;
    let mut b = scene(MassSpringSettings {
        ground: None,
        ..MassSpringSettings::evogym()
    })
    .0;
    let mut lanes = MassSpringLanes::new(&a);
    assert!(lanes.fits(&a) && !lanes.fits(&b));
    // a world of another build with the same constants fits, before and after a step remembers
    // its build; one of another shape does not, however often it is asked
    let mut twin = scene(MassSpringSettings::evogym()).0;
    assert!(lanes.fits(&twin));
    let one = vec![1.0; a.actuator_count()];
    assert!(lanes.step(&mut [&mut twin], &[&one]).unwrap()[0]
        .as_ref()
        .unwrap()
        .is_ok());
    assert!(lanes.fits(&twin.clone()));
    assert!(lanes.step(&mut [&mut b], &[&one]).is_err() && !lanes.fits(&b));
    let before = bits(&a);
    let targets = vec![1.0; a.actuator_count()];
    assert!(lanes.step(&mut [&mut a, &mut b], &[&targets, &targets]).is_err());
    assert!(bits(&a) == before, "nothing stepped");
    let mut more = vec![a.clone(); 4];
    let mut five: Vec<&mut MassSpringWorld> = more.iter_mut().collect();
    five.push(&mut a);
    let lists: Vec<&[f64]> = vec![&targets; 5];
    assert!(lanes.step(&mut five, &lists).is_err(), "more worlds than lanes");
    assert!(
        lanes.step(&mut [&mut a], &[&targets, &targets]).is_err(),
        "a list per world"
    );
}
