#!/usr/bin/python3
"""plot_force.py TRACE.npz FORCE.png -- the force a person feels along a VesselTouch trace.

Reads the .npz that HapticSession.SaveLog() writes (pvpython side) and plots, against time: the
force magnitude sent to the device, the signed force along the agent's on-screen travel (negative
pushes back as the vessel climbs toward the viewer, positive pulls on as it falls away) and the
agent's depth along the viewing direction. Runs with Debian's Python (/usr/bin/python3: NumPy,
matplotlib), which pvpython does not necessarily have.
"""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy  # noqa: E402


def main(trace, output):
    data = numpy.load(trace)
    time = data["time"] - data["time"][0]
    tracing = data["tracing"].astype(bool)
    depth = numpy.where(tracing, data["depth_mm"], numpy.nan)
    figure, (forces, depths) = plt.subplots(2, 1, sharex=True, figsize=(9, 6), dpi=100,
                                            gridspec_kw={"height_ratios": [3, 2]})
    forces.plot(time, data["force_magnitude"], color="0.35", lw=1.2, label="|force| (N)")
    forces.plot(time, data["force_along_travel"], color="tab:red", lw=1.2,
                label="force along the agent's travel (N): < 0 pushes back, > 0 pulls on")
    forces.axhline(0.0, color="black", lw=0.6)
    forces.set_ylabel("force (N)")
    forces.legend(loc="upper right", fontsize=8)
    forces.grid(alpha=0.3)
    depths.plot(time, depth, color="tab:blue", lw=1.2)
    depths.set_ylabel("agent depth (mm)\nlarger = farther")
    depths.set_xlabel("time (s)")
    depths.grid(alpha=0.3)
    # Shade where the agent was not tracing (exploring: no vessel under the cursor, no force law).
    edges = numpy.flatnonzero(numpy.diff(numpy.r_[0, (~tracing).astype(int), 0]))
    for begin, end in zip(edges[::2], edges[1::2]):
        for axis in (forces, depths):
            axis.axvspan(time[begin], time[end - 1], color="0.9", zorder=0)
    if len(edges):
        forces.text(time[edges[0]], 0.97, " exploring", transform=forces.get_xaxis_transform(),
                    va="top", fontsize=8, color="0.4")
    forces.set_title("VesselTouch trace: %.2f s, %d ticks, tracing %.0f %%"
                     % (time[-1], len(time), 100.0 * tracing.mean()))
    figure.tight_layout()
    figure.savefig(output)
    print("plot_force: wrote %s" % output)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__.splitlines()[0])
    main(sys.argv[1], sys.argv[2])
