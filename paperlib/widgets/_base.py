"""Plumbing shared by the explorers: quiet control updates, callbacks, PNG figure, status line.

An explorer subclass sets ``widget``, ``image`` (an ipywidgets Image), ``status`` (an HTML
widget), ``times``, ``message``, ``error``, ``_dpi`` and ``_quiet_depth = 0``, and implements
``_draw()`` (a matplotlib Figure) and ``_summary_text()`` (the status lines).
"""

from __future__ import annotations

import html
import io
import math
import time
from contextlib import contextmanager
from pathlib import Path

from paperlib._checks import integer_at_least

#: Largest figure an explorer draws, in pixels (figsize width x height x dpi**2): 2**25, about 33 M.
MAX_FIGURE_PIXELS = 2**25


def figure_settings(figsize, dpi) -> tuple[tuple[float, float], int]:
    """``(figsize, dpi)`` of an explorer's figure, checked: a pair of positive inches and an int dpi >= 10.

    Raises a ValueError naming the parameter for anything else, or for a figure above
    :data:`MAX_FIGURE_PIXELS` pixels.
    """
    dpi = integer_at_least(dpi, "dpi", 10)
    try:
        width, height = (float(side) for side in figsize)
    except (TypeError, ValueError):
        raise ValueError(f"figsize must be a pair of numbers (inches), got {figsize!r:.60}") from None
    if not all(math.isfinite(side) and side > 0 for side in (width, height)):
        raise ValueError(f"figsize must be a pair of positive finite numbers (inches), got {figsize!r}")
    if width * height * dpi**2 > MAX_FIGURE_PIXELS:
        raise ValueError(f"figsize {figsize!r} at dpi {dpi} makes a figure above {MAX_FIGURE_PIXELS:,} pixels")
    return (width, height), dpi


def expanded_path(text, name: str) -> Path:
    """``Path(text).expanduser()``, or a ValueError naming ``name`` where ``~user`` is a user this machine
    does not know (pathlib raises RuntimeError there)."""
    try:
        return Path(text).expanduser()
    except RuntimeError:
        raise ValueError(f"{name} names the home of an unknown user, got {str(text)!r:.80}") from None


def check_file_root(file_root) -> Path | None:
    """The folder an explorer's file boxes are confined to, checked: None (anywhere) or an existing folder.

    Parameters
    ----------
    file_root : str, os.PathLike or None
        None lets the boxes name any path (a notebook on your own machine); a folder confines every
        path typed in them to that folder (a served app, :mod:`paperlib.apps`).

    Returns
    -------
    Path or None
        The folder, resolved (symbolic links followed), or None.
    """
    if file_root is None:
        return None
    if isinstance(file_root, bool) or not isinstance(file_root, (str, Path)):
        raise TypeError(f"file_root must be None, a str or a Path, got {type(file_root).__name__}")
    if not str(file_root).strip() or "\0" in str(file_root):
        raise ValueError(f"file_root must name a folder, got {str(file_root)!r:.80}")
    folder = expanded_path(file_root, "file_root").resolve()
    if not folder.is_dir():
        raise ValueError(f"file_root must be an existing folder, got {str(file_root)!r}")
    return folder


def user_path(text, file_root: Path | None, what: str) -> Path:
    """The path typed in a file box: anywhere without a file root, else inside it.

    With a root, a relative path is taken from the root, and a path that leaves it (an absolute
    path elsewhere, ``..``, a symbolic link pointing out) is refused: a served app must not read or
    write the server's other files.

    Parameters
    ----------
    text : str or os.PathLike
        What the box holds.
    file_root : Path or None
        From :func:`check_file_root`.
    what : str
        The box's label, for the messages ("SVG", "script path", ...).

    Returns
    -------
    Path
    """
    text = str(text).strip()
    if not text:
        raise ValueError(f"no path given: type one in the '{what}' box")
    if file_root is None:
        return expanded_path(text, f"the path in the '{what}' box")
    path = (file_root / text).resolve()
    if path != file_root and file_root not in path.parents:
        raise ValueError(f"the path {text!r} in the '{what}' box is outside the folder this app may use "
                         f"({file_root}): give a path inside it, or upload the file")
    return path


def uploaded_file(upload) -> tuple[str, bytes] | None:
    """Name and bytes of the file last chosen in an ipywidgets ``FileUpload`` (None if none)."""
    if not upload.value:
        return None
    chosen = upload.value[-1]
    return str(chosen["name"]), bytes(chosen["content"])


