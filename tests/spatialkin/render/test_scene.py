"""The Scene's data against oracles (identities, exact distances, the drive's dimensions), its exports read
back, atomic writes, argument checks, and the lazy import of pyvista."""
import os
import subprocess
import sys

import numpy as np
import pytest
import pyvista

import spatialkin as sk
from spatialkin.render import Scene, looper_scene
from tests.oracles.ssi import face_margin, to_local
from spatialkin.render import geometry as geo
from spatialkin.render import scene as scene_module


def no_temporaries(folder):
    return not [p for p in os.listdir(folder) if p.startswith(".tmp-")]


def test_import_spatialkin_does_not_import_pyvista():
    code = ("import sys, spatialkin, spatialkin.render; "
            "sys.exit(1 if {'pyvista', 'vtk', 'vtkmodules'} & set(sys.modules) else 0)")
    assert subprocess.run([sys.executable, "-c", code]).returncode == 0


def test_tube_carries_the_curves_arc_length(pair):
    """Identity: the tube's points around polyline point i carry its s and lie at the tube radius from it (1e-9
    relative); the caps carry the end values."""
    curve = pair[2][0]
    scene = Scene()
    scene.add_curve(curve, name="c", radius=0.5)
    tube = scene.meshes()["c"]
    line = scene.data("c")
    n, sides = line.n_points, scene_module.TUBE_SIDES
    s_line = np.asarray(line.point_data["s"])
    s = np.asarray(tube.point_data["s"])
    assert np.array_equal(s[:n * sides].reshape(n, sides), np.repeat(s_line[:, None], sides, axis=1))
    assert set(s[n * sides:]) <= {s_line[0], s_line[-1]}
    gap = np.linalg.norm(np.asarray(tube.points[:n * sides]).reshape(n, sides, 3) - np.asarray(line.points)[:, None],
                         axis=2)
    np.testing.assert_allclose(gap, 0.5, rtol=1e-9)


def test_curve_drawn_as_a_dense_polyline_with_its_speed(pair):
    """A traced curve is drawn by a polyline of exact curve points (on both surfaces to 1e-12) at its own arc
    lengths, spaced by the chord height (every chord's midpoint within it of the curve), never the solver's
    steps; a speed given at the curve's points is interpolated onto it (oracle: numpy.interp)."""
    torus, sphere, curves = pair
    curve = curves[1]
    speed = np.linspace(1.0, 2.0, len(curve))
    scene = Scene()
    chord = 1e-4
    scene.add_curve(curve, name="c", color_by="speed", speed=speed, chord_tol=chord)
    data = scene.data("c")
    pts, s = np.asarray(data.points), np.asarray(data.point_data["s"])
    assert len(pts) > len(curve) and s[0] == 0 and abs(s[-1] - curve.length) < 1e-12
    assert max(torus.distance(pts).max(), sphere.distance(pts).max()) < 1e-12
    mid = curve(0.5 * (s[1:] + s[:-1]))
    assert np.max(np.linalg.norm(mid - 0.5 * (pts[1:] + pts[:-1]), axis=1)) <= chord
    np.testing.assert_allclose(np.asarray(data.point_data["speed"]), np.interp(s, curve.s, speed), rtol=1e-12)


def test_path_arc_length_is_the_chord_length():
    """A path given as points gets s = cumulative chord length: on a polygon of a circle, the sum of the
    chords 2 R sin(pi/n) (1e-12 relative)."""
    n, radius = 36, 5.0
    t = np.linspace(0.0, 2 * np.pi, n + 1)
    scene = Scene()
    scene.add_curve(np.column_stack([radius * np.cos(t), radius * np.sin(t), 0 * t]), name="p")
    s = np.asarray(scene.data("p").point_data["s"])
    np.testing.assert_allclose(s, np.arange(n + 1) * 2 * radius * np.sin(np.pi / n), rtol=1e-12)


