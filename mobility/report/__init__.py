"""Formatting results for people: text, JSON, Markdown and pictures.

``text``
    the report of ``mobility analyze`` and its JSON form.
``markdown``
    a Markdown report.
``plotting``
    pictures of a mechanism with its freedoms and constraints (matplotlib, optional).
"""
