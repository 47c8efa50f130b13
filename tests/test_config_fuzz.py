"""Fuzz table of bad configs: every one is refused before any job, in one line per problem naming the key.

Each row is a one-string edit of config/config.yaml as a user might make it (a typo, a unit slip, a
name that would become a path, a number that is not finite, a grid far too big for this machine).  The
edited text goes through exactly what the Snakefile runs (``load_yaml`` then ``validate_config``); a
row passes only if a ``ConfigError`` names the key (no other exception, no traceback, no silent
acceptance).  A sample of the rows, every kind of refusal, also goes through ``snakemake -n`` on a copy of the project.
"""

from __future__ import annotations

import copy
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

from test_workflow import DryRuns, copy_project, snakemake

from linkwork.papers import PAPERS
from linkwork.pipeline.errors import ConfigError
from linkwork.project.published import check_published
from linkwork.project.validate import load_yaml, published_schema, validate_config

PROJECT = Path(__file__).resolve().parents[1]
CONFIG_TEXT = (PROJECT / "config" / "config.yaml").read_text(encoding="utf-8")


def line_of(text: str) -> str:
    """'line N': the config line where ``text`` starts (the rows' edits replace it; no line number typed in)."""
    return f"line {CONFIG_TEXT[:CONFIG_TEXT.index(text)].count(chr(10)) + 1}"

