"""Properties of equations (1)-(4), literal and interpreted (``ifgm_ref.paper.equations``).

Each test is named after the equation and the property it checks; the properties are the ones
``proofs/`` proves with sympy, here checked on floats. Where the proofs say the literal and
interpreted forms agree, the tests check that they agree (exactly, or within a stated rounding
tolerance); where the proofs say they differ, the tests check the difference.

The equations' inputs are drawn from their domains, defined once in
``ifgm_ref/oracle/domains.py`` and shared with the oracle's equation checks and the
test vectors: bounded floats (no nan, inf or subnormals), coordinates within 1000 ft (a
world a few times the paper's 197 ft scenario), sensor ranges 0.1-15 ft (``SensorParams``),
weights in {0} or [1e-3, 1e3]. Transformations the properties apply (scale factors, turns,
angles written with extra turns) have their own ranges here.
"""

from __future__ import annotations

import math
import sys

import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.pose import wrap_angle
from ifgm_ref.oracle.domains import DOMAINS, HALF_FOV, floats
from ifgm_ref.paper.equations import (
    eq1_gap_midpoint,
    eq2_gap_angle,
    eq2_gap_angle_literal,
    eq3_goal_angle,
    eq3_goal_angle_literal,
    eq4_final_heading,
    eq4_final_heading_fgm,
    eq4_final_heading_literal,
    fgm_gap_centre_angle,
)

EPS = sys.float_info.epsilon
#: The domains of the arguments drawn here.
EQ4 = DOMAINS["eq4_final_heading"]
FGM_GAP = DOMAINS["fgm_gap_centre_angle"]
#: Angles from one atan/atan2/acos-free evaluation: a few ulps of pi (ulp(pi) = 4.4e-16).
ANGLE_TOL = 1e-15
#: Angles of points that were rotated or scaled first: the points' rounding (~1e-15 ft at
#: 15 ft) divided by the midpoint's distance (>= 0.038 ft for visible points) -- about 1e-13.
TRANSFORMED_ANGLE_TOL = 1e-12
#: FGM's arccos form near +-1 (narrow gaps) turns an argument error dc ~ 1e-16 into an angle
#: error of about sqrt(2 dc) ~ 1.5e-8 rad.
ARCCOS_TOL = 1e-7
#: A direction this close to straight behind the robot may round to either side of the wrap at
#: +-pi, where the robot-frame mean of eq. (4) jumps (see test_eq4_goal_straight_behind).
BEHIND_MARGIN = 1e-9


# ---- strategies ----------------------------------------------------------------------------


def finite_floats(*, min_value: float, max_value: float) -> st.SearchStrategy[float]:
    """Floats in ``[min_value, max_value]``, no nan, inf or subnormals."""
    return st.floats(
        min_value=min_value,
        max_value=max_value,
        allow_nan=False,
        allow_infinity=False,
        allow_subnormal=False,
    )


def signed_floats(*, smallest: float, largest: float) -> st.SearchStrategy[float]:
    """0.0, or floats with ``smallest <= |x| <= largest`` (shrinks towards 0.0).

    Leaving out magnitudes below ``smallest`` keeps products with weights and scale factors
    (>= 1e-3) normal: near 1e-308 they would go subnormal and lose relative precision.
    """
    return st.one_of(
        st.just(0.0),
        finite_floats(min_value=smallest, max_value=largest),
        finite_floats(min_value=-largest, max_value=-smallest),
    )


def coordinates() -> st.SearchStrategy[float]:
    """Coordinates in ft: 0 or 1e-6 to 1e3 ft in size (the domain of eqs. (1) to (3))."""
    return floats(DOMAINS["eq3_goal_angle"].argument("current").domain)


def points() -> st.SearchStrategy[tuple[float, float]]:
    """World points in ft."""
    return st.tuples(coordinates(), coordinates())


def sensor_ranges() -> st.SearchStrategy[float]:
    """Distances the sensor returns, 0.1-15 ft (the domain of FGM's border distances)."""
    return floats(FGM_GAP.argument("d1").domain)


