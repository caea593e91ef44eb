//! Reproducible random actions shared with `bench/evogym`'s Python scripts, so that EvoGym and
//! vsrlab can be driven by the very same action sequences and their trajectories compared.

/// A splitmix64 stream of actions (the generator both sides implement bit for bit).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ActionStream(u64);

impl ActionStream {
    /// The stream of seed `seed`.
    pub fn new(seed: u64) -> ActionStream {
        ActionStream(seed)
    }

    /// The next 64 random bits.
    pub fn next_bits(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A number in [0, 1): the top 53 bits.
    pub fn uniform(&mut self) -> f64 {
        (self.next_bits() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Fills `actions` with values uniform in [`low`, `high`).
    pub fn fill_uniform(&mut self, actions: &mut [f64], low: f64, high: f64) {
        actions
            .iter_mut()
            .for_each(|a| *a = low + self.uniform() * (high - low));
    }

    /// Fills `actions` with `low` or `high`, each with probability one half.
    pub fn fill_extremes(&mut self, actions: &mut [f64], low: f64, high: f64) {
        actions
            .iter_mut()
            .for_each(|a| *a = if self.uniform() < 0.5 { low } else { high });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The first outputs of splitmix64 from seed 0 (its reference values), and the uniform draw
    /// the Python side computes from the first of them.
    #[test]
    fn the_stream_is_splitmix64() {
        let mut s = ActionStream::new(0);
        assert_eq!(s.next_bits(), 0xE220_A839_7B1D_CDAF);
        assert_eq!(s.next_bits(), 0x6E78_9E6A_A1B9_65F4);
        let mut s = ActionStream::new(0);
        assert_eq!(
            s.uniform(),
            (0xE220_A839_7B1D_CDAFu64 >> 11) as f64 / 9007199254740992.0
        );
    }
}
