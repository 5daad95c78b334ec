"""Text in the pictures: colour-bar titles (the curve as the user knows it, the unit of s, clear of the tick
labels), labels set off their points clear of the drawing and of each other, the scale bar's length, and the
camera's focal point. Oracles: the titles' expected text, rectangle overlap, a projection of known lengths."""
import numpy as np
import pytest

from spatialkin.render import Scene, looper_scene
from spatialkin.render import labels as lab
from spatialkin.render import scene as scene_module
from spatialkin.render.looper import JOINT_NAMES


def box_of(plotter, actor):
    """(x0, y0, x1, y1) in pixels of a text actor as drawn."""
    x, y = actor.GetPosition()
    bounds = [0.0] * 4
    actor.GetBoundingBox(plotter.renderer, bounds)
    return np.array([x, y, x + bounds[1] - bounds[0], y + bounds[3] - bounds[2]])


def overlap(a, b):
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


def readme_scene(pair, theme, **scene_args):
    """The README's Scene example: two surfaces, then the curves coloured by arc length, none named."""
    torus, sphere, curves = pair
    scene = Scene(theme=theme, **scene_args)
    scene.add_surface(torus, resolution=(24, 12))
    scene.add_surface(sphere, opacity=0.2, resolution=(16, 8))
    for c in curves:
        scene.add_curve(c, color_by="s")
    return scene


def test_bar_titles_name_the_curves_and_the_unit_of_s(pair, testing_theme):
    """Curves added unnamed after two surfaces are 'curve 0' and 'curve 1' (counted among curves), the arc length
    in the scene's unit ('length unit' when it has none); a given name is used as it is."""
    scene = readme_scene(pair, testing_theme, unit="mm")
    assert scene.names == ["surface0", "surface1", "curve0", "curve1"]
    assert [scene.bar_title(n) for n in ("curve0", "curve1")] == ["curve 0: arc length s [mm]",
                                                                  "curve 1: arc length s [mm]"]
    assert readme_scene(pair, testing_theme).bar_title("curve1") == "curve 1: arc length s [length unit]"
    named = Scene(unit="cm")
    named.add_curve(pair[2][0], name="outer loop", color_by="s")
    named.add_curve(pair[2][1], name="inner", color_by="speed", speed=np.ones(len(pair[2][1])))
    assert named.bar_title("outer loop") == "outer loop: arc length s [cm]"
    assert named.bar_title("inner") == "inner: speed"


def test_bar_titles_are_drawn_above_their_tick_labels(pair, testing_theme):
    """In the picture each bar's own (VTK) title is empty and its title is a text whose box lies above the bar's
    box (tick labels included) and clear of the other bar and its title."""
    scene = readme_scene(pair, testing_theme, unit="mm")
    plotter = scene.plotter()
    try:
        titles = [scene.bar_title(n) for n in ("curve0", "curve1")]
        boxes = []
        for title in titles:
            bar = plotter.scalar_bars[title]
            assert bar.GetTitle() == ""
            text = box_of(plotter, plotter.actors[title])
            x, y = (np.asarray(bar.GetPositionCoordinate().GetValue()[:2]) * plotter.window_size)
            w, h = np.asarray(bar.GetPosition2Coordinate().GetValue()[:2]) * plotter.window_size
            assert text[1] >= y + h - 1.0, (title, text, (x, y, w, h))
            boxes.append((text, np.array([x, y, x + w, y + h])))
        (t0, b0), (t1, b1) = boxes
        assert not any(overlap(p, q) for p in (t0, b0) for q in (t1, b1))
    finally:
        plotter.close()


