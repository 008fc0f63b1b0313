"""The haptic parameters of a VesselTouch session, from the one table
(Logic/Haptics/vtouchHapticParameters.def) as the session proxy carries it: the names, defaults,
ranges, choices and meanings are read from the proxy (its properties, domains and definition),
never written here; the values are read back from the C++ session (AppliedHapticParametersInfo).
HapticSession inherits this; it needs ``self.proxy``, ``self._set``, ``self._info`` and
``self.GetLastError``."""

from paraview import servermanager


def _key(name):
    """A name compared loosely: lower case, letters and digits only."""
    return "".join(c for c in str(name).lower() if c.isalnum())


class HapticParameterAccess(object):
    """Every haptic parameter by name: list, set (checked by the C++ session), read, describe."""

    @staticmethod
    def _whole(name, value):
        """An integer property's value as an int; ValueError for a number that is not whole
        (the property cannot carry it to the session)."""
        number = float(value)
        if not number.is_integer():
            raise ValueError("%s = %r is not a whole number (an integer property)"
                             % (name, value))
        return int(number)

    def HapticParameterNames(self):
        """The names of the haptic parameters, in table order, as the session reports them."""
        names = getattr(self, "_parameter_names", None)
        if names is None:
            names = [pair.split("=", 1)[0]
                     for pair in str(self._info("AppliedHapticParametersInfo")).split()]
            self._parameter_names = names
        return names

    def SetHapticParameters(self, **values):
        """Sets haptic parameters by name (``SetHapticParameters(LdgfLambda=0.01, Zoom=2)``) in
        one push. Booleans are given as True/False or 1/0, choices as their values. Raises
        ValueError for an unknown name, and with the session's message (name, value, range,
        unit) for a value it refuses; a refused parameter keeps its value."""
        names = self.HapticParameterNames()
        unknown = [n for n in values if n not in names]
        if unknown:
            raise ValueError("unknown haptic parameter(s) %s (see HapticParameterNames())"
                             % ", ".join(unknown))
        self._set(**{n: (int(v) if isinstance(v, bool) else v) for n, v in values.items()})

    def GetHapticParameters(self):
        """The haptic parameters the C++ session holds (what the haptic thread reads), as a dict
        name -> value (float)."""
        text = str(self._info("AppliedHapticParametersInfo"))
        return {name: float(value) for name, value in
                (pair.split("=", 1) for pair in text.split())}

    def DescribeHapticParameters(self):
        """Per haptic parameter: its default, range (minimum, maximum), choices (value -> label,
        for the choices) and documentation (label, unit, meaning), read from the proxy's
        properties and domains, which are generated from the parameter table."""
        out = {}
        defaults = self._xml_defaults()
        for name in self.HapticParameterNames():
            prop = self.proxy.SMProxy.GetProperty(name)
            entry = {"default": defaults[name],
                     "documentation": prop.GetDocumentation().GetDescription().strip()}
            domain = prop.FindDomain("vtkSMEnumerationDomain")
            if domain is not None:
                entry["choices"] = {domain.GetEntryValue(i): domain.GetEntryText(i)
                                    for i in range(domain.GetNumberOfEntries())}
            domain = domain or prop.FindDomain("vtkSMBooleanDomain")
            if domain is None:
                domain = prop.FindDomain("vtkSMDoubleRangeDomain") or \
                    prop.FindDomain("vtkSMIntRangeDomain")
                entry["range"] = (float(domain.GetMinimum(0)), float(domain.GetMaximum(0)))
            elif "choices" in entry:
                entry["range"] = (min(entry["choices"]), max(entry["choices"]))
            else:
                entry["range"] = (0.0, 1.0)
            out[name] = entry
        return out

    def _xml_defaults(self):
        """{property name: default value} of the proxy's definition (the generated XML)."""
        definition = servermanager.ProxyManager().SMProxyManager.GetProxyDefinitionManager() \
            .GetProxyDefinition(self.proxy.SMProxy.GetXMLGroup(), self.proxy.SMProxy.GetXMLName())
        defaults = {}
        for i in range(definition.GetNumberOfNestedElements()):
            element = definition.GetNestedElement(i)
            value = element.GetAttribute("default_values")
            if element.GetAttribute("name") and value and len(value.split()) == 1:
                defaults[element.GetAttribute("name")] = float(value)
        return defaults

    def _choices(self, name):
        """The choices of an enumeration property as {key: value} (key: the label, lower case,
        letters and digits only)."""
        domain = self.proxy.SMProxy.GetProperty(name).FindDomain("vtkSMEnumerationDomain")
        return {_key(domain.GetEntryText(i)): domain.GetEntryValue(i)
                for i in range(domain.GetNumberOfEntries())}

    def _check_refused(self, requested):
        """Raises ValueError when the session kept another value than the one requested (it
        refused it), after setting the property back to what the session holds."""
        applied = self.GetHapticParameters()
        refused = [n for n, v in requested.items() if applied.get(n) != v]
        if not refused:
            return
        message = self.GetLastError()
        smproxy = self.proxy.SMProxy
        for name in refused:
            prop = smproxy.GetProperty(name)
            kept = applied[name]
            prop.SetElement(0, int(kept) if prop.GetClassName() == "vtkSMIntVectorProperty"
                            else kept)
        smproxy.UpdateVTKObjects()
        raise ValueError(message or "refused: %s" % ", ".join(refused))
