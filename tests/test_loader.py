"""The loader: the whole v1 format, our extensions, and one clear line for every bad input."""

import math
import textwrap

import numpy as np
import pytest

import mobility
from mobility.errors import MechanismError, MechanismFileError
from mobility.io.expressions import evaluate
from conftest import MECHANISMS

HEAD = """\
name: test
ground: g
end_effector: e
"""


def load_text(write_yaml, body: str):
    return mobility.load(write_yaml(HEAD + textwrap.dedent(body)))


def error_of(write_yaml, body: str, head: str = HEAD) -> MechanismFileError:
    path = write_yaml(head + textwrap.dedent(body))
    with pytest.raises(MechanismFileError) as info:
        mobility.load(path)
    err = info.value
    assert err.file == str(path)
    assert "\n" not in str(err)
    return err


def test_every_joint_type_loads_with_its_freedoms(write_yaml):
    m = load_text(
        write_yaml,
        """\
        joints:
          - {name: R1, type: R, links: [g, a], axis: [0, 0, 2], point: [1, 0, 0]}
          - {name: P1, type: P, links: [a, b], axis: [1, 1, 0]}
          - {name: H1, type: H, links: [b, c], axis: [0, 0, 1], point: [0, 0, 0], pitch: 0.1}
          - {name: C1, type: C, links: [c, d], axis: [1, 0, 0], point: [0, 1, 0]}
          - {name: U1, type: U, links: [d, f], point: [0, 0, 1], axes: [[1, 0, 0], [0, 1, 0]]}
          - {name: S1, type: S, links: [f, h], point: [1, 1, 1]}
          - {name: E1, type: E, links: [h, e], normal: [0, 0, 3]}
        """,
    )
    assert [j.dof for j in m.joints] == [1, 1, 1, 2, 2, 3, 3]
    assert m.joints[0].axis == (0.0, 0.0, 1.0)
    assert m.joints[1].axis == pytest.approx((math.sqrt(0.5), math.sqrt(0.5), 0.0))
    assert m.joints[6].normal == (0.0, 0.0, 1.0)
    assert m.freedom_count == 13
    kinds = [f.kind for j in m.joints for f in j.freedoms()]
    assert kinds == ["R", "P", "H", "R", "P", "R", "R", "R", "R", "R", "P", "P", "R"]


def test_frames_with_parent_chains_and_degrees(write_yaml):
    m = load_text(
        write_yaml,
        """\
        frames:
          base: {origin: [1, 0, 0], rpy: [0, 0, 90]}
          leg: {origin: [0, 2, 0], parent: base}
        joints:
          - {name: R1, type: R, links: [g, e], axis: [1, 0, 0], point: [1, 0, 0], frame: leg}
        """,
    )
    j = m.world_joints[0]
    # leg origin in world: base maps (0, 2, 0) to (1, 0, 0) + Rz(90) (0, 2, 0) = (-1, 0, 0); point (1, 0, 0) of leg -> (-1, 1, 0)
    assert np.allclose(j.point, (-1, 1, 0))
    assert np.allclose(j.axis, (0, 1, 0))
    assert m.joints[0].frame == "leg"


def test_radians_and_axis_angle_frames(write_yaml):
    m = load_text(
        write_yaml,
        """\
        units: {angle: rad, length: mm}
        frames:
          f: {axis: [0, 0, 1], angle: 1.5707963267948966}
        joints:
          - {name: P1, type: P, links: [g, e], axis: [1, 0, 0], frame: f}
        """,
    )
    assert np.allclose(m.world_joints[0].axis, (0, 1, 0))
    assert m.length_unit == "mm"


def test_parameters_expressions_and_limb_patterns(write_yaml):
    m = load_text(
        write_yaml,
        """\
        parameters:
          r: 2
          h: "r * sqrt(2)"
        limbs:
          - copies: 3
            frame: {name: "leg{i+1}", rpy: [0, 0, "120*i"]}
            joints:
              - {name: "R{i+1}", type: R, links: [g, "l{i+1}"], axis: [0, 1, 0], point: [r, 0, 0]}
              - {name: "S{i+1}", type: S, links: ["l{i+1}", e], point: ["r/2", 0, h]}
        """,
    )
    assert [j.name for j in m.joints] == ["R1", "S1", "R2", "S2", "R3", "S3"]
    assert [j.frame for j in m.joints[::2]] == ["leg1", "leg2", "leg3"]
    assert np.allclose(m.world_joints[2].point, (2 * math.cos(2 * math.pi / 3), 2 * math.sin(2 * math.pi / 3), 0))
    assert m.world_joints[1].point[2] == pytest.approx(2 * math.sqrt(2))


