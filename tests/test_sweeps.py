"""The parameter sweeps: jobs of several points, the facts that interpret a sweep (trends, threshold crossings,
colour ranges), and why the heald sweep does not sweep the warp branch."""

import numpy as np
import pytest

from linkwork.pipeline.sweeps import (
    COLOUR_FLOOR_FACTOR, batches, crossings, gather, grid, interpret, points_dataset, trend,
)

from conftest import load_yaml


def _heald_cfg(config):
    return {k: config["heald"][k] for k in ("parameters", "excitation", "speeds")}


def test_jobs_cover_the_grid_once_and_gather_back():
    axes = {"clearance_m": [1e-5, 2e-5, 4e-5], "crank_speed_rad_s": [10.0, 20.0, 30.0, 40.0]}
    points = grid(axes)
    jobs = batches(points, 5)
    assert [len(j) for j in jobs] == [4, 4, 4] and [p for j in jobs for p in j] == points
    assert len(batches(points, 100)) == 1 and len(batches(points, 1)) == 12
    with pytest.raises(ValueError):
        batches(points, 0)
    outputs = {"y": ("N", "a force")}
    parts = [points_dataset(j, [{"y": p["clearance_m"] * p["crank_speed_rad_s"]} for p in j], outputs) for j in jobs]
    out = gather(axes, parts)
    assert np.allclose(out.y.values, np.outer(axes["clearance_m"], axes["crank_speed_rad_s"]))
    with pytest.raises(ValueError, match="once each"):
        gather(axes, parts[:-1])


def test_crossing_is_exact_for_a_power_law_on_a_log_axis():
    x = np.array([1.0, 2.0, 4.0, 8.0])
    y = x**2  # linear in log x after taking logs: log-linear interpolation of y is not exact, but of log y is
    assert crossings(x, np.log(y), np.log(10.0)) == pytest.approx(np.sqrt(10.0), rel=1e-12)
    assert crossings(x, y, 4.0) == 2.0  # a grid value exactly at the threshold
    assert np.isnan(crossings(x, y, 100.0)) and np.isnan(crossings(x, -y, 0.5))
    assert crossings(np.array([-1.0, 1.0]), np.array([0.0, 2.0]), 1.0) == pytest.approx(
        0.0
    )  # linear where x is not positive


def test_trend_change_and_monotone_lines():
    v = np.array([[1.0, 2.0], [1.5, 1.0], [2.0, 3.0]])  # axis 0 swept; line 0 monotone (+100 %), line 1 not (+50 %)
    t = trend(v)
    assert (
        t["change_low"] == pytest.approx(0.5)
        and t["change_high"] == pytest.approx(1.0)
        and t["monotone_fraction"] == 0.5
    )


def test_interpret_states_crossings_and_a_colour_range_that_does_not_exaggerate():
    axes = {"clearance_m": [1e-5, 2e-5, 4e-5, 8e-5], "reaction_ratio_EF": [1.0, 2.0, 4.0]}
    pts = grid(axes)
    values = [
        {"r": p["reaction_ratio_EF"] * (1 + p["clearance_m"] * 1e3), "flat": 1.0 + 0.05 * p["clearance_m"] / 8e-5}
        for p in pts
    ]
    ds = gather(axes, [points_dataset(pts, values, {"r": ("1", "ratio"), "flat": ("N", "a 5 % change")})])
    out = interpret(
        ds, {"clearance_m": 2.1e-5, "reaction_ratio_EF": 2.0},
        {"r": {"value": 3.0, "along": "reaction_ratio_EF", "label": "t"}},
    )
    assert out.attrs["reference_clearance_m"] == 2e-5
    # r = ratio x (1 + 1e3 c) crosses 3 on the log ratio axis at 3 / (1 + 1e3 c) when that lies on the grid
    for c, cross, side in zip(axes["clearance_m"], out.r_threshold_crossing.values, out.r_threshold_side.values):
        expected = 3.0 / (1 + c * 1e3)
        x = np.array(axes["reaction_ratio_EF"])
        k = np.searchsorted(x, expected) - 1
        y0, y1 = x[k] * (1 + c * 1e3), x[k + 1] * (1 + c * 1e3)  # linear in y, log in x between the two grid values
        f = (3.0 - y0) / (y1 - y0)
        assert side == 0 and cross == pytest.approx(np.exp(np.log(x[k]) + f * np.log(x[k + 1] / x[k])), rel=1e-12)
    assert float(out.threshold_holds_fraction.sel(output="r")) == pytest.approx(
        np.mean(np.array([v["r"] for v in values]) >= 3.0)
    )
    assert np.isnan(float(out.threshold_value.sel(output="flat")))
    # the 5 % map: centred on its reference value, the colour range is the floor, and its whole spread takes a few % of
    # the bar
    low, high, ref = (float(out[k].sel(output="flat")) for k in ("colour_low", "colour_high", "reference_value"))
    assert high / ref == pytest.approx(COLOUR_FLOOR_FACTOR) and ref / low == pytest.approx(COLOUR_FLOOR_FACTOR)
    assert np.log(ds.flat.values.max() / ds.flat.values.min()) / np.log(high / low) < 0.04
    # a map spreading further than the floor: the range is symmetric in log about the threshold and holds every value
    low, high = float(out.colour_low.sel(output="r")), float(out.colour_high.sel(output="r"))
    assert low * high == pytest.approx(9.0) and low <= ds.r.values.min() and high >= ds.r.values.max()
    assert high == pytest.approx(max(ds.r.values.max(), 9.0 / ds.r.values.min()))  # the further end sets the factor
    change = out.trend_change_low.sel(output="r", axis="reaction_ratio_EF")
    assert float(change) == pytest.approx(3.0)  # ratio 1 -> 4 multiplies r by 4 on every line