def visible_points(
    *,
    ranges: st.SearchStrategy[float] | None = None,
    bearings: st.SearchStrategy[float] | None = None,
) -> st.SearchStrategy[tuple[float, float]]:
    """Robot-frame obstacle points the sensor sees: range 0.1-15 ft, |bearing| <= 67.5 deg."""
    if ranges is None:
        ranges = sensor_ranges()
    if bearings is None:
        bearings = border_angles()
    return st.builds(lambda r, a: (r * math.cos(a), r * math.sin(a)), ranges, bearings)


def border_angles() -> st.SearchStrategy[float]:
    """Robot-frame angles inside the 135-degree field of view, rad (the domain of FGM's border
    angles)."""
    return floats(FGM_GAP.argument("phi2").domain)


def angles(*, bound: float | None = None) -> st.SearchStrategy[float]:
    """Angles in ``[-bound, bound]``, rad: 0 or at least 1e-9 rad in size (the sensor resolves
    1.8 degrees); by default the domain of eq. (4)'s angles, ``[-pi, pi]``."""
    if bound is None:
        return floats(EQ4.argument("theta_g").domain)
    return signed_floats(smallest=1e-9, largest=bound)


def weight_sets(domain: str = "eq4_final_heading") -> st.SearchStrategy[tuple[float, float, float]]:
    """``(w_g, w_d, d_th)`` of eq. (4) from its domain: weights in {0} or [1e-3, 1e3], not both
    0; d_th in [1e-2, 1e2]. With ``domain="eq4_final_heading_fgm"``: ``(alpha, beta, d_min)``."""
    gap, goal, divisor = DOMAINS[domain].arguments[2:5]
    return st.tuples(floats(gap.domain), floats(goal.domain), floats(divisor.domain)).filter(
        lambda w: w[0] > 0 or w[1] > 0
    )


def _angle_distance(a: float, b: float) -> float:
    """Unsigned difference of two directions, in [0, pi]."""
    return abs(wrap_angle(a - b))


def _clear_of_behind(*angles_and_headings: tuple[float, float]) -> bool:
    """True if no ``(angle, heading)`` pair is within BEHIND_MARGIN of straight behind."""
    return all(
        math.pi - abs(wrap_angle(angle - heading)) > BEHIND_MARGIN
        for angle, heading in angles_and_headings
    )


def _rotate(p: tuple[float, float], phi: float) -> tuple[float, float]:
    c, s = math.cos(phi), math.sin(phi)
    return (c * p[0] - s * p[1], s * p[0] + c * p[1])


# ---- equation (1) --------------------------------------------------------------------------


@pytest.mark.paper("eq1")
@given(data=st.data())
def test_eq1_midpoint_equidistant(data: st.DataObject) -> None:
    """proofs.eq1:midpoint_equidistant, on floats."""
    p1 = data.draw(points(), label="p1")
    p2 = data.draw(points(), label="p2")
    m = eq1_gap_midpoint(p1, p2)
    to_p1, to_p2 = math.dist(m, p1), math.dist(m, p2)
    # Each distance is rounded from coordinates of size <= 1e3: a few ulps of 2e3.
    assert math.isclose(to_p1, to_p2, abs_tol=8 * EPS * 2e3), f"{to_p1=}, but should be {to_p2=}"
    assert math.isclose(to_p1, math.dist(p1, p2) / 2, abs_tol=8 * EPS * 2e3)


@given(data=st.data())
def test_eq1_scaling_equivariant(data: st.DataObject) -> None:
    """eq1(k P1, k P2) = k eq1(P1, P2) (proofs.eq1:scaling_equivariant)."""
    p1 = data.draw(points(), label="p1")
    p2 = data.draw(points(), label="p2")
    k = data.draw(finite_floats(min_value=1e-3, max_value=1e3), label="k")
    scaled = eq1_gap_midpoint((k * p1[0], k * p1[1]), (k * p2[0], k * p2[1]))
    expected = eq1_gap_midpoint(p1, p2)
    for axis in (0, 1):
        # Rounding of k*x1, k*x2, their sum and k*(x1 + x2): a few ulps of k (|x1| + |x2|).
        tol = 4 * EPS * k * (abs(p1[axis]) + abs(p2[axis]))
        assert math.isclose(scaled[axis], k * expected[axis], rel_tol=0.0, abs_tol=tol)


