// When an exploring cursor may be captured by a vessel (Yi & Hayward 2002, §3.2), for a hand that
// clicks, rests, and crosses vessels on its way to another.
#pragma once

namespace vtouch
{

/// Decides, tick by tick, whether the exploring cursor may make contact. §3.2 says "proximity of
/// the cursor to a vessel terminates [exploration]" and "a button click returns the user to the
/// exploration state". Taken literally, a click with a still hand is undone at the next tick (the
/// cursor is still within the capture radius), a cursor that rests on a vessel when the session
/// starts is captured before the user did anything, and the first vessel merely crossed on the
/// way to another takes the agent. Two rules, both documented in Docs/HAPTICS.md:
///
/// - Approach: contact is armed only once the cursor has been outside every capture radius since
///   the last release (a click, a new skeleton) and, unless `approachAtStart` is false, since the
///   start. A click therefore returns to exploring until the cursor has left the vessel.
/// - Dwell: an armed cursor makes contact once it has stayed within the capture radius for
///   `dwell_s` without interruption. A vessel crossed faster than 2 r / dwell_s (r: capture
///   radius) does not take the agent; a cursor that stops on, or moves along, a vessel does.
///   dwell_s = 0 is the paper's immediate capture.
///
/// Not thread-safe; lives in the haptic tick. Never allocates, locks or throws.
class ContactGate
{
public:
  /// Time the cursor must stay within the capture radius, s (>= 0).
  double dwell_s = 0.05;
  /// At start the cursor must approach a vessel from outside the capture radius.
  bool approachAtStart = true;

  /// Start of a session: armed unless approachAtStart.
  void reset() noexcept;
  /// After a release (button click, new skeleton): disarmed until the cursor leaves.
  void disarm() noexcept;
  /// One exploring tick: `nearVessel` is true when the cursor is within the capture radius of a
  /// vessel (the contact map has an entry under it). True when contact should be made now.
  bool update(bool nearVessel, double dt_s) noexcept;

  bool armed() const { return this->Armed; }
  /// Time spent within the capture radius since arming or the last exit, s.
  double dwelt_s() const { return this->Dwelt_s; }

private:
  bool Armed = false;
  double Dwelt_s = 0.0;
};

} // namespace vtouch
