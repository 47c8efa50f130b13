"""The GN721 six-bar with a clearance at the sley pin E: the sley's acceleration around the front dead centre with and
without it, beside the four-bar's (a question the paper could not answer; every mass, the loom speed and the pin are
assumed and labelled in config ``beatup.sley_pin``).

The six-bar is written as a linkage description for the shared multibody engine: crank AB, coupler BC, rocker DC,
link CE and the sley (sword FE with its beam and reed, one rigid body turning about the rocking shaft F), ideal
revolutes at A, B, C (twice: coupler and link on the rocker), D and F, and at E either an ideal joint or the link's pin
in the sley's bushing with a dry clearance (contact and friction).  The crank turns at the loom speed in the paper's
sense (``sixbar.crank_sense``), from the front dead centre.  The dry scene is run turn by turn until its state is
found (``engines.states.settle``: the pin's eccentricity and its rate once a turn at the front dead centre); the
judged turns' sley acceleration is compared with the ideal six-bar's and with the four-bar's (its ideal kinematics
at the same loom speed, from its own front dead centre).  Its numerical error: the same state rerun from its section
point at a tighter tolerance.  SI units inside, degrees at the output boundary.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import xarray as xr

from ...configformat import labelled
from ...engines.kinematics import four_bar, solve_chain
from ...engines.multibody import assembly
from ...engines.multibody.linkage import Body, Clearance, Driver, Joint, Linkage
from ...engines.multibody.simulate import Run
from ...engines.states import settle
from ...units import rpm_to_rad_s
from .adapter import crank_sense, four_bar_beatup, six_bar
from .model import CRANK_SENSES, dead_centres

#: The bodies of the six-bar: (name, its two named points, the chain's point names, the chain link giving its angle).
BODIES = (
    ("crank", ("A", "B"), "A-B"), ("coupler", ("B", "C"), "B-C"), ("rocker", ("D", "C"), "D-C"),
    ("link", ("C", "E"), "C-E"), ("sley", ("F", "E"), "F-E"),
)


def _linkage(mech, sp: Mapping[str, Any], omega: float, front: float, pin: Clearance | None) -> Linkage:
    """The six-bar as a description, started at the crank angle ``front`` (rad) and driven at ``omega`` (rad/s)."""
    chain = mech.chain()
    m = solve_chain(chain, np.array([front]))
    lengths = {"crank": mech.l1, "coupler": mech.l2, "rocker": mech.l3, "link": mech.l5, "sley": mech.l6}
    masses = sp["masses_kg"]
    bodies = []
    for name, (p, q), link in BODIES:
        length = lengths[name]
        mass = labelled(masses[name])
        if name == "sley":  # its centre of mass on FE at the assumed distance from F, its assumed inertia there
            r = labelled(sp["sley_centre_of_mass_m"])
            points, inertia = {p: (-r, 0.0), q: (length - r, 0.0)}, labelled(sp["sley_inertia_kg_m2"])
        else:  # a slender steel link, centre of mass at mid-length
            points, inertia = {p: (-length / 2, 0.0), q: (length / 2, 0.0)}, mass * length**2 / 12
        bodies.append(Body(name, mass, inertia, points, float(m.links[link].angle[0])))
    ground = {k: tuple(v) for k, v in chain.ground.items()}
    joints = (Joint("A", ("crank", "A"), ("ground", "A")), Joint("B", ("crank", "B"), ("coupler", "B")),
              Joint("C", ("coupler", "C"), ("rocker", "C")), Joint("D", ("rocker", "D"), ("ground", "D")),
              Joint("C'", ("link", "C"), ("rocker", "C")), Joint("E", ("link", "E"), ("sley", "E"), pin),
              Joint("F", ("sley", "F"), ("ground", "F")))
    return Linkage(tuple(bodies), ground, joints, Driver("crank", omega, front), output="sley")


def _pin(sp: Mapping[str, Any]) -> Clearance:
    """The sley pin's clearance (contact and friction), from ``sley_pin.pin``."""
    p = sp["pin"]
    r = labelled(p["journal_radius_m"])
    return Clearance(
        r, r + labelled(p["radial_clearance_m"]), ("contact", "friction"), (p["youngs_modulus_Pa"],) * 2,
        (p["poisson"],) * 2, labelled(p["restitution"]), "lankarani-nikravesh", "hertz-sphere", labelled(p["friction"]),
        p["v0_m_s"], p["v1_m_s"], impact_velocity_floor=p["impact_velocity_floor_m_s"],
    )


