//! Terrains (vsr-model.md §2.3): polylines with increasing x, turned into static ground quads.

use crate::java_random::JavaRandom;
use serde::{Deserialize, Serialize};
use vsrlab_field::FieldError;
use vsrlab_physics::{Polygon, Vec2, WorldBuilder};

/// Length of every terrain (world units).
pub const TERRAIN_LENGTH: f64 = 2000.0;
/// Width of the border walls at each end.
pub const BORDER_WIDTH: f64 = 10.0;
/// Height of the border walls.
pub const BORDER_HEIGHT: f64 = 100.0;
/// Largest standard deviation of a hilly or steppy terrain's height changes.
pub const MAX_STEP_HEIGHT: f64 = 100.0;
/// Largest mean segment width of a hilly or steppy terrain (half the terrain's length).
pub const MAX_STEP_WIDTH: f64 = TERRAIN_LENGTH / 2.0;
/// Friction coefficient of the ground (dyn4j's default fixture friction).
pub const GROUND_FRICTION: f64 = 0.2;

/// A terrain description, as written in configs: `flat`, `hilly-H-W[-S]`, `steppy-H-W[-S]`,
/// `uphill-A`, `downhill-A`. Without an explicit seed S, random terrains take the episode seed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "String", into = "String")]
pub enum Terrain {
    /// Flat ground at y = 5 between two walls.
    Flat,
    /// Random walk: steps of width ≈ W (±25 %), heights N(0, H²).
    Hilly {
        /// Standard deviation of each height change.
        height: f64,
        /// Mean width of each segment.
        width: f64,
        /// Explicit seed, or `None` for the episode seed.
        seed: Option<i64>,
    },
    /// Like hilly, but flat treads joined by 0.5-wide risers.
    Steppy {
        /// Standard deviation of each riser height.
        height: f64,
        /// Mean width of each tread.
        width: f64,
        /// Explicit seed, or `None` for the episode seed.
        seed: Option<i64>,
    },
    /// Ground rising by 1980·sin(A°) over its length.
    Uphill {
        /// Angle in degrees.
        angle: f64,
    },
    /// Ground falling by 1980·sin(A°) over its length.
    Downhill {
        /// Angle in degrees.
        angle: f64,
    },
    /// The PSA paper's hills (psa-model.md "Terrains"): vertices |N(0, H²)| high, segments
    /// max(W·N(1, 1/16), 1) wide, from x = −20 to about 400, a wall at each end.
    PsaHilly {
        /// Standard deviation of each vertex's height.
        height: f64,
        /// Mean width of each segment.
        width: f64,
        /// Explicit seed, or `None` for the episode seed.
        seed: Option<i64>,
    },
}

/// Where the PSA hills start and roughly end (x).
pub const PSA_HILLS: (f64, f64) = (-20.0, 400.0);

impl TryFrom<String> for Terrain {
    type Error = FieldError;
    fn try_from(s: String) -> Result<Self, FieldError> {
        s.parse()
    }
}

impl From<Terrain> for String {
    fn from(t: Terrain) -> String {
        t.to_string()
    }
}

impl std::fmt::Display for Terrain {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let seed = |s: &Option<i64>| s.map(|v| format!("-{v}")).unwrap_or_default();
        match self {
            Terrain::Flat => write!(f, "flat"),
            Terrain::Hilly { height, width, seed: s } => write!(f, "hilly-{height}-{width}{}", seed(s)),
            Terrain::Steppy { height, width, seed: s } => write!(f, "steppy-{height}-{width}{}", seed(s)),
            Terrain::Uphill { angle } => write!(f, "uphill-{angle}"),
            Terrain::Downhill { angle } => write!(f, "downhill-{angle}"),
            Terrain::PsaHilly { height, width, seed: s } => write!(f, "psa-hilly-{height}-{width}{}", seed(s)),
        }
    }
}

