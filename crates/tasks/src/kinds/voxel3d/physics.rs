//! [`Physics3d`]: the 3D world's settings as a task file gives them (material, lattice, gravity,
//! collisions, time step, thermal actuation), defaulting to the affordance study's voxcraft-sim
//! settings (thesis §5.1.2.1, docs/voxelyze-model.md §12), and the world they build around a
//! body and its fixed obstacle voxels.

use super::grid::BodyGrid3;
use serde::{Deserialize, Serialize};
use vsrlab_field::FieldError;
use vsrlab_physics3d::{Dof, Material, VoxelId, World, WorldSettings};

/// Most steps an episode may take (duration over time step): beyond this the settings are
/// refused before anything runs.
pub const MAX_STEPS: f64 = 5e7;

/// The 3D world of a task.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Physics3d {
    /// Lattice size: every voxel's edge (m).
    pub voxel_size: f64,
    /// Downward gravity (m/s²).
    pub gravity: f64,
    /// Whether voxels that are not linked collide (voxcraft-sim's default).
    pub collisions: bool,
    /// The time step as a fraction of the model's recommended one (voxcraft-sim: 0.95).
    pub dt_fraction: f64,
    /// Temperature at actuation ±1 (the study's 14.4714: ±50 % volume with CTE 0.01).
    pub amplitude: f64,
    /// Young's modulus (Pa).
    pub youngs_modulus: f64,
    /// Density (kg/m³).
    pub density: f64,
    /// Coefficient of thermal expansion (1/degree).
    pub cte: f64,
    /// Static friction coefficient with the floor.
    pub static_friction: f64,
    /// Kinetic friction coefficient with the floor.
    pub kinetic_friction: f64,
    /// Damping ratio of the links (bond damping).
    pub internal_damping: f64,
    /// Damping ratio on every voxel's velocity.
    pub global_damping: f64,
    /// Damping ratio of contacts (floor and voxel–voxel).
    pub collision_damping: f64,
}

impl Default for Physics3d {
    fn default() -> Self {
        let m = Material::affordance();
        Physics3d {
            voxel_size: 0.01,
            gravity: vsrlab_physics3d::STANDARD_GRAVITY,
            collisions: true,
            dt_fraction: 0.95,
            amplitude: 14.4714,
            youngs_modulus: m.youngs_modulus,
            density: m.density,
            cte: m.cte,
            static_friction: m.static_friction,
            kinetic_friction: m.kinetic_friction,
            internal_damping: m.internal_damping,
            global_damping: m.global_damping,
            collision_damping: m.collision_damping,
        }
    }
}

/// A body and its obstacles in a 3D world, with their voxels' handles.
#[derive(Debug, Clone)]
pub struct Built {
    /// The world.
    pub world: World,
    /// The body's voxels, in the grid's cell order (the brain's units).
    pub body: Vec<VoxelId>,
    /// The obstacles' voxels.
    pub obstacles: Vec<VoxelId>,
    /// The time step (s).
    pub dt: f64,
}

impl Physics3d {
    /// The material of every voxel.
    pub fn material(&self) -> Material {
        Material {
            youngs_modulus: self.youngs_modulus,
            density: self.density,
            cte: self.cte,
            static_friction: self.static_friction,
            kinetic_friction: self.kinetic_friction,
            internal_damping: self.internal_damping,
            global_damping: self.global_damping,
            collision_damping: self.collision_damping,
        }
    }

    /// Checks every value; the error names the field (relative to this table).
    pub fn validate(&self) -> Result<(), FieldError> {
        let check = |name: &str, v: f64, ok: bool, range: &str| {
            if v.is_finite() && ok {
                Ok(())
            } else {
                Err(FieldError::new(name, format!("must be {range}, got {v}")))
            }
        };
        let s = self.voxel_size;
        check("voxel_size", s, s > 0.0 && s <= 10.0, "in (0, 10] m")?;
        check(
            "gravity",
            self.gravity,
            self.gravity.abs() <= 1e4,
            "in [-10000, 10000] m/s²",
        )?;
        let f = self.dt_fraction;
        check("dt_fraction", f, f > 0.0 && f <= 1.0, "in (0, 1]")?;
        check(
            "amplitude",
            self.amplitude,
            self.amplitude >= 0.0,
            "a finite number ≥ 0",
        )?;
        self.material().validate()?;
        let swing = self.amplitude * self.cte.abs();
        check(
            "amplitude",
            self.amplitude,
            swing < 0.9,
            "below 0.9 / |cte| (a voxel's rest size must stay positive)",
        )?;
        Ok(())
    }