@pytest.mark.paper("eq1")
@given(data=st.data())
def test_eq1_rotation_equivariant(data: st.DataObject) -> None:
    """eq1(R P1, R P2) = R eq1(P1, P2) (proofs.eq1:rotation_equivariant)."""
    p1 = data.draw(points(), label="p1")
    p2 = data.draw(points(), label="p2")
    phi = data.draw(angles(), label="phi")
    rotated = eq1_gap_midpoint(_rotate(p1, phi), _rotate(p2, phi))
    expected = _rotate(eq1_gap_midpoint(p1, p2), phi)
    # cos/sin and the products each round: a few ulps of |P1| + |P2| per coordinate.
    tol = 8 * EPS * (math.hypot(*p1) + math.hypot(*p2))
    assert math.dist(rotated, expected) <= tol, f"{rotated=}, but should be {expected=}"


# ---- equation (2) --------------------------------------------------------------------------


@given(data=st.data())
def test_eq2_literal_agrees_with_atan2_ahead(data: st.DataObject) -> None:
    """x_g > 0: atan(y_g / x_g) = atan2(y_g, x_g) (proofs.eq2:atan_of_ratio_is_atan2_ahead)."""
    x_g = data.draw(finite_floats(min_value=1e-3, max_value=1e3), label="x_g")
    y_g = data.draw(coordinates(), label="y_g")
    literal = math.atan(eq2_gap_angle_literal(x_g, y_g))
    assert math.isclose(literal, eq2_gap_angle(x_g, y_g), rel_tol=0.0, abs_tol=ANGLE_TOL)


@pytest.mark.paper("eq2")
@given(data=st.data())
def test_eq2_literal_differs_by_pi_behind(data: st.DataObject) -> None:
    """x_g < 0: atan of the printed ratio is off by exactly pi (proofs.eq3, same algebra)."""
    x_g = data.draw(finite_floats(min_value=-1e3, max_value=-1e-3), label="x_g")
    y_g = data.draw(coordinates(), label="y_g")
    difference = eq2_gap_angle(x_g, y_g) - math.atan(eq2_gap_angle_literal(x_g, y_g))
    assert math.isclose(abs(difference), math.pi, rel_tol=0.0, abs_tol=ANGLE_TOL)


@pytest.mark.paper("eq2")
@given(data=st.data())
def test_eq2_literal_is_ratio_not_angle(data: st.DataObject) -> None:
    """The printed ratio tan(theta_g) exceeds |theta_g| off the heading (proofs.eq2:ratio_series).

    Gaps at least 1e-4 rad off the heading: below about 3e-8 rad, tan(theta) and theta round to
    the same float (theta^3/3 < ulp(theta)).
    """
    theta = data.draw(finite_floats(min_value=1e-4, max_value=HALF_FOV), label="|theta_g|")
    side = data.draw(st.sampled_from([-1.0, 1.0]), label="side")
    rho = data.draw(sensor_ranges(), label="rho")
    x_g, y_g = rho * math.cos(side * theta), rho * math.sin(side * theta)
    assert abs(eq2_gap_angle_literal(x_g, y_g)) > abs(eq2_gap_angle(x_g, y_g))


@given(data=st.data())
def test_eq2_visible_gap_is_ahead(data: st.DataObject) -> None:
    """Gaps inside the field of view have x_g > 0 (proofs.eq2:midpoint_ahead_in_fov)."""
    m = eq1_gap_midpoint(
        data.draw(visible_points(), label="p1"), data.draw(visible_points(), label="p2")
    )
    assert m.x > 0
    literal = math.atan(eq2_gap_angle_literal(*m))
    assert math.isclose(literal, eq2_gap_angle(*m), rel_tol=0.0, abs_tol=ANGLE_TOL)


@given(data=st.data())
def test_eq2_scaling_invariant(data: st.DataObject) -> None:
    """theta_g of scaled obstacle points is unchanged (proofs.eq2:direction_scale_invariant)."""
    p1 = data.draw(visible_points(), label="p1")
    p2 = data.draw(visible_points(), label="p2")
    k = data.draw(finite_floats(min_value=1e-3, max_value=1e3), label="k")
    scaled = eq2_gap_angle(*eq1_gap_midpoint((k * p1[0], k * p1[1]), (k * p2[0], k * p2[1])))
    original = eq2_gap_angle(*eq1_gap_midpoint(p1, p2))
    assert _angle_distance(scaled, original) <= TRANSFORMED_ANGLE_TOL


