"""Bad input raises magfoam.InputError (a ValueError) with the apps' messages:
where (file:line:col, or the Python argument), the key, what was expected."""
import numpy as np
import pytest

import magfoam as mf


def cube_system():
    s = mf.System()
    s.add_body("a", box=[0.01] * 3, Br=1.0, magnetization=[0, 0, 1], fixed=True)
    return s


def test_unknown_field_type_lists_the_valid_ones():
    with pytest.raises(mf.InputError, match=r"field\.type: unknown field evaluator type 'MBN'; valid types: .*MBM"):
        mf.System(field={"type": "MBN"})


def test_misspelled_key_names_the_closest_valid_one():
    with pytest.raises(mf.InputError, match=r"field.*quadratur.*quadrature"):
        mf.System(field={"type": "MBM", "quadratur": {"type": "gauss", "n": 4}})


def test_bad_values_name_the_key_and_what_was_expected():
    s = cube_system()
    with pytest.raises(mf.InputError, match=r"add_body\('b'\): magnetization: expected a vector of 3 numbers like \[0, 0, 1\], got '\[0, 1\]'"):
        s.add_body("b", box=[0.01] * 3, Br=1.0, magnetization=[0, 1])
    with pytest.raises(mf.InputError, match=r"add_body\('b'\): position: expected a vector of 3 finite numbers"):
        s.add_body("b", box=[0.01] * 3, Br=1.0, magnetization=[0, 0, 1], position=[0, 0, np.nan])
    with pytest.raises(mf.InputError, match=r"add_body\('b'\): unknown key 'postion' \(did you mean 'position'\?\)"):
        s.add_body("b", box=[0.01] * 3, Br=1.0, magnetization=[0, 0, 1], postion=[0, 0, 0.02])
    with pytest.raises(mf.InputError, match=r"name: duplicate body name 'a'"):
        s.add_body("a", box=[0.01] * 3, Br=1.0, magnetization=[0, 0, 1])
    with pytest.raises(mf.InputError, match=r"exactly one geometry.*\(2 given\)"):
        s.add_body("b", box=[0.01] * 3, sphere=0.005, Br=1.0, magnetization=[0, 0, 1])
    with pytest.raises(mf.InputError, match=r"give Br="):
        s.add_body("b", box=[0.01] * 3, magnetization=[0, 0, 1])
    with pytest.raises(mf.InputError, match=r"unknown material 'steel'"):
        s.add_body("b", box=[0.01] * 3, material="steel", magnetization=[0, 0, 1])
    with pytest.raises(mf.InputError, match=r"quaternion: quaternion has zero length"):
        s.add_body("b", box=[0.01] * 3, Br=1.0, magnetization=[0, 0, 1], quaternion=[0, 0, 0, 0])
    assert s.bodies == ["a"]  # nothing half-added


def test_mesh_from_arrays_is_checked():
    s = mf.System()
    V = np.array([[0, 0, 0], [0.01, 0, 0], [0, 0.01, 0], [0, 0, 0.01]], float)
    open_mesh = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2]])  # a tetrahedron without its fourth face
    with pytest.raises(mf.InputError, match=r"add_body\('t'\)"):
        s.add_body("t", mesh=(V, open_mesh), Br=1.0, magnetization=[0, 0, 1])
    with pytest.raises(mf.InputError, match=r"faces\[0\]: vertex index 7 out of range 0..3"):
        s.add_body("t", mesh=(V, [[0, 1, 7]]), Br=1.0, magnetization=[0, 0, 1])
    s.add_body("t", mesh=(V, np.vstack([open_mesh, [1, 2, 3]])), Br=1.0, magnetization=[0, 0, 1])
    assert np.isfinite(s.field([[0.02, 0.02, 0.02]])).all()


def test_evaluation_arguments():
    s = cube_system()
    with pytest.raises(mf.InputError, match=r"field: points: expected an array of shape \(n, 3\), got shape \(4, 2\)"):
        s.field(np.zeros((4, 2)))
    with pytest.raises(mf.InputError, match=r"points\[1\]: expected 3 finite numbers"):
        s.field([[0, 0, 0.02], [0, np.inf, 0]])
    with pytest.raises(mf.InputError, match=r"wrench\('c'\): unknown body 'c'; bodies: a"):
        s.wrench("c")
    with pytest.raises(mf.InputError, match=r"set_pose\('a'\): position: expected a vector of 3"):
        s.set_pose("a", position=[1, 2])
    with pytest.raises(mf.InputError, match=r"positions has 2 rows but quaternions 3"):
        s.sweep("a", positions=np.zeros((2, 3)), quaternions=np.tile([1.0, 0, 0, 0], (3, 1)))
    with pytest.raises(TypeError, match=r"field.quadrature: expected a number, string, list or dict, got object"):
        mf.System(field={"type": "MBM", "quadrature": object()})


def test_case_errors_cite_file_line_and_column(tmp_path):
    from conftest import SOURCE
    with pytest.raises(mf.InputError, match=r"case folder not found"):
        mf.Case(tmp_path / "doesNotExist")
    with pytest.raises(mf.InputError, match=r"bodies.yaml:[0-9]+:[0-9]+: bodies\[1\]\.position: expected a vector of 3 finite numbers"):
        mf.Case(SOURCE / "tests/badCases/nanPosition")
    with pytest.raises(mf.InputError, match=r"magSchemes.yaml:1:[0-9]+: field.type: unknown field evaluator type 'MBN'"):
        mf.Case(SOURCE / "tests/badCases/unknownType")
    with pytest.raises(mf.InputError, match=r"end_time: expected a finite time > startTime"):
        mf.Case(SOURCE / "tutorials/twoCubes").run(end_time=-1)


def test_a_result_that_cannot_be_written_raises_output_error(copy_case):
    # postProcessing/ is a file, not a folder: the run cannot write its CSVs.
    case = copy_case("tutorials/dropMagnet")
    (case / "postProcessing").write_text("in the way\n")
    with pytest.raises(mf.OutputError, match=r"postProcessing: cannot create the folder"):
        mf.Case(case).run(end_time=0.001)
    assert issubclass(mf.OutputError, OSError)
