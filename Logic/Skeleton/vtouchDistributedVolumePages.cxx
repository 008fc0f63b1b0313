#include "vtouchDistributedVolumePages.h"
#include "vtouchFloatWords.h"

#include <algorithm>
#include <cstring>
#include <exception>
#include <utility>

namespace vtouch
{
namespace
{
/// The reader read a page not held (DistributedVolumePages::value): caught by run() only.
struct PageMiss
{
};

/// The first rank's broadcast: the end, or the pages it wants (after the word).
constexpr std::int64_t kEnd = 0;
constexpr std::int64_t kFetch = 1;
/// A part's encoding: two floats per word, or one double per word (their bits, exactly).
constexpr std::int64_t kFloats = 0;
constexpr std::int64_t kDoubles = 1;
/// An owner's failure record instead of parts: the word, the text's length, one char a word.
constexpr std::int64_t kFailure = -1;

VoxelBox intersection(const VoxelBox& a, const VoxelBox& b)
{
  VoxelBox c;
  for (std::size_t x = 0; x < 3; ++x)
  {
    c.lo[x] = std::max(a.lo[x], b.lo[x]);
    c.hi[x] = std::min(a.hi[x], b.hi[x]);
  }
  return c;
}

std::int64_t voxels(const VoxelBox& b)
{
  return b.empty() ? 0
                   : (b.hi[0] - b.lo[0] + 1) * (b.hi[1] - b.lo[1] + 1) * (b.hi[2] - b.lo[2] + 1);
}

/// Calls `f(voxel)` for every voxel of `b`, x fastest.
template<class F>
void forEachVoxel(const VoxelBox& b, F&& f)
{
  for (std::int64_t k = b.lo[2]; k <= b.hi[2]; ++k)
    for (std::int64_t j = b.lo[1]; j <= b.hi[1]; ++j)
      for (std::int64_t i = b.lo[0]; i <= b.hi[0]; ++i)
      {
        f(std::array<std::int64_t, 3>{ i, j, k });
      }
}

void appendText(std::vector<std::int64_t>& words, const std::string& text)
{
  words.push_back(kFailure);
  words.push_back(static_cast<std::int64_t>(text.size()));
  for (const char c : text)
  {
    words.push_back(static_cast<unsigned char>(c));
  }
}
} // namespace

DistributedVolumePages::DistributedVolumePages(RankCollectives& collectives,
  const PieceLayout& layout,
  OwnedIntensity mine)
  : Collectives(collectives)
  , Layout(layout)
  , Mine(std::move(mine))
{
  for (std::size_t a = 0; a < 3; ++a)
  {
    this->PerAxis[a] = (layout.wholeDims[a] + kPageEdge_voxels - 1) / kPageEdge_voxels;
  }
  if (collectives.rank() == 0)
  {
    this->Pages.resize(
      static_cast<std::size_t>(this->PerAxis[0] * this->PerAxis[1] * this->PerAxis[2]));
  }
}

std::int64_t DistributedVolumePages::pageOf(const std::array<std::int64_t, 3>& v) const
{
  return v[0] / kPageEdge_voxels +
         this->PerAxis[0] *
           (v[1] / kPageEdge_voxels + this->PerAxis[1] * (v[2] / kPageEdge_voxels));
}

VoxelBox DistributedVolumePages::pageBox(std::int64_t page) const
{
  const std::array<std::int64_t, 3> p{ page % this->PerAxis[0],
    (page / this->PerAxis[0]) % this->PerAxis[1],
    page / (this->PerAxis[0] * this->PerAxis[1]) };
  VoxelBox b;
  for (std::size_t a = 0; a < 3; ++a)
  {
    b.lo[a] = p[a] * kPageEdge_voxels;
    b.hi[a] = std::min(this->Layout.wholeDims[a] - 1, b.lo[a] + kPageEdge_voxels - 1);
  }
  return b;
}

bool DistributedVolumePages::holds(std::int64_t page) const
{
  if (page < 0 || page >= static_cast<std::int64_t>(this->Pages.size()))
  {
    return false;
  }
  return this->Pages[static_cast<std::size_t>(page)].complete;
}

double DistributedVolumePages::value(std::uint64_t lin) const
{
  const auto& d = this->Layout.wholeDims;
  const auto l = static_cast<std::int64_t>(lin);
  const std::array<std::int64_t, 3> v{ l % d[0], (l / d[0]) % d[1], l / (d[0] * d[1]) };
  const std::int64_t page = this->pageOf(v);
  if (!this->holds(page))
  {
    this->Missed.push_back(page);
    throw PageMiss{};
  }
  const Page& p = this->Pages[static_cast<std::size_t>(page)];
  const VoxelBox b = this->pageBox(page);
  const std::int64_t at =
    (v[0] - b.lo[0]) +
    (b.hi[0] - b.lo[0] + 1) * ((v[1] - b.lo[1]) + (b.hi[1] - b.lo[1] + 1) * (v[2] - b.lo[2]));
  return p.doubles.empty() ? static_cast<double>(p.floats[static_cast<std::size_t>(at)])
                           : p.doubles[static_cast<std::size_t>(at)];
}

SectionForeground DistributedVolumePages::inRange(double lower, double upper) const
{
  return { this->Layout.wholeDims, [this, lower, upper](std::uint64_t lin) {
            return inIntensityRange(this->value(lin), lower, upper);
          } };
}

SectionIntensity DistributedVolumePages::intensity() const
{
  return { this->Layout.wholeDims, [this](std::uint64_t lin) { return this->value(lin); } };
}

std::vector<std::int64_t> DistributedVolumePages::parts(
  const std::vector<std::int64_t>& pages) const
{
  std::vector<std::int64_t> words;
  const VoxelBox& owned = this->Layout.owned[static_cast<std::size_t>(this->Layout.rank)];
  std::vector<double> values;
  for (const std::int64_t page : pages)
  {
    const VoxelBox b = intersection(this->pageBox(page), owned);
    if (b.empty())
    {
      continue;
    }
    if (!this->Mine)
    {
      words.clear();
      appendText(words,
        "rank " + std::to_string(this->Layout.rank) + " holds no piece of the voxels it owns");
      return words;
    }
    values.clear();
    bool floats = true;
    try
    {
      forEachVoxel(b,
        [&](const std::array<std::int64_t, 3>& v)
        {
          const double x = this->Mine(v);
          floats = floats && static_cast<double>(static_cast<float>(x)) == x;
          values.push_back(x);
        });
    }
    catch (const std::exception& e)
    {
      words.clear();
      appendText(words, "rank " + std::to_string(this->Layout.rank) + ": " + e.what());
      return words;
    }
    words.push_back(page);
    words.push_back(floats ? kFloats : kDoubles);
    const std::size_t count = floats ? (values.size() + 1) / 2 : values.size();
    words.push_back(static_cast<std::int64_t>(count));
    for (std::size_t i = 0; i < count; ++i)
    {
      if (floats)
      {
        const std::int64_t lo = floatToWord(static_cast<float>(values[2 * i]));
        const std::int64_t hi =
          2 * i + 1 < values.size() ? floatToWord(static_cast<float>(values[2 * i + 1])) : 0;
        words.push_back(lo | static_cast<std::int64_t>(static_cast<std::uint64_t>(hi) << 32U));
      }
      else
      {
        std::int64_t w = 0;
        std::memcpy(&w, &values[i], sizeof w);
        words.push_back(w);
      }
    }
  }
  return words;
}

std::string DistributedVolumePages::store(int r, const std::vector<std::int64_t>& words)
{
  const VoxelBox& owned = this->Layout.owned[static_cast<std::size_t>(r)];
  std::size_t at = 0;
  while (at < words.size())
  {
    if (words[at] == kFailure)
    {
      const auto length = static_cast<std::size_t>(at + 1 < words.size() ? words[at + 1] : 0);
      std::string text;
      for (std::size_t c = 0; c < length && at + 2 + c < words.size(); ++c)
      {
        text.push_back(static_cast<char>(words[at + 2 + c]));
      }
      return text;
    }
    if (at + 3 > words.size() || words[at] < 0 ||
        words[at] >= static_cast<std::int64_t>(this->Pages.size()))
    {
      return "rank " + std::to_string(r) + " sent an unreadable page";
    }
    const std::int64_t page = words[at];
    const bool floats = words[at + 1] == kFloats;
    const auto count = static_cast<std::size_t>(words[at + 2]);
    const VoxelBox pb = this->pageBox(page);
    const VoxelBox b = intersection(pb, owned);
    const auto n = static_cast<std::size_t>(voxels(b));
    if (count != (floats ? (n + 1) / 2 : n) || at + 3 + count > words.size())
    {
      return "rank " + std::to_string(r) + " sent a page of the wrong size";
    }
    Page& p = this->Pages[static_cast<std::size_t>(page)];
    const auto size = static_cast<std::size_t>(voxels(pb));
    if (!floats && p.doubles.empty())
    {
      p.doubles.assign(p.floats.begin(), p.floats.end()); // exact: float to double
      p.doubles.resize(size, 0.0);
      p.floats.clear();
      p.floats.shrink_to_fit();
    }
    else if (floats && p.doubles.empty() && p.floats.empty())
    {
      p.floats.resize(size, 0.0F);
    }
    const std::int64_t* w = words.data() + at + 3;
    std::size_t i = 0;
    forEachVoxel(b,
      [&](const std::array<std::int64_t, 3>& v)
      {
        double x = 0.0;
        if (floats)
        {
          x = wordToFloat(i % 2 == 0
                          ? w[i / 2]
                          : static_cast<std::int64_t>(static_cast<std::uint64_t>(w[i / 2]) >> 32U));
        }
        else
        {
          std::memcpy(&x, &w[i], sizeof x);
        }
        const auto local = static_cast<std::size_t>(
          (v[0] - pb.lo[0]) +
          (pb.hi[0] - pb.lo[0] + 1) *
            ((v[1] - pb.lo[1]) + (pb.hi[1] - pb.lo[1] + 1) * (v[2] - pb.lo[2])));
        if (p.doubles.empty())
        {
          p.floats[local] = static_cast<float>(x);
        }
        else
        {
          p.doubles[local] = x;
        }
        ++i;
      });
    p.filled += static_cast<std::int64_t>(n);
    p.complete = p.filled == static_cast<std::int64_t>(size);
    at += 3 + count;
  }
  return std::string();
}

std::string DistributedVolumePages::incomplete(const std::vector<std::int64_t>& pages) const
{
  for (const std::int64_t page : pages)
  {
    if (!this->holds(page))
    {
      return "page " + std::to_string(page) +
             " of the volume was not answered in full (do the "
             "ranks' pieces cover the volume?)";
    }
  }
  return std::string();
}

DistributedVolumePages::Outcome DistributedVolumePages::run(
  const std::vector<std::int64_t>& prefetch,
  const std::function<void()>& reader)
{
  Outcome out;
  const bool first = this->Collectives.rank() == 0;
  std::vector<std::int64_t> want; // first rank: the pages of the next round
  bool prefetched = false;
  std::string failure;
  const auto notHeld = [this](std::vector<std::int64_t> pages)
  {
    std::sort(pages.begin(), pages.end());
    pages.erase(std::unique(pages.begin(), pages.end()), pages.end());
    pages.erase(
      std::remove_if(pages.begin(),
        pages.end(),
        [this](std::int64_t p)
        { return p < 0 || p >= static_cast<std::int64_t>(this->Pages.size()) || this->holds(p); }),
      pages.end());
    return pages;
  };
  for (;;)
  {
    std::vector<std::int64_t> message{ kEnd };
    if (first && reader)
    {
      if (!prefetched)
      {
        want = notHeld(prefetch);
        prefetched = true;
      }
      while (failure.empty() && want.empty() && !out.completed)
      {
        this->Missed.clear();
        ++out.runs;
        try
        {
          reader();
          out.completed = true;
        }
        catch (const PageMiss&)
        {
          // The missed page and the pages around it (project rule: a section that left the
          // prefetched pages goes on into the next ones; one round instead of one per page).
          std::vector<std::int64_t> around;
          for (const std::int64_t m : this->Missed)
          {
            const VoxelBox b = this->pageBox(m);
            for (std::int64_t dz = -1; dz <= 1; ++dz)
              for (std::int64_t dy = -1; dy <= 1; ++dy)
                for (std::int64_t dx = -1; dx <= 1; ++dx)
                {
                  const std::array<std::int64_t, 3> v{ b.lo[0] + dx * kPageEdge_voxels,
                    b.lo[1] + dy * kPageEdge_voxels,
                    b.lo[2] + dz * kPageEdge_voxels };
                  bool inside = true;
                  for (std::size_t a = 0; a < 3; ++a)
                  {
                    inside = inside && v[a] >= 0 && v[a] < this->Layout.wholeDims[a];
                  }
                  if (inside)
                  {
                    around.push_back(this->pageOf(v));
                  }
                }
          }
          want = notHeld(around);
          if (want.empty())
          {
            failure = "a read missed a page already held"; // cannot happen: no loop for ever
          }
        }
        catch (const std::exception& e)
        {
          failure = e.what();
        }
        catch (...)
        {
          failure = "the reader failed";
        }
      }
      if (failure.empty() && !out.completed)
      {
        message.assign(1, kFetch);
        message.insert(message.end(), want.begin(), want.end());
      }
    }
    message = this->Collectives.broadcast(message, 0);
    if (message.empty() || message[0] != kFetch)
    {
      break;
    }
    const std::vector<std::int64_t> pages(message.begin() + 1, message.end());
    const std::vector<std::vector<std::int64_t>> all =
      this->Collectives.gather(this->parts(pages), 0);
    ++out.rounds;
    if (first)
    {
      for (int r = 0; r < static_cast<int>(all.size()); ++r)
      {
        const std::vector<std::int64_t>& words = all[static_cast<std::size_t>(r)];
        out.bytesGathered += static_cast<std::int64_t>(words.size() * sizeof(std::int64_t));
        const std::string error = this->store(r, words);
        failure = failure.empty() ? error : failure;
      }
      failure = failure.empty() ? this->incomplete(pages) : failure;
      want.clear();
    }
  }
  if (first)
  {
    out.message = failure;
    for (std::int64_t p = 0; p < static_cast<std::int64_t>(this->Pages.size()); ++p)
    {
      out.pagesFetched += this->holds(p) ? 1 : 0;
    }
  }
  return out;
}

} // namespace vtouch
