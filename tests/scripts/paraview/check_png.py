"""Checks a picture of scripts/paraview/xshell_view.py (run by pvpython):

  check_png.py PICTURE WIDTH HEIGHT [--no-bar]

its size; that over MIN_DRAWN of the pixels above the colour bar's band (the
bottom 15% of the picture) are not the white background; and, unless
--no-bar, that a row of that band holds the colour bar: strongly blue pixels
(Cool to Warm's low end) left of strongly red ones (its high end), each over
10% of the width. Prints what it measured; exit status 1 on a failed check.
"""

import sys

from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

MIN_DRAWN = 0.02


def pixels(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    array = vtk_to_numpy(image.GetPointData().GetScalars())
    # VTK's rows go bottom to top: row 0 is the picture's bottom row.
    return width, height, array.reshape(height, width, -1)[:, :, :3].astype(int)


def main(path, width, height, bar):
    w, h, rgb = pixels(path)
    failures = []
    if (w, h) != (width, height):
        failures.append("size %dx%d, expected %dx%d" % (w, h, width, height))
    band = int(0.15 * h)
    drawing = rgb[band:]
    drawn = (drawing.min(axis=2) < 235).mean()
    print("check_png: %s %dx%d, %.1f%% of the pixels above the bar's band drawn" % (path, w, h, 100 * drawn))
    if drawn < MIN_DRAWN:
        failures.append("%.2f%% drawn, under %.0f%%" % (100 * drawn, 100 * MIN_DRAWN))
    if bar:
        best = (0, 0, 0)
        for row in rgb[:band]:
            r, b = row[:, 0], row[:, 2]
            blue, red = (b - r > 80).nonzero()[0], (r - b > 80).nonzero()[0]
            if len(blue) and len(red) and blue.mean() < red.mean():
                best = max(best, (min(len(blue), len(red)), len(blue), len(red)))
        print("check_png: colour bar row: %d blue and %d red pixels (blue on the left)" % best[1:])
        if best[0] < 0.1 * w:
            failures.append("no colour bar row with over %d blue and red pixels" % (0.1 * w))
    for failure in failures:
        print("check_png: FAILED: " + failure)
    return 1 if failures else 0


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if a != "--no-bar"]
    sys.exit(main(args[0], int(args[1]), int(args[2]), "--no-bar" not in sys.argv))
