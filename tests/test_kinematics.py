"""Four-bar kinematics: loop closure, rates against finite differences, Grashof classes, hard cases."""

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from linkwork.engines.kinematics import (
    FourBar,
    dyad_position,
    four_bar,
    grashof_class,
    inversion,
    loop_closure_residual,
    toggle_positions,
)

PAPER = FourBar(crank=0.015, coupler=0.138, rocker=0.115, ground=0.170, branch=1)
TURN = np.linspace(0.0, 2.0 * np.pi, 3601)


#: The crank-rocker strategy rejects most draws by design (Grashof margin, inversion, transmission angle): Hypothesis's
#: filter health check then fails a run at random (CI, 2026-11-26: 9 kept, 50 rejected); every example kept is checked.
FILTERED = [HealthCheck.filter_too_much]


@st.composite
def crank_rockers(draw):
    """Random well-conditioned Grashof crank-rockers, either branch, any frame angle."""
    crank = draw(st.floats(0.01, 0.2))
    coupler, rocker, ground = (draw(st.floats(crank * 1.2, 1.0)) for _ in range(3))
    lengths = sorted((crank, coupler, rocker, ground))
    assume(lengths[0] + lengths[3] < 0.95 * (lengths[1] + lengths[2]))  # Grashof with a 5 % margin
    lw = FourBar(
        crank, coupler, rocker, ground, branch=draw(st.sampled_from([1, -1])), ground_angle=draw(st.floats(-3, 3))
    )
    assume(inversion(lw) == "crank-rocker")
    # well conditioned: transmission angle at least 20 deg (near-singular cases are the hard-case tests)
    assume(np.all(np.sin(four_bar(lw, np.linspace(0, 2 * np.pi, 361)).transmission_angle) > np.sin(np.radians(20))))
    return lw


@settings(max_examples=60, deadline=None, suppress_health_check=FILTERED)
@given(crank_rockers())
def test_loop_closure_residual_over_a_full_turn(lw):
    motion = four_bar(lw, TURN)
    assert np.all(np.isfinite(motion.B))
    assert loop_closure_residual(lw, motion).max() <= 1e-12 * max(lw.lengths)
    # the joint lengths are kept, too
    ab = np.hypot(*(motion.B - motion.A).T)
    assert np.abs(ab - lw.coupler).max() <= 1e-12 * max(lw.lengths)


def test_loop_closure_residual_paper_linkage_absolute():
    motion = four_bar(PAPER, TURN)
    assert loop_closure_residual(PAPER, motion).max() <= 1e-12


def _central_differences(lw, alpha, h):
    plus, minus, mid = four_bar(lw, alpha + h), four_bar(lw, alpha - h), four_bar(lw, alpha)
    out = {}
    for name in ("coupler", "rocker"):
        p, m, c = (getattr(x, f"{name}_angle") for x in (plus, minus, mid))
        dp = np.angle(np.exp(1j * (p - c)))  # unwrap differences across +-pi
        dm = np.angle(np.exp(1j * (m - c)))
        out[name + "_rate"] = (dp - dm) / (2 * h)
        out[name + "_accel"] = (dp + dm) / h**2
    return out


@settings(max_examples=30, deadline=None, suppress_health_check=FILTERED)
@given(crank_rockers())
def test_rates_match_finite_differences(lw):
    alpha = np.linspace(0.0, 2 * np.pi, 73)
    motion = four_bar(lw, alpha)
    fd = _central_differences(lw, alpha, 1e-4)
    scale = 1 + np.abs(motion.rocker_rate).max() + np.abs(motion.coupler_rate).max()
    for name in ("coupler_rate", "rocker_rate"):
        assert np.abs(fd[name] - getattr(motion, name)).max() <= 1e-6 * scale
    ascale = 1 + np.abs(motion.rocker_accel).max() + np.abs(motion.coupler_accel).max()
    for name in ("coupler_accel", "rocker_accel"):
        assert np.abs(fd[name] - getattr(motion, name)).max() <= 1e-4 * ascale


