"""Regression checks of mechanism files against their ``expected`` block.

:func:`check_paths` (``mobility check``) and the pytest plugin
(:func:`~mobility.testing.pytest_plugin.mechanism_tests`, ``pytest --mobility-check``).
"""

from .check import CheckReport, CheckResult, Comparison, check_file, check_mechanism, check_paths

__all__ = ["check_mechanism", "check_file", "check_paths", "CheckResult", "CheckReport", "Comparison"]
