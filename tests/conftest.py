"""Shared test configuration: deterministic hypothesis runs, no deadlines (CI machines vary)."""

from hypothesis import HealthCheck, settings

settings.register_profile(
    "segplan",
    derandomize=True,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow],
    print_blob=True,
)
settings.load_profile("segplan")