@pytest.mark.paper("eq2")
@given(data=st.data())
def test_eq2_rotation_equivariant(data: st.DataObject) -> None:
    """Rotating both points turns theta_g as much (proofs.eq2:direction_rotation_equivariant)."""
    p1 = data.draw(visible_points(), label="p1")
    p2 = data.draw(visible_points(), label="p2")
    phi = data.draw(angles(), label="phi")
    rotated = eq2_gap_angle(*eq1_gap_midpoint(_rotate(p1, phi), _rotate(p2, phi)))
    original = eq2_gap_angle(*eq1_gap_midpoint(p1, p2))
    assert _angle_distance(rotated, original + phi) <= TRANSFORMED_ANGLE_TOL


def test_eq2_straight_behind() -> None:
    """A gap straight behind: the printed ratio is -0.0 (atan 0, ahead); atan2 gives pi."""
    assert eq2_gap_angle_literal(-2.0, 0.0) == 0.0
    assert eq2_gap_angle(-2.0, 0.0) == math.pi


def test_eq2_rejects_midpoint_at_robot() -> None:
    with pytest.raises(ParameterError, match="direction is undefined"):
        eq2_gap_angle(0.0, 0.0)
    with pytest.raises(ParameterError, match="division by zero"):
        eq2_gap_angle_literal(0.0, 3.0)


@given(data=st.data())
def test_fgm_gap_centre_angle_is_midpoint_angle(data: st.DataObject) -> None:
    """FGM's cosine/Apollonius angle = atan2 of the eq. (1) midpoint
    (proofs.eq2:fgm_angle_is_midpoint_direction)."""
    d1 = data.draw(sensor_ranges(), label="d1")
    d2 = data.draw(sensor_ranges(), label="d2")
    angle1 = data.draw(border_angles(), label="angle of border 1")
    angle2 = data.draw(
        finite_floats(min_value=angle1, max_value=HALF_FOV), label="angle of border 2"
    )
    b1 = (d1 * math.cos(angle1), d1 * math.sin(angle1))
    b2 = (d2 * math.cos(angle2), d2 * math.sin(angle2))
    fgm = fgm_gap_centre_angle(d1, -angle1, d2, angle2)
    midpoint = eq2_gap_angle(*eq1_gap_midpoint(b1, b2))
    assert _angle_distance(fgm, midpoint) <= ARCCOS_TOL, f"{fgm=}, but should be {midpoint=}"


@pytest.mark.parametrize(
    ("d1", "phi1", "d2", "phi2", "message"),
    [
        (0.0, 0.1, 1.0, 0.1, "`d1` must be finite and > 0"),
        (1.0, 0.1, math.inf, 0.1, "`d2` must be finite and > 0"),
        (1.0, 0.5, 1.0, -0.6, r"gap width `phi1 \+ phi2` must be in \[0, pi\]"),
        (1.0, 2.0, 1.0, 2.0, r"gap width `phi1 \+ phi2` must be in \[0, pi\]"),
        (2.0, math.pi / 2, 2.0, math.pi / 2, "midpoint is at the robot"),
    ],
)
def test_fgm_gap_centre_angle_rejects_bad_input(
    d1: float, phi1: float, d2: float, phi2: float, message: str
) -> None:
    with pytest.raises(ParameterError, match=message):
        fgm_gap_centre_angle(d1, phi1, d2, phi2)


# ---- equation (3) --------------------------------------------------------------------------


@given(data=st.data())
def test_eq3_literal_agrees_ahead(data: st.DataObject) -> None:
    """x_d > x_c: the printed arctan is atan2 (proofs.eq3:literal_equals_atan2_ahead)."""
    current = data.draw(points(), label="current")
    dx = data.draw(finite_floats(min_value=1e-3, max_value=1e3), label="x_d - x_c")
    y_d = data.draw(coordinates(), label="y_d")
    destination = (current[0] + dx, y_d)
    assume(destination[0] > current[0])  # the sum can round back onto x_c
    literal = eq3_goal_angle_literal(current, destination)
    assert math.isclose(literal, eq3_goal_angle(current, destination), abs_tol=ANGLE_TOL)


