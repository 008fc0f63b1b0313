"""Vessel centerlines from a volume: the VesselCenterline filter (voxel-coding Q-skeleton)."""

from paraview import servermanager, simple

from .connection import require_server_plugin

__all__ = ["ExtractCenterlines", "IntensityRangeUsed", "ExtractionMessage", "ShadingCorrection"]


def _scalar_range(port):
    port.UpdatePipeline()
    info = port.GetDataInformation()
    if info.GetDataSetType() != 6:  # VTK_IMAGE_DATA
        raise ValueError("ExtractCenterlines needs an image (vtkImageData), got %s"
                         % info.GetDataSetTypeAsString())
    scalars = info.GetPointDataInformation().GetAttributeInformation(0)  # SCALARS
    if info.GetNumberOfPoints() == 0 or scalars is None:
        raise ValueError("ExtractCenterlines: the image is empty or has no point scalars")
    return scalars.GetComponentRange(0)


def ExtractCenterlines(volume=None, seed=None, lower=None, upper=None, port=0,
                       registrationName=None, **properties):
    """Extracts the centerlines of the vessels in ``volume`` (a source proxy, default: the
    active source; output ``port``) with a VesselCenterline filter and returns that filter.

    With neither ``lower`` nor ``upper`` the filter estimates the vessel's intensity range
    (AutomaticIntensityRange): from the neighbourhood of ``seed`` (x, y, z in world mm, a point
    on a vessel) for a raw bright-on-dark angiogram, or from the whole volume without a seed; it
    keeps the seed's network and cuts its non-tubular parts off. A binary mask is thresholded at
    its midpoint. Read the range it used with ``IntensityRangeUsed(filter)`` and why an output is
    empty with ``ExtractionMessage(filter)``. ``lower``/``upper`` override the estimate: the
    vessel mask is then ``lower <= intensity <= upper``, ``lower`` defaulting to the middle of the
    volume's intensity range and ``upper`` to no limit. Without a seed every component larger
    than ``MinimumComponentSize`` voxels is kept. Other keyword arguments set the filter's
    properties (MinimumBranchLength, SmoothingWindow, ...). The output is one polyline per path
    with point arrays such as ``Radius`` (mm); pass the filter to
    ``HapticSession``/``logic().Bind()``."""
    volume = volume or simple.GetActiveSource()
    if volume is None:
        raise ValueError("ExtractCenterlines: no volume given and no active source")
    require_server_plugin("ExtractCenterlines")
    source = servermanager.OutputPort(volume, port) if port else volume
    lo, hi = _scalar_range(source)
    params = dict(properties)
    params["Input"] = source
    if lower is not None or upper is not None:
        params["AutomaticIntensityRange"] = 0
        params["LowerThreshold"] = float(lower) if lower is not None else 0.5 * (lo + hi)
        if upper is not None:
            params["UpperThreshold"] = float(upper)
    if seed is not None:
        seed = [float(v) for v in seed]
        if len(seed) != 3:
            raise ValueError("ExtractCenterlines: seed must be (x, y, z) in mm")
        params["UseSeedPoint"] = 1
        params["SeedPoint"] = seed
    if registrationName:
        params["registrationName"] = registrationName
    create = simple._create_func("VesselCenterline", servermanager.filters)
    active = simple.GetActiveSource()
    try:
        centerline = create(**params)
    finally:
        simple.SetActiveSource(active)
    centerline.UpdatePipeline()
    return centerline


def _field_data(filter_proxy):
    return servermanager.Fetch(filter_proxy).GetFieldData()


def IntensityRangeUsed(filter_proxy):
    """(lower, upper): the intensity range a VesselCenterline or VesselCandidateRegion filter
    used in its last run (estimated, or the override), or None before a run."""
    filter_proxy.UpdatePipeline()
    filter_proxy.UpdatePropertyInformation()
    info = filter_proxy.GetProperty("IntensityRangeUsedInfo")
    if info is not None and len(info) == 2:
        return (float(info[0]), float(info[1]))
    array = _field_data(filter_proxy).GetArray("IntensityRangeUsed")
    return (array.GetValue(0), array.GetValue(1)) if array is not None else None


def ExtractionMessage(filter_proxy):
    """Why the last run of a VesselCenterline or VesselCandidateRegion filter gave an empty
    output (for example "The seed is on background (...): pick a point on a vessel in the
    MIP."), or "" on success."""
    filter_proxy.UpdatePipeline()
    array = _field_data(filter_proxy).GetAbstractArray("ExtractionMessage")
    return array.GetValue(0) if array is not None and array.GetNumberOfValues() else ""


def ShadingCorrection(filter_proxy):
    """What the last automatic run of a VesselCenterline or VesselCandidateRegion filter did of
    the volume's smooth shading (its CorrectShading property, on by default): a dict with
    ``corrected`` (bool), ``gain_span`` ((lowest, highest) gain of the volume relative to the
    seed's, (1, 1) when not corrected) and ``message`` (for example "No shading correction: the
    fitted gain spans 1.04 (P95 / P5), under 1.10."); None when the run wrote none (the range
    given by hand)."""
    filter_proxy.UpdatePipeline()
    fields = _field_data(filter_proxy)
    corrected = fields.GetArray("ShadingCorrected")
    if corrected is None:
        return None
    span = fields.GetArray("ShadingGainSpan")
    text = fields.GetAbstractArray("ShadingMessage")
    return {"corrected": corrected.GetValue(0) != 0,
            "gain_span": (span.GetValue(0), span.GetValue(1)) if span is not None else (1.0, 1.0),
            "message": text.GetValue(0) if text is not None and text.GetNumberOfValues() else ""}
