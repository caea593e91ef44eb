//! The assembled PSA body: n square masses on a circle, joined in a ring by springs, around a gas
//! whose pressure pushes every edge outward (thesis §6.2.1).
//!
//! Actuators, in order: one per spring (spring i joins mass i and mass i+1), then the gas.
//! A spring value s ∈ [−1, 1] sets the target length (thesis eq. 6.1: s = 1 shortest, s = −1
//! longest, linear in between); the gas value is Δp (N/m), added to the pressure and clipped to
//! [p_min, p_max]. Without pressure control the gas value is ignored and p = nRT/A every step.

use super::params::{PressureLength, PsaParams};
use crate::body::Body;
use crate::robot::VoxelState;
use vsrlab_physics::{
    EdgeLength, PartDesc, PartHandle, Polygon, PressureRingDesc, RingHandle, SpringDesc, SpringHandle, SpringMassModel,
    Vec2, World, WorldBuilder,
};

/// A pressure-based soft agent in a world.
#[derive(Debug, Clone)]
pub struct Psa {
    params: PsaParams,
    masses: Vec<PartHandle>,
    springs: Vec<SpringHandle>,
    ring: RingHandle,
    rest: f64,
    max_pressure: f64,
    min_pressure: f64,
    n_r_t: f64,
}

impl Psa {
    /// Adds the masses, springs and gas to `builder`, the circle's centre at `centre`. The
    /// parameters must be valid ([`PsaParams::validate`]).
    pub fn assemble(builder: &mut WorldBuilder, params: &PsaParams, centre: Vec2, group: u32) -> Psa {
        let n = params.masses;
        let density = params.density;
        let masses: Vec<PartHandle> = (0..n)
            .map(|i| {
                let a = 2.0 * std::f64::consts::PI * i as f64 / n as f64;
                let at = centre + Vec2::new(a.cos(), a.sin()) * params.radius;
                let square = Polygon::square(Vec2::ZERO, params.mass_side);
                builder.add_part(
                    PartDesc::new(at, square)
                        .density(density)
                        .friction(params.friction)
                        .group(group, true)
                        .fixed_rotation(),
                )
            })
            .collect();
        let rest = params.rest_length();
        let springs: Vec<SpringHandle> = (0..n)
            .map(|i| {
                builder.add_spring(SpringDesc {
                    part_a: masses[i],
                    anchor_a: Vec2::ZERO,
                    part_b: masses[(i + 1) % n],
                    anchor_b: Vec2::ZERO,
                    rest_length: rest,
                    frequency: params.spring_frequency,
                    damping_ratio: params.spring_damping,
                    mass_model: SpringMassModel::ReducedMass,
                    collide_connected: false,
                })
            })
            .collect();
        let initial = params.n_r_t() / params.initial_area();
        let max_pressure = params.max_pressure();
        let min_pressure = params.min_pressure();
        let (length, ring_springs) = match params.pressure_length {
            PressureLength::Actual => (EdgeLength::Actual, Vec::new()),
            PressureLength::Target => (EdgeLength::SpringRest, springs.clone()),
        };
        let pressure = if params.pressure_control {
            initial.clamp(min_pressure, max_pressure)
        } else {
            initial
        };
        let ring = builder.add_pressure_ring(PressureRingDesc {
            parts: masses.clone(),
            length,
            springs: ring_springs,
            pressure,
        });
        Psa {
            params: params.clone(),
            masses,
            springs,
            ring,
            rest,
            max_pressure,
            min_pressure,
            n_r_t: params.n_r_t(),
        }
    }

    /// The constants.
    pub fn params(&self) -> &PsaParams {
        &self.params
    }
    /// The masses, in ring order.
    pub fn masses(&self) -> &[PartHandle] {
        &self.masses
    }
    /// Number of masses.
    pub fn mass_count(&self) -> usize {
        self.masses.len()
    }
    /// Current pressure (N/m).
    pub fn pressure(&self, world: &World) -> f64 {
        world.ring_pressure(self.ring)
    }
    /// Largest pressure p_max (N/m).
    pub fn max_pressure(&self) -> f64 {
        self.max_pressure
    }
    /// Area enclosed by the mass centres now (m²).
    pub fn area(&self, world: &World) -> f64 {
        world.ring_area(self.ring)
    }
    /// φ: the enclosed area over that of a circle of the agent's radius (thesis §6.4.1).
    pub fn area_ratio(&self, world: &World) -> f64 {
        self.area(world) / (std::f64::consts::PI * self.params.radius * self.params.radius)
    }
    /// Sets the pressure directly, clipped to [p_min, p_max] (the inflation protocol starts at 0,
    /// below p_min: `clip = false` allows that).
    pub fn set_pressure(&self, world: &mut World, p: f64, clip: bool) {
        let p = if clip {
            p.clamp(self.min_pressure, self.max_pressure)
        } else {
            p.min(self.max_pressure)
        };
        world.set_ring_pressure(self.ring, p);
    }

    /// Target length of a spring for a control value s ∈ [−1, 1] (thesis eq. 6.1).
    fn target_length(&self, s: f64) -> f64 {
        let s = if s.is_finite() { s.clamp(-1.0, 1.0) } else { 0.0 };
        let l = self.rest;
        if s > 0.0 {
            l - s * (l - self.params.min_length * l)
        } else {
            l - s * (self.params.max_length * l - l)
        }
    }
}

