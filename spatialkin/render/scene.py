"""sk.render.Scene: what the caller asks to see - surfaces, traced curves, links, arrows - drawn off-screen by
pyvista, saved as PNG, or exported as VTK / PLY for other tools.

A Scene keeps each item as its data (a pyvista dataset of the caller's points and scalars, made when the
item is added) and turns it into drawn geometry (tubes, arrow glyphs, joint spheres) only when a picture or
a tube export is asked for, with sizes relative to the whole scene's extent. Nothing is meshed that is not
added.
"""
import os
import shutil
import tempfile

import numpy as np

from ..export import polylines
from .._lib.files import atomic_path
from ..tracing.curve.result import Curve
from .._lib.validation import check_choice, check_points, check_positive, check_range, check_vector
from . import geometry as geo
from . import labels as lab
from ._backend import pyvista

#: Default window (pixels) of a picture.
WINDOW_SIZE = (1024, 768)
#: Tube radius of curves and links, and arrow length, as fractions of the scene's extent (bounding-box
#: diagonal) when the caller gives no absolute size.
TUBE_FRACTION = 0.004
LINK_FRACTION = 0.008
JOINT_FRACTION = 0.018
ARROW_FRACTION = 0.12
#: Sides of a tube's cross-section, and the resolution of a joint sphere.
TUBE_SIDES = 16
JOINT_RESOLUTION = 16
#: Anti-aliasing of the default theme. Not multisampling: with translucent surfaces we use depth peeling,
#: and depth peeling on a multisampled off-screen buffer renders blank through Mesa's EGL.
ANTI_ALIASING = "ssaa"
#: Default opacity of a surface (translucent, so the curves on it show).
SURFACE_OPACITY = 0.3
#: Grid points of a surface closer than this (relative to its extent) are merged: periodic seams, poles.
SEAM_TOLERANCE = 1e-12
#: Colour modes of a curve.
COLOR_MODES = ("s", "speed", None)
#: Colours used in turn when the caller gives none.
PALETTE = ("#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#17becf")
#: Colours of the mechanism's parts.
LINK_COLOR, JOINT_COLOR, SHAFT_COLOR = "#4d4d4d", "#b8860b", "#9e9e9e"
#: Text: title and colour bars (pyvista's points), labels (VTK's font size, about its height in pixels), a
#: horizontal bar's size (fractions of the window) and ticks.
TITLE_FONT_SIZE, LABEL_FONT_SIZE, BAR_FONT_SIZE = 14, 16, 13
BAR_WIDTH, BAR_HEIGHT, BAR_LABELS, BAR_TITLE_SIZE = 0.38, 0.07, 5, 11
#: Colour bars placed by the scene: lower-left corner of the first, the step to the next one in a row (two a
#: row), and the height of a row (bar, its tick labels and its title above), as fractions of the window.
BAR_ORIGIN, BAR_STEP, BAR_ROW, BARS_PER_ROW = (0.05, 0.03), 0.5, 0.13, 2
#: Space kept between a bar's title and the next bar (fraction of the window's width); a longer title is made
#: smaller. Titles are text of VTK font size 2 x BAR_TITLE_SIZE (pyvista's points).
BAR_TITLE_GAP = 0.03
#: Placements of labels: set off their points clear of what is drawn (with leader lines), or at their points.
LABEL_PLACEMENTS = ("auto", "point")
#: Label boxes: opacity of their white background; spacing (pixels) of the drawn points they keep clear of;
#: margin (pixels) kept from the window's edges.
LABEL_BOX_OPACITY, OBSTACLE_STEP, LABEL_MARGIN = 0.8, 3.0, 6.0
#: Scale bar: longest length (fraction of the window's width), lower-left corner (fraction of the width;
#: pixels above the colour bars), tick height and line width (pixels).
SCALE_BAR_FRACTION, SCALE_BAR_X, SCALE_BAR_GAP, SCALE_BAR_TICK, SCALE_BAR_LINE = 0.22, 0.05, 10.0, 8.0, 3.0
#: Height (pixels) kept below the drawing for the scale bar: its gap, half its tick and its length's text.
SCALE_BAR_ROOM = SCALE_BAR_GAP + 0.5 * SCALE_BAR_TICK + 2.0 * LABEL_FONT_SIZE
#: Where the orientation marker goes (fractions of the window: x0, y0, x1, y1): lower right, above colour bars.
AXES_VIEWPORT = (0.82, 0.13, 1.0, 0.31)
#: File suffixes of screenshot() and export().
IMAGE_SUFFIXES = (".png",)
EXPORT_SUFFIXES = (".vtm", ".vtp", ".ply")
#: What the camera can be fitted to (Scene's fit).
FITS = ("all", "curves")
#: Name of the arc-length and speed arrays on a curve's data.
S_ARRAY, SPEED_ARRAY, VECTOR_ARRAY = "s", "speed", "vectors"


class Item:
    """One thing in a scene: its data (pyvista dataset) and how to draw it."""

    def __init__(self, name, kind, data, style):
        self.name, self.kind, self.data, self.style = name, kind, data, style


