// vtouch::CollectiveRounds: the round loop of the distributed stages (see the header for how
// every rank agrees on stopping).
#include "vtouchCollectiveRounds.h"

#include <exception>
#include <stdexcept>
#include <utility>

namespace vtouch
{
namespace
{
/// The status word each rank appends to its indices: whether its step failed this round.
constexpr std::int64_t kStepOk = 0;
constexpr std::int64_t kStepFailed = 1;

std::vector<double> encodeText(const std::string& text)
{
  return std::vector<double>(text.begin(), text.end());
}

std::string decodeText(const std::vector<double>& v)
{
  std::string text;
  for (double c : v)
  {
    text.push_back(static_cast<char>(c));
  }
  return text;
}
} // namespace

CollectiveRounds::CollectiveRounds(Description description, Payload payload)
  : Words(std::move(description))
  , Carries(payload)
{
}

std::string CollectiveRounds::capMessage(int maximumRounds) const
{
  return this->Words.subject + " did not settle in " + std::to_string(maximumRounds) + " rounds (" +
         this->Words.capReason + "): " + this->Words.capAdvice;
}

RoundsOutcome CollectiveRounds::run(RankCollectives& collectives,
  const Step& step,
  int maximumRounds) const
{
  if (maximumRounds < 1)
  {
    throw std::invalid_argument("CollectiveRounds (" + this->Words.subject +
                                "): the round cap must be at least 1, not " +
                                std::to_string(maximumRounds));
  }
  const auto ranks = static_cast<std::size_t>(collectives.ranks());
  const bool withValues = this->Carries == Payload::IndicesAndValues;
  RoundsOutcome o;
  Exchange previous;
  previous.indices.assign(ranks, {});
  previous.values.assign(ranks, {});
  while (true)
  {
    // This rank's step; a failure is kept to be told to the others in this round's exchange.
    Report mine;
    std::exception_ptr failure;
    std::string failureText;
    try
    {
      mine = step(previous);
      if (withValues ? mine.values.size() != mine.indices.size() : !mine.values.empty())
      {
        throw std::logic_error("CollectiveRounds (" + this->Words.subject +
                               "): a report's values do not match its indices");
      }
    }
    catch (const std::exception& e)
    {
      failure = std::current_exception();
      failureText = e.what();
    }
    catch (...)
    {
      failure = std::current_exception();
      failureText = "an exception that is not a std::exception";
    }
    if (failure)
    {
      mine = Report();
    }
    o.reportedVoxels += mine.indices.size();
    mine.indices.push_back(failure ? kStepFailed : kStepOk);
    Exchange next;
    next.rounds = previous.rounds + 1;
    next.indices = collectives.allGather(mine.indices);
    next.values = withValues ? collectives.allGather(mine.values)
                             : std::vector<std::vector<double>>(next.indices.size());
    o.rounds = next.rounds;
    // Every rank reads the same gathered words, so every rank takes the same branch below.
    int failedRank = -1;
    bool anyReported = false;
    for (std::size_t r = 0; r < next.indices.size(); ++r)
    {
      std::vector<std::int64_t>& theirs = next.indices[r];
      if (theirs.empty())
      {
        throw std::runtime_error("CollectiveRounds (" + this->Words.subject + "): rank " +
                                 std::to_string(r) +
                                 " sent no status word: it is not running the same rounds");
      }
      if (theirs.back() != kStepOk && failedRank < 0)
      {
        failedRank = static_cast<int>(r);
      }
      theirs.pop_back();
      anyReported = anyReported || !theirs.empty();
    }
    if (failedRank >= 0)
    {
      const std::vector<std::vector<double>> texts =
        collectives.allGather(encodeText(failure ? failureText : std::string()));
      if (failure)
      {
        std::rethrow_exception(failure);
      }
      throw std::runtime_error(this->Words.subject + ": rank " + std::to_string(failedRank) +
                               " failed in round " + std::to_string(o.rounds) + ": " +
                               decodeText(texts[static_cast<std::size_t>(failedRank)]));
    }
    if (!anyReported)
    {
      o.settled = true;
      return o;
    }
    if (o.rounds >= maximumRounds)
    {
      o.message = this->capMessage(maximumRounds);
      return o;
    }
    previous = std::move(next);
  }
}

} // namespace vtouch
