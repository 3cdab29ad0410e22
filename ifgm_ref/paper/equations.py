"""Equations (1)-(4) of the IFGM paper, as printed and as the planner runs them.

Reference
---------
M. Zohaib, S. M. Pasha, N. Javaid, A. Salaam and J. Iqbal, "An Improved Algorithm for
Collision Avoidance in Environments Having U and H Shaped Obstacles", *Studies in Informatics
and Control* 23(1):97-106, 2014; section 4, Case-1, equations (1)-(4).

Equation (4) cites FGM: V. Sezer and M. Gokasan, "A novel obstacle avoidance algorithm:
'Follow the Gap Method'", *Robotics and Autonomous Systems* 60(9):1123-1134, 2012.

Every equation appears once as printed (``*_literal``) and once as the planner runs it, where
the two differ; ``docs/errata.md`` says why each reading was chosen and ``proofs/`` proves,
with sympy, where the two forms agree and where they do not.

==========================  ===================  ===============================================
paper symbol                here                 meaning
==========================  ===================  ===============================================
``(x_1, y_1), (x_2, y_2)``  ``p1``, ``p2``       obstacle points of the max gap, robot frame, ft
``(x_g, y_g)``              ``x_g``, ``y_g``     gap midpoint, eq. (1), robot frame, ft
``theta_g``                 ``theta_g``          gap centre angle, eq. (2), rad
``(x_c, y_c)``              ``current``          robot position, world frame, ft
``(x_d, y_d)``              ``destination``      goal position, world frame, ft
``theta_d``                 ``theta_d``          destination angle, eq. (3), rad
``w_g``, ``w_d``            ``w_g``, ``w_d``     gap and goal weight coefficients, eq. (4)
``d_th``                    ``d_th``             gap threshold, eq. (4), ft
``theta_f``                 (returned)           final heading angle, eq. (4), rad
FGM ``alpha``, ``beta``     ``alpha``, ``beta``  FGM's gap and goal weights
FGM ``d_min``               ``d_min``            distance to the nearest obstacle, ft
FGM ``d_1``, ``d_2``        ``d1``, ``d2``       distances of the two gap borders, ft
FGM ``phi_1``, ``phi_2``    ``phi1``, ``phi2``   angles of the gap borders, rad
==========================  ===================  ===============================================

Frames: REP-103 (x forward, y left, angles counter-clockwise positive). Obstacle points, and
so the gap midpoint and ``theta_g``, are in the *robot* frame ("measured w.r.t. reference" in
the paper, section 2.2); positions of eq. (3) are in the *world* frame.

Errors: input outside an equation's domain raises :class:`~ifgm_ref.core.errors.ParameterError`,
including the divisions by zero of the printed forms (2) and (3).
"""

from __future__ import annotations

import math

from ifgm_ref.core.elements import traces
from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.pose import Point, wrap_angle

__all__ = [
    "eq1_gap_midpoint",
    "eq2_gap_angle",
    "eq2_gap_angle_literal",
    "eq3_goal_angle",
    "eq3_goal_angle_literal",
    "eq4_final_heading",
    "eq4_final_heading_fgm",
    "eq4_final_heading_literal",
    "fgm_gap_centre_angle",
]


# ---- equation (1) --------------------------------------------------------------------------------


@traces("eq1")
def eq1_gap_midpoint(p1: tuple[float, float], p2: tuple[float, float]) -> Point:
    r"""Return the midpoint of the gap between two obstacle points, equation (1).

    Printed (section 4, Case-1)::

        (x_g, y_g = (x_1 + x_2)/2, (y_1 + y_2)/2)        (1)

    The misplaced parenthesis is a typo (errata row 1): the two forms coincide, so there is
    one function. The midpoint is the centre of the largest disc centred on the gap segment
    that holds neither obstacle point (``proofs.eq1``).

    Parameters
    ----------
    p1, p2 : tuple of float
        The saved obstacle points ``(x_1, y_1)`` and ``(x_2, y_2)``, robot frame, ft.

    Returns
    -------
    Point
        ``(x_g, y_g)``, in the frame of the inputs.

    Examples
    --------
    >>> eq1_gap_midpoint((4.0, -1.0), (2.0, 3.0))
    Point(x=3.0, y=1.0)

    Coincident points are their own midpoint (a gap of width 0):

    >>> eq1_gap_midpoint((1.0, 1.0), (1.0, 1.0))
    Point(x=1.0, y=1.0)
    """
    (x1, y1), (x2, y2) = p1, p2
    return Point((x1 + x2) / 2.0, (y1 + y2) / 2.0)


