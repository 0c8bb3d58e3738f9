#include "OutOfMemory.h"

#include <exception>
#include <utility>

namespace cloudvis
{

namespace
{
// Written only by a destructor during unwinding, where it must not allocate: the name is moved
// in (std::string's move assignment is noexcept and takes the buffer over).
thread_local FailedMemoryUse Failed;
thread_local bool HasFailed = false;
} // namespace

MemoryUse::MemoryUse(std::string what, double bytes)
  : What(std::move(what))
  , Bytes(bytes)
  , UncaughtAtStart(std::uncaught_exceptions())
{
  HasFailed = false;
}

MemoryUse::~MemoryUse()
{
  if (std::uncaught_exceptions() > this->UncaughtAtStart && !HasFailed)
  {
    Failed.What = std::move(this->What);
    Failed.Bytes = this->Bytes;
    HasFailed = true;
  }
}

std::optional<FailedMemoryUse> TakeFailedMemoryUse()
{
  if (!HasFailed)
  {
    return std::nullopt;
  }
  HasFailed = false;
  return std::move(Failed);
}

} // namespace cloudvis
