//! What can go wrong while building or stepping a 3D world.

/// An error of the 3D engine.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Physics3dError {
    /// A description that cannot be simulated; the message names the value.
    #[error("{0}")]
    Invalid(String),
    /// A material value out of its range; the error names the field.
    #[error("{0}")]
    Material(vsrlab_field::FieldError),
    /// A link stretched beyond 100 times its length (before any voxel moved), or a voxel's
    /// state became NaN or infinite.
    #[error("the simulation diverged at step {step} (voxel {voxel})")]
    Diverged {
        /// Steps taken before the one that diverged.
        step: u64,
        /// The first voxel (or a voxel of the first link) found diverging.
        voxel: usize,
    },
}
