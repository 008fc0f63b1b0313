// Where a distributed VesselCenterline run's wall time goes on one rank (issue 19, item 4): the
// time stamps the filter takes in its pipeline passes, before its RequestData can time anything
// itself. Not a wrapped class: the filter's member, read by vtouch::DistributedRequest.
#pragma once

#include "vtkTimeStamp.h" // for the request's modification time

#include <chrono>

namespace vtouch
{

/// Seconds since the Unix epoch (std::chrono::system_clock): comparable between the processes of
/// one machine (the ranks and the client), not between machines.
inline double epochSeconds()
{
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

/// One rank's stamps of the executive's passes through the filter, epoch seconds (0: not taken).
struct RankTimeline
{
  /// The last RequestUpdateExtent before RequestData: the executive updates the input (the
  /// reader re-executes for the grown piece) between it and RequestData. (Not the first: a pass
  /// that did not re-execute the filter, a Fetch, a view's update, requests too.)
  double lastRequest_Epoch_s = 0.0;
  /// RequestData's entry.
  double dataEntry_Epoch_s = 0.0;
  /// VTK's modification time at the last request: an input whose update time
  /// (vtkDataObject::GetUpdateTime) is later was produced for this run (its source re-executed).
  vtkMTimeType lastRequest_MTime = 0;

  void markRequest()
  {
    vtkTimeStamp now;
    now.Modified();
    lastRequest_MTime = now.GetMTime();
    lastRequest_Epoch_s = epochSeconds();
  }
  void markDataEntry() { dataEntry_Epoch_s = epochSeconds(); }
  /// Returns the stamps of this run and starts the next one.
  RankTimeline take()
  {
    const RankTimeline taken = *this;
    *this = RankTimeline{};
    return taken;
  }
};

} // namespace vtouch
