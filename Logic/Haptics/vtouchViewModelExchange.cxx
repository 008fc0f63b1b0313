#include "vtouchViewModelExchange.h"

#include <utility>

namespace vtouch
{

ViewModelExchange::~ViewModelExchange() = default;

void ViewModelExchange::publish(std::shared_ptr<ViewModel> snapshot)
{
  std::lock_guard<std::mutex> lock(this->ProducerMutex);
  if (this->CurrentOwner)
  {
    this->Retired.push_back(std::move(this->CurrentOwner));
  }
  this->CurrentOwner = std::move(snapshot);
  this->Current.store(this->CurrentOwner.get(), std::memory_order_seq_cst);
  this->collectLocked();
}

void ViewModelExchange::clear()
{
  std::lock_guard<std::mutex> lock(this->ProducerMutex);
  if (this->CurrentOwner)
  {
    this->Retired.push_back(std::move(this->CurrentOwner));
  }
  this->Current.store(nullptr, std::memory_order_seq_cst);
  this->collectLocked();
}

void ViewModelExchange::collectLocked()
{
  // Current was stored before Hazard is read (both seq_cst): a reader that has not announced an
  // old snapshot yet will see the new Current when it re-checks, and retry.
  const ViewModel* hazard = this->Hazard.load(std::memory_order_seq_cst);
  std::vector<std::shared_ptr<ViewModel>> keep;
  for (auto& old : this->Retired)
  {
    if (old.get() == hazard)
    {
      keep.push_back(std::move(old));
    }
    else if (this->Spares.size() < kSpares && old.use_count() == 1)
    {
      this->Spares.push_back(std::move(old));
    }
    // else: released here, on the producer thread.
  }
  this->Retired = std::move(keep);
}

std::shared_ptr<ViewModel> ViewModelExchange::takeRecyclable()
{
  std::lock_guard<std::mutex> lock(this->ProducerMutex);
  this->collectLocked();
  if (this->Spares.empty())
  {
    return nullptr;
  }
  std::shared_ptr<ViewModel> spare = std::move(this->Spares.back());
  this->Spares.pop_back();
  return spare;
}

std::shared_ptr<const ViewModel> ViewModelExchange::current() const
{
  std::lock_guard<std::mutex> lock(this->ProducerMutex);
  return this->CurrentOwner;
}

const ViewModel* ViewModelExchange::acquire() noexcept
{
  const ViewModel* p = this->Current.load(std::memory_order_seq_cst);
  for (;;)
  {
    this->Hazard.store(p, std::memory_order_seq_cst);
    const ViewModel* q = this->Current.load(std::memory_order_seq_cst);
    if (q == p)
    {
      return p;
    }
    p = q;
  }
}

void ViewModelExchange::release() noexcept
{
  this->Hazard.store(nullptr, std::memory_order_seq_cst);
}

} // namespace vtouch
