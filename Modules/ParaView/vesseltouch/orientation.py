"""Patient orientation labels (L/R, A/P, S/I) in a render view.

VesselTouch's readers give images in LPS millimetres (+x toward the patient's Left, +y Posterior,
+z Superior) or, with OutputFrame = RAS, in RAS (+x Right, +y Anterior, +z Superior). The labels
are billboard texts placed just outside the centre of each face of the image's world bounds, so
they stay right whatever the camera does::

    reader = OpenDataFile('angio.nii.gz')
    vesseltouch.ShowAsMIP(reader)
    vesseltouch.ShowPatientOrientation(reader)
"""

from paraview import simple

# World axis -> (label at the positive end, label at the negative end), per world frame.
_FRAMES = {
    "LPS": (("L", "R"), ("P", "A"), ("S", "I")),
    "RAS": (("R", "L"), ("A", "P"), ("S", "I")),
}
_NAME = "PatientOrientation-%s"


def _frame_of(source, frame):
    if frame:
        frame = frame.upper()
        if frame not in _FRAMES:
            raise ValueError("frame must be 'LPS' or 'RAS', got %r" % frame)
        return frame
    # The reader's OutputFrame (an enumeration: read the raw element, 1 = RAS).
    prop = source.SMProxy.GetProperty("OutputFrame") if hasattr(source, "SMProxy") else None
    if prop is not None and prop.GetElement(0) == 1:
        return "RAS"
    return "LPS"


def OrientationLabelPositions(bounds, frame="LPS", margin=0.08):
    """{label: (x, y, z)}: the centre of each face of ``bounds`` (xmin, xmax, ymin, ymax, zmin,
    zmax, world mm) pushed out by ``margin`` times the largest side, labelled for ``frame``."""
    centre = [0.5 * (bounds[2 * a] + bounds[2 * a + 1]) for a in range(3)]
    pad = margin * max(bounds[2 * a + 1] - bounds[2 * a] for a in range(3))
    positions = {}
    for axis, (positive, negative) in enumerate(_FRAMES[frame]):
        for label, end, sign in ((positive, bounds[2 * axis + 1], 1.0),
                                 (negative, bounds[2 * axis], -1.0)):
            point = list(centre)
            point[axis] = end + sign * pad
            positions[label] = tuple(point)
    return positions


def ShowPatientOrientation(source=None, view=None, frame=None, margin=0.08, font_size=24,
                           color=(1.0, 0.85, 0.2)):
    """Shows L/R, A/P, S/I labels around ``source`` (default: the active source) in ``view``
    (default: the active render view). ``frame`` is 'LPS' or 'RAS'; by default it follows the
    reader's OutputFrame property (LPS when there is none). Calling it again moves the labels.
    Returns {label: text source}."""
    source = source or simple.GetActiveSource()
    if source is None:
        raise ValueError("ShowPatientOrientation: no source given and no active source")
    view = view or simple.GetActiveViewOrCreate("RenderView")
    source.UpdatePipeline()
    bounds = source.GetDataInformation().GetBounds()
    if bounds[0] > bounds[1]:
        raise ValueError("ShowPatientOrientation: the source is empty (see the output messages)")
    texts = {}
    for label, point in OrientationLabelPositions(bounds, _frame_of(source, frame), margin).items():
        text = simple.FindSource(_NAME % label)
        if text is None:
            text = simple.Text(registrationName=_NAME % label, Text=label)
        rep = simple.Show(text, view)
        rep.TextPropMode = "Billboard 3D Text"
        rep.BillboardPosition = list(point)
        rep.FontSize = font_size
        rep.Bold = 1
        rep.Color = list(color)
        texts[label] = text
    return texts


def HidePatientOrientation():
    """Deletes the labels made by ShowPatientOrientation."""
    for label in "LRAPSI":
        text = simple.FindSource(_NAME % label)
        if text is not None:
            simple.Delete(text)