    /// The time step of these settings: `dt_fraction` of the recommended step of a link of
    /// this material.
    pub fn dt(&self) -> f64 {
        let s = self.voxel_size;
        let mass = self.density * s * s * s;
        self.dt_fraction / (2.0 * std::f64::consts::PI * (self.youngs_modulus * s / mass).sqrt())
    }

    /// The world with `body` at lattice cells (x, y, z) from the origin and `obstacles` fixed in
    /// every degree of freedom (a piece of their own: never linked to the body); an obstacle on a
    /// body cell is refused naming it. Error paths are those of a task's table (`physics.…`,
    /// `obstacles[i]`).
    pub fn build(&self, body: &BodyGrid3, obstacles: &[[i32; 3]]) -> Result<Built, FieldError> {
        self.validate().map_err(|e| e.at("physics"))?;
        let settings = WorldSettings {
            voxel_size: self.voxel_size,
            gravity: self.gravity,
            floor: true,
            collisions: self.collisions,
        };
        let invalid = |e: vsrlab_physics3d::Physics3dError| FieldError::message(e.to_string());
        let mut world = World::new(settings).map_err(invalid)?;
        let material = world.add_material(self.material()).map_err(invalid)?;
        let mut ids = Vec::with_capacity(body.voxel_count());
        for c in body.cells() {
            ids.push(world.add_voxel(material, c.map(|v| v as i32)).map_err(invalid)?);
        }
        let mut walls = Vec::with_capacity(obstacles.len());
        for (i, &cell) in obstacles.iter().enumerate() {
            let at_obstacle = |m: String| FieldError::message(m).at_index(i).at("obstacles");
            if cell.iter().any(|v| v.abs() > 10_000) {
                return Err(at_obstacle(format!("{cell:?}: cells are within ±10000 of the origin")));
            }
            if body.has(cell[0] as isize, cell[1] as isize, cell[2] as isize) {
                return Err(at_obstacle(format!("{cell:?} is a cell of the robot's body")));
            }
            let v = world
                .add_voxel_to_piece(material, cell, 1)
                .map_err(|_| at_obstacle(format!("{cell:?} is given twice")))?;
            world.set_fixed(v, &Dof::ALL, true);
            walls.push(v);
        }
        let dt = self.dt();
        Ok(Built {
            world,
            body: ids,
            obstacles: walls,
            dt,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_defaults_are_the_affordance_studys_and_give_its_time_step() {
        let p = Physics3d::default();
        p.validate().unwrap();
        // 0.95 / (2π √(E s / ρ s³)) = 0.95 / (2π √(1e4 · 0.01 / 1e-5)) = 4.78e-5 s
        assert!((p.dt() - 4.7809e-5).abs() < 1e-8, "{}", p.dt());
        let body = BodyGrid3::parse("quadruped").unwrap();
        let built = p.build(&body, &[[6, 0, 0], [6, 0, 1]]).unwrap();
        assert_eq!((built.body.len(), built.obstacles.len()), (28, 2));
        assert!((built.world.recommended_time_step() * 0.95 / built.dt - 1.0).abs() < 1e-12);
    }

    #[test]
    fn bad_settings_and_obstacles_are_refused_naming_the_field() {
        let err = |p: Physics3d| p.validate().unwrap_err().to_string();
        assert!(err(Physics3d {
            dt_fraction: 2.0,
            ..Default::default()
        })
        .starts_with("dt_fraction"));
        assert!(err(Physics3d {
            youngs_modulus: -1.0,
            ..Default::default()
        })
        .contains("youngs_modulus"));
        assert!(err(Physics3d {
            density: f64::NAN,
            ..Default::default()
        })
        .contains("density"));
        assert!(err(Physics3d {
            amplitude: 100.0,
            ..Default::default()
        })
        .starts_with("amplitude"));
        let body = BodyGrid3::parse("cube-2").unwrap();
        let p = Physics3d::default();
        let e = p.build(&body, &[[3, 0, 0], [1, 1, 1]]).unwrap_err().to_string();
        assert!(e.starts_with("obstacles[1]") && e.contains("cell of the robot"), "{e}");
        let e = p.build(&body, &[[3, 0, 0], [3, 0, 0]]).unwrap_err().to_string();
        assert!(e.contains("obstacles[1]") && e.contains("twice"), "{e}");
    }
}
