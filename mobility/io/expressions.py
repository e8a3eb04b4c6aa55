"""Safe arithmetic expressions for the ``parameters`` extension of the file format.

Only numbers, names, ``+ - * / ** %``, parentheses and :data:`FUNCTIONS` (in radians; the ``...d`` variants in degrees).
An expression is compiled once into a flat postfix program (cached) run on an explicit stack, its length and depth
bounded, every intermediate value a finite real number (``(-8)**(1/3)``, ``exp(1000)`` are errors, not a silent ``nan``).

Examples
--------
>>> evaluate("a * sind(30) + sqrt(b)", {"a": 2.0, "b": 9.0})
4.0
>>> evaluate("__import__('os')", {})
Traceback (most recent call last):
...
ValueError: function '__import__' is not allowed; allowed: abs, acos, acosd, asin, asind, atan, atan2, atan2d, atand, cos, cosd, degrees, exp, hypot, log, max, min, radians, sin, sind, sqrt, tan, tand
>>> evaluate("(-8)**(1/3)", {})
Traceback (most recent call last):
...
ValueError: cannot evaluate '(-8)**(1/3)': a negative number to a fractional power is complex
"""

from __future__ import annotations

import ast
import keyword
import math
import operator
import re
import sys
from functools import lru_cache
from typing import Any, Callable, Mapping

from ..errors import name_list
from .limits import DEFAULT_LIMITS

__all__ = ["FUNCTIONS", "CONSTANTS", "RESERVED_NAMES", "evaluate", "compile_expression", "require_literal", "uses_radians"]

FUNCTIONS: Mapping[str, Callable[..., float]] = {
    "abs": abs, "acos": math.acos, "acosd": lambda x: math.degrees(math.acos(x)), "asin": math.asin, "asind": lambda x: math.degrees(math.asin(x)),
    "atan": math.atan, "atan2": math.atan2, "atan2d": lambda y, x: math.degrees(math.atan2(y, x)), "atand": lambda x: math.degrees(math.atan(x)),
    "cos": math.cos, "cosd": lambda x: math.cos(math.radians(x)), "degrees": math.degrees, "exp": math.exp, "hypot": math.hypot, "log": math.log,
    "max": max, "min": min, "radians": math.radians, "sin": math.sin, "sind": lambda x: math.sin(math.radians(x)), "sqrt": math.sqrt,
    "tan": math.tan, "tand": lambda x: math.tan(math.radians(x))}
"""Functions an expression may call."""

CONSTANTS: Mapping[str, float] = {"pi": math.pi, "tau": math.tau, "e": math.e}
"""Names every expression knows."""

RESERVED_NAMES = frozenset(CONSTANTS) | frozenset(FUNCTIONS)
"""Names a file may not define (as a parameter or a limb index): the constants and the functions."""

_BINARY: dict[type, Callable[[float, float], Any]] = {ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul, ast.Div: operator.truediv,
                                                      ast.Pow: operator.pow, ast.Mod: operator.mod}
_UNARY: dict[type, Callable[[float], float]] = {ast.USub: operator.neg, ast.UAdd: operator.pos}

_NEVER_ZERO = {operator.mul, operator.truediv, operator.pow, math.exp, math.sqrt, math.hypot}
"""Operations whose result is not zero when no argument is: a zero (or a subnormal number) from them is an underflow."""

_HEX_PREFIX = re.compile(r"[+-]?0[xX]")
"""How a hexadecimal float (``0x1p-3``, as MuJoCo and ``float.fromhex`` read it) begins."""

_NUMBER, _NAME, _APPLY = 0, 1, 2  # the instructions of a program (tuples: hashable and cacheable)

Program = tuple[tuple[Any, ...], ...]
"""A compiled expression: ``(_NUMBER, x)``, ``(_NAME, name)`` or ``(_APPLY, function, arity)``, in postfix order."""