@pytest.mark.parametrize("kind", ["torus", "sphere", "plane", "cylinder", "cone"])
def test_surface_mesh_lies_on_the_surface(kind):
    """Every mesh point is on the surface (exact distance <= 1e-12 of its size); periodic seams and the
    sphere's poles are merged: torus (nu-1)(nv-1) points, sphere (nu-1)(nv-2)+2."""
    frame = sk.Frame((1.0, -2.0, 3.0), sk.rotation_about((1, 1, 0), 0.7))
    surface = {"torus": sk.Torus(8.0, 3.0, frame), "sphere": sk.Sphere(4.0, frame),
               "plane": sk.Plane(frame, u_range=(-2, 3), v_range=(0, 1)),
               "cylinder": sk.Cylinder(2.0, frame, v_range=(-1, 4)),
               "cone": sk.Cone(0.4, frame, v_range=(1, 5))}[kind]
    nu, nv = 40, 20
    scene = Scene()
    scene.add_surface(surface, name="s", resolution=(nu, nv))
    mesh = scene.data("s")
    assert surface.distance(np.asarray(mesh.points)).max() <= 1e-12 * surface.size
    expected = {"torus": (nu - 1) * (nv - 1), "sphere": (nu - 1) * (nv - 2) + 2,
                "cylinder": (nu - 1) * nv, "cone": (nu - 1) * nv}.get(kind, nu * nv)
    assert mesh.n_points == expected
    assert mesh.n_cells == (nu - 1) * (nv - 1)


@pytest.mark.parametrize("kind", ["torus", "sphere", "cylinder", "cone", "annulus"])
def test_face_mesh_covers_its_trims(kind):
    """A CAD face is meshed over its trims only: every mesh point on the surface and inside the face by the
    angles of the point (atan2, tests.oracles.ssi.face_margin), and the mesh reaches its edges (both ends of an
    angular range, a disc's rims)."""
    frame = sk.Frame((1.0, -2.0, 3.0), sk.rotation_about((1, 1, 0), 0.7))
    surface = {"torus": sk.Torus(8.0, 3.0, frame, u_range=(0.5, 4.0), v_range=(-1.0, 2.0)),
               "sphere": sk.Sphere(4.0, frame, u_range=(-1.0, 1.0), v_range=(0.2, 1.2)),
               "cylinder": sk.Cylinder(2.0, frame, v_range=(-1, 4), u_range=(2.0, 5.0)),
               "cone": sk.Cone(0.4, frame, v_range=(1, 5), u_range=(-0.5, 0.5)),
               "annulus": sk.Plane(frame, radius=3.0, inner_radius=1.0)}[kind]
    scene = Scene()
    scene.add_surface(surface, name="s", resolution=(40, 20))
    points = np.asarray(scene.data("s").points)
    assert surface.distance(points).max() <= 1e-12 * surface.size
    margin = face_margin(surface, to_local(surface, points))
    assert margin.min() >= -1e-9 * surface.size
    assert np.abs(margin).min() <= 1e-9 * surface.size          # on an edge
    if kind == "annulus":
        rho = np.hypot(*to_local(surface, points)[:, :2].T)
        assert rho.min() == pytest.approx(1.0) and rho.max() == pytest.approx(3.0)


def test_arrow_spans_point_to_point_plus_scaled_vector():
    scene = Scene()
    scene.add_arrows([[1.0, 2.0, 3.0]], [[2.0, 0.0, 0.0]], scale=3.0, name="a")
    bounds = np.asarray(scene.meshes()["a"].bounds)
    np.testing.assert_allclose(bounds[:2], [1.0, 7.0], rtol=1e-6)


def test_looper_links_have_the_drives_dimensions(motion):
    """Oracle: the drive's own lengths, and the looper tip of the motion."""
    drive = motion.drive
    for index in (0, 45, -1):
        links, joints = geo.looper_links(motion, index)
        length = {k: np.linalg.norm(v[1] - v[0]) for k, v in links.items()}
        assert abs(length["crank"] - drive.crank_radius) < 1e-9
        assert abs(length["coupler"] - drive.coupler_length) < 1e-9
        assert abs(length["rocker_arm"] - drive.rocker_length) < 1e-9
        np.testing.assert_allclose(links["looper"][-1], motion.looper_tip.position[index], atol=1e-9)
        np.testing.assert_allclose(joints[2], motion.ball_center[index], atol=1e-9)