def test_finite_difference_error_converges_at_second_order():
    """The FD error against the analytic rates falls as h^2: the analytic rates are the limit."""
    alpha = np.linspace(0.1, 2 * np.pi, 37)
    motion = four_bar(PAPER, alpha)
    steps = np.array([0.08, 0.04, 0.02, 0.01, 0.005])
    for name in ("rocker_rate", "rocker_accel", "coupler_rate", "coupler_accel"):
        errors = [np.abs(_central_differences(PAPER, alpha, h)[name] - getattr(motion, name)).max() for h in steps]
        rate = np.polyfit(np.log(steps), np.log(errors), 1)[0]
        assert 1.9 < rate < 2.1, (name, rate, errors)


def test_grashof_classes():
    assert grashof_class((0.015, 0.138, 0.115, 0.170)) == "grashof"
    assert grashof_class((1.0, 3.0, 2.0, 2.0)) == "change-point"
    assert grashof_class((2.0, 1.5, 1.2, 2.5)) == "non-grashof"
    assert inversion(PAPER) == "crank-rocker"
    assert inversion(FourBar(3.0, 4.0, 3.5, 1.0)) == "double-crank"
    assert inversion(FourBar(3.0, 1.0, 3.5, 3.2)) == "double-rocker"
    assert inversion(FourBar(3.0, 3.5, 1.0, 3.2)) == "rocker-crank"
    assert inversion(FourBar(2.0, 1.5, 1.2, 2.5)) == "triple-rocker"
    assert inversion(FourBar(1.0, 3.0, 2.0, 2.0)) == "change-point"


def test_double_crank_turns_fully_with_continuous_output():
    lw = FourBar(3.0, 4.0, 3.5, 1.0)
    motion = four_bar(lw, TURN)
    out = np.unwrap(motion.rocker_angle)
    assert abs(out[-1] - out[0] - 2 * np.pi) < 1e-9  # the output link also turns once


def test_transmission_angle_law_of_cosines():
    motion = four_bar(PAPER, TURN)
    d2 = np.sum((PAPER.rocker_pivot - motion.A) ** 2, axis=-1)
    mu = np.arccos((PAPER.coupler**2 + PAPER.rocker**2 - d2) / (2 * PAPER.coupler * PAPER.rocker))
    assert np.allclose(motion.transmission_angle, mu, atol=1e-12)


def test_branch_is_kept_over_several_turns():
    """The same branch over several turns: the motion repeats and never jumps."""
    alpha = np.linspace(0.0, 6 * np.pi, 5401)
    for branch in (1, -1):
        lw = FourBar(PAPER.crank, PAPER.coupler, PAPER.rocker, PAPER.ground, branch=branch)
        motion = four_bar(lw, alpha)
        step = alpha[1] - alpha[0]
        for name in ("coupler", "rocker"):
            jumps = np.abs(np.diff(np.unwrap(getattr(motion, f"{name}_angle"))))
            assert jumps.max() <= 1.01 * np.abs(getattr(motion, f"{name}_rate")).max() * step
        u, v = lw.rocker_pivot - motion.A, motion.B - motion.A
        side = np.sign(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0])
        assert np.all(side == branch)
        per_turn = motion.rocker_angle.reshape(-1)[: 5400].reshape(3, 1800)
        assert np.allclose(per_turn[0], per_turn[2], atol=1e-12)


def test_vectorised_over_any_shape():
    alpha = np.linspace(0, 2 * np.pi, 12).reshape(3, 4)
    motion = four_bar(PAPER, alpha)
    flat = four_bar(PAPER, alpha.ravel())
    assert motion.B.shape == (3, 4, 2)
    assert np.allclose(motion.rocker_rate.ravel(), flat.rocker_rate)