def test_expected_block(write_yaml):
    m = load_text(
        write_yaml,
        """\
        joints:
          - {name: P1, type: P, links: [g, e], axis: [0, 0, 1]}
        expected: {dof: 1, pattern: 1T, translations: [[0, 0, 1]], mobility: 1}
        """,
    )
    assert m.expected.dof == 1 and m.expected.pattern == "1T" and m.expected.mobility == 1
    assert m.expected.translations == ((0.0, 0.0, 1.0),)


@pytest.mark.parametrize(
    "body, line, key, words",
    [
        ("joints:\n  - {name: A, type: R, links: [g, e], axis: [0, 0, 1]}\n", 5, "joints[0].point", "missing"),
        ("joints:\n  - {name: A, type: Q, links: [g, e], axis: [0, 0, 1]}\n", 5, "joints[0].type", "unknown joint type 'Q'"),
        ("joints:\n  - {name: A, type: P, links: [g, e], axis: [0, 1]}\n", 5, "joints[0].axis", "expected a list of 3 numbers, got 2"),
        ("joints:\n  - {name: A, type: P, links: [g, e], axis: [0, 0, 0]}\n", 5, "joints[0].axis", "non-zero"),
        ("joints:\n  - {name: A, type: P, links: [g, e], axis: [0, .nan, 1]}\n", 5, "joints[0].axis[1]", "finite"),
        ("joints:\n  - {name: A, type: P, links: [g, e], axis: [0, x, 1]}\n", 5, "joints[0].axis[1]", "unknown name 'x'"),
        ("joints:\n  - {name: A, type: U, links: [g, e], point: [0, 0, 0], axes: [[1, 0, 0], [2, 0, 0]]}\n", 5, "joints[0].axes", "parallel"),
        ("joints:\n  - {name: A, type: P, links: [g, e], axis: [0, 0, 1]}\n  - {name: A, type: P, links: [g, e], axis: [1, 0, 0]}\n", 6, "joints[1].name", "duplicate joint name 'A'"),
        ("joints:\n  - {name: A, type: P, links: [g, g], axis: [0, 0, 1]}\n  - {name: B, type: P, links: [g, e], axis: [0, 0, 1]}\n", 5, "joints[0].links", "two different links"),
        ("frames:\n  a: {parent: b}\n  b: {parent: a}\njoints:\n  - {name: A, type: P, links: [g, e], axis: [0, 0, 1], frame: a}\n", 5, "frames.a.parent", "cycle"),
        ("joints:\n  - {name: A, type: P, links: [g, e], axis: [0, 0, 1], frame: nowhere}\n", 5, "joints[0].frame", "unknown frame 'nowhere'"),
        ("joints:\n  - {name: A, type: P, links: [g, x], axis: [0, 0, 1]}\n  - {name: B, type: P, links: [y, e], axis: [0, 0, 1]}\n", 3, "end_effector", "not connected to the ground"),
        ("joints:\n  - {name: A, type: P, links: [g, e], axis: [0, 0, 1], pointt: 3}\n", 5, "joints[0].pointt", "did you mean 'point'"),
        ("joints:\n  - {name: A, type: P, links: [g, e], axis: [0, 0, 1]}\nexpected: {dof: -1}\n", 6, "expected.dof", "non-negative integer"),
        ("joints:\n  - {name: A, type: P, links: [g, e], axis: [0, 0, 1]}\nexpected: {pattern: 2X}\n", 6, "expected.pattern", "pattern"),
        ("joints: {name: A}\n", 4, "joints", "list of joints"),
        ("joints:\n  - {name: A, type: P, links: [g, e], axis: [0, 0, 1]}\nunits: {angle: grad}\n", 6, "units.angle", "deg or rad"),
        ("joints:\n  - {name: A, type: P, links: [g, e], axis: \"1/0\"}\n", 5, "joints[0].axis", "a list of 3 numbers"),
        ("joints:\n  - {name: A, type: R, links: [g, e], axis: [0, 0, 1], point: [\"1/0\", 0, 0]}\n", 5, "joints[0].point[0]", "division by zero"),
        ("joints:\n  - {name: A, type: S, links: [g, e], point: [0, 0, 0], axis: [0, 0, 1]}\n", 5, "joints[0].axis", "not a field of a joint of type S"),
    ],
)
def test_bad_input_names_file_line_key(write_yaml, body, line, key, words):
    err = error_of(write_yaml, body)
    assert err.line == line, str(err)
    assert err.key == key, str(err)
    assert words in err.message, str(err)
    assert str(err).startswith(f"{err.file}:{line}: {key}: ")


