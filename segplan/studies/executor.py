"""The one executor of every time-budgeted run of the studies (beyond the paper): fair and resumable.

OMPL's planners stop at a wall-clock budget, so what a run finds depends on how much of a
core it got during that budget: an anytime planner given 40 % of a core for 5 s is a 2 s
planner. Every OMPL run of chapters 8 and 9 (``benchmarks/peers.py``,
``benchmarks/robustness.py``) and of the robots probe (``benchmarks/robots.py``) goes
through :func:`run_jobs`, which

- runs **at most one job per free core** (:func:`free_cores`: the cores less the 1-minute
  load average when the executor starts, rounded, at least 1; ``cap`` bounds it from
  above, the command lines' ``--jobs``), in a :class:`concurrent.futures.ThreadPoolExecutor`
  (each OMPL job is a fresh process started from its thread); or, when the user passes a
  Dask scheduler address (``--scheduler tcp://host:8786``), on that cluster through
  :meth:`distributed.Client.get_executor` (``distributed`` is imported only then; start
  its workers with one thread per core: ``dask worker tcp://host:8786 --nthreads 1
  --nworkers <cores>``);
- **enforces fairness** (:class:`FairnessRule`, :data:`FAIRNESS`): a run whose wall time is
  at least ``min_seconds`` (0.5 s: it used a budget long enough for the share to be
  measured; BIT* stops sooner when it proves a path optimal) and whose CPU share
  ``cpu_seconds / seconds`` is below ``min_share`` (0.9) is *refused*: never stored, run
  again after a back-off (10, 20, 40 s; other runs go on), at most ``retries`` times, then
  :class:`UnfairRunError` stops the study loudly;
- **stores each accepted run as it finishes** in a :class:`Journal` (JSON lines), so an
  interrupted study resumes where it stopped: a run already in the journal that the rule
  accepts is not run again;
- shows **progress** with :func:`segplan.studies.progress.progress` (tqdm, on a terminal
  only) and prints each refusal above the bar.

A job's function returns a record (a JSON-serialisable ``dict``) with at least ``seconds``
(wall time of the budgeted part) and ``cpu_seconds`` (the CPU time it got);
:func:`segplan.studies.ompl_runner.solve_ompl` also records ``load_before`` and
``load_after`` (the machine's 1-minute load average around ``solve``), and
:func:`run_jobs` adds ``cpu_share`` and ``attempts``.
"""

from __future__ import annotations

import concurrent.futures as cf
import json
import math
import os
import time
from collections.abc import Callable, Iterable
from dataclasses import asdict, dataclass
from pathlib import Path

from .progress import progress, say

__all__ = [
    "FAIRNESS",
    "FairnessRule",
    "Journal",
    "UnfairRunError",
    "cpu_share",
    "free_cores",
    "run_jobs",
]


class UnfairRunError(RuntimeError):
    """A run kept getting less CPU than :class:`FairnessRule` asks, after every retry."""


def cpu_share(record: dict) -> float:
    """``cpu_seconds / seconds`` of a run's record (NaN when either is missing or ``seconds`` <= 0)."""
    try:
        seconds, cpu = float(record["seconds"]), float(record["cpu_seconds"])
    except (KeyError, TypeError, ValueError):
        return math.nan
    return cpu / seconds if seconds > 0 and math.isfinite(cpu) else math.nan