class Scene:
    """A picture of surfaces, traced curves, mechanism links and velocity / acceleration arrows.

    Parameters
    ----------
    window_size : (int, int), optional
        Pixels (width, height) of screenshots; default WINDOW_SIZE, or the theme's when a theme is given.
    theme : pyvista.themes.Theme, optional
        Look of the picture (background, multisampling, ...); default pyvista's document theme (white).
    camera_position : str or list, optional
        pyvista camera position: 'iso', 'xy', 'xz', ... or [position, focal point, view up]. Default 'iso'.
    zoom : float
        Camera zoom after fitting the scene (> 1 moves closer).
    off_screen : bool
        Render without a window (default); False lets ``plotter().show()`` open one.
    title : str, optional
        A title along the picture's upper edge.
    axes : bool
        Draw an orientation marker (the x, y, z axes, lower right).
    unit : str, optional
        The length unit of the coordinates (e.g. 'mm'): colour bars of arc length and the scale bar name it.
    scale_bar : bool
        Draw a scale bar of a round length (in `unit`), lower left; the view is then a parallel projection,
        so that the bar measures lengths anywhere in the picture (in planes facing the camera).
    focal_point : array_like (3,), optional
        The point the camera looks at (the scene fitted first, then the camera moved parallel to its view);
        default the middle of the scene.
    note : str, optional
        A line of small text in the upper-left corner, below the title (a key: what an arrow's length means),
        made smaller where it would not fit the window's width.
    fit : {'all', 'curves'} or sequence of str
        What the camera is fitted to: everything drawn (default), the curves alone (the surfaces around them
        cut by the picture's edges: intersection curves small beside their surfaces fill the picture), or the
        items of these names.

    Examples
    --------
    >>> import spatialkin as sk
    >>> from spatialkin.render import Scene
    >>> torus, sphere = sk.Torus(1.0, 0.4), sk.Sphere(1.0, sk.Frame((1.0, 0.0, 0.3)))
    >>> scene = Scene(fit="curves", unit="mm")
    >>> scene.add_surface(torus), scene.add_surface(sphere, opacity=0.3)
    ('surface0', 'surface1')
    >>> [scene.add_curve(curve, color_by="s") for curve in sk.intersect(torus, sphere)]
    ['curve0', 'curve1']
    >>> scene.screenshot("curves.png").shape        # writes the PNG; the picture (height, width, RGB)
    (768, 1024, 3)
    >>> scene.export("curves.vtm")                  # a multiblock for ParaView
    """

    def __init__(self, window_size=None, theme=None, camera_position="iso", zoom=1.0, off_screen=True, title=None,
                 axes=False, unit=None, scale_bar=False, focal_point=None, fit="all", note=None):
        if window_size is not None:
            try:
                w, h = (int(x) for x in window_size)
            except (TypeError, ValueError):
                raise ValueError(f"window_size must be a pair (width, height), got {window_size!r}") from None
            if min(w, h) <= 0:
                raise ValueError(f"window_size must be positive, got {window_size!r}")
            window_size = (w, h)
        self.window_size = window_size
        self.theme = theme
        self.camera_position = camera_position
        self.zoom = check_positive("zoom", zoom)
        self.off_screen = bool(off_screen)
        self.title = None if title is None else str(title)
        self.note = None if note is None else str(note)
        self.axes = bool(axes)
        self.unit = None if unit is None else str(unit)
        self.scale_bar = bool(scale_bar)
        self.focal_point = None if focal_point is None else check_vector("focal_point", focal_point, 3)
        if isinstance(fit, str):
            self.fit = check_choice("fit", fit, FITS)
        elif isinstance(fit, (list, tuple)) and fit and all(isinstance(name, str) for name in fit):
            self.fit = tuple(fit)
        else:
            raise ValueError(f"fit must be one of {FITS} or a sequence of item names, got {fit!r}")
        self._items = []

    def __repr__(self):
        size = "x".join(map(str, self.window_size or WINDOW_SIZE))
        return f"Scene({size}, items={self.names}" + (f", title={self.title!r}" if self.title else "") + ")"

    # --- what is in the scene ---------------------------------------------------------------------
    @property
    def names(self):
        """Names of the items, in the order they were added."""
        return [item.name for item in self._items]

    def data(self, name=None):
        """The data of an item (pyvista dataset: surface mesh, curve polyline with its 's' and 'speed'
        arrays, arrow points with their 'vectors'), or a dict of all of them by name."""
        if name is None:
            return {item.name: item.data for item in self._items}
        return self._item(name).data

    def _item(self, name):
        for item in self._items:
            if item.name == name:
                return item
        raise ValueError(f"name: no item {name!r} in the scene; it holds {self.names}")

    def _add(self, name, kind, data, style):
        if name is None:                           # the kind's own count: 'curve0' is the first curve added
            number = sum(item.kind == kind for item in self._items)
            while f"{kind}{number}" in self.names:
                number += 1
            name, style["label"] = f"{kind}{number}", f"{kind} {number}"
        name = str(name)
        style.setdefault("label", name)
        if name in self.names:
            raise ValueError(f"name: the scene already holds an item named {name!r}")
        if style.get("color") is None and kind != "links":
            style["color"] = PALETTE[len(self._items) % len(PALETTE)]
        self._items.append(Item(name, kind, data, style))
        return name

    # --- adding things ----------------------------------------------------------------------------
    def add_surface(self, surface, name=None, u_range=None, v_range=None, resolution=geo.SURFACE_RESOLUTION,
                    color=None, opacity=SURFACE_OPACITY):
        """Mesh a surface by its parametrisation ``surface.point(u, v)`` and add it (translucent).

        Parameters
        ----------
        surface : spatialkin.Surface
        u_range, v_range : (float, float), optional
            Parameter ranges to mesh; default the surface's own (the full turn of an angle, the trimmed
            range of a plane, cylinder or cone, which must then be finite).
        resolution : (int, int)
            Grid samples along u and v.
        opacity : float in (0, 1]

        Returns
        -------
        str : the item's name.
        """
        opacity = _check_opacity(opacity)
        grid = geo.surface_grid(surface, u_range, v_range, resolution)
        mesh = grid_mesh(grid).clean(tolerance=SEAM_TOLERANCE * max(1.0, float(np.ptp(grid))), absolute=True)
        return self._add(name, "surface", mesh, {"color": color, "opacity": opacity})

    def add_curve(self, curve, name=None, color_by="s", speed=None, radius=None, color=None, cmap="viridis",
                  clim=None, scalar_bar=True, bar_title=None, bar_position=None, breaks=(), chord_tol=None):
        """Add a traced curve (or any polyline) drawn as a tube.

        Parameters
        ----------
        curve : sk.Curve or array_like (N, 3)
            A traced curve (drawn by a dense polyline of its exact points, spaced by `chord_tol`, with their
            arc lengths) or points of a path (arc length then the cumulative chord length).
        color_by : {'s', 'speed', None}
            Colour the tube by arc length, by `speed`, or plainly (`color`).
        speed : array_like (N,), optional
            A scalar per point (e.g. |velocity| of the motion); needed for color_by='speed', kept as the
            'speed' array otherwise.
        radius : float, optional
            Tube radius (length); default TUBE_FRACTION of the scene's extent.
        clim : (float, float), optional
            Range of the colour map (share one between curves to compare them); default the curve's own.
        scalar_bar : bool
            Show a horizontal colour bar, titled above its tick labels with the curve's name ('curve 0' for the
            first curve added without one) and the quantity: 'curve 0: arc length s [mm]' (the scene's unit,
            or 'length unit' when it has none), 'curve 0: speed'.
        bar_title : str, optional
            The colour bar's title instead (give the quantity and its unit).
        bar_position : (float, float), optional
            Lower-left corner of the colour bar, as fractions of the window; by default the scene lines its
            bars up along the bottom, two to a row.
        breaks : sequence of int
            Indices of points that start a new piece (a path with gaps: nothing is drawn across them).
        chord_tol : float, optional
            Chord height of the polyline drawn for a traced curve (default 1e-6 of its extent).

        Returns
        -------
        str : the item's name.
        """
        check_choice("color_by", color_by, COLOR_MODES)
        if isinstance(curve, (list, tuple)) and curve and all(isinstance(c, Curve) for c in curve):
            raise TypeError(f"curve must be one Curve (or points (N, 3)), got a list of {len(curve)} Curves: add "
                            "each one (for c in curves: scene.add_curve(c))")
        if isinstance(curve, Curve):
            # a dense polyline spaced by the chord height, never the solver's steps
            (s, points, _), = polylines(curve, chord_tol)
            points = check_points("curve.points", points)
        else:
            points = check_points("curve", curve)
            s = geo.chord_length(points)
        if color_by == "speed" and speed is None:
            raise ValueError("speed must be given (one value per point) for color_by='speed'")
        data = polyline(points, breaks)
        data.point_data[S_ARRAY] = s
        if speed is not None:
            if isinstance(curve, Curve):         # given at the curve's own points: onto the dense polyline
                speed = np.interp(s, curve.s, check_vector("speed", speed, len(curve.s)))
            data.point_data[SPEED_ARRAY] = check_vector("speed", speed, len(points))
        style = {"color_by": color_by, "radius": check_positive("radius", radius, allow_none=True),
                 "color": color, "cmap": cmap, "clim": _check_clim(clim), "scalar_bar": bool(scalar_bar),
                 "bar_title": None if bar_title is None else str(bar_title),
                 "bar_position": None if bar_position is None else tuple(float(x) for x in bar_position)}
        return self._add(name, "curve", data, style)

    def add_labels(self, points, labels, name=None, color="black", font_size=LABEL_FONT_SIZE, placement="auto"):
        """Add text labels (names of joints or links) at points (N, 3), drawn always visible.

        Parameters
        ----------
        points : array_like (N, 3)
        labels : sequence of str (N,)
        font_size : int
            Height of the text (VTK's font size: about its height in pixels).
        placement : {'auto', 'point'}
            'auto': each label set off its point where it covers least of the curves, links and joints and
            no other label, joined to its point by a leader line (chosen in the picture, after the camera);
            'point': at its point.

        Returns
        -------
        str : the item's name.
        """
        points = check_points("points", points)
        labels = [str(x) for x in labels]
        if len(labels) != len(points):
            raise ValueError(f"labels must give one text per point ({len(points)}), got {len(labels)}")
        check_choice("placement", placement, LABEL_PLACEMENTS)
        style = {"labels": labels, "color": color, "font_size": int(check_positive("font_size", font_size)),
                 "placement": placement}
        return self._add(name, "labels", pyvista().PolyData(points), style)

    def add_arrows(self, points, vectors, scale=None, name=None, color=None):
        """Add arrows (velocity or acceleration glyphs) at points.

        Parameters
        ----------
        points, vectors : array_like (N, 3)
            Where the arrows start, and the vectors they show.
        scale : float, optional
            Arrow length per unit of vector (e.g. mm per mm/s); default: the longest arrow is ARROW_FRACTION
            of the scene's extent.

        Returns
        -------
        str : the item's name.
        """
        points = check_points("points", points)
        vectors = check_points("vectors", vectors, count=len(points))
        data = pyvista().PolyData(points)
        data.point_data[VECTOR_ARRAY] = vectors
        style = {"scale": check_positive("scale", scale, allow_none=True), "color": color}
        return self._add(name, "arrows", data, style)

    def add_looper(self, motion, index=0, name="looper"):
        """Add the looper drive's links and joints at one of the motion's crank angles.

        Parameters
        ----------
        motion : spatialkin.mechanisms.looper.drive.LooperMotion
        index : int
            Which of ``motion.crank_angle`` to draw.

        Returns
        -------
        str : the item's name (its data is a MultiBlock: one polyline per link, then the joints).
        """
        links, joints = geo.looper_links(motion, index)
        pv = pyvista()
        data = pv.MultiBlock()
        for key, pts in links.items():
            data[key] = polyline(pts)
        data["joints"] = pv.PolyData(joints)
        return self._add(name, "links", data, {})

    # --- drawing ----------------------------------------------------------------------------------
    def extent(self):
        """Diagonal of the bounding box of everything added (1 for an empty or point-like scene)."""
        boxes = [np.asarray(item.data.bounds, dtype=float).reshape(3, 2) for item in self._items]
        if not boxes:
            return 1.0
        lo = np.min([b[:, 0] for b in boxes], axis=0)
        hi = np.max([b[:, 1] for b in boxes], axis=0)
        diag = float(np.linalg.norm(hi - lo))
        return diag if diag > 0 else 1.0

    def meshes(self):
        """What is drawn, by name: surface meshes, curve tubes (with the curve's arrays), arrow glyphs, link
        tubes and joint spheres (a MultiBlock for the links)."""
        size = self.extent()
        return {item.name: _drawn(item, size) for item in self._items}

    def plotter(self, off_screen=None):
        """A pyvista Plotter holding the scene, camera set (off-screen as the scene says unless given);
        call .show() on it for a window, or see image()."""
        pv = pyvista()
        off_screen = self.off_screen if off_screen is None else bool(off_screen)
        kwargs = {"off_screen": off_screen, "theme": self.theme if self.theme is not None
                  else default_theme()}
        if self.window_size is not None or self.theme is None:
            kwargs["window_size"] = list(self.window_size or WINDOW_SIZE)
        plotter = pv.Plotter(**kwargs)
        size = self.extent()
        bars = self._bar_places()
        if not isinstance(self.fit, str) and not set(self.fit) <= set(self.names):
            raise ValueError(f"fit names items the scene does not have: "
                             f"{sorted(set(self.fit) - set(self.names))} (it has {self.names})")
        framed = []
        for item in self._items:
            mesh = _drawn(item, size)
            _draw(plotter, item, mesh, self, bars)
            if item.kind == "curve" if self.fit == "curves" else item.name in self.fit:
                framed.append(mesh.bounds)
        if any(item.kind == "surface" and item.style["opacity"] < 1 for item in self._items):
            plotter.ren_win.SetMultiSamples(0)      # see ANTI_ALIASING
            plotter.enable_depth_peeling()
        plotter.camera_position = self.camera_position
        if self.scale_bar:
            plotter.camera.parallel_projection = True
        if self.fit != "all" and framed:
            lows, highs = np.min(np.array(framed)[:, 0::2], axis=0), np.max(np.array(framed)[:, 1::2], axis=0)
            plotter.reset_camera(bounds=[x for pair in zip(lows, highs) for x in pair])
        else:
            plotter.reset_camera()
        if self.focal_point is not None:
            camera = plotter.camera
            shift = self.focal_point - np.asarray(camera.focal_point)
            camera.focal_point = tuple(self.focal_point)
            camera.position = tuple(np.asarray(camera.position) + shift)
            plotter.renderer.ResetCameraClippingRange()
        plotter.camera.zoom(self.zoom)
        width, height = plotter.window_size
        bottom = max([(y + BAR_HEIGHT) * height + 2.5 * BAR_TITLE_SIZE for _, y in bars.values()], default=0.0)
        top = height - (3.0 * TITLE_FONT_SIZE if self.title else 0.0)
        _into_band(plotter, bottom + (SCALE_BAR_ROOM if self.scale_bar else 0.0),
                   top - (LABEL_MARGIN + 3.0 * BAR_TITLE_SIZE if self.note else 0.0))
        if self.title:
            plotter.add_text(self.title, position="upper_edge", font_size=TITLE_FONT_SIZE, color="black")
        if self.axes:
            plotter.add_axes(line_width=3, labels_off=False, viewport=AXES_VIEWPORT)
        if self.scale_bar:
            bottom = _draw_scale_bar(plotter, self.unit, bottom)
        if self.note:
            size = 2 * BAR_TITLE_SIZE
            actor, (w, h) = _text(plotter, self.note, (LABEL_MARGIN, top - LABEL_MARGIN - 1.5 * size), size,
                                  name="note")
            room = width - 2 * LABEL_MARGIN
            if w > room:
                size = int(size * room / w)
                actor.GetTextProperty().SetFontSize(size)
            actor.SetPosition(LABEL_MARGIN, top - LABEL_MARGIN - 1.5 * size)
            top -= LABEL_MARGIN + 1.5 * size
        placed = [item for item in self._items if item.kind == "labels" and item.style["placement"] == "auto"]
        if placed:
            _place_labels(plotter, placed, self, (LABEL_MARGIN, bottom + LABEL_MARGIN, width - LABEL_MARGIN,
                                                  top - LABEL_MARGIN))
        return plotter

    def bar_title(self, name):
        """The colour-bar title of the curve `name`: its bar_title, else its name ('curve 0' for the first curve
        added unnamed) and the quantity it is coloured by, arc length with the scene's unit."""
        item = self._item(name)
        style = item.style
        if style.get("bar_title"):
            return style["bar_title"]
        if style["color_by"] == "s":
            return f"{style['label']}: arc length s [{self.unit or 'length unit'}]"
        return f"{style['label']}: {style['color_by']}"

    def _bar_places(self):
        """Lower-left corners (fractions of the window) of the colour bars shown, by title: the curve's own
        bar_position, else the next free place along the bottom (BARS_PER_ROW a row, rows upwards)."""
        places, count = {}, 0
        for item in self._items:
            if item.kind != "curve" or item.style["color_by"] is None or not item.style["scalar_bar"]:
                continue
            title = self.bar_title(item.name)
            if title in places:
                continue
            if item.style.get("bar_position") is not None:
                places[title] = item.style["bar_position"]
                continue
            row, column = divmod(count, BARS_PER_ROW)
            places[title] = (BAR_ORIGIN[0] + column * BAR_STEP, BAR_ORIGIN[1] + row * BAR_ROW)
            count += 1
        return places

    def image(self):
        """The picture as an array (height, width, 3) of uint8, rendered off-screen."""
        plotter = self.plotter(off_screen=True)
        try:
            return np.asarray(plotter.screenshot(None, return_img=True))
        finally:
            plotter.close()

    def _repr_png_(self):
        """PNG bytes: Jupyter shows a Scene returned from a cell as its off-screen picture."""
        import io
        buffer = io.BytesIO()
        _pil_image(self.image()).save(buffer, format="PNG")
        return buffer.getvalue()

    def screenshot(self, path):
        """Render off-screen and write a PNG, whole or not at all. Returns the image array."""
        _check_suffix(path, IMAGE_SUFFIXES)
        img = self.image()
        pil = _pil_image(img)
        with atomic_path(path) as tmp:
            pil.save(tmp, format="PNG")
        return img

    # --- export -----------------------------------------------------------------------------------
    def export(self, path, name=None, tubes=False):
        """Write the scene for other tools, whole or not at all.

        Parameters
        ----------
        path : str
            '.vtm' (VTK multiblock: one block per item, by name; VTK writes the blocks into a folder named
            like the file beside it), '.vtp' (VTK polydata) or '.ply' (one mesh: the item `name`, or all
            items merged when name is None; PLY keeps geometry and colours only).
        name : str, optional
            The one item to write.
        tubes : bool
            Write what is drawn (tubes, glyphs) instead of the data (curve polylines with their 's' and
            'speed' arrays, arrow points with their vectors).
        """
        suffix = _check_suffix(path, EXPORT_SUFFIXES)
        if not self._items:
            raise ValueError("the scene is empty: nothing to export")
        blocks = self.meshes() if tubes else self.data()
        if name is not None:
            blocks = {name: blocks[self._item(name).name]}
        pv = pyvista()
        if suffix == ".vtm":
            multi = pv.MultiBlock()
            for key, mesh in blocks.items():
                multi[key] = mesh
            write_multiblock(multi, path)
            return
        mesh = as_polydata(list(blocks.values()))
        with atomic_path(path) as tmp:
            mesh.save(tmp)


