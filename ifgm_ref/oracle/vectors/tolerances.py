"""The tolerances of the vectors file: every compared quantity, its unit and why its bounds.

An implementation's output passes when it is within the tolerance of its quantity
(:class:`~ifgm_ref.oracle.vectors.schema.Tolerance`): one set for IEEE double, a looser one
for a float32 port (``docs/vectors-format.md``, "tolerances"). ``tests/test_vectors.py``
evaluates every equation in numpy float32 and checks it passes the float32 set and fails the
double one: the evidence that the sets are neither too tight nor pointless.

>>> QUANTITIES["direction"].tolerance("float32")
Tolerance(absolute=0.0001, relative=0.0)
"""

from __future__ import annotations

from ifgm_ref.oracle.vectors.schema import Quantity, Tolerance

__all__ = ["QUANTITIES"]

_DOUBLE_REASON = (
    "double: the reference's own results are exact to the last bit for anyone who evaluates "
    "the same IEEE 754 operations, and other math libraries' atan, atan2, acos, cos and sqrt "
    "differ from it by an ulp or two (1e-15 here); 1e-9 is far above that and far below the "
    "effect of any misreading (a wrong quadrant is off by pi, a flipped sign by twice the "
    "angle). "
)

#: Every compared quantity, by the name the equation forms and the traces use.
QUANTITIES: dict[str, Quantity] = {
    "length": Quantity(
        unit="ft",
        periodic=False,
        double=Tolerance(1e-9),
        float32=Tolerance(1e-4),
        reason=_DOUBLE_REASON
        + "float32 (24-bit significand): every input (|x|, |y| <= 20 ft in these cases) is "
        "stored within 1e-6 ft, and the midpoint adds one rounding; 1e-4 ft leaves room for "
        "world-scale inputs up to 256 ft (half an ulp there: 7.6e-6 ft).",
    ),
    "ratio": Quantity(
        unit="1",
        periodic=False,
        double=Tolerance(1e-9),
        float32=Tolerance(1e-6, 1e-6),
        reason=_DOUBLE_REASON
        + "float32: the printed eq. (2) is a ratio, unbounded near x_g = 0, so its float32 "
        "tolerance is relative: the two inputs and the quotient are rounded once each "
        "(3 x 6e-8 of the value); 1e-6 of the value, plus 1e-6 near 0, leaves margin.",
    ),
    "angle": Quantity(
        unit="rad",
        periodic=False,
        double=Tolerance(1e-9),
        float32=Tolerance(1e-4),
        reason=_DOUBLE_REASON
        + "Compared as plain numbers: the printed forms return numbers that are not wrapped "
        "(atan in (-pi/2, pi/2), the mean of two numbers). float32: world positions of up to "
        "200 ft are stored within 7.6e-6 ft each, which moves the direction between two "
        "points at least 10 ft apart (as in every eq. (3) case with large coordinates) by "
        "under 2e-6 rad; a weighted mean of angles of a few pi adds a few roundings of 5e-7 "
        "rad; 1e-4 rad leaves margin.",
    ),
    "direction": Quantity(
        unit="rad",
        periodic=True,
        double=Tolerance(1e-9),
        float32=Tolerance(1e-4),
        reason=_DOUBLE_REASON
        + "Compared modulo 2 pi: the interpreted forms return directions, and pi and -pi are "
        "the same direction (float32(pi) > pi, so a float32 port may land on either side of "
        "the wrap). float32 as for `angle`; FGM's arccos form (fgm_gap_centre_angle) is "
        "ill-conditioned where its argument nears 1 -- an argument error dc moves the angle "
        "by dc / sin(angle), and by sqrt(2 dc) at 0 -- so its cases keep the angle between "
        "border 1 and the midpoint above 0.1 rad (bar the zero-width case, whose argument is "
        "exactly 1), where float32's 1e-7 becomes 1e-6 rad. A numpy float32 evaluation of "
        "every equation passes within 1e-4 with a margin of 80 or more "
        "(tests/test_vectors.py).",
    ),
    "heading": Quantity(
        unit="rad",
        periodic=True,
        double=Tolerance(1e-9),
        float32=Tolerance(1e-3),
        reason="Trace command heading, world frame, compared modulo 2 pi. double: the replay "
        "is open loop -- every step's observation is recorded, so a difference cannot grow "
        "through the robot's motion, only through the planner's own memory (obstacle points "
        "kept in the world frame by odometry), where an ulp stays an ulp; 1e-9 rad as for "
        "the equations. float32: world positions of up to 200 ft are stored within 7.6e-6 "
        "ft, remembered points and the edge follower's targets (about 2 ft away) are then "
        "good to about 1e-5 rad; 1e-3 rad leaves margin. Either precision may take another "
        "discrete decision where a decision quantity (a gap width against d_th, the nearest "
        "obstacle against d_obs, a corridor length) lies within its rounding of the "
        "threshold: that shows as a branch or a large heading mismatch, to be examined, not "
        "loosened away.",
    ),
    "speed": Quantity(
        unit="ft/s",
        periodic=False,
        double=Tolerance(1e-9),
        float32=Tolerance(1e-3),
        reason="Trace command speed. The planners command the robot's speed v, 0 (turning in "
        "place), v times max(0, cos(turn still to make)), or, at the goal, the distance left "
        "over dt: the error is at most the heading's times v (1.32 ft/s), or "
        "a position error over dt (1e-4 ft/s in float32); the tolerances are the heading's.",
    ),
}
