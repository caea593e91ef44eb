//! Where sensors go: the sensorizing strings of 2D-VSR-Sim (vsr-model.md §3.3) or an explicit list
//! of sensor names per voxel.
//!
//! Placement strings:
//! - `empty`: no sensor anywhere.
//! - `uniform-<k1>+<k2>+…-<σ>`: the named sensors k1, k2, … on every voxel, in that order.
//! - `uniformAll-<σ>`: every named sensor on every voxel, in [`SENSOR_NAMES`] order (the original's
//!   sorted order; its `lf5` "foot lidar" is not implemented).
//! - `spinedTouch-<cpg>-<malfunction>-<σ>` (flags `t` or `f`): on each voxel, in this order, `a`
//!   everywhere; `m` everywhere if malfunction is `t`; `t` on the bottom row; `vxy` on the top row;
//!   `cpg` on the top-right voxel if cpg is `t`.
//! - `spinedTouchSighted-<cpg>-<malfunction>-<σ>`: the same, plus `l5` last on the rightmost column.
//! - The sensory apparatuses of the Hebbian study (thesis §5.3, 2D-VSR-Sim 07f9395), written
//!   `<level>_<shape>-<σ>-<cpg>` as in the original (e.g. `high_biped-0.01-f`):
//!   `high_*`: `a` everywhere, `t` on the bottom row, `vxy` on the top row, `l3` on the rightmost
//!   column; `medium_*`: the same without `l3`; `low_biped`: `a` on the top two rows only;
//!   `low_worm`: `a` on the columns 2, 3 and 4 only (counted from the leftmost, the three central
//!   voxels of a worm-7x1); every one adds `cpg` on the top-right voxel if cpg is `t`. For
//!   biped-4x3 they give 29, 20 and 8 readings; for worm-7x1 31, 28 and 3 (the thesis text says
//!   48, 36 and 8 for the biped, which the original code does not produce).
//!
//! With σ > 0 every placed sensor is wrapped in `Noisy(σ)`. σ is any finite number ≥ 0 (the
//! original only accepted digits with an optional fraction).
//!
//! Choices where the sources are silent or differ: the order within a voxel follows the original
//! (a, m, t, vxy, cpg, l5). Rows and columns are those of the occupied cells: the bottom row is the
//! lowest row holding a voxel, the top row the highest, the rightmost column the rightmost holding
//! a voxel; for grids without empty border rows or columns (every named shape) this is the
//! original's grid rows y = 0, y = H − 1 and column x = W − 1. The top-right voxel is the rightmost
//! voxel of the top row; the original used grid cell (W − 1, H − 1) and silently placed no `cpg`
//! when that cell was empty (e.g. `ball-5`).

use super::named::SENSOR_NAMES;
use super::spec::SensorSpec;
use super::SensorError;
use crate::morphology::Morphology;
use crate::params::Preset;
use serde::de::{self, SeqAccess, Visitor};
use serde::ser::SerializeSeq;
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::fmt;
use std::str::FromStr;

/// A sensor placement, as written in configs and robot files: a placement string, or per voxel (grid
/// order: row-major from the bottom row) a list of sensor names.
///
/// Serialised as the placement string, or as a list of lists of names.
#[derive(Debug, Clone, PartialEq)]
pub enum SensorConfig {
    /// `empty`: no sensors.
    Empty,
    /// `uniform-<k1>+<k2>+…-<σ>`: the same sensors on every voxel.
    Uniform {
        /// Sensor names, in order.
        sensors: Vec<String>,
        /// Noise level (0: no noise wrapper).
        sigma: f64,
    },
    /// `uniformAll-<σ>`: every named sensor on every voxel.
    UniformAll {
        /// Noise level (0: no noise wrapper).
        sigma: f64,
    },
    /// `spinedTouch-…` or, when `sighted`, `spinedTouchSighted-…`.
    SpinedTouch {
        /// Adds `l5` on the rightmost column (`spinedTouchSighted`).
        sighted: bool,
        /// `cpg` on the top-right voxel.
        cpg: bool,
        /// `m` on every voxel.
        malfunction: bool,
        /// Noise level (0: no noise wrapper).
        sigma: f64,
    },
    /// `<level>_<shape>-<σ>-<cpg>`: a sensory apparatus of the Hebbian study (module docs).
    Apparatus {
        /// `high`, `medium` or `low`.
        level: Level,
        /// The shape the apparatus was written for (it only matters for `low`).
        shape: ApparatusShape,
        /// Noise level (0: no noise wrapper).
        sigma: f64,
        /// `cpg` on the top-right voxel.
        cpg: bool,
    },
    /// One list of sensor names per voxel, in grid order.
    PerVoxel(Vec<Vec<String>>),
}