# --- helpers ----------------------------------------------------------------------------------------
def default_theme():
    """pyvista's document theme (white background, black text), no multisampling, SSAA anti-aliasing (FXAA is not supported off-screen by EGL)."""
    theme = pyvista().themes.DocumentTheme()
    theme.multi_samples = 0
    theme.anti_aliasing = ANTI_ALIASING
    return theme


def polyline(points, breaks=()):
    """A pyvista PolyData of points (N, 3) joined in order: one polyline, or one per piece when breaks lists
    the indices where a new piece starts (pieces of a single point are left out)."""
    pv = pyvista()
    data = pv.PolyData(np.asarray(points, dtype=float))
    edges = [0, *sorted(int(b) for b in breaks if 0 < int(b) < len(points)), len(points)]
    cells = [np.concatenate([[b - a], np.arange(a, b)]) for a, b in zip(edges[:-1], edges[1:]) if b - a > 1]
    if cells:
        data.lines = np.concatenate(cells)
    return data


def grid_mesh(grid):
    """A quad mesh (PolyData, float64 points) of a grid of points (nu, nv, 3); point (i, j) is i * nv + j."""
    nu, nv = grid.shape[:2]
    corner = (np.arange(nu - 1)[:, None] * nv + np.arange(nv - 1)[None, :]).ravel()
    quads = np.column_stack([np.full_like(corner, 4), corner, corner + nv, corner + nv + 1, corner + 1])
    return pyvista().PolyData(np.ascontiguousarray(grid.reshape(-1, 3), dtype=float), faces=quads.ravel())