# ---- equation (2) --------------------------------------------------------------------------------


@traces("eq2")
def eq2_gap_angle_literal(x_g: float, y_g: float) -> float:
    r"""Return ``theta_g`` exactly as printed in equation (2): the ratio ``y_g / x_g``.

    Printed (section 4, Case-1)::

        theta_g = y_g / x_g        (2)

    This is ``tan(theta_g)``, not an angle (errata row 2, ``proofs.eq2``); it is kept to show
    how far the printed form is from the angle it names. Use :func:`eq2_gap_angle` to steer.

    Parameters
    ----------
    x_g, y_g : float
        Gap midpoint, eq. (1), robot frame, ft.

    Returns
    -------
    float
        The dimensionless ratio ``y_g / x_g``.

    Raises
    ------
    ParameterError
        If ``x_g == 0``: the printed form divides by zero.

    Examples
    --------
    A gap 45 degrees to the left gives 1.0, not pi/4 = 0.785...:

    >>> eq2_gap_angle_literal(2.0, 2.0)
    1.0

    Behind the robot the sign says nothing about the side:

    >>> eq2_gap_angle_literal(-2.0, 2.0)
    -1.0
    >>> eq2_gap_angle_literal(0.0, 1.0)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: eq. (2) as printed is undefined for x_g == 0 (division ...
    """
    if x_g == 0:
        raise ParameterError(
            "eq. (2) as printed is undefined for x_g == 0 (division by zero); "
            f"got (x_g, y_g) = ({x_g!r}, {y_g!r})"
        )
    return y_g / x_g


@traces("eq2")
def eq2_gap_angle(x_g: float, y_g: float) -> float:
    r"""Return the gap centre angle ``theta_g = atan2(y_g, x_g)``, equation (2) as run.

    The printed ratio (:func:`eq2_gap_angle_literal`) is ``tan(theta_g)``; the planner needs
    the direction of the gap midpoint itself (errata row 2). On the half-plane ``x_g > 0``,
    which holds for every gap in the 135-degree field of view, it equals ``atan(y_g / x_g)``
    exactly (``proofs.eq2``).

    Parameters
    ----------
    x_g, y_g : float
        Gap midpoint, eq. (1), robot frame, ft.

    Returns
    -------
    float
        ``theta_g`` in radians, robot frame, in ``[-pi, pi]``.

    Raises
    ------
    ParameterError
        If ``(x_g, y_g) == (0, 0)``: a midpoint at the robot has no direction.

    Examples
    --------
    >>> eq2_gap_angle(2.0, 2.0) == math.pi / 4
    True
    >>> eq2_gap_angle(-2.0, 2.0) == 3 * math.pi / 4
    True
    >>> eq2_gap_angle(0.0, -1.0) == -math.pi / 2
    True
    >>> eq2_gap_angle(0.0, 0.0)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: the gap midpoint (x_g, y_g) = (0.0, 0.0) is at the ...
    """
    if x_g == 0 and y_g == 0:
        raise ParameterError(
            f"the gap midpoint (x_g, y_g) = ({x_g!r}, {y_g!r}) is at the robot: "
            "its direction is undefined"
        )
    return math.atan2(y_g, x_g)