def test_scene_without_surfaces_meshes_none(motion):
    bare = looper_scene(motion, 10)
    assert {"torus", "sphere"}.isdisjoint(bare.names)
    assert all(item.kind != "surface" for item in bare._items)
    full = looper_scene(motion, 10, surfaces=True, velocities=5)
    assert {"torus", "sphere", "ball_velocity", "tip_velocity"} <= set(full.names)
    assert full.data("ball_velocity").n_points == 5


def test_export_reads_back(tmp_path, pair):
    torus, sphere, curves = pair
    scene = Scene()
    scene.add_surface(sphere, name="sphere", resolution=(24, 12))
    scene.add_curve(curves[0], name="loop")
    n = scene.data("loop").n_points
    scene.export(tmp_path / "loop.vtp", name="loop")
    back = pyvista.read(tmp_path / "loop.vtp")
    assert back.n_points == n
    np.testing.assert_array_equal(np.asarray(back.point_data["s"]), np.asarray(scene.data("loop").point_data["s"]))
    scene.export(tmp_path / "scene.vtm")
    multi = pyvista.read(tmp_path / "scene.vtm")
    assert list(multi.keys()) == ["sphere", "loop"]
    assert multi["sphere"].n_points == scene.data("sphere").n_points and multi["loop"].n_points == n
    scene.export(tmp_path / "scene.vtm")                      # again: the blocks' folder is replaced
    assert pyvista.read(tmp_path / "scene.vtm")["loop"].n_points == n
    scene.export(tmp_path / "sphere.ply", name="sphere")
    assert pyvista.read(tmp_path / "sphere.ply").n_points == scene.data("sphere").n_points
    scene.export(tmp_path / "tubes.ply", tubes=True)
    meshes = scene.meshes()
    assert pyvista.read(tmp_path / "tubes.ply").n_points == sum(m.n_points for m in meshes.values())
    assert no_temporaries(tmp_path)


def test_screenshot_is_a_png_of_the_window(tmp_path, pair, testing_theme):
    scene = Scene(theme=testing_theme)
    scene.add_curve(pair[2][0])
    img = scene.screenshot(tmp_path / "c.png")
    from PIL import Image
    with Image.open(tmp_path / "c.png") as png:
        assert png.format == "PNG" and png.size == (400, 400)
    assert img.shape == (400, 400, 3) and img.std() > 5


def test_writes_are_atomic(tmp_path, pair, monkeypatch):
    """A write that fails half-way leaves no file (or the previous one) and no temporary."""
    scene = Scene(window_size=(64, 64))
    scene.add_curve(pair[2][0], name="c")
    target = tmp_path / "c.png"

    class Broken:
        def save(self, path, format=None):
            with open(path, "wb") as f:
                f.write(b"\x89PNG half")
            raise OSError("disk full")

    monkeypatch.setattr(scene_module, "_pil_image", lambda img: Broken())
    with pytest.raises(OSError, match="disk full"):
        scene.screenshot(target)
    assert not target.exists() and no_temporaries(tmp_path)
    target.write_bytes(b"old")
    with pytest.raises(OSError):
        scene.screenshot(target)
    assert target.read_bytes() == b"old"

    def broken_save(self, path, *args, **kwargs):
        with open(path, "w") as f:
            f.write("<VTKFile")
        raise OSError("disk full")

    monkeypatch.setattr(pyvista.PolyData, "save", broken_save)
    monkeypatch.setattr(pyvista.MultiBlock, "save", broken_save)
    for name in ("c.vtp", "c.vtm", "c.ply"):
        with pytest.raises(OSError):
            scene.export(tmp_path / name)
        assert not (tmp_path / name).exists()
    assert no_temporaries(tmp_path)


