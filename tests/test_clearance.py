"""Clearance multibody engine: independent routes, effects that cost nothing, hard cases, bad input."""

import copy
from dataclasses import replace

import numpy as np
import pytest

from conftest import load_yaml
from linkwork.engines.multibody.kernels import film_forces, friction_coefficient
from linkwork.engines.multibody.model import generate_source
from linkwork.papers.clearance.fourbar import initial_state, integrate, inverse_dynamics, linkage
from linkwork.papers.clearance.adapter import parameters
from linkwork.papers.clearance.studies import scene as scene_dataset

SECTION = load_yaml("config/config.yaml")["clearance"]
SLENDER = parameters(
    {
        **SECTION,
        "scenes": {"all": {"clearance_joints": [1, 2], "effects": ["contact", "friction", "lubrication", "gravity"]}},
    },
    "slender",
    "all",
)
EXPLICIT = SECTION["integrators"]["explicit"]
STIFF = SECTION["integrators"]["stiff"]
DRIFT_BOUND = 1e-6  # m


#: The pipeline's dry and lubricated scenes' effects (config clearance.scenes): a test that needs no other set uses
#: these, so that its scene is one the workflow compiles too (a scene of its own costs a compile of its own).
DRY = tuple(SECTION["scenes"]["dry_both"]["effects"])
LUBRICATED = tuple(SECTION["scenes"]["lubricated_both"]["effects"])


def run(p, joints, effects, cycles=2.0, integ=EXPLICIT, y0=None, points=720):
    t = np.linspace(0.0, cycles * 2 * np.pi / p.crank_speed, int(cycles * points) + 1)
    ys, diags, steps, rejected, counts, _ = integrate(p, joints, effects, t, integ, y0=y0)
    assert np.all(np.isfinite(diags)), "NaN or inf in the response"
    assert diags[:, 3].max() < DRIFT_BOUND, f"constraint drift {diags[:, 3].max():.2e} m"
    return t, ys, diags, counts


def test_forward_integration_of_the_ideal_linkage_equals_inverse_dynamics():
    t, ys, diags, _ = run(SLENDER, (), ("gravity",), cycles=1.0, integ={"method": "rk4", "step_s": 1e-5})
    ideal = inverse_dynamics(SLENDER, t, gravity=True)
    scale = np.abs(ideal["rocker_acceleration"]).max()
    assert np.abs(diags[:, 0] - ideal["rocker_acceleration"]).max() < 1e-6 * scale
    assert np.abs(diags[:, 1] - ideal["crank_torque"]).max() < 1e-6 * np.abs(ideal["crank_torque"]).max()


def test_inverse_dynamics_equals_the_closed_form_four_bar_route():
    """The engine's inverse dynamics (Newton's method on the description's constraints, stacked solves) against an
    independent route: the four-bar's closed-form kinematics (engines.kinematics.four_bar) and a solve per instant of
    the constraint rows the compiled scenes' own kernels assemble, with gravity; to 1e-9 of each response's range."""
    from linkwork.engines.kinematics import four_bar
    from linkwork.engines.multibody.kernels import body_trig, driver, revolute
    from linkwork.papers.clearance.fourbar import start_angle

    p = SLENDER
    t = np.linspace(0.0, 3 * np.pi / p.crank_speed, 55)
    ideal = inverse_dynamics(p, t, gravity=True)
    phi0 = start_angle(p)
    m = four_bar(p.four_bar(), phi0 + p.crank_speed * t)
    w, (l2, l3, l4) = p.crank_speed, p.lengths
    ang = np.stack([m.crank_angle, m.coupler_angle, m.rocker_angle], axis=-1)
    rate = np.stack([np.ones_like(t), m.coupler_rate, m.rocker_rate], axis=-1) * w
    acc = np.stack([np.zeros_like(t), m.coupler_accel, m.rocker_accel], axis=-1) * w**2
    mass = np.repeat(np.array(p.masses), 3)
    mass[2::3] = p.inertias
    g = np.zeros(9)
    g[1::3] -= mass[0::3] * p.gravity
    torque, rocker = np.empty(t.size), np.empty(t.size)
    for i in range(t.size):
        e = np.stack([np.cos(ang[i]), np.sin(ang[i])], axis=-1)
        perp = np.stack([-e[:, 1], e[:, 0]], axis=-1)
        starts = [np.zeros(2), l2 * e[0], np.array([p.ground, 0.0])]
        start_acc = [np.zeros(2), -l2 * w**2 * e[0], np.zeros(2)]
        q, qd, qdd = np.empty(9), np.empty(9), np.empty(9)
        for b, half in enumerate((l2 / 2, l3 / 2, l4 / 2)):
            start_vel = l2 * w * perp[0] if b == 1 else np.zeros(2)
            q[3 * b : 3 * b + 2], q[3 * b + 2] = starts[b] + half * e[b], ang[i, b]
            qd[3 * b : 3 * b + 2], qd[3 * b + 2] = start_vel + half * rate[i, b] * perp[b], rate[i, b]
            qdd[3 * b : 3 * b + 2] = start_acc[b] + half * (acc[i, b] * perp[b] - rate[i, b] ** 2 * e[b])
            qdd[3 * b + 2] = acc[i, b]
        phi, phiq, gamma, phidot, cs = np.zeros(9), np.zeros((9, 9)), np.zeros(9), np.zeros(9), np.empty(6)
        body_trig(q, cs)
        revolute(q, qd, cs, 0, -0.5 * l2, 0.0, -1, 0.0, 0.0, 0.0, 0.0, 0, phi, phiq, gamma, phidot)
        driver(q, qd, t[i], 0, phi0, w, 2, phi, phiq, gamma, phidot)
        revolute(q, qd, cs, 2, -0.5 * l4, 0.0, -1, 0.0, 0.0, p.ground, 0.0, 3, phi, phiq, gamma, phidot)
        revolute(q, qd, cs, 0, 0.5 * l2, 0.0, 1, -0.5 * l3, 0.0, 0.0, 0.0, 5, phi, phiq, gamma, phidot)
        revolute(q, qd, cs, 1, 0.5 * l3, 0.0, 2, 0.5 * l4, 0.0, 0.0, 0.0, 7, phi, phiq, gamma, phidot)
        torque[i] = -np.linalg.solve(phiq.T, g - mass * qdd)[2]
        rocker[i] = qdd[8]
    for ours, theirs in ((ideal["crank_torque"], torque), (ideal["rocker_acceleration"], rocker)):
        assert np.abs(ours - theirs).max() < 1e-9 * np.abs(theirs).max()