def require_literal(written: str, value: float) -> float:
    """``value``, the ``float`` the number ``written`` reads as, unless it overflows to infinity or underflows to zero; else a ``ValueError`` saying why.

    The one rule for a number written out (YAML, an expression, an MJCF or URDF attribute, hexadecimal too), as the
    evaluator refuses a product that underflows; a subnormal is what was written; ``inf`` and ``nan`` are the caller's.

    Examples
    --------
    >>> require_literal("0.0e-400", 0.0), require_literal("-0x0p3", -0.0)
    (0.0, -0.0)
    >>> require_literal("1e-400", 0.0)
    Traceback (most recent call last):
    ValueError: the number '1e-400' underflows: it is below the smallest float (4.94e-324) and would read as 0.0
    >>> require_literal("1e400", math.inf)
    Traceback (most recent call last):
    ValueError: the number '1e400' is too large for a float (it would read as inf)
    """
    if math.isinf(value) and any(c.isdigit() for c in written):
        raise ValueError(f"the number {_shown(written)!r} is too large for a float (it would read as {value!r})")
    if value != 0.0:
        return value
    hexadecimal = _HEX_PREFIX.match(written)
    mantissa, digits = (written[hexadecimal.end():].lower().partition("p")[0], "123456789abcdef") if hexadecimal else (written.lower().partition("e")[0], "123456789")
    if any(c in digits for c in mantissa):
        raise ValueError(f"the number {_shown(written)!r} underflows: it is below the smallest float ({sys.float_info.min * sys.float_info.epsilon:.3g}) and would read as {value!r}")
    return value


def _children(node: ast.AST, text: str, source: str = "") -> tuple[list[ast.AST], tuple[Any, ...] | None]:
    """The operands of ``node`` and the instruction it becomes after them (``None``: no instruction); ``text`` is the expression as messages show it, ``source`` as parsed."""
    if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)) and not isinstance(node.value, bool):
        try:
            value = float(node.value)
        except OverflowError:
            raise ValueError(f"a number in {text!r} is too large") from None
        if not math.isfinite(value):
            raise ValueError(f"a number in {text!r} is too large (not finite)")
        if isinstance(node.value, float) and value == 0.0:
            try:
                require_literal(ast.get_source_segment(source, node) or "", value)
            except ValueError as exc:
                raise ValueError(f"expression {text!r}: {exc}") from None
        return [], (_NUMBER, value)
    if isinstance(node, ast.Name):
        return [], (_NAME, node.id)
    if isinstance(node, ast.BinOp) and type(node.op) in _BINARY:
        return [node.left, node.right], (_APPLY, _BINARY[type(node.op)], 2)
    if isinstance(node, ast.UnaryOp) and type(node.op) in _UNARY:
        return [node.operand], (_APPLY, _UNARY[type(node.op)], 1)
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and not node.keywords:
        fn = FUNCTIONS.get(node.func.id)
        if fn is None:
            raise ValueError(f"function {node.func.id!r} is not allowed; allowed: {', '.join(sorted(FUNCTIONS))}")
        if any(isinstance(a, ast.Starred) for a in node.args):
            raise ValueError(f"Starred is not allowed in expression {text!r}")
        return list(node.args), (_APPLY, fn, len(node.args))
    raise ValueError(f"{type(node).__name__} is not allowed in expression {text!r}")


@lru_cache(maxsize=4096)
def compile_expression(text: str, max_length: int = DEFAULT_LIMITS.max_expression_length, max_depth: int = DEFAULT_LIMITS.max_expression_depth) -> Program:
    """Check an expression and turn it into a flat program.

    Raises
    ------
    ValueError
        With a one-line reason: too long, too deep, syntax, or a forbidden construct.

    Examples
    --------
    >>> [op[1] for op in compile_expression("2 * a") if op[0] != 2]
    [2.0, 'a']
    >>> compile_expression("-" * 20 + "1", max_depth=10)
    Traceback (most recent call last):
    ...
    ValueError: expression '--------------------1' is nested deeper than the limit of 10 levels (set MOBILITY_MAX_EXPRESSION_DEPTH to raise it)
    """
    source = text.strip()
    if len(source) > max_length:
        raise ValueError(f"an expression of {len(source)} characters is longer than the limit of {max_length} (set MOBILITY_MAX_EXPRESSION_LENGTH to raise it)")
    shown = _shown(source)
    if not source.isascii():  # Python would read a fullwidth 'ａ' as 'a' (NFKC) inside an expression, not alone
        bad = next(c for c in source if not c.isascii())
        raise ValueError(f"expression {shown!r} holds the character {bad!r}; expressions are written in ASCII (names, digits, + - * / ** %)")
    if source.isidentifier() and not keyword.iskeyword(source):  # a lone name, the commonest expression
        return ((_NAME, source),)
    try:
        tree = ast.parse(source, mode="eval")
    except SyntaxError as exc:
        raise ValueError(f"cannot parse expression {shown!r}: {exc.msg}") from None
    except (RecursionError, MemoryError, ValueError):
        raise ValueError(f"cannot parse expression {shown!r}: too complex") from None
    program: list[tuple[Any, ...]] = []
    # Post-order walk with an explicit stack: (node, depth, instruction once its operands are emitted).
    pending: list[tuple[ast.AST, int, tuple[Any, ...] | None]] = [(tree.body, 1, None)]
    while pending:
        node, depth, done = pending.pop()
        if done is not None:
            program.append(done)
            continue
        if depth > max_depth:
            raise ValueError(f"expression {shown!r} is nested deeper than the limit of {max_depth} levels (set MOBILITY_MAX_EXPRESSION_DEPTH to raise it)")
        operands, instruction = _children(node, shown, source)
        if instruction is not None:
            pending.append((node, depth, instruction))
        pending.extend((child, depth + 1, None) for child in reversed(operands))
    return tuple(program)