def test_missing_required_key(write_yaml):
    err = error_of(write_yaml, "joints:\n  - {name: A, type: P, links: [g, e], axis: [0, 0, 1]}\n", head="name: t\nground: g\n")
    assert err.key == "end_effector" and err.message == "missing required key"  # the error names the key path
    assert err.line == 1


def test_yaml_syntax_error_has_its_line(write_yaml):
    err = error_of(write_yaml, "joints:\n  - {name: A, type: P, links: [g, e], axis: [0, 0, 1]\n  - oops\n")
    assert "YAML syntax error" in err.message
    assert err.line in (6, 7)


def test_duplicate_yaml_keys_are_errors(write_yaml):
    err = error_of(write_yaml, "joints:\n  - {name: A, type: P, links: [g, e], axis: [0, 0, 1]}\nground: h\n")
    assert err.key == "ground" and err.message == "duplicate key" and err.line == 6


def test_limb_template_errors_point_at_the_template(write_yaml):
    err = error_of(
        write_yaml,
        "limbs:\n  - copies: 2\n    joints:\n      - {name: \"R{i}\", type: R, links: [g, e], axis: [0, 0, 0], point: [0, 0, 0]}\n",
    )
    assert err.key == "limbs[0].joints[0].axis" and err.line == 7
    err = error_of(write_yaml, "limbs:\n  - copies: 2\n    joints:\n      - {name: R, type: P, links: [g, e], axis: [0, 0, 1]}\n")
    assert "duplicate joint name 'R'" in err.message and err.line == 7


def test_missing_file_and_directory(tmp_path):
    with pytest.raises(MechanismFileError, match="no such file"):
        mobility.load(tmp_path / "absent.yaml")
    with pytest.raises(MechanismFileError, match="is a directory"):
        mobility.load(tmp_path)


def test_empty_file(write_yaml):
    with pytest.raises(MechanismFileError, match="the file is empty"):
        mobility.load(write_yaml(""))


def test_model_errors_in_code_name_the_key():
    with pytest.raises(MechanismError) as info:
        mobility.Joint("A", "R", ("a", "b"), axis=(0, 0, 1))
    assert info.value.key == "point"
    with pytest.raises(MechanismError) as info:
        mobility.Mechanism("m", "g", "g", (mobility.Joint("A", "P", ("g", "e"), axis=(0, 0, 1)),))
    assert info.value.key == "end_effector"


@pytest.mark.parametrize("point", [(0, 0, 10**400), [0.0, 0.0, math.inf], (0.0, float("nan"), 0.0), [0, 0, 1e308 * 10]])
def test_model_vectors_refuse_what_is_not_a_finite_float(point):
    with pytest.raises(MechanismError) as info:
        mobility.Joint("A", "R", ("a", "b"), axis=(0, 0, 1), point=point)
    assert info.value.key == "point"
    assert "finite" in str(info.value)


def test_model_vectors_keep_their_values_exactly():
    joint = mobility.Joint("A", "R", ("a", "b"), axis=(0, 0, 2), point=[1, 0.1, -3])
    assert joint.point == (1.0, 0.1, -3.0)
    assert all(type(x) is float for x in joint.point)
    assert joint.axis == (0.0, 0.0, 1.0)


def test_expressions_are_safe_and_clear():
    assert evaluate("2 ** 3 % 5 - -1", {}) == 4.0
    assert evaluate("atan2d(1, 1)", {}) == pytest.approx(45.0)
    for bad in ("__import__('os').system('true')", "a.b", "[1][0]", "lambda: 1", "x if 1 else 2"):
        with pytest.raises(ValueError):
            evaluate(bad, {"a": 1.0})
    with pytest.raises(ValueError, match="math domain error"):
        evaluate("sqrt(-1)", {})


# -- arguments of load and loads: a wrong type is a RequestError naming it, never a bare builtin -------------

@pytest.mark.parametrize("path, expected", [
    (None, r"^load: expected a file name \(str or Path\), got NoneType$"),
    (3, r"^load: expected a file name \(str or Path\), got int$"),
    (True, r"^load: expected a file name \(str or Path\), got bool$"),
    (b"four_bar.yaml", r"^load: expected a file name \(str or Path\), got bytes$"),
    ({"name": "m"}, r"^load: expected a file name \(str or Path\), got dict$"),
    ("a\x00b.yaml", r"^load: expected a file name without a NUL character, got 'a\\x00b\.yaml'$"),
    ("a\x00b.urdf", r"^load: expected a file name without a NUL character, got 'a\\x00b\.urdf'$"),
])
def test_load_refuses_what_is_not_a_file_name(path, expected):
    with pytest.raises(mobility.errors.RequestError, match=expected):
        mobility.load(path)


