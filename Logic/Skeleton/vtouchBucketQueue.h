// Circular bucket queue (Dial's algorithm) for the propagations of the voxel coding.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vtouch
{

/// Circular bucket queue (Dial). With a bucket width no larger than the shortest edge, popping a
/// bucket in any order is exact Dijkstra; each push and pop is O(1), so propagation is linear.
class BucketQueue
{
public:
  BucketQueue(double width, double maxStep)
    : Inverse(1.0 / width)
  {
    // A power of two of buckets, so that the circular index is a mask, not a division.
    std::size_t n = 1;
    while (n < static_cast<std::size_t>(std::ceil(maxStep / width)) + 3)
    {
      n *= 2;
    }
    this->Buckets.resize(n);
    this->Mask = n - 1;
  }
  void push(std::uint32_t lin, double key)
  {
    // Keys are >= 0: truncation is the floor (std::floor is a libm call on baseline x86-64).
    const double b = key * this->Inverse;
    std::uint64_t bucket = b > 0.0 ? static_cast<std::uint64_t>(b) : 0;
    bucket = std::max(bucket, this->Current);
    this->Buckets[bucket & this->Mask].push_back(lin);
    ++this->Size;
    this->Peak = std::max(this->Peak, this->Size);
  }
  bool pop(std::uint32_t& lin)
  {
    while (this->Size > 0)
    {
      std::vector<std::uint32_t>& b = this->Buckets[this->Current & this->Mask];
      if (!b.empty())
      {
        lin = b.back();
        b.pop_back();
        --this->Size;
        return true;
      }
      ++this->Current;
    }
    return false;
  }
  std::size_t peak() const { return this->Peak; }

  // For sources that start at different keys (SeedCodeStage::relax, the distributed SS code's
  // rounds): the caller pushes each source when the queue reaches its bucket, so that every key
  // pushed stays within the circular window of the current bucket.

  /// The bucket of `key` (>= 0).
  std::uint64_t bucketOf(double key) const
  {
    const double b = key * this->Inverse;
    return b > 0.0 ? static_cast<std::uint64_t>(b) : 0;
  }
  bool empty() const { return this->Size == 0; }
  /// Like pop(), but never moves past bucket `last`: false when no entry lies at or below it
  /// (the queue is then at bucket `last`, or empty).
  bool popUpTo(std::uint32_t& lin, std::uint64_t last)
  {
    while (this->Size > 0)
    {
      std::vector<std::uint32_t>& b = this->Buckets[this->Current & this->Mask];
      if (!b.empty())
      {
        if (this->Current > last)
        {
          return false;
        }
        lin = b.back();
        b.pop_back();
        --this->Size;
        return true;
      }
      if (this->Current >= last)
      {
        return false;
      }
      ++this->Current;
    }
    return false;
  }
  /// Moves an empty queue on to `bucket` (no move back), so that keys from there on fit.
  void skipTo(std::uint64_t bucket)
  {
    if (this->Size == 0)
    {
      this->Current = std::max(this->Current, bucket);
    }
  }

private:
  double Inverse; // 1 / bucket width
  std::vector<std::vector<std::uint32_t>> Buckets;
  std::uint64_t Mask = 0;
  std::uint64_t Current = 0;
  std::size_t Size = 0;
  std::size_t Peak = 0;
};

} // namespace vtouch
