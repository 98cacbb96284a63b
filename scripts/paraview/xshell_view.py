"""Draws an xshell run with ParaView: run by pvpython or pvbatch (5.11).

Opens the run's series.pvd (the output folder of `xshell relax` and of
deployments: rods_*, frames_*, joints_* and solids_* step files, see README
"Outputs"), draws the rods as tubes, the material frames as arrows (d1, and
d2 when asked, at every edge's midpoint) and the joints as spheres, colours
them by a point or cell array with a colour bar titled with the array's unit,
and saves a PNG of one step, or an animation of the whole series.

  pvpython scripts/paraview/xshell_view.py out/grid_gravity --out grid.png
  pvpython scripts/paraview/xshell_view.py out/grid_gravity --color curvature \\
      --step 0 --frames d1 d2 --out first.png
  pvpython scripts/paraview/xshell_view.py out/grid_gravity --animation grid.avi

Rendering needs an X display (Debian's ParaView renders through GLX): on a
machine without one, run it under `xvfb-run -a`.

Exit statuses (as the xshell program's): 0 written, 2 invalid input (no
series.pvd, a step or array that the run does not have: the message lists
what there is), 4 the picture could not be written.
"""

import argparse
import json
import math
import os
import re
import sys

PARTS = ("rods", "frames", "joints")
VIEWS = {  # camera direction (from the focal point to the eye) and up, as `xshell render`
    "iso": ((1.0, -1.0, 0.8), (0.0, 0.0, 1.0)),
    "top": ((0.0, 0.0, 1.0), (0.0, 1.0, 0.0)),
    "front": ((0.0, -1.0, 0.0), (0.0, 0.0, 1.0)),
    "side": ((1.0, 0.0, 0.0), (0.0, 0.0, 1.0)),
}
STRESS_NAMES = {"N/mm^2": "MPa", "N/m^2": "Pa", "kN/m^2": "kPa", "MN/m^2": "MPa"}
ANIMATION_SUFFIXES = (".png", ".avi", ".ogv")
FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"  # fonts-dejavu-core, as `xshell render`


class InvalidInput(Exception):
    """The arguments name something the run does not have (exit status 2)."""


def parse_arguments(argv):
    parser = argparse.ArgumentParser(
        prog="xshell_view.py",
        description="Draw an xshell run (its series.pvd) with ParaView: rods as tubes, "
        "material frames as arrows, coloured by an array with a colour bar.",
    )
    parser.add_argument("run", help="the run's output folder, or its series.pvd")
    parser.add_argument("--out", help="PNG to write (default RUN/paraview.png)")
    parser.add_argument(
        "--color", default="bending_density",
        help='point or cell array to colour by (a vector by its magnitude); "" for one colour '
        "(default bending_density)",
    )
    parser.add_argument(
        "--step", default="last",
        help="step to draw: its index in the series (0 first, -1 last) or 'last' (default)",
    )
    parser.add_argument(
        "--frames", nargs="*", default=["d1"], choices=["d1", "d2"],
        help="material frame vectors drawn as arrows (default d1; none: --frames with no value)",
    )
    parser.add_argument("--frame-stride", type=int, default=1, help="an arrow every N edges (default 1)")
    parser.add_argument("--view", default="iso", choices=sorted(VIEWS), help="camera direction (default iso)")
    parser.add_argument("--width", type=int, default=1200, help="picture width in pixels (default 1200)")
    parser.add_argument("--height", type=int, default=800, help="picture height in pixels (default 800)")
    parser.add_argument(
        "--animation",
        help="write the whole series instead of one step: NAME.png (a picture per step, "
        "NAME.0000.png, ...), NAME.avi or NAME.ogv",
    )
    parser.add_argument("--fps", type=int, default=5, help="frames per second of a movie (default 5)")
    args = parser.parse_args(argv)
    if args.width < 16 or args.height < 16:
        parser.error("--width and --height must be at least 16")
    if args.frame_stride < 1:
        parser.error("--frame-stride must be at least 1")
    if args.animation and not args.animation.lower().endswith(ANIMATION_SUFFIXES):
        parser.error("--animation must end in " + ", ".join(ANIMATION_SUFFIXES))
    return args