class ExplorerBase:
    """Behaviour common to every explorer of :mod:`paperlib.widgets` (see the module docstring)."""

    def _on_change(self, control, method) -> None:
        """Call ``method()`` when ``control``'s value changes, unless set inside :meth:`_quiet`."""
        control.observe(lambda change: None if self._quiet_depth else method(), names="value")

    @contextmanager
    def _quiet(self):
        """Set controls without triggering their callbacks."""
        self._quiet_depth += 1
        try:
            yield
        finally:
            self._quiet_depth -= 1

    def _repr_mimebundle_(self, **kwargs):
        return self.widget._repr_mimebundle_(**kwargs)

    def _show(self, began: float) -> None:
        """Draw the figure into the PNG image widget, then the status line; record the times."""
        t0 = time.perf_counter()
        self.figure = self._draw()
        buffer = io.BytesIO()
        self.figure.savefig(buffer, format="png", dpi=self._dpi)
        self.image.value = buffer.getvalue()
        self.times["draw"] = time.perf_counter() - t0
        self.times["total"] = time.perf_counter() - began
        self._show_status()

    def _show_status(self) -> None:
        """The summary lines, then the message in red (an error) or amber (a note)."""
        self.summary = self._summary_text()
        text = "<br>".join(html.escape(line) for line in self.summary.splitlines())
        if self.message:
            colour = "#b00020" if self.error is not None else "#a15c00"
            text += f"<br><span style='color:{colour}'>{html.escape(self.message).replace(chr(10), '<br>')}</span>"
        self.status.value = f"<div style='font-family:monospace;font-size:12px'>{text}</div>"


class CanvasDrawing:
    """Drawing with the mouse on an ipycanvas ``Canvas``: press, drag, release (or leave the canvas).

    A subclass sets ``canvas``, ``drawn_points = []`` and ``_stroke_active = False``, calls
    :meth:`_connect_canvas`, and implements ``_draw_canvas()`` (paint the whole canvas) and
    ``_drawing_finished()`` (what the released drawing does: become the target, be elaborated, ...).

    The canvas is painted only once a browser view of it has said it is ready (ipycanvas's
    ``client_ready`` event), and painted again for every view that connects later: a draw command sent
    before the page has the canvas fails in the page ("Cannot read properties of undefined"), as Voila
    showed while it executed the app, and a view that connects late would start blank.
    """

    _canvas_ready = False

    def _connect_canvas(self) -> None:
        """Route the canvas's mouse events to the handlers below; paint it when a view is ready."""
        self.canvas.on_client_ready(self._on_client_ready)
        self.canvas.on_mouse_down(self._on_mouse_down)
        self.canvas.on_mouse_move(self._on_mouse_move)
        self.canvas.on_mouse_up(self._on_mouse_up)
        self.canvas.on_mouse_out(self._on_mouse_out)

    def _on_client_ready(self) -> None:
        self._canvas_ready = True
        self._redraw_canvas()

    def _redraw_canvas(self) -> None:
        """Paint the whole canvas (:meth:`_draw_canvas`) if a view can receive it."""
        if self._canvas_ready:
            self._draw_canvas()

    def _on_mouse_down(self, x, y) -> None:
        """Start a new drawing (the previous one is forgotten)."""
        self.drawn_points, self._stroke_active = [(float(x), float(y))], True
        self._redraw_canvas()

    def _on_mouse_move(self, x, y) -> None:
        """Extend the drawing while the button is down (the new segment is drawn at once)."""
        if not self._stroke_active:
            return
        point = (float(x), float(y))
        if point == self.drawn_points[-1]:
            return
        previous = self.drawn_points[-1]
        self.drawn_points.append(point)
        if self._canvas_ready:
            self.canvas.stroke_style, self.canvas.line_width = "#1f77b4", 2
            self.canvas.stroke_line(*previous, *point)

    def _on_mouse_up(self, x, y) -> None:
        """End the drawing and hand it to :meth:`_drawing_finished`."""
        if not self._stroke_active:
            return
        self._on_mouse_move(x, y)
        self._stroke_active = False
        self._drawing_finished()

    def _on_mouse_out(self, x, y) -> None:
        """Leaving the canvas ends the drawing, as a release would."""
        self._on_mouse_up(x, y)

    def _pixels_to_units(self, points):
        """Canvas pixels (x right, y down) to the explorer's units (x right, y up) at ``self.canvas_scale``."""
        import numpy as np

        pixels = np.asarray(points, dtype=np.float64).reshape(-1, 2)
        return np.column_stack([pixels[:, 0], self.canvas.height - pixels[:, 1]]) * self.canvas_scale

    def _paint_drawing(self, canvas, *, close: bool) -> None:
        """The drawn polyline in blue; closed and lightly filled when ``close`` (a released outline)."""
        if len(self.drawn_points) < 2:
            return
        canvas.stroke_style, canvas.line_width = "#1f77b4", 2
        canvas.begin_path()
        canvas.move_to(*self.drawn_points[0])
        for point in self.drawn_points[1:]:
            canvas.line_to(*point)
        if close:
            canvas.close_path()
            canvas.fill_style = "rgba(31, 119, 180, 0.12)"
            canvas.fill()
        canvas.stroke()