@pytest.mark.paper("eq3")
@given(data=st.data())
def test_eq3_literal_differs_by_pi_behind(data: st.DataObject) -> None:
    """x_d < x_c: the printed arctan is off by exactly pi
    (proofs.eq3:literal_differs_by_pi_behind_left, _right, _straight_behind)."""
    current = data.draw(points(), label="current")
    dx = data.draw(finite_floats(min_value=1e-3, max_value=1e3), label="x_c - x_d")
    y_d = data.draw(coordinates(), label="y_d")
    destination = (current[0] - dx, y_d)
    assume(destination[0] < current[0])
    difference = eq3_goal_angle(current, destination) - eq3_goal_angle_literal(current, destination)
    assert math.isclose(abs(difference), math.pi, rel_tol=0.0, abs_tol=ANGLE_TOL)
    # ... and the printed heading points away: its unit vector is opposite to the goal's.
    literal = eq3_goal_angle_literal(current, destination)
    assert _angle_distance(literal, eq3_goal_angle(current, destination) + math.pi) <= ANGLE_TOL


@pytest.mark.paper("eq3")
@given(data=st.data())
def test_eq3_points_at_destination(data: st.DataObject) -> None:
    """The interpreted angle's unit vector is (destination - current)/distance."""
    current = data.draw(points(), label="current")
    destination = data.draw(points(), label="destination")
    offset = (destination[0] - current[0], destination[1] - current[1])
    norm = math.hypot(*offset)
    assume(norm > 1e-3)
    theta_d = eq3_goal_angle(current, destination)
    # cos/sin of an angle within an ulp or two: 1e-15 per component.
    assert math.isclose(math.cos(theta_d), offset[0] / norm, abs_tol=ANGLE_TOL)
    assert math.isclose(math.sin(theta_d), offset[1] / norm, abs_tol=ANGLE_TOL)


def test_eq3_literal_undefined_on_vertical_line() -> None:
    """x_d = x_c: the printed form divides by zero; atan2 gives +-pi/2
    (proofs.eq3:literal_limit_from_ahead, literal_limit_from_behind)."""
    with pytest.raises(ParameterError, match="division by zero"):
        eq3_goal_angle_literal((1.0, 1.0), (1.0, 5.0))
    assert eq3_goal_angle((1.0, 1.0), (1.0, 5.0)) == math.pi / 2
    assert eq3_goal_angle((1.0, 1.0), (1.0, -5.0)) == -math.pi / 2
    # The printed form jumps from +pi/2 to -pi/2 across the line.
    assert eq3_goal_angle_literal((1.0, 1.0), (1.0 + 1e-9, 5.0)) == pytest.approx(math.pi / 2)
    assert eq3_goal_angle_literal((1.0, 1.0), (1.0 - 1e-9, 5.0)) == pytest.approx(-math.pi / 2)


def test_eq3_rejects_reached_goal() -> None:
    with pytest.raises(ParameterError, match="direction is undefined"):
        eq3_goal_angle((2.0, 3.0), (2.0, 3.0))


# ---- equation (4) --------------------------------------------------------------------------


@given(data=st.data())
def test_eq4_literal_between_inputs(data: st.DataObject) -> None:
    """theta_f is a convex combination of its inputs (proofs.eq4:convex_combination)."""
    theta_g = data.draw(angles(bound=10.0), label="theta_g")
    theta_d = data.draw(angles(bound=10.0), label="theta_d")
    w_g, w_d, d_th = data.draw(weight_sets(), label="(w_g, w_d, d_th)")
    theta_f = eq4_final_heading_literal(theta_g, theta_d, w_g=w_g, w_d=w_d, d_th=d_th)
    # A weighted mean rounds by a few ulps of its largest input.
    tol = 4 * EPS * max(abs(theta_g), abs(theta_d))
    assert min(theta_g, theta_d) - tol <= theta_f <= max(theta_g, theta_d) + tol


