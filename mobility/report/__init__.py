"""Formatting results for people: text, JSON, Markdown and pictures (matplotlib, optional, imported on first use).

Only formatting: every answer is computed by the core or a feature; the command line prints what these return.
"""