impl std::str::FromStr for Terrain {
    type Err = FieldError;
    /// Parses a terrain name; the error is about the name as a whole (no field path).
    fn from_str(s: &str) -> Result<Self, FieldError> {
        match s.strip_prefix("psa-") {
            Some(rest) if rest.starts_with("hilly-") => match parse_plain(rest, s)? {
                Terrain::Hilly { height, width, seed } => Ok(Terrain::PsaHilly { height, width, seed }),
                _ => Err(unknown_terrain(s)),
            },
            Some(_) => Err(unknown_terrain(s)),
            None => parse_plain(s, s),
        }
    }
}

/// The error for a name that is no terrain.
fn unknown_terrain(name: &str) -> FieldError {
    FieldError::message(format!(
        "unknown terrain '{name}': expected flat, hilly-H-W[-SEED], steppy-H-W[-SEED], uphill-DEG, downhill-DEG or psa-hilly-H-W[-SEED]"
    ))
}

/// Parses a terrain of the original's forms (`flat`, `hilly-…`, `steppy-…`, `uphill-…`,
/// `downhill-…`); errors quote `name`, the whole name the user wrote (`psa-hilly-…` for the
/// PSA hills, which share the hilly form).
fn parse_plain(s: &str, name: &str) -> Result<Terrain, FieldError> {
    let bad = || unknown_terrain(name);
    let parts: Vec<&str> = s.split('-').collect();
    let num = |i: usize| -> Result<f64, FieldError> {
        let v: f64 = parts.get(i).ok_or_else(bad)?.parse().map_err(|_| bad())?;
        if v.is_finite() && v >= 0.0 {
            Ok(v)
        } else {
            Err(bad())
        }
    };
    let seed = |i: usize| -> Result<Option<i64>, FieldError> {
        match parts.get(i) {
            None => Ok(None),
            Some(p) => p.parse().map(Some).map_err(|_| bad()),
        }
    };
    let out_of_range = |what: &str| FieldError::message(format!("terrain '{name}': {what}"));
    match parts[0] {
        "flat" if parts.len() == 1 => Ok(Terrain::Flat),
        "hilly" | "steppy" if (3..=4).contains(&parts.len()) => {
            let (height, width, seed) = (num(1)?, num(2)?, seed(3)?);
            if width <= 0.0 || width > MAX_STEP_WIDTH {
                return Err(out_of_range(&format!("width must be in (0, {MAX_STEP_WIDTH}]")));
            }
            if height > MAX_STEP_HEIGHT {
                return Err(out_of_range(&format!("height must be at most {MAX_STEP_HEIGHT}")));
            }
            Ok(if parts[0] == "hilly" {
                Terrain::Hilly { height, width, seed }
            } else {
                Terrain::Steppy { height, width, seed }
            })
        }
        "uphill" | "downhill" if parts.len() == 2 => {
            let angle = num(1)?;
            if angle >= 90.0 {
                return Err(out_of_range("angle must be below 90 degrees"));
            }
            Ok(if parts[0] == "uphill" {
                Terrain::Uphill { angle }
            } else {
                Terrain::Downhill { angle }
            })
        }
        _ => Err(bad()),
    }
}