def tube(data, radius, scalars=None):
    """The polyline `data` as a tube of the given radius, carrying its point arrays; a single point becomes
    a small sphere."""
    if data.n_lines == 0:
        return pyvista().Sphere(radius=radius, center=data.points[0], theta_resolution=JOINT_RESOLUTION,
                                phi_resolution=JOINT_RESOLUTION)
    return data.tube(radius=radius, n_sides=TUBE_SIDES, capping=True, scalars=scalars)


def arrows(data, scale):
    """Arrow glyphs at data's points along its 'vectors', length |vector| * scale."""
    pv = pyvista()
    glyphs = data.copy()
    glyphs.point_data["length"] = np.linalg.norm(glyphs.point_data[VECTOR_ARRAY], axis=1)
    return glyphs.glyph(orient=VECTOR_ARRAY, scale="length", factor=scale, geom=pv.Arrow())


def _drawn(item, size):
    """The geometry drawn for an item in a scene of the given extent."""
    style = item.style
    if item.kind in ("surface", "labels"):
        return item.data
    if item.kind == "curve":
        return tube(item.data, style["radius"] or TUBE_FRACTION * size)
    if item.kind == "arrows":
        scale = style["scale"]
        if scale is None:
            longest = float(np.max(np.linalg.norm(item.data.point_data[VECTOR_ARRAY], axis=1)))
            scale = ARROW_FRACTION * size / longest if longest > 0 else 1.0
        return arrows(item.data, scale)
    pv = pyvista()
    out = pv.MultiBlock()
    for key in item.data.keys():
        block = item.data[key]
        if key == "joints":
            out[key] = block.glyph(geom=pv.Sphere(radius=JOINT_FRACTION * size, theta_resolution=JOINT_RESOLUTION,
                                                  phi_resolution=JOINT_RESOLUTION), orient=False, scale=False)
        else:
            out[key] = tube(block, LINK_FRACTION * size * (0.5 if key.endswith("shaft") else 1.0))
    return out


