#!/usr/bin/env python3
"""Check a PNG written by paraview/render.py.

    /usr/bin/python3 paraview/check_png.py IMAGE.png [--size W H]
        [--min-pixels N] [--min-span F] [--centroid-box X0 Y0 X1 Y1]
        [--time-text] [--min-grey N] [--max-grey N]

Checks, printing what it measured:
  * the image has the requested size (--size);
  * it is not blank: at least N "particle" pixels (--min-pixels, default
    50), i.e. coloured pixels (not background, not grey: the domain outline
    and the text are grey or black) in the plot area, which is the image
    without the legend strip on the right and the time annotation on top
    (the layout of render.py);
  * the particle colours span at least the fraction F of the colour map
    (--min-span): the legend's colour bar is read from the image and each
    particle pixel is matched to its nearest legend colour;
  * the centroid of the particle pixels lies in a box given in fractions of
    the image, origin lower left (--centroid-box 0 0 0.5 0.5 is the lower
    left quarter);
  * the time annotation is there (--time-text): dark text pixels in the
    strip above the plot area, left of the legend;
  * grey (wall) particles: the number of grey pixels in the plot area (not
    background, not coloured, not the black text) is at least --min-grey
    or at most --max-grey.

Needs numpy and VTK's Python modules (Debian: python3-paraview, so run it
with /usr/bin/python3 or pvpython).  Exit status 0 when every check passes,
1 otherwise.
"""
import argparse
import sys
sys.dont_write_bytecode = True   # keep the source tree clean

try:
    import numpy as np
    from vtkmodules.vtkIOImage import vtkPNGReader
    from vtkmodules.util.numpy_support import vtk_to_numpy
except ImportError as e:
    sys.exit("check_png.py: needs numpy and VTK's Python modules (%s); run "
             "it with /usr/bin/python3 from Debian (python3-paraview)" % e)

import os
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from render import Layout  # noqa: E402  (the layout render.py draws)
COLOURED = 40         # min channel spread of a particle pixel (grey < this)
GREY_SPREAD = 12      # max channel spread of a grey pixel
DARK = 100            # text pixels: every channel below this
MIN_TEXT_PIXELS = 15  # the time annotation has at least this many
BACKGROUND_TOL = 30   # max channel difference still counted as background


def read_png(path):
    r = vtkPNGReader()
    if not r.CanReadFile(path):
        raise SystemExit("check_png.py: %s is not a readable PNG" % path)
    r.SetFileName(path)
    r.Update()
    img = r.GetOutput()
    w, h, _ = img.GetDimensions()
    scalars = img.GetPointData().GetScalars()
    a = vtk_to_numpy(scalars).reshape(h, w, -1)[:, :, :3].astype(np.int32)
    return a[::-1]          # VTK stores rows bottom-up: make row 0 the top


