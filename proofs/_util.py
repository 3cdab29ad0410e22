"""The machinery of the proofs: a derivation is a list of steps, and every claim is checked.

A :class:`Derivation` is built step by step: prose (:meth:`Derivation.text`), definitions
shown to the reader (:meth:`Derivation.define`), and claims. A claim is *proved* only when
sympy reduces it to exactly ``0`` (:meth:`Derivation.prove_equal`: ``simplify(lhs - rhs) == 0``)
or to exactly ``True`` (:meth:`Derivation.prove_true`, :meth:`Derivation.prove_sign`); anything
else -- a non-zero remainder, ``False``, or sympy's "don't know" (``None``) -- raises
:class:`ClaimFailed` at once. Evaluating a formula at sample points is a regression test, not
a proof: :meth:`Derivation.spot_check` records it with the kind
:attr:`ClaimKind.SPOT_CHECK`.

The finished derivation renders as a worked page (:meth:`Derivation.render`, unicode
pretty-printing) or as Markdown with LaTeX (:meth:`Derivation.to_markdown`).
"""

from __future__ import annotations

import math
import textwrap
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from enum import StrEnum

import sympy as sp
from sympy.matrices import MatrixBase

#: Width of the rendered page, in characters (formulas and wrapped prose).
PAGE_WIDTH = 96


class ClaimKind(StrEnum):
    """How a claim was established."""

    #: sympy reduced the claim to exactly 0 or True.
    PROOF = "proved"
    #: evaluated at sample points within a stated tolerance: a regression test, not a proof.
    SPOT_CHECK = "numeric spot check"


class ClaimFailed(AssertionError):
    """A claim was not established: sympy did not reduce it to 0 or True, or a spot check missed."""


@dataclass(frozen=True)
class Claim:
    """One established claim of a derivation.

    Parameters
    ----------
    name : str
        Identifier, unique within the derivation (cited as ``proofs.eqN:name``).
    statement : str
        The claim in words.
    kind : ClaimKind
        Proof or numeric spot check.
    formula : sympy.Basic or None
        What was proved, for display (an equation or a relation); ``None`` for spot checks.
    method : str
        How it was established, e.g. ``"simplify(lhs - rhs) == 0"``.
    """

    name: str
    statement: str
    kind: ClaimKind
    formula: sp.Basic | None
    method: str


@dataclass(frozen=True)
class _Text:
    paragraph: str


@dataclass(frozen=True)
class _Definition:
    name: str
    expr: sp.Basic


_Step = _Text | _Definition | Claim


def _is_zero(expr: object) -> bool:
    """True only for an exact sympy (or Python) zero, or a matrix of them."""
    if isinstance(expr, MatrixBase):
        return all(entry == 0 for entry in expr)
    return expr == 0