# (id, old text, new text, fragments the message must contain)
CASES = [
    # values out of range, and linkages that cannot be assembled
    ("zero-length", "crank_m: 0.015", "crank_m: 0.0", ["stiffness.linkage.crank_m", "0.0"]),
    ("negative-length", "crank_m: 0.015", "crank_m: -0.015", ["stiffness.linkage.crank_m", "-0.015"]),
    ("cannot-assemble", "crank_m: 0.015", "crank_m: 0.2", ["stiffness.linkage", "crank_m=0.2", "cannot be assembled"]),
    (
        "yaml-string-number", "assembly_tol: 1.0e-9", "assembly_tol: 1e-9",
        ["stiffness.numerics.assembly_tol", "'1e-9'", "string"],
    ),
    ("unknown-key", "    branch: 1 ", "    branch: 1\n    brnach: 1 ", ["stiffness.linkage.brnach", "unknown key"]),
    (
        "sixbar-cannot-assemble", "l5_m: 0.500", "l5_m: 0.200",
        ["beatup.sixbar.l1_m", "cannot be assembled", "crank angle"],
    ),
    ("branch-not-unit", "branch_sley: -1", "branch_sley: 0", ["beatup.sixbar.branch_sley", "0"]),
    (
        "sw-above-stroke", "value: 0.100, status: assumed", "value: 0.200, status: assumed",
        ["beatup.fourbar.weft_clearance_m", "0.2", "stroke"],
    ),
    ("negative-mass", "M_P: {value: 8.0", "M_P: {value: -8.0", ["heald.parameters.M_P.value", "-8.0"]),
    (
        "lever-ratio-zero", "eta7: {value: 2.0", "eta7: {value: 0.0",
        ["heald.parameters.eta7.value", "0.0", "lever ratio"],
    ),
    # numbers that are not finite
    ("nan-length", "crank_m: 0.015", "crank_m: .nan", ["stiffness.linkage.crank_m", "nan"]),
    (
        "inf-modulus", "OA: {youngs_modulus_Pa: 2.1e+8", "OA: {youngs_modulus_Pa: .inf",
        ["stiffness.members.OA.youngs_modulus_Pa", "inf"],
    ),
    ("minus-inf-speed", "crank_speed_rpm: 300.0", "crank_speed_rpm: -.inf", ["transplanter.crank_speed_rpm", "inf"]),
    (
        "nan-in-list", "initial_diameters_m: [0.008, 0.008", "initial_diameters_m: [.nan, 0.008",
        ["transplanter.initial_diameters_m.0", "nan"],
    ),
    ("nan-in-range", "range: [0.3, 1.2]", "range: [.nan, 1.2]", ["heald.parameters.m_D.range.0", "nan"]),
    (
        "nan-sweep-point", "clearance_m: [1.500e-5, 2.500e-5,", "clearance_m: [.nan, 2.500e-5,",
        ["sweeps.clearance.small.clearance_m.0", "nan"],
    ),
    # names that would become paths or wildcards
    (
        "scene-parent-dir", "    dry_1: {clearance_joints: [1]", "    ../x: {clearance_joints: [1]",
        ["clearance.scenes.../x", "not allowed"],
    ),
    (
        "scene-slash", "    dry_1: {clearance_joints: [1]", "    a/b: {clearance_joints: [1]",
        ["clearance.scenes.a/b", "not allowed"],
    ),
    (
        "scene-paren", "    dry_1: {clearance_joints: [1]", "    dry(: {clearance_joints: [1]",
        ["clearance.scenes.dry(", "not allowed"],
    ),
    (
        "scene-regex", "    dry_1: {clearance_joints: [1]", "    '.*': {clearance_joints: [1]",
        ["clearance.scenes..*", "not allowed"],
    ),
    (
        "scene-braces", "    dry_1: {clearance_joints: [1]", "    '{scene}': {clearance_joints: [1]",
        ["clearance.scenes.{scene}", "not allowed"],
    ),
    (
        "scene-digit-first", "    dry_1: {clearance_joints: [1]", "    1dry: {clearance_joints: [1]",
        ["clearance.scenes.1dry", "not allowed"],
    ),
    (
        "scene-number", "    dry_1: {clearance_joints: [1]", "    1: {clearance_joints: [1]",
        ["clearance.scenes.1", "not allowed"],
    ),
    (
        "scene-too-long",
        "    dry_1: {clearance_joints: [1]",
        "    dry_" + "abcdefghij" * 3 + ": {clearance_joints: [1]",
        ["clearance.scenes.dry_" + "abcdefghij" * 3, "32 characters"],
    ),
    (
        "variant-space", "    slender: {inertia: slender}", "    'sl ender': {inertia: slender}",
        ["clearance.variants.sl ender", "not allowed"],
    ),
    ("material-dots", "  materials:\n    LF6:", "  materials:\n    ..:", ["transplanter.materials...", "not allowed"]),
    ("scene-home", "    dry_1: {clearance_joints: [1]", "    '~': {clearance_joints: [1]", ["not allowed"]),
    # integrator and step settings outside what the numerics can honour
    (
        "rtol-one", "explicit: {method: dop853, rtol: 1.0e-9", "explicit: {method: dop853, rtol: 1.0",
        ["clearance.integrators.explicit.rtol", "1.0"],
    ),
    (
        "rtol-zero", "explicit: {method: dop853, rtol: 1.0e-9", "explicit: {method: dop853, rtol: 0.0",
        ["clearance.integrators.explicit.rtol", "0.0"],
    ),
    (
        "rtol-negative", "- {method: ndf, rtol: 1.0e-10", "- {method: ndf, rtol: -1.0e-10",
        ["clearance.check_integrators.stiff.0.rtol", "-1e-10"],
    ),
    (
        "unknown-method", "explicit: {method: dop853, rtol: 1.0e-9", "explicit: {method: euler, rtol: 1.0e-9",
        ["clearance.integrators.explicit.method", "euler"],
    ),
    (
        "fine-step-tiny", "    fine_step_deg: 1.0", "    fine_step_deg: 1.0e-5",
        ["stiffness.grids.fine_step_deg", "1e-05"],
    ),
    (
        "angle-step-huge", "angle_step_deg: 1.0  ", "angle_step_deg: 180.0  ",
        ["transplanter.fe.angle_step_deg", "180.0"],
    ),
    (
        "points-per-cycle-huge", "points_per_cycle: 14400", "points_per_cycle: 100000000",
        ["clearance.numerics.points_per_cycle", "size guard"],
    ),
    (
        "record-cycles-huge", "record_cycles: 2  ", "record_cycles: 100000  ",
        ["clearance.numerics.record_cycles", "size guard"],
    ),
    ("revolutions-huge", "revolutions: 8 ", "revolutions: 1000000 ", ["transplanter.fe.revolutions", "size guard"]),
    ("scan-points-huge", "scan_points: 3601", "scan_points: 1000000000", ["beatup.numerics.scan_points", "size guard"]),
    ("heald-points-huge", "    points: 1200", "    points: 100000000", ["heald.speeds.points", "size guard"]),
    (
        "sweep-num-huge", "weft_clearance_m: {start: 0.010, stop: 0.150, num: 57}",
        "weft_clearance_m: {start: 0.010, stop: 0.150, num: 10000000}",
        ["beatup.sweep.weft_clearance_m.num", "size guard"],
    ),
    # physical magnitudes no linkage has
    (
        "rpm-astronomical", "crank_speed_rpm: 300.0", "crank_speed_rpm: 1.0e+300",
        ["transplanter.crank_speed_rpm", "1e+300"],
    ),
    (
        "rad-s-astronomical", "crank_speed_rad_s: 62.83185307179586", "crank_speed_rad_s: 1.0e+300",
        ["clearance.crank_speed_rad_s", "1e+300"],
    ),
    ("length-subatomic", "crank_m: 0.015", "crank_m: 1.0e-300", ["stiffness.linkage.crank_m", "1e-300"]),
    ("length-kilometres", "    ground_m: 0.170", "    ground_m: 1.7e+5", ["stiffness.linkage.ground_m", "170000.0"]),
    ("heald-max-below-min", "max_rpm: 1200.0", "max_rpm: 5.0", ["heald.speeds", "max_rpm"]),
    (
        "band-reversed", "band_rpm: {start: 300.0, stop: 700.0}", "band_rpm: {start: 700.0, stop: 300.0}",
        ["heald.accuracy.band_rpm", "700.0"],
    ),
    (
        "heald-sweep-reversed", "heald_mass: {start: 5.0, stop: 12.0", "heald_mass: {start: 12.0, stop: 5.0",
        ["heald.sweeps.heald_mass", "12.0"],
    ),
    # cross-references
    ("wp-unknown-scene", "      dry_2: {rk4:", "      dry_9: {rk4:", ["clearance.work_precision", "dry_9"]),
    ("wp-ideal-scene", "      dry_2: {rk4:", "      ideal: {rk4:", ["clearance.work_precision", "ideal"]),
    (
        "wp-no-reference", "      lubricated_2: {method: radau, rtol: 1.0e-12, check_rtol: 1.0e-11}\n", "",
        ["clearance.work_precision.reference", "lubricated_2"],
    ),
    (
        "wp-check-is-reference", "check_rtol: 1.0e-13}", "check_rtol: 1.0e-14}",
        ["clearance.work_precision.reference.dry_2.check_rtol", "1e-14"],
    ),
    (
        "wp-window-past-horizon", "dry_error_window_cycles: 0.02", "dry_error_window_cycles: 0.8",
        ["clearance.work_precision.dry_error_window_cycles", "0.8"],
    ),
    (
        "wp-unknown-variant", "    variant: slender\n    cycles: 0.5", "    variant: stiffest\n    cycles: 0.5",
        ["clearance.work_precision.variant", "stiffest"],
    ),
    ("sweep-unknown-scene", "    scene: dry_both", "    scene: dry_all", ["sweeps.clearance.scene", "dry_all"]),
    ("unknown-material", "    name: LF6", "    name: LF7", ["transplanter.material.name", "LF7"]),
    (
        "sweep-clearance-exceeds-bearing", "clearance_m: [1.500e-5, 2.500e-5,", "clearance_m: [1.0e-2, 2.500e-5,",
        ["sweeps.clearance.small.clearance_m", "0.01", "bearing_radius_m"],
    ),
    (
        "sweep-duplicate-values", "reaction_ratio_EF: [1.0, 1.5,", "reaction_ratio_EF: [1.0, 1.0,",
        ["sweeps.heald.small.reaction_ratio_EF"],
    ),
    (
        "sweep-grid-too-big",
        (
            "small: {clearance_m: [2.000e-5, 3.500e-5, 5.000e-5, 1.000e-4, 1.500e-4, 2.000e-4, 3.000e-4],"
            " reaction_ratio_EF: [1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0, 5.0, 7.0, 10.0]}"
        ),
        "small: {clearance_m: [%s], reaction_ratio_EF: [%s]}"
        % (
            ", ".join(f"{1e-5 + i * 1e-6:.3e}" for i in range(60)),
            ", ".join(f"{5.0 + i * 0.1:.2f}" for i in range(60)),
        ),
        ["sweeps.heald.small", "3600", "size guard"],
    ),
    (
        "journal-bigger-than-bearing", "journal_radius_m: 9.95e-3", "journal_radius_m: 10.05e-3",
        ["clearance.joints", "journal_radius_m"],
    ),
    # structure and YAML
    ("missing-key", "    restitution: 0.9\n", "", ["clearance.joints.restitution", "missing"]),
    (
        "missing-section",
        "  numerics:\n    assembly_tol: 1.0e-9   # relative slack on the triangle inequality at the edge of assembly\n",
        "",
        ["stiffness.numerics", "missing"],
    ),
    (
        "duplicate-key", "    restitution: 0.9\n", "    restitution: 0.9\n    restitution: 0.8\n",
        ["line", "'restitution' is given twice"],
    ),
    ("yaml-syntax", "  crank_speed_rpm: 300.0", "  crank_speed_rpm: [300.0", ["line", "not valid YAML"]),
    ("yaml-tab", "    restitution: 0.9\n", "\trestitution: 0.9\n", ["line", "not valid YAML"]),
    ("string-for-number", "restitution: 0.9", "restitution: high", ["clearance.joints.restitution", "'high'"]),
    ("list-for-number", "restitution: 0.9", "restitution: [0.9]", ["clearance.joints.restitution", "[0.9]"]),
    ("bool-for-number", "restitution: 0.9", "restitution: true", ["clearance.joints.restitution", "True"]),
    (
        "python-tag", "restitution: 0.9", "restitution: !!python/object/apply:os.system ['true']",
        ["line", "not valid YAML"],
    ),
    ("empty-scenes", "  scenes:\n    ideal:", "  scenes: {}\n  unused:\n    ideal:", ["clearance"]),
    # YAML 1.1 surprises (PyYAML reads 0720 as octal 464 and 5:00 as 300 in base 60), and an alias bomb (10^7 entries)
    (
        "yaml11-octal", "    points_per_cycle: 720\n", "    points_per_cycle: 0720\n",
        [line_of("    points_per_cycle: 720\n"), "heald.contact.points_per_cycle", "0720", "464"],
    ),
    (
        "yaml11-base-60", "crank_speed_rpm: 300.0", "crank_speed_rpm: 5:00",
        ["transplanter.crank_speed_rpm", "5:00", "300"],
    ),
    (
        "yaml-alias-bomb",
        "\nsweeps:\n",
        (
            "\nbomb:\n  a: &a [1, 1, 1, 1, 1, 1, 1, 1, 1, 1]\n  b: &b [*a, *a, *a, *a, *a, *a, *a, *a, *a, *a]\n  c: &c"
            " [*b, *b, *b, *b, *b, *b, *b, *b, *b, *b]\n  d: &d [*c, *c, *c, *c, *c, *c, *c, *c, *c, *c]\n  e: &e [*d,"
            " *d, *d, *d, *d, *d, *d, *d, *d, *d]\n  f: &f [*e, *e, *e, *e, *e, *e, *e, *e, *e, *e]\n  g: &g [*f, *f,"
            " *f, *f, *f, *f, *f, *f, *f, *f]\nsweeps:\n"
        ),
        ["config.yaml", "entries", "size guard"],
    ),
    # size guards on every count and step that multiplies work or memory, and counts given as floats
    (
        "guard-work-precision-cycles", "    cycles: 0.5 ", "    cycles: 1.0e+6 ",
        ["clearance.work_precision.cycles", "1000000.0", "size guard"],
    ),
    (
        "guard-heald-accuracy-points", "points: [25, 50, 100, 200, 400, 800, 1600, 3200, 6400]",
        "points: [25, 100000000]", ["heald.accuracy.points.1", "100000000", "size guard"],
    ),
    (
        "guard-elements-per-member", "elements_per_member: [1, 2, 2, 4]", "elements_per_member: [1, 2, 2, 100000]",
        ["transplanter.fe.elements_per_member.3", "size guard"],
    ),
    (
        "guard-sumt-iterations", "iterations: 8", "iterations: 1000000",
        ["transplanter.optimization.iterations", "size guard"],
    ),
    (
        "guard-coarse-angle-step", "coarse_angle_step_deg: 10.0", "coarse_angle_step_deg: 1.0e-6",
        ["transplanter.numerical_checks.coarse_angle_step_deg", "size guard"],
    ),
    ("guard-repeats", "    repeats: 5\n", "    repeats: 100000\n", ["stiffness.accuracy.repeats", "size guard"]),
    (
        "guard-fixed-step", "steps_s: [1.0e-3, 3.0e-4", "steps_s: [1.0e-12, 3.0e-4",
        ["clearance.crosscheck.steps_s.0", "size guard"],
    ),
    (
        "integer-as-float", "    points: 1200\n", "    points: 1200.0\n",
        ["heald.speeds.points", "1200.0", "not an integer"],
    ),
    (
        "integer-as-float-batch", "batch_size: 180", "batch_size: 180.0",
        ["heald.uncertainty.batch_size", "not an integer"],
    ),
    # rules across keys: a clearance joint held by contact or a film, e0 below the clearance, batches that fit in the
    # shortest judged window, a state search that can decide within its cap
    (
        "ideal-given-a-clearance-joint", "ideal: {clearance_joints: [], effects: [gravity]}",
        "ideal: {clearance_joints: [1], effects: [gravity]}",
        ["clearance.scenes.ideal", "every claim's reference with ideal joints"],
    ),
    (
        "clearance-joint-without-effects", "dry_1: {clearance_joints: [1], effects: [contact, friction, gravity]}",
        "dry_1: {clearance_joints: [1], effects: []}",
        ["clearance.scenes.dry_1.effects", "neither contact nor lubrication"],
    ),
    (
        "ideal-with-contact", "ideal: {clearance_joints: [], effects: [gravity]}",
        "ideal: {clearance_joints: [1], effects: [contact, friction, gravity]}",
        ["clearance.scenes.ideal", "every claim's reference with ideal joints"],
    ),
    (
        "crosscheck-scene-unknown", "      scene: dry_2\n", "      scene: dry_9\n",
        ["clearance.crosscheck.work_precision.scene", "'dry_9'"],
    ),
    (
        "crosscheck-scene-without-reference", "      scene: dry_2\n", "      scene: dry_1\n",
        ["clearance.crosscheck.work_precision.scene", "'dry_1'", "reference"],
    ),
    (
        "crosscheck-dry-scene-lubricated", "dry_scenes: [dry_1, dry_2, dry_both]", "dry_scenes: [dry_1, lubricated_2]",
        ["clearance.crosscheck.dry_scenes", "'lubricated_2'"],
    ),
    (
        "e0-above-clearance", "e0_m: {value: 2.5e-6", "e0_m: {value: 6.0e-5",
        ["clearance.assumed.e0_m.value", "6e-05", "not below the radial clearance"],
    ),
    (
        "batch-above-window", "batch_cycles: 5 ", "batch_cycles: 50 ",
        ["clearance.statistics.batch_cycles", "50", "fewer than two batches"],
    ),
    (
        "states-min-above-cap", "max_period: 4, section_tolerance: 5.0e-3, periods: 3, min_cycles: 12,",
        "max_period: 4, section_tolerance: 5.0e-3, periods: 3, min_cycles: 100,",
        ["beatup.sley_pin.states.min_cycles", "max_cycles = 60"],
    ),
    # keys YAML reads as something else than a name; a section the workflow reads, deleted
    (
        "scene-date-key", "    dry_1: {clearance_joints: [1]", "    2021-01-01: {clearance_joints: [1]",
        ["clearance.scenes.2021-01-01", "not allowed"],
    ),
    (
        "scene-list-key", "    dry_1: {clearance_joints: [1]", "    [a, b]: {clearance_joints: [1]",
        [line_of("    dry_1: {clearance_joints: [1]"), "a config key is a list, not a name"],
    ),
    ("root-crosscheck-deleted", "\ncrosscheck: false", "\n", ["crosscheck", "missing"]),
    # linkages that assemble but cannot run: a change point passed every turn, a clearance four-bar with no dead point
    (
        "stiffness-change-point", "    ground_m: 0.170 ", "    ground_m: 0.2379999 ",
        ["stiffness.linkage", "ground_m=0.2379999", "change-point linkage"],
    ),
    (
        "clearance-change-point", "  ground_m: 0.4\n", "  ground_m: 0.248074069840786\n",
        ["clearance.bodies", "clearance.ground_m 0.248074069840786", "change-point"],
    ),
    (
        "clearance-drag-link", "  ground_m: 0.4\n", "  ground_m: 0.1\n",
        ["clearance.bodies", "double-crank", "need a crank-rocker"],
    ),
    (
        "clearance-long-crank", "crank: {length_m: 0.2,", "crank: {length_m: 0.7,",
        ["clearance.bodies", "crank 0.7 m", "need a crank-rocker"],
    ),
    # a linkage of your own (config linkages): bad descriptions stop before any job with the key named
    (
        "linkage-unknown-point", "C: {journal: bellcrank.C, bearing: link.C}",
        "C: {journal: bellcrank.C, bearing: link.X}",
        ["linkages.watt_six_bar_worn_pin.linkage.joints.C.bearing", "unknown point 'X'"],
    ),
    (
        "linkage-not-connected",
        "      ground: {O2: [0.0, 0.0], O4: [0.3, 0.0], O6: [0.3, 0.3]}",
        (
            "        weight: {mass_kg: 1.0, inertia_kg_m2: 0.1, points: {P: [0.0, 0.0]}}\n      ground: {O2: [0.0,"
            " 0.0], O4: [0.3, 0.0], O6: [0.3, 0.3]}"
        ),
        ["linkages.watt_six_bar_worn_pin.linkage.bodies.weight", "not connected to the ground"],
    ),
    (
        "linkage-driver-not-grounded", "driver: {body: crank, speed_rad_s: 31.41592653589793",
        "driver: {body: coupler, speed_rad_s: 31.41592653589793",
        ["linkages.watt_six_bar_worn_pin.linkage.driver.body", "not pinned to the ground"],
    ),
    (
        "linkage-cannot-assemble", "ground: {O2: [0.0, 0.0], O4: [0.3, 0.0], O6: [0.3, 0.3]}",
        "ground: {O2: [0.0, 0.0], O4: [0.3, 0.0], O6: [0.3, 0.9]}",
        ["linkages.watt_six_bar_worn_pin.linkage.driver", "does not assemble"],
    ),
    (
        "linkage-locks-up", "coupler: {mass_kg: 1.2, inertia_kg_m2: 9.0e-3, points: {A: [-0.15, 0.0], B: [0.15, 0.0]}",
        "coupler: {mass_kg: 1.2, inertia_kg_m2: 9.0e-3, points: {A: [-0.075, 0.0], B: [0.075, 0.0]}",
        ["linkages.watt_six_bar_worn_pin.linkage", "locks up between the driver angles"],
    ),
    (
        "linkage-mobile", "        O6: {journal: rocker.O, bearing: ground.O6}\n", "",
        ["linkages.watt_six_bar_worn_pin.linkage.joints", "free motions"],
    ),
    (
        "linkage-effect-key", "impact_velocity_floor_m_s: 1.0e-3, friction: 0.05",
        "impact_velocity_floor_m_s: 1.0e-3, viscosity_Pa_s: 0.1, friction: 0.05",
        ["linkages.watt_six_bar_worn_pin.linkage.joints.D.clearance.viscosity_Pa_s", "unknown key"],
    ),
    # a linkage's names: the one name rule, which Snakemake's wildcards accept (a name of 40 a's or ending in 20
    # repeated digits used to pass, then stop the dry run with a PeriodicWildcardError), and no code in a name
    (
        "linkage-name-forty-a", "  watt_six_bar_worn_pin:", "  " + "a" * 40 + ":",
        ["linkages." + "a" * 40, "not allowed", "32 characters"],
    ),
    (
        "linkage-name-periodic", "  watt_six_bar_worn_pin:", "  watt" + "7" * 20 + ":",
        ["linkages.watt" + "7" * 20, "not allowed", "repeated 20 times"],
    ),
    (
        "linkage-joint-name-code", "        D:\n          journal: link.D",
        "        \"D\\nopen('pwned.txt','w').write('pwned')\\nif True:\":\n          journal: link.D",
        ["linkages.watt_six_bar_worn_pin.linkage.joints.\"D\\nopen(", "not allowed"],
    ),
    (
        "linkage-body-name-path", "        link: {mass_kg: 0.9", "        ../link: {mass_kg: 0.9",
        ["linkages.watt_six_bar_worn_pin.linkage.bodies.../link", "not allowed"],
    ),
    # an integrator without a key its method reads: dop853 without first_step_s ran with a first step of 0.0 and never
    # advanced; rk4 without step_s stopped with a KeyError
    (
        "linkage-dop853-no-first-step",
        "    points_per_turn: 3600\n    integrator: {method: dop853, rtol: 1.0e-9, atol: 1.0e-12, first_step_s: 1.0e-7",
        "    points_per_turn: 3600\n    integrator: {method: dop853, rtol: 1.0e-9, atol: 1.0e-12",
        ["linkages.watt_six_bar_worn_pin.integrator.first_step_s: missing", "dop853"],
    ),
    (
        "linkage-rk4-no-step",
        "    points_per_turn: 3600\n    integrator: {method: dop853, rtol: 1.0e-9, atol: 1.0e-12, first_step_s: 1.0e-7,"
        " max_step_s: 1.0e-3}",
        "    points_per_turn: 3600\n    integrator: {method: rk4}",
        ["linkages.watt_six_bar_worn_pin.integrator.step_s: missing", "rk4"],
    ),
    # magnitudes outside the documented ranges, and a clearance that holds nothing (issue 50: each was accepted and ran
    # to nonsense, or to numpy warnings)
    (
        "linkage-mass-1e30", "        coupler: {mass_kg: 1.2,", "        coupler: {mass_kg: 1.2e+30,",
        [
            "linkages.watt_six_bar_worn_pin.linkage.bodies.coupler.mass_kg", "above the largest allowed value",
            "schema.yaml",
        ],
    ),
    (
        "linkage-speed-1e6", "driver: {body: crank, speed_rad_s: 31.41592653589793",
        "driver: {body: crank, speed_rad_s: 1.0e+6",
        ["linkages.watt_six_bar_worn_pin.linkage.driver.speed_rad_s", "above the largest allowed value 10000"],
    ),
    (
        "linkage-speed-crawl", "driver: {body: crank, speed_rad_s: 31.41592653589793",
        "driver: {body: crank, speed_rad_s: 1.0e-9",
        ["linkages.watt_six_bar_worn_pin.linkage.driver.speed_rad_s", "must be at least 0.001 rad/s"],
    ),
    (
        "linkage-point-1e300", "      ground: {O2: [0.0, 0.0],", "      ground: {O2: [1.0e+300, 0.0],",
        ["linkages.watt_six_bar_worn_pin.linkage.ground.O2.0", "within 1 km of the origin"],
    ),
    (
        "linkage-clearance-no-effects", "effects: [contact, friction], youngs_modulus_Pa: 207.0e+9,",
        "effects: [], youngs_modulus_Pa: 207.0e+9,",
        ["linkages.watt_six_bar_worn_pin.linkage.joints.D.clearance.effects", "needs contact or lubrication"],
    ),
    # Pereira's law at a 1 nm clearance: its fitted exponent is undefined there (a ValueError inside the run)
    (
        "linkage-pereira-below-its-clearance",
        "bearing_radius_m: 5.0e-3, effects: [contact, friction], youngs_modulus_Pa: 207.0e+9,\n"
        "                      poisson: 0.3, restitution: 0.9, contact_law: lankarani-nikravesh,"
        " elastic_law: hertz-sphere,",
        "bearing_radius_m: 4.9505e-3, effects: [contact, friction], youngs_modulus_Pa: 207.0e+9,\n"
        "                      poisson: 0.3, restitution: 0.9, contact_law: lankarani-nikravesh,"
        " elastic_law: pereira, length_m: 0.01,",
        ["linkages.watt_six_bar_worn_pin.linkage.joints.D.clearance.elastic_law", "pereira needs a radial clearance"],
    ),
    (
        "integrator-scipy-no-max-step",
        "    explicit: {method: dop853, rtol: 1.0e-9, atol: 1.0e-12, first_step_s: 1.0e-7, max_step_s: 1.0e-3}",
        "    explicit: {method: radau, rtol: 1.0e-9, atol: 1.0e-12, first_step_s: 1.0e-7}",
        ["clearance.integrators.explicit.max_step_s: missing", "scipy"],
    ),
    (
        "linkage-turns-guard", "    turns: 1\n    points_per_turn: 3600", "    turns: 2000\n    points_per_turn: 3600",
        ["linkages.watt_six_bar_worn_pin.turns", "2000"],
    ),
    # the heald contact scene: a case must name a parameter with a range; the linkage must close
    (
        "heald-contact-case-unknown", "weight_dominant: {k_O: low, stroke_D: low, M_P: high}",
        "weight_dominant: {k_X: low}", ["heald.contact.cases.weight_dominant.k_X", "with a range"],
    ),
    (
        "heald-contact-arm-too-short", "D_to_E: 0.3, E_to_F: 1.2, arm_E: 0.1,",
        "D_to_E: 0.3, E_to_F: 1.2, arm_E: 0.01,", ["heald.contact", "does not assemble"],
    ),
]