@pytest.mark.parametrize("limits", [3, "x", {"max_joints": 3}])
def test_limits_must_be_a_limits_object(limits, write_yaml):
    path = write_yaml(HEAD + "joints:\n  - {name: P1, type: P, links: [g, e], axis: [0, 0, 1]}\n")
    for call in (lambda: mobility.load(path, limits=limits), lambda: mobility.loads(path.read_text(), limits=limits)):
        with pytest.raises(mobility.errors.RequestError, match=rf"^limits: expected a Limits \(mobility\.io\.limits\.Limits\) or None, got {type(limits).__name__}$"):
            call()


def test_robot_options_left_at_their_defaults_do_not_make_a_yaml_file_a_robot(write_yaml):
    path = write_yaml(HEAD + "joints:\n  - {name: P1, type: P, links: [g, e], axis: [0, 0, 1]}\n")
    assert [j.name for j in mobility.load(path, ground=None, close=(), floating=False).joints] == ["P1"]


@pytest.mark.parametrize("file", [3, None, b"m.yaml"])
def test_loads_refuses_a_file_name_for_messages_that_is_not_one(file):
    with pytest.raises(mobility.errors.RequestError, match=rf"^loads: file: expected a file name \(str or Path\), got {type(file).__name__}$"):
        mobility.loads(HEAD + "joints: []\n", file=file)


# --- a field of another joint type: named as such, with the field this type takes ---------------------------

_GEOMETRY = {"axis": "[0, 0, 1]", "point": "[0, 0, 0]", "pitch": "0.5", "axes": "[[1, 0, 0], [0, 1, 0]]", "normal": "[0, 0, 1]"}
_TAKES = {"R": ("axis", "point"), "P": ("axis",), "H": ("axis", "point", "pitch"), "C": ("axis", "point"), "U": ("point", "axes"), "S": ("point",), "E": ("normal",)}
_OPTIONAL = {"P": ("point",), "E": ("point",)}


@pytest.mark.parametrize("jtype", sorted(_TAKES))
def test_a_field_of_another_joint_type_is_named_as_such(write_yaml, jtype):
    need = _TAKES[jtype]
    for key, value in _GEOMETRY.items():
        if key in need + _OPTIONAL.get(jtype, ()):
            continue
        fields = ", ".join(f"{k}: {_GEOMETRY[k]}" for k in need)
        wrong = "[0, 0, 1]" if key == "axes" else value  # written as the type's own field would be: as a user who mixed them up
        err = error_of(write_yaml, f"joints:\n  - {{name: A, type: {jtype}, links: [g, e], {fields}, {key}: {wrong}}}\n")
        assert err.key == f"joints[0].{key}" and err.line == 5, str(err)
        owners = [t for t, n in _TAKES.items() if key in n + _OPTIONAL.get(t, ())]
        assert f"not a field of a joint of type {jtype} (it takes {', '.join(need)}" in err.message, str(err)
        assert f"of a joint of type {owners[0]}" in err.message if len(owners) == 1 else f"is a field of joints of type {', '.join(owners)}" in err.message, str(err)
        assert "expected two directions" not in err.message and "list of 3" not in err.message, str(err)


def test_axes_on_a_revolute_joint_points_at_axis(write_yaml):
    err = error_of(write_yaml, "joints:\n  - {name: A, type: R, links: [g, e], axes: [0, 0, 1], point: [0, 0, 0]}\n")
    assert str(err) == (f"{err.file}:5: joints[0].axes: not a field of a joint of type R (it takes axis, point): "
                        "axes holds the two directions of a joint of type U; write its direction as axis: [x, y, z]")


# --- warnings: a misspelt link name, angles in radians in a file read in degrees -----------------------------

SLIDER_CRANK = """\
name: slider-crank
ground: ground
end_effector: slider
joints:
  - {name: A, type: R, links: [ground, crank], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B, type: R, links: [crank, rod], axis: [0, 0, 1], point: [1, 1, 0]}
  - {name: C, type: R, links: [rod, slider], axis: [0, 0, 1], point: [3, 0, 0]}
  - {name: D, type: P, links: [slider, ground], axis: [1, 0, 0]}
"""


def notes_of(path) -> list[str]:
    """The warnings loading ``path`` gives, as text."""
    import warnings

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        mobility.load(path)
    return [str(w.message) for w in caught if issubclass(w.category, UserWarning)]