@given(data=st.data())
def test_eq4_interpreted_agrees_with_literal_in_robot_frame(data: st.DataObject) -> None:
    """Robot-frame angles in [-pi, pi), heading 0: both forms give the same number, exactly."""
    theta_g = data.draw(angles(), label="theta_g")
    theta_d = data.draw(angles(), label="theta_d")
    assume(theta_g < math.pi and theta_d < math.pi)
    w_g, w_d, d_th = data.draw(weight_sets(), label="(w_g, w_d, d_th)")
    literal = eq4_final_heading_literal(theta_g, theta_d, w_g=w_g, w_d=w_d, d_th=d_th)
    interpreted = eq4_final_heading(theta_g, theta_d, w_g=w_g, w_d=w_d, d_th=d_th, heading=0.0)
    if -math.pi <= literal < math.pi:
        assert interpreted == literal
    else:  # the mean of two angles at -pi rounded just below -pi: the same direction
        assert _angle_distance(interpreted, literal) <= ANGLE_TOL


@pytest.mark.paper("eq4")
@given(data=st.data())
def test_eq4_interpreted_between_inputs_in_robot_frame(data: st.DataObject) -> None:
    """Relative to the heading, theta_f lies between the relative gap and goal angles.

    The gap is inside the field of view (|relative theta_g| <= 67.5 deg); the goal anywhere.
    """
    heading = data.draw(angles(), label="heading")
    relative_g = data.draw(border_angles(), label="theta_g - heading")
    relative_d = data.draw(angles(), label="theta_d - heading")
    w_g, w_d, d_th = data.draw(weight_sets(), label="(w_g, w_d, d_th)")
    assume(_clear_of_behind((relative_d, 0.0)))
    theta_f = eq4_final_heading(
        wrap_angle(heading + relative_g),
        wrap_angle(heading + relative_d),
        w_g=w_g,
        w_d=w_d,
        d_th=d_th,
        heading=heading,
    )
    relative_f = wrap_angle(theta_f - heading)
    # heading + relative, its wrap, and the difference back each round by an ulp of 2 pi.
    tol = 1e-14
    low, high = min(relative_g, relative_d) - tol, max(relative_g, relative_d) + tol
    assert any(
        low <= candidate <= high
        for candidate in (relative_f, relative_f - 2 * math.pi, relative_f + 2 * math.pi)
    ), f"relative theta_f={relative_f}, but should be in [{low}, {high}]"


@given(data=st.data())
def test_eq4_interpreted_invariant_under_full_turns(data: st.DataObject) -> None:
    """theta_d and theta_d + 2 pi k are one direction: the interpreted heading is unchanged."""
    theta_g = data.draw(angles(), label="theta_g")
    theta_d = data.draw(angles(), label="theta_d")
    heading = data.draw(angles(), label="heading")
    k = data.draw(st.integers(min_value=-3, max_value=3), label="k")
    w_g, w_d, d_th = data.draw(weight_sets(), label="(w_g, w_d, d_th)")
    assume(_clear_of_behind((theta_g, heading), (theta_d, heading)))
    base = eq4_final_heading(theta_g, theta_d, w_g=w_g, w_d=w_d, d_th=d_th, heading=heading)
    turned = eq4_final_heading(
        theta_g, theta_d + 2 * math.pi * k, w_g=w_g, w_d=w_d, d_th=d_th, heading=heading
    )
    # theta_d + 2 pi k (|k| <= 3) and its wrap round by an ulp of 7 pi: ~3.6e-15.
    assert _angle_distance(base, turned) <= 1e-13


@given(data=st.data())
def test_eq4_literal_depends_on_angle_representation(data: st.DataObject) -> None:
    """Writing theta_d + 2 pi k moves the printed theta_f by 2 pi k (1 - lambda)
    (proofs.eq4:literal_depends_on_angle_representation)."""
    theta_g = data.draw(angles(), label="theta_g")
    theta_d = data.draw(angles(), label="theta_d")
    k = data.draw(st.integers(min_value=-3, max_value=3), label="k")
    w_g, w_d, d_th = data.draw(weight_sets(), label="(w_g, w_d, d_th)")
    base = eq4_final_heading_literal(theta_g, theta_d, w_g=w_g, w_d=w_d, d_th=d_th)
    turned = eq4_final_heading_literal(
        theta_g, theta_d + 2 * math.pi * k, w_g=w_g, w_d=w_d, d_th=d_th
    )
    goal_share = w_d / (w_g / d_th + w_d)
    # Values up to ~7 pi: a few ulps of 22 is ~1e-14.
    assert math.isclose(turned - base, 2 * math.pi * k * goal_share, rel_tol=0.0, abs_tol=1e-13)


