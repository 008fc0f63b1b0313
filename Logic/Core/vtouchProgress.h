// Progress and cancellation of the centerline's long stages. The caller's callback receives the
// fraction done, in [0, 1], at the stages' check points and returns false to stop them; a stopped
// stage throws vtouch::Cancelled, which frees everything it allocated on the way out (RAII) and
// joins any thread it started. The callback is called on the computing thread only: a GUI that
// cancels from its own thread sets an atomic flag that the callback reads.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <stdexcept>

namespace vtouch
{

/// Fraction done in [0, 1]; returns false to cancel. Called on the computing thread.
using ProgressCallback = std::function<bool(double)>;

/// Thrown by a computation whose ProgressCallback returned false.
class Cancelled : public std::runtime_error
{
public:
  Cancelled()
    : std::runtime_error("cancelled")
  {
  }
};

/// A stage's part of the caller's progress: report(f) maps f in [0, 1] to
/// begin + f * (end - begin) of the callback's range. A default span has no callback: it never
/// reports and never cancels (the stages' callers that want neither pass nothing).
class ProgressSpan
{
public:
  ProgressSpan() = default;
  /// `callback` (may be null or empty) must outlive the span and its parts.
  explicit ProgressSpan(const ProgressCallback* callback, double begin = 0.0, double end = 1.0)
    : Callback(callback && *callback ? callback : nullptr)
    , Begin(begin)
    , Scale(end - begin)
  {
  }

  /// The part [begin, end] (fractions of this span) of this span.
  ProgressSpan part(double begin, double end) const
  {
    ProgressSpan p;
    p.Callback = this->Callback;
    p.Begin = this->Begin + begin * this->Scale;
    p.Scale = (end - begin) * this->Scale;
    return p;
  }

  /// Reports `fraction` (clamped to [0, 1]) of this span done; throws Cancelled when the callback
  /// asks to stop.
  void report(double fraction) const
  {
    if (this->Callback &&
        !(*this->Callback)(this->Begin + std::clamp(fraction, 0.0, 1.0) * this->Scale))
    {
      throw Cancelled();
    }
  }

  bool active() const { return this->Callback != nullptr; }

private:
  const ProgressCallback* Callback = nullptr;
  double Begin = 0.0;
  double Scale = 1.0;
};

/// The check points of one loop: reports 0 when constructed (every stage has a check point at
/// its start), then counts units of work (voxels, tiles, paths) and reports the fraction done to
/// its span every `period` units, so a cancel takes effect within `period` units. Reporting is a
/// counter compare per unit when the span has no callback.
class ProgressCounter
{
public:
  /// Default period: 2^16 voxel visits (well under a millisecond of any stage's loop).
  static constexpr std::uint64_t kVoxelPeriod = std::uint64_t{ 1 } << 16;

  ProgressCounter(const ProgressSpan& span,
    std::uint64_t total,
    std::uint64_t period = kVoxelPeriod)
    : Span(span)
    , Total(std::max<std::uint64_t>(1, total))
    , Period(std::max<std::uint64_t>(1, period))
    , Next(span.active() ? Period : UINT64_MAX)
  {
    this->Span.report(0.0);
  }

  void tick(std::uint64_t amount = 1)
  {
    this->Done += amount;
    if (this->Done >= this->Next)
    {
      this->Next = this->Done + this->Period;
      this->Span.report(static_cast<double>(this->Done) / static_cast<double>(this->Total));
    }
  }

private:
  ProgressSpan Span;
  std::uint64_t Total;
  std::uint64_t Period;
  std::uint64_t Next;
  std::uint64_t Done = 0;
};

} // namespace vtouch
