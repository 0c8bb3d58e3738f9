// What cloudvis was doing when memory ran out. A MemoryUse names a step that makes one large
// allocation or several ("generating a field of 2048 x 2048 x 512 voxels (big.json)", 8 GiB)
// while it lives. When an exception unwinds through it, the innermost MemoryUse it passed is
// kept, so that the command line's report of a std::bad_alloc names the step and its size
// instead of a bare "out of memory". A new MemoryUse forgets what an earlier, handled exception
// left.
#ifndef cloudvis_OutOfMemory_h
#define cloudvis_OutOfMemory_h

#include <optional>
#include <string>

namespace cloudvis
{

class MemoryUse
{
public:
  // `what` completes "out of memory while WHAT"; `bytes` is about what the step needs.
  MemoryUse(std::string what, double bytes);
  ~MemoryUse();
  MemoryUse(const MemoryUse&) = delete;
  MemoryUse& operator=(const MemoryUse&) = delete;

private:
  std::string What;
  double Bytes;
  int UncaughtAtStart;
};

struct FailedMemoryUse
{
  std::string What;
  double Bytes = 0.0;
};

// The innermost MemoryUse the last exception unwound through on this thread, and forgets it;
// none when no MemoryUse was passed.
std::optional<FailedMemoryUse> TakeFailedMemoryUse();

} // namespace cloudvis

#endif