def test_the_engines_assembly_gives_the_papers_starts_to_rounding():
    """The paper's starts (closed-form kinematics at the dead point; Newton's method on the four-bar's own nine
    equations with complex-step Jacobians for the off-centre start) against the engine's assembly from the linkage
    description (Newton's method on the generic constraints): equal to 1e-13 of the state's scale, centred and
    off-centre, for each set of clearance joints."""
    from linkwork.engines.multibody import assembly
    from linkwork.papers.clearance.fourbar import JOINT_NAMES, offset_start

    p = SLENDER
    scale = np.abs(initial_state(p)).max()
    assert np.abs(initial_state(p) - assembly.start_state(linkage(p))).max() < 1e-13 * scale
    ecc, rate = np.array([0.6, -0.6]) * p.clearance, np.array([0.5, 0.5]) * p.clearance * p.crank_speed
    for joints in ((1,), (2,), (1, 2)):
        names = [JOINT_NAMES[j] for j in joints]
        ours = assembly.start_state(
            linkage(p, joints, ("contact",)), dict.fromkeys(names, tuple(ecc)), dict.fromkeys(names, tuple(rate))
        )
        assert np.abs(offset_start(p, joints, ecc, rate) - ours).max() < 1e-13 * scale


def test_the_dop853_tableau_held_as_data_is_scipys_to_the_bit():
    from scipy.integrate._ivp import dop853_coefficients as scipy_table

    from linkwork.engines.multibody import integrators as ours

    for name in ("A", "B", "C", "E3", "E5", "D"):
        theirs = np.asarray(getattr(scipy_table, name), dtype=float)
        mine = getattr(ours, f"D853_{name}")
        assert mine.shape == theirs.shape and np.array_equal(mine, theirs), name


def test_an_effect_left_out_is_never_evaluated():
    """Each effect's counter (contact, friction, lubrication, gravity) stays at zero in a scene that leaves the effect
    out, and counts in one that names it (scenes the pipeline and the energy tests compile too)."""
    _, _, _, dry = run(SLENDER, (1, 2), DRY, cycles=0.5)
    assert dry[2] == 0 and dry[0] > 0 and dry[1] > 0 and dry[3] > 0  # no lubrication evaluation in a dry scene
    _, _, _, bare = run(SLENDER, (1, 2), ("contact",), cycles=0.5)
    assert bare[0] > 0 and bare[1] == 0 and bare[2] == 0 and bare[3] == 0  # no friction, lubrication or gravity
    _, _, _, lub = run(SLENDER, (2,), LUBRICATED, cycles=0.5, integ=STIFF)
    assert lub[2] > 0
    src = generate_source(linkage(SLENDER, (1,), ("contact",)), gravity=False)
    assert "film_forces(" not in src and "friction_coefficient(" not in src.split("def rhs")[1]


def _quick(section, max_cycles=10):
    """A section whose scenes run one start, at most ``max_cycles`` cycles and short checks (the tests' size)."""
    out = copy.deepcopy(section)
    out["states"] = {
        **out["states"],
        "starts": out["states"]["starts"][:1],
        "max_cycles": max_cycles,
        "check_cycles": 2,
    }
    return out


def test_scene_dataset_records_units_and_counts():
    ds = scene_dataset(_quick(SECTION), "slender", "dry_2")
    assert ds.attrs["evaluations_lubrication"] == 0 and ds.attrs["evaluations_contact"] > 0
    assert np.isnan(ds.penetration.sel(joint=1)).all() and np.isfinite(ds.penetration.sel(joint=2)).all()


