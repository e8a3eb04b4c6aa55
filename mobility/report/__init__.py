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
``actuation``, ``synthesis``, ``jacobian``
    the reports (text and JSON) of the features of the same names.
``sweep``
    a sweep's summary, its table as CSV, and JSON.
``plotting`` (a package)
    pictures of a mechanism and of its joint graph, and the matplotlib
    backend (optional, imported on first use) every picture is built and
    saved with.
``sweep_plot``
    pictures of a sweep: a curve, a map or slices.
"""
