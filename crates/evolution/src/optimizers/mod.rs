//! The optimizers, one per file. Each implements [`Optimizer`](crate::Optimizer) and
//! [`Tell`](crate::Tell) and is serde-serialisable for checkpoints.

pub mod canonical_es;
pub mod cma_es;
pub mod cma_termination;
pub mod ga;
pub mod map_elites;
pub mod neat;
pub mod nsga2;
pub mod speciated;
