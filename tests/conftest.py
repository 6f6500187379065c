"""Shared pytest configuration: bounded hypothesis runs.

Hypothesis runs at most ``max_examples`` examples per property test and has no deadline, because
the first call of a numba kernel compiles it (or loads it from the cache), which can take seconds.
Select a longer run with ``HYPOTHESIS_PROFILE=fastrest-long pytest ...``.
"""
import os

from hypothesis import settings

settings.register_profile("fastrest", max_examples=50, deadline=None)
settings.register_profile("fastrest-long", max_examples=1000, deadline=None)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "fastrest"))
