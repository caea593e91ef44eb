//! NEAT's network genomes (Stanley & Miikkulainen 2002): node and connection genes with
//! innovation numbers, the compatibility distance that groups them into species, crossover
//! that lines genes up by innovation, and the structural and weight mutations. The optimizer
//! is [`crate::optimizers::neat`]. Any feed-forward network can be evolved this way: the CPPNs
//! of thesis ch. 5.2 are one use.

pub mod activation;
pub mod genome;
pub mod innovations;

pub use activation::Activation;
pub use genome::{ConnectionGene, Mutation, NetworkGenome, NodeGene, NodeKind};
pub use innovations::Innovations;