def test_contact_laws_are_pluggable():
    """Every contact law runs in the one compiled scene of its topology and effects (the law is data, not generated
    code: here the pipeline's dry scene at joint 2), and each law's hysteresis gives its own contact forces."""
    from linkwork.papers.clearance.fourbar import run as start_run

    effects, modules, peaks = DRY, set(), {}
    for law in ("lankarani-nikravesh", "hunt-crossley", "flores"):
        p = replace(SLENDER, contact_law=law)
        _, _, diags, counts = run(p, (2,), effects, cycles=0.5)
        assert counts[0] > 0, law  # the journal met its bearing
        modules.add(start_run(p, (2,), effects, EXPLICIT).module.__name__)
        peaks[law] = float(diags[:, 7].max())  # the joint's dry normal force (N)
    assert len(modules) == 1, modules
    assert len(set(peaks.values())) == 3, peaks


def _energy_balance(p, effects):
    """(mechanical energy - driver work) over a run, with the journals starting centred."""
    _, ys, diags, _ = run(p, (1, 2), effects, cycles=1.0, integ={**EXPLICIT, "rtol": 1e-9, "atol": 1e-12})
    return diags[:, 2] - ys[:, 18]


# --- hard cases ----------------------------------------------------------------------------------


@pytest.mark.hard
@pytest.mark.parametrize("clearance", [1e-6, 1e-3])
def test_clearance_1_micron_and_1_mm(clearance):
    p = replace(SLENDER, journal_radius=SLENDER.bearing_radius - clearance, e0=0.05 * clearance)
    _, _, diags, _ = run(p, (1, 2), ("contact", "friction", "gravity"), cycles=1.0)
    assert np.nanmax(diags[:, [5, 11]]) < 2 * clearance + 1e-4  # penetration stays bounded


@pytest.mark.hard
def test_crank_speed_times_ten():
    run(replace(SLENDER, crank_speed=10 * SLENDER.crank_speed), (1, 2), ("contact", "friction", "gravity"), cycles=0.5)


@pytest.mark.hard
def test_restitution_one_does_not_create_energy():
    """Elastic impacts (c_e = 1, no friction, no gravity): energy minus driver work must not grow."""
    balance = _energy_balance(replace(SLENDER, restitution=1.0), ("contact",))
    scale = np.abs(balance).max()
    assert balance.max() - balance[0] < 1e-3 * scale


@pytest.mark.hard
def test_restitution_0_3_dissipates():
    balance = _energy_balance(replace(SLENDER, restitution=0.3), ("contact",))
    assert balance[-1] < balance[0]


@pytest.mark.hard
def test_lubrication_driven_to_eps_one():
    """A film far too thin to hold the journal: eps reaches 1, the film stays bounded, contact takes over."""
    p = replace(SLENDER, viscosity=1e-4)
    _, _, diags, _ = run(p, (1, 2), LUBRICATED, cycles=0.5, integ=STIFF)
    assert np.nanmax(diags[:, 4]) >= p.clearance  # e reached c
    f_r, f_t = film_forces(0.9999999, 1.0, 10.0, 1.0, p.film_coefficient, 1.0 - p.e0 / p.clearance)
    assert np.isfinite(f_r) and np.isfinite(f_t)
    assert np.isfinite(film_forces(2.0, -1.0, 10.0, 1.0, p.film_coefficient, 0.95)).all()


@pytest.mark.hard
def test_friction_at_zero_slip():
    assert friction_coefficient(0.0, 0.1, 1e-4, 1e-3) == 0.0
    assert friction_coefficient(-0.0, 0.1, 0.0, 1e-3) == 0.0
    run(replace(SLENDER, friction=0.3, v0=0.0), (2,), DRY, cycles=0.5)


@pytest.mark.hard
def test_journal_starting_in_contact():
    """Rotate the coupler about B (its ideal joint with the rocker) until the bushing at A touches the journal."""
    y0 = initial_state(SLENDER)
    l3 = SLENDER.lengths[1]
    x3, y3, phi3 = y0[3:6]
    bx, by = x3 + 0.5 * l3 * np.cos(phi3), y3 + 0.5 * l3 * np.sin(phi3)
    dphi = 1.02 * SLENDER.clearance / l3
    phi_new = phi3 + dphi
    y0[3], y0[4], y0[5] = bx - 0.5 * l3 * np.cos(phi_new), by - 0.5 * l3 * np.sin(phi_new), phi_new
    _, _, diags, _ = run(SLENDER, (1,), DRY, cycles=0.5, y0=y0)
    assert diags[0, 5] > 0  # joint 1 starts in contact (penetration > 0)


# --- bad input -----------------------------------------------------------------------------------


from conftest import expect_config_error as _expect  # noqa: E402


def test_bad_clearance_input(config, schema):
    c = copy.deepcopy(config)
    c["clearance"]["joints"]["journal_radius_m"] = 0.010
    _expect(c, schema, "clearance.joints.journal_radius_m", "0.01", "clearance must be > 0")
    c = copy.deepcopy(config)
    c["clearance"]["scenes"]["dry_1"]["effects"] = ["contact", "magnetism"]
    _expect(c, schema, "clearance.scenes.dry_1.effects.1", "'magnetism'")
    c = copy.deepcopy(config)
    del c["clearance"]["joints"]["viscosity_Pa_s"]
    _expect(c, schema, "clearance.scenes.lubricated_1.effects", "lubrication", "viscosity_Pa_s")