def series_file(run):
    path = os.path.join(run, "series.pvd") if os.path.isdir(run) else run
    if not os.path.isfile(path):
        raise InvalidInput("no series %s (give a run's output folder or its series.pvd)" % path)
    return path


def unit_names(folder):
    """The configuration's unit names ({'length': 'm', 'force': 'N'}) from summary.json."""
    try:
        with open(os.path.join(folder, "summary.json")) as f:
            units = json.load(f).get("configuration", {}).get("units", {})
    except (OSError, ValueError, AttributeError):
        return {}
    return {k: v for k, v in units.items() if isinstance(v, str)} if isinstance(units, dict) else {}


def unit_label(dimension, names):
    """'force/length^2' in the configured names ('N/m^2' is 'Pa'), as io/unit_names.hpp."""
    label = re.sub(r"\w+", lambda m: names.get(m.group(0), m.group(0)) if m.group(0) in ("length", "force")
                   else m.group(0), dimension)
    return STRESS_NAMES.get(label, label)


def array_unit(data, name):
    """The unit that the field data 'units' ("NAME=UNIT" values) of `data` gives `name`."""
    units = data.GetFieldData().GetAbstractArray("units") if data else None
    if units is None:
        return ""
    for i in range(units.GetNumberOfValues()):
        key, _, unit = units.GetValue(i).partition("=")
        if key == name:
            return unit
    return ""


def series_steps(pvd):
    """The series' times (sorted) and the names of its parts ('rods', 'frames', ...)."""
    import xml.etree.ElementTree as ElementTree

    try:
        entries = ElementTree.parse(pvd).getroot().iter("DataSet")
        entries = [(float(e.get("timestep", "0")), e.get("name", "")) for e in entries]
    except (ElementTree.ParseError, ValueError) as error:
        raise InvalidInput("%s: not a ParaView collection (%s)" % (pvd, error))
    if not entries:
        raise InvalidInput("%s lists no step (the run wrote none yet)" % pvd)
    return sorted({t for t, _ in entries}), {name for _, name in entries}


def chosen_step(step, times):
    """The index in `times` of --step ('last', or an index, negative from the end)."""
    if step == "last":
        return len(times) - 1
    try:
        index = int(step)
    except ValueError:
        raise InvalidInput("--step %r: give an index or 'last'" % step)
    if not -len(times) <= index < len(times):
        raise InvalidInput("--step %d: the series has %d steps (0 to %d)" % (index, len(times), len(times) - 1))
    return index % len(times)


class Scene:
    """The ParaView pipeline: a block of the .pvd per part, tubes, arrows, spheres."""

    def __init__(self, pvd, parts, time, args):
        from paraview import simple as pv

        self.pv = pv
        self.reader = pv.PVDReader(FileName=pvd)
        self.blocks = {p: pv.ExtractBlock(Input=self.reader, Selectors=["/Root/" + p]) for p in PARTS if p in parts}
        if "rods" not in self.blocks:
            raise InvalidInput("%s has no rods files" % pvd)
        rods = self.merged("rods", time)
        bounds = rods.GetDataInformation().GetBounds()
        self.bounds = bounds
        self.diagonal = max(sum((bounds[2 * i + 1] - bounds[2 * i]) ** 2 for i in range(3)) ** 0.5, 1e-12)
        self.sources = {"rods": pv.Tube(Input=self.blocks["rods"], Radius=0.004 * self.diagonal, NumberofSides=16)}
        if "frames" in self.blocks:
            length = self.arrow_length(time)
            for vector in args.frames:
                self.sources[vector] = pv.Glyph(
                    Input=self.blocks["frames"], GlyphType="Arrow", OrientationArray=["POINTS", vector],
                    ScaleArray=["POINTS", "No scale array"], ScaleFactor=length,
                    GlyphMode="Every Nth Point", Stride=args.frame_stride)
        if "joints" in self.blocks:
            self.sources["joints"] = pv.Glyph(
                Input=self.blocks["joints"], GlyphType="Sphere", OrientationArray=["POINTS", "No orientation array"],
                ScaleArray=["POINTS", "No scale array"], ScaleFactor=0.024 * self.diagonal, GlyphMode="All Points")

    def merged(self, part, time):
        merged = self.pv.MergeBlocks(Input=self.blocks[part])
        merged.UpdatePipeline(time)
        return merged

    def arrow_length(self, time):
        """0.8 edge lengths (the longest edge's), so that neighbouring arrows do not touch."""
        frames = self.merged("frames", time)
        if "edge_length" in frames.PointData.keys():
            return 0.8 * frames.PointData["edge_length"].GetRange()[1]
        return 0.02 * self.diagonal

    def arrays(self, time):
        """{array name: (association, the part that has it)} over every drawn part."""
        found = {}
        for part in self.blocks:
            merged = self.merged(part, time)
            for association, arrays in (("CELLS", merged.CellData), ("POINTS", merged.PointData)):
                for name in arrays.keys():
                    if name != "Normals":
                        found.setdefault(name, (association, part))
        return found

    def unit(self, name, part, time):
        from paraview import servermanager

        return array_unit(servermanager.Fetch(self.merged(part, time)), name)


