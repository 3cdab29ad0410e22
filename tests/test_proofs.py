"""The sympy derivations of ``proofs/`` run under pytest, and their checks have teeth.

``test_proofs_hold[eqN]`` builds each derivation (a claim sympy does not reduce to exactly 0
or True raises ``ClaimFailed``) and pins the list of claims, so a claim cannot silently
disappear. The ``test_*_rejects_*`` tests feed deliberately wrong claims to the same helpers,
including a wrong eq. (4) into the real derivation, and expect them to be rejected.
``test_errata_citations_resolve`` checks that every proof claim and test cited in
``docs/errata.md`` exists.
"""

from __future__ import annotations

import ast
import functools
import importlib
import re
import subprocess
import sys
from pathlib import Path

import pytest
import sympy as sp

from ifgm_ref.core.formulas import Unit
from ifgm_ref.planners import PLANNERS
from ifgm_ref.planners.tuning import ParamInfo
from proofs._util import ClaimFailed, ClaimKind, Derivation

ROOT = Path(__file__).resolve().parents[1]

#: Every claim of every derivation, in order. Spot checks are the ``library_*`` claims.
EXPECTED_CLAIMS: dict[str, tuple[str, ...]] = {
    "eq1": (
        "midpoint_on_segment",
        "midpoint_equidistant",
        "midpoint_half_gap",
        "segment_point_distance_to_p1",
        "segment_point_distance_to_p2",
        "largest_free_disc_radius",
        "largest_free_disc_centre_is_midpoint",
        "robot_fits_iff_gap_at_least_diameter",
        "rotation_equivariant",
        "scaling_equivariant",
        "library_midpoint_x_matches_formula",
        "library_midpoint_y_matches_formula",
    ),
    "eq2": (
        "printed_form_is_tangent",
        "ratio_minus_angle_derivative",
        "ratio_series",
        "ratio_at_fov_edge",
        "ratio_exceeds_angle_at_fov_edge",
        "atan_of_ratio_is_atan2_ahead",
        "fov_edge_is_ahead",
        "midpoint_ahead_in_fov",
        "direction_scale_invariant",
        "direction_rotation_equivariant",
        "width_parametrisation",
        "cosine_theorem",
        "apollonius_theorem",
        "median_length",
        "median_length_positive_form",
        "median_length_positive",
        "sine_of_arccos_positive",
        "sine_of_arccos_squared",
        "angle_difference_identities",
        "fgm_angle_is_midpoint_direction",
        "library_literal_is_tangent_of_angle",
        "library_fgm_angle_is_midpoint_angle",
    ),
    "eq3": (
        "literal_equals_atan2_ahead",
        "literal_differs_by_pi_behind_left",
        "literal_differs_by_pi_behind_right",
        "literal_differs_by_pi_straight_behind",
        "literal_points_away_behind",
        "literal_heading_increases_distance",
        "literal_limit_from_ahead",
        "literal_limit_from_behind",
        "atan2_on_vertical_line",
        "library_literal_differs_by_pi_behind",
    ),
    "eq4": (
        "convex_combination",
        "gap_share_positive",
        "goal_share_is_complement",
        "goal_share_positive",
        "offset_from_goal",
        "offset_from_gap",
        "limit_w_g_to_0",
        "limit_w_d_to_0",
        "limit_d_th_to_oo",
        "limit_d_th_to_0",
        "d_theta_g_is_gap_share",
        "d_theta_d_is_goal_share",
        "d_w_g_sign",
        "d_w_g_sign_factor_positive",
        "d_w_d_sign",
        "d_w_d_sign_factor_positive",
        "d_d_th_sign",
        "d_d_th_sign_factor_positive",
        "fgm_form_is_renamed_eq4",
        "fgm_gap_share_derivative",
        "fgm_gap_share_falls_with_d_min",
        "literal_depends_on_angle_representation",
        "counterexample_literal_mean",
        "counterexample_relative_angles",
        "counterexample_robot_frame_mean",
        "counterexample_opposite_directions",
        "counterexample_printed_far_from_gap",
        "counterexample_printed_far_from_goal",
        "counterexample_inputs_close",
        "library_literal_matches_formula",
        "library_counterexample_literal",
        "library_counterexample_robot_frame",
        "library_fgm_matches_renamed_eq4",
    ),
    # One claim per parameter of every registered planner: read from the registry, so that a
    # parameter cannot go unproved; the simulator's stall time and lap thresholds before them.
    "scale": (
        "min_commutes_with_scaling",
        "max_commutes_with_scaling",
        "simulator_stall_time_scales_as_length_power_0",
        "simulator_lap_radius_scales_as_length_power_1",
        "simulator_lap_length_scales_as_length_power_1",
        "simulator_lap_progress_scales_as_length_power_1",
        *(
            f"{planner}_{p.name}_scales_as_length_power_{p.unit.length_power}"
            for planner, info in PLANNERS.items()
            for p in info.infos
        ),
        "ifgm_d_th_exceeds_the_robot_diameter",
        "fgm_beta_is_the_paper_value",
    ),
    # The braking governor (ifgm_ref/planners/governor.py) keeps the robot passively safe.
    "braking": (
        "braking_distance",
        "mitsch_bound",
        "response_stretch",
        "ramp_formula",
        "stopping_distance_with_response",
        "speeding_up_period",
        "slowing_down_period",
        "braking_period",
        "continuous_pieces",
        "cap_only_tightens",
        "cap_only_tightens_sign",
        "increasing_in_command",
        "increasing_in_command_sign",
        "increasing_in_speed",
        "root_of_quadratic",
        "root_has_no_cancellation",
        "code_quadratics",
        "bound_when_speeding_up",
        "bound_when_slowing_down",
        "ramp_composes",
        "ramp_continuous_in_target",
        "ramp_increasing_in_target",
        "window_holds_the_commands_in_effect",
        "next_state_with_long_response",
        "step_cross_products",
        "step_between_the_edges",
        "displacement_no_longer_than_path",
        "displacement_no_longer_than_path_sign",
        "fan_edge_touch",
        "fan_inside_touch",
        "margin_only_shrinks_the_room",
        "margin_hysteresis",
        "profile_increases_with_acceleration",
        "one_period_leaves_the_stop",
        "one_period_leaves_the_stop_sign",
        "long_response_leaves_the_stop",
        "rest_rule",
        "margin_covers_odometry",
        "no_braking_term_at_infinite_b",
        "one_period_left_at_infinite_b",
        "one_period_at_top_speed_at_infinite_a",
        "library_stopping_distance_pieces",
        "library_safe_speed_is_root",
        "library_no_speed_when_braking_does_not_fit",
        "library_next_state",
        "library_window_kept",
        "library_fan_room_edge",
        "library_fan_room_margin",
        "library_failed_check_brakes_along_last_heading",
        "library_standing_turns_in_place",
        "library_fan_holds_the_carried_turn",
        "library_fallback_keeps_heading_while_moving",
        "library_governed_robot_never_touches",
        "library_governed_robot_responding_late_never_touches",
        "library_governed_robot_steps_late_never_touches",
    ),
}