impl Terrain {
    /// The terrain's polyline, (x, y) with increasing x; `episode_seed` seeds random terrains
    /// that have no explicit seed.
    pub fn profile(&self, episode_seed: u64) -> Vec<Vec2> {
        let end = TERRAIN_LENGTH - BORDER_WIDTH;
        match *self {
            Terrain::Flat => vec![
                Vec2::new(0.0, BORDER_HEIGHT),
                Vec2::new(BORDER_WIDTH, 5.0),
                Vec2::new(end, 5.0),
                Vec2::new(TERRAIN_LENGTH, BORDER_HEIGHT),
            ],
            Terrain::Hilly { height, width, seed } | Terrain::Steppy { height, width, seed } => {
                let steppy = matches!(self, Terrain::Steppy { .. });
                let mut rng = JavaRandom::new(seed.unwrap_or(episode_seed as i64));
                let mut pts = vec![Vec2::new(0.0, BORDER_HEIGHT), Vec2::new(BORDER_WIDTH, 0.0)];
                let (mut x, mut y) = (BORDER_WIDTH, 0.0);
                while x < end {
                    x += ((rng.next_gaussian() * 0.25 + 1.0) * width).max(1.0);
                    if steppy {
                        pts.push(Vec2::new(x, y));
                        x += 0.5;
                    }
                    y += rng.next_gaussian() * height;
                    pts.push(Vec2::new(x, y));
                }
                pts.push(Vec2::new(x + BORDER_WIDTH, BORDER_HEIGHT));
                pts
            }
            Terrain::PsaHilly { height, width, seed } => {
                let mut rng = JavaRandom::new(seed.unwrap_or(episode_seed as i64));
                let (start, end) = PSA_HILLS;
                let mut x = start;
                let mut pts = vec![Vec2::new(start - 1.0, BORDER_HEIGHT)];
                while x < end {
                    pts.push(Vec2::new(x, (rng.next_gaussian() * height).abs()));
                    x += ((rng.next_gaussian() * 0.25 + 1.0) * width).max(1.0);
                }
                let last = pts[pts.len() - 1];
                pts.push(Vec2::new(last.x + 1.0, BORDER_HEIGHT));
                pts
            }
            Terrain::Downhill { angle } => {
                let dy = end_drop(angle);
                vec![
                    Vec2::new(0.0, BORDER_HEIGHT + dy),
                    Vec2::new(BORDER_WIDTH, 5.0 + dy),
                    Vec2::new(end, 5.0),
                    Vec2::new(TERRAIN_LENGTH, BORDER_HEIGHT),
                ]
            }
            Terrain::Uphill { angle } => {
                let dy = end_drop(angle);
                vec![
                    Vec2::new(0.0, BORDER_HEIGHT),
                    Vec2::new(BORDER_WIDTH, 5.0),
                    Vec2::new(end, 5.0 + dy),
                    Vec2::new(TERRAIN_LENGTH, BORDER_HEIGHT + dy),
                ]
            }
        }
    }
}

fn end_drop(angle_deg: f64) -> f64 {
    (TERRAIN_LENGTH - 2.0 * BORDER_WIDTH) * angle_deg.to_radians().sin()
}

/// Height of the profile at `x` by linear interpolation; `None` outside it.
pub fn height_at(profile: &[Vec2], x: f64) -> Option<f64> {
    let i = profile.partition_point(|p| p.x < x);
    if i == 0 {
        return (profile.first()?.x == x).then(|| profile[0].y);
    }
    let (a, b) = (profile[i - 1], *profile.get(i)?);
    let t = if b.x > a.x { (x - a.x) / (b.x - a.x) } else { 0.0 };
    Some(a.y + (b.y - a.y) * t)
}

