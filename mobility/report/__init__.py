"""Formatting results for people: text, JSON, Markdown and pictures.

Only formatting: every answer is computed by the core or a feature; the
command line prints what these return. ``text`` (``mobility analyze`` and the
shared ``fmt_number``, ``fmt_vector``, ``screw_text``: round-off shown as 0 by
the one rule), ``markdown``, ``finite``, ``check``, ``actuation``,
``synthesis``, ``jacobian``, ``sweep`` (summary, CSV, JSON), ``sweep_plot`` and
the ``plotting`` package (matplotlib, optional, imported on first use).
"""
