// A single-writer sequence lock for small trivially copyable structs (agent state, parameters).
#pragma once

#include <atomic>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace vtouch
{

/// Writer: one thread at a time (callers serialize writers). Readers: any threads, never block the
/// writer. The payload is stored as atomic words, so the racy copy that a seqlock makes is well
/// defined in C++ and clean under ThreadSanitizer. No standalone fences (TSan does not model them):
/// payload words are stored with release and loaded with acquire (Boehm's fence-free variant),
/// which orders them against the sequence counter; free on x86. Neither side allocates, locks or
/// throws.
template<typename T>
class SeqLock
{
  static_assert(std::is_trivially_copyable<T>::value, "SeqLock payload must be trivially copyable");

public:
  SeqLock() { this->store(T{}); }
  explicit SeqLock(const T& value) { this->store(value); }

  void store(const T& value) noexcept
  {
    std::uint64_t words[kWords] = {};
    std::memcpy(words, &value, sizeof(T));
    const std::uint64_t s = this->Sequence.load(std::memory_order_relaxed);
    this->Sequence.store(s + 1, std::memory_order_relaxed);
    for (std::size_t i = 0; i < kWords; ++i)
    {
      // release: a reader that sees this word also sees the odd sequence stored before it.
      this->Words[i].store(words[i], std::memory_order_release);
    }
    this->Sequence.store(s + 2, std::memory_order_release);
  }

  /// One attempt; false when a write was in progress (the copy is then discarded).
  bool tryLoad(T& out) const noexcept
  {
    const std::uint64_t s1 = this->Sequence.load(std::memory_order_acquire);
    if (s1 & 1u)
    {
      return false;
    }
    std::uint64_t words[kWords];
    for (std::size_t i = 0; i < kWords; ++i)
    {
      // acquire: the sequence re-check below cannot move before these loads.
      words[i] = this->Words[i].load(std::memory_order_acquire);
    }
    if (this->Sequence.load(std::memory_order_relaxed) != s1)
    {
      return false;
    }
    std::memcpy(&out, words, sizeof(T));
    return true;
  }

  /// Retries until a consistent copy is read (the writer never holds the lock for long).
  T load() const noexcept
  {
    T out;
    while (!this->tryLoad(out))
    {
    }
    return out;
  }

  /// Even number of completed writes x 2; changes on every store.
  std::uint64_t version() const noexcept { return this->Sequence.load(std::memory_order_acquire); }

private:
  static constexpr std::size_t kWords = (sizeof(T) + 7) / 8;
  std::atomic<std::uint64_t> Sequence{ 0 };
  std::atomic<std::uint64_t> Words[kWords];
};

} // namespace vtouch