class Derivation:
    """A worked derivation of one equation: prose, definitions and checked claims.

    Every ``prove_*`` and ``spot_check`` method checks its claim immediately and raises
    :class:`ClaimFailed` if it does not hold, so a derivation that finishes building has
    established every claim in it.

    Parameters
    ----------
    key : str
        Short identifier used in claim citations, e.g. ``"eq4"``.
    title : str
        Heading of the rendered page.

    Examples
    --------
    >>> x = sp.Symbol("x", positive=True)
    >>> d = Derivation("demo", "Demo")
    >>> d.prove_equal("sqrt_of_square", sp.sqrt(x**2), x, "sqrt(x^2) = x for x > 0").kind
    <ClaimKind.PROOF: 'proved'>

    Without the assumption the same claim is not proved:

    >>> y = sp.Symbol("y", real=True)
    >>> d.prove_equal("wrong", sp.sqrt(y**2), y, "sqrt(y^2) = y")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    proofs._util.ClaimFailed: demo:wrong not proved: simplify(lhs - rhs) = -y + Abs(y), but ...
    """

    def __init__(self, key: str, title: str) -> None:
        self.key = key
        self.title = title
        self._steps: list[_Step] = []

    # ---- building -----------------------------------------------------------------------

    def text(self, paragraph: str) -> None:
        """Add a paragraph of prose."""
        self._steps.append(_Text(textwrap.dedent(paragraph).strip()))

    def define(self, name: str, expr: sp.Basic, *, shown: sp.Basic | None = None) -> sp.Basic:
        """Show the definition ``name = expr`` (or ``name = shown``) and return ``expr``."""
        self._steps.append(_Definition(name, expr if shown is None else shown))
        return expr

    def _add(self, claim: Claim) -> Claim:
        if any(isinstance(s, Claim) and s.name == claim.name for s in self._steps):
            raise ValueError(f"claim name {claim.name!r} used twice in {self.key}")
        self._steps.append(claim)
        return claim

    def _fail(self, name: str, detail: str, statement: str) -> ClaimFailed:
        return ClaimFailed(f"{self.key}:{name} not proved: {detail} [{statement}]")

    def prove_equal(
        self,
        name: str,
        lhs: sp.Basic,
        rhs: sp.Basic,
        statement: str,
        *,
        simplifier: Callable[[sp.Basic], sp.Basic] = sp.simplify,
        shown: sp.Basic | None = None,
    ) -> Claim:
        """Prove ``lhs == rhs`` by reducing ``simplifier(lhs - rhs)`` to exactly 0.

        Matrices are compared entry by entry. ``shown`` replaces ``Eq(lhs, rhs)`` on the page
        (e.g. to show an unevaluated ``Limit``).
        """
        difference = lhs - rhs
        if isinstance(difference, MatrixBase):
            reduced = difference.applyfunc(simplifier)
        else:
            reduced = simplifier(difference)
        method = f"{getattr(simplifier, '__name__', 'simplify')}(lhs - rhs) == 0"
        if not _is_zero(reduced):
            raise self._fail(
                name,
                f"{method.removesuffix(' == 0')} = {reduced}, but should be 0",
                statement,
            )
        formula = shown if shown is not None else held_eq(lhs, rhs)
        return self._add(Claim(name, statement, ClaimKind.PROOF, formula, method))

    def prove_true(
        self, name: str, predicate: object, statement: str, *, shown: sp.Basic | None = None
    ) -> Claim:
        """Prove a claim that sympy has evaluated to exactly ``True``.

        ``predicate`` is a sympy relational or boolean (e.g. ``Eq(solveset(...), {1/2})``);
        only ``sympy.true`` or ``True`` counts: an unevaluated relation is not a proof.
        """
        if not (predicate is sp.true or predicate is True):
            raise self._fail(name, f"evaluated to {predicate}, but should be True", statement)
        return self._add(Claim(name, statement, ClaimKind.PROOF, shown, "evaluates to True"))

    def prove_sign(self, name: str, expr: sp.Basic, sign: str, statement: str) -> Claim:
        """Prove ``expr`` is ``"positive"``, ``"negative"``, ``"nonnegative"`` or ``"nonpositive"``.

        Uses sympy's assumption system (``expr.is_positive`` and so on), which answers
        True, False or None (unknown); only True proves the claim.
        """
        relations = {
            "positive": sp.StrictGreaterThan,
            "negative": sp.StrictLessThan,
            "nonnegative": sp.GreaterThan,
            "nonpositive": sp.LessThan,
        }
        if sign not in relations:
            raise ValueError(f"`sign` must be one of {sorted(relations)}, got {sign!r}")
        answer = getattr(expr, f"is_{sign}")
        if answer is not True:
            raise self._fail(name, f"({expr}).is_{sign} is {answer}, but should be True", statement)
        formula = relations[sign](expr, 0, evaluate=False)
        return self._add(Claim(name, statement, ClaimKind.PROOF, formula, f"is_{sign} is True"))

    def spot_check(
        self,
        name: str,
        actual: Callable[..., float],
        expected: Callable[..., float],
        points: Sequence[tuple[float, ...]],
        statement: str,
        *,
        abs_tol: float,
        reason: str,
    ) -> Claim:
        """Check ``|actual(*p) - expected(*p)| <= abs_tol`` at every sample point ``p``.

        This is a numeric regression test, *not* a proof; ``reason`` justifies the tolerance.
        """
        for point in points:
            got, want = actual(*point), expected(*point)
            if not math.isclose(got, want, rel_tol=0.0, abs_tol=abs_tol):
                raise self._fail(
                    name,
                    f"at {point}: value={got!r}, but should be {want!r} (abs_tol={abs_tol})",
                    statement,
                )
        method = f"{len(points)} sample points, abs_tol={abs_tol:g} ({reason})"
        return self._add(Claim(name, statement, ClaimKind.SPOT_CHECK, None, method))

    # ---- reading ------------------------------------------------------------------------

    @property
    def claims(self) -> tuple[Claim, ...]:
        """Every established claim, in order."""
        return tuple(s for s in self._steps if isinstance(s, Claim))

    def claim(self, name: str) -> Claim:
        """The claim called ``name``."""
        for c in self.claims:
            if c.name == name:
                return c
        raise KeyError(f"{self.key} has no claim {name!r}")

    def render(self) -> str:
        """The derivation as a plain-text worked page (unicode pretty-printing)."""
        lines = [self.title, "=" * len(self.title), ""]
        for step in self._steps:
            if isinstance(step, _Text):
                lines += [*textwrap.wrap(step.paragraph, PAGE_WIDTH), ""]
            elif isinstance(step, _Definition):
                lines += [
                    _indent(_pretty(sp.Eq(sp.Symbol(step.name), step.expr, evaluate=False)), 4),
                    "",
                ]
            else:
                lines += textwrap.wrap(
                    f"[{step.kind}] {self.key}:{step.name} -- {step.statement}",
                    PAGE_WIDTH,
                    subsequent_indent="    ",
                )
                if step.formula is not None:
                    lines.append(_indent(_pretty(step.formula), 8))
                lines += textwrap.wrap(
                    f"by: {step.method}",
                    PAGE_WIDTH,
                    initial_indent=" " * 8,
                    subsequent_indent=" " * 12,
                )
                lines.append("")
        proved = sum(c.kind is ClaimKind.PROOF for c in self.claims)
        checked = len(self.claims) - proved
        lines.append(
            f"{proved} claim(s) proved by sympy; {checked} numeric spot check(s), "
            "which are regression tests, not proofs."
        )
        return "\n".join(lines)

    def to_markdown(self, *, level: int = 3, anchors: bool = False) -> str:
        """The derivation as Markdown with LaTeX formulas (for the notebook and the site).

        ``level`` is the title's heading level; with ``anchors``, every claim is preceded by a
        MyST target ``(proof-KEY-NAME)=`` (:func:`claim_anchor`), which the documentation
        site links citations such as ``proofs.eq4:convex_combination`` to.
        """
        parts = [f"{'#' * level} {self.title}"]
        for step in self._steps:
            if isinstance(step, _Text):
                parts.append(step.paragraph)
            elif isinstance(step, _Definition):
                parts.append(f"$${sp.latex(sp.Symbol(step.name))} = {sp.latex(step.expr)}$$")
            else:
                claim = f"**[{step.kind}]** `{self.key}:{step.name}` -- {step.statement}"
                if anchors:
                    claim = f"({claim_anchor(self.key, step.name)})=\n{claim}"
                parts.append(claim)
                if step.formula is not None:
                    parts.append(f"$${sp.latex(step.formula)}$$")
                parts.append(f"*by:* `{step.method}`")
        return "\n\n".join(parts)