def _draw(plotter, item, mesh, scene, bars):
    style = item.style
    if item.kind == "surface":
        plotter.add_mesh(mesh, color=style["color"], opacity=style["opacity"], smooth_shading=True,
                         split_sharp_edges=True, name=item.name)     # (flat at a spindle torus's or cone's apex)
    elif item.kind == "curve":
        mode = style["color_by"]
        if mode is None:
            plotter.add_mesh(mesh, color=style["color"], name=item.name)
        else:
            title = scene.bar_title(item.name)
            bar = {"title": title}
            if style["scalar_bar"]:
                x, y = bars[title]
                bar.update(position_x=x, position_y=y, width=BAR_WIDTH, height=BAR_HEIGHT, vertical=False,
                           title_font_size=BAR_FONT_SIZE, label_font_size=BAR_FONT_SIZE, n_labels=BAR_LABELS,
                           fmt="%.3g", color="black")
            plotter.add_mesh(mesh, scalars=mode, cmap=style["cmap"], clim=style["clim"],
                             show_scalar_bar=style["scalar_bar"], scalar_bar_args=bar, name=item.name)
            if style["scalar_bar"] and title not in plotter.actors:
                # VTK draws a horizontal bar's title over its tick labels: the title goes above, as text
                plotter.scalar_bars[title].SetTitle("")
                width, height = plotter.window_size
                room = (BAR_STEP - BAR_TITLE_GAP) * width         # a title never reaches the next bar's
                actor, (w, _) = _text(plotter, title, (x * width, (y + BAR_HEIGHT) * height),
                                      2 * BAR_TITLE_SIZE, name=title)
                if w > room:
                    actor.GetTextProperty().SetFontSize(int(2 * BAR_TITLE_SIZE * room / w))
    elif item.kind == "labels":
        if style["placement"] == "point":
            plotter.add_point_labels(mesh, style["labels"], font_size=style["font_size"], text_color=style["color"],
                                     point_size=0, shape_opacity=0.55, always_visible=True, name=item.name)
    elif item.kind == "arrows":
        plotter.add_mesh(mesh, color=style["color"], name=item.name)
    else:
        for key in mesh.keys():
            color = JOINT_COLOR if key == "joints" else SHAFT_COLOR if key.endswith("shaft") else LINK_COLOR
            plotter.add_mesh(mesh[key], color=color, smooth_shading=True, name=f"{item.name}/{key}")