# The published-numbers files (config/published/<paper>.yaml), validated like the config before any job:
# (id, paper, old text, new text, fragments the message must contain)
PUBLISHED_CASES = [
    (
        "published-negative-tolerance", "stiffness", "tolerance: {abs: 5.0e+3}", "tolerance: {abs: -5.0e+3}",
        ["stiffness.yaml, quantities.0.tolerance.abs", "-5000.0"],
    ),
    (
        "published-nan-tolerance", "stiffness", "tolerance: {abs: 5.0e+3}", "tolerance: {abs: .nan}",
        ["stiffness.yaml, quantities.0.tolerance.abs", "not a finite number"],
    ),
    (
        "published-value-twice", "stiffness", "    value: 3.46e+6\n", "    value: 3.46e+6\n    value: 3.5e+6\n",
        ["stiffness.yaml, line", "'value' is given twice"],
    ),
    (
        "published-tolerance-missing", "stiffness",
        '    unit: N/m\n    where: "Sec. 3.2 text; Fig. 7(a)"\n    tolerance: {abs: 5.0e+3}\n',
        '    unit: N/m\n    where: "Sec. 3.2 text; Fig. 7(a)"\n', ["stiffness.yaml, quantities.0.tolerance", "missing"],
    ),
    (
        "published-relation-unknown", "heald", "relation: ge", "relation: gt",
        ["heald.yaml, quantities", "relation", "'gt'"],
    ),
    (
        "published-value-text", "stiffness", "value: 3.46e+6", "value: abc",
        ["stiffness.yaml, quantities.0.value", "'abc'"],
    ),
    (
        "published-id-twice", "stiffness", "id: K_h_min", "id: K_h_max",
        ["stiffness.yaml, quantities.2", "'K_h_max' is given twice"],
    ),
    (
        "published-variable-misspelt", "stiffness", "measure: {variable: K_h, reduce: max",
        "measure: {variable: K_hh, reduce: max",
        ["stiffness.yaml, quantities.0 (K_h_max)", "'K_hh'", "RESULT_VARIABLES"],
    ),
    (
        "published-paper-other", "stiffness", "paper: stiffness", "paper: beatup",
        ["stiffness.yaml, paper", "not the file's paper"],
    ),
    (
        "published-table-row-short", "beatup", "- [0, 42.45, 0.0403, 0.2289, 65.44, 0.0176, 0.1002]",
        "- [0, 42.45, 0.0403, 0.2289, 65.44, 0.0176]", ["beatup.yaml, tables.0.rows.0", "6 values", "(7)"],
    ),
    (
        "published-unknown-key", "stiffness", 'tolerance_source: "the crank angle', 'tolerance_sauce: "the crank angle',
        ["stiffness.yaml, quantities.1.tolerance_sauce", "unknown key"],
    ),
    (
        "published-reduce-unknown", "stiffness", "reduce: max, dim", "reduce: maximum, dim",
        ["stiffness.yaml, quantities.0.measure.reduce", "'maximum'"],
    ),
    (
        "published-at-without-point", "clearance", "reduce: at, at: {claim: acceleration_order}", "reduce: at",
        ["clearance.yaml, quantities.0.measure.at: missing"],
    ),
]


