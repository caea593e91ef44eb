//! [`EvoGymSim`]: any world of EvoGym's objects simulated as EvoGym's `EvoSim` does
//! (`evogym/sim.py`, commit `f63c649`), without a task: objects with actuators are robots, each
//! driven by its own actions; every step is 30 substeps of the mass-spring engine.
//!
//! As `EvoSim._init_world_items` loads them, the robots come first, then the other objects, each
//! group in name order; a robot's actuators are its actuator cells in row-major order from the
//! top row. Until a robot is given an action, its actuators hold their rest length (1.0).

use super::assemble::plan_object;
use super::error::EvoGymError;
use super::worlds::World;
use std::ops::Range;
use vsrlab_field::FieldError;
use vsrlab_physics::mass_spring::{MassSpringBuilder, MassSpringError, MassSpringSettings, MassSpringWorld};

/// One object of a simulation: where its points and its actuators' targets are.
#[derive(Debug, Clone, PartialEq)]
pub struct SimObject {
    /// Its name in the world.
    pub name: String,
    /// Whether it has actuators (EvoGym's robots).
    pub robot: bool,
    /// Its points in the physics world.
    pub points: Range<usize>,
    /// Its actuators' places in the simulation's list of targets.
    pub actuators: Range<usize>,
}

/// A world of objects, stepped with each robot's actions.
#[derive(Debug, Clone)]
pub struct EvoGymSim {
    /// The world it was built from (for drawing its objects).
    layout: World,
    start: MassSpringWorld,
    world: MassSpringWorld,
    objects: Vec<SimObject>,
    targets: Vec<f64>,
    steps: usize,
}

impl EvoGymSim {
    /// The simulation of `world`'s objects. Refuses an empty world, a robot that is not a valid
    /// robot (naming it), or a world the engine refuses.
    pub fn new(world: &World) -> Result<EvoGymSim, EvoGymError> {
        if world.objects().is_empty() {
            return Err(EvoGymError::World(FieldError::new("objects", "no object to simulate")));
        }
        let mut order: Vec<_> = world.objects().iter().collect();
        order.sort_by_key(|o| (o.grid.actuator_count() == 0, o.name.clone()));
        let mut builder = MassSpringBuilder::new(MassSpringSettings::evogym());
        let (mut objects, mut actuators) = (Vec::with_capacity(order.len()), 0);
        for o in order {
            let robot = o.grid.actuator_count() > 0;
            if robot {
                o.grid
                    .validate_robot()
                    .map_err(|e| EvoGymError::Robot(e.at(&o.name).at("objects")))?;
            }
            let plan = plan_object(&o.grid, o.origin);
            let placed = plan.add_to(&mut builder, robot);
            objects.push(SimObject {
                name: o.name.clone(),
                robot,
                points: placed.points(),
                actuators: actuators..actuators + plan.actuators.len(),
            });
            actuators += plan.actuators.len();
        }
        let start = builder.build().map_err(EvoGymError::Physics)?;
        Ok(EvoGymSim {
            layout: world.clone(),
            world: start.clone(),
            start,
            objects,
            targets: vec![1.0; actuators],
            steps: 0,
        })
    }

    /// The objects, in the simulation's order (robots first, then by name).
    pub fn objects(&self) -> &[SimObject] {
        &self.objects
    }

    /// The object named `name`; the error lists the names there are.
    pub fn object(&self, name: &str) -> Result<&SimObject, EvoGymError> {
        self.objects.iter().find(|o| o.name == name).ok_or_else(|| {
            let names: Vec<&str> = self.objects.iter().map(|o| o.name.as_str()).collect();
            EvoGymError::World(FieldError::new(
                "name",
                format!("no object '{name}': the objects are {}", names.join(", ")),
            ))
        })
    }

    /// The robot named `name` (an object with actuators).
    pub fn robot(&self, name: &str) -> Result<&SimObject, EvoGymError> {
        let object = self.object(name)?;
        match object.robot {
            true => Ok(object),
            false => Err(EvoGymError::World(FieldError::new(
                "name",
                format!("'{name}' has no actuator: only robots take actions"),
            ))),
        }
    }

    /// Sets robot `name`'s targets (one length ratio per actuator, clipped into [0.6, 1.6] when
    /// stepped) for the next steps.
    pub fn set_action(&mut self, name: &str, action: &[f64]) -> Result<(), EvoGymError> {
        let range = self.robot(name)?.actuators.clone();
        if action.len() != range.len() {
            return Err(EvoGymError::ActionCount {
                expected: range.len(),
                got: action.len(),
            });
        }
        if let Some(index) = action.iter().position(|a| !a.is_finite()) {
            return Err(EvoGymError::NonFiniteAction {
                index,
                value: action[index],
            });
        }
        self.targets[range].copy_from_slice(action);
        Ok(())
    }