def claim_anchor(key: str, name: str) -> str:
    """The site's label of claim ``key:name`` (letters, digits and hyphens).

    >>> claim_anchor("eq4", "convex_combination")
    'proof-eq4-convex-combination'
    """
    return f"proof-{key}-{name}".replace("_", "-").lower()


def held_eq(lhs: sp.Basic, rhs: sp.Basic) -> sp.Basic:
    """``Eq(lhs, rhs)`` left unevaluated, for display: ``Eq(x, x)`` is shown, not ``True``."""
    return sp.Eq(lhs, rhs, evaluate=False)


def _pretty(expr: sp.Basic) -> str:
    return sp.pretty(expr, use_unicode=True, num_columns=PAGE_WIDTH - 8)


def _indent(block: str, spaces: int) -> str:
    return textwrap.indent(block, " " * spaces)


def wrap_exact(angle: sp.Expr) -> sp.Expr:
    """Wrap an exact sympy angle into ``[-pi, pi)``, as :func:`ifgm_ref.core.pose.wrap_angle` does.

    >>> wrap_exact(3 * sp.pi / 2), wrap_exact(sp.pi)
    (-pi/2, -pi)
    """
    return sp.Mod(angle + sp.pi, 2 * sp.pi) - sp.pi


def entry_points(
    derivation: Callable[[], Derivation],
) -> tuple[Callable[[], tuple[Claim, ...]], Callable[[], None]]:
    """The ``claims()`` and ``main()`` every proof module exports, for its ``derivation``.

    ``claims()`` returns every checked claim (building the derivation raises ``ClaimFailed``
    if one does not hold); ``main()`` prints the derivation as a worked page.
    """

    def claims() -> tuple[Claim, ...]:
        return derivation().claims

    def main() -> None:
        print(derivation().render())

    claims.__doc__ = f"Every claim of {derivation.__module__}, checked."
    main.__doc__ = f"Print {derivation.__module__} as a worked page."
    return claims, main
