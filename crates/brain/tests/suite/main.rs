//! Every integration test of this crate in one binary (one link instead of one per file: CI
//! time); each file is a module.

mod attention_props;
mod bounds;
mod graph_ops_props;
mod graph_props;
mod hebbian_props;
mod layouts;
