//! Sensors (filled in next).