def test_claimed_order_of_the_dry_scenes():
    from linkwork.papers.clearance.studies import order_as_claimed

    # values: dry_1, dry_2, dry_both (then the lubricated ones, ignored)
    assert order_as_claimed(np.array([1.0, 2.0, 3.0, 0, 0, 0]), "rocker_acceleration")
    assert not order_as_claimed(np.array([2.0, 1.0, 3.0]), "rocker_acceleration")
    assert order_as_claimed(np.array([2.0, 1.0, 3.0]), "crank_torque")
    assert not order_as_claimed(np.array([2.0, 1.0, 1.5]), "crank_torque")  # both joints not the largest


def test_small_linear_solve_equals_lapack():
    """The Schur-complement solve (pivoted Gaussian elimination, compiled) against numpy's LAPACK."""
    from linkwork.engines.multibody.kernels import gauss_solve_into

    rng = np.random.default_rng(7)
    for n in (1, 3, 9):
        a = rng.normal(size=(n, n)) + np.diag(rng.uniform(0.1, 1.0, n))
        a[[0, -1]] = a[[-1, 0]]  # needs pivoting
        b = rng.normal(size=n)
        x = np.empty(n)
        gauss_solve_into(a.copy(), b.copy(), x)
        assert np.allclose(x, np.linalg.solve(a, b), rtol=1e-10, atol=1e-12)


def test_sparse_schur_source_solves_the_saddle_point_system():
    """The generated Schur-complement lines (only Phi_q's nonzero products, each symmetric pair once) against numpy's
    LAPACK on the whole saddle-point system [[M, Phi_q^T], [Phi_q, 0]] [q''; lam] = [g; gamma_b], for the constraint
    patterns of the four-bar's scenes (no, one or two ideal joints), with random entries on each pattern."""
    from linkwork.engines.multibody.kernels import gauss_solve_into
    from linkwork.engines.multibody.model import revolute_pattern, schur_source

    rng = np.random.default_rng(11)
    base = [*revolute_pattern(0, -1), [2], *revolute_pattern(2, -1)]
    for extra in ([], revolute_pattern(1, 2), revolute_pattern(0, 1) + revolute_pattern(1, 2)):
        pattern = base + extra
        nc = len(pattern)
        phiq = np.zeros((nc, 9))
        for r, cols in enumerate(pattern):
            phiq[r, cols] = rng.normal(size=len(cols)) + np.where(rng.random(len(cols)) < 0.5, 1.0, -1.0)
        mass, g, gamma_b = rng.uniform(0.1, 2.0, 9), rng.normal(size=9), rng.normal(size=nc)
        scope = {
            "phiq": phiq,
            "mass": mass,
            "g": g,
            "gamma_b": gamma_b,
            "schur": np.zeros((nc, nc)),
            "schur_rhs": np.zeros(nc),
            "lam": np.zeros(nc),
            "qdd": np.zeros(9),
            "gauss_solve_into": gauss_solve_into,
        }
        exec("\n".join(line[4:] for line in schur_source(pattern, 9)), scope)
        kkt = np.block([[np.diag(mass), phiq.T], [phiq, np.zeros((nc, nc))]])
        expected = np.linalg.solve(kkt, np.r_[g, gamma_b])
        assert np.allclose(scope["qdd"], expected[:9], rtol=1e-10, atol=1e-12)
        assert np.allclose(scope["lam"], expected[9:], rtol=1e-10, atol=1e-12)


def test_validity_measures_against_hand_values():
    from linkwork.engines.multibody import validity

    c = 5e-5
    pen = np.array([[np.nan] * 4, [-1e-5, 0.0, 2e-5, 1e-4]])  # joint 1 without clearance, joint 2 down to 2 c
    assert validity.penetration_ratio(pen, c) == pytest.approx(2.0)
    assert np.isnan(validity.penetration_ratio(np.full((2, 3), np.nan), c))
    ecc = np.array([[4e-5, 4.9e-5, 1e-5, np.nan], [0.0, 0.0, 4.8e-5, 1e-5]])  # |e|/c: 0.8, 0.98 | 0.96
    assert validity.beyond_cap_fraction(ecc, c, cap=0.95) == pytest.approx(0.5)
    assert validity.warnings(0.05, 0.0, 0.0635) == ""
    assert (
        "outside its contact law" in validity.warnings(2.0, None, 0.0635)
        and validity.warnings(2.0, None, float("inf")) == ""
    )
    assert "beyond the film cap during 50 %" in validity.warnings(0.05, 0.5, 0.0635)
    # the sphere law's limit: the rigid overlap's contact half-angle at which parabolic profiles err by 1 %
    assert validity.penetration_limit("hertz-sphere", 0.00995, 0.01) == pytest.approx(0.0635, abs=5e-4)
    assert validity.penetration_limit("pereira", 0.00995, 0.01) == float("inf")


