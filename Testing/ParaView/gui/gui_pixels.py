"""Colour counts in captures of the render view, for the driven GUI tests: what VesselTouch draws
over the grey MIP has colours no grey (and no view background) has."""

import numpy
from PIL import Image


def _rgb(png):
    rgb = numpy.asarray(Image.open(png).convert("RGB")).astype(int)
    return rgb[..., 0], rgb[..., 1], rgb[..., 2]


def orange_pixels(png):
    """The centerlines' orange (the MIP's greys have R = G = B, the view's background is grey or
    blue-grey, the orientation axes are pure red, green and blue)."""
    r, g, b = _rgb(png)
    return int(numpy.count_nonzero((r > 170) & (g > 80) & (g < 200) & (b < 90) & (r - g > 40)))


def cyan_pixels(png):
    """The seed marker's cyan."""
    r, g, b = _rgb(png)
    return int(numpy.count_nonzero((r < 60) & (g > 60) & (b > 60) & (numpy.abs(g - b) < 40)))


def magenta_pixels(png):
    """Preview's translucent magenta region, over any grey (red and blue well above green)."""
    r, g, b = _rgb(png)
    return int(numpy.count_nonzero((r - g > 60) & (b - g > 50)))