def main(argv=None):
    ap = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0],
        epilog="See the module docstring for the details of each check.")
    ap.add_argument("png")
    ap.add_argument("--size", nargs=2, type=int, metavar=("W", "H"))
    ap.add_argument("--min-pixels", type=int, default=50)
    ap.add_argument("--min-span", type=float, default=None)
    ap.add_argument("--centroid-box", nargs=4, type=float,
                    metavar=("X0", "Y0", "X1", "Y1"))
    ap.add_argument("--time-text", action="store_true")
    ap.add_argument("--min-grey", type=int)
    ap.add_argument("--max-grey", type=int)
    a = ap.parse_args(argv)

    img = read_png(a.png)
    H, W = img.shape[:2]
    failures = []
    print("%s: %d x %d" % (a.png, W, H))
    if a.size and (W, H) != tuple(a.size):
        failures.append("size is %dx%d, expected %dx%d"
                        % (W, H, a.size[0], a.size[1]))

    # Background: the most common colour of the left margin column.
    column = img[:, 1, :]
    values, counts = np.unique(column, axis=0, return_counts=True)
    bg = values[np.argmax(counts)]
    print("background colour: %s" % list(bg))

    spread = img.max(axis=2) - img.min(axis=2)
    not_bg = np.abs(img - bg).max(axis=2) > BACKGROUND_TOL
    coloured = not_bg & (spread >= COLOURED)

    lay = Layout(W, H)
    legend_x = int(lay.legend_x * W)
    plot = np.zeros((H, W), bool)
    plot[int(round((1 - lay.annotation_y) * H)):, :legend_x] = True
    particles = coloured & plot
    n = int(particles.sum())
    print("particle pixels: %d (%.2f%% of the plot area)"
          % (n, 100.0 * n / plot.sum()))
    if n < a.min_pixels:
        failures.append("blank: %d particle pixels, expected at least %d"
                        % (n, a.min_pixels))

    if a.time_text:
        strip = np.zeros((H, W), bool)
        strip[:int(round((1 - lay.annotation_y) * H)), :legend_x] = True
        dark = (img.max(axis=2) < DARK) & strip
        print("time annotation: %d dark pixels above the plot area"
              % dark.sum())
        if dark.sum() < MIN_TEXT_PIXELS:
            failures.append("no time annotation: %d dark pixels above the "
                            "plot area, expected at least %d"
                            % (dark.sum(), MIN_TEXT_PIXELS))

    if a.min_grey is not None or a.max_grey is not None:
        grey = not_bg & (spread <= GREY_SPREAD) & (img.max(axis=2) >= DARK) \
            & plot
        g = int(grey.sum())
        print("grey pixels in the plot area: %d" % g)
        if a.min_grey is not None and g < a.min_grey:
            failures.append("%d grey pixels, expected at least %d"
                            % (g, a.min_grey))
        if a.max_grey is not None and g > a.max_grey:
            failures.append("%d grey pixels, expected at most %d"
                            % (g, a.max_grey))

    if n and a.centroid_box:
        rows, cols = np.nonzero(particles)
        cx = (cols.mean() + 0.5) / W
        cy = 1.0 - (rows.mean() + 0.5) / H
        x0, y0, x1, y1 = a.centroid_box
        print("centroid of particle pixels: (%.3f, %.3f) of the image "
              "(origin lower left)" % (cx, cy))
        if not (x0 <= cx <= x1 and y0 <= cy <= y1):
            failures.append("centroid (%.3f, %.3f) outside [%g, %g] x [%g, %g]"
                            % (cx, cy, x0, x1, y0, y1))

    if a.min_span is not None and n:
        # The colour bar: the legend column with the most distinct colours.
        legend = coloured.copy()
        legend[:, :legend_x] = False
        best, best_count = None, 0
        for c in range(legend_x, W):
            rows = np.nonzero(legend[:, c])[0]
            if len(rows) < 10:
                continue
            k = len(np.unique(img[rows, c], axis=0))
            if k > best_count:
                best, best_count = c, k
        if best is None or best_count < 16:
            failures.append("no colour legend found right of x = %d"
                            % legend_x)
        else:
            rows = np.nonzero(legend[:, best])[0]
            bar = img[rows, best]                 # top (max) to bottom (min)
            pix = img[particles]
            if len(pix) > 20000:
                pix = pix[np.linspace(0, len(pix) - 1, 20000).astype(int)]
            d = ((pix[:, None, :] - bar[None, :, :]) ** 2).sum(axis=2)
            nearest = d.argmin(axis=1)
            close = d[np.arange(len(pix)), nearest] <= 30 ** 2
            if close.sum() == 0:
                failures.append("no particle colour matches the legend")
            else:
                pos = 1.0 - nearest[close] / max(1, len(bar) - 1)
                lo, hi = np.percentile(pos, 1), np.percentile(pos, 99)
                span = hi - lo
                print("legend bar: column %d, %d pixels; particle colours "
                      "cover %.2f .. %.2f of the colour map (span %.2f)"
                      % (best, len(bar), lo, hi, span))
                if span < a.min_span:
                    failures.append("colours span %.2f of the colour map, "
                                    "expected at least %.2f"
                                    % (span, a.min_span))

    for f in failures:
        print("FAIL: " + f)
    if not failures:
        print("OK")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