@pytest.mark.paper("eq4")
@given(data=st.data())
def test_eq4_interpreted_rotation_equivariant(data: st.DataObject) -> None:
    """Turning the frame by phi (inputs and heading) turns theta_f by phi."""
    theta_g = data.draw(angles(), label="theta_g")
    theta_d = data.draw(angles(), label="theta_d")
    heading = data.draw(angles(), label="heading")
    phi = data.draw(angles(), label="phi")
    w_g, w_d, d_th = data.draw(weight_sets(), label="(w_g, w_d, d_th)")
    assume(_clear_of_behind((theta_g, heading), (theta_d, heading)))
    base = eq4_final_heading(theta_g, theta_d, w_g=w_g, w_d=w_d, d_th=d_th, heading=heading)
    turned = eq4_final_heading(
        theta_g + phi, theta_d + phi, w_g=w_g, w_d=w_d, d_th=d_th, heading=heading + phi
    )
    # Sums of angles up to 2 pi, wrapped: a few ulps of 2 pi.
    assert _angle_distance(turned, base + phi) <= 1e-14


@pytest.mark.paper("eq4")
@given(data=st.data())
def test_eq4_wraparound_counterexample(data: st.DataObject) -> None:
    """Gap and goal either side of +-pi: the printed mean points back, the robot-frame mean on
    (proofs.eq4:counterexample_literal_mean, counterexample_robot_frame_mean)."""
    a = data.draw(
        finite_floats(min_value=math.pi / 2 + 0.01, max_value=math.pi - 1e-6),
        label="|theta| of gap and goal",
    )
    weight = data.draw(finite_floats(min_value=1e-3, max_value=1e3), label="w_g = w_d, d_th = 1")
    literal = eq4_final_heading_literal(a, -a, w_g=weight, w_d=weight, d_th=1.0)
    interpreted = eq4_final_heading(a, -a, w_g=weight, w_d=weight, d_th=1.0, heading=math.pi)
    assert literal == 0.0
    assert _angle_distance(interpreted, math.pi) <= ANGLE_TOL
    assert _angle_distance(literal, interpreted) >= math.pi - ANGLE_TOL


def test_eq4_goal_straight_behind() -> None:
    """A goal exactly behind is at relative angle -pi (the wrap is [-pi, pi)), so the mean
    turns clockwise; a hair to either side of behind, it turns either way: the robot-frame mean
    is discontinuous there, as any mean of directions must be somewhere."""
    behind = eq4_final_heading(0.5, math.pi, w_g=1.0, w_d=1.0, d_th=1.0, heading=0.0)
    assert behind == (0.5 - math.pi) / 2
    left = eq4_final_heading(0.5, math.pi - 1e-9, w_g=1.0, w_d=1.0, d_th=1.0, heading=0.0)
    right = eq4_final_heading(0.5, -math.pi + 1e-9, w_g=1.0, w_d=1.0, d_th=1.0, heading=0.0)
    assert left == pytest.approx((0.5 + math.pi) / 2)
    assert right == pytest.approx((0.5 - math.pi) / 2)


@pytest.mark.paper("eq4")
@given(data=st.data())
def test_eq4_limits(data: st.DataObject) -> None:
    """w_g = 0 gives theta_d, w_d = 0 gives theta_g (proofs.eq4:limit_w_g_to_0, limit_w_d_to_0)."""
    theta_g = data.draw(angles(), label="theta_g")
    theta_d = data.draw(angles(), label="theta_d")
    weight = data.draw(finite_floats(min_value=1e-3, max_value=1e3), label="the other weight")
    d_th = data.draw(finite_floats(min_value=1e-2, max_value=1e2), label="d_th")
    goal_only = eq4_final_heading_literal(theta_g, theta_d, w_g=0.0, w_d=weight, d_th=d_th)
    gap_only = eq4_final_heading_literal(theta_g, theta_d, w_g=weight, w_d=0.0, d_th=d_th)
    # (w theta) / w rounds twice: 2 ulps of theta.
    assert math.isclose(goal_only, theta_d, rel_tol=2 * EPS, abs_tol=0.0)
    assert math.isclose(gap_only, theta_g, rel_tol=2 * EPS, abs_tol=0.0)