@dataclass(frozen=True)
class FairnessRule:
    """Which runs count: a budget used is a budget of CPU.

    Parameters
    ----------
    min_share : float
        The least CPU share (``cpu_seconds / seconds``) of a run that counts. 0.9: a
        single-threaded planner on a core of its own gets 0.97-1.0 here; the stored runs
        before this rule had a median of 0.31.
    min_seconds : float
        The rule applies to runs of at least this wall time (s). Shorter runs (0.1 s
        budgets; BIT* proving a path optimal early) are too short for the share to be
        measured: process start-up and the clock's granularity dominate.
    retries : int
        A refused run is run again at most this many times; then :func:`run_jobs` raises
        :class:`UnfairRunError`.
    backoff : float
        Seconds a refused run waits before its first retry, doubled at each further one
        (10, 20, 40 s): time for a passing load to pass; other runs go on meanwhile.
    """

    min_share: float = 0.9
    min_seconds: float = 0.5
    retries: int = 3
    backoff: float = 10.0

    def __post_init__(self):
        if not (isinstance(self.min_share, int | float) and 0.0 < self.min_share <= 1.0):
            raise ValueError(f"min_share must be in (0, 1], got {self.min_share!r}")
        if not (isinstance(self.min_seconds, int | float) and self.min_seconds >= 0.0):
            raise ValueError(f"min_seconds must be >= 0, got {self.min_seconds!r}")
        if isinstance(self.retries, bool) or not isinstance(self.retries, int) or self.retries < 0:
            raise ValueError(f"retries must be an integer >= 0, got {self.retries!r}")
        if not (isinstance(self.backoff, int | float) and self.backoff >= 0.0):
            raise ValueError(f"backoff must be >= 0 seconds, got {self.backoff!r}")

    def wait(self, attempt: int) -> float:
        """Seconds to wait before running again a run refused at its ``attempt``-th attempt."""
        return self.backoff * 2.0 ** (attempt - 1)

    def refuses(self, record: dict) -> bool:
        """Does the rule refuse this run (long enough to judge, and starved or unmeasured)?"""
        seconds = float(record.get("seconds", math.nan))
        if not seconds >= self.min_seconds:  # NaN seconds: nothing ran long enough to judge
            return False
        share = cpu_share(record)
        return not share >= self.min_share

    def text(self) -> str:
        """The rule in words, as the provenance stores it."""
        return (
            f"a run of at least {self.min_seconds:g} s wall time whose CPU share (cpu_seconds / seconds) "
            f"is below {self.min_share:g} is refused and run again (at most {self.retries} times, after "
            f"{self.backoff:g} s, doubled each time; then the study stops); refused runs are never stored"
        )

    def provenance(self) -> dict:
        """The rule's parameters and its text (stored in the results' JSON)."""
        return {**asdict(self), "rule": self.text()}


#: The studies' rule.
FAIRNESS = FairnessRule()


def free_cores(cap: int | None = None, cores: int | None = None, load: float | None = None) -> int:
    """Cores free for time-budgeted runs: ``cores - load`` rounded (half up), at least 1,
    at most ``cap``.

    Parameters
    ----------
    cap : int, optional
        Upper bound (a command line's ``--jobs``).
    cores, load : optional
        The machine's cores (default ``os.cpu_count()``) and its 1-minute load average
        (default ``os.getloadavg()[0]``; 0 where the system has none).
    """
    if cap is not None and (isinstance(cap, bool) or not isinstance(cap, int) or cap < 1):
        raise ValueError(f"cap must be an integer >= 1 or None, got {cap!r}")
    cores = (os.cpu_count() or 1) if cores is None else cores
    if load is None:
        load = os.getloadavg()[0] if hasattr(os, "getloadavg") else 0.0
    n = max(1, math.floor(cores - load + 0.5))
    return n if cap is None else min(n, cap)


class Journal:
    """Accepted runs, one JSON line each (``{"key": ..., "record": ...}``), appended as they finish.

    Parameters
    ----------
    path : str or Path
        The file (created with its folder on the first append).
    """

    def __init__(self, path: str | Path):
        self.path = Path(path)

    def read(self) -> dict[str, dict]:
        """Every stored record by key (a later line wins; a torn last line is skipped)."""
        out = {}
        if not self.path.exists():
            return out
        with self.path.open(encoding="utf-8") as fh:
            for line in fh:
                try:
                    d = json.loads(line)
                except json.JSONDecodeError:
                    continue  # an interrupted write
                out[d["key"]] = d["record"]
        return out

    def append(self, key: str, record: dict) -> None:
        """Store one record under ``key`` (flushed at once)."""
        self.path.parent.mkdir(parents=True, exist_ok=True)
        with self.path.open("a", encoding="utf-8") as fh:
            fh.write(json.dumps({"key": key, "record": record}, separators=(",", ":")) + "\n")
            fh.flush()
            os.fsync(fh.fileno())


def _executor(scheduler: str | None, slots: int):
    """A concurrent.futures executor and the slots it runs at once: threads here, or a Dask cluster."""
    if scheduler is None:
        return cf.ThreadPoolExecutor(max_workers=slots), slots, None
    try:
        from distributed import Client
    except ImportError:
        raise RuntimeError(
            "scheduler: running on a Dask cluster needs the 'distributed' package "
            "(pip install 'segplan[peers]' or pip install distributed)"
        ) from None
    client = Client(scheduler)
    return client.get_executor(pure=False), slots, client