@traces("fgm")
def fgm_gap_centre_angle(d1: float, phi1: float, d2: float, phi2: float) -> float:
    r"""Return FGM's gap centre angle from the two gap borders (cosine and Apollonius theorems).

    Section 2.2 of the paper says FGM determines ``theta_g`` "using Cosine and Apollonius
    theorems"; Sezer & Gokasan (2012) write it as::

        theta_gap_c = arccos( (d_1 + d_2 cos(phi_1 + phi_2))
                              / sqrt(d_1^2 + d_2^2 + 2 d_1 d_2 cos(phi_1 + phi_2)) ) - phi_1

    with border 1 at robot-frame angle ``-phi1`` (``phi1`` measured clockwise from the heading)
    and border 2 at ``+phi2`` (counter-clockwise), so that ``phi1 + phi2`` is the angular width
    of the gap. It is the direction of the eq. (1) midpoint of the two border points
    (errata row 10, ``proofs.eq2``).

    Parameters
    ----------
    d1, phi1 : float
        Distance (ft, > 0) and clockwise angle (rad) of the right-hand gap border.
    d2, phi2 : float
        Distance (ft, > 0) and counter-clockwise angle (rad) of the left-hand gap border.

    Returns
    -------
    float
        The gap centre angle in radians, robot frame (counter-clockwise positive).

    Raises
    ------
    ParameterError
        If a distance is not positive and finite, if the gap width ``phi1 + phi2`` is outside
        ``[0, pi]``, or if the midpoint falls on the robot (``phi1 + phi2 == pi`` with
        ``d1 == d2``).

    Notes
    -----
    ``arccos`` is ill-conditioned near 1 (narrow gaps): an error ``dc`` in its argument moves the
    angle by about ``sqrt(2 dc)``, so results agree with ``atan2`` of the midpoint only to about
    1e-8 rad there. The argument is clipped to ``[-1, 1]`` against rounding.

    Examples
    --------
    A gap symmetric about the heading is straight ahead (to rounding):

    >>> abs(fgm_gap_centre_angle(2.0, math.pi / 4, 2.0, math.pi / 4)) < 1e-15
    True

    Border 1 straight ahead at 1 ft, border 2 at 90 degrees left at 1 ft: the midpoint is at
    (0.5, 0.5), 45 degrees left:

    >>> math.isclose(fgm_gap_centre_angle(1.0, 0.0, 1.0, math.pi / 2), math.pi / 4)
    True

    A zero-width gap points at its border:

    >>> fgm_gap_centre_angle(3.0, 0.5, 1.0, -0.5)
    -0.5
    """
    return math.acos(min(1.0, max(-1.0, _arccos_argument(d1, phi1, d2, phi2)))) - phi1


def _arccos_argument(d1: float, phi1: float, d2: float, phi2: float) -> float:
    """The argument of FGM's arccos (:func:`fgm_gap_centre_angle`): the cosine of the angle
    from border 1 to the midpoint, after checking the borders."""
    for name, value in (("d1", d1), ("d2", d2)):
        if not (math.isfinite(value) and value > 0):
            raise ParameterError(f"`{name}` must be finite and > 0, got {value!r}")
    width = phi1 + phi2
    if not 0.0 <= width <= math.pi:
        raise ParameterError(
            f"the gap width `phi1 + phi2` must be in [0, pi], got {width!r} "
            f"(phi1={phi1!r}, phi2={phi2!r})"
        )
    cos_width = math.cos(width)
    squared = d1 * d1 + d2 * d2 + 2.0 * d1 * d2 * cos_width  # (2 |midpoint|)^2, Apollonius
    if squared <= 0.0:
        raise ParameterError(
            f"the gap midpoint is at the robot (d1={d1!r}, d2={d2!r}, phi1 + phi2 = pi): "
            "its direction is undefined"
        )
    return (d1 + d2 * cos_width) / math.sqrt(squared)


# ---- equation (3) --------------------------------------------------------------------------------