@pytest.mark.parametrize("equation", sorted(EXPECTED_CLAIMS))
def test_proofs_hold(equation: str) -> None:
    module = importlib.import_module(f"proofs.{equation}")
    claims = module.claims()  # raises ClaimFailed on the first claim that does not hold
    names = tuple(c.name for c in claims)
    assert names == EXPECTED_CLAIMS[equation], (
        f"claims of proofs.{equation}={names}, but should be {EXPECTED_CLAIMS[equation]}"
    )
    for claim in claims:
        expected_kind = (
            ClaimKind.SPOT_CHECK if claim.name.startswith("library_") else ClaimKind.PROOF
        )
        assert claim.kind is expected_kind, f"{equation}:{claim.name} kind={claim.kind}"


@pytest.mark.parametrize("equation", sorted(EXPECTED_CLAIMS))
def test_proofs_main_prints_worked_page(equation: str, capsys: pytest.CaptureFixture[str]) -> None:
    """``main()`` prints every claim, its kind and the summary line."""
    importlib.import_module(f"proofs.{equation}").main()
    page = capsys.readouterr().out
    for name in EXPECTED_CLAIMS[equation]:
        assert f"{equation}:{name}" in page
    spot_checks = sum(n.startswith("library_") for n in EXPECTED_CLAIMS[equation])
    proved = len(EXPECTED_CLAIMS[equation]) - spot_checks
    assert f"{proved} claim(s) proved by sympy; {spot_checks} numeric spot check(s)" in page