/// How many sensors an apparatus has (thesis §5.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Level {
    /// Area, touch, velocity and lidar.
    High,
    /// Area, touch and velocity.
    Medium,
    /// Area on a few voxels.
    Low,
}

/// The shape an apparatus names.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ApparatusShape {
    /// `*_biped`.
    Biped,
    /// `*_worm`.
    Worm,
}

const APPARATUSES: [(&str, Level, ApparatusShape); 6] = [
    ("high_biped", Level::High, ApparatusShape::Biped),
    ("medium_biped", Level::Medium, ApparatusShape::Biped),
    ("low_biped", Level::Low, ApparatusShape::Biped),
    ("high_worm", Level::High, ApparatusShape::Worm),
    ("medium_worm", Level::Medium, ApparatusShape::Worm),
    ("low_worm", Level::Low, ApparatusShape::Worm),
];

/// What a placement string should look like, for error messages.
const PLACEMENT_FORMS: &str =
    "one of uniform-<k1>+<k2>+…-<σ>, uniformAll-<σ>, spinedTouch-<t|f>-<t|f>-<σ>, spinedTouchSighted-<t|f>-<t|f>-<σ>, <high|medium|low>_<biped|worm>-<σ>-<t|f>, empty";

impl SensorConfig {
    /// Parses a placement string; every name, flag and number is checked.
    pub fn parse(text: &str) -> Result<SensorConfig, SensorError> {
        let s = text.trim();
        let bad = |token: &str, expected: &str| SensorError::BadPlacement {
            placement: s.to_string(),
            token: token.to_string(),
            expected: expected.to_string(),
        };
        if s == "empty" {
            return Ok(SensorConfig::Empty);
        }
        let Some((kind, rest)) = s.split_once('-') else {
            return Err(bad(s, PLACEMENT_FORMS));
        };
        match kind {
            "uniform" => {
                // names never contain '-', so the first '-' ends them (σ may be written 1e-3)
                let Some((names, sigma)) = rest.split_once('-') else {
                    return Err(bad(rest, "<k1>+<k2>+…-<σ> after uniform-"));
                };
                let sensors = names
                    .split('+')
                    .map(|n| check_name(n).map(|_| n.to_string()))
                    .collect::<Result<Vec<_>, _>>()?;
                Ok(SensorConfig::Uniform {
                    sensors,
                    sigma: parse_sigma(sigma, &bad)?,
                })
            }
            "uniformAll" => Ok(SensorConfig::UniformAll {
                sigma: parse_sigma(rest, &bad)?,
            }),
            "spinedTouch" | "spinedTouchSighted" => {
                let parts: Vec<&str> = rest.splitn(3, '-').collect();
                let [cpg, malfunction, sigma] = parts[..] else {
                    return Err(bad(rest, "<cpg t|f>-<malfunction t|f>-<σ> after spinedTouch-"));
                };
                Ok(SensorConfig::SpinedTouch {
                    sighted: kind == "spinedTouchSighted",
                    cpg: parse_flag(cpg, "cpg", &bad)?,
                    malfunction: parse_flag(malfunction, "malfunction", &bad)?,
                    sigma: parse_sigma(sigma, &bad)?,
                })
            }
            _ => {
                let Some(&(_, level, shape)) = APPARATUSES.iter().find(|a| a.0 == kind) else {
                    return Err(bad(kind, PLACEMENT_FORMS));
                };
                let Some((sigma, cpg)) = rest.rsplit_once('-') else {
                    return Err(bad(rest, "<σ>-<cpg t|f> after the apparatus name"));
                };
                Ok(SensorConfig::Apparatus {
                    level,
                    shape,
                    sigma: parse_sigma(sigma, &bad)?,
                    cpg: parse_flag(cpg, "cpg", &bad)?,
                })
            }
        }
    }

