//! Soft-constraint coefficients (Box2D-style "soft step").

/// Coefficients that make a rigid constraint behave like a stiff damped spring for one sub-step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Softness {
    /// Fraction of the position error corrected per second.
    pub bias_rate: f64,
    /// Scale of the effective mass.
    pub mass_scale: f64,
    /// Scale of the accumulated impulse that is fed back.
    pub impulse_scale: f64,
}

impl Softness {
    /// Softness for natural frequency `hertz`, damping ratio `zeta`, sub-step `h`.
    pub fn new(hertz: f64, zeta: f64, h: f64) -> Softness {
        let omega = 2.0 * std::f64::consts::PI * hertz;
        let a1 = 2.0 * zeta + h * omega;
        let a2 = h * omega * a1;
        let a3 = 1.0 / (1.0 + a2);
        Softness {
            bias_rate: omega / a1,
            mass_scale: a2 * a3,
            impulse_scale: a3,
        }
    }
}
