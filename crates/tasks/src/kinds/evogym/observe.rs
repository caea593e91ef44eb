//! What EvoGym's tasks observe of an object, computed from a world's point slices without
//! allocating. Units are the simulator's (a cell is 0.1): `EvoSim` divides positions and
//! velocities by 0.1 (`evogym/sim.py:185-228`) and `BenchmarkBase` multiplies them by 0.1 again
//! (`evogym/envs/base.py:396-424`), so the two cancel.

use std::ops::Range;

/// Mean of `values` over `points` (EvoGym's centre of mass: every point has mass 1).
pub fn mean(values: &[f64], points: Range<usize>) -> f64 {
    let n = points.len() as f64;
    values[points].iter().sum::<f64>() / n
}

/// The object's points relative to their mean: all x first, then all y, as numpy flattens a
/// `(2, n)` array (`get_relative_pos_obs`, `evogym/envs/base.py:250-262`). `out` holds `2 n`.
pub fn relative_positions(xs: &[f64], ys: &[f64], points: Range<usize>, out: &mut [f64]) {
    let n = points.len();
    let (cx, cy) = (mean(xs, points.clone()), mean(ys, points.clone()));
    for (k, i) in points.enumerate() {
        out[k] = xs[i] - cx;
        out[n + k] = ys[i] - cy;
    }
}

/// Rotation of an object since the start, in radians within [0, 2π), as EvoGym estimates it
/// (`Environment::object_orientation_at_time`, `Environment.cpp:317-380`): each point's angle
/// between its start and current offsets from the centre (acos of the unit vectors' dot,
/// clamped into ±0.99999, 0.99999 when either offset is shorter than ~3e-4), averaged with
/// weights the start distances; when the summed cross product `new × old` is positive (a
/// clockwise turn) the angle is 2π − angle, with π written 3.1415926.
#[derive(Debug, Clone, PartialEq)]
pub struct Orientation {
    /// Start offsets of the points from their centre.
    start: Vec<(f64, f64)>,
}

impl Orientation {
    /// Remembers the object's start offsets.
    pub fn new(xs: &[f64], ys: &[f64], points: Range<usize>) -> Orientation {
        let (cx, cy) = (mean(xs, points.clone()), mean(ys, points.clone()));
        Orientation {
            start: points.map(|i| (xs[i] - cx, ys[i] - cy)).collect(),
        }
    }

    /// The current orientation of the object whose points are `points`.
    pub fn angle(&self, xs: &[f64], ys: &[f64], points: Range<usize>) -> f64 {
        let (cx, cy) = (mean(xs, points.clone()), mean(ys, points.clone()));
        let (mut weighted, mut weights, mut cross) = (0.0, 0.0, 0.0);
        for (&(ox, oy), i) in self.start.iter().zip(points) {
            let (nx, ny) = (xs[i] - cx, ys[i] - cy);
            let (old_len, new_len) = (ox.hypot(oy), nx.hypot(ny));
            let (ou, nu) = (unit(ox, oy, old_len), unit(nx, ny, new_len));
            let mut dot = nu.0 * ou.0 + nu.1 * ou.1;
            if new_len * old_len < 1e-7 || dot > 1.0 {
                dot = 0.99999;
            } else if dot < -1.0 {
                dot = -0.99999;
            }
            weighted += dot.acos() * old_len;
            weights += old_len;
            cross += nu.0 * ou.1 - nu.1 * ou.0;
        }
        let average = weighted / weights;
        if cross > 0.0 {
            2.0 * EVOGYM_PI - average
        } else {
            average
        }
    }
}

/// π as EvoGym writes it in `object_orientation_at_time` (`Environment.cpp:369`).
#[allow(clippy::approx_constant)]
const EVOGYM_PI: f64 = 3.1415926;

/// `(x, y)` divided by its length `len`, or unchanged when the length is 0 (Eigen's
/// `normalized`).
fn unit(x: f64, y: f64, len: f64) -> (f64, f64) {
    if len > 0.0 {
        (x / len, y / len)
    } else {
        (x, y)
    }
}

/// Which way [`terrain_distances`] looks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Look {
    /// Down to the highest terrain point below the centre (`get_floor_obs`).
    Floor,
    /// Up to the lowest terrain point above the centre (`get_ceil_obs`).
    Ceiling,
}

/// How a floor or ceiling observation places the robot's centre in cells, and what an empty bin
/// reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Centre {
    /// EvoGym's arithmetic: each point's coordinate divided by the cell size, then numpy's mean
    /// of them (its pairwise sum, [`numpy_sum`]); an empty bin reads `cy − (cy − range)` (floor)
    /// or `(range + cy) − cy` (ceiling) before the clip, as `base.py:313`/`:366` compute it.
    /// At reset the centre sits on a bin border, and only this arithmetic puts the border points
    /// in EvoGym's bins.
    EvoGym,
    /// vsrlab's first form, kept for CaveCrawler-v0 (ch. 5.2's results were run with it): the
    /// mean in simulator units, then divided by the cell size; an empty bin reads `range`. It
    /// differs from EvoGym's in bins whose points lie on a border (docs/evogym-envs.md).
    MeanFirst,
}