    /// The sensors of each voxel of `body`, in grid order, as the default preset (2021) builds them.
    pub fn specs(&self, body: &Morphology) -> Result<Vec<Vec<SensorSpec>>, SensorError> {
        self.specs_in(body, Preset::default())
    }

    /// The sensors of each voxel of `body`, in grid order, as `preset`'s simulator builds them
    /// (soft-normalisation clipping and lidar ray layout differ: [`SensorSpec::named_in`]).
    pub fn specs_in(&self, body: &Morphology, preset: Preset) -> Result<Vec<Vec<SensorSpec>>, SensorError> {
        let cells: Vec<(usize, usize)> = body.voxels().collect();
        let named_lists = |lists: Vec<Vec<&str>>, sigma: f64| -> Result<Vec<Vec<SensorSpec>>, SensorError> {
            lists
                .iter()
                .enumerate()
                .map(|(v, names)| {
                    names
                        .iter()
                        .map(|n| {
                            let spec = SensorSpec::named_in(n, preset).ok_or_else(|| SensorError::UnknownSensor {
                                voxel: Some(v),
                                name: n.to_string(),
                            })?;
                            Ok(if sigma > 0.0 { spec.noisy(sigma) } else { spec })
                        })
                        .collect()
                })
                .collect()
        };
        match self {
            SensorConfig::Empty => Ok(vec![Vec::new(); cells.len()]),
            SensorConfig::Uniform { sensors, sigma } => {
                let names: Vec<&str> = sensors.iter().map(String::as_str).collect();
                named_lists(vec![names; cells.len()], checked_sigma(self, *sigma)?)
            }
            SensorConfig::UniformAll { sigma } => {
                named_lists(vec![SENSOR_NAMES.to_vec(); cells.len()], checked_sigma(self, *sigma)?)
            }
            SensorConfig::SpinedTouch {
                sighted,
                cpg,
                malfunction,
                sigma,
            } => {
                let lists = spined_names(&cells, *sighted, *cpg, *malfunction);
                named_lists(lists, checked_sigma(self, *sigma)?)
            }
            SensorConfig::Apparatus {
                level,
                shape,
                sigma,
                cpg,
            } => named_lists(
                apparatus_names(&cells, *level, *shape, *cpg),
                checked_sigma(self, *sigma)?,
            ),
            SensorConfig::PerVoxel(lists) => {
                if lists.len() != cells.len() {
                    return Err(SensorError::WrongVoxelCount {
                        expected: cells.len(),
                        got: lists.len(),
                    });
                }
                named_lists(
                    lists.iter().map(|l| l.iter().map(String::as_str).collect()).collect(),
                    0.0,
                )
            }
        }
    }
}

/// Names per voxel for the spined placements (see the module docs).
fn spined_names(cells: &[(usize, usize)], sighted: bool, cpg: bool, malfunction: bool) -> Vec<Vec<&'static str>> {
    let bottom = cells.iter().map(|c| c.1).min().unwrap_or(0);
    let top = cells.iter().map(|c| c.1).max().unwrap_or(0);
    let right = cells.iter().map(|c| c.0).max().unwrap_or(0);
    let top_right = cells.iter().filter(|c| c.1 == top).map(|c| c.0).max();
    cells
        .iter()
        .map(|&(x, y)| {
            let mut names = vec!["a"];
            if malfunction {
                names.push("m");
            }
            if y == bottom {
                names.push("t");
            }
            if y == top {
                names.push("vxy");
            }
            if cpg && y == top && Some(x) == top_right {
                names.push("cpg");
            }
            if sighted && x == right {
                names.push("l5");
            }
            names
        })
        .collect()
}