def run_jobs(
    fn: Callable[[object], dict],
    jobs: Iterable,
    key: Callable[[object], str] = str,
    journal: Journal | str | Path | None = None,
    rule: FairnessRule = FAIRNESS,
    cap: int | None = None,
    scheduler=None,
    desc: str = "runs",
) -> dict[str, dict]:
    """Run ``fn(job)`` for every job not yet in ``journal``, fairly; every accepted record by key.

    Parameters
    ----------
    fn : callable
        ``fn(job) -> dict`` with ``seconds`` and ``cpu_seconds``; on a Dask cluster it and
        the jobs must pickle (a module-level function).
    jobs : iterable
        The jobs, in the order they should start; keys must be unique.
    key : callable
        ``key(job) -> str``: a job's name in the journal.
    journal : Journal or path, optional
        Where accepted records are appended as they finish and read from on a re-run
        (records the rule refuses are run again). ``None``: kept in memory only.
    rule : FairnessRule
        Which runs count (:data:`FAIRNESS`).
    cap : int, optional
        At most this many runs at once (``--jobs``).
    scheduler : str or distributed.LocalCluster, optional
        A Dask scheduler's address (``"tcp://host:8786"``) or cluster: run there, ``cap``
        (default: the cluster's threads) runs at a time. ``None``: this machine,
        :func:`free_cores` runs at a time.

    Returns
    -------
    dict
        ``key(job) -> record`` for every job, each with ``cpu_share`` and ``attempts``
        (1 for a run accepted the first time) added.

    Raises
    ------
    UnfairRunError
        If a run is refused ``rule.retries + 1`` times (the accepted runs stay in the journal).
    """
    if not isinstance(rule, FairnessRule):
        raise ValueError(f"rule must be a FairnessRule, got {type(rule).__name__}")
    if journal is not None and not isinstance(journal, Journal):
        journal = Journal(journal)
    jobs = list(jobs)
    keys = [key(j) for j in jobs]
    if len(set(keys)) != len(keys):
        raise ValueError("jobs: two jobs have the same key")
    stored = journal.read() if journal is not None else {}
    done = {k: r for k, r in stored.items() if k in set(keys) and not rule.refuses(r)}
    todo = [(k, j) for k, j in zip(keys, jobs, strict=True) if k not in done]
    if not todo:
        return {k: done[k] for k in keys}
    slots = cap if scheduler is not None else free_cores(cap)
    pool, slots, client = _executor(scheduler, slots or 1)
    if client is not None and cap is None:
        slots = max(1, sum(client.nthreads().values()))
    attempts: dict[str, int] = {}
    queue = list(reversed(todo))  # pop() takes the first job
    waiting: list[tuple[float, str, object]] = []  # refused runs: (time they may start again, key, job)
    running: dict[cf.Future, tuple[str, object]] = {}
    try:
        with progress(total=len(todo), desc=desc) as bar:
            while queue or running or waiting:
                now = time.monotonic()
                queue += [(k, j) for t, k, j in waiting if t <= now]  # due retries start next
                waiting = [w for w in waiting if w[0] > now]
                while queue and len(running) < slots:
                    k, j = queue.pop()
                    attempts[k] = attempts.get(k, 0) + 1
                    running[pool.submit(fn, j)] = (k, j)
                due = min((t for t, _, _ in waiting), default=None)
                if not running:
                    time.sleep(max(0.0, due - time.monotonic()))
                    continue
                timeout = None if due is None else max(0.0, due - time.monotonic())
                finished, _ = cf.wait(running, timeout=timeout, return_when=cf.FIRST_COMPLETED)
                for fut in finished:
                    k, j = running.pop(fut)
                    record = dict(fut.result())
                    record.update(cpu_share=cpu_share(record), attempts=attempts[k])
                    if rule.refuses(record):
                        load = (record.get(f"load_{w}", math.nan) for w in ("before", "after"))
                        say(
                            f"refused {k}: CPU share {record['cpu_share']:.2f} < {rule.min_share:g} "
                            f"over {float(record['seconds']):.2f} s (attempt {attempts[k]}, load "
                            "{:.1f} -> {:.1f})".format(*load)
                        )
                        if attempts[k] > rule.retries:
                            raise UnfairRunError(
                                f"{k}: CPU share below {rule.min_share:g} in {attempts[k]} attempts "
                                f"(last {record['cpu_share']:.2f}); the machine is too busy for "
                                "time-budgeted runs: free it (or lower --jobs) and run again, "
                                "the accepted runs are kept"
                            )
                        waiting.append((time.monotonic() + rule.wait(attempts[k]), k, j))
                        continue
                    done[k] = record
                    if journal is not None:
                        journal.append(k, record)
                    bar.update()
    finally:
        for fut in running:
            fut.cancel()
        pool.shutdown(wait=True)
        if client is not None:
            client.close()
    return {k: done[k] for k in keys}
