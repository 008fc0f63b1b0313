"""VesselCenterline: a cancelled run keeps the output of the run before it, and a run with that run's
parameters again returns it without computing (issue 19 item 1: after a Cancel on a pvserver the
panel restores the previous parameters, and every rank returns its kept output at once).

Built in, the cancel is VTK's AbortExecute set at the run's first progress report (the filter
treats it as its cancel flag). Asserts: the cancelled run's output is empty with "Cancelled.";
the parameters set back give the previous paths, point for point, with GetLastRunPrecomputed()
(no computing); a third run with other parameters computes again; a cancelled run with no run
before it keeps nothing (the restored parameters compute).
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from vtouch_testing import Check, plugin_path  # noqa: E402

from paraview import simple  # noqa: E402

check = Check("VesselCenterline cancelled run keeps the previous output")
simple.LoadPlugin(plugin_path(), ns=globals())


def message(poly):
    a = poly.GetFieldData().GetAbstractArray("ExtractionMessage")
    return a.GetValue(0) if a is not None and a.GetNumberOfValues() else ""


def points(poly):
    return [poly.GetPoint(i) for i in range(poly.GetNumberOfPoints())]


def precomputed(filt):
    filt.UpdatePropertyInformation()
    return filt.GetPropertyValue("LastRunPrecomputedInfo") == 1


def cancelled_update(filt):
    algorithm = filt.GetClientSideObject()
    tag = algorithm.AddObserver("ProgressEvent", lambda o, e: o.SetAbortExecute(1))
    filt.UpdatePipeline()
    algorithm.RemoveObserver(tag)
    algorithm.SetAbortExecute(0)


phantom = VesselPhantom(Shape="Tree", Dimensions=[64, 64, 64],  # noqa: F821
                        NoiseStandardDeviation=0.0, OutputScalarType="Float")
filt = VesselCenterline(Input=phantom, AutomaticIntensityRange=0, LowerThreshold=550.0)  # noqa: F821
algorithm = filt.GetClientSideObject()
filt.UpdatePipeline()
previous = algorithm.GetOutput()
paths, previous_points = previous.GetNumberOfLines(), points(previous)
check.true(paths > 0, "the first run finds paths (%d)" % paths)

filt.LowerThreshold = 500.0
cancelled_update(filt)
out = algorithm.GetOutput()
check.true(out.GetNumberOfLines() == 0 and message(out) == "Cancelled.",
           "its output is empty with 'Cancelled.' (%d lines, %r)"
           % (out.GetNumberOfLines(), message(out)))

filt.LowerThreshold = 550.0
filt.UpdatePipeline()
out = algorithm.GetOutput()
check.true(precomputed(filt),
           "the first run's parameters again return its kept output without computing")
check.true(message(out) == "", "that run is not cancelled (%r)" % message(out))
check.equal(out.GetNumberOfLines(), paths, "the previous paths are back")
check.true(points(out) == previous_points, "point for point")

filt.LowerThreshold = 560.0
filt.UpdatePipeline()
check.true(not precomputed(filt), "other parameters compute again")
check.true(algorithm.GetOutput().GetNumberOfLines() > 0, "and find paths")

# Nothing before the cancelled run: nothing kept.
fresh = VesselCenterline(Input=phantom, AutomaticIntensityRange=0, LowerThreshold=500.0)  # noqa: F821
cancelled_update(fresh)
check.true(message(fresh.GetClientSideObject().GetOutput()) == "Cancelled.",
           "a first run cancelled")
fresh.LowerThreshold = 550.0
fresh.UpdatePipeline()
check.true(not precomputed(fresh),
           "with no run before it, the next run computes")
check.equal(fresh.GetClientSideObject().GetOutput().GetNumberOfLines(), paths,
            "and finds the same paths")

check.finish()