/// Adds one static quad per segment, down to 50 below the lowest point. Its corners are listed
/// as 2D-VSR-Sim lists them (top left, down, across, up), so that the top edge closes the
/// polygon: dyn4j numbers contact points by edge, and the closing edge's number is the one that
/// changes from step to step (vsr-model.md §2.1, docs/fidelity.md).
pub fn add_ground(builder: &mut WorldBuilder, profile: &[Vec2]) {
    let base = profile.iter().map(|p| p.y).fold(f64::INFINITY, f64::min) - 50.0;
    for w in profile.windows(2) {
        let (a, b) = (w[0], w[1]);
        let quad = [a, Vec2::new(a.x, base), Vec2::new(b.x, base), b];
        if let Some(poly) = Polygon::convex(&quad) {
            builder.add_static_polygon(poly, GROUND_FRICTION, 0.0);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for s in [
            "flat",
            "hilly-1-10",
            "hilly-1-10-3",
            "steppy-2-5-7",
            "uphill-20",
            "downhill-30",
            "psa-hilly-3-10",
            "psa-hilly-3-10-4",
        ] {
            let t: Terrain = s.parse().unwrap();
            assert_eq!(t.to_string(), s);
        }
        assert!("hilly-1".parse::<Terrain>().is_err());
        assert!("bumpy".parse::<Terrain>().is_err());
        assert!("hilly-1e9-10"
            .parse::<Terrain>()
            .unwrap_err()
            .message
            .contains("height"));
        assert!("steppy-1-1e9".parse::<Terrain>().unwrap_err().message.contains("width"));
        assert!("uphill-95".parse::<Terrain>().is_err());
        // the PSA hills quote the whole name
        let e = "psa-hilly-1e9-10".parse::<Terrain>().unwrap_err();
        assert_eq!(e.to_string(), "terrain 'psa-hilly-1e9-10': height must be at most 100");
        let e = "psa-hilly-x-10".parse::<Terrain>().unwrap_err();
        assert!(
            e.to_string().starts_with("unknown terrain 'psa-hilly-x-10': expected"),
            "{e}"
        );
        assert_eq!(e.path, "");
    }

    #[test]
    fn flat_profile_and_height() {
        let p = Terrain::Flat.profile(0);
        assert_eq!(height_at(&p, 100.0), Some(5.0));
        assert_eq!(height_at(&p, 5.0), Some(52.5));
        assert_eq!(height_at(&p, 2500.0), None);
    }

    /// Each ground quad closes on its top edge (last corner to the first), as in 2D-VSR-Sim, so
    /// that contact points on the ground are numbered (and warm started) as dyn4j numbers them.
    #[test]
    fn ground_quads_close_on_their_top_edge() {
        let profile: Vec<Vec2> = "hilly-1-10".parse::<Terrain>().unwrap().profile(3);
        let mut builder = WorldBuilder::new(vsrlab_physics::WorldSettings::default());
        add_ground(&mut builder, &profile);
        let world = builder.build().unwrap();
        let mut quads = 0;
        for (poly, w) in world.static_polygons().zip(profile.windows(2)) {
            let v = poly.verts();
            assert_eq!((v[0], v[v.len() - 1]), (w[0], w[1]));
            quads += 1;
        }
        assert_eq!(quads, profile.len() - 1);
    }

    #[test]
    fn uphill_uses_sine_of_the_angle() {
        let p = Terrain::Uphill { angle: 30.0 }.profile(0);
        assert!((p[2].y - (5.0 + 990.0)).abs() < 1e-9);
    }

    #[test]
    fn hilly_is_seeded_and_spans_the_terrain() {
        let t: Terrain = "hilly-1-10".parse().unwrap();
        let a = t.profile(1);
        assert_eq!(a, t.profile(1));
        assert_ne!(a, t.profile(2));
        assert!(a.windows(2).all(|w| w[1].x > w[0].x));
        assert!(a[a.len() - 2].x >= TERRAIN_LENGTH - BORDER_WIDTH);
        let explicit: Terrain = "hilly-1-10-5".parse().unwrap();
        assert_eq!(explicit.profile(1), explicit.profile(9));
        let steppy: Terrain = "steppy-1-10".parse().unwrap();
        let s = steppy.profile(3);
        // treads are flat: every other segment has zero slope
        assert!(s[1..s.len() - 1].windows(2).step_by(2).all(|w| w[0].y == w[1].y));
    }

    #[test]
    fn psa_hills_are_non_negative_seeded_and_walled() {
        let t: Terrain = "psa-hilly-3-10".parse().unwrap();
        let p = t.profile(5);
        assert_eq!(p, t.profile(5));
        assert_ne!(p, t.profile(6));
        assert!(p.windows(2).all(|w| w[1].x > w[0].x));
        assert_eq!(p[1].x, PSA_HILLS.0);
        assert!(p[1..p.len() - 1].iter().all(|v| v.y >= 0.0));
        assert!(p[p.len() - 2].x >= PSA_HILLS.1 - 30.0);
        assert_eq!((p[0].y, p[p.len() - 1].y), (BORDER_HEIGHT, BORDER_HEIGHT));
        let mean = p[1..p.len() - 1].iter().map(|v| v.y).sum::<f64>() / (p.len() - 2) as f64;
        // E|N(0, 3²)| = 3·√(2/π) ≈ 2.39
        assert!((mean - 2.39).abs() < 0.6, "mean height {mean}");
        assert!("psa-hilly-1e9-10"
            .parse::<Terrain>()
            .unwrap_err()
            .message
            .contains("height"));
        assert!("psa-flat".parse::<Terrain>().is_err());
    }
}