def test_place_labels_keeps_clear_of_points_and_of_each_other():
    """Three labels round a crowded point: boxes inside the frame, pairwise apart, none over a drawn point
    where there is room; a leader from each point to its box."""
    rng = np.random.default_rng(3)
    line = lab.densify([(50, 200), (350, 200)], 3.0)             # a horizontal path through the points
    anchors = np.array([(200.0, 200.0), (210.0, 200.0), (190.0, 200.0)])
    sizes = np.array([(80.0, 18.0), (60.0, 18.0), (70.0, 18.0)])
    boxes, leaders = lab.place_labels(anchors, sizes, line + rng.normal(0, 0.1, line.shape), (0, 0, 400, 400))
    assert np.all(boxes[:, :2] >= 0) and np.all(boxes[:, 2:] <= 400)
    assert not any(overlap(boxes[i], boxes[j]) for i in range(3) for j in range(i))
    for box in boxes:
        assert not np.any((line[:, 0] > box[0]) & (line[:, 0] < box[2]) & (line[:, 1] > box[1]) & (line[:, 1] < box[3]))
    for anchor, box, leader in zip(anchors, boxes, leaders):
        assert leader is not None and np.allclose(leader[0], anchor)
        np.testing.assert_allclose(leader[1], lab.nearest_on_box(box, anchor))


def test_round_length():
    assert [lab.round_length(x) for x in (0.99, 1.0, 3.7, 19.9, 20.0, 730.0)] == [0.5, 1.0, 2.0, 10.0, 20.0, 500.0]
    with pytest.raises(ValueError, match="longest"):
        lab.round_length(0.0)


def test_labelled_looper_picture_labels_do_not_collide(motion, testing_theme):
    """labels=True: every label drawn apart from the others, inside the window, none over a joint other than its
    own; a scale bar whose text is its round length in mm, and whose length in pixels is that length seen in the
    parallel projection (oracle: two points that far apart across the view, projected)."""
    scene = looper_scene(motion, 30, labels=True, unit="mm", theme=testing_theme, window_size=(600, 640))
    plotter = scene.plotter()
    try:
        labels = scene._item("names").style["labels"]
        boxes = [box_of(plotter, plotter.actors[f"names/{k}"]) for k in range(len(labels))]
        width, height = plotter.window_size
        for i, a in enumerate(boxes):
            assert a[0] >= 0 and a[1] >= 0 and a[2] <= width and a[3] <= height, labels[i]
            for j in range(i):
                assert not overlap(a, boxes[j]), (labels[i], labels[j])
        joints = scene_module.to_pixels(plotter, scene.data("names").points[:len(JOINT_NAMES)])
        for i, a in enumerate(boxes):
            inside = (joints[:, 0] > a[0]) & (joints[:, 0] < a[2]) & (joints[:, 1] > a[1]) & (joints[:, 1] < a[3])
            assert not np.any(np.delete(inside, i) if i < len(joints) else inside), labels[i]
        assert plotter.camera.parallel_projection
        text = plotter.actors["scale_bar"].GetInput()
        length = float(text.split()[0])
        assert text == f"{length:g} mm" and length == lab.round_length(length * 1.0000001)
        camera = plotter.camera
        view = np.asarray(camera.direction)
        across = np.cross(view, camera.up)
        across /= np.linalg.norm(across)
        ends = scene_module.to_pixels(plotter, np.array([camera.focal_point, camera.focal_point + length * across]))
        seen = np.linalg.norm(ends[1] - ends[0])
        np.testing.assert_allclose(seen, length * scene_module.pixels_per_length(plotter), rtol=1e-9)
        assert 0.05 * width < seen <= scene_module.SCALE_BAR_FRACTION * width + 1e-9
    finally:
        plotter.close()


def test_focal_point_is_the_middle_of_the_picture(pair, testing_theme):
    """focal_point: the camera looks at it, so it is drawn at the window's centre (to a pixel)."""
    torus, sphere, curves = pair
    point = curves[0].points[7]
    scene = Scene(theme=testing_theme, zoom=2.0, focal_point=point)
    scene.add_surface(torus, resolution=(24, 12))
    scene.add_surface(sphere, resolution=(16, 8))
    plotter = scene.plotter()
    try:
        np.testing.assert_allclose(scene_module.to_pixels(plotter, [point])[0], np.array(plotter.window_size) / 2,
                                   atol=1.0)
    finally:
        plotter.close()


