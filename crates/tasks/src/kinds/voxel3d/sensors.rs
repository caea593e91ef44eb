//! The sensors of a 3D voxel: what each voxel reads every step (the affordance study's five by
//! default, in its order: a CPG, touch, floor contact, velocity along y and x; thesis-code-facts
//! §7.2). Short form: names joined by commas (`cpg,touch,floor,vy,vx`; `cpg:F` for F Hz).

use glam::DVec3;
use vsrlab_field::FieldError;

/// The affordance study's sensors, in its order.
pub const DEFAULT_SENSORS: &str = "cpg,touch,floor,vy,vx";

/// One reading of a voxel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Sensor3 {
    /// `sin(2π f t)`, t in seconds: a clock every voxel shares (f in Hz, default 1).
    Cpg(f64),
    /// +1 while the voxel touches another voxel it is not linked to (its own body's, or a wall's),
    /// −1 otherwise.
    Touch,
    /// +1 while the voxel touches the floor, −1 otherwise.
    Floor,
    /// The voxel's velocity along x (m/s).
    VelocityX,
    /// Along y (m/s).
    VelocityY,
    /// Along z (m/s).
    VelocityZ,
}

/// What a voxel's sensors read from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VoxelSense {
    /// Simulated time (s).
    pub time: f64,
    /// Whether it touches another voxel.
    pub touches_voxel: bool,
    /// Whether it touches the floor.
    pub touches_floor: bool,
    /// Its velocity (m/s).
    pub velocity: DVec3,
}

impl Sensor3 {
    /// The sensors of a short form; the error names the sensor.
    pub fn parse_list(text: &str) -> Result<Vec<Sensor3>, FieldError> {
        if text.trim().is_empty() || text.trim() == "none" {
            return Ok(Vec::new());
        }
        text.split(',')
            .enumerate()
            .map(|(i, s)| Sensor3::parse(s.trim()).map_err(|e| e.at_index(i)))
            .collect()
    }

    fn parse(name: &str) -> Result<Sensor3, FieldError> {
        let (head, arg) = match name.split_once(':') {
            Some((h, a)) => (h, Some(a)),
            None => (name, None),
        };
        let sensor = match head {
            "cpg" => {
                let f = match arg {
                    None => 1.0,
                    Some(a) => a
                        .parse::<f64>()
                        .ok()
                        .filter(|f| f.is_finite() && *f > 0.0 && *f <= 1e4)
                        .ok_or_else(|| {
                            FieldError::message(format!("cpg:{a}: the frequency is a number of Hz in (0, 10000]"))
                        })?,
                };
                return Ok(Sensor3::Cpg(f));
            }
            "touch" => Sensor3::Touch,
            "floor" => Sensor3::Floor,
            "vx" => Sensor3::VelocityX,
            "vy" => Sensor3::VelocityY,
            "vz" => Sensor3::VelocityZ,
            other => {
                return Err(FieldError::message(format!(
                    "unknown 3D sensor '{other}': expected cpg[:Hz], touch, floor, vx, vy or vz"
                )))
            }
        };
        match arg {
            Some(_) => Err(FieldError::message(format!("the sensor '{head}' takes no argument"))),
            None => Ok(sensor),
        }
    }

    /// The reading.
    pub fn read(self, sense: &VoxelSense) -> f64 {
        let sign = |b: bool| if b { 1.0 } else { -1.0 };
        match self {
            Sensor3::Cpg(f) => (2.0 * std::f64::consts::PI * f * sense.time).sin(),
            Sensor3::Touch => sign(sense.touches_voxel),
            Sensor3::Floor => sign(sense.touches_floor),
            Sensor3::VelocityX => sense.velocity.x,
            Sensor3::VelocityY => sense.velocity.y,
            Sensor3::VelocityZ => sense.velocity.z,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_sensors_read_the_affordance_studys_five() {
        let list = Sensor3::parse_list(DEFAULT_SENSORS).unwrap();
        let sense = VoxelSense {
            time: 0.25,
            touches_voxel: true,
            touches_floor: false,
            velocity: DVec3::new(0.1, -0.2, 0.3),
        };
        let readings: Vec<f64> = list.iter().map(|s| s.read(&sense)).collect();
        assert!((readings[0] - 1.0).abs() < 1e-12, "sin(2π · 0.25) = 1: {readings:?}");
        assert_eq!(readings[1..], [1.0, -1.0, -0.2, 0.1]);
        assert_eq!(Sensor3::parse_list("cpg:2").unwrap(), vec![Sensor3::Cpg(2.0)]);
        assert!(Sensor3::parse_list("none").unwrap().is_empty());
    }

    #[test]
    fn unknown_sensors_and_bad_frequencies_are_named() {
        let e = Sensor3::parse_list("cpg,lidar").unwrap_err().to_string();
        assert!(e.contains("[1]") && e.contains("unknown 3D sensor 'lidar'"), "{e}");
        assert!(Sensor3::parse_list("cpg:0")
            .unwrap_err()
            .to_string()
            .contains("(0, 10000]"));
        assert!(Sensor3::parse_list("cpg:nan").is_err());
        assert!(Sensor3::parse_list("touch:1")
            .unwrap_err()
            .to_string()
            .contains("no argument"));
    }
}