@traces("eq3")
def eq3_goal_angle_literal(current: tuple[float, float], destination: tuple[float, float]) -> float:
    r"""Return ``theta_d`` exactly as printed in equation (3): the arctan of a ratio.

    Printed (section 4, Case-1)::

        theta_d = tan^-1( (y_d - y_c) / (x_d - x_c) )        (3)

    ``arctan`` only returns angles in ``(-pi/2, pi/2)``: with the destination behind
    (``x_d < x_c``) the printed form is off by pi (errata row 5, ``proofs.eq3``). Use
    :func:`eq3_goal_angle` to steer.

    Parameters
    ----------
    current : tuple of float
        The robot position ``(x_c, y_c)``, world frame, ft.
    destination : tuple of float
        The destination ``(x_d, y_d)``, world frame, ft.

    Returns
    -------
    float
        An angle in ``(-pi/2, pi/2)``, radians, world frame.

    Raises
    ------
    ParameterError
        If ``x_d == x_c``: the printed form divides by zero.

    Examples
    --------
    >>> eq3_goal_angle_literal((0.0, 0.0), (1.0, 1.0)) == math.pi / 4
    True

    The destination behind and to the left gives the direction ahead and to the right:

    >>> eq3_goal_angle_literal((0.0, 0.0), (-1.0, 1.0)) == -math.pi / 4
    True
    >>> eq3_goal_angle_literal((0.0, 0.0), (0.0, 5.0))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: eq. (3) as printed is undefined for x_d == x_c ...
    """
    (x_c, y_c), (x_d, y_d) = current, destination
    if x_d == x_c:
        raise ParameterError(
            "eq. (3) as printed is undefined for x_d == x_c (division by zero); "
            f"got current={current!r}, destination={destination!r}"
        )
    return math.atan((y_d - y_c) / (x_d - x_c))


@traces("eq3")
def eq3_goal_angle(current: tuple[float, float], destination: tuple[float, float]) -> float:
    r"""Return the destination angle ``theta_d = atan2(y_d - y_c, x_d - x_c)``, eq. (3) as run.

    The two-argument arctangent keeps the quadrant the printed form
    (:func:`eq3_goal_angle_literal`) loses (errata row 5): equal to it when ``x_d > x_c``, pi
    apart when ``x_d < x_c`` (``proofs.eq3``).

    Parameters
    ----------
    current : tuple of float
        The robot position ``(x_c, y_c)``, world frame, ft.
    destination : tuple of float
        The destination ``(x_d, y_d)``, world frame, ft.

    Returns
    -------
    float
        ``theta_d`` in radians, world frame, in ``[-pi, pi]``.

    Raises
    ------
    ParameterError
        If ``current == destination``: the direction to a reached goal is undefined.

    Examples
    --------
    >>> eq3_goal_angle((0.0, 0.0), (-1.0, 1.0)) == 3 * math.pi / 4
    True
    >>> eq3_goal_angle((1.0, 2.0), (1.0, 7.0)) == math.pi / 2
    True
    >>> eq3_goal_angle((1.0, 2.0), (1.0, 2.0))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: the destination (1.0, 2.0) is the current position: ...
    """
    (x_c, y_c), (x_d, y_d) = current, destination
    if x_d == x_c and y_d == y_c:
        raise ParameterError(
            f"the destination {destination!r} is the current position: its direction is undefined"
        )
    return math.atan2(y_d - y_c, x_d - x_c)


# ---- equation (4) --------------------------------------------------------------------------------


def _check_weights(
    gap_name: str, gap: float, goal_name: str, goal: float, divisor_name: str, divisor: float
) -> None:
    """Raise :class:`ParameterError` unless the weights make (4) a convex combination."""
    for name, value in ((gap_name, gap), (goal_name, goal), (divisor_name, divisor)):
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise ParameterError(f"`{name}` must be a number, got {value!r}")
        if not math.isfinite(value):
            raise ParameterError(f"`{name}` must be finite, got {value!r}")
    if divisor <= 0:
        raise ParameterError(f"`{divisor_name}` must be > 0, got {divisor!r}")
    for name, value in ((gap_name, gap), (goal_name, goal)):
        if value < 0:
            raise ParameterError(f"`{name}` must be >= 0, got {value!r}")
    if gap == 0 and goal == 0:
        both = f"`{gap_name}` and `{goal_name}` must not both be 0 (eq. (4) would be 0/0)"
        raise ParameterError(both)


