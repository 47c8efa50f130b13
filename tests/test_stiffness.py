"""Energy-method stiffness against independent routes: statics + quadrature, and a frame FE solve."""

import numpy as np
import pytest
from scipy.integrate import quad

from linkwork.engines.fem import assemble_frame, solve_static
from linkwork.engines.kinematics import FourBar, four_bar
from conftest import load_yaml
from linkwork.papers.stiffness.model import (
    Section,
    axial_share,
    compliance_parts,
    equivalent_stiffness,
    moment_jump_at_b,
    paper_angles,
    printed_eq8,
    printed_eq14,
    unit_force_internal_forces,
    unit_load_displacement,
    unit_moment_internal_forces,
)

LINKAGE = FourBar(crank=0.015, coupler=0.138, rocker=0.115, ground=0.170, branch=1)
SECTIONS = (Section(2.1e8, 0.0330, 1.49e-5), Section(2.1e8, 0.0081, 5.46e-6), Section(2.1e8, 0.0132, 2.35e-5))
ALPHA = np.radians(np.arange(0.0, 360.0, 10.0))


def _joints(alpha):
    m = four_bar(LINKAGE, np.array([alpha]))
    return np.zeros(2), m.A[0], m.B[0], LINKAGE.rocker_pivot


def _members(alpha):
    o, a, b, o2 = _joints(alpha)
    # members as (start, end): OA from O, AB from A, BO' from O' (the paper's x origins)
    return [(o, a), (a, b), (o2, b)]


def _reactions_moment_case(l4):
    """Pinned O (Rx, Ry), roller O' (Ry'), unit moment at O': solve the three equilibrium equations."""
    # unknowns (Rx, Ry, Ry2): sum Fx = 0, sum Fy = 0, sum M about O = 1 + l4 * Ry2 = 0
    a = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 1.0], [0.0, 0.0, l4]])
    return np.linalg.solve(a, np.array([0.0, 0.0, -1.0]))


def _section_forces(case, point, tangent):
    """Axial force and bending moment at a section from statics (independent of Tables 1-2)."""
    if case == "force":  # clamp at O, unit horizontal force at O': take the part beyond the section
        load, at = np.array([1.0, 0.0]), LINKAGE.rocker_pivot
        arm = at - point
        moment = arm[0] * load[1] - arm[1] * load[0]
        return load @ tangent, moment
    rx, ry, _ = _reactions_moment_case(LINKAGE.ground)  # part between O and the section
    r = np.array([rx, ry])
    arm = -point
    return r @ tangent, arm[0] * r[1] - arm[1] * r[0]


def _energy_integrand(case, start, end, section):
    length = np.linalg.norm(end - start)
    tangent = (end - start) / length

    def density(x):
        n, m = _section_forces(case, start + x * tangent, tangent)
        return n**2 / (section.youngs_modulus * section.area) + m**2 / (section.youngs_modulus * section.second_moment)

    return density, length


def _quadrature_compliance(case, alpha):
    total = 0.0
    for (start, end), sec in zip(_members(alpha), SECTIONS, strict=True):
        f, length = _energy_integrand(case, start, end, sec)
        total += quad(f, 0.0, length, epsabs=0.0, epsrel=1e-13)[0]
    return total


def test_equilibrium_form_matches_statics_and_quadrature():
    curves = equivalent_stiffness(LINKAGE, SECTIONS, ALPHA, "equilibrium")
    for i, alpha in enumerate(ALPHA):
        assert np.isclose(1 / _quadrature_compliance("force", alpha), curves.linear[i], rtol=1e-11)
        assert np.isclose(1 / _quadrature_compliance("moment", alpha), curves.rotational[i], rtol=1e-11)


def test_trapezoid_quadrature_converges_at_second_order_to_the_closed_form():
    alpha = np.radians(100.0)
    exact = 1 / equivalent_stiffness(LINKAGE, SECTIONS, np.array([alpha]), "equilibrium").linear[0]
    panels = np.array([4, 8, 16, 32, 64])
    errors = []
    for n in panels:
        total = 0.0
        for (start, end), sec in zip(_members(alpha), SECTIONS, strict=True):
            f, length = _energy_integrand("force", start, end, sec)
            x = np.linspace(0.0, length, n + 1)
            y = np.array([f(xi) for xi in x])
            total += np.trapezoid(y, x)
        errors.append(abs(total - exact))
    rate = -np.polyfit(np.log(panels), np.log(errors), 1)[0]
    assert 1.98 < rate < 2.02, (rate, errors)