def test_fit_curves_fills_the_picture_with_the_curves(pair, testing_theme):
    """fit='curves': the camera frames the curves alone, so their drawn points span most of the room above the
    colour bars (the README pair's loops are small beside a spindle torus: a fifth of the picture when the camera
    frames everything)."""
    torus, sphere, curves = pair
    points = np.vstack([c(np.linspace(0.0, c.length, 64)) for c in curves])
    spans = {}
    for fit in ("all", "curves"):
        plotter = readme_scene(pair, testing_theme, fit=fit).plotter()
        try:
            pixels = scene_module.to_pixels(plotter, points)
            spans[fit] = np.max(np.ptp(pixels, axis=0) / np.array(plotter.window_size))
            inside = (pixels >= 0).all() and (pixels <= np.array(plotter.window_size)).all()
        finally:
            plotter.close()
        assert inside
    assert spans["curves"] > 0.5 and spans["curves"] > 2.0 * spans["all"]
    with pytest.raises(ValueError, match="fit"):
        Scene(fit="surfaces")


def test_the_velocity_arrows_key_gives_their_scale_and_colours(motion, testing_theme):
    """looper_scene's note: the arrows' length per m/s (mm drive: the arrows' scale / 1e-3 m per mm), the ball
    centre's arrows in the blue of its path's colours, the tip's in the red; the note is drawn in the window."""
    from spatialkin.render.looper import ARROW_COLOURS
    scene = looper_scene(motion, 10, velocities=4, unit="mm", theme=testing_theme)
    scale = scene._item("tip_velocity").style["scale"]
    assert scene.note == f"velocity arrows: {scale / 1e-3:.3g} mm per m/s (C dark blue, T dark red)"
    assert [scene._item(n).style["color"] for n in ("ball_velocity", "tip_velocity")] == list(ARROW_COLOURS)
    plotter = scene.plotter()
    try:
        x0, y0, x1, y1 = box_of(plotter, plotter.actors["note"])
        assert 0 <= x0 and x1 <= plotter.window_size[0] and y1 <= plotter.window_size[1]
    finally:
        plotter.close()
    assert looper_scene(motion, 10, velocities=4, theme=testing_theme).note.startswith("velocity arrows: length = ")


def test_fit_names_the_items_framed(pair, testing_theme):
    torus, sphere, curves = pair
    scene = readme_scene(pair, testing_theme, fit=("curve0",))
    plotter = scene.plotter()
    plotter.close()
    with pytest.raises(ValueError, match="fit names items the scene does not have: \\['ring'\\]"):
        readme_scene(pair, testing_theme, fit=("ring",)).plotter()
    with pytest.raises(ValueError, match="fit must be one of"):
        Scene(fit=3)


def test_the_drawing_keeps_clear_of_the_bars_scale_bar_and_title(motion, testing_theme):
    """A labelled looper picture (the notebook's): every point of the links, the shaft axes and the two paths is
    drawn above the colour bars' titles and the scale bar's text, and below the title."""
    from spatialkin.render import geometry as geo
    scene = looper_scene(motion, 120, labels=True, unit="mm", window_size=(720, 760), title="crank angle 60 deg",
                         theme=testing_theme)
    links, joints = geo.looper_links(motion, 120)
    points = np.vstack([*links.values(), joints, motion.ball_center, motion.looper_tip.position])
    plotter = scene.plotter()
    try:
        pixels = scene_module.to_pixels(plotter, points)
        texts = [box_of(plotter, plotter.actors[scene.bar_title(name)]) for name in ("ball_path", "tip_path")]
        scale_bar = box_of(plotter, plotter.actors["scale_bar"])
        height = plotter.window_size[1]
    finally:
        plotter.close()
    below = max([y1 for _, _, _, y1 in texts] + [scale_bar[3]])
    assert pixels[:, 1].min() > below
    assert pixels[:, 1].max() < height - 2.0 * scene_module.TITLE_FONT_SIZE
