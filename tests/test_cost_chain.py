"""The exact LONGD of a chain of unions has one home, segplan.model.cost.chain_longd (issue 24):
it gives the bits of the three sums the planners wrote (literal copies below)."""

import math

import numpy as np

from segplan import Pose, Union
from segplan.model.cost import chain_longd, checked_intrinsic, longd_exact_intrinsic
from segplan.model.frame import heuristic_alpha
from segplan.model.pose import alpha_interval, intrinsic_interval

RTOL = 1e-8  # the planners' PLAN_RTOL


def _chains(seed=24, n_chains=12):
    """Chains of unions as the planners build them: by the constructor (numpy geometry) and by
    ``Union.from_intrinsic`` from the link model's ``math`` values (which may differ in the
    last bit from the poses' numpy geometry)."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n_chains):
        poses = [Pose(0.0, 0.0, float(rng.uniform(-1, 1)))]
        for _ in range(int(rng.integers(1, 7))):
            p = poses[-1]
            step, turn = float(rng.uniform(0.3, 6.0)), float(rng.uniform(-0.8, 0.8))
            poses.append(
                Pose(
                    p.x + step * math.cos(p.theta + turn / 2),
                    p.y + step * math.sin(p.theta + turn / 2),
                    p.theta + turn,
                )
            )
        built, fast = [], []
        for a, b in zip(poses[:-1], poses[1:], strict=True):
            d, psi, phi0, phi1, lo, hi = intrinsic_interval(a, b)
            alpha = min(max(heuristic_alpha(d, phi0, phi1, 1.2), lo + 1e-9), hi - 1e-9)
            built.append(Union(a, b, alpha, 1.2))
            fast.append(Union.from_intrinsic(a, b, alpha, 1.2, d, psi, phi0, phi1))
        out += [built, fast]
    return out


def test_chain_longd_is_the_lattice_planners_sum():
    """planning/plan.py ``unions_longd``: ``sum(union_longd(u))`` from the unions' own parameters
    (the same bits as a loop on Python 3.11; ``sum`` compensates from 3.12 on)."""
    for chain in _chains():
        old = sum(float(longd_exact_intrinsic(u.d, u.phi0, u.phi1, u.alpha, u.L, rtol=RTOL)) for u in chain)
        assert chain_longd(chain, RTOL).hex() == float(old).hex()
        one = float(
            longd_exact_intrinsic(
                chain[0].d, chain[0].phi0, chain[0].phi1, chain[0].alpha, chain[0].L, rtol=RTOL
            )
        )
        assert chain_longd(chain[:1], RTOL).hex() == one.hex()  # union_longd
    assert chain_longd([], RTOL) == 0.0


def test_chain_longd_from_poses_is_the_paper_planners_and_the_refinements_loop():
    """planning/api.py ``finish`` and planning/refine.py: the geometry again from the poses."""
    for chain in _chains(seed=7):
        exact = 0.0
        for u in chain:
            geo = checked_intrinsic(u.p0, u.p1, u.alpha, u.L)
            exact += float(longd_exact_intrinsic(*geo, rtol=RTOL))
        assert chain_longd(chain, RTOL, from_poses=True).hex() == exact.hex()


def test_the_two_geometries_differ_in_the_last_bit_sometimes():
    """Why ``from_poses`` is an option and not a duplicate: for unions built from the ``math``
    module's values, the poses' numpy geometry gives another last bit on some chains."""
    chains = [c for s in range(10) for c in _chains(seed=s)]
    assert any(chain_longd(c, RTOL) != chain_longd(c, RTOL, from_poses=True) for c in chains)


def test_longd_of_each_union_in_a_batch_is_its_own_calls_bit_for_bit():
    # longd_exact_intrinsic(..., each=True) (the primitives' batches of exact LONGD): every
    # value and error estimate is that of a call for the union alone, whatever the batch
    rng = np.random.default_rng(25)
    n = 400
    d = np.exp(rng.uniform(-2.0, 2.5, n))
    phi0, phi1 = rng.uniform(-1.3, 1.3, (2, n))
    lo, hi = alpha_interval(phi0, phi1)
    keep = hi - lo > 0.01
    d, phi0, phi1, lo, hi = d[keep], phi0[keep], phi1[keep], lo[keep], hi[keep]
    alpha = lo + rng.uniform(0.02, 0.98, len(d)) * (hi - lo)
    L = np.exp(rng.uniform(-1.0, 1.0, len(d)))
    alone = [
        longd_exact_intrinsic(*(float(v[k]) for v in (d, phi0, phi1, alpha, L)), full_output=True)
        for k in range(len(d))
    ]
    for size in (1, 3, 8, 13, len(d)):
        for start in range(0, len(d) - size + 1, max(size, 37)):
            sl = slice(start, start + size)
            value, error = longd_exact_intrinsic(
                d[sl], phi0[sl], phi1[sl], alpha[sl], L[sl], full_output=True, each=True
            )
            assert value.tolist() == [v for v, _ in alone[sl]]
            assert error.tolist() == [e for _, e in alone[sl]]
