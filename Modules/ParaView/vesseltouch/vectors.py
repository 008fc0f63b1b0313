"""Small 3-vector helpers shared by the session's camera frame and the agent overlay."""

import math


def unit(v, error):
    """``v`` divided by its length; raises ``error`` (an exception) when ``v`` is zero or not
    finite."""
    n = math.sqrt(sum(c * c for c in v))
    if n == 0.0 or not math.isfinite(n):
        raise error
    return [c / n for c in v]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