/// Names per voxel for the Hebbian study's apparatuses (see the module docs).
fn apparatus_names(cells: &[(usize, usize)], level: Level, shape: ApparatusShape, cpg: bool) -> Vec<Vec<&'static str>> {
    let bottom = cells.iter().map(|c| c.1).min().unwrap_or(0);
    let top = cells.iter().map(|c| c.1).max().unwrap_or(0);
    let left = cells.iter().map(|c| c.0).min().unwrap_or(0);
    let right = cells.iter().map(|c| c.0).max().unwrap_or(0);
    let top_right = cells.iter().filter(|c| c.1 == top).map(|c| c.0).max();
    cells
        .iter()
        .map(|&(x, y)| {
            let area = match (level, shape) {
                (Level::Low, ApparatusShape::Biped) => y + 1 >= top,
                (Level::Low, ApparatusShape::Worm) => (2..=4).contains(&(x - left)),
                _ => true,
            };
            let mut names = Vec::new();
            if area {
                names.push("a");
            }
            if level != Level::Low && y == bottom {
                names.push("t");
            }
            if level != Level::Low && y == top {
                names.push("vxy");
            }
            if level == Level::High && x == right {
                names.push("l3");
            }
            if cpg && y == top && Some(x) == top_right {
                names.push("cpg");
            }
            names
        })
        .collect()
}

fn check_name(name: &str) -> Result<(), SensorError> {
    match SensorSpec::named(name) {
        Some(_) => Ok(()),
        None => Err(SensorError::UnknownSensor {
            voxel: None,
            name: name.to_string(),
        }),
    }
}

fn parse_sigma(token: &str, bad: &dyn Fn(&str, &str) -> SensorError) -> Result<f64, SensorError> {
    const EXPECTED: &str = "a noise level σ: a finite number ≥ 0";
    match token.parse::<f64>() {
        Ok(v) if v.is_finite() && v >= 0.0 => Ok(v),
        _ => Err(bad(token, EXPECTED)),
    }
}

/// σ of `config`, checked again for placements built in code (parsed ones are already checked).
fn checked_sigma(config: &SensorConfig, sigma: f64) -> Result<f64, SensorError> {
    if sigma.is_finite() && sigma >= 0.0 {
        Ok(sigma)
    } else {
        Err(SensorError::BadPlacement {
            placement: config.to_string(),
            token: sigma.to_string(),
            expected: "a noise level σ: a finite number ≥ 0".into(),
        })
    }
}

fn parse_flag(token: &str, what: &str, bad: &dyn Fn(&str, &str) -> SensorError) -> Result<bool, SensorError> {
    match token {
        "t" => Ok(true),
        "f" => Ok(false),
        _ => Err(bad(token, &format!("t or f for the {what} flag"))),
    }
}

impl FromStr for SensorConfig {
    type Err = SensorError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        SensorConfig::parse(s)
    }
}

impl fmt::Display for SensorConfig {
    /// The placement string (`PerVoxel`: its lists, JSON style).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let flag = |b: bool| if b { "t" } else { "f" };
        match self {
            SensorConfig::Empty => f.write_str("empty"),
            SensorConfig::Uniform { sensors, sigma } => {
                write!(f, "uniform-{}-{sigma}", sensors.join("+"))
            }
            SensorConfig::UniformAll { sigma } => write!(f, "uniformAll-{sigma}"),
            SensorConfig::SpinedTouch {
                sighted,
                cpg,
                malfunction,
                sigma,
            } => {
                let kind = if *sighted { "spinedTouchSighted" } else { "spinedTouch" };
                write!(f, "{kind}-{}-{}-{sigma}", flag(*cpg), flag(*malfunction))
            }
            SensorConfig::Apparatus {
                level,
                shape,
                sigma,
                cpg,
            } => {
                let name = APPARATUSES
                    .iter()
                    .find(|a| a.1 == *level && a.2 == *shape)
                    .map_or("", |a| a.0);
                write!(f, "{name}-{sigma}-{}", flag(*cpg))
            }
            SensorConfig::PerVoxel(lists) => write!(f, "{lists:?}"),
        }
    }
}