impl Psa {
    /// Sets every spring's target length from its control value (one per spring), whether or
    /// not the brain controls the springs (the inflation protocol holds them at rest).
    pub fn actuate_springs(&self, world: &mut World, values: &[f64]) {
        for (h, &s) in self.springs.iter().zip(values) {
            world.set_spring_rest_length(*h, self.target_length(s));
        }
    }
}

impl Body for Psa {
    fn actuator_count(&self) -> usize {
        self.masses.len() + 1
    }

    fn actuate(&self, world: &mut World, values: &[f64]) {
        let n = self.masses.len();
        if self.params.spring_control {
            self.actuate_springs(world, &values[..n]);
        }
        if self.params.pressure_control {
            let dp = values[n];
            let dp = if dp.is_finite() { dp } else { 0.0 };
            let p = self.pressure(world) + dp;
            world.set_ring_pressure(self.ring, p.clamp(self.min_pressure, self.max_pressure));
        } else {
            let area = self.area(world).max(1e-9);
            world.set_ring_pressure(self.ring, self.n_r_t / area);
        }
    }

    fn center(&self, world: &World) -> Vec2 {
        let sum = self
            .masses
            .iter()
            .fold(Vec2::ZERO, |acc, &m| acc + world.part_position(m));
        sum / self.masses.len() as f64
    }

    fn sensing_units(&self) -> usize {
        self.masses.len()
    }

    fn unit_state(&self, world: &World, i: usize) -> VoxelState {
        let m = self.masses[i];
        let c = world.part_position(m);
        let h = 0.5 * self.params.mass_side;
        VoxelState {
            polygon: [
                c + Vec2::new(-h, h),
                c + Vec2::new(h, h),
                c + Vec2::new(h, -h),
                c + Vec2::new(-h, -h),
            ],
            area_ratio: 1.0,
            center: c,
            velocity: world.part_velocity(m),
            angle: 0.0,
            touching: world.part_touching(m),
        }
    }

    /// The membrane (one polygon through the mass centres), then each mass's square.
    fn outline_corners(&self) -> Vec<usize> {
        let n = self.masses.len();
        std::iter::once(n).chain(std::iter::repeat_n(4, n)).collect()
    }

    fn outline(&self, world: &World, out: &mut Vec<Vec2>) {
        out.extend(self.masses.iter().map(|&m| world.part_position(m)));
        let h = 0.5 * self.params.mass_side;
        for &m in &self.masses {
            let c = world.part_position(m);
            out.extend([
                c + Vec2::new(-h, -h),
                c + Vec2::new(h, -h),
                c + Vec2::new(h, h),
                c + Vec2::new(-h, h),
            ]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::psa::params::PsaSize;
    use vsrlab_physics::WorldSettings;

    fn world_with(params: &PsaParams) -> (World, Psa) {
        let mut b = WorldBuilder::new(WorldSettings::default());
        let psa = Psa::assemble(&mut b, params, Vec2::new(0.0, 20.0), 1);
        (b.build().unwrap(), psa)
    }

    #[test]
    fn spring_targets_follow_thesis_equation_6_1() {
        let (_, psa) = world_with(&PsaParams::of_size(PsaSize::Medium));
        let l = psa.params().rest_length();
        assert!((psa.target_length(1.0) - 0.75 * l).abs() < 1e-12);
        assert!((psa.target_length(-1.0) - 1.25 * l).abs() < 1e-12);
        assert!((psa.target_length(0.0) - l).abs() < 1e-12);
        assert!((psa.target_length(0.5) - 0.875 * l).abs() < 1e-12);
        assert!((psa.target_length(f64::NAN) - l).abs() < 1e-12);
    }

    #[test]
    fn pressure_is_added_and_clipped_or_follows_the_gas_law() {
        let params = PsaParams::of_size(PsaSize::Small);
        let (mut w, psa) = world_with(&params);
        let n = psa.mass_count();
        let p0 = psa.pressure(&w);
        assert!((p0 - params.n_r_t() / params.initial_area()).abs() < 1e-9 * p0);
        let mut values = vec![0.0; n + 1];
        values[n] = 100.0;
        psa.actuate(&mut w, &values);
        assert!((psa.pressure(&w) - (p0 + 100.0)).abs() < 1e-9);
        values[n] = 1e12;
        psa.actuate(&mut w, &values);
        assert_eq!(psa.pressure(&w), params.max_pressure());
        values[n] = -1e12;
        psa.actuate(&mut w, &values);
        assert_eq!(psa.pressure(&w), params.min_pressure());

        let ideal = PsaParams {
            pressure_control: false,
            ..params.clone()
        };
        let (mut w, psa) = world_with(&ideal);
        values[n] = 1e12;
        psa.actuate(&mut w, &values);
        let expected = ideal.n_r_t() / psa.area(&w);
        assert!((psa.pressure(&w) - expected).abs() < 1e-9 * expected);
    }

    #[test]
    fn outline_is_the_membrane_then_the_squares() {
        let (w, psa) = world_with(&PsaParams::of_size(PsaSize::Small));
        let corners = psa.outline_corners();
        assert_eq!(corners.len(), 11);
        assert_eq!(corners[0], 10);
        let mut pts = Vec::new();
        psa.outline(&w, &mut pts);
        assert_eq!(pts.len(), corners.iter().sum::<usize>());
        assert!((psa.center(&w) - Vec2::new(0.0, 20.0)).length() < 1e-9);
        assert!((psa.area_ratio(&w) - 0.9355).abs() < 1e-3);
    }
}