def test_equilibrium_form_matches_frame_finite_elements():
    curves = equivalent_stiffness(LINKAGE, SECTIONS, ALPHA, "equilibrium")
    props = [(s.youngs_modulus, s.area, s.second_moment) for s in SECTIONS]
    for i, alpha in enumerate(ALPHA):
        o, a, b, o2 = _joints(alpha)
        nodes = np.array([o, a, b, o2])
        k = assemble_frame(nodes, [(0, 1), (1, 2), (2, 3)], props)
        f = np.zeros(12)
        f[9] = 1.0  # unit horizontal force at O', frame clamped at O
        x = solve_static(k, f, [0, 1, 2])[9]
        m = np.zeros(12)
        m[11] = 1.0  # unit moment at O', O pinned, O' on a vertical roller
        phi = solve_static(k, m, [0, 1, 10])[11]
        assert np.isclose(1 / x, curves.linear[i], rtol=1e-9)
        assert np.isclose(1 / phi, curves.rotational[i], rtol=1e-9)


def test_tables_form_is_the_printed_tables_integrated():
    """Quadrature of the expressions exactly as printed in Tables 1-2 equals the 'tables' closed form."""
    l1, l2, l3, l4 = LINKAGE.lengths
    curves = equivalent_stiffness(LINKAGE, SECTIONS, ALPHA, "tables")
    a, b, g = curves.alpha, curves.beta, curves.gamma
    for i in range(0, len(ALPHA), 5):
        ai, bi, gi = a[i], b[i], g[i]
        table1 = [
            (lambda x: np.cos(ai), lambda x: x * np.sin(ai)),
            (lambda x: np.cos(gi), lambda x: l1 * np.sin(ai) - x * np.sin(gi)),
            (lambda x: np.cos(bi), lambda x: x * np.sin(bi)),
        ]
        table2 = [
            (lambda x: np.sin(ai) / l4, lambda x: x * np.cos(ai) / l4),
            (lambda x: np.sin(gi) / l4, lambda x: x * np.cos(gi) / l4 - l1 * np.cos(ai) / l4),
            (lambda x: np.sin(bi) / l4, lambda x: x * np.cos(bi) / l4 - 1.0),
        ]
        for rows, expected in ((table1, 1 / curves.linear[i]), (table2, 1 / curves.rotational[i])):
            total = 0.0
            for (n, m), length, s in zip(rows, (l1, l2, l3), SECTIONS, strict=True):
                total += quad(
                    lambda x: n(x) ** 2 / (s.youngs_modulus * s.area)
                    + m(x) ** 2 / (s.youngs_modulus * s.second_moment),
                    0.0,
                    length,
                    epsrel=1e-13,
                )[0]
            assert np.isclose(total, expected, rtol=1e-11)


def test_printed_equations_against_the_tables():
    """Eq. (8) is Table 1 integrated; eq. (14) differs from Table 2 integrated by its E2 I2 slip only."""
    l1, l2, l3, l4 = LINKAGE.lengths
    tables = equivalent_stiffness(LINKAGE, SECTIONS, ALPHA, "tables")
    a, b, g = tables.alpha, tables.beta, tables.gamma
    assert np.allclose(printed_eq8(l1, l2, l3, SECTIONS, a, b, g), 1 / tables.linear, rtol=1e-12, atol=0)
    e2i2 = SECTIONS[1].youngs_modulus * SECTIONS[1].second_moment
    e3i3 = SECTIONS[2].youngs_modulus * SECTIONS[2].second_moment
    slip = l3**3 * np.cos(b) ** 2 / (3 * l4**2) * (1 / e2i2 - 1 / e3i3)
    diff = printed_eq14(l1, l2, l3, l4, SECTIONS, a, b, g) - 1 / tables.rotational
    assert np.allclose(diff, slip, rtol=1e-9, atol=0)
    assert np.abs(slip).min() > 0  # the slip really changes every value


