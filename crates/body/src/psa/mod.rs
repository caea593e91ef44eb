//! Pressure-based soft agents (thesis ch. 6): a membrane of square masses joined in a ring by
//! springs, around a gas whose pressure gives the body its shape. [`PsaParams`] holds the
//! constants (sizes small/medium/large as presets), [`Psa`] is the body in a world, and
//! [`PsaSensors`] its 3n+3 averaged readings.

pub mod membrane;
pub mod params;
pub mod sensors;
pub mod spec;

pub use membrane::Psa;
pub use params::{GasAmount, PressureLength, PsaParams, PsaSize, SCALE_RANGE};
pub use sensors::PsaSensors;
pub use spec::PsaBody;