def to_pixels(plotter, points):
    """Window pixels (N, 2) of points (N, 3) as the plotter's camera shows them (x right, y up from the lower
    left)."""
    width, height = plotter.window_size
    matrix = plotter.camera.GetCompositeProjectionTransformMatrix(width / height, -1.0, 1.0)
    m = np.array([[matrix.GetElement(i, j) for j in range(4)] for i in range(4)])
    h = np.column_stack([np.asarray(points, dtype=float).reshape(-1, 3), np.ones(len(points))]) @ m.T
    ndc = h[:, :2] / h[:, 3:]
    return np.column_stack([(ndc[:, 0] + 1.0) * 0.5 * width, (ndc[:, 1] + 1.0) * 0.5 * height])


def pixels_per_length(plotter):
    """Pixels per length unit at the camera's focal point (everywhere in a parallel projection)."""
    camera = plotter.camera
    height = plotter.window_size[1]
    if camera.parallel_projection:
        return height / (2.0 * camera.parallel_scale)
    return height / (2.0 * camera.distance * np.tan(np.radians(camera.view_angle) / 2.0))


def _into_band(plotter, low, high):
    """Shrink and move the view so that what filled the window's height fills the rows from low to high (pixels
    from the bottom) instead: the drawing clear of the colour bars and scale bar below it and of the title and
    note above it."""
    height = plotter.window_size[1]
    if not 0.0 < high - low < height:
        return
    camera = plotter.camera
    camera.zoom((high - low) / height)
    shift = (0.5 * (low + high) - 0.5 * height) / pixels_per_length(plotter)
    focal, position = np.asarray(camera.focal_point), np.asarray(camera.position)
    view = (focal - position) / np.linalg.norm(focal - position)
    up = np.asarray(camera.up, dtype=float)
    up = up - up.dot(view) * view
    up /= np.linalg.norm(up)
    camera.focal_point = tuple(focal - shift * up)
    camera.position = tuple(position - shift * up)
    plotter.renderer.ResetCameraClippingRange()


