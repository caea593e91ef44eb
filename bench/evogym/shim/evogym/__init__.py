"""Stands in for EvoGym's package so that EvoGym's own scripts and tests run on vsrlab unchanged
(bench/evogym/own_tests.sh puts this folder first on the path): every name comes from
vsrlab.evogym."""

from vsrlab.evogym import *  # noqa: F401,F403
from vsrlab.evogym import BASELINE_ENV_NAMES, VOXEL_TYPES  # noqa: F401
