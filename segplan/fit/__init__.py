"""The fitting procedures behind the stored constants, and the command that rewrites them.

The paper fitted two things empirically: ``k_alpha`` and the validated domain of formula
[2] ("Approximate computation of cost function"), and the closed formula of the heuristic
optimal reference system, case b ("Heuristic Algorithm"). Here they are code:

* :mod:`segplan.fit.formula2`: ``k_alpha`` and the domain of [2] on a grid of exact LONGD;
* :mod:`segplan.fit.heuristic`: the case-b coefficients from exact optima;
* :mod:`segplan.fit.store`: runs both and writes (or checks) the data file that
  :mod:`segplan.model.constants` reads, ``python -m segplan.fit [--check]``.

The planner never imports this package: it reads the stored results.
"""

__all__: list[str] = []
