"""EvoGym's own PPO beside vsrlab's, on one fixed body (issue 35).

EvoGym 2.0's example trains controllers with stable-baselines3's PPO (examples/ppo/run.py).
This script runs that PPO with the settings vsrlab's PPO uses by default (the EvoGym 2022
examples': 4 environments x 128 steps per iteration, 4 epochs of 4 minibatches, learning rate
2.5e-4 falling linearly to 0, clip 0.1, GAE lambda 0.95, gamma 0.99, value coefficient 0.5,
entropy 0.01, gradient norm 0.5, separate 64-64 tanh actor and critic, log sigma 0 at first,
observations normalised and clipped to +-10, rewards not normalised). As EvoGym 2022's
environments did (and vsrlab's), the policy's action a is the target length ratio 1 + a:
EvoGym 2.0 dropped the shift, and without it a fresh policy's actions near 0 are all clipped to
0.6. It prints the return of a deterministic episode every EVERY iterations and the seconds per
iteration of training (collection + update, the evaluations excluded): the figures
`cargo run --release -p vsrlab-experiment --example ppo_evogym` prints for vsrlab.

    bench/evogym/ppo.sh                      # creates bench/evogym/.venv-ppo (torch, SB3, EvoGym)
    bench/evogym/.venv-ppo/bin/python bench/evogym/ppo.py --task BridgeWalker-v0 --iterations 20
"""
import argparse
import time

import gymnasium as gym
import numpy as np
import torch
import evogym.envs  # noqa: F401  (registers the environments)
from stable_baselines3 import PPO
from stable_baselines3.common.callbacks import BaseCallback
from stable_baselines3.common.env_util import make_vec_env
from stable_baselines3.common.vec_env import VecNormalize

STEPS = {"Walker-v0": 500, "BridgeWalker-v0": 500, "BeamToppler-v0": 1000, "CaveCrawler-v0": 1000}


class ShiftedAction(gym.ActionWrapper):
    """The policy's a becomes EvoGym's 1 + a (EvoGym 2022's environments)."""

    def __init__(self, env):
        super().__init__(env)
        low, high = env.action_space.low - 1.0, env.action_space.high - 1.0
        self.action_space = gym.spaces.Box(low=low, high=high, dtype=env.action_space.dtype)

    def action(self, action):
        return action + 1.0


def make(task, body):
    return ShiftedAction(gym.make(task, body=body))


def episode(model, normalize, task, body):
    """Return of one episode of the policy's mean actions, observations normalised as in training."""
    env = make(task, body)
    obs, _ = env.reset(seed=0)
    total = 0.0
    for _ in range(STEPS[task]):
        action, _ = model.predict(normalize.normalize_obs(obs), deterministic=True)
        obs, reward, term, trunc, _ = env.step(action)
        total += reward
        if term or trunc:
            break
    return total


class Report(BaseCallback):
    """Times the training and evaluates every `every` iterations (not timed)."""

    def __init__(self, task, body, every, steps_per_iteration):
        super().__init__()
        self.task, self.body, self.every, self.per = task, body, every, steps_per_iteration
        self.training, self.started, self.done = 0.0, None, 0

    def _on_training_start(self):
        self.started = time.perf_counter()

    def _on_rollout_start(self):
        done = self.model.num_timesteps // self.per
        if done > self.done or done == 0:
            self.training += time.perf_counter() - self.started
            if done % self.every == 0:
                ret = episode(self.model, self.model.get_env(), self.task, self.body)
                print(f"after {done:4d} iterations: return of the mean policy {ret:+.3f}", flush=True)
            self.done = done
            self.started = time.perf_counter()

    def _on_training_end(self):
        self.training += time.perf_counter() - self.started
        done = self.model.num_timesteps // self.per
        ret = episode(self.model, self.model.get_env(), self.task, self.body)
        print(f"after {done:4d} iterations: return of the mean policy {ret:+.3f}", flush=True)

    def _on_step(self):
        return True


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--task", default="Walker-v0", choices=sorted(STEPS))
    p.add_argument("--iterations", type=int, default=100)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--every", type=int, default=25)
    p.add_argument("--threads", type=int, default=1, help="torch threads (default 1)")
    p.add_argument("--body", default="33333/33333/33333/33333/33333", help="rows of material digits, top first")
    a = p.parse_args()
    torch.set_num_threads(a.threads)
    body = np.array([[int(c) for c in row] for row in a.body.split("/")])
    envs, steps = 4, 128
    vec = make_vec_env(lambda: make(a.task, body), n_envs=envs, seed=a.seed)
    vec = VecNormalize(vec, norm_obs=True, norm_reward=False, clip_obs=10.0, gamma=0.99)
    model = PPO(
        "MlpPolicy",
        vec,
        learning_rate=lambda remaining: 2.5e-4 * remaining,
        n_steps=steps,
        batch_size=envs * steps // 4,
        n_epochs=4,
        gamma=0.99,
        gae_lambda=0.95,
        clip_range=0.1,
        ent_coef=0.01,
        vf_coef=0.5,
        max_grad_norm=0.5,
        policy_kwargs=dict(net_arch=dict(pi=[64, 64], vf=[64, 64]), activation_fn=torch.nn.Tanh, log_std_init=0.0),
        seed=a.seed,
        device="cpu",
        verbose=0,
    )
    report = Report(a.task, body, a.every, envs * steps)
    model.learn(total_timesteps=a.iterations * envs * steps, callback=report)
    total = a.iterations * envs * steps
    print(
        f"{a.task}, body {a.body}: {a.iterations} iterations ({total} steps) in {report.training:.1f} s of training: "
        f"{1000 * report.training / a.iterations:.1f} ms per iteration, {total / report.training:.0f} steps/s with the updates"
    )


if __name__ == "__main__":
    main()