def test_unassemblable_position_names_lengths_and_angle():
    lw = FourBar(crank=0.2, coupler=0.138, rocker=0.115, ground=0.170)
    with pytest.raises(ValueError) as info:
        four_bar(lw, np.radians([0.0, 90.0, 180.0]))
    msg = str(info.value)
    for text in ("crank=0.2 m", "coupler=0.138 m", "rocker=0.115 m", "ground=0.17 m", "crank angle"):
        assert text in msg
    assert "deg" in msg


def test_bad_lengths_and_branch_rejected():
    for bad in (0.0, -1.0, np.nan):
        with pytest.raises(ValueError, match="crank length must be positive"):
            FourBar(bad, 1.0, 1.0, 1.0)
    with pytest.raises(ValueError, match="branch"):
        FourBar(1.0, 3.0, 3.0, 3.0, branch=0)
    with pytest.raises(ValueError, match="branch"):
        dyad_position(np.zeros(2), np.ones(2), 1.0, 1.0, 2)


# --- hard cases ----------------------------------------------------------------------------------


@pytest.mark.hard
def test_change_point_linkage_passes_its_singular_position():
    """s + l = p + q: at alpha = 0 all four links are collinear; positions stay exact, rates are flagged."""
    lw = FourBar(crank=1.0, coupler=3.0, rocker=2.0, ground=2.0)
    assert grashof_class(lw.lengths) == "change-point"
    alpha = np.linspace(-np.pi, np.pi, 2001)  # contains 0 exactly
    motion = four_bar(lw, alpha)
    assert loop_closure_residual(lw, motion).max() <= 1e-12 * max(lw.lengths)
    singular = motion.singular
    assert singular[1000] and singular.sum() <= 3
    assert np.isnan(motion.rocker_rate[1000]) and np.isnan(motion.coupler_accel[1000])
    assert np.all(np.isfinite(motion.rocker_rate[~singular]))
    away = np.abs(alpha) > 0.05
    fd = _central_differences(lw, alpha[away], 1e-5)
    assert np.allclose(fd["rocker_rate"], motion.rocker_rate[away], atol=1e-5)


@pytest.mark.hard
def test_crank_at_toggle_positions():
    """At the crank-coupler toggles the rocker reverses: zero rate, extreme angle."""
    tog = toggle_positions(PAPER)
    assert np.all(np.isfinite(tog.crank_angle))
    motion = four_bar(PAPER, tog.crank_angle)
    assert np.abs(motion.rocker_rate).max() < 1e-12
    ob = np.hypot(*motion.B.T)
    assert np.isclose(ob[0], PAPER.crank + PAPER.coupler, rtol=1e-12)
    assert np.isclose(ob[1], PAPER.coupler - PAPER.crank, rtol=1e-12)
    fine = four_bar(PAPER, np.linspace(0, 2 * np.pi, 200001))
    extremes = np.sort([fine.rocker_angle.min(), fine.rocker_angle.max()])
    assert np.allclose(np.sort(tog.rocker_angle), extremes, atol=1e-9)
    # a double crank has no toggles
    assert np.all(np.isnan(toggle_positions(FourBar(3.0, 4.0, 3.5, 1.0)).crank_angle))


@pytest.mark.hard
def test_lengths_at_the_edge_of_assembly():
    """A triple rocker evaluated exactly at its limit angle (coupler and rocker stretched), then just beyond."""
    lw = FourBar(crank=2.0, coupler=1.5, rocker=1.2, ground=2.5)
    assert inversion(lw) == "triple-rocker"
    # |AO'| = coupler + rocker = 2.7 at the limit
    limit = np.arccos((2.0**2 + 2.5**2 - 2.7**2) / (2 * 2.0 * 2.5))
    motion = four_bar(lw, np.array([0.0, limit * (1 - 1e-15), limit]))
    assert np.all(np.isfinite(motion.B))
    assert motion.singular[-1]
    assert loop_closure_residual(lw, motion).max() <= 1e-12 * max(lw.lengths)
    with pytest.raises(ValueError, match="cannot be assembled"):
        four_bar(lw, np.array([limit + 1e-6]))