def _overlay_lines(plotter, segments, color="black", width=1.0):
    """Lines in window pixels drawn over everything: segments (K, 2, 2)."""
    pv = pyvista()
    from vtkmodules.vtkRenderingCore import vtkActor2D, vtkPolyDataMapper2D
    segments = np.asarray(segments, dtype=float).reshape(-1, 2, 2)
    points = np.column_stack([segments.reshape(-1, 2), np.zeros(2 * len(segments))])
    cells = np.column_stack([np.full(len(segments), 2), 2 * np.arange(len(segments)), 2 * np.arange(len(segments)) + 1])
    lines = pv.PolyData(points, lines=cells.ravel())
    mapper = vtkPolyDataMapper2D()
    mapper.SetInputData(lines)
    actor = vtkActor2D()
    actor.SetMapper(mapper)
    actor.GetProperty().SetColor(pv.Color(color).float_rgb)
    actor.GetProperty().SetLineWidth(width)
    plotter.add_actor(actor, reset_camera=False, pickable=False)
    return actor


def _text(plotter, text, position, font_size, color="black", box=False, name=None):
    """A text actor at a pixel position (lower-left corner), VTK font size `font_size`, on a translucent white
    box when asked; returns it with its (width, height) in pixels."""
    actor = plotter.add_text(text, position=tuple(int(round(x)) for x in position), color=color, name=name)
    prop = actor.GetTextProperty()
    prop.SetFontSize(int(font_size))
    if box:
        prop.SetBackgroundColor(1.0, 1.0, 1.0)
        prop.SetBackgroundOpacity(LABEL_BOX_OPACITY)
    bounds = [0.0] * 4
    actor.GetBoundingBox(plotter.renderer, bounds)
    return actor, (bounds[1] - bounds[0], bounds[3] - bounds[2])


def _draw_scale_bar(plotter, unit, bottom):
    """A bar of a round length (at most SCALE_BAR_FRACTION of the window's width) with end ticks and its length
    above it, lower left above `bottom` (pixels); returns the pixel height it reaches."""
    per_unit = pixels_per_length(plotter)
    width = plotter.window_size[0]
    length = lab.round_length(SCALE_BAR_FRACTION * width / per_unit)
    x0, y0 = SCALE_BAR_X * width, bottom + SCALE_BAR_GAP
    x1 = x0 + length * per_unit
    tick = SCALE_BAR_TICK
    _overlay_lines(plotter, [[(x0, y0), (x1, y0)], [(x0, y0), (x0, y0 + tick)], [(x1, y0), (x1, y0 + tick)]],
                   width=SCALE_BAR_LINE)
    text = f"{length:g} {unit}" if unit else f"{length:g} (length unit)"
    actor, (w, h) = _text(plotter, text, (x0, y0), LABEL_FONT_SIZE, name="scale_bar")
    actor.SetPosition(0.5 * (x0 + x1) - 0.5 * w, y0 + 0.5 * tick)
    return y0 + 0.5 * tick + h