def test_crank_speed_times_hundred_is_flagged_outside_hertz():
    """Real run of the issue's case: crank speed x100 drives the dry journals far into their bushings; the scene
    records the depth and warns (it used to be written as a plain success)."""
    section = _quick(SECTION)
    section["crank_speed_rad_s"] *= 100
    section["numerics"] = {**section["numerics"], "record_cycles": 1, "points_per_cycle": 720}
    ds = scene_dataset(section, "slender", "dry_both")
    assert ds.attrs["validity_penetration_over_clearance"] > ds.attrs["validity_penetration_limit"]
    assert "outside its contact law" in ds.attrs["validity_warnings"]
    nominal = scene_dataset({**_quick(SECTION), "numerics": section["numerics"]}, "slender", "lubricated_1")
    assert nominal.attrs["validity_warnings"] == "" and nominal.attrs["validity_beyond_film_cap_fraction"] == 0.0


@pytest.mark.parametrize("method", ["rk45", "scipy-dop853", "lsoda", "dop853"])
def test_scipys_integrators_on_the_compiled_right_hand_side_agree_with_dormand_prince(method):
    """Second route for the scipy path added for the side-by-side study and for the compiled DOP853: on the ideal
    linkage, forward integration by each integrator around the compiled right-hand side equals inverse dynamics."""
    integ = {"method": method, "rtol": 1e-10, "atol": 1e-13, "first_step_s": 1e-6, "max_step_s": 1e-3}
    t, _, diags, _ = run(SLENDER, (), ("gravity",), cycles=0.5, integ=integ)
    ideal = inverse_dynamics(SLENDER, t, gravity=True)
    scale = np.abs(ideal["rocker_acceleration"]).max()
    assert np.abs(diags[:, 0] - ideal["rocker_acceleration"]).max() < 1e-5 * scale


# --- statistics of the claims (issue 12) ---------------------------------------------------------


def test_batch_means_interval_against_the_t_distribution():
    """Batch size 1 is the textbook t-interval (closed form); over many normal samples the 95 % interval
    covers the true mean in 95 % +- 1.5 % of the cases, for batch sizes 1 and 4."""
    from scipy import stats as st

    from linkwork.papers.clearance.statistics import mean_ci

    x = np.array([1.0, 2.0, 4.0, 7.0])
    mean, half, se, dof = mean_ci(x, 1, 0.95)
    assert mean == pytest.approx(3.5) and dof == 3
    assert half == pytest.approx(st.t.ppf(0.975, 3) * x.std(ddof=1) / 2.0)
    rng = np.random.default_rng(12)
    for batch in (1, 4):
        covered = [abs((m := mean_ci(rng.normal(5.0, 2.0, 20), batch, 0.95))[0] - 5.0) <= m[1] for _ in range(4000)]
        assert np.mean(covered) == pytest.approx(0.95, abs=0.015)
    assert mean_ci(np.ones(3), 4, 0.95)[1] == np.inf  # fewer than two batches: no interval


def test_an_ordering_is_decided_only_beyond_both_margins():
    from linkwork.papers.clearance.statistics import FAILS, HOLDS, UNDETERMINED, conjunction, decide, difference

    assert decide(2.0, 1.0, 1.5) == HOLDS
    assert decide(-2.0, 1.0, 1.5) == FAILS
    assert decide(2.0, 2.5, 1.0) == UNDETERMINED  # within the statistical margin
    assert decide(2.0, 1.0, 2.5) == UNDETERMINED  # within the numerical error
    assert conjunction([HOLDS, HOLDS]) == HOLDS and conjunction([HOLDS, UNDETERMINED]) == UNDETERMINED
    assert conjunction([UNDETERMINED, FAILS]) == FAILS
    # Welch: two means with equal standard errors and dof -> sqrt(2) se, dof 2(n - 1)
    from scipy import stats as st

    d, half, num = difference([(1.0, 10.0, 1.0, 4.0, 0.5), (-1.0, 7.0, 1.0, 4.0, 0.25)], 0.95)
    assert d == 3.0 and num == 0.75 and half == pytest.approx(st.t.ppf(0.975, 8.0) * np.sqrt(2.0))
    assert difference([(1.0, 1.0, np.inf, 1.0, 0.0), (-1.0, 0.0, 0.1, 4.0, 0.0)], 0.95)[1] == np.inf  # unsettled scene
    from linkwork.papers.clearance.statistics import _t_quantile

    for dof in (1.0, 2.5, 7.3, 40.0):  # scipy.special's inverse t against scipy.stats (real Welch dof included)
        assert _t_quantile(0.95, dof) == pytest.approx(st.t.ppf(0.975, dof), rel=1e-12)


def test_gap_and_penetration_are_named_by_their_sign():
    from linkwork.engines.multibody import validity
    from linkwork.engines.multibody.validity import contact_extent

    assert contact_extent(0.73) == ("max penetration / c", 0.73)
    assert contact_extent(-0.12) == ("min gap / c", 0.12)
    assert contact_extent(0.0)[0] == "max penetration / c"
    attrs = validity.attributes(np.array([[-2e-5, -1e-5]]), np.array([[3e-5, 4e-5]]), 5e-5, None, 0.0635)
    assert (attrs["validity_contact_label"], attrs["validity_contact_value"]) == ("min gap / c", pytest.approx(0.2))


