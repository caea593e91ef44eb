//! The ground half-plane: a penalty spring along y and regularised Coulomb friction along x.

use super::settings::GroundPlane;
use vsrlab_lanes::fdlibm_tanh;

/// The force `(fx, fy)` the ground puts on a point at height `y` moving at `vx` along the ground:
/// nothing above the surface; below it a normal force `stiffness × depth` and a friction
/// `-friction × normal × tanh(sharpness × vx × normal)`.
pub(crate) fn ground_force(g: &GroundPlane, y: f64, vx: f64) -> (f64, f64) {
    let depth = g.height - y;
    if depth <= 0.0 {
        return (0.0, 0.0);
    }
    let normal = depth * g.stiffness;
    let friction = -g.friction * normal * fdlibm_tanh(g.friction_sharpness * vx * normal);
    (friction, normal)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ground_pushes_up_in_proportion_to_depth_and_friction_saturates_at_mu_times_normal() {
        let g = GroundPlane::evogym();
        assert_eq!(ground_force(&g, 0.0, 5.0), (0.0, 0.0), "touching is not contact");
        let (fx, fy) = ground_force(&g, -1e-5, 10.0);
        assert!((fy - 140.0).abs() < 1e-9, "1.4e7 × 1e-5");
        assert!((fx + 2.0 * 140.0).abs() < 1e-6, "fast sliding: μ = 2");
        let (fx, _) = ground_force(&g, -1e-5, -1e-6);
        // Slow sliding is viscous: -2 × 140 × (0.2 × -1e-6 × 140).
        assert!((fx - 2.0 * 140.0 * 0.2 * 1e-6 * 140.0).abs() < 1e-9);
    }
}
