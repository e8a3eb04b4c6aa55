"""Formatting results for people: text, JSON, Markdown and pictures.

Only formatting: every answer is computed by the core or a feature, and
the command line prints what these return.  Pictures use matplotlib (optional,
imported on first use).
"""
