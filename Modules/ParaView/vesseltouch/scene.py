"""The built-in default scene: the vessel phantom shown as a MIP in a render view."""

from paraview import simple

from .mip import ShowAsMIP

#: Default phantom of the main job: a bifurcating tree (seven vessels, three generations) that rises
#: toward and falls away from the viewer, in a 128^3 volume with mild noise.
DEFAULT_PHANTOM = dict(Shape="Tree", Dimensions=[128, 128, 128], NoiseStandardDeviation=10.0)


def _phantom_factory():
    """paraview.simple's VesselPhantom function. LoadPlugin(..., ns=globals()) adds the plugin's
    functions to the caller's namespace only, so make sure paraview.simple has them too."""
    if not hasattr(simple, "VesselPhantom"):
        simple._add_functions(vars(simple))  # the same refresh LoadPlugin performs
    if not hasattr(simple, "VesselPhantom"):
        raise RuntimeError("the VesselTouch plugin is not loaded")
    return simple.VesselPhantom


def OpenDefaultScene(view=None, **phantom_overrides):
    """Creates the default VesselPhantom (keyword arguments override its properties), shows its
    volume as a MIP on a black background and returns (phantom, representation)."""
    properties = dict(DEFAULT_PHANTOM)
    properties.update(phantom_overrides)
    phantom = _phantom_factory()(registrationName="VesselPhantom1", **properties)
    simple.SetActiveSource(phantom)
    view = view or simple.GetActiveViewOrCreate("RenderView")
    # An angiogram reads best as white vessels on black.
    view.UseColorPaletteForBackground = 0
    view.Background = [0.0, 0.0, 0.0]
    view.OrientationAxesVisibility = 1
    rep = ShowAsMIP(phantom, view)
    view.CameraPosition = [64.0, 64.0, 400.0]
    view.CameraFocalPoint = [64.0, 64.0, 64.0]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.ResetCamera()
    simple.Render(view)
    return phantom, rep