def _turn_measures(acc: np.ndarray, ideal: np.ndarray, windows: list[np.ndarray]) -> np.ndarray:
    """Per turn: the largest |sley acceleration| within each window about the front dead centre, over the whole turn,
    and the RMS deviation from the ideal's (rad/s^2)."""
    return np.array(
        [*(np.abs(acc[w]).max() for w in windows), np.abs(acc).max(), np.sqrt(np.mean((acc[:-1] - ideal[:-1]) ** 2))]
    )


class _Turns:
    """Runs the dry scene turn by turn for ``engines.states.settle``; keeps each turn's run state and sley
    acceleration."""

    def __init__(self, linkage, gravity, integrator, ideal, windows, per, y0=None, memory=None):
        self.linkage, self.ideal, self.windows, self.per = linkage, ideal, windows, per
        self.run = Run(linkage, gravity, integrator, y0=y0, memory=memory)
        self.c = linkage.clearance_joints[0].clearance.clearance
        self.scale = np.array([1.0, 1.0, abs(linkage.driver.speed), abs(linkage.driver.speed)]) * self.c
        self.memories, self.turns, self.contact = [], [], []

    def step(self, n: int):
        points, measures = [], []
        for _ in range(n):
            self.memories.append(self.run.memory())
            points.append(assembly.journal_offsets(self.linkage, self.run.y)[0] / self.scale)
            t = self.run.t + np.arange(self.per + 1) * self.linkage.driver.period / self.per
            _, diags = self.run.advance(t)
            self.turns.append(diags[:, 0])
            self.contact.append((diags[:, 5].max(), diags[:, 7].max()))  # penetration, dry contact force
            measures.append(_turn_measures(diags[:, 0], self.ideal, self.windows))
        return np.array(points), np.array(measures)


def study(section: Mapping[str, Any]) -> xr.Dataset:
    """Rule study: the sley's acceleration with and without a clearance at the sley pin, beside the four-bar's."""
    sp = section["sley_pin"]
    mech = six_bar(section["sixbar"])
    sense = CRANK_SENSES[crank_sense(section["sixbar"])]
    omega = sense * rpm_to_rad_s(labelled(sp["loom_speed_rev_min"]))
    front = dead_centres(mech).front
    ideal_lk, pin_lk = _linkage(mech, sp, omega, front, None), _linkage(mech, sp, omega, front, _pin(sp))
    per = int(sp["points_per_turn"])
    t = np.arange(per + 1) * ideal_lk.driver.period / per
    from_front = np.degrees(np.abs(omega) * t)  # crank angle turned since the front dead centre, deg
    windows = [(from_front <= w) | (from_front >= 360.0 - w) for w in sp["windows_deg"]]
    ideal = assembly.inverse_dynamics(ideal_lk, t, sp["gravity"])["output_acceleration"]
    st = sp["states"]
    runner = _Turns(pin_lk, sp["gravity"], sp["integrator"], ideal, windows, per, y0=assembly.start_state(pin_lk))
    found = settle(
        runner.step, st["chunk_cycles"], st["max_cycles"], st["max_period"], st["section_tolerance"], st["periods"],
        st["min_cycles"], 0.95,
    )
    first, stop = found["window"]
    judged = np.array(runner.turns[max(first, stop - sp["kept_turns"]):stop])
    measures = found["measures"][first:stop]
    n_check = min(st["check_cycles"], stop - first)  # the first judged turns rerun at the check integrator
    check = _Turns(pin_lk, sp["gravity"], sp["check_integrator"], ideal, windows, per, memory=runner.memories[first])
    _, check_measures = check.step(n_check)
    numerical = np.abs(check_measures.mean(axis=0) - measures[:n_check].mean(axis=0))
    fb = four_bar_beatup(section["fourbar"])
    fb_front = _four_bar_front(fb)
    fb_acc = four_bar(fb.linkage(), fb_front + omega * t).rocker_accel * omega**2
    grid = np.linspace(0.0, 2 * np.pi, 36001)
    swings = np.array([dead_centres(mech).swing, np.ptp(fb.sword_angle(grid))])
    print(f"beatup_sley_pin: {found['status']} (period {found['period']}, transient {found['transient']} turns, "
          f"{len(runner.turns)} turns run)", flush=True)
    fixed = {"ideal": _turn_measures(ideal, ideal, windows), "fourbar": _turn_measures(fb_acc, ideal, windows)}
    judged_all = np.abs(np.array(runner.turns[first:stop]))
    turn_peak_at = {"ideal": from_front[np.argmax(np.abs(ideal))], "fourbar": from_front[np.argmax(np.abs(fb_acc))],
                    "pin": from_front[np.argmax(judged_all.max(axis=0))]}
    after = from_front <= 180.0  # the half turn after the front dead centre, and the one before it
    halves = [(judged_all[:, ~after].max(), from_front[~after][np.argmax(judged_all[:, ~after].max(axis=0))]),
              (judged_all[:, after].max(), from_front[after][np.argmax(judged_all[:, after].max(axis=0))])]
    turn_peak_at["halves"] = halves
    return _dataset(
        sp, from_front, ideal, judged, fb_acc, fixed, turn_peak_at, found, measures, numerical, runner, omega, n_check,
        swings,
    )


