"""Vessel centerlines from a volume: the VesselCenterline filter (voxel-coding Q-skeleton)."""

from paraview import servermanager, simple

__all__ = ["ExtractCenterlines"]


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

    The vessel mask is ``lower <= intensity <= upper``; ``lower`` defaults to the middle of the
    volume's intensity range (half maximum on a dark background), ``upper`` to no limit.
    ``seed`` (x, y, z in world mm) keeps only the vessel tree connected to that point; without
    it every component larger than ``MinimumComponentSize`` voxels is kept. Other keyword
    arguments set the filter's properties (MinimumBranchLength, SmoothingWindow, UseVesselness,
    ...). The output is one polyline per path with point arrays such as ``Radius`` (mm); pass the
    filter to ``HapticSession``/``logic().Bind()``."""
    volume = volume or simple.GetActiveSource()
    if volume is None:
        raise ValueError("ExtractCenterlines: no volume given and no active source")
    source = servermanager.OutputPort(volume, port) if port else volume
    lo, hi = _scalar_range(source)
    params = dict(properties)
    params["Input"] = source
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