def test_bad_input_names_the_argument(pair):
    curve = pair[2][0]
    scene = Scene()
    with pytest.raises(ValueError, match="color_by"):
        scene.add_curve(curve, color_by="velocity")
    with pytest.raises(ValueError, match="speed"):
        scene.add_curve(curve, color_by="speed")
    with pytest.raises(ValueError, match="speed"):
        scene.add_curve(curve, color_by="speed", speed=np.ones(3))
    with pytest.raises(ValueError, match="curve"):
        scene.add_curve(np.ones((5, 2)))
    with pytest.raises(ValueError, match="curve.*row 1"):
        scene.add_curve([[0, 0, 0], [np.nan, 0, 0]])
    with pytest.raises(ValueError, match="vectors"):
        scene.add_arrows(np.zeros((3, 3)), np.zeros((2, 3)))
    with pytest.raises(ValueError, match="points"):
        scene.add_arrows(np.full((1, 3), np.inf), np.zeros((1, 3)))
    with pytest.raises(ValueError, match="scale"):
        scene.add_arrows(np.zeros((1, 3)), np.ones((1, 3)), scale=-1.0)
    with pytest.raises(ValueError, match="u_range"):
        scene.add_surface(sk.Plane())
    with pytest.raises(TypeError, match="surface must be a spatialkin surface .*got str"):
        scene.add_surface("torus")
    with pytest.raises(TypeError, match="one Curve .* a list of 2 Curves: add each one"):
        scene.add_curve(pair[2])
    with pytest.raises(ValueError, match="opacity"):
        scene.add_surface(pair[0], opacity=1.5)
    with pytest.raises(ValueError, match="resolution"):
        scene.add_surface(pair[0], resolution=(2, 10))
    scene.add_curve(curve, name="c")
    with pytest.raises(ValueError, match="name"):
        scene.add_curve(curve, name="c")
    with pytest.raises(ValueError, match="path"):
        scene.screenshot("picture.jpg")
    with pytest.raises(ValueError, match="path"):
        scene.export("scene.stl")
    with pytest.raises(ValueError, match="index"):
        looper_scene(_motion_of_three(), index=3)
    with pytest.raises(ValueError, match="velocities"):
        looper_scene(_motion_of_three(), velocities=1.5)
    with pytest.raises(ValueError, match="window_size"):
        Scene(window_size=(0, 10))


def _motion_of_three():
    from spatialkin.mechanisms import LooperDrive
    return LooperDrive.reference().solve([0.0, 1.0, 2.0])


def test_labelled_looper_scene_names_joints_links_and_paths(motion, testing_theme):
    """labels=True: one label per joint, the tip, each named link and each path, placed exactly at those
    points (oracle: geometry.looper_links); a colour bar per path in m/s (speeds = |v| x 1e-3 for mm)."""
    from spatialkin.render import geometry as geo
    from spatialkin.render.looper import JOINT_NAMES, LINK_NAMES, TIP_NAME
    scene = looper_scene(motion, 30, labels=True, unit="mm", title="t", theme=testing_theme)
    assert scene.title == "t" and scene.axes
    names = scene.data("names")
    labels = scene._item("names").style["labels"]
    assert labels[:4] == list(JOINT_NAMES) and TIP_NAME in labels and set(LINK_NAMES.values()) <= set(labels)
    links, joints = geo.looper_links(motion, 30)
    np.testing.assert_allclose(names.points[1:4], joints[1:4], rtol=0, atol=1e-12)
    np.testing.assert_allclose(names.points[4], links["looper"][-1], rtol=0, atol=1e-12)
    ball = scene._item("ball_path").style
    assert "m/s" in ball["bar_title"] and ball["bar_position"] is not None
    np.testing.assert_allclose(scene.data("ball_path").point_data["speed"],
                               1e-3 * np.linalg.norm(motion.ball_velocity, axis=1), rtol=1e-15)
    img = scene.image()
    assert img.shape[:2] == (400, 400) and img.std() > 5.0


def test_path_with_gaps_is_drawn_in_pieces():
    """polyline(points, breaks): one line per piece, none across a break (oracle: the cell sizes)."""
    from spatialkin.render.scene import polyline
    pts = np.random.default_rng(1).normal(size=(10, 3))
    lines = polyline(pts, breaks=[4, 9]).lines          # pieces 0-3, 4-8, and 9 alone (left out)
    assert list(lines) == [4, 0, 1, 2, 3, 5, 4, 5, 6, 7, 8]
    assert list(polyline(pts).lines) == [10, *range(10)]


def test_labels_need_one_text_per_point():
    scene = Scene()
    with pytest.raises(ValueError, match="labels"):
        scene.add_labels(np.zeros((2, 3)), ["one"])
