//! The run's record of structural innovations: every connection (from, to) gets one innovation
//! number, and splitting a connection gets one new node id, the same whichever genome makes it
//! first, so that the same structure arising twice lines up in crossover and in the distance.

use serde::{Deserialize, Serialize};

/// Innovation numbers of connections and node ids of splits, kept for a whole run.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Innovations {
    /// (from, to, innovation) of every connection seen.
    connections: Vec<(u32, u32, u32)>,
    /// (from, to, node) of every connection split.
    splits: Vec<(u32, u32, u32)>,
    next_innovation: u32,
    next_node: u32,
}

impl Innovations {
    /// A record whose new node ids start after `nodes` (the inputs, bias and outputs).
    pub fn new(nodes: u32) -> Innovations {
        Innovations {
            next_node: nodes,
            ..Innovations::default()
        }
    }

    /// The innovation number of the connection `from → to`, given on first sight.
    pub fn connection(&mut self, from: u32, to: u32) -> u32 {
        if let Some(&(_, _, i)) = self.connections.iter().find(|c| c.0 == from && c.1 == to) {
            return i;
        }
        let i = self.next_innovation;
        self.next_innovation += 1;
        self.connections.push((from, to, i));
        i
    }

    /// The id of the node that splits `from → to`, given on first sight.
    pub fn split(&mut self, from: u32, to: u32) -> u32 {
        if let Some(&(_, _, n)) = self.splits.iter().find(|s| s.0 == from && s.1 == to) {
            return n;
        }
        let n = self.next_node;
        self.next_node += 1;
        self.splits.push((from, to, n));
        n
    }
}
