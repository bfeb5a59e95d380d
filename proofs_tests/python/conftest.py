"""Hypothesis settings for fhr's own pytest suite: reproducible in CI (derandomized, no example
database written into the tree, no deadline: a run's time is measured by bench/, never judged here)."""

from hypothesis import settings

settings.register_profile("fhr", derandomize=True, database=None, deadline=None)
settings.load_profile("fhr")