def test_moment_continuity_at_joint_b_separates_the_forms():
    """Statics makes the bending moment continuous at the rigid joint B; the printed tables do not.

    Independent route for the force case: a unit horizontal force at O' bends every section by its
    height above the line OO', so |M(B)| is |y_B| from the four-bar solution.
    """
    l1, l2, l3, l4 = LINKAGE.lengths
    alpha = np.radians(np.arange(0.0, 360.0, 1.0))
    a, b, g = paper_angles(LINKAGE, alpha)
    y_b = np.abs(four_bar(LINKAGE, alpha).B[:, 1])
    for form, continuous in (("equilibrium", True), ("tables", False)):
        force = unit_force_internal_forces(l1, a, b, g, form)
        moment = unit_moment_internal_forces(l1, l4, a, b, g, form)
        for forces in (force, moment):
            assert (moment_jump_at_b(l2, l3, forces).max() < 1e-12) == continuous
        assert np.allclose(np.abs(force[2].m0 + force[2].m1 * l3), y_b, atol=1e-12)
        if continuous:
            assert np.allclose(np.abs(force[1].m0 + force[1].m1 * l2), y_b, atol=1e-12)


def test_axial_share_is_the_axial_fraction_of_the_compliance():
    l1, l2, l3, l4 = LINKAGE.lengths
    a, b, g = paper_angles(LINKAGE, ALPHA)
    forces = unit_force_internal_forces(l1, a, b, g, "equilibrium")
    share = axial_share((l1, l2, l3), SECTIONS, forces)
    stiff = tuple(Section(s.youngs_modulus, s.area * 1e6, s.second_moment) for s in SECTIONS)
    assert np.all((share > 0) & (share < 1))
    assert axial_share((l1, l2, l3), stiff, forces).max() < 1e-5  # rigid in tension: no axial share
    axial, bending = compliance_parts((l1, l2, l3), SECTIONS, forces)
    assert np.allclose(share * unit_load_displacement((l1, l2, l3), SECTIONS, forces), axial, rtol=1e-12)


def test_the_result_dataset_states_what_its_curves_show():
    from linkwork.papers.stiffness.studies import stiffness

    ds = stiffness(load_yaml("config/config.yaml")["stiffness"])
    for form in ds.form.values:
        s = ds.sel(form=form)
        # every quoted extreme is over the paper's frames, the grid the published numbers are read on
        assert float(s.K_h_max) == float(s.K_h.max())
        assert float(s.K_c_argmin) == float(s.crank_angle[int(np.argmin(s.K_c.values))])
        assert np.isclose(float(s.K_h_spread), float((s.K_h.max() - s.K_h.min()) / s.K_h.mean()))
        assert np.isclose(float(s.K_pinned_over_K_c_max), float((ds.K_pinned / s.K_c).max()))
    assert ds.sizes["crank_angle"] == 36 and "36 frames" in ds.attrs["extremes_grid"]
    assert not [v for v in ds.data_vars if ds[v].ndim and "crank_angle_fine" not in ds[v].dims and v.endswith("_fine")]
    assert float(ds.moment_jump_B.sel(force_form="equilibrium").max()) < 1e-12
    assert float(ds.moment_jump_B.sel(force_form="tables", load_case="unit force")) > 0.01


def test_stiffness_is_proportional_to_youngs_modulus():
    base = equivalent_stiffness(LINKAGE, SECTIONS, ALPHA, "equilibrium")
    steel = tuple(Section(s.youngs_modulus * 1000, s.area, s.second_moment) for s in SECTIONS)
    scaled = equivalent_stiffness(LINKAGE, steel, ALPHA, "equilibrium")
    assert np.allclose(scaled.linear, 1000 * base.linear, rtol=1e-12)
    assert np.allclose(scaled.rotational, 1000 * base.rotational, rtol=1e-12)


def test_bad_form_and_section_rejected():
    with pytest.raises(ValueError, match="unknown stiffness form"):
        equivalent_stiffness(LINKAGE, SECTIONS, ALPHA, "eq8")
    with pytest.raises(ValueError, match="youngs_modulus must be positive"):
        Section(0.0, 1.0, 1.0)