def test_validity_exit_numbers_are_in_the_findings():
    """physics() on a hand-made claims set: penetration, torque, film cap, where friction acted in a lubricated scene,
    and an effect evaluated in a scene that does not name it, come out as computed."""
    import xarray as xr

    from linkwork.papers.clearance.findings import physics
    from linkwork.papers.clearance.studies import COMPARED, QUANTITIES

    runs = ["ideal", *COMPARED]
    def per_run(values):
        return (("variant", "run"), np.array([values]))
    pen = np.full((1, len(runs), 2), np.nan)
    pen[0, 1:4, 1] = [1.2, 1.5, 0.9]  # dry scenes, joint 2
    ecc = np.full_like(pen, np.nan)
    ecc[0, 4:, 1] = [0.9, 0.98, 0.97]
    force = np.zeros_like(pen)
    force[0, 5, 1] = 1000.0  # lubricated_2 touches with 1 kN
    claims = xr.Dataset(
        {
            "summary_max_penetration_ratio": (("variant", "run", "joint"), pen),
            "summary_max_eccentricity_ratio": (("variant", "run", "joint"), ecc),
            "summary_max_contact_force": (("variant", "run", "joint"), force),
            "summary_film_cap": per_run([np.nan] * 4 + [0.95] * 3),
            "summary_max_abs_torque": per_run([100.0, 1.0e4, 1.5e4, 2.0e3, 1.0, 1.0, 1.0]),
            "summary_n_lubrication": per_run([0.0] * 7),
            "summary_n_friction": per_run([0.0, 5.0, 5.0, 5.0, 0.0, 7.0, 0.0]),  # friction acted in lubricated_2
            "mean_deviation": (("variant", "measure", "quantity", "scene"), np.full((1, 2, 2, 6), 10.0)),
        },
        coords={
            "variant": ["decoded"],
            "run": runs,
            "joint": [1, 2],
            "measure": ["rms", "peak"],
            "quantity": list(QUANTITIES),
            "scene": list(COMPARED),
        },
        attrs={"crank_mass_kg": 1.0},
    )
    scenes = load_yaml("config/config.yaml")["clearance"]["scenes"]
    joints = load_yaml("config/config.yaml")["clearance"]["joints"]
    f = physics(claims, {"scenes": scenes, "joints": joints}).sel(variant="decoded")
    assert float(f.dry_penetration_max) == 1.5 and float(f.dry_torque_max) == 1.5e4 and float(f.crank_mass) == 1.0
    assert float(f.lubricated_2_eccentricity_max) == 0.98 and int(f.beyond_film_cap) == 1
    assert f.lubricated_friction_evaluations.values.tolist() == [0.0, 7.0, 0.0] and float(f.stray_evaluations) == 0.0
    # the same counts where the lubricated scenes named no friction: those 7 evaluations are stray
    no_friction = {
        k: {**v, "effects": [e for e in v["effects"] if e != "friction" or k.startswith("dry")]}
        for k, v in scenes.items()
    }
    assert (
        float(physics(claims, {"scenes": no_friction, "joints": joints}).sel(variant="decoded").stray_evaluations)
        == 7.0
    )


def test_the_repeated_ideal_cycle_equals_inverse_dynamics_over_three_cycles():
    """The scenes repeat one cycle of the ideal response; inverse dynamics over the whole span must agree."""
    from linkwork.papers.clearance.studies import cycle, periodic_ideal

    per = 90
    t = np.arange(3 * per + 1) * cycle(SLENDER) / per
    whole = inverse_dynamics(SLENDER, t, gravity=True)
    tiled = periodic_ideal(SLENDER, per, 3, True)
    for key in ("rocker_acceleration", "crank_torque", "energy"):
        assert np.abs(tiled[key] - whole[key]).max() < 1e-9 * np.abs(whole[key]).max()


def test_an_undetermined_ordering_names_the_margin_that_decides_it():
    from linkwork.papers.clearance.studies import claim_reason, undecided_reason

    assert undecided_reason(1.0, 2.0, 0.5, []) == "statistical margin"
    assert undecided_reason(1.0, 0.5, 2.0, []) == "numerical error"
    assert (
        undecided_reason(1.0, float("inf"), 0.1, ["dry_both"]) == "statistics (not settled / not stationary: dry_both)"
    )
    assert (
        claim_reason(["", "numerical error", "statistical margin", "numerical error"])
        == "numerical error; statistical margin"
    )