def _four_bar_front(fb) -> float:
    """The four-bar's front dead centre: the crank angle (rad) of the sword's largest angle (a fine scan)."""
    grid = np.linspace(0.0, 2 * np.pi, 36001)
    return float(grid[np.argmax(fb.sword_angle(grid))])


def _signed(angle_deg: float) -> float:
    """A crank angle turned since the front dead centre (deg, 0..360) as an angle about it (-180..180]."""
    return float(angle_deg - 360.0 if angle_deg > 180.0 else angle_deg)


def _dataset(
    sp, from_front, ideal, judged, fb_acc, fixed, turn_peak_at, found, measures, numerical, runner, omega, n_check,
    swings,
) -> xr.Dataset:
    pen, force = np.array(runner.contact).T
    first, stop = found["window"]
    nw = len(sp["windows_deg"])
    # one turn, ordered from half a turn before the front dead centre to half a turn after it (the end point dropped)
    about = np.where(from_front > 180.0, from_front - 360.0, from_front)[:-1]
    order = np.argsort(about, kind="stable")
    ideal, fb_acc, judged, about = ideal[:-1][order], fb_acc[:-1][order], judged[:, :-1][:, order], about[order]
    pin_mean = measures.mean(axis=0)
    window_peaks = np.array([fixed["ideal"][:nw], pin_mean[:nw], fixed["fourbar"][:nw]])
    turn_peaks = np.array([fixed["ideal"][nw], measures[:, nw].max(), fixed["fourbar"][nw]])
    mech = ("mechanism", "window")
    data = {
        "sley_acceleration_ideal": (
            "crank_angle", ideal,
            {"units": "rad/s^2", "long_name": "sley angular acceleration, six-bar with an ideal pin"},
        ),
        "sley_acceleration_pin": (
            ("judged_turn", "crank_angle"),
            judged,
            {
                "units": "rad/s^2",
                "long_name": (
                    "sley angular acceleration, six-bar with the clearance at the sley pin (the last judged turns)"
                ),
            },
        ),
        "sley_acceleration_fourbar": (
            "crank_angle",
            fb_acc,
            {
                "units": "rad/s^2",
                "long_name": (
                    "sword angular acceleration of the four-bar (ideal, the same loom speed, from its own front dead"
                    " centre)"
                ),
            },
        ),
        "peak_in_window": (
            mech,
            window_peaks,
            {
                "units": "rad/s^2",
                "long_name": (
                    "largest |sley angular acceleration| within the window of crank angle about the front dead centre"
                    " (clearance: mean over the judged turns)"
                ),
            },
        ),
        "pin_peak_in_window_low": (
            "window", measures[:, :nw].min(axis=0),
            {"units": "rad/s^2", "long_name": "clearance scene: the smallest of the judged turns' peaks in the window"},
        ),
        "pin_peak_in_window_high": (
            "window", measures[:, :nw].max(axis=0),
            {"units": "rad/s^2", "long_name": "clearance scene: the largest of the judged turns' peaks in the window"},
        ),
        "pin_peak_in_window_spread": (
            "window",
            measures[:, :nw].std(axis=0, ddof=1),
            {
                "units": "rad/s^2",
                "long_name": "clearance scene: standard deviation of the judged turns' peaks in the window",
            },
        ),
        "pin_peak_in_window_numerical_error": (
            "window",
            numerical[:nw],
            {
                "units": "rad/s^2",
                "long_name": (
                    "change of the clearance scene's mean peak over the first judged turns when they are rerun from"
                    " their section point at the check integrator"
                ),
            },
        ),
        "pin_over_ideal_in_window": (
            "window", window_peaks[1] / window_peaks[0],
            {"units": "1", "long_name": "the clearance scene's mean peak in the window over the ideal six-bar's"},
        ),
        "turn_peak": (
            "mechanism",
            turn_peaks,
            {
                "units": "rad/s^2",
                "long_name": (
                    "largest |sley angular acceleration| over the whole turn (clearance: the largest over the judged"
                    " turns)"
                ),
            },
        ),
        "turn_peak_at": (
            "mechanism", np.array([_signed(turn_peak_at[k]) for k in ("ideal", "pin", "fourbar")]),
            {"units": "deg", "long_name": "crank angle of that largest |acceleration| from the front dead centre"},
        ),
        "pin_half_turn_peak": (
            "half_turn",
            np.array([h[0] for h in turn_peak_at["halves"]]),
            {
                "units": "rad/s^2",
                "long_name": (
                    "clearance scene: the largest |sley angular acceleration| in the half turn before and after the"
                    " front dead centre, over the judged turns"
                ),
            },
        ),
        "pin_half_turn_peak_at": (
            "half_turn", np.array([_signed(h[1]) for h in turn_peak_at["halves"]]),
            {"units": "deg", "long_name": "crank angle of that largest |acceleration| from the front dead centre"},
        ),
        "pin_peak_by_turn": (
            ("turn_judged", "window"),
            measures[:, :nw],
            {
                "units": "rad/s^2",
                "long_name": "clearance scene: each judged turn's largest |sley angular acceleration| in the window",
            },
        ),
        "pin_turn_peak_by_turn": (
            "turn_judged",
            measures[:, nw],
            {
                "units": "rad/s^2",
                "long_name": (
                    "clearance scene: each judged turn's largest |sley angular acceleration| over the whole turn"
                ),
            },
        ),
        "swing": (
            "linkage", np.degrees(swings), {"units": "deg", "long_name": "sley (sword) swing between its dead centres"},
        ),
        "ideal_turn_peak_per_swing": (
            "linkage",
            np.array([turn_peaks[0], turn_peaks[2]]) / np.degrees(swings),
            {
                "units": "rad/s^2 per deg",
                "long_name": (
                    "largest |sley angular acceleration| of the ideal linkage over a turn, per degree of its swing"
                ),
            },
        ),
        "rms_deviation": (
            (),
            pin_mean[nw + 1],
            {
                "units": "rad/s^2",
                "long_name": (
                    "RMS deviation of the sley acceleration from the ideal six-bar's over a turn (mean over the judged"
                    " turns)"
                ),
            },
        ),
        "rms_numerical_error": (
            (),
            numerical[nw + 1],
            {
                "units": "rad/s^2",
                "long_name": "change of that RMS deviation at the check integrator (the first judged turns)",
            },
        ),
        "judged_turns": (
            (), int(measures.shape[0]), {"units": "1", "long_name": "turns the clearance scene is judged on"},
        ),
        "max_penetration": (
            (), float(pen[first:stop].max()),
            {"units": "m", "long_name": "largest penetration at the sley pin over the judged turns"},
        ),
        "max_contact_force": (
            (), float(force[first:stop].max()),
            {"units": "N", "long_name": "largest dry contact force at the sley pin over the judged turns"},
        ),
        "state_period": (
            (), int(found["period"]),
            {"units": "1", "long_name": "period of the settled state in turns (0: not periodic)"},
        ),
        "state_transient": ((), int(found["transient"]), {"units": "1", "long_name": "turns before the judged window"}),
        "turns_run": ((), len(runner.turns), {"units": "1", "long_name": "turns integrated"}),
        "check_turns": ((), int(n_check), {"units": "1", "long_name": "judged turns rerun at the check integrator"}),
    }
    coords = {
        "crank_angle": (
            "crank_angle", about,
            {"units": "deg", "long_name": "crank angle from the front dead centre (negative: before it)"},
        ),
        "judged_turn": (
            "judged_turn", np.arange(stop - judged.shape[0], stop),
            {"units": "1", "long_name": "turn from the start (the last judged turns)"},
        ),
        "mechanism": (
            "mechanism", ["six-bar, ideal pin", "six-bar, clearance at the sley pin", "four-bar"],
            {"units": "1", "long_name": "mechanism"},
        ),
        "window": (
            "window", np.asarray(sp["windows_deg"], dtype=float),
            {"units": "deg", "long_name": "half-width of the window of crank angle about the front dead centre"},
        ),
        "linkage": ("linkage", ["six-bar", "four-bar"], {"units": "1", "long_name": "beat-up linkage"}),
        "half_turn": (
            "half_turn", ["before the front dead centre", "after the front dead centre"],
            {"units": "1", "long_name": "half of the crank turn"},
        ),
        "turn_judged": (
            "turn_judged", np.arange(first, stop), {"units": "1", "long_name": "judged turn, from the start"},
        ),
    }
    attrs = {
        "state_status": str(found["status"]),
        "loom_speed_rad_s": abs(omega),
        "loom_speed_rev_min": labelled(sp["loom_speed_rev_min"]),
        "radial_clearance_m": labelled(sp["pin"]["radial_clearance_m"]),
        "integrator": str(sp["integrator"]),
        "check_integrator": str(sp["check_integrator"]),
    }
    return xr.Dataset(data, coords=coords, attrs=attrs)
