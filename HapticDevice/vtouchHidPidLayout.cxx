#include "vtouchHidPidLayout.h"

namespace vtouch
{

namespace
{
/// Fields of one report type inside the collection opened with `reportUsage` (and, when
/// `innerUsage` is not 0, inside a collection opened with `innerUsage` too).
template<typename Visitor>
void forEachField(const HidReportDescriptor& d,
  HidReportType type,
  std::uint32_t reportUsage,
  std::uint32_t innerUsage,
  Visitor visit)
{
  const auto& fields = d.fields();
  for (std::size_t i = 0; i < fields.size(); ++i)
  {
    const HidField& f = fields[i];
    if (f.type != type || f.isConstant() || !d.insideCollection(f.collection, reportUsage))
    {
      continue;
    }
    if (innerUsage != 0 && !d.insideCollection(f.collection, innerUsage))
    {
      continue;
    }
    if (visit(static_cast<int>(i), f))
    {
      return;
    }
  }
}

HidReportRef locateReport(const HidReportDescriptor& d, HidReportType type, std::uint32_t usage)
{
  HidReportRef ref;
  forEachField(d,
    type,
    usage,
    0,
    [&](int, const HidField& f)
    {
      ref.present = true;
      ref.type = type;
      ref.reportId = f.reportId;
      ref.bytes = d.reportBytes(type, f.reportId);
      return true;
    });
  return ref;
}

/// The `occurrence`-th element carrying `usage` in a variable field of the report.
HidValueRef findValue(const HidReportDescriptor& d,
  const HidReportRef& report,
  std::uint32_t reportUsage,
  std::uint32_t usage,
  std::uint32_t innerUsage = 0,
  int occurrence = 0)
{
  HidValueRef ref;
  if (!report.present)
  {
    return ref;
  }
  int seen = 0;
  forEachField(d,
    report.type,
    reportUsage,
    innerUsage,
    [&](int index, const HidField& f)
    {
      if (f.reportId != report.reportId || !f.isVariable())
      {
        return false;
      }
      for (std::uint32_t e = 0; e < f.reportCount; ++e)
      {
        if (d.usageAt(f, e) == usage && seen++ == occurrence)
        {
          ref.field = index;
          ref.element = e;
          return true;
        }
      }
      return false;
    });
  return ref;
}

/// The n-th variable element of any usage inside `innerUsage` (e.g. the Direction collection,
/// whose elements are Ordinals on some devices and X/Y on others).
HidValueRef findNthInside(const HidReportDescriptor& d,
  const HidReportRef& report,
  std::uint32_t reportUsage,
  std::uint32_t innerUsage,
  std::uint32_t n)
{
  HidValueRef ref;
  if (!report.present)
  {
    return ref;
  }
  std::uint32_t seen = 0;
  forEachField(d,
    report.type,
    reportUsage,
    innerUsage,
    [&](int index, const HidField& f)
    {
      if (f.reportId != report.reportId || !f.isVariable())
      {
        return false;
      }
      if (n < seen + f.reportCount)
      {
        ref.field = index;
        ref.element = n - seen;
        return true;
      }
      seen += f.reportCount;
      return false;
    });
  return ref;
}

HidUsageSelector findSelector(const HidReportDescriptor& d,
  const HidReportRef& report,
  std::uint32_t reportUsage,
  std::uint32_t usage)
{
  HidUsageSelector selector;
  if (!report.present)
  {
    return selector;
  }
  forEachField(d,
    report.type,
    reportUsage,
    0,
    [&](int index, const HidField& f)
    {
      if (f.reportId != report.reportId)
      {
        return false;
      }
      if (f.isArray())
      {
        const std::int64_t k = d.indexOfUsage(f, usage);
        if (k >= 0)
        {
          selector.field = index;
          selector.element = 0;
          selector.value = f.logicalMinimum + k;
          return true;
        }
        return false;
      }
      for (std::uint32_t e = 0; e < f.reportCount; ++e)
      {
        if (d.usageAt(f, e) == usage)
        {
          selector.field = index;
          selector.element = e;
          selector.value = 1;
          return true;
        }
      }
      return false;
    });
  return selector;
}

bool insideAnyPidCollection(const HidReportDescriptor& d, int collection)
{
  int guard = 0;
  while (collection >= 0 && guard++ <= HidReportDescriptor::kMaxCollectionDepth)
  {
    const HidCollection& c = d.collections()[static_cast<std::size_t>(collection)];
    if ((c.usage >> 16) == pid::kPage)
    {
      return true;
    }
    collection = c.parent;
  }
  return false;
}

void findInput(const HidReportDescriptor& d, HidPidLayout& layout)
{
  const auto& fields = d.fields();
  // X first; Y, buttons and pressure must come in the same report.
  for (std::size_t i = 0; i < fields.size() && !layout.x.valid(); ++i)
  {
    const HidField& f = fields[i];
    if (f.type != HidReportType::Input || f.isConstant() || !f.isVariable() ||
        insideAnyPidCollection(d, f.collection))
    {
      continue;
    }
    for (std::uint32_t e = 0; e < f.reportCount; ++e)
    {
      if (d.usageAt(f, e) == pid::kGenericDesktopX)
      {
        layout.x = HidValueRef{ static_cast<int>(i), e };
        layout.input.present = true;
        layout.input.type = HidReportType::Input;
        layout.input.reportId = f.reportId;
        layout.input.bytes = d.reportBytes(HidReportType::Input, f.reportId);
        break;
      }
    }
  }
  if (!layout.input.present)
  {
    return;
  }
  for (std::size_t i = 0; i < fields.size(); ++i)
  {
    const HidField& f = fields[i];
    if (f.type != HidReportType::Input || f.reportId != layout.input.reportId || f.isConstant() ||
        !f.isVariable() || insideAnyPidCollection(d, f.collection))
    {
      continue;
    }
    for (std::uint32_t e = 0; e < f.reportCount; ++e)
    {
      const std::uint32_t usage = d.usageAt(f, e);
      const HidValueRef ref{ static_cast<int>(i), e };
      if (usage == pid::kGenericDesktopY && !layout.y.valid())
      {
        layout.y = ref;
      }
      else if (usage == pid::kTipPressure && !layout.pressure.valid())
      {
        layout.pressure = ref;
      }
      else if ((usage >> 16) == pid::kButtonPage && f.reportSize == 1)
      {
        const std::uint32_t number = usage & 0xFFFFu; // Button 1 is usage 1
        if (number >= 1 && number <= 32)
        {
          if (layout.buttons.size() < number)
          {
            layout.buttons.resize(number);
          }
          layout.buttons[number - 1] = ref;
        }
      }
    }
  }
}
} // namespace

HidPidLayout HidPidLayout::find(const HidReportDescriptor& d)
{
  HidPidLayout l;
  findInput(d, l);
  const HidReportType out = HidReportType::Output;
  const HidReportType feature = HidReportType::Feature;

  l.setEffect = locateReport(d, out, pid::kSetEffectReport);
  const std::uint32_t se = pid::kSetEffectReport;
  l.seBlockIndex = findValue(d, l.setEffect, se, pid::kEffectBlockIndex);
  l.seDuration = findValue(d, l.setEffect, se, pid::kDuration);
  l.seTriggerRepeat = findValue(d, l.setEffect, se, pid::kTriggerRepeatInterval);
  l.seSamplePeriod = findValue(d, l.setEffect, se, pid::kSamplePeriod);
  l.seStartDelay = findValue(d, l.setEffect, se, pid::kStartDelay);
  l.seGain = findValue(d, l.setEffect, se, pid::kGain);
  l.seTriggerButton = findValue(d, l.setEffect, se, pid::kTriggerButton);
  l.seAxisX = findValue(d, l.setEffect, se, pid::kGenericDesktopX, pid::kAxesEnable);
  l.seAxisY = findValue(d, l.setEffect, se, pid::kGenericDesktopY, pid::kAxesEnable);
  l.seDirectionEnable = findValue(d, l.setEffect, se, pid::kDirectionEnable);
  l.seDirection0 = findNthInside(d, l.setEffect, se, pid::kDirection, 0);
  l.seDirection1 = findNthInside(d, l.setEffect, se, pid::kDirection, 1);
  l.seConstantForce = findSelector(d, l.setEffect, se, pid::kEtConstantForce);

  l.setConstantForce = locateReport(d, out, pid::kSetConstantForceReport);
  l.cfBlockIndex =
    findValue(d, l.setConstantForce, pid::kSetConstantForceReport, pid::kEffectBlockIndex);
  l.cfMagnitude = findValue(d, l.setConstantForce, pid::kSetConstantForceReport, pid::kMagnitude);

  l.effectOperation = locateReport(d, out, pid::kEffectOperationReport);
  const std::uint32_t eo = pid::kEffectOperationReport;
  l.eoBlockIndex = findValue(d, l.effectOperation, eo, pid::kEffectBlockIndex);
  l.eoLoopCount = findValue(d, l.effectOperation, eo, pid::kLoopCount);
  l.eoStart = findSelector(d, l.effectOperation, eo, pid::kOpEffectStart);
  l.eoStop = findSelector(d, l.effectOperation, eo, pid::kOpEffectStop);

  // Some devices open the report with Device Control Report (0x95), others only with Device
  // Control (0x96): the collection found first is the one that holds the control usages.
  std::uint32_t dc = pid::kDeviceControlReport;
  l.deviceControl = locateReport(d, out, dc);
  if (!l.deviceControl.present)
  {
    dc = pid::kDeviceControl;
    l.deviceControl = locateReport(d, out, dc);
  }
  l.dcEnableActuators = findSelector(d, l.deviceControl, dc, pid::kDcEnableActuators);
  l.dcDisableActuators = findSelector(d, l.deviceControl, dc, pid::kDcDisableActuators);
  l.dcStopAllEffects = findSelector(d, l.deviceControl, dc, pid::kDcStopAllEffects);
  l.dcReset = findSelector(d, l.deviceControl, dc, pid::kDcDeviceReset);

  l.deviceGain = locateReport(d, out, pid::kDeviceGainReport);
  l.dgGain = findValue(d, l.deviceGain, pid::kDeviceGainReport, pid::kDeviceGain);

  l.blockFree = locateReport(d, out, pid::kBlockFreeReport);
  l.bfBlockIndex = findValue(d, l.blockFree, pid::kBlockFreeReport, pid::kEffectBlockIndex);

  l.createNewEffect = locateReport(d, feature, pid::kCreateNewEffectReport);
  l.cneConstantForce =
    findSelector(d, l.createNewEffect, pid::kCreateNewEffectReport, pid::kEtConstantForce);

  l.blockLoad = locateReport(d, feature, pid::kBlockLoadReport);
  const std::uint32_t bl = pid::kBlockLoadReport;
  l.blBlockIndex = findValue(d, l.blockLoad, bl, pid::kEffectBlockIndex);
  l.blSuccess = findSelector(d, l.blockLoad, bl, pid::kBlockLoadSuccess);
  l.blFull = findSelector(d, l.blockLoad, bl, pid::kBlockLoadFull);
  l.blError = findSelector(d, l.blockLoad, bl, pid::kBlockLoadError);

  l.pool = locateReport(d, feature, pid::kPoolReport);
  l.ppSimultaneousEffectsMax = findValue(d, l.pool, pid::kPoolReport, pid::kSimultaneousEffectsMax);
  return l;
}

} // namespace vtouch