def _published_copy(folder: Path, paper: str, old: str, new: str) -> None:
    """The published files and their schema copied to ``folder``/published with one edit of ``paper``'s file."""
    target = folder / "published"
    target.mkdir(parents=True)
    for name in PAPERS:
        text = (PROJECT / "config" / "published" / f"{name}.yaml").read_text(encoding="utf-8")
        if name == paper:
            assert text.count(old) >= 1, f"fuzz row out of date: {old!r} is not in config/published/{paper}.yaml"
            text = text.replace(old, new, 1)
        (target / f"{name}.yaml").write_text(text, encoding="utf-8")
    (folder / "published.schema.yaml").write_bytes((PROJECT / "config" / "published.schema.yaml").read_bytes())


def test_the_published_files_pass():
    check_published(PROJECT / "config" / "published", published_schema(PROJECT / "config" / "published"), list(PAPERS))


@pytest.mark.parametrize(
    ("paper", "old", "new", "fragments"), [c[1:] for c in PUBLISHED_CASES], ids=[c[0] for c in PUBLISHED_CASES]
)
def test_bad_published_file_is_refused_naming_the_entry(tmp_path, paper, old, new, fragments):
    _published_copy(tmp_path, paper, old, new)
    with pytest.raises(ConfigError) as info:
        check_published(tmp_path / "published", published_schema(tmp_path / "published"), list(PAPERS))
    message = str(info.value)
    for fragment in fragments:
        assert fragment in message, message
    assert all(len(line) < 400 for line in message.splitlines()) and "Traceback" not in message, message