def test_the_ripple_sentence_says_what_decides_claim_3s_second_part():
    """ripples_text on hand-made findings: where the first part holds and the ripple orderings are undetermined, the
    sentence gives the check reruns' change (read, not typed), the convergence term and the whole bar where the term is
    the larger, which side of joint 1's joint 2's ripple lies at the tightest tolerance and how far it still moves, the
    ripples' size against the ideal, and the cutoffs that decide;
    where the ripple orderings fail decidedly, it says they are not larger; no sentence where the ripple part holds."""
    import xarray as xr

    from linkwork.papers.clearance.findings import ripples_text
    from prose import leaks

    vs = ("variant", "start")
    findings = xr.Dataset(
        {
            "claim3_close_holds": (vs, [[1, 1], [1, 1]]),
            "claim3_ripples_outcome": (vs, [[-1, -1], [-1, -1]]),
            "ripple_check_ratio": (vs, [[0.86, 0.8], [0.96, 0.9]]),
            "ripple_convergence_ratio": (vs, [[37.0, 1.0], [0.01, 0.0]]),
            "ripple_error_ratio": (vs, [[38.0, 2.0], [0.97, 1.0]]),
            "ripple_tight_above": (vs, [[1, 1], [0, 0]]),
            "ripple_tight_joint_1": (vs, [[3.6e-5, 4e-5], [0.002, 0.0018]]),
            "ripple_tight_joint_2": (vs, [[7e-4, 8e-4], [6e-4, 1e-3]]),
            "ripple_tight_change": (vs, [[0.54, 0.5], [0.38, 0.4]]),
            "ripple_tight_change_joint_1": (vs, [[0.33, 0.3], [1.0, 1.01]]),
            "ripple_over_ideal": ("variant", [3.7e-6, 6.3e-6]),
            "lubricated_deviation_over_ideal": ("variant", [0.0031, 0.00052]),
            "ripple_cutoff_holds": (("variant", "ripple_cutoff"), [[0, 1, 1], [1, 1, 1]]),
        },
        coords={"variant": ["decoded", "slender"], "start": ["a", "b"], "ripple_cutoff": [150.0, 500.0, 2000.0]},
    )
    text = ripples_text(findings)
    for part in (
        "is undetermined", "0.86 (decoded) and 0.96 (slender)", "is 37 times it, and the error bar 38 times",
        "above joint 1's in decoded (0.0007 against 3.6e-05", "below joint 1's in slender (0.0006 against 0.002",
        "factors of 0.54 and 0.33", "points against the ordering", "3.7e-06 (decoded) and 6.3e-06 (slender)",
        "holds at 500, 2000 Hz and not at 150 Hz",
    ):
        assert part in text, (part, text)
    assert "slender (each" not in text and not leaks(text)
    assert "are not larger than at joint 1" in ripples_text(
        findings.assign(claim3_ripples_outcome=(vs, [[0, 0], [0, 0]]))
    )
    assert ripples_text(findings.assign(claim3_ripples_outcome=(vs, [[1, 1], [1, 1]]))) == ""


def test_the_contact_memory_decides_only_a_claim_that_holds_from_one_start_and_fails_from_the_other():
    """``memory_causes``: where the memory swap explains the starts' states, a claim holding decidedly from one start
    and failing decidedly from the other is told to the classifier as decided by the paper's model (the memory), and
    the classifier classes every row of it so; one undetermined from a start and failing from the other is not (no
    start shows it holding)."""
    import pandas as pd
    import xarray as xr

    from linkwork.papers.clearance.findings import (
        MEMORY_DECIDES, NOMINAL_ONLY, NOT_PROPAGATED, memory_causes, nominal_only,
    )
    from linkwork.pipeline.compare import compare

    claims = xr.Dataset({"outcome_by_start": (("variant", "start", "claim"), np.array([[[0, -1], [1, 0]]]))},
                        coords={"variant": ["decoded"], "start": ["centred", "off-centre"], "claim": ["c1", "c2"]})
    phys = xr.Dataset(
        {"memory_explains": (("variant", "scene"), np.array([[1, 1]]))},
        coords={"variant": ["decoded"], "scene": ["dry_1", "dry_2"]},
    )
    table = pd.DataFrame(
        {
            "model": ["decoded"] * 4,
            "scenario": ["start centred", "start centred", "start off-centre", "start off-centre"],
            "id": ["c1", "c2", "c1", "c2"],
            "verdict": ["differs", "undetermined by our numerics", "reproduced", "differs"],
            "decided_by": ["", "numerical error", "", ""],
            "input_low": [0.0, 0.0, np.nan, np.nan],
        }
    )
    causes = memory_causes(claims, phys)
    from linkwork.papers.clearance.findings import memory_explains

    own = np.array([[[100.0, 150.0], [100.0, 100.5]]])  # one variant, two scenes: starts 50 apart, and 0.5 apart
    assert memory_explains(own, np.array([[[100.4, 149.0], [100.0, 100.5]]])).tolist() == [[1, 1]]  # swaps land
    assert memory_explains(own, np.array([[[140.0, 150.0], [100.5, 100.0]]])).tolist() == [[0, 0]]  # swaps stay
    assert causes == {"decoded": {"model_decides": {"c1": MEMORY_DECIDES}}}
    published = {"quantities": [
        {"id": c, "quantity": c, "value": 1, "unit": "1", "where": "", "relation": "ge", "tolerance": {"abs": 0},
         "measure": {"variable": c, "reduce": "value"}} for c in ("c1", "c2")
    ]}
    ds = xr.Dataset({"c1": ((), 0.0), "c2": ((), 0.0)})
    rows = compare(published, ds, model="decoded", causes=causes["decoded"]).set_index("id")
    assert rows.verdict["c1"] == "decided by the paper's model" and rows.decided_by["c1"] == MEMORY_DECIDES
    assert rows.verdict["c2"] == "differs"  # the classifier's own class where the model is not named
    # a decided verdict in a start without propagated inputs says it holds at the nominal inputs only
    marked = nominal_only(table.assign(input_source="12 samples over 5 inputs"))
    assert marked.decided_by.tolist() == ["", "numerical error", NOMINAL_ONLY, NOMINAL_ONLY]
    assert marked.input_source.tolist() == ["12 samples over 5 inputs"] * 2 + [NOT_PROPAGATED] * 2


