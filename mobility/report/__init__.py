"""Formatting results for people: text, JSON, Markdown and pictures.

Only formatting: every answer is computed by the core or a feature; a module
here writes it.  The command line prints what these return.

``text``
    the report of ``mobility analyze`` and its JSON form; ``fmt_number``,
    ``fmt_vector``, ``screw_text`` (numbers, vectors and screw axes in words,
    round-off shown as 0 by the one rule) for every other report.
``markdown``
    a Markdown report of an analysis, and Markdown tables.
``finite``
    the finite-motion section of ``mobility analyze --finite``.
``check``
    the table of ``mobility check``.
``actuation``, ``synthesis``, ``jacobian``, ``sweep``
    the reports of the features of the same names.
``plotting`` (a package), ``sweep_plot``
    pictures (matplotlib, optional).
"""