def _edit(old: str, new: str) -> str:
    assert CONFIG_TEXT.count(old) >= 1, f"fuzz row out of date: {old!r} is not in config/config.yaml"
    return CONFIG_TEXT.replace(old, new, 1)


def test_the_table_is_large_and_names_are_unique():
    ids = [c[0] for c in CASES]
    assert len(ids) >= 40 and len(set(ids)) == len(ids)


@pytest.mark.parametrize(("old", "new", "fragments"), [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_bad_config_is_refused_naming_the_key(tmp_path, schema, old, new, fragments, validation_memo):
    path = tmp_path / "config.yaml"
    path.write_text(_edit(old, new), encoding="utf-8")
    with pytest.raises(ConfigError) as info:
        validate_config(load_yaml(path), schema, validation_memo)
    message = str(info.value)
    for fragment in fragments:
        assert fragment in message, message
    lines = message.splitlines()
    assert all(len(line) < 400 for line in lines), message
    assert "Traceback" not in message


@pytest.mark.parametrize("encoding", ["latin-1", "utf-16"])
def test_a_config_not_in_utf8_is_refused_naming_the_file(tmp_path, encoding):
    path = tmp_path / "config.yaml"
    path.write_bytes(_edit("(Sec. 2)", "(Sec. 2, café)").encode(encoding, errors="replace"))
    with pytest.raises(
        ConfigError, match=r"config.yaml: not UTF-8 text \(byte 0x[0-9a-f]{2} at offset \d+\); save the file as UTF-8"
    ):
        load_yaml(path)


#: The rows that also go through ``snakemake -n``: every kind of refusal (reading, schema, names, physics, rules across
#: keys, size guards, published numbers) by a sample, since each costs a Snakemake start (every row's message is
#: checked above on the same validation the Snakefile runs).
SNAKEMAKE_SAMPLE = {
    "zero-length",
    "cannot-assemble",
    "yaml-string-number",
    "unknown-key",
    "nan-length",
    "scene-parent-dir",
    "rtol-one",
    "yaml-tab",
    "python-tag",
    "yaml11-octal",
    "yaml-alias-bomb",
    "guard-work-precision-cycles",
    "integer-as-float",
    "batch-above-window",
    "crosscheck-scene-unknown",
    "scene-date-key",
    "scene-list-key",
    "root-crosscheck-deleted",
    "clearance-drag-link",
    "stiffness-change-point",
    "linkage-unknown-point",
    "linkage-name-periodic",
    "heald-contact-case-unknown",
    "published-negative-tolerance",
    "published-value-twice",
    "published-variable-misspelt",
    "published-table-row-short",
}


def test_the_snakemake_sample_names_rows_of_the_tables():
    assert SNAKEMAKE_SAMPLE <= {c[0] for c in CASES + PUBLISHED_CASES}


@pytest.mark.workflow
def test_snakemake_stops_the_sampled_rows_before_any_job(tmp_path):
    """The sampled rows through ``snakemake -n`` on their own copy of the project (two at a time, each dry run a
    child forked from a process that imported Snakemake once, as the edit tests'): exit non-zero, the message names
    the key in a line starting ``linkwork:``, no job planned, nothing in results/."""

    def edited(case) -> Path:
        name, *paper, old, new, _ = case
        root = copy_project(tmp_path / name)
        if paper:  # a published-numbers file
            path = root / "config" / "published" / f"{paper[0]}.yaml"
            path.write_text(path.read_text(encoding="utf-8").replace(old, new, 1), encoding="utf-8")
        else:
            (root / "config" / "config.yaml").write_text(_edit(old, new), encoding="utf-8")
        return root

    def run(part: list) -> list:  # one dry-run server per thread, each run in the case's own copy
        roots = [edited(case) for case in part]
        with DryRuns(copy_project(tmp_path / f"server-{part[0][0]}")) as dry:
            return [(case[0], root, *dry.run(cwd=root), case[-1]) for case, root in zip(part, roots, strict=True)]

    sample = [c for c in CASES + PUBLISHED_CASES if c[0] in SNAKEMAKE_SAMPLE]
    with ThreadPoolExecutor(max_workers=2) as pool:
        runs = [r for part in pool.map(run, [sample[0::2], sample[1::2]]) for r in part]
    assert len(runs) == len(SNAKEMAKE_SAMPLE)
    for name, root, code, message, fragments in runs:
        assert code != 0, f"{name}: snakemake accepted the config\n{message[-2000:]}"
        line = next((text for text in message.splitlines() if text.startswith("linkwork: ")), "")
        for fragment in fragments:
            assert fragment in message, f"{name}: {fragment!r} not in\n{message[-2000:]}"
        assert line and (fragments[0] in line or "invalid" in line), f"{name}: no one-line message\n{message[-2000:]}"
        assert "Traceback" not in message and "Job stats" not in message, f"{name}\n{message[-2000:]}"
        assert not (root / "results").exists() and not (root / ".snakemake" / "linkwork-validated").exists(), name


def test_the_validation_memo_tells_a_quoted_date_from_a_date(tmp_path):
    """The memo's key keeps what YAML read: a quoted date that passed does not let the unquoted one skip validation."""
    import datetime

    from linkwork.project.validate import validation_key

    schema, lib = PROJECT / "config" / "schema.yaml", PROJECT / "lib"
    quoted = validation_key({"scenes": {"2021-01-01": 1}}, schema, lib)
    assert quoted != validation_key({"scenes": {datetime.date(2021, 1, 1): 1}}, schema, lib)
    assert validation_key({"a": "2021-01-01"}, schema, lib) != validation_key(
        {"a": datetime.date(2021, 1, 1)}, schema, lib
    )
    assert quoted == validation_key({"scenes": {"2021-01-01": 1}}, schema, lib)


def test_command_line_text_is_read_as_the_schema_asks(schema):
    """Snakemake hands nested --config values and ``false`` over as text: they become the schema's numbers and
    booleans at their keys; text the schema wants as text, or that is no number, stays text (the schema check then
    names it)."""
    from linkwork.project.validate import coerce_overrides

    given = {
        "crosscheck": "false",
        "clearance": {
            "numerics": {"points_per_cycle": "360"},
            "joints": {"restitution": "0.8"},
            "scenes": {"dry_1": {"integrator": "explicit"}},
        },
        "sweeps": {"clearance": {"small": {"clearance_m": ["1.0e-5", "2e-5"]}}},
        "heald": {"contact": {"gravity": "TRUE"}},
        "transplanter": {"crank_speed_rpm": "fast"},
    }
    config = copy.deepcopy(given)
    coerce_overrides(config, given, schema)
    assert config["crosscheck"] is False and config["heald"]["contact"]["gravity"] is True
    assert config["clearance"]["numerics"]["points_per_cycle"] == 360 and isinstance(
        config["clearance"]["numerics"]["points_per_cycle"], int
    )
    assert config["clearance"]["joints"]["restitution"] == 0.8
    assert config["sweeps"]["clearance"]["small"]["clearance_m"] == [1.0e-5, 2.0e-5]
    assert config["clearance"]["scenes"]["dry_1"]["integrator"] == "explicit"  # text where the schema wants text
    assert config["transplanter"]["crank_speed_rpm"] == "fast"  # no number: the schema check names the key


def test_command_line_text_is_read_as_the_schema_asks_inside_a_linkage_and_a_labelled_value(config, schema):
    """A linkage's own keys (under a name the user chose, then the linkage's description: additionalProperties and
    $ref) and a labelled value (allOf) are typed too: the driver's speed, a joint's restitution and a damping ratio
    given on the command line were refused as text ("must be a finite number, got '62.8'").  The overrides, as the
    Snakefile lays them over the file, pass validation."""
    from linkwork.project.validate import coerce_overrides, merge_overrides

    given = {
        "linkages": {
            "watt_six_bar_worn_pin": {
                "linkage": {
                    "driver": {"speed_rad_s": "62.8"},
                    "joints": {"D": {"clearance": {"restitution": "0.5", "youngs_modulus_Pa": ["2.0e+11", "1.1e+11"]}}},
                },
                "points_per_turn": "720",
            }
        },
        "transplanter": {"fe": {"damping_ratio": {"value": "0.03"}}},
    }
    overridden = copy.deepcopy(given)
    coerce_overrides(overridden, given, schema)
    scene = overridden["linkages"]["watt_six_bar_worn_pin"]
    assert scene["linkage"]["driver"]["speed_rad_s"] == 62.8 and scene["points_per_turn"] == 720
    clearance = scene["linkage"]["joints"]["D"]["clearance"]
    assert clearance["restitution"] == 0.5 and clearance["youngs_modulus_Pa"] == [2.0e11, 1.1e11]
    assert overridden["transplanter"]["fe"]["damping_ratio"]["value"] == 0.03
    merge_overrides(overridden, config)
    validate_config(overridden, schema)
    assert overridden["linkages"]["watt_six_bar_worn_pin"]["linkage"]["joints"]["D"]["clearance"]["poisson"] == 0.3


#: Names a hostile user might choose: code after a newline (it ran when a joint's name was written into the generated
#: scene's source), markup for the reports, a path out of results/, a space, unicode, 5000 characters.
HOSTILE_NAMES = [
    "D\nopen('pwned.txt','w').write('pwned')\nif True:", "</script><script>alert(1)</script>", "../x", "a b", "Körper",
    "j" * 5000,
]
NAME_FIELDS = ["linkage", "body", "point", "ground point", "joint", "spring"]


def _named(config: dict, field: str, name: str) -> tuple[dict, str]:
    """``config`` with one name of the shipped linkage replaced by ``name`` (a spring added for ``spring``), and the key
    path of the section that holds the name."""
    config = copy.deepcopy(config)
    old = "watt_six_bar_worn_pin"
    linkage = config["linkages"][old]["linkage"]
    sections = {
        "linkage": (config, "linkages", old),
        "body": (linkage, "bodies", "link"),
        "point": (linkage["bodies"]["link"], "points", "C"),
        "ground point": (linkage, "ground", "O2"),
        "joint": (linkage, "joints", "D"),
    }
    if field == "spring":
        linkage["springs"] = {name: {"point": "link.C", "rest_m": [0.0, 0.0], "stiffness_N_m": [1.0, 1.0]}}
        return config, f"linkages.{old}.linkage.springs"
    holder, section, was = sections[field]
    holder[section] = {name if k == was else k: v for k, v in holder[section].items()}
    where = {"linkage": "linkages", "point": f"linkages.{old}.linkage.bodies.link.points"}
    return config, where.get(field, f"linkages.{old}.linkage.{section}")


@pytest.mark.parametrize("name", HOSTILE_NAMES, ids=["code", "markup", "path", "space", "unicode", "long"])
@pytest.mark.parametrize("field", NAME_FIELDS)
def test_a_hostile_name_in_any_name_field_is_refused_before_any_job(config, schema, field, name):
    """A name with code, markup or a path in every field where a linkage's author chooses a name: refused by the
    validation the Snakefile runs before any job, in one line naming the key path and the name."""
    edited, section = _named(config, field, name)
    with pytest.raises(ConfigError) as info:
        validate_config(edited, schema)
    message = str(info.value)
    assert len(message.splitlines()) == 1 and len(message) < 400, message
    shown = name if name.isprintable() and len(name) <= 80 else repr(name)  # as written, or its repr (cut)
    assert message.startswith(f"config key {section}.{shown[:60]}") and "not allowed" in message, message


def test_the_name_rule_admits_no_wildcard_value_snakemake_takes_for_a_cycle():
    """The name rule is the plain pattern (a letter, then letters, digits or _, at most 32) less exactly the values
    Snakemake's own detector calls periodic (PeriodicWildcardError in a dry run), on names built to end in repeats."""
    import re

    from snakemake.io import PeriodicityDetector

    from linkwork.project.validate import SAFE_NAME

    detector = PeriodicityDetector()
    names = [
        prefix + unit * k
        for prefix in ("", "a", "w_", "watt_six_")
        for unit in ("a", "7", "ab", "_1", "abc")
        for k in range(1, 26)
    ]
    refused_for_repeats = 0
    for name in names:
        plain = re.fullmatch(r"[A-Za-z][A-Za-z0-9_]{0,31}", name) is not None
        periodic = detector.is_periodic(name) is not None
        assert (SAFE_NAME.fullmatch(name) is not None) == (plain and not periodic), name
        refused_for_repeats += plain and periodic
    assert refused_for_repeats >= 10  # the rows exercise the repeats, not only the length


@pytest.mark.workflow
def test_snakemake_reads_nested_overrides_and_refuses_a_configfile_with_a_key_twice(tmp_path):
    root = copy_project(tmp_path / "project")
    proc = snakemake(root, "-n", "--config", "clearance={numerics: {points_per_cycle: 360}}", "crosscheck=false")
    assert "clearance_scene" in proc.stdout, proc.stdout[-2000:]
    linkage = (
        "linkages={watt_six_bar_worn_pin: {linkage: {driver: {speed_rad_s: 62.8},"
        " joints: {D: {clearance: {restitution: 0.5}}}}}}"
    )
    proc = snakemake(root, "-n", "--config", linkage)
    assert "linkage" in proc.stdout and "Traceback" not in proc.stdout + proc.stderr, proc.stdout[-2000:]
    extra = tmp_path / "mine.yaml"
    extra.write_text("clearance:\n  crank_speed_rad_s: 10.0\n  crank_speed_rad_s: 20.0\n", encoding="utf-8")
    proc = snakemake(root, "-n", "--configfile", str(extra), check=False)
    message = proc.stdout + proc.stderr
    assert (
        proc.returncode != 0 and f"linkwork: {extra}, line 3: config key 'crank_speed_rad_s' is given twice" in message
    ), message[-2000:]
    assert "Traceback" not in message and not (root / "results").exists()


def test_a_configfile_with_a_syntax_error_is_named_by_the_checker(tmp_path, capsys):
    """Snakemake reads a --configfile before the workflow and says only that it is not valid YAML; the checker the
    README points to names the file, the line and the column."""
    from linkwork.project.validate import main

    bad = tmp_path / "mine.yaml"
    bad.write_text("clearance:\n  crank_speed_rad_s: [10.0\n", encoding="utf-8")
    good = tmp_path / "good.yaml"
    good.write_text("clearance:\n  crank_speed_rad_s: 10.0\n", encoding="utf-8")
    assert main([str(good)]) == 0
    assert main([str(bad)]) == 1
    assert f"linkwork: {bad}, line 3, column 1: not valid YAML" in capsys.readouterr().err