def _check_angles(**angles: float) -> None:
    """Raise :class:`ParameterError` unless every angle is a finite number."""
    for name, value in angles.items():
        if not math.isfinite(value):
            raise ParameterError(f"`{name}` must be finite, got {value!r}")


@traces("eq4")
def eq4_final_heading_literal(
    theta_g: float, theta_d: float, *, w_g: float, w_d: float, d_th: float
) -> float:
    r"""Return ``theta_f`` exactly as printed in equation (4): a weighted mean of two numbers.

    Printed (section 4, Case-1)::

        theta_f = ( (w_g / d_th) * theta_g + w_d * theta_d ) / ( w_g / d_th + w_d )        (4)

    The angles are averaged as plain numbers, so ``theta_d`` and ``theta_d + 2 pi`` give
    different headings and two directions either side of +-pi average to the opposite one
    (errata row 6, ``proofs.eq4``). Use :func:`eq4_final_heading` to steer.

    Parameters
    ----------
    theta_g, theta_d : float
        Gap centre angle (eq. 2) and destination angle (eq. 3), rad, as numbers.
    w_g, w_d : float
        Gap and goal weight coefficients, >= 0, not both 0.
    d_th : float
        The gap threshold, ft, > 0. FGM divides by ``d_min`` here instead; see
        :func:`eq4_final_heading_fgm`.

    Returns
    -------
    float
        ``theta_f``, radians, between ``theta_g`` and ``theta_d`` (not wrapped).

    Examples
    --------
    >>> eq4_final_heading_literal(0.5, -0.25, w_g=2.0, w_d=1.0, d_th=2.0)
    0.125

    Zero gap weight gives the destination angle:

    >>> eq4_final_heading_literal(0.5, -0.25, w_g=0.0, w_d=1.0, d_th=2.0)
    -0.25

    Two directions 10 degrees apart across +-pi average to straight ahead, the wrong way:

    >>> a = math.radians(175.0)
    >>> eq4_final_heading_literal(a, -a, w_g=1.0, w_d=1.0, d_th=1.0)
    0.0
    """
    _check_angles(theta_g=theta_g, theta_d=theta_d)
    _check_weights("w_g", w_g, "w_d", w_d, "d_th", d_th)
    gap_weight = w_g / d_th
    return (gap_weight * theta_g + w_d * theta_d) / (gap_weight + w_d)


def _wrap(angle: float) -> float:
    """Wrap to ``[-pi, pi)``, returning angles already in range unchanged (bit for bit).

    :func:`~ifgm_ref.core.pose.wrap_angle` rounds in-range angles by up to an ulp of pi; leaving
    them alone makes the robot-frame mean of in-range angles equal the printed mean exactly.
    """
    return angle if -math.pi <= angle < math.pi else wrap_angle(angle)


def _robot_frame_mean(
    theta_g: float, theta_d: float, gap_weight: float, goal_weight: float, heading: float
) -> float:
    """Weighted mean of two directions, taken relative to ``heading``; wrapped to [-pi, pi)."""
    relative_g, relative_d = _wrap(theta_g - heading), _wrap(theta_d - heading)
    mean = (gap_weight * relative_g + goal_weight * relative_d) / (gap_weight + goal_weight)
    return _wrap(heading + mean)


