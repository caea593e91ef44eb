"""EvoGym's task ids as EvoGym registers them (``gym.make("Walker-v0", body=...)``), each
vsrlab's environment of that task, with its episode length."""

import gymnasium

import vsrlab  # noqa: F401  (registers vsrlab-evogym/<id>)
from vsrlab.envs import EVOGYM_ENVIRONMENTS

for _id, _class in EVOGYM_ENVIRONMENTS.items():
    if _id.startswith("vsrlab-evogym/"):
        _name = _id.split("/", 1)[1]
        if _name not in gymnasium.registry:
            _spec = gymnasium.spec(_id)
            gymnasium.register(id=_name, entry_point=f"vsrlab.envs:{_class}", max_episode_steps=_spec.max_episode_steps)