# --- the pinned mechanism: an independent route by frame finite elements with pins -----------------------------


def _pinned_frame(alpha):
    """Frame FE model of the pinned linkage: six nodes (O, A on the crank, A on the coupler, B on the coupler,
    B on the rocker, O'), pins as shared translations of the two nodes at A and at B (a reduction matrix).

    Returns (reduced stiffness, reduction matrix); the reduced dofs are the full ones with each pin's second
    node's two translations dropped (they equal the first node's)."""
    o, a, b, o2 = _joints(alpha)
    nodes = np.array([o, a, a, b, b, o2])
    props = [(s.youngs_modulus, s.area, s.second_moment) for s in SECTIONS]
    k = assemble_frame(nodes, [(0, 1), (2, 3), (5, 4)], props)
    keep = [d for d in range(18) if d not in (6, 7, 12, 13)]  # node 2 and node 4 translations follow nodes 1 and 3
    t = np.zeros((18, len(keep)))
    for j, d in enumerate(keep):
        t[d, j] = 1.0
    for slave, master in ((6, 3), (7, 4), (12, 9), (13, 10)):
        t[slave, keep.index(master)] = 1.0
    return t.T @ k @ t, t, keep


def test_pinned_output_stiffness_matches_frame_finite_elements_with_pins():
    from linkwork.papers.stiffness.model import pinned_output_compliance, pinned_output_stiffness

    closed = pinned_output_stiffness(LINKAGE, SECTIONS, ALPHA)
    parts = pinned_output_compliance(LINKAGE, SECTIONS, ALPHA)
    assert np.allclose(parts.sum(axis=-1), 1 / closed, rtol=1e-14)
    for i, alpha in enumerate(ALPHA):
        kr, _, keep = _pinned_frame(alpha)
        load = np.zeros(len(keep))
        load[keep.index(17)] = 1.0  # unit torque on the rocker at O'
        fixed = [keep.index(d) for d in (0, 1, 2, 15, 16)]  # crank clamped at O (held), O' pivoted on the frame
        phi = solve_static(kr, load, fixed)[keep.index(17)]
        assert np.isclose(1 / phi, closed[i], rtol=1e-12), (np.degrees(alpha), 1 / phi, closed[i])


def test_pinned_stiffness_changes_with_each_part_as_its_formula_says():
    """Doubling one modulus-area product halves exactly the parts it enters (regression of the part bookkeeping)."""
    from linkwork.papers.stiffness.model import PINNED_PARTS, pinned_output_compliance

    base = pinned_output_compliance(LINKAGE, SECTIONS, ALPHA)
    coupler = (
        SECTIONS[0], Section(SECTIONS[1].youngs_modulus, 2 * SECTIONS[1].area, SECTIONS[1].second_moment), SECTIONS[2],
    )
    changed = pinned_output_compliance(LINKAGE, coupler, ALPHA)
    i = PINNED_PARTS.index("coupler axial")
    assert np.allclose(changed[:, i], base[:, i] / 2, rtol=1e-14)
    assert np.allclose(np.delete(changed, i, axis=1), np.delete(base, i, axis=1), rtol=1e-14)


def test_mobility_counts_agree_with_the_null_space_of_the_pinned_frame():
    """Grübler's counts against the rank of the FE stiffness: with the crank held and O' free the pinned frame has two
    mechanism modes (so a horizontal force at O' finds no elastic resistance: no pinned K_h); with O' pivoted none."""
    from linkwork.papers.stiffness.model import MOBILITY_CASES, planar_mobility

    counts = [planar_mobility(*case) for case in MOBILITY_CASES.values()]
    assert counts == [2, 0, 1]
    kr, _, keep = _pinned_frame(np.radians(40.0))
    scale = np.abs(kr).max()
    for fixed_dofs, expected in (((0, 1, 2), counts[0]), ((0, 1, 2, 15, 16), counts[1]), ((0, 1, 15, 16), counts[2])):
        free = [j for j, d in enumerate(keep) if d not in fixed_dofs]
        singular = np.linalg.svd(kr[np.ix_(free, free)], compute_uv=False)
        assert int((singular < 1e-9 * scale).sum()) == expected
    # the horizontal force at a free O' does work on a mechanism mode: K u = f has no solution (the best
    # least-squares u leaves a residual of the order of the force itself, not of rounding)
    free = [j for j, d in enumerate(keep) if d not in (0, 1, 2)]
    force = np.zeros(len(free))
    force[free.index(keep.index(15))] = 1.0
    k_free = kr[np.ix_(free, free)]
    u = np.linalg.lstsq(k_free, force, rcond=1e-12)[0]
    assert np.linalg.norm(k_free @ u - force) > 1e-2