@traces("eq4")
def eq4_final_heading(
    theta_g: float, theta_d: float, *, w_g: float, w_d: float, d_th: float, heading: float
) -> float:
    r"""Return the final heading ``theta_f`` of equation (4), averaged in the robot frame.

    The printed weights (``w_g / d_th`` and ``w_d``, :func:`eq4_final_heading_literal`),
    applied to the angles relative to ``heading``, each wrapped to ``[-pi, pi)``, and the
    heading added back: FGM's robot-frame reading, so the mean of two directions lies between
    them on the side the robot faces, whatever multiple of 2 pi either was written with
    (errata row 6, ``proofs.eq4``).

    Parameters
    ----------
    theta_g, theta_d : float
        Gap centre angle and destination angle, rad, in the frame of ``heading``: pass world
        angles with the world heading, or robot-frame angles with ``heading=0.0``.
    w_g, w_d, d_th : float
        Gap and goal weight coefficients (>= 0, not both 0) and the gap threshold (ft, > 0).
    heading : float
        The robot heading in the frame of ``theta_g`` and ``theta_d``, rad.

    Returns
    -------
    float
        ``theta_f`` in radians, same frame as the inputs, wrapped to ``[-pi, pi)``. Relative to
        ``heading`` it lies between the relative gap and destination angles.

    Examples
    --------
    Robot-frame angles (heading 0) that are already in ``[-pi, pi)`` give the printed mean:

    >>> eq4_final_heading(0.5, -0.25, w_g=2.0, w_d=1.0, d_th=2.0, heading=0.0)
    0.125

    Facing -x (heading pi), a gap 5 degrees to the right and the goal 5 degrees to the left,
    written as world angles either side of +-pi, give a heading of pi, straight on; the
    printed mean of the same numbers gives 0, straight back:

    >>> a = math.radians(175.0)
    >>> theta_f = eq4_final_heading(a, -a, w_g=1.0, w_d=1.0, d_th=1.0, heading=math.pi)
    >>> math.isclose(abs(theta_f), math.pi)
    True

    A goal written with an extra turn is the same goal:

    >>> eq4_final_heading(0.5, -0.25 + 2 * math.pi, w_g=2.0, w_d=1.0, d_th=2.0, heading=0.0)
    0.125
    """
    _check_angles(theta_g=theta_g, theta_d=theta_d, heading=heading)
    _check_weights("w_g", w_g, "w_d", w_d, "d_th", d_th)
    return _robot_frame_mean(theta_g, theta_d, w_g / d_th, w_d, heading)


@traces("fgm")
def eq4_final_heading_fgm(
    theta_g: float, theta_d: float, *, alpha: float, beta: float, d_min: float, heading: float
) -> float:
    r"""Return FGM's final heading: eq. (4) with the gap weight divided by ``d_min``, not ``d_th``.

    Sezer & Gokasan (2012), the source eq. (4) cites, compute::

        theta_final = ( (alpha / d_min) * theta_gap + beta * theta_goal ) / ( alpha / d_min + beta )

    where ``d_min`` is the distance to the nearest obstacle, so the gap weighs more as obstacles
    come closer; the IFGM paper prints the constant ``d_th`` in its place (errata row 8). It
    averages in the robot frame exactly as :func:`eq4_final_heading` does.

    Parameters
    ----------
    theta_g, theta_d : float
        Gap centre angle and goal angle, rad, in the frame of ``heading``.
    alpha, beta : float
        FGM's gap and goal weights, >= 0, not both 0.
    d_min : float
        Distance from the robot to the nearest obstacle, ft, > 0.
    heading : float
        The robot heading in the frame of ``theta_g`` and ``theta_d``, rad.

    Returns
    -------
    float
        ``theta_final`` in radians, wrapped to ``[-pi, pi)``.

    Examples
    --------
    The nearer the obstacle, the more the gap counts:

    >>> far = eq4_final_heading_fgm(0.5, 0.0, alpha=1.0, beta=1.0, d_min=4.0, heading=0.0)
    >>> near = eq4_final_heading_fgm(0.5, 0.0, alpha=1.0, beta=1.0, d_min=0.25, heading=0.0)
    >>> far, near
    (0.1, 0.4)
    >>> eq4_final_heading_fgm(0.5, 0.0, alpha=1.0, beta=1.0, d_min=0.0, heading=0.0)
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: `d_min` must be > 0, got 0.0
    """
    _check_angles(theta_g=theta_g, theta_d=theta_d, heading=heading)
    _check_weights("alpha", alpha, "beta", beta, "d_min", d_min)
    return _robot_frame_mean(theta_g, theta_d, alpha / d_min, beta, heading)