    /// One step (30 substeps) with the targets set; `true` when the simulation became unstable
    /// (a robot folded into itself or the state became non-finite), as `EvoSim.step` answers;
    /// the state is then the last stable one's.
    pub fn step(&mut self) -> Result<bool, EvoGymError> {
        let unstable = match self.world.step(&self.targets) {
            Ok(_) => false,
            Err(MassSpringError::SelfOverlap { .. } | MassSpringError::NonFinite { .. }) => true,
            Err(e) => return Err(EvoGymError::Physics(e)),
        };
        self.steps += 1;
        Ok(unstable)
    }

    /// Back to the start, every target at rest (1.0).
    pub fn reset(&mut self) {
        self.world.clone_from(&self.start);
        self.targets.fill(1.0);
        self.steps = 0;
    }

    /// Steps taken since the start (EvoGym's `get_time`).
    pub fn steps(&self) -> usize {
        self.steps
    }

    /// The world of objects it was built from.
    pub fn layout(&self) -> &World {
        &self.layout
    }

    /// The physics world: every point's position and velocity.
    pub fn world(&self) -> &MassSpringWorld {
        &self.world
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinds::evogym::{EvoGymEnv, EvoGymTask, MaterialGrid, WorldObject};

    const FULL: &str = "33333/33333/33333/33333/33333";

    /// Walker-v0's world with a robot named `robot` where the task puts it.
    fn walker_world(robot_name: &str) -> World {
        let mut world = EvoGymTask::Walker.world();
        let robot = MaterialGrid::from_rows(FULL).unwrap();
        world.add(WorldObject::new(robot_name, (1, 1), robot)).unwrap();
        world
    }

    /// The simulation of Walker-v0's world moves the robot as the task's environment does, bit
    /// for bit, step after step.
    #[test]
    fn a_task_world_steps_as_its_environment() {
        let mut sim = EvoGymSim::new(&walker_world("robot")).unwrap();
        let mut env = EvoGymEnv::new(EvoGymTask::Walker, &MaterialGrid::from_rows(FULL).unwrap()).unwrap();
        assert_eq!(sim.objects()[0].name, "robot", "robots first");
        assert_eq!(sim.robot("robot").unwrap().actuators, 0..25);
        for t in 0..60 {
            let action: Vec<f64> = (0..25)
                .map(|i| if (t + 5 * (i % 5)) % 20 < 10 { 1.6 } else { 0.6 })
                .collect();
            sim.set_action("robot", &action).unwrap();
            assert!(!sim.step().unwrap());
            env.step(&action).unwrap();
        }
        assert_eq!(sim.world().positions_x(), env.world().positions_x());
        assert_eq!(sim.world().velocities_y(), env.world().velocities_y());
        assert_eq!(sim.steps(), 60);
        let moved = sim.world().positions_x().to_vec();
        sim.reset();
        let fresh = EvoGymSim::new(&walker_world("robot")).unwrap();
        assert_ne!(sim.world().positions_x(), moved.as_slice());
        assert_eq!(sim.world().positions_x(), fresh.world().positions_x());
        assert_eq!(sim.steps(), 0);
    }

    /// Unknown names, objects without actuators and wrong actions are refused, naming what.
    #[test]
    fn bad_names_and_actions_are_refused() {
        let mut sim = EvoGymSim::new(&walker_world("walker")).unwrap();
        let e = sim.set_action("robot", &[1.0; 25]).unwrap_err().to_string();
        assert!(e.contains("no object 'robot'") && e.contains("walker, ground"), "{e}");
        let e = sim.set_action("ground", &[1.0]).unwrap_err().to_string();
        assert!(e.contains("no actuator"), "{e}");
        assert!(matches!(
            sim.set_action("walker", &[1.0; 3]),
            Err(EvoGymError::ActionCount { expected: 25, got: 3 })
        ));
        let mut bad = vec![1.0; 25];
        bad[7] = f64::NAN;
        assert!(matches!(
            sim.set_action("walker", &bad),
            Err(EvoGymError::NonFiniteAction { index: 7, .. })
        ));
        assert!(EvoGymSim::new(&World::new()).is_err());
    }
}
