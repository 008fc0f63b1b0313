// GUI -> haptic thread hand-over of immutable ViewModel snapshots, lock-free on the haptic side.
#pragma once

#include "vtouchViewModel.h"

#include <atomic>
#include <memory>
#include <mutex>
#include <vector>

namespace vtouch
{

/// One reader (the haptic thread) and any number of producers.
///
/// The reader never touches a shared_ptr (libstdc++'s std::atomic_load on shared_ptr takes a lock,
/// and dropping the last reference would free megabytes inside a tick). Producers keep ownership;
/// the reader announces the snapshot it uses in a hazard pointer, and a producer frees or recycles
/// an old snapshot only when it is neither current nor announced (hazard-pointer protocol with
/// sequentially consistent atomics). Memory is therefore always released on a producer thread.
class ViewModelExchange
{
public:
  ViewModelExchange() = default;
  ~ViewModelExchange();
  ViewModelExchange(const ViewModelExchange&) = delete;
  ViewModelExchange& operator=(const ViewModelExchange&) = delete;

  /// Producer side: makes `snapshot` current. Old snapshots the reader no longer uses are kept (up
  /// to `spares`) for takeRecyclable() or released here.
  void publish(std::shared_ptr<ViewModel> snapshot);
  /// Producer side: a retired snapshot nobody reads any more, to rebuild in place; null if none.
  std::shared_ptr<ViewModel> takeRecyclable();
  /// Producer side: the newest published snapshot (for the GUI, tests and the offline session).
  std::shared_ptr<const ViewModel> current() const;
  /// Producer side: drops the current snapshot (the reader sees null from its next acquire()).
  void clear();

  /// Reader side (one thread): the newest snapshot, valid until the reader's next acquire() or
  /// release(). Wait-free in practice: it retries only while a publish races with it.
  const ViewModel* acquire() noexcept;
  /// Reader side: announces that the reader holds no snapshot any more.
  void release() noexcept;

  /// How many retired snapshots are kept for recycling. Default 2.
  static constexpr std::size_t kSpares = 2;

private:
  void collectLocked();

  std::atomic<const ViewModel*> Current{ nullptr };
  std::atomic<const ViewModel*> Hazard{ nullptr };
  mutable std::mutex ProducerMutex; // producers only; the reader never locks
  std::shared_ptr<ViewModel> CurrentOwner;
  std::vector<std::shared_ptr<ViewModel>> Retired;
  std::vector<std::shared_ptr<ViewModel>> Spares;
};

} // namespace vtouch