def test_proofs_run_as_module() -> None:
    """``python -m proofs.eq3`` runs from the project root and prints the worked page."""
    result = subprocess.run(
        [sys.executable, "-m", "proofs.eq3"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=False,
        timeout=120,
    )
    assert result.returncode == 0, result.stderr
    assert result.stdout.startswith("Equation (3): the destination angle")
    assert "eq3:literal_differs_by_pi_behind_left" in result.stdout


def test_proofs_render_markdown() -> None:
    markdown = importlib.import_module("proofs.eq4").derivation().to_markdown()
    assert markdown.startswith("### Equation (4)")
    assert "`eq4:convex_combination`" in markdown
    assert "$$" in markdown


# ---- the checks have teeth -----------------------------------------------------------------


def test_prove_equal_rejects_false_claim() -> None:
    """atan(y/x) = atan2(y, x) is false behind the robot; the helper must say so."""
    x = sp.Symbol("x", negative=True)
    y = sp.Symbol("y", positive=True)
    d = Derivation("teeth", "Teeth")
    with pytest.raises(ClaimFailed, match=r"teeth:wrong not proved: simplify\(lhs - rhs\) = -pi"):
        d.prove_equal("wrong", sp.atan(y / x), sp.atan2(y, x), "atan = atan2 behind")
    assert d.claims == ()


def test_prove_equal_rejects_unproved_claim() -> None:
    """sqrt(y^2) = y needs y >= 0: without the assumption sympy leaves Abs(y) - y, not 0."""
    y = sp.Symbol("y", real=True)
    with pytest.raises(ClaimFailed, match=r"Abs\(y\)"):
        Derivation("teeth", "Teeth").prove_equal("sqrt", sp.sqrt(y**2), y, "sqrt(y^2) = y")


def test_prove_sign_rejects_unknown_sign() -> None:
    """sympy's "don't know" (None) is not a proof."""
    z = sp.Symbol("z", real=True)
    with pytest.raises(ClaimFailed, match="is_positive is None"):
        Derivation("teeth", "Teeth").prove_sign("sign", z, "positive", "z > 0")
    with pytest.raises(ClaimFailed, match="is_negative is False"):
        Derivation("teeth", "Teeth").prove_sign("sign", sp.pi, "negative", "pi < 0")


def test_prove_true_rejects_unevaluated_relation() -> None:
    a, b = sp.symbols("a b", real=True)
    with pytest.raises(ClaimFailed, match="should be True"):
        Derivation("teeth", "Teeth").prove_true("eq", sp.Eq(a, b), "a = b")
    with pytest.raises(ClaimFailed, match="should be True"):
        Derivation("teeth", "Teeth").prove_true("false", sp.false, "false")


def test_spot_check_rejects_out_of_tolerance() -> None:
    with pytest.raises(ClaimFailed, match=r"at \(1.0,\): value=1.5, but should be 1.0"):
        Derivation("teeth", "Teeth").spot_check(
            "off",
            lambda x: x + 0.5,
            lambda x: x,
            [(1.0,)],
            "x + 0.5 = x",
            abs_tol=0.1,
            reason="test",
        )


def test_wrong_eq4_is_rejected_by_its_derivation(monkeypatch: pytest.MonkeyPatch) -> None:
    """The real eq. (4) derivation fed a wrong formula (w_g * d_th for w_g / d_th) fails."""
    eq4 = importlib.import_module("proofs.eq4")

    def wrong(
        theta_g: sp.Expr, theta_d: sp.Expr, w_g: sp.Expr, w_d: sp.Expr, d_th: sp.Expr
    ) -> sp.Expr:
        return ((w_g * d_th) * theta_g + w_d * theta_d) / (w_g * d_th + w_d)

    monkeypatch.setattr(eq4, "final_heading", wrong)
    with pytest.raises(ClaimFailed, match="eq4:convex_combination not proved"):
        eq4.derivation.__wrapped__()  # the uncached builder


@pytest.mark.parametrize(
    ("formula", "unit", "remainder"),
    [
        ("r + 1", Unit.LENGTH, r"1 - k"),  # an absolute 1 ft margin
        ("Max(r, 1)", Unit.LENGTH, r"Max"),  # an absolute floor
        ("50*r**4", Unit.LENGTH, r"k\*\*3 - 1"),  # the right formula, the wrong unit
        ("v*dt", Unit.TIME, r"k - 1"),  # a length declared a time
    ],
)
def test_scale_proof_rejects_an_absolute_length(formula: str, unit: Unit, remainder: str) -> None:
    scale = importlib.import_module("proofs.scale")
    toy = {"toy": [ParamInfo("margin", formula, unit)]}
    with pytest.raises(
        ClaimFailed, match=rf"scale:toy_margin_scales_as_length_power_\d not proved: .*{remainder}"
    ):
        scale.build(toy, paper_values={})
    ok = {"toy": [ParamInfo("margin", "Min(R, 15*r) + v/w", Unit.LENGTH)]}
    assert [c.name for c in scale.build(ok, paper_values={}).claims][-1] == (
        "toy_margin_scales_as_length_power_1"
    )


def test_scale_proof_rejects_a_wrong_paper_value() -> None:
    scale = importlib.import_module("proofs.scale")
    fgm = {"fgm": PLANNERS["fgm"].infos}
    with pytest.raises(ClaimFailed, match="scale:fgm_beta_is_the_paper_value not proved"):
        scale.build(fgm, paper_values={("fgm", "beta"): sp.Integer(2)})


def test_claim_names_are_unique() -> None:
    d = Derivation("teeth", "Teeth")
    d.prove_equal("same", sp.Integer(1), sp.Integer(1), "1 = 1")
    with pytest.raises(ValueError, match="used twice"):
        d.prove_equal("same", sp.Integer(2), sp.Integer(2), "2 = 2")


# ---- docs/errata.md cites what exists ------------------------------------------------------

_PROOF_CITATION = re.compile(r"proofs\.(eq\d|scale|flowchart|braking):(\w+)")
_TEST_CITATION = re.compile(r"((?:tests|ifgm_ref)/[\w/]+\.py)::([\w.]+)")


@functools.cache
def _defined_names(path: Path) -> frozenset[str]:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    return frozenset(
        node.name
        for node in ast.walk(tree)
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef)
    )


def test_errata_citations_resolve() -> None:
    """Every ``proofs.eqN:claim`` and ``path.py::name`` cited in docs/errata.md exists."""
    text = (ROOT / "docs" / "errata.md").read_text(encoding="utf-8")
    proof_citations = _PROOF_CITATION.findall(text)
    test_citations = _TEST_CITATION.findall(text)
    assert proof_citations and test_citations, "docs/errata.md cites nothing"
    for equation, name in proof_citations:
        assert name in EXPECTED_CLAIMS.get(equation, ()), f"proofs.{equation}:{name} not found"
    for path, name in test_citations:
        file = ROOT / path
        assert file.is_file(), f"{path} cited in docs/errata.md does not exist"
        # A pytest id: test function, or a doctest id "module.function" -> the function.
        function = name.split("[")[0].rsplit(".", 1)[-1]
        assert function in _defined_names(file), f"{path}::{name} not found"