def test_heald_model_b_joint_forces_do_not_see_the_warp_branch(config):
    """Under the velocity drive, model B's E and F branches hang on the driven node: M_P and k_O cannot change
    Q_E, Q_F (to round-off).  Model A's can (the test could fail), and model B's Q_E is the closed-form force of a
    spring-mass branch driven in velocity (an independent route)."""
    from linkwork.papers.heald.adapter import amplitude, omega_grid
    from linkwork.papers.heald.model import joint_stiffness, model_b_parameters, reduced_masses
    from linkwork.papers.heald.dynamics import joint_forces
    from linkwork.papers.heald.sweep import point_parameters, warp_branch_independence

    cfg = _heald_cfg(config)
    point = {"clearance_m": 1e-4, "reaction_ratio_EF": 3.0}
    for changes in ({"M_P": 20.0}, {"k_O": 5e4}, {"M_P": 5.0, "k_O": 5e3, "c_O": 80.0}):
        assert warp_branch_independence(cfg, point, "B", changes) < 1e-8
        assert warp_branch_independence(cfg, point, "A", changes) > 1e-2
    p = {**point_parameters(cfg, point), "c_joint": 0.0}
    w, amp = omega_grid(cfg["speeds"]), amplitude(cfg)
    _, q_e, _, _ = joint_forces("B", p, "elastic", w, amp)
    m_e, _ = reduced_masses(p)
    k_e = joint_stiffness(model_b_parameters(p), "E", "elastic")  # model B's joints carry its kinetostatic reactions
    closed = np.abs(1j * w * amp / (1j * w / k_e + 1 / (1j * w * m_e)))
    assert np.allclose(np.abs(q_e), closed, rtol=1e-8)


def test_heald_sweep_point_moves_the_reaction_ratio_only_in_E(config):
    from linkwork.papers.heald.sweep import point_parameters, thresholds

    cfg = _heald_cfg(config)
    p = point_parameters(cfg, {"clearance_m": 2e-5, "reaction_ratio_EF": 4.0})
    base = config["heald"]["parameters"]
    assert p["reaction_F"] == base["reaction_F"]["value"] and p["reaction_E"] == 4.0 * base["reaction_F"]["value"]
    assert p["clearance_E"] == p["clearance_F"] == 2e-5 and p["M_P"] == base["M_P"]["value"]
    assert thresholds(load_yaml("config/published/heald.yaml"))["ratio_EF_min"]["value"] == 3.0


def test_a_clearance_sweep_point_is_the_scene_settled_from_the_first_start():
    """Second route for a sweep point: at the reference clearance and speed, its state and its measure (relative RMS
    deviation of the rocker acceleration) are those of the scene study run from the first start without checks
    (the same settling rule), the measure over the RMS of the ideal response; its section points are the state's."""
    import copy

    from linkwork.papers.clearance.fourbar import inverse_dynamics
    from linkwork.papers.clearance.adapter import parameters
    from linkwork.papers.clearance.studies import cycle, scene
    from linkwork.papers.clearance.sweep import SECTION_POINTS, sweep_point

    cfg = copy.deepcopy(load_yaml("config/config.yaml")["clearance"])
    cfg["numerics"]["points_per_cycle"] = 1800  # coarser than the pipeline's, the same for both routes
    c = cfg["joints"]["bearing_radius_m"] - cfg["joints"]["journal_radius_m"]
    out = sweep_point(
        cfg, {"clearance_m": c, "crank_speed_rad_s": cfg["crank_speed_rad_s"]}, {"scene": "dry_2", "variant": "decoded"}
    )
    ds = scene(cfg, "decoded", "dry_2", first_start_only=True, check=False)
    p = parameters(cfg, "decoded", "dry_2")
    per = cfg["numerics"]["points_per_cycle"]
    ideal = inverse_dynamics(p, np.arange(per + 1) * cycle(p) / per, True)["rocker_acceleration"][:-1]
    assert out["state_period"] == int(ds.state_period[0]) and out["state_transient"] == int(ds.state_transient[0])
    measure = float(ds.judged_mean.sel(measure="rms", quantity="rocker_acceleration")[0]) / np.sqrt(np.mean(ideal**2))
    assert out["rocker_acceleration_deviation"] == pytest.approx(measure, rel=1e-12)
    first, stop = int(ds.window_first[0]), int(ds.window_stop[0])
    kept = ds.section.values[0, first:stop, 0][-SECTION_POINTS:]
    assert [out[f"section_{k}"] for k in range(kept.size)] == pytest.approx(kept.tolist(), rel=1e-12)