SOLID_COLORS = {"rods": (0.55, 0.6, 0.7), "d1": (0.9, 0.55, 0.0), "d2": (0.1, 0.6, 0.25), "joints": (0.3, 0.3, 0.3)}


def show(scene, view, color, times):
    """Shows every source, coloured by `color` where it has it; returns the colour map or None."""
    pv = scene.pv
    coloured = []
    for key, source in scene.sources.items():
        display = pv.Show(source, view)
        display.Specular = 0.2
        source.UpdatePipeline(times[0])
        association = next((a for a, data in (("POINTS", source.PointData), ("CELLS", source.CellData))
                            if color and color in data.keys()), None)
        if association is None:
            display.ColorArrayName = ["POINTS", ""]
            display.AmbientColor = display.DiffuseColor = SOLID_COLORS[key]
        else:
            pv.ColorBy(display, (association, color, "Magnitude"))
            coloured.append((source, association))
    if not coloured:
        return None
    lut = pv.GetColorTransferFunction(color)
    lut.ApplyPreset("Cool to Warm", True)
    lo, hi = float("inf"), -float("inf")
    for time in times:  # the range over every drawn step
        for source, association in coloured:
            source.UpdatePipeline(time)
            data = source.PointData if association == "POINTS" else source.CellData
            a, b = data[color].GetRange(-1)
            lo, hi = min(lo, a), max(hi, b)
    lut.RescaleTransferFunction(lo, hi if hi > lo else lo + 1e-12)
    lut.AutomaticRescaleRangeMode = "Never"
    return lut


def colour_bar(lut, view, title):
    bar = lut and __import__("paraview.simple", fromlist=["GetScalarBar"]).GetScalarBar(lut, view)
    if not bar:
        return
    bar.Title = title
    bar.ComponentTitle = ""
    bar.Orientation = "Horizontal"
    bar.WindowLocation = "Any Location"
    bar.Position = [0.2, 0.03]
    bar.ScalarBarLength = 0.6
    bar.ScalarBarThickness = 16
    bar.TitleColor = bar.LabelColor = [0.0, 0.0, 0.0]
    bar.TitleFontSize = bar.LabelFontSize = 16
    bar.TitleBold = 0
    if os.path.isfile(FONT):  # VTK's own font draws brackets as parentheses
        bar.TitleFontFamily = bar.LabelFontFamily = "File"
        bar.TitleFontFile = bar.LabelFontFile = FONT
    bar.RangeLabelFormat = bar.LabelFormat = "%.3g"
    bar.AddRangeLabels = 1
    bar.Visibility = 1


