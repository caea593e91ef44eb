//! Shared helpers for the integration tests.
#![allow(dead_code)]

use vsrlab_body::sensors::SensorConfig;
use vsrlab_body::{Morphology, Preset};
use vsrlab_brain::{BrainSpec, PhaseSpec};
use vsrlab_tasks::{Locomotion, RobotSpec, Terrain};

pub fn robot(body: &str, preset: Preset, brain: BrainSpec) -> RobotSpec {
    RobotSpec {
        body: Morphology::parse(body).unwrap(),
        preset,
        voxel: None,
        sensors: SensorConfig::parse("uniform-a+vxy+t-0").unwrap(),
        brain,
    }
}

pub fn task(terrain: &str, duration: f64) -> Locomotion {
    Locomotion {
        terrain: terrain.parse::<Terrain>().unwrap(),
        duration,
        ..Default::default()
    }
}

pub fn phase() -> BrainSpec {
    BrainSpec::default()
}

pub fn sine() -> BrainSpec {
    BrainSpec::Phase(PhaseSpec {
        frequency: 1.0,
        amplitude: 1.0,
        phase_x: 0.0,
        phase_y: 0.0,
    })
}
