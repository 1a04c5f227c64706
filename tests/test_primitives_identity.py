"""Computed primitive sets are those of the reference: the same selection, the same numbers.

``tests/data/primitive_sets.npz`` holds 28 sets (unit ``L``, steering limits 5-80 deg,
resolutions ``L / 2`` to ``L / 16`` and ``R / 32``) computed by
:func:`segplan.planning.lattice.primitives.compute_primitive_set` before issue 25 made it
faster, written by ``benchmarks/primitives_identity.py --write ... --sample test`` (its
docstring: which sets, which fields). On the machine that wrote them the sets computed now
are equal bit for bit; other processors round the last bits differently (primitives module
docstring), hence the tolerance of 1e-12 relative.
"""

import math

import numpy as np
import pytest
from load_file import ROOT, load_file

from segplan.planning.lattice.primitives import compute_primitive_set, primitive_arrays

DATA = ROOT / "tests" / "data" / "primitive_sets.npz"


@pytest.fixture(scope="module")
def identity():
    return load_file(ROOT / "benchmarks" / "primitives_identity.py", "primitives_identity")


def test_computed_sets_equal_the_stored_reference(identity):
    with np.load(DATA) as z:
        old = {k: z[k] for k in z.files}
    pairs = [tuple(map(float, s.split("/"))) for s in identity.sets_of(old)]
    assert len(pairs) == 28
    new = identity.compute(pairs, identity.TEST_FIELDS, identity.TEST_POINTS)
    bad, worst, _ = identity.differences(new, old)
    assert bad == []
    assert set(worst) == {*identity.TEST_FIELDS, "points"}
    assert max(worst.values()) <= 1e-12, worst


@pytest.mark.parametrize(
    ("steer_deg", "cells"),
    [(31.7, 8.0), (44.9, 4.0), (58.3, 16.0), (12.0, 32.0 * math.tan(math.radians(12.0)))],
)
def test_the_screened_selection_is_the_fully_sampled_one(steer_deg, cells):
    # with margins every peak curvature is sampled at all 49 abscissae (the margins need
    # them); without, the unions whose ends already break the limit are not sampled further
    full = primitive_arrays(compute_primitive_set(1.0, math.radians(steer_deg), 1.0 / cells, margins={}))
    fast = primitive_arrays(compute_primitive_set(1.0, math.radians(steer_deg), 1.0 / cells))
    assert full.keys() == fast.keys()
    for key, value in full.items():
        assert np.array_equal(value, fast[key]), key
