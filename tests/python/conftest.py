# SPDX-License-Identifier: Apache-2.0
"""Shared pytest setup: hypothesis profiles sized for the 5-minute budget on 2 cores.

``HYPOTHESIS_PROFILE=thorough`` runs many more examples (use it when changing the C core).
Under CI (``CI`` set) the examples are derandomized: a run checks the same cases every time, so
a landing is judged on the change, not on the draw; local runs keep exploring new cases.
"""
import os

from hypothesis import HealthCheck, settings

# deadline=None: the first call of a test compiles nothing but may touch a cold cache; the
# budget is enforced on the whole suite, not per example.
settings.register_profile("default", max_examples=100, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("thorough", max_examples=1000, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("ci", max_examples=100, deadline=None, derandomize=True,
                          database=None, suppress_health_check=[HealthCheck.too_slow])
_default = "ci" if os.environ.get("CI") else "default"
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", _default))


def pytest_collection_modifyitems(config, items):
    """Full-size campaigns (``@pytest.mark.long``) run only with ``SMOOTHSHAPER_LONG=1``; each
    has a smaller fixed-seed draw in the default suite, so nothing is dropped, only sized."""
    if os.environ.get("SMOOTHSHAPER_LONG") == "1":
        return
    import pytest
    skip = pytest.mark.skip(reason="full-size campaign: set SMOOTHSHAPER_LONG=1 to run it")
    for item in items:
        if "long" in item.keywords:
            item.add_marker(skip)