def _compared(**changes):
    from linkwork.papers.stiffness.findings import compare
    from linkwork.papers.stiffness.studies import stiffness

    cfg = load_yaml("config/config.yaml")["stiffness"] | changes
    return compare(cfg, load_yaml("config/published/stiffness.yaml"), stiffness(cfg))


def test_findings_state_one_grid_angles_in_degrees_and_the_axial_verdict():
    table, fnd = _compared()
    head = table[(table.role == "headline")].set_index(["model", "id"])
    # crank angles: our value minus the published one in degrees, on the circle (70 deg against 280 deg is 150 deg)
    assert fnd.deviation_unit.sel(quantity_id="K_h_argmin") == "deg"
    assert float(fnd.deviation_shown.sel(form="equilibrium", quantity_id="K_h_argmin")) == 150.0
    assert (
        float(fnd.deviation_shown.sel(form="equilibrium", quantity_id="K_h_argmax"))
        == head.loc[("equilibrium", "K_h_argmax"), "reproduced"] - 100
    )
    assert np.isclose(
        float(fnd.deviation_shown.sel(form="tables", quantity_id="K_c_max")),
        head.loc[("tables", "K_c_max"), "relative_deviation"],
    )
    # the axial verdict follows its threshold: 22.8 % of x_O' is not negligible at 5 %, is at 30 %
    assert 0.2 < float(fnd.axial_share_largest_force) < 0.25 and not fnd.axial_terms_negligible.any()
    _, loose = _compared(axial_negligible_share=0.3)
    assert bool(loose.axial_terms_negligible.all())


def test_material_statement_is_computed_from_the_printed_sections():
    _, fnd = _compared()
    text = fnd.attrs["material_statement"]
    assert "E = 210 MPa is not steel's: steel's modulus is 1000 times the printed one" in text
    assert f"A₁ = 330 cm² would be a square {np.sqrt(0.0330) * 1e3:.0f} mm on a side on a 15 mm crank" in text
    from linkwork.pipeline import statements

    rendered = {r.id: r for r in statements.render("stiffness", fnd, _compared()[0])}
    assert "It used 210 MPa: steel links would be 1000 times stiffer." in statements.plain_answer(
        list(rendered.values())
    )
    assert "a square 182 mm on a side on a 15 mm crank" in rendered["sections"].text


def test_pinned_stiffness_statement_follows_the_result():
    from linkwork.papers.stiffness.studies import stiffness

    ds = stiffness(load_yaml("config/config.yaml")["stiffness"])
    assert float(ds.K_pinned_min) == float(ds.K_pinned.min()) and float(ds.K_pinned_max) == float(ds.K_pinned.max())
    assert list(ds.mobility.values) == [2, 0, 1]
    shares = ds.pinned_share_max.sel(pinned_part=["coupler axial", "rocker bending"]).values
    assert np.all(shares > 0.4)  # the torque goes through the coupler's tension and the rocker's bending
    _, fnd = _compared()
    assert float(fnd.pinned_varies_considerably) == float(float(ds.K_pinned_max_over_min) >= 1.2)


