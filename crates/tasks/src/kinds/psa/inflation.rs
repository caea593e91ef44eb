//! The PSA inflation protocol (thesis §6.4.1, "validation of the mechanical model"): a PSA on flat
//! ground with its springs at rest, its pressure starting at 0 and rising by p_max/100 every step
//! up to p_max; φ = area / (π r²) is recorded at every step. A valid balloon reaches φ ≈ 1.

use crate::agent::Robot;
use crate::episode::EpisodeError;
use crate::kinds::psa::robot::PsaRobot;
use crate::locomotion::place_on_ground;
use crate::terrain::{add_ground, Terrain};
use vsrlab_body::psa::{Psa, PsaParams};
use vsrlab_physics::{PhysicsError, Vec2, WorldBuilder, WorldSettings};

/// One step of the protocol.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InflationPoint {
    /// Simulated time (s).
    pub time: f64,
    /// Pressure over p_max.
    pub pressure_ratio: f64,
    /// Area over that of a circle of the agent's radius.
    pub phi: f64,
}

/// The physics settings of PSA worlds: the engine's defaults at 60 Hz, with the original's
/// gravity of −10 (its Box2D framework's default).
pub fn psa_physics() -> WorldSettings {
    WorldSettings {
        dt: 1.0 / 60.0,
        gravity: Vec2::new(0.0, -10.0),
        ..WorldSettings::default()
    }
}

/// Runs the protocol for `steps` steps (the pressure reaches p_max after 100).
pub fn inflate(params: &PsaParams, physics: &WorldSettings, steps: usize) -> Result<Vec<InflationPoint>, EpisodeError> {
    params.validate().map_err(|e| e.at("body").at("robot"))?;
    let mut builder = WorldBuilder::new(physics.clone());
    let terrain = Terrain::Flat.profile(0);
    add_ground(&mut builder, &terrain);
    let robot = PsaRobot {
        body: vsrlab_body::psa::PsaBody {
            size: Default::default(),
            params: params.clone(),
        },
        brain: vsrlab_brain::BrainSpec::default(),
    };
    let origin = place_on_ground(&terrain, &robot.footprint(), 11.0, 0.5);
    let centre = origin + Vec2::new(params.radius, params.radius);
    let psa = Psa::assemble(&mut builder, params, centre, 1);
    let mut world = builder.build().map_err(|e| EpisodeError::Invalid(e.to_string()))?;
    let p_max = psa.max_pressure();
    let rest = vec![0.0; psa.mass_count()];
    let mut p = 0.0;
    psa.set_pressure(&mut world, p, false);
    let mut points = Vec::with_capacity(steps);
    for _ in 0..steps {
        world.step().map_err(|source| EpisodeError::Physics {
            time: world.time(),
            source,
        })?;
        // springs at rest; the pressure follows the protocol, not the controller
        psa.actuate_springs(&mut world, &rest);
        p = (p + p_max / 100.0).min(p_max);
        psa.set_pressure(&mut world, p, false);
        let phi = psa.area_ratio(&world);
        if !phi.is_finite() {
            return Err(EpisodeError::Physics {
                time: world.time(),
                source: PhysicsError::NonFinite {
                    step: world.step_count(),
                    body: 0,
                },
            });
        }
        points.push(InflationPoint {
            time: world.time(),
            pressure_ratio: p / p_max,
            phi,
        });
    }
    Ok(points)
}
