"""EvoGym's ``evogym.utils`` names, from vsrlab.evogym."""

from vsrlab.evogym import (  # noqa: F401
    BASELINE_ENV_NAMES,
    VOXEL_TYPES,
    draw,
    get_full_connectivity,
    get_uniform,
    has_actuator,
    is_connected,
    sample_robot,
)