def test_a_misspelt_link_name_is_a_warning_with_the_name_meant(write_yaml):
    path = write_yaml(SLIDER_CRANK.replace("links: [rod, slider]", "links: [rod, slidr]"))
    assert notes_of(path) == [f"{path}:7: joints[2].links[1]: link 'slidr' is named by this joint only (did you mean 'slider'?): "
                              "a misspelt link name makes a link of its own, and another mechanism"]
    assert notes_of(write_yaml(SLIDER_CRANK)) == []


def test_a_link_named_once_on_purpose_is_no_warning(write_yaml):
    # a probe off the path, the numbered tips of fingers, the end effector itself: named once, as meant
    body = SLIDER_CRANK + "  - {name: E, type: P, links: [ground, probe], axis: [0, 1, 0]}\n"
    body += "  - {name: F1, type: R, links: [rod, tip1], axis: [0, 0, 1], point: [2, 0, 0]}\n  - {name: F2, type: R, links: [rod, tip2], axis: [0, 0, 1], point: [2, 1, 0]}\n"
    assert notes_of(write_yaml(body)) == []
    assert [notes_of(path) for path in sorted(MECHANISMS.glob("*.yaml"))] == [[] for _ in MECHANISMS.glob("*.yaml")]


def test_the_command_line_shows_the_warning_and_still_answers(write_yaml, capsys):
    from mobility.cli import main

    path = write_yaml(SLIDER_CRANK.replace("links: [rod, slider]", "links: [rod, slidr]"))
    assert main(["analyze", str(path)]) == 0
    out, err = capsys.readouterr()
    assert "idle DOF: 3" in out
    assert err == (f"mobility: note: {path}:7: joints[2].links[1]: link 'slidr' is named by this joint only (did you mean 'slider'?): "
                   "a misspelt link name makes a link of its own, and another mechanism\n")


LEGS = """\
name: three legs
ground: base
end_effector: leg0
{units}parameters: {{step: 2*pi/3}}
limbs:
  - copies: 3
    frame: {{rpy: [0, 0, "{angle}"]}}
    joints:
      - {{name: "R{{i}}", type: R, links: [base, "leg{{i}}"], axis: [1, 0, 0], point: [1, 0, 0]}}
"""


@pytest.mark.parametrize("angle", ["2*pi/3*i", "step*i", "tau/3*i"])
def test_an_angle_in_radians_in_a_file_read_in_degrees_is_a_warning(write_yaml, angle):
    path = write_yaml(LEGS.format(units="", angle=angle))
    notes = notes_of(path)
    assert len(notes) == 1 and notes[0].startswith(f"{path}:7: limbs[0].frame.rpy[2]: the angle {angle!r} uses pi, but the file's angles are in degrees"), notes
    assert "it turns by 2.0944 deg; if 2.0944 rad (120 deg) was meant, write the angle in degrees" in notes[0], notes


@pytest.mark.parametrize("units, angle", [("units: {angle: rad}\n", "2*pi/3*i"), ("", "120*i"), ("", "degrees(pi/3)*i"), ("units: {angle: deg}\n", "degrees(step)*i")])
def test_angles_in_their_files_unit_are_no_warning(write_yaml, units, angle):
    assert notes_of(write_yaml(LEGS.format(units=units, angle=angle))) == []


@pytest.mark.parametrize("frame, key, hint", [
    ("{rpy: [0, 0, 1.5708]}", "frames.f.rpy[2]", "this one turns by only 1.5708 deg; if 1.5708 rad (90.0002 deg) was meant, give units: {angle: rad}"),
    ("{axis: [0, 0, 1], angle: 0.7854}", "frames.f.angle", "if 0.7854 rad (45.0001 deg) was meant"),
])
def test_every_angle_as_small_as_radians_in_a_degrees_file_is_a_warning(write_yaml, frame, key, hint):
    path = write_yaml(HEAD + f"frames:\n  f: {frame}\n" + "joints:\n  - {name: A, type: R, links: [g, e], axis: [1, 0, 0], point: [0, 0, 0], frame: f}\n")
    notes = notes_of(path)
    assert len(notes) == 1 and notes[0].startswith(f"{path}:5: {key}: every angle of the file is at most 2π (6.283), as in radians, but the file's angles are in degrees"), notes
    assert hint in notes[0], notes
    # a tilt of a round number of degrees, or one angle beyond 2π: degrees, as meant
    for fine in (frame.replace("1.5708", "5").replace("0.7854", "2.5"), frame.replace("[0, 0, 1.5708]", "[0, 90, 1.5708]").replace("0.7854", "45")):
        assert notes_of(write_yaml(HEAD + f"frames:\n  f: {fine}\n" + "joints:\n  - {name: A, type: R, links: [g, e], axis: [1, 0, 0], point: [0, 0, 0], frame: f}\n")) == []