impl Serialize for SensorConfig {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            SensorConfig::PerVoxel(lists) => {
                let mut seq = serializer.serialize_seq(Some(lists.len()))?;
                for l in lists {
                    seq.serialize_element(l)?;
                }
                seq.end()
            }
            other => serializer.serialize_str(&other.to_string()),
        }
    }
}

struct ConfigVisitor;

impl<'de> Visitor<'de> for ConfigVisitor {
    type Value = SensorConfig;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(
            "a sensor placement string (e.g. \"uniform-a+vxy+t-0.01\", \"spinedTouch-t-f-0\", \"empty\") \
             or a list of sensor-name lists, one per voxel",
        )
    }

    fn visit_str<E: de::Error>(self, s: &str) -> Result<SensorConfig, E> {
        SensorConfig::parse(s).map_err(E::custom)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<SensorConfig, A::Error> {
        let mut lists: Vec<Vec<String>> = Vec::with_capacity(seq.size_hint().unwrap_or(0).min(4096));
        while let Some(list) = seq.next_element::<Vec<String>>()? {
            lists.push(list);
        }
        for (v, list) in lists.iter().enumerate() {
            for name in list {
                if SensorSpec::named(name).is_none() {
                    let e = SensorError::UnknownSensor {
                        voxel: Some(v),
                        name: name.clone(),
                    };
                    return Err(de::Error::custom(e));
                }
            }
        }
        Ok(SensorConfig::PerVoxel(lists))
    }
}

impl<'de> Deserialize<'de> for SensorConfig {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(ConfigVisitor)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names_per_voxel(config: &str, body: &str) -> Vec<Vec<String>> {
        let body = Morphology::parse(body).unwrap();
        let specs = SensorConfig::parse(config).unwrap().specs(&body).unwrap();
        specs
            .iter()
            .map(|list| {
                list.iter()
                    .map(|spec| {
                        let plain = match spec {
                            SensorSpec::Noisy(noisy) => noisy.inner.as_ref(),
                            s => s,
                        };
                        SENSOR_NAMES
                            .iter()
                            .find(|n| SensorSpec::named(n).as_ref() == Some(plain))
                            .unwrap()
                            .to_string()
                    })
                    .collect()
            })
            .collect()
    }

    fn lists(rows: &[&[&str]]) -> Vec<Vec<String>> {
        rows.iter().map(|r| r.iter().map(|s| s.to_string()).collect()).collect()
    }

    #[test]
    fn uniform_puts_the_same_list_everywhere() {
        let got = names_per_voxel("uniform-a+vxy+t-0.01", "box-2x2");
        assert_eq!(got, vec![vec!["a".to_string(), "vxy".into(), "t".into()]; 4]);
        let body = Morphology::named("box-2x1").unwrap();
        let specs = SensorConfig::parse("uniform-a+t-0.01").unwrap().specs(&body).unwrap();
        assert_eq!(specs[1][1], SensorSpec::named("t").unwrap().noisy(0.01));
        let plain = SensorConfig::parse("uniform-a-0").unwrap().specs(&body).unwrap();
        assert_eq!(plain[0][0], SensorSpec::named("a").unwrap());
        assert_eq!(
            SensorConfig::parse("uniform-a-1e-3").unwrap(),
            SensorConfig::Uniform {
                sensors: vec!["a".into()],
                sigma: 1e-3
            }
        );
    }