def _obstacle_pixels(plotter, scene):
    """Pixels (M, 2) of what the scene draws that labels should keep clear of: curves, links, joints and arrows
    (each polyline densified to OBSTACLE_STEP pixels)."""
    out = [np.zeros((0, 2))]
    for item in scene._items:
        if item.kind == "curve":
            pieces = [item.data]
        elif item.kind == "links":
            pieces = [item.data[key] for key in item.data.keys()]
        elif item.kind == "arrows":
            tips = np.asarray(item.data.points) + np.asarray(item.data.point_data[VECTOR_ARRAY])
            out += [lab.densify(to_pixels(plotter, [a, b]), OBSTACLE_STEP) for a, b in zip(item.data.points, tips)]
            continue
        else:
            continue
        for piece in pieces:
            pixels = to_pixels(plotter, np.asarray(piece.points))
            if piece.n_lines == 0:
                out.append(pixels)
                continue
            lines = np.asarray(piece.lines)
            k = 0
            while k < len(lines):
                n = lines[k]
                out.append(lab.densify(pixels[lines[k + 1:k + 1 + n]], OBSTACLE_STEP))
                k += n + 1
    return np.vstack(out)


def _place_labels(plotter, items, scene, frame):
    """Draw labels items set off their points, all placed together (labels.place_labels, in the order added),
    with leader lines."""
    anchors, actors, sizes, colours = [], [], [], []
    for item in items:
        style = item.style
        anchors.append(to_pixels(plotter, np.asarray(item.data.points)))
        for k, text in enumerate(style["labels"]):
            actor, size = _text(plotter, text, (0, 0), style["font_size"], color=style["color"], box=True,
                                name=f"{item.name}/{k}")
            actors.append(actor)
            sizes.append(size)
            colours.append(style["color"])
    boxes, leaders = lab.place_labels(np.vstack(anchors), sizes, _obstacle_pixels(plotter, scene), frame)
    for actor, box in zip(actors, boxes):
        actor.SetPosition(box[0], box[1])
    for colour in dict.fromkeys(colours):
        segments = [leader for leader, c in zip(leaders, colours) if leader is not None and c == colour]
        if segments:
            _overlay_lines(plotter, segments, color=colour, width=1.0)


def as_polydata(meshes):
    """One PolyData from datasets (MultiBlocks flattened): the one itself, or all merged."""
    pv = pyvista()
    flat = list(_leaves(meshes, pv))
    if len(flat) == 1:
        return flat[0]
    return pv.merge(flat, merge_points=False).extract_surface(algorithm=None)


def _leaves(meshes, pv):
    for mesh in meshes:
        if isinstance(mesh, pv.MultiBlock):
            yield from _leaves([mesh[k] for k in mesh.keys()], pv)
        else:
            yield mesh


def write_multiblock(multi, path):
    """Save a MultiBlock as .vtm: the blocks go into the folder VTK names after the file, written first;
    the .vtm that lists them is renamed into place last, so it is whole or absent. A previous export's
    folder of the same name is replaced."""
    folder = os.path.dirname(os.path.abspath(path))
    base = os.path.basename(path)
    stem = os.path.splitext(base)[0]
    work = tempfile.mkdtemp(prefix=".tmp-", dir=folder)
    try:
        multi.save(os.path.join(work, base))
        blocks_dir, target_dir = os.path.join(work, stem), os.path.join(folder, stem)
        if os.path.isdir(blocks_dir):
            if os.path.isdir(target_dir):
                os.replace(target_dir, os.path.join(work, ".old"))
            os.replace(blocks_dir, target_dir)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(os.path.join(work, base), 0o666 & ~umask)
        os.replace(os.path.join(work, base), path)
    finally:
        shutil.rmtree(work, ignore_errors=True)


def _check_suffix(path, allowed):
    suffix = os.path.splitext(str(path))[1].lower()
    if suffix not in allowed:
        raise ValueError(f"path must end in one of {allowed}, got {str(path)!r}")
    return suffix


def _check_clim(clim):
    if clim is None:
        return None
    lo, hi = check_range("clim", clim)
    if not (np.isfinite(lo) and np.isfinite(hi)):
        raise ValueError(f"clim must be finite with min < max, got {clim!r}")
    return lo, hi


def _check_opacity(opacity):
    x = check_positive("opacity", opacity)
    if x > 1:
        raise ValueError(f"opacity must lie in (0, 1], got {opacity!r}")
    return x


def _pil_image(img):
    from PIL import Image
    return Image.fromarray(np.ascontiguousarray(img))
