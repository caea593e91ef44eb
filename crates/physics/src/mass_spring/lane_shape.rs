//! The part of a world's shape the laned work reads, renumbered compactly: only the points the
//! RK4 stages move and the ends of the springs they need, only those springs, only the tight
//! limits that can move a free point. A world's terrain is most of its points (BridgeWalker: 356
//! points, a robot of 36), and lanes multiply every array by the lane count, so the laned arrays
//! hold these alone. Renumbering keeps the order of points and springs, so every sum runs in the
//! scalar world's order.

use super::points::Points;
use super::projection::Projection;
use super::runs::Runs;
use super::springs::Springs;

/// The laned points and springs, numbered from 0 in the world's order.
#[derive(Debug, Clone)]
pub(crate) struct LaneShape {
    /// The world's index of each laned point.
    pub points: Vec<u32>,
    /// Laned points free to move.
    pub free: Runs,
    /// Laned points each RK4 stage moves.
    pub stage: [Runs; 4],
    pub mass: Vec<f64>,
    pub inverse_mass: Vec<f64>,
    pub masses_are_powers_of_two: bool,
    pub fixed: Vec<bool>,
    /// The world's index of each laned spring (the active ones).
    pub springs: Vec<u32>,
    /// Each laned spring's ends as laned points.
    pub a: Vec<u32>,
    pub b: Vec<u32>,
    pub stiffness: Vec<f64>,
    pub initial: Vec<f64>,
    pub band: Vec<f64>,
    /// Laned springs each RK4 stage needs.
    pub spring_stage: [Runs; 4],
    /// Laned springs with a free end (those the loose bands project).
    pub touching_free: Runs,
    /// The tight limits with a free end, in the world's order: laned spring and band.
    pub limits: Vec<(u32, f64)>,
}

impl LaneShape {
    /// The laned shape of a world's points, springs and projection.
    pub fn of(points: &Points, springs: &Springs, projection: &Projection) -> LaneShape {
        let n = points.x.len();
        let spring_list: Vec<u32> = springs.active.indices().map(|s| s as u32).collect();
        let mut laned = vec![false; n];
        points.stage[0].indices().for_each(|i| laned[i] = true);
        for &s in &spring_list {
            laned[springs.a[s as usize] as usize] = true;
            laned[springs.b[s as usize] as usize] = true;
        }
        let point_list: Vec<u32> = (0..n).filter(|&i| laned[i]).map(|i| i as u32).collect();
        let mut local = vec![u32::MAX; n];
        for (k, &i) in point_list.iter().enumerate() {
            local[i as usize] = k as u32;
        }
        let in_runs = |runs: &Runs, list: &[u32], total: usize| {
            let mut member = vec![false; total];
            runs.indices().for_each(|i| member[i] = true);
            Runs::where_(list.len(), |k| member[list[k] as usize])
        };
        let of_point = |v: &[f64]| point_list.iter().map(|&i| v[i as usize]).collect::<Vec<f64>>();
        let of_spring = |v: &[f64]| spring_list.iter().map(|&s| v[s as usize]).collect::<Vec<f64>>();
        let ends = |v: &[u32]| spring_list.iter().map(|&s| local[v[s as usize] as usize]).collect();
        let mut spring_local = vec![u32::MAX; springs.a.len()];
        for (k, &s) in spring_list.iter().enumerate() {
            spring_local[s as usize] = k as u32;
        }
        let free_end = |s: usize| !points.fixed[springs.a[s] as usize] || !points.fixed[springs.b[s] as usize];
        let limits = projection
            .limit_spring
            .iter()
            .zip(&projection.limit_band)
            .filter(|(&s, _)| free_end(s as usize))
            .map(|(&s, &band)| (spring_local[s as usize], band))
            .collect();
        let spring_count = springs.a.len();
        LaneShape {
            free: in_runs(&points.free, &point_list, n),
            stage: std::array::from_fn(|k| in_runs(&points.stage[k], &point_list, n)),
            mass: of_point(&points.mass),
            inverse_mass: of_point(&points.inverse_mass),
            masses_are_powers_of_two: points.masses_are_powers_of_two,
            fixed: point_list.iter().map(|&i| points.fixed[i as usize]).collect(),
            a: ends(&springs.a),
            b: ends(&springs.b),
            stiffness: of_spring(&springs.stiffness),
            initial: of_spring(&springs.initial),
            band: of_spring(&springs.band),
            spring_stage: std::array::from_fn(|k| in_runs(&springs.stages[k], &spring_list, spring_count)),
            touching_free: in_runs(springs.touching_free(), &spring_list, spring_count),
            limits,
            points: point_list,
            springs: spring_list,
        }
    }
}