def place_camera(scene, view, name):
    direction, up = VIEWS[name]
    b = scene.bounds
    centre = [(b[2 * i] + b[2 * i + 1]) / 2 for i in range(3)]
    view.CameraFocalPoint = centre
    view.CameraPosition = [c + d * scene.diagonal for c, d in zip(centre, direction)]
    view.CameraViewUp = list(up)
    view.ResetCamera(True)  # the closest view that shows every point
    # A margin, and the drawing raised above the colour bar: the camera
    # backs off 15% and moves down by 5% of the picture's height.
    camera = view.GetActiveCamera()
    camera.Dolly(0.85)
    height = 2 * camera.GetDistance() * math.tan(math.radians(camera.GetViewAngle() / 2))
    shift = [-0.05 * height * u for u in camera.GetViewUp()]
    camera.SetFocalPoint(*[a + b for a, b in zip(camera.GetFocalPoint(), shift)])
    camera.SetPosition(*[a + b for a, b in zip(camera.GetPosition(), shift)])


def render(args):
    pvd = series_file(args.run)
    folder = os.path.dirname(os.path.abspath(pvd))
    times, parts = series_steps(pvd)
    index = chosen_step(args.step, times)
    scene = Scene(pvd, parts, times[index], args)
    arrays = scene.arrays(times[index])
    if args.color and args.color not in arrays:
        raise InvalidInput("no array %r in the run's %s files; arrays: %s"
                           % (args.color, ", ".join(sorted(scene.blocks)), ", ".join(sorted(arrays))))
    pv = scene.pv
    view = pv.CreateView("RenderView")
    try:
        return draw(scene, view, arrays, times, index, folder, args)
    finally:
        # Deleted before the interpreter's exit, which otherwise releases the
        # view's OpenGL context after others and fails (GLXBadContext, Xvfb).
        pv.Delete(view)


def draw(scene, view, arrays, times, index, folder, args):
    pv = scene.pv
    view.ViewSize = [args.width, args.height]
    view.OrientationAxesVisibility = 0
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    view.Background = [1.0, 1.0, 1.0]
    drawn = times if args.animation else [times[index]]
    lut = show(scene, view, args.color, drawn)
    if lut is not None:
        association, part = arrays[args.color]
        unit = scene.unit(args.color, part, times[index])
        colour_bar(lut, view, args.color + (" [%s]" % unit_label(unit, unit_names(folder)) if unit else ""))
    place_camera(scene, view, args.view)
    animation = pv.GetAnimationScene()
    animation.UpdateAnimationUsingDataTimeSteps()
    if args.animation:
        return save_animation(pv, view, args)
    animation.AnimationTime = times[index]
    out = args.out or os.path.join(folder, "paraview.png")
    check_writable(out)
    pv.SaveScreenshot(out, view, ImageResolution=[args.width, args.height])
    return written([out])


def save_animation(pv, view, args):
    check_writable(args.animation)
    pv.SaveAnimation(args.animation, view, ImageResolution=[args.width, args.height], FrameRate=args.fps)
    stem, suffix = os.path.splitext(args.animation)
    if suffix.lower() != ".png":
        return written([args.animation])
    folder = os.path.dirname(stem) or "."
    pictures = sorted(os.path.join(folder, f) for f in os.listdir(folder)
                      if re.fullmatch(re.escape(os.path.basename(stem)) + r"\.\d+\.png", f))
    return written(pictures)


class OutputError(Exception):
    """A picture could not be written (exit status 4)."""


def check_writable(path):
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder) or not os.access(folder, os.W_OK):
        raise OutputError("cannot write %s: no writable folder %s" % (path, folder))


def written(paths):
    if not paths or not all(os.path.isfile(p) and os.path.getsize(p) > 0 for p in paths):
        raise OutputError("ParaView did not write %s" % (", ".join(paths) or "any picture"))
    for path in paths[:3]:
        print("xshell_view: wrote %s" % path)
    if len(paths) > 3:
        print("xshell_view: ... %d pictures in all" % len(paths))
    return 0


def main(argv):
    args = parse_arguments(argv)
    try:
        return render(args)
    except InvalidInput as error:
        print("xshell_view: %s" % error, file=sys.stderr)
        return 2
    except OutputError as error:
        print("xshell_view: %s" % error, file=sys.stderr)
        return 4


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
