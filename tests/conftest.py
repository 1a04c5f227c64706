"""Shared test configuration: deterministic hypothesis runs, no deadlines (CI machines vary);
the refits of the stored data, computed once per session for the modules that read them; a
small ROS map for the command line's tests."""

import pytest
from hypothesis import HealthCheck, settings

settings.register_profile(
    "segplan",
    derandomize=True,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow],
    print_blob=True,
)
settings.load_profile("segplan")


@pytest.fixture(scope="session")
def refit():
    """``segplan.fit.store.compute()``: the fits of the stored constants (about 1 s of CPU),
    for test_constants (compared with the stored file, and fed to ``--check``)."""
    from segplan.fit.store import compute

    return compute()


@pytest.fixture(scope="session")
def recomputed():
    """``segplan.fit.store.compute_primitives()``: the stored default primitives recomputed
    (about 1 s of CPU), for test_primitives_data and test_constants' ``--check``. Read only."""
    from segplan.fit.store import compute_primitives

    return compute_primitives()


@pytest.fixture(scope="session", autouse=True)
def cold_primitive_sets():
    """Each session starts without primitive sets in memory (``primitive_set``'s cache, with
    each set's fine points and heading tables). A fresh process has none anyway; a session run
    in a process that already planned does: benchmarks/mutation.py's mutmut forks every
    mutant's session from the process that ran the clean tests, whose sets, made by the
    unmutated code, would hide a mutant of the code that makes them."""
    from segplan.planning.lattice.primitives import primitive_set

    primitive_set.cache_clear()


@pytest.fixture
def room_map(tmp_path):
    """A 10 x 6 m room at 0.1 m (map_server PGM and YAML): walls, and an unknown (grey) block
    at x 4..6 m, y 0..6 m across the room, so only unknown cells made free let a plan through."""
    import numpy as np

    img = np.full((60, 100), 254, dtype=np.uint8)
    img[:, :2] = img[:, -2:] = img[:2, :] = img[-2:, :] = 0
    img[2:-2, 40:60] = 205
    (tmp_path / "room.pgm").write_bytes(b"P5\n100 60\n255\n" + img.tobytes())
    path = tmp_path / "room.yaml"
    path.write_text("image: room.pgm\nresolution: 0.1\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n")
    return str(path)