@given(data=st.data())
def test_eq4_fgm_is_renamed_eq4(data: st.DataObject) -> None:
    """FGM's form is eq. (4) with alpha, beta, d_min for w_g, w_d, d_th
    (proofs.eq4:fgm_form_is_renamed_eq4)."""
    theta_g = data.draw(angles(), label="theta_g")
    theta_d = data.draw(angles(), label="theta_d")
    heading = data.draw(angles(), label="heading")
    alpha, beta, d_min = data.draw(
        weight_sets("eq4_final_heading_fgm"), label="(alpha, beta, d_min)"
    )
    fgm = eq4_final_heading_fgm(
        theta_g, theta_d, alpha=alpha, beta=beta, d_min=d_min, heading=heading
    )
    renamed = eq4_final_heading(theta_g, theta_d, w_g=alpha, w_d=beta, d_th=d_min, heading=heading)
    assert fgm == renamed


@given(data=st.data())
def test_eq4_fgm_gap_share_grows_as_obstacle_nears(data: st.DataObject) -> None:
    """A nearer obstacle (smaller d_min) steers closer to the gap
    (proofs.eq4:fgm_gap_share_falls_with_d_min)."""
    relative_g = data.draw(border_angles(), label="theta_g (robot frame)")
    relative_d = data.draw(angles(bound=math.pi / 2), label="theta_d (robot frame)")
    near = data.draw(sensor_ranges(), label="d_min near")
    far = data.draw(finite_floats(min_value=near, max_value=15.0), label="d_min far")
    kwargs = {"alpha": 1.0, "beta": 1.0, "heading": 0.0}
    at_near = eq4_final_heading_fgm(relative_g, relative_d, d_min=near, **kwargs)
    at_far = eq4_final_heading_fgm(relative_g, relative_d, d_min=far, **kwargs)
    assert abs(at_near - relative_g) <= abs(at_far - relative_g) + ANGLE_TOL


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"w_g": 1.0, "w_d": 1.0, "d_th": 0.0}, "`d_th` must be > 0, got 0.0"),
        ({"w_g": 1.0, "w_d": 1.0, "d_th": -2.0}, "`d_th` must be > 0"),
        ({"w_g": -1.0, "w_d": 1.0, "d_th": 1.0}, "`w_g` must be >= 0"),
        ({"w_g": 1.0, "w_d": -1.0, "d_th": 1.0}, "`w_d` must be >= 0"),
        ({"w_g": 0.0, "w_d": 0.0, "d_th": 1.0}, "must not both be 0"),
        ({"w_g": math.nan, "w_d": 1.0, "d_th": 1.0}, "`w_g` must be finite"),
        ({"w_g": 1.0, "w_d": 1.0, "d_th": math.inf}, "`d_th` must be finite"),
        ({"w_g": True, "w_d": 1.0, "d_th": 1.0}, "`w_g` must be a number"),
    ],
)
@pytest.mark.parametrize("form", ["literal", "interpreted"])
def test_eq4_rejects_bad_weights(kwargs: dict[str, float], message: str, form: str) -> None:
    with pytest.raises(ParameterError, match=message):
        if form == "literal":
            eq4_final_heading_literal(0.1, 0.2, **kwargs)
        else:
            eq4_final_heading(0.1, 0.2, heading=0.0, **kwargs)


def test_eq4_rejects_non_finite_angles() -> None:
    with pytest.raises(ParameterError, match="`theta_d` must be finite"):
        eq4_final_heading_literal(0.1, math.nan, w_g=1.0, w_d=1.0, d_th=1.0)
    with pytest.raises(ParameterError, match="`heading` must be finite"):
        eq4_final_heading(0.1, 0.2, w_g=1.0, w_d=1.0, d_th=1.0, heading=math.inf)
