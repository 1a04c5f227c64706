"""The batched computations of the primitive sets equal their one-at-a-time oracles bit for bit.

:func:`segplan.model.union.max_curvatures` (many unions' exact peak curvature, the roots of
quartics of one degree in one eigenvalue call), ``cubic_coefficients(..., each=True)`` and the
chain index :class:`segplan.planning.lattice.chains.Chains` against literal copies of the
per-union and breadth-first code they replaced in ``compute_primitive_set``.
"""

import math

import numpy as np
import pytest

import segplan.planning.lattice.primitives as primitives
from segplan import Union
from segplan.model.pose import alpha_interval
from segplan.model.union import _quartic, cubic_coefficients, max_curvatures
from segplan.planning.lattice.chains import Chains


def _random_unions(n, seed):
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < n:
        d, phi0, phi1 = rng.uniform(0.05, 5.0), *rng.uniform(-1.4, 1.4, 2)
        lo, hi = alpha_interval(phi0, phi1)
        if hi - lo > 1e-6:
            a = lo + (hi - lo) * rng.uniform(0.01, 0.99)
            out.append(Union((0.0, 0.0, phi0), (d, 0.0, phi1), a, rng.uniform(0.5, 2.0)))
    return out


def _max_curvature_per_union(u):
    """``Union.max_curvature`` as it was (literal copy): the roots of one quartic, then the curvature."""
    _, c1, c2, c3 = u.coefficients
    crit = _quartic(c1, c2, c3)
    roots = []
    if np.any(crit != 0):
        if len(crit) == 2:
            r = np.array([-crit[0] / crit[1]])
        else:
            n = len(crit) - 1
            mat = np.zeros((n, n))
            mat.reshape(-1)[n :: n + 1] = 1
            mat[:, -1] -= crit[:-1] / crit[-1]
            r = np.linalg.eigvals(mat)
            r.sort()
        roots = [v.real for v in r if abs(v.imag) < 1e-9 and 0.0 < v.real < u.x_end]
    x = np.array([0.0, u.x_end, *roots])
    return float(
        np.max(np.abs((6.0 * c3 * x + 2.0 * c2) / (1.0 + ((3.0 * c3 * x + 2.0 * c2) * x + c1) ** 2) ** 1.5))
    )


def test_max_curvatures_are_the_per_union_values_bit_for_bit():
    unions = _random_unions(3000, 1)
    X = [u.x_end for u in unions]
    c1, c2, c3 = zip(*(u.coefficients[1:] for u in unions), strict=True)
    got = max_curvatures(X, c1, c2, c3)
    want = np.array([_max_curvature_per_union(u) for u in unions])
    assert np.array_equal(got, want)
    assert [u.max_curvature() for u in unions[:200]] == want[:200].tolist()


def test_cubic_coefficients_each_are_the_scalar_calls_bit_for_bit():
    unions = _random_unions(3000, 2)
    d, phi0, phi1, alpha = (
        np.array(v) for v in zip(*((u.d, u.phi0, u.phi1, u.alpha) for u in unions), strict=True)
    )
    got = np.stack(cubic_coefficients(d, phi0, phi1, alpha, each=True), axis=1)
    want = np.array(
        [[float(v) for v in cubic_coefficients(*args)] for args in zip(d, phi0, phi1, alpha, strict=True)]
    )
    assert np.array_equal(got, want)


@pytest.mark.parametrize(("steer_deg", "cells"), [(31.7, 8.0), (52.0, 2.0), (14.0, 4.0)])
def test_the_chain_index_answers_as_the_breadth_first_search(monkeypatch, steer_deg, cells):
    looked_up = Chains.reaches
    answers = []

    def both(self, h0, target, budget):
        answer = looked_up(self, h0, target, budget)
        assert answer == primitives._reaches(self.kept, h0, target, budget), (h0, target, budget)
        answers.append(answer)
        return answer

    monkeypatch.setattr(Chains, "reaches", both)
    primitives.compute_primitive_set(1.0, math.radians(steer_deg), 1.0 / cells)
    assert True in answers and False in answers