    #[test]
    fn hebbian_apparatuses_have_the_original_reading_counts() {
        let count = |config: &str, body: &str| -> usize {
            let body = Morphology::named(body).unwrap();
            let specs = SensorConfig::parse(config).unwrap().specs(&body).unwrap();
            specs.iter().flatten().map(|s| s.dimension()).sum()
        };
        assert_eq!(count("high_biped-0.01-f", "biped-4x3"), 29);
        assert_eq!(count("medium_biped-0.01-f", "biped-4x3"), 20);
        assert_eq!(count("low_biped-0.01-f", "biped-4x3"), 8);
        assert_eq!(count("high_worm-0.01-f", "worm-7x1"), 31);
        assert_eq!(count("medium_worm-0.01-f", "worm-7x1"), 28);
        assert_eq!(count("low_worm-0.01-f", "worm-7x1"), 3);
        assert_eq!(count("low_worm-0-t", "worm-7x1"), 4);
        let got = names_per_voxel("high_biped-0-f", "biped-4x3");
        assert_eq!(got[1], vec!["a".to_string(), "t".into(), "l3".into()]);
        assert_eq!(got[5], vec!["a".to_string(), "l3".into()]);
        assert_eq!(names_per_voxel("low_biped-0-f", "biped-4x3")[1], Vec::<String>::new());
        let low_worm = names_per_voxel("low_worm-1e-3-f", "worm-7x1");
        let with_area: Vec<usize> = (0..7).filter(|&v| !low_worm[v].is_empty()).collect();
        assert_eq!(with_area, [2, 3, 4]);
        for text in ["high_biped-0.01-f", "low_worm-0-t"] {
            assert_eq!(SensorConfig::parse(text).unwrap().to_string(), text);
        }
        let err = SensorConfig::parse("high_biped-0.01").unwrap_err().to_string();
        assert!(err.contains("'0.01'") || err.contains("<σ>-<cpg"), "{err}");
        let err = SensorConfig::parse("huge_biped-0-f").unwrap_err().to_string();
        assert!(err.contains("high|medium|low"), "{err}");
    }

    #[test]
    fn spined_touch_on_a_biped() {
        // biped-4x3: rows from the bottom: #..# / #### / ####
        let got = names_per_voxel("spinedTouch-t-f-0", "biped-4x3");
        let expected = lists(&[
            &["a", "t"],
            &["a", "t"],
            &["a"],
            &["a"],
            &["a"],
            &["a"],
            &["a", "vxy"],
            &["a", "vxy"],
            &["a", "vxy"],
            &["a", "vxy", "cpg"],
        ]);
        assert_eq!(got, expected);
    }

    #[test]
    fn spined_touch_sighted_with_malfunction_on_a_worm() {
        let got = names_per_voxel("spinedTouchSighted-f-t-0.01", "worm-3x1");
        let expected = lists(&[
            &["a", "m", "t", "vxy"],
            &["a", "m", "t", "vxy"],
            &["a", "m", "t", "vxy", "l5"],
        ]);
        assert_eq!(got, expected);
    }

    #[test]
    fn spined_rows_are_those_of_the_occupied_cells() {
        // an empty top row and left column in the grid: the body is the 2×2 block at the bottom right
        let got = names_per_voxel("spinedTouchSighted-t-f-0", "...\n.##\n.##");
        let expected = lists(&[
            &["a", "t"],
            &["a", "t", "l5"],
            &["a", "vxy"],
            &["a", "vxy", "cpg", "l5"],
        ]);
        assert_eq!(got, expected);
        // ball-5: grid cell (4, 4) is empty; the cpg goes to the rightmost voxel of the top row
        let ball = names_per_voxel("spinedTouch-t-f-0", "ball-5");
        let with_cpg: Vec<usize> = (0..ball.len())
            .filter(|&v| ball[v].contains(&"cpg".to_string()))
            .collect();
        let cells: Vec<_> = Morphology::named("ball-5").unwrap().voxels().collect();
        assert_eq!(with_cpg.len(), 1);
        assert_eq!(cells[with_cpg[0]], (3, 4));
    }

    #[test]
    fn uniform_all_and_empty() {
        let all = names_per_voxel("uniformAll-0", "box-1x1");
        assert_eq!(all[0], SENSOR_NAMES.to_vec());
        assert_eq!(names_per_voxel("empty", "box-2x1"), vec![Vec::<String>::new(); 2]);
    }

