"""Safe arithmetic expressions for the ``parameters`` extension of the file format.

A number field of a mechanism file may be a string holding an arithmetic
expression over the file's parameters.  Only numbers, names, ``+ - * / ** %``,
parentheses and the functions of :data:`FUNCTIONS` are allowed; nothing else
of Python is reachable.  Trigonometric functions take radians; the ``...d``
variants take or give degrees.

Examples
--------
>>> evaluate("a * sind(30) + sqrt(b)", {"a": 2.0, "b": 9.0})
4.0
>>> evaluate("__import__('os')", {})
Traceback (most recent call last):
...
ValueError: function '__import__' is not allowed; allowed: abs, acos, acosd, asin, asind, atan, atan2, atan2d, atand, cos, cosd, degrees, exp, hypot, log, max, min, radians, sin, sind, sqrt, tan, tand
"""

from __future__ import annotations

import ast
import math
import operator
from typing import Callable, Mapping

__all__ = ["FUNCTIONS", "CONSTANTS", "evaluate"]

FUNCTIONS: Mapping[str, Callable[..., float]] = {
    "abs": abs,
    "acos": math.acos,
    "acosd": lambda x: math.degrees(math.acos(x)),
    "asin": math.asin,
    "asind": lambda x: math.degrees(math.asin(x)),
    "atan": math.atan,
    "atan2": math.atan2,
    "atan2d": lambda y, x: math.degrees(math.atan2(y, x)),
    "atand": lambda x: math.degrees(math.atan(x)),
    "cos": math.cos,
    "cosd": lambda x: math.cos(math.radians(x)),
    "degrees": math.degrees,
    "exp": math.exp,
    "hypot": math.hypot,
    "log": math.log,
    "max": max,
    "min": min,
    "radians": math.radians,
    "sin": math.sin,
    "sind": lambda x: math.sin(math.radians(x)),
    "sqrt": math.sqrt,
    "tan": math.tan,
    "tand": lambda x: math.tan(math.radians(x)),
}
"""Functions an expression may call."""

CONSTANTS: Mapping[str, float] = {"pi": math.pi, "tau": math.tau, "e": math.e}
"""Names every expression knows."""

_BINARY = {
    ast.Add: operator.add,
    ast.Sub: operator.sub,
    ast.Mult: operator.mul,
    ast.Div: operator.truediv,
    ast.Pow: operator.pow,
    ast.Mod: operator.mod,
}
_UNARY = {ast.USub: operator.neg, ast.UAdd: operator.pos}


def evaluate(text: str, names: Mapping[str, float]) -> float:
    """Evaluate an arithmetic expression.

    Parameters
    ----------
    text : str
        The expression.
    names : mapping
        Values of the parameters it may use (:data:`CONSTANTS` are added).

    Returns
    -------
    float

    Raises
    ------
    ValueError
        With a one-line reason: syntax, unknown name, forbidden construct,
        or a math error such as a division by zero.
    """
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except SyntaxError as exc:
        raise ValueError(f"cannot parse expression {text!r}: {exc.msg}") from None
    scope = {**CONSTANTS, **names}

    def ev(node: ast.AST) -> float:
        if isinstance(node, ast.Expression):
            return ev(node.body)
        if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)) and not isinstance(node.value, bool):
            return float(node.value)
        if isinstance(node, ast.Name):
            if node.id not in scope:
                known = ", ".join(sorted(names)) or "(none)"
                raise ValueError(f"unknown name {node.id!r} in {text!r}; parameters defined: {known}")
            return float(scope[node.id])
        if isinstance(node, ast.BinOp) and type(node.op) in _BINARY:
            return _BINARY[type(node.op)](ev(node.left), ev(node.right))
        if isinstance(node, ast.UnaryOp) and type(node.op) in _UNARY:
            return _UNARY[type(node.op)](ev(node.operand))
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and not node.keywords:
            fn = FUNCTIONS.get(node.func.id)
            if fn is None:
                raise ValueError(f"function {node.func.id!r} is not allowed; allowed: {', '.join(sorted(FUNCTIONS))}")
            return float(fn(*(ev(a) for a in node.args)))
        raise ValueError(f"{type(node).__name__} is not allowed in expression {text!r}")

    try:
        value = ev(tree)
    except (ArithmeticError, TypeError) as exc:
        raise ValueError(f"cannot evaluate {text!r}: {exc}") from None
    except ValueError as exc:
        if "math domain error" in str(exc):
            raise ValueError(f"cannot evaluate {text!r}: math domain error") from None
        raise
    if not math.isfinite(value):
        raise ValueError(f"expression {text!r} is not finite")
    return value