/// numpy's sum of `n` values `value(0)`, …, `value(n − 1)` along a contiguous row (`add.reduce`):
/// fewer than 8 left to right from 0; up to 128 in eight interleaved sums, combined pairwise,
/// then the rest; more in halves (a multiple of 8 first), recursively. `np.mean` is this over n.
pub fn numpy_sum(n: usize, value: &impl Fn(usize) -> f64) -> f64 {
    numpy_sum_from(0, n, value)
}

fn numpy_sum_from(start: usize, n: usize, value: &impl Fn(usize) -> f64) -> f64 {
    if n < 8 {
        return (start..start + n).fold(0.0, |sum, i| sum + value(i));
    }
    if n <= 128 {
        let mut r: [f64; 8] = std::array::from_fn(|j| value(start + j));
        let mut i = 8;
        while i < n - n % 8 {
            for (j, r) in r.iter_mut().enumerate() {
                *r += value(start + i + j);
            }
            i += 8;
        }
        let mut sum = ((r[0] + r[1]) + (r[2] + r[3])) + ((r[4] + r[5]) + (r[6] + r[7]));
        for k in i..n {
            sum += value(start + k);
        }
        return sum;
    }
    let half = n / 2 - (n / 2) % 8;
    numpy_sum_from(start, half, value) + numpy_sum_from(start + half, n - half, value)
}

