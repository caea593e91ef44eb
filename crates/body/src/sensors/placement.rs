//! Where sensors go: placement strings of 2D-VSR-Sim (`uniform-…`, `spinedTouch-…`,
//! `spinedTouchSighted-…`, `empty`) or an explicit list per voxel.

use super::spec::SensorSpec;
use super::SensorError;
use crate::morphology::Morphology;
use serde::{Deserialize, Serialize};

/// A sensor placement, as written in configs and robot files: either a placement string or, per
/// voxel in grid order (row-major from the bottom row), a list of sensor names.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum SensorConfig {
    /// `uniform-a+vxy+t-0.01`, `spinedTouch-t-f-0`, `spinedTouchSighted-f-f-0.01`, `empty`.
    Named(String),
    /// One list of sensor names per voxel.
    PerVoxel(Vec<Vec<String>>),
}

impl SensorConfig {
    /// Parses a placement string, checking its syntax (the body is checked when the robot is built).
    pub fn parse(s: &str) -> Result<SensorConfig, SensorError> {
        let c = SensorConfig::Named(s.to_string());
        // a 1×1 body is enough to check names and numbers
        c.specs(&Morphology::named("box-1x1").expect("box-1x1 is valid"))?;
        Ok(c)
    }

    /// The sensors of each voxel (grid order).
    pub fn specs(&self, m: &Morphology) -> Result<Vec<Vec<SensorSpec>>, SensorError> {
        let cells: Vec<(usize, usize)> = m.voxels().collect();
        match self {
            SensorConfig::PerVoxel(lists) => {
                if lists.len() != cells.len() {
                    return Err(SensorError::WrongVoxelCount {
                        expected: cells.len(),
                        got: lists.len(),
                    });
                }
                lists.iter().map(|l| l.iter().map(|n| named(n)).collect()).collect()
            }
            SensorConfig::Named(s) => parse_placement(s, m, &cells),
        }
    }
}

fn named(name: &str) -> Result<SensorSpec, SensorError> {
    SensorSpec::named(name).ok_or_else(|| SensorError::UnknownSensor(name.to_string()))
}

fn noisy(spec: SensorSpec, sigma: f64) -> SensorSpec {
    if sigma > 0.0 {
        SensorSpec::Noisy { sigma, of: Box::new(spec) }
    } else {
        spec
    }
}

fn parse_sigma(token: &str, whole: &str) -> Result<f64, SensorError> {
    match token.parse::<f64>() {
        Ok(v) if v.is_finite() && v >= 0.0 => Ok(v),
        _ => Err(SensorError::BadPlacement {
            placement: whole.to_string(),
            msg: format!("noise '{token}' must be a number ≥ 0"),
        }),
    }
}

fn parse_flag(token: &str, whole: &str) -> Result<bool, SensorError> {
    match token {
        "t" | "true" => Ok(true),
        "f" | "false" => Ok(false),
        _ => Err(SensorError::BadPlacement {
            placement: whole.to_string(),
            msg: format!("flag '{token}' must be t or f"),
        }),
    }
}

fn parse_placement(s: &str, m: &Morphology, cells: &[(usize, usize)]) -> Result<Vec<Vec<SensorSpec>>, SensorError> {
    if s == "empty" {
        return Ok(vec![Vec::new(); cells.len()]);
    }
    let bad = |msg: &str| SensorError::BadPlacement {
        placement: s.to_string(),
        msg: msg.to_string(),
    };
    let (kind, rest) = s.split_once('-').ok_or_else(|| bad("expected uniform-…, spinedTouch-…, spinedTouchSighted-… or empty"))?;
    match kind {
        "uniform" => {
            let (names, sigma) = rest.rsplit_once('-').ok_or_else(|| bad("expected uniform-<s1>+<s2>…-<noise>"))?;
            let sigma = parse_sigma(sigma, s)?;
            let specs: Vec<SensorSpec> = names.split('+').map(|n| named(n).map(|x| noisy(x, sigma))).collect::<Result<_, _>>()?;
            Ok(vec![specs; cells.len()])
        }
        "spinedTouch" | "spinedTouchSighted" => {
            let parts: Vec<&str> = rest.split('-').collect();
            if parts.len() != 3 {
                return Err(bad("expected spinedTouch[Sighted]-<cpg t/f>-<malfunction t/f>-<noise>"));
            }
            let (cpg, malfunction, sigma) = (parse_flag(parts[0], s)?, parse_flag(parts[1], s)?, parse_sigma(parts[2], s)?);
            let (w, h) = (m.width(), m.height());
            let top_right = cells.iter().filter(|c| c.1 == h - 1).map(|c| c.0).max();
            let sense = |n: &str| noisy(SensorSpec::named(n).expect("built-in sensor name"), sigma);
            Ok(cells
                .iter()
                .map(|&(x, y)| {
                    let mut v = vec![sense("a")];
                    if y == 0 {
                        v.push(sense("t"));
                    }
                    if y == h - 1 {
                        v.push(sense("vxy"));
                    }
                    if cpg && y == h - 1 && Some(x) == top_right {
                        v.push(sense("cpg"));
                    }
                    if malfunction {
                        v.push(sense("m"));
                    }
                    if kind == "spinedTouchSighted" && x == w - 1 {
                        v.push(sense("l5"));
                    }
                    v
                })
                .collect())
        }
        _ => Err(bad("expected uniform-…, spinedTouch-…, spinedTouchSighted-… or empty")),
    }
}