    #[test]
    fn per_voxel_lists_must_match_the_body() {
        let body = Morphology::named("box-2x1").unwrap();
        let config = SensorConfig::PerVoxel(lists(&[&["a", "l1"], &[]]));
        let specs = config.specs(&body).unwrap();
        assert_eq!(
            specs[0],
            vec![SensorSpec::named("a").unwrap(), SensorSpec::named("l1").unwrap()]
        );
        assert!(specs[1].is_empty());
        let short = SensorConfig::PerVoxel(lists(&[&["a"]]));
        assert_eq!(
            short.specs(&body).unwrap_err(),
            SensorError::WrongVoxelCount { expected: 2, got: 1 }
        );
        let unknown = SensorConfig::PerVoxel(lists(&[&["a"], &["a", "q"]]));
        let e = unknown.specs(&body).unwrap_err();
        assert!(
            e.to_string().contains("'q'") && e.to_string().contains("voxel 1"),
            "{e}"
        );
    }

    #[test]
    fn bad_strings_name_the_token() {
        let cases = [
            ("uniform-a+zz-0", "'zz'"),
            ("uniform-a+-0", "''"),
            ("uniform-a-x", "'x'"),
            ("uniform-a--0.1", "'-0.1'"),
            ("uniform-a-inf", "'inf'"),
            ("uniform-a", "'a'"),
            ("everywhere", "'everywhere'"),
            ("uniformly-a-0", "'uniformly'"),
            ("spinedTouch-q-f-0", "'q'"),
            ("spinedTouch-t-true-0", "'true'"),
            ("spinedTouch-t-f", "'t-f'"),
            ("spinedTouchSighted-t-f-0.1x", "'0.1x'"),
            ("uniformAll-", "''"),
            ("", "''"),
        ];
        for (text, token) in cases {
            let e = SensorConfig::parse(text).unwrap_err().to_string();
            assert!(e.contains(token), "{text}: {e}");
        }
        let e = SensorConfig::parse("spinedTouch-q-f-0").unwrap_err().to_string();
        assert!(e.contains("t or f"), "{e}");
        let e = SensorConfig::parse("uniform-a+zz-0").unwrap_err().to_string();
        assert!(e.contains("expected one of a, ax"), "{e}");
    }

    #[test]
    fn strings_round_trip_through_display_and_serde() {
        for text in [
            "empty",
            "uniform-a+vxy+t-0.01",
            "uniformAll-0",
            "spinedTouch-t-f-0",
            "spinedTouchSighted-f-t-0.05",
        ] {
            let c = SensorConfig::parse(text).unwrap();
            assert_eq!(c.to_string(), text);
            let json = serde_json::to_string(&c).unwrap();
            assert_eq!(json, format!("\"{text}\""));
            assert_eq!(serde_json::from_str::<SensorConfig>(&json).unwrap(), c);
        }
        let per_voxel: SensorConfig = serde_json::from_str(r#"[["a", "t"], []]"#).unwrap();
        assert_eq!(per_voxel, SensorConfig::PerVoxel(lists(&[&["a", "t"], &[]])));
        assert_eq!(serde_json::to_string(&per_voxel).unwrap(), r#"[["a","t"],[]]"#);
    }

    #[test]
    fn serde_errors_are_readable() {
        let e = serde_json::from_str::<SensorConfig>("\"uniform-a+zz-0\"")
            .unwrap_err()
            .to_string();
        assert!(e.contains("'zz'"), "{e}");
        let e = serde_json::from_str::<SensorConfig>(r#"[["a"], ["nope"]]"#)
            .unwrap_err()
            .to_string();
        assert!(e.contains("'nope'") && e.contains("voxel 1"), "{e}");
        let e = serde_json::from_str::<SensorConfig>("5").unwrap_err().to_string();
        assert!(e.contains("sensor placement string"), "{e}");
    }
}