def _shown(text: str) -> str:
    """An expression as an error message shows it (long ones cut)."""
    text = text.strip()
    return text if len(text) <= 60 else text[:57] + "..."


def _run(program: Program, names: Mapping[str, float], text: str) -> float:
    stack: list[float] = []
    for op in program:
        kind = op[0]
        if kind == _NUMBER:
            stack.append(op[1])
            continue
        if kind == _NAME:
            value = names.get(op[1], CONSTANTS.get(op[1]))
            if value is None:
                raise _unknown_name(op[1], text, names)
            stack.append(value)
            continue
        arity = op[2]
        args = stack[len(stack) - arity:]
        del stack[len(stack) - arity:]
        try:
            result = op[1](*args)
        except (ArithmeticError, TypeError, ValueError) as exc:
            if isinstance(exc, OverflowError):
                reason = "the result is too large for a float"
            elif isinstance(exc, ZeroDivisionError):
                reason = "division by zero"
            else:
                reason = "math domain error" if "math domain error" in str(exc) else str(exc)
            raise ValueError(f"cannot evaluate {_shown(text)!r}: {reason}") from None
        if isinstance(result, complex):
            raise ValueError(f"cannot evaluate {_shown(text)!r}: a negative number to a fractional power is complex")
        result = float(result)
        if not math.isfinite(result):
            raise ValueError(f"expression {_shown(text)!r} is not finite")
        if abs(result) < sys.float_info.min and op[1] in _NEVER_ZERO and args and all(a != 0.0 for a in args):
            what = "an exp" if op[1] is math.exp else "a product, quotient or power"
            hint = "" if op[1] is math.exp else "; write the lengths in a larger unit"
            raise ValueError(f"expression {_shown(text)!r} underflows: {what} of its numbers is below the smallest float ({sys.float_info.min:.3g}){hint}")
        stack.append(result)
    return stack[-1]


def _unknown_name(name: str, text: str, names: Mapping[str, float]) -> ValueError:
    known = name_list(sorted(names))
    return ValueError(f"unknown name {name!r} in {_shown(text)!r}; parameters defined: {known}")


_GIVE_DEGREES = frozenset(id(FUNCTIONS[name]) for name in ("degrees", "acosd", "asind", "atand", "atan2d"))
"""The functions whose result is in degrees."""


def uses_radians(text: str, radian_names: frozenset[str] | set[str] = frozenset(), *, max_length: int = DEFAULT_LIMITS.max_expression_length,
                 max_depth: int = DEFAULT_LIMITS.max_expression_depth) -> bool:
    """True when expression ``text`` is written in radians: it uses ``pi`` or ``tau`` (or a parameter of ``radian_names``) and no function that gives degrees.

    For the warning on an angle read in degrees (``"2*pi/3*i"`` is then 2.09 degrees).

    Examples
    --------
    >>> uses_radians("2*pi/3*i"), uses_radians("120*i"), uses_radians("degrees(pi/3)"), uses_radians("step*i", {"step"})
    (True, False, False, True)
    """
    program = compile_expression(text, max_length, max_depth)
    names = {op[1] for op in program if op[0] == _NAME}
    in_degrees = any(op[0] == _APPLY and id(op[1]) in _GIVE_DEGREES for op in program)
    return not in_degrees and bool(names & ({"pi", "tau"} | set(radian_names)))


def evaluate(text: str, names: Mapping[str, float], *, max_length: int = DEFAULT_LIMITS.max_expression_length, max_depth: int = DEFAULT_LIMITS.max_expression_depth) -> float:
    """Evaluate an arithmetic expression; ``names`` are the parameters' values (:data:`CONSTANTS` are added).

    Raises
    ------
    ValueError
        With a one-line reason: syntax, a limit passed, an unknown name, a
        forbidden construct, or a math error (division by zero, overflow, complex).

    Examples
    --------
    >>> evaluate("atan2d(1, 1) + r", {"r": 0.5})
    45.5
    """
    return _run(compile_expression(text, max_length, max_depth), names, text)