def test_resolved_trend_counts_only_changes_beyond_the_cycle_spread():
    from linkwork.pipeline.sweeps import TREND_CLASSES, resolved_trend, trend_class

    v = np.array([[1.0, 1.0, 1.0], [1.5, 1.1, 1.2], [2.0, 1.2, 0.5]])  # axis 0 swept; three lines
    s = np.array([[0.1, 0.3, 0.1], [0.1, 0.3, 0.1], [0.1, 0.3, 0.1]])
    r = resolved_trend(v, s)
    # line 0: +1.0 > 0.2 (up); line 1: +0.2 < 0.6 (scatter); line 2: -0.5 > 0.2 (down)
    assert r["resolved_up"] == pytest.approx(1 / 3) and r["resolved_down"] == pytest.approx(1 / 3)
    # steps: line 0 both (0.5 > 0.2), line 1 none (0.1 < 0.6), line 2 the second only (0.2 = 0.2 is not beyond, 0.7 is)
    assert r["resolved_steps"] == pytest.approx(3 / 6)
    assert trend_class(r["resolved_up"], r["resolved_down"]) == "partly"
    assert trend_class(1.0, 0.0) == "grows" and trend_class(0.0, 1.0) == "falls" and trend_class(0.0, 0.0) == "none"
    # a scatter larger than every change: nothing is a trend, however monotone the lines
    assert resolved_trend(v[:, :1], np.full((3, 1), 1.0)) == {
        "resolved_up": 0.0,
        "resolved_down": 0.0,
        "resolved_steps": 0.0,
    }
    axes = {"clearance_m": [1e-5, 2e-5, 4e-5], "crank_speed_rad_s": [10.0, 20.0, 30.0]}
    pts = grid(axes)
    vals = [{"y": 1.0 + p["clearance_m"] * 1e5, "y_spread": 0.1} for p in pts]  # grows by 1 per grid step in clearance
    out = interpret(gather(axes, [points_dataset(pts, vals, {"y": ("1", "y"), "y_spread": ("1", "spread")})]),
                    {"clearance_m": 2e-5, "crank_speed_rad_s": 20.0}, {}, scatter={"y": "y_spread"})
    assert str(out.trend_resolved_class.sel(output="y", axis="clearance_m").values) == TREND_CLASSES["grows"]
    assert str(out.trend_resolved_class.sel(output="y", axis="crank_speed_rad_s").values) == TREND_CLASSES["none"]
    assert float(out.relative_scatter_reference.sel(output="y")) == pytest.approx(0.1 / 3.0)
    assert np.isnan(float(out.trend_resolved_up_fraction.sel(output="y_spread", axis="clearance_m")))


def test_clearance_ideal_response_is_periodic_so_one_cycle_serves_every_recorded_cycle(config):
    """The sweep computes the ideal joints over one cycle and compares every recorded cycle with it: the ideal
    response two cycles on is the same (inverse dynamics at the later times, an independent evaluation)."""
    from linkwork.papers.clearance.fourbar import inverse_dynamics
    from linkwork.papers.clearance.adapter import parameters

    p = parameters(
        config["clearance"], config["sweeps"]["clearance"]["variant"], config["sweeps"]["clearance"]["scene"]
    )
    period = 2 * np.pi / p.crank_speed
    t = np.linspace(0.0, period, 73)
    first, later = inverse_dynamics(p, t, True), inverse_dynamics(p, t + 2 * period, True)
    for k in ("rocker_acceleration", "crank_torque", "force_A", "force_B"):
        assert np.allclose(later[k], first[k], rtol=1e-9, atol=1e-9 * np.ptp(first[k]))