def test_the_conclusion_is_one_verdict_per_form_and_the_counts_count_rows():
    from linkwork.papers.stiffness.findings import CONCLUSION, conclusion_verdicts

    table, fnd = _compared()
    forms = [str(f) for f in fnd.form.values]
    # each form's count holds its rows as the classifier classed them: eight stiffness numbers and the two claims
    for form in forms:
        counted = int(fnd.verdict_count.sel(count_model=form, role="headline").isel(count_scenario=0).sum())
        assert counted == int(fnd.headline_total.sel(form=form)) + 2 == 10
    assert list(fnd.conclusion_verdict.values) == ["reproduced"] * (len(forms) - 1) + ["no counterpart in this model"]
    assert (
        int(fnd.verdict_count.sel(count_model="tables", role="headline", verdict="reproduced").isel(count_scenario=0))
        == int(fnd.headline_matches.sel(form="tables")) + 2
    )
    # the combined verdict: one stiffness found near constant makes the conclusion deviate
    claims = table[table.id.isin(CONCLUSION)].copy()
    forms = forms[:3]
    claims.loc[(claims.model == "equilibrium") & (claims.id == "K_c_not_constant"), "verdict"] = "differs"
    undetermined = "undetermined by our numerics"
    claims.loc[(claims.model == "tables") & (claims.id == "K_h_not_constant"), "verdict"] = undetermined
    assert conclusion_verdicts(claims, forms) == ["differs", "undetermined by our numerics", "reproduced"]
    # a threshold claim shows our max/min itself, not a percentage of the threshold
    assert str(fnd.deviation_unit.sel(quantity_id="K_h_not_constant").values) == "ratio"
    head = table[table.role == "headline"].set_index(["model", "id"])
    assert (
        float(fnd.deviation_shown.sel(form="tables", quantity_id="K_h_not_constant"))
        == head.loc[("tables", "K_h_not_constant"), "reproduced"]
    )
    # eq. (8) is Table 1 integrated: the printed form's K_h is the tables' (why two rows of section 6 agree)
    assert int(fnd.printed_K_h_same_as_tables) == 1


def _ids(table, form, verdict):
    rows = table[(table.model == form) & (table.role == "headline")]
    return set(rows[rows.verdict == verdict].id)


def test_the_pinned_form_judges_the_conclusion_on_the_real_joints():
    from linkwork.papers.stiffness.studies import stiffness
    from linkwork.pipeline.results import check_finite

    table, fnd = _compared()
    ds = stiffness(load_yaml("config/config.yaml")["stiffness"])
    # the joint model is a named scenario: three welded forms of the paper and the pinned mechanism
    assert list(fnd.joints.values) == ["welded", "welded", "welded", "pinned"]
    check_finite(fnd, "findings")  # the writer's check: a NaN says what it means (no pinned K_h)
    assert np.isnan(float(fnd.deviation_shown.sel(form="pinned", quantity_id="K_h_max")))
    # the pinned mechanism is a different quantity: every published row of the pinned form says so (the model's
    # cause, not the paper's), with the reason, and no number stands beside a published one it is not
    headline_ids = set(table[(table.model == "equilibrium") & (table.role == "headline")].id)
    assert _ids(table, "pinned", "no counterpart in this model") == headline_ids
    missing = table[(table.model == "pinned") & (table.role == "headline")]
    assert (
        missing.reproduced.isna().all()
        and missing.numerical_error.isna().all()
        and missing.input_source.str.contains("different quantity").all()
        and missing.input_source.str.contains("mobility 2").all()
    )
    assert int(fnd.pinned_K_h_exists) == 0 and int(fnd.pinned_free_mobility) == 2
    # our own pinned reading: the output stiffness's max/min (about 1.05, below 1.2), from the result itself
    assert float(fnd.pinned_max_over_min) == float(ds.K_pinned.max() / ds.K_pinned.min()) < 1.2
    assert int(fnd.pinned_varies_considerably) == 0
    # the conclusion per joint model: it holds welded; the pinned joints have no counterpart, so nothing decides it
    assert list(fnd.conclusion_by_joints.values) == ["reproduced", "no counterpart in this model"]
    assert int(fnd.conclusion_decided_by_joints) == 0
    # the defensible model's count holds its rows as classified: every stiffness number differs, both claims hold
    counted = fnd.verdict_count.sel(count_model="equilibrium", role="headline").isel(count_scenario=0)
    assert int(fnd.headline_matches.sel(form="equilibrium")) == 0 and int(counted.sel(verdict="reproduced")) == 2
    assert int(counted.sel(verdict="differs")) == int(fnd.headline_total.sel(form="equilibrium"))


