//! One PPO epoch's network work on the actor of a 5×5 EvoGym Walker (74 observations, 64-64 tanh,
//! 25 actions): forward and backward passes of 512 samples (4 environments × 128 steps) in
//! minibatches of 128, with vsrlab-learning's per-sample `Mlp` and with candle's batched tensors
//! (matmul, tanh, autograd) on the CPU, one thread. Prints milliseconds per epoch.

use candle_core::{DType, Device, Tensor, Var};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::time::Instant;
use vsrlab_learning::Mlp;

const SIZES: [usize; 4] = [74, 64, 64, 25];
const SAMPLES: usize = 512;
const MINIBATCH: usize = 128;

/// Milliseconds of `f` per call, the best of `repeats` rounds of `calls` calls.
fn time(repeats: usize, calls: usize, mut f: impl FnMut()) -> f64 {
    (0..repeats)
        .map(|_| {
            let start = Instant::now();
            for _ in 0..calls {
                f();
            }
            1000.0 * start.elapsed().as_secs_f64() / calls as f64
        })
        .fold(f64::INFINITY, f64::min)
}

fn ours() -> f64 {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let mlp = Mlp::new(&SIZES, 0.01, &mut rng);
    let inputs: Vec<Vec<f64>> = (0..SAMPLES)
        .map(|i| {
            (0..SIZES[0])
                .map(|j| ((i * 31 + j * 7) % 13) as f64 / 13.0 - 0.5)
                .collect()
        })
        .collect();
    let mut gradient = vec![0.0; mlp.parameters.len()];
    let upstream = vec![0.1; SIZES[3]];
    time(5, 3, || {
        for batch in inputs.chunks(MINIBATCH) {
            gradient.iter_mut().for_each(|g| *g = 0.0);
            for x in batch {
                let pass = mlp.forward(x);
                mlp.backward(&pass, &upstream, &mut gradient);
            }
        }
    })
}

fn candle(dtype: DType) -> candle_core::Result<f64> {
    let device = Device::Cpu;
    let layers: Vec<(Var, Var)> = SIZES
        .windows(2)
        .map(|p| {
            let w = Var::from_tensor(&Tensor::randn(0.0, 0.1, (p[1], p[0]), &device)?.to_dtype(dtype)?)?;
            let b = Var::from_tensor(&Tensor::zeros(p[1], dtype, &device)?)?;
            Ok((w, b))
        })
        .collect::<candle_core::Result<_>>()?;
    let inputs = Tensor::randn(0.0, 1.0, (SAMPLES, SIZES[0]), &device)?.to_dtype(dtype)?;
    let mut result = Ok(());
    let ms = time(5, 3, || {
        for k in 0..SAMPLES / MINIBATCH {
            let step = || -> candle_core::Result<()> {
                let mut x = inputs.narrow(0, k * MINIBATCH, MINIBATCH)?;
                for (l, (w, b)) in layers.iter().enumerate() {
                    x = x.matmul(&w.as_tensor().t()?)?.broadcast_add(b.as_tensor())?;
                    if l + 1 < layers.len() {
                        x = x.tanh()?;
                    }
                }
                let loss = (x.sum_all()? * 0.1)?;
                let grads = loss.backward()?;
                for (w, _) in &layers {
                    grads.get(w.as_tensor()).expect("a gradient per weight");
                }
                Ok(())
            };
            if let Err(e) = step() {
                result = Err(e);
            }
        }
    });
    result.map(|()| ms)
}

fn main() -> candle_core::Result<()> {
    println!(
        "one epoch: {SAMPLES} samples in minibatches of {MINIBATCH}, actor {SIZES:?}, forward + backward, 1 thread"
    );
    println!("vsrlab-learning (f64, per sample): {:.2} ms", ours());
    println!("candle-core 0.9 (f64, batched):      {:.2} ms", candle(DType::F64)?);
    println!("candle-core 0.9 (f32, batched):      {:.2} ms", candle(DType::F32)?);
    Ok(())
}