/// EvoGym's floor or ceiling observation (`evogym/envs/base.py:276-379`, scaled by 0.1 at
/// `:420-424`). In cells: for each column offset `i` in `-sight..=sight`, the terrain points whose
/// x lies strictly between `cx + i - 0.5` and `cx + i + 0.5` and whose y is below (floor) or
/// above (ceiling) the centre `cy`; the distance from `cy` to the highest (floor) or lowest
/// (ceiling) of them, `range` when there is none, clipped into `[0, range]`; then times 0.1.
/// The centre is the mean of the `robot` points, placed as `centre` says; `out` holds
/// `2 sight + 1` values; bins past the 64th are never filled (EvoGym's tasks use a sight of at
/// most 5).
#[allow(clippy::too_many_arguments)]
pub fn terrain_distances(
    xs: &[f64],
    ys: &[f64],
    terrain: Range<usize>,
    robot: Range<usize>,
    centre: Centre,
    (sight, range): (usize, f64),
    look: Look,
    out: &mut [f64],
) {
    const VOXEL: f64 = 0.1;
    let n = robot.len();
    let (cx, cy) = match centre {
        Centre::EvoGym => {
            let (x, y) = (&xs[robot.clone()], &ys[robot]);
            (
                numpy_sum(n, &|i| x[i] / VOXEL) / n as f64,
                numpy_sum(n, &|i| y[i] / VOXEL) / n as f64,
            )
        }
        Centre::MeanFirst => (mean(xs, robot.clone()) / VOXEL, mean(ys, robot) / VOXEL),
    };
    let s = sight as f64;
    let mut found = [false; 64];
    for i in terrain {
        let (x, y) = (xs[i] / VOXEL, ys[i] / VOXEL);
        let beside = x > cx - (s + 0.5) && x < cx + (s + 0.5);
        let on_side = match look {
            Look::Floor => y < cy,
            Look::Ceiling => y > cy,
        };
        if !beside || !on_side {
            continue;
        }
        let offset = (x - cx).round();
        let k = offset + s;
        let in_bin = x > cx + (offset - 0.5) && x < cx + (offset + 0.5);
        if !in_bin || !(0.0..=2.0 * s).contains(&k) {
            continue;
        }
        let k = k as usize;
        if k >= found.len() {
            continue;
        }
        let better = match look {
            Look::Floor => y > out[k],
            Look::Ceiling => y < out[k],
        };
        if !found[k] || better {
            out[k] = y;
            found[k] = true;
        }
    }
    for (k, v) in out.iter_mut().enumerate().take(2 * sight + 1) {
        let found = found.get(k).copied().unwrap_or(false);
        let distance = match (found, look, centre) {
            (false, _, Centre::MeanFirst) => range,
            (false, Look::Floor, Centre::EvoGym) => cy - (-range + cy),
            (false, Look::Ceiling, Centre::EvoGym) => (range + cy) - cy,
            (true, Look::Floor, _) => cy - *v,
            (true, Look::Ceiling, _) => *v - cy,
        };
        *v = distance.clamp(0.0, range) * VOXEL;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn relative_positions_list_all_x_then_all_y() {
        let xs = [9.0, 0.0, 2.0, 2.0, 0.0];
        let ys = [9.0, 0.0, 0.0, 1.0, 1.0];
        let mut out = [0.0; 8];
        relative_positions(&xs, &ys, 1..5, &mut out);
        assert_eq!(out, [-1.0, 1.0, 1.0, -1.0, -0.5, -0.5, 0.5, 0.5]);
        assert_eq!(mean(&xs, 1..5), 1.0);
    }

    /// A square of four points turned by a quarter turn counter-clockwise: every offset turns by
    /// π/2, the cross product `new × old` is negative, so the angle is π/2; turned clockwise the
    /// angle is 2·3.1415926 − π/2.
    #[test]
    fn orientation_of_a_turned_square() {
        let (xs, ys) = ([1.0, -1.0, -1.0, 1.0], [1.0, 1.0, -1.0, -1.0]);
        let o = Orientation::new(&xs, &ys, 0..4);
        assert!(o.angle(&xs, &ys, 0..4).abs() < 1e-2, "acos(0.99999) ≈ 0.0045");
        // Counter-clockwise by π/2: (x, y) → (−y, x).
        let (cx, cy): (Vec<f64>, Vec<f64>) = xs.iter().zip(&ys).map(|(x, y)| (-y, *x)).unzip();
        assert!((o.angle(&cx, &cy, 0..4) - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        let (wx, wy): (Vec<f64>, Vec<f64>) = xs.iter().zip(&ys).map(|(x, y)| (*y, -x)).unzip();
        let expected = 2.0 * EVOGYM_PI - std::f64::consts::FRAC_PI_2;
        assert!((o.angle(&wx, &wy, 0..4) - expected).abs() < 1e-12);
    }

    /// A one-point robot at (0, 0.3) = cell coordinates (0, 3). Terrain points in cells: (0, 1)
    /// and (0, 2) below (highest 2: distance 1 cell), (2, 9) above (distance 6, clipped to 5),
    /// (0.5, 0) exactly on the border of bins 0 and 1 (in neither), (6, 0) beyond the sight of 5.
    #[test]
    fn floor_and_ceiling_distances_by_hand() {
        let pts = [(0.0, 1.0), (0.0, 2.0), (2.0, 9.0), (0.5, 0.0), (6.0, 0.0), (0.0, 3.0)];
        let xs: Vec<f64> = pts.iter().map(|p| p.0 * 0.1).collect();
        let ys: Vec<f64> = pts.iter().map(|p| p.1 * 0.1).collect();
        let mut floor = [0.0; 11];
        terrain_distances(
            &xs,
            &ys,
            0..5,
            5..6,
            Centre::MeanFirst,
            (5, 5.0),
            Look::Floor,
            &mut floor,
        );
        for (k, v) in floor.iter().enumerate() {
            let expected = if k == 5 { 0.1 } else { 0.5 };
            assert!((v - expected).abs() < 1e-12, "floor[{k}] = {v}");
        }
        let mut ceiling = [0.0; 11];
        terrain_distances(
            &xs,
            &ys,
            0..5,
            5..6,
            Centre::MeanFirst,
            (5, 5.0),
            Look::Ceiling,
            &mut ceiling,
        );
        assert!(ceiling.iter().all(|v| (v - 0.5).abs() < 1e-12), "{ceiling:?}");
        // Terrain above the centre in bin +2 closer than the range: 4 − 3 = 1 cell.
        let ys2: Vec<f64> = [1.0, 2.0, 4.0, 0.0, 0.0, 3.0].iter().map(|y| y * 0.1).collect();
        terrain_distances(
            &xs,
            &ys2,
            0..5,
            5..6,
            Centre::MeanFirst,
            (5, 5.0),
            Look::Ceiling,
            &mut ceiling,
        );
        assert!(
            (ceiling[7] - 0.1).abs() < 1e-12 && (ceiling[6] - 0.5).abs() < 1e-12,
            "{ceiling:?}"
        );
        // EvoGym's arithmetic agrees away from borders
        let mut exact = [0.0; 11];
        terrain_distances(
            &xs,
            &ys2,
            0..5,
            5..6,
            Centre::EvoGym,
            (5, 5.0),
            Look::Ceiling,
            &mut exact,
        );
        assert_eq!(exact, ceiling);
    }

    /// numpy's pairwise sum, not left to right, against numpy's own results (`np.add.reduce`,
    /// numpy 1.26 of bench/evogym/.venv): 2^53 then eight 1.0s sums to 2^53 + 8 (left to right
    /// each 1.0 is lost: 2^53 + 1 rounds to 2^53), the first seven to 2^53; 129 values, 1.0 but
    /// 2^53 at index 64, to 2^53 + 120.
    #[test]
    fn numpy_sum_adds_in_numpys_order() {
        let big = 2f64.powi(53);
        let values: Vec<f64> = std::iter::once(big).chain([1.0; 8]).collect();
        assert_eq!(values.iter().fold(0.0, |s, v| s + v), big);
        assert_eq!(numpy_sum(9, &|i| values[i]), big + 8.0);
        assert_eq!(numpy_sum(7, &|i| values[i]), big);
        let many: Vec<f64> = (0..129).map(|i| if i == 64 { big } else { 1.0 }).collect();
        assert_eq!(numpy_sum(129, &|i| many[i]), big + 120.0);
    }
}
