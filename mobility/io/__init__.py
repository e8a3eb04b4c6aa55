"""Reading and writing mechanism files: YAML text in, a :class:`~mobility.core.model.Mechanism` out.

``yaml_source``
    YAML parsed with the line of every key kept, for one-line error messages.
``expressions``
    the safe arithmetic of ``parameters`` and numeric fields.
``loader``
    the format of ``docs/spec-v1.md`` and its extensions: :func:`load`, :func:`loads`.

Loaders know the model and nothing of screws.
"""

from .loader import load, loads

__all__ = ["load", "loads"]