def test_a_pinned_mechanism_that_varies_considerably_changes_our_reading_only():
    """A longer crank and a stiff rocker make the pinned output vary by more than 1.2: our reading of the machine says
    so, while the paper's quantities still have no pinned counterpart."""
    cfg = load_yaml("config/config.yaml")["stiffness"]
    members = {k: dict(v) for k, v in cfg["members"].items()}
    members["BO"]["second_moment_m4"] *= 1e4
    table, fnd = _compared(linkage=cfg["linkage"] | {"crank_m": 0.03}, members=members)
    assert float(fnd.pinned_max_over_min) > 1.2 and int(fnd.pinned_varies_considerably) == 1
    assert not _ids(table, "pinned", "reproduced")
    assert list(fnd.conclusion_by_joints.values) == ["reproduced", "no counterpart in this model"]


def test_the_report_opens_with_its_answer_and_the_one_figure_in_plain_words(tmp_path):
    """The stiffness report rendered from results built here: the title names the paper, the answer comes first and
    the figure of K_h and K_c per form right after it (before anything else), and its prose holds no code name
    (snake_case), no config key path and no unrendered template.  Provenance lists attribute names on purpose."""
    import html
    import re

    from conftest import render_stiffness_page

    page, table, fnd = render_stiffness_page(tmp_path, load_yaml("config/config.yaml")["stiffness"])
    assert "Traceback" not in page and 'vnd.jupyter.stderr" tabindex' not in page  # no warning or error printed
    body = page[page.index("<body"):]
    text = re.sub(
        r"\s+", " ",
        html.unescape(re.sub(r"<[^>]+>", " ", re.sub(r"<style.*?</style>|<script.*?</script>", "", body, flags=re.S))),
    )
    from linkwork.pipeline import statements

    answer = statements.plain_answer(statements.render("stiffness", fnd, table))
    heading = text.index("The stiffness paper (Huang, Wu, Li 2022)")
    assert text.index(answer) > heading
    # the answer, then the one figure (its caption), then the paper's citation and the rest
    first_figure = body.index("<img")
    assert body.index("Does the paper hold up?") < first_figure < body.index("What the paper does")
    assert text.index(
        "Figure: Linear stiffness K_h (N/m, left) and rotational stiffness K_c (N·m/rad, right)"
    ) < text.index("Paper.")
    assert f"the pinned one by {float(fnd.pinned_max_over_min):.2f}" in text
    prose = text[:text.index("Provenance")]
    assert not re.findall(r"\b[a-z][a-z0-9]*_[a-z0-9_]+\b", prose), sorted(
        set(re.findall(r"\b[a-z][a-z0-9]*_[a-z0-9_]+\b", prose))
    )
    assert "stiffness." not in prose.replace("stiffness. ", "") and not re.search(r"\{[^}]*\}", prose)
    # the conclusion judged on the pinned joints is stated, with the joint model as the deciding scenario
    plain = re.sub(r" ([:;,.])", r"\1", text)
    assert "Welded joints, as the paper models them: reproduced. Pinned joints (a different quantity" in plain
    assert "its 8 numbers have no counterpart" in plain  # the pinned mechanism's numbers, counted
    assert "On the machine's pinned joints the paper's stiffnesses have no counterpart" in plain




def test_the_papers_closures_hold_and_its_tables_jump_at_b_by_the_closed_forms():
    """Eqs. (3) and (9) are the loop's closures: on our linkage they hold to rounding at every frame. The tables'
    bending moments jump at B by 2 l1 (unit force) and 2 l1 / l4 (unit moment): the sign error's closed forms."""
    _, fnd = _compared()
    assert float(fnd.eq3_residual) < 1e-12 and float(fnd.eq9_residual) < 1e-12
    assert np.isclose(float(fnd.tables_moment_jump), 2 * 0.015, rtol=1e-9)
    assert np.isclose(float(fnd.tables_moment_jump_unit_moment), 2 * 0.015 / 0.170, rtol=1e-9)