def test_a_row_whose_samples_are_all_undetermined_shows_no_range():
    """``undetermined_ranges``: a first-start row whose samples (the nominal one included) its margins all leave
    undetermined loses its range cells and says why; so does an undetermined row with only some samples decided (how
    many, in the cell); a decided row with one undetermined sample keeps them, and so does another start's row (no
    samples of its own there)."""
    import pandas as pd
    import xarray as xr

    from linkwork.papers.clearance.findings import (
        ALL_UNDETERMINED, DECIDED_SAMPLES, PARTLY_UNDETERMINED, undetermined_ranges,
    )

    outcome = np.array(
        [[[-1, 0, -1]], [[-1, -1, 1]], [[-1, 1, -1]]]
    )  # sample, variant, claim: c1 undetermined at every sample of both starts
    unc = xr.Dataset(
        {"sample_claim_outcome": (("sample", "variant", "claim"), outcome)},
        coords={
            "sample": ["nominal", "x low", "b | nominal"],
            "sample_scenario": ("sample", ["start a", "start a", "start b"]),
            "variant": ["decoded"],
            "claim": ["c1", "c2", "c3"],
        },
    )
    table = pd.DataFrame(
        {
            "model": ["decoded"] * 5,
            "scenario": ["start a", "start a", "start b", "start b", "start a"],
            "id": ["c1", "c2", "c1", "c2", "c3"],
            "input_low": [0.0, 0.0, np.nan, np.nan, 1.0],
            "input_high": [0.0, 1.0, np.nan, np.nan, 1.0],
            "input_source": ["12 samples"] * 5,
            "verdict": [
                "undetermined by our numerics", "differs", "differs", "differs", "undetermined by our numerics",
            ],
            "decided_by": ["numerical error", np.nan, "", "", "numerical error"],
        }
    )
    out = undetermined_ranges(table, unc)
    assert np.isnan(out.input_low[4]) and out.input_source[4] == f"{PARTLY_UNDETERMINED} 1 of 2 samples only"
    assert np.isnan(out.input_low[0]) and np.isnan(out.input_high[0]) and out.input_source[0] == ALL_UNDETERMINED
    assert out.input_low[1] == 0.0 and out.input_high[1] == 1.0 and out.input_source[1] == "12 samples"
    # a decided verdict with an undetermined sample holds at the decided ones: 'decided by' names the other
    assert out.decided_by[1] == f"{DECIDED_SAMPLES}: x (low end)"
    assert out.input_source[2:4].tolist() == ["12 samples"] * 2 and out.decided_by[2:4].tolist() == ["", ""]


def test_contact_frequency_uses_the_lightest_body_of_its_own_joint():
    """The linearised contact frequency of a clearance joint: sqrt(1.5 K sqrt(delta) / m) / 2 pi with m the lighter of
    the two bodies that joint connects (joint 2: coupler and rocker, never the crank), by hand."""
    from linkwork.papers.clearance.studies import contact_frequency

    p = parameters(SECTION, "decoded", "dry_both")
    delta = 1e-6
    for joint, bodies in ((1, (0, 1)), (2, (1, 2))):
        mass = min(p.masses[b] for b in bodies)
        expected = np.sqrt(1.5 * p.hertz_stiffness * np.sqrt(delta) / mass) / (2 * np.pi)
        assert contact_frequency(p, delta, joint) == pytest.approx(expected, rel=1e-12)
    assert np.isnan(contact_frequency(p, 0.0, 1))


def test_a_printed_bound_is_rounded_up_so_that_at_most_stays_true():
    """``words.at_most`` against exact decimal arithmetic: the printed number is the smallest two-digit value not below
    the bound (ceiling at two significant digits), on random values over twelve decades and on exact two-digit ones."""
    from decimal import ROUND_CEILING, Decimal

    from linkwork.papers.clearance.words import at_most

    rng = np.random.default_rng(7)
    values = [*(10.0 ** rng.uniform(-6, 6, 300)), 0.03, 0.035, 0.1, 1.0, 0.0999, 2.5e-4]
    for x in values:
        d = Decimal(repr(float(x)))
        expected = d.quantize(Decimal(1).scaleb(d.adjusted() - 1), rounding=ROUND_CEILING)
        printed = Decimal(at_most(float(x)))
        assert printed >= d and printed == expected, (x, at_most(float(x)), expected)
