"""Maximum-intensity projection of an image in a render view."""

from paraview import simple

# ParaView's Volume representation names only Composite, Isosurface and Slice blend modes;
# maximum intensity is blend mode 1, set on the property itself and named "Maximum Intensity" in the
# property's list (as the GUI plugin does) so that rep.BlendMode and traces tell the truth.
MAXIMUM_INTENSITY_BLEND = 1


def _name_maximum_intensity(rep):
    domain = rep.SMProxy.GetProperty("BlendMode").FindDomain("vtkSMEnumerationDomain")
    if domain is None:
        return
    values = [domain.GetEntryValue(i) for i in range(domain.GetNumberOfEntries())]
    if MAXIMUM_INTENSITY_BLEND not in values:
        domain.AddEntry("Maximum Intensity", MAXIMUM_INTENSITY_BLEND)


def _scalar_array(source, port):
    info = source.GetDataInformation(port)
    if info.GetDataSetType() != 6:  # VTK_IMAGE_DATA
        raise ValueError("ShowAsMIP needs an image (vtkImageData), got %s"
                         % info.GetDataSetTypeAsString())
    if info.GetNumberOfPoints() == 0:
        raise ValueError("ShowAsMIP: the image is empty (see the output messages)")
    extent = info.GetExtent()
    dimensions = [extent[2 * i + 1] - extent[2 * i] + 1 for i in range(3)]
    if min(dimensions) < 2:
        # A PNG or a single slice: its MIP is the image itself, and volume-renders very slowly.
        raise ValueError("ShowAsMIP needs a 3D volume; this is a 2D image (%d x %d x %d voxels)"
                         % tuple(dimensions))
    scalars = info.GetPointDataInformation().GetAttributeInformation(0)  # SCALARS
    if scalars is None or not scalars.GetName():
        raise ValueError("ShowAsMIP needs point scalars on the image")
    return scalars.GetName(), scalars.GetComponentRange(0)


def ShowAsMIP(source=None, view=None, port=0):
    """Shows output ``port`` of ``source`` (default: the active source) in ``view`` (default: the active render
    view) as a MIP: Volume representation, blend mode 1, grey colour map and a linear opacity
    ramp over the data range. Returns the representation."""
    source = source or simple.GetActiveSource()
    if source is None:
        raise ValueError("ShowAsMIP: no source given and no active source")
    view = view or simple.GetActiveViewOrCreate("RenderView")
    source.UpdatePipeline()
    name, (lo, hi) = _scalar_array(source, port)
    rep = simple.Show(simple.OutputPort(source, port), view)
    rep.SetRepresentationType("Volume")
    _name_maximum_intensity(rep)
    rep.SMProxy.GetProperty("BlendMode").SetElement(0, MAXIMUM_INTENSITY_BLEND)
    rep.UpdateVTKObjects()
    simple.ColorBy(rep, ("POINTS", name))
    lut = simple.GetColorTransferFunction(name)
    lut.ApplyPreset("Grayscale", True)
    lut.RescaleTransferFunction(lo, hi)
    pwf = simple.GetOpacityTransferFunction(name)
    pwf.Points = [lo, 0.0, 0.5, 0.0, hi, 1.0, 0.5, 0.0]
    pwf.RescaleTransferFunction(lo, hi)
    # A MIP is read on black, from the first frame.
    view.UseColorPaletteForBackground = 0
    view.Background = [0.0, 0.0, 0.0]
    _radiological_camera(source, port, view)
    view.ResetCamera()
    return rep


def _radiological_camera(source, port, view):
    """Patient images (VesselTouch's readers: OutputFrame LPS = 0, RAS = 1) open in the
    radiological axial view: seen from the feet (toward +z, superior), anterior up, the patient's
    left on the screen's right. A phantom keeps ParaView's default view."""
    prop = source.SMProxy.GetProperty("OutputFrame") if hasattr(source, "SMProxy") else None
    if prop is None:
        return
    ras = prop.GetElement(0) == 1
    bounds = source.GetDataInformation(port).GetBounds()
    centre = [0.5 * (bounds[2 * i] + bounds[2 * i + 1]) for i in range(3)]
    size = max(max(bounds[2 * i + 1] - bounds[2 * i] for i in range(3)), 1.0)
    view.CameraFocalPoint = centre
    view.CameraPosition = [centre[0], centre[1], centre[2] - 3.0 * size]
    view.CameraViewUp = [0.0, 1.0 if ras else -1.0, 0.0]


def BlendMode(rep):
    """The blend mode of a volume representation as an integer (1 = maximum intensity)."""
    return rep.SMProxy.GetProperty("BlendMode").GetElement(0)
