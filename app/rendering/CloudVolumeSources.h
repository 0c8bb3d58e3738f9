// The one rule that decides whether a GPU volume of vtkCloudVolumeMapper is stale: each volume
// records the numbers it was made from (MTimes, sizes, settings, its input's identity) and is
// made again when they differ from those of its sources now. Every 3-D texture of the mapper
// decides by it: the density, the occupancy and extinction-bounds bricks, the light volumes, the
// multiple-scattering volume, and the optical depths and scattering from outside the field.
// Private to the rendering module.
#ifndef CloudVolumeSources_h
#define CloudVolumeSources_h

#include <vtkTextureObject.h>

#include <cstdint>
#include <utility>
#include <vector>

namespace cloudvis
{

class VolumeSources
{
public:
  using Numbers = std::vector<double>;

  // The volume was made from `now`, has not been forgotten since, and `texture` (the volume's, or
  // the first of its set) is on the GPU.
  bool Current(const Numbers& now, vtkTextureObject* texture) const
  {
    return this->Made && now == this->From && texture && texture->GetHandle();
  }
  // The volume is now made from `from`.
  void Take(Numbers from)
  {
    this->From = std::move(from);
    this->Made = true;
  }
  // The volume is gone or half made: whatever its sources, it is stale.
  void Forget()
  {
    this->From.clear();
    this->Made = false;
  }

private:
  Numbers From;
  bool Made = false;
};

// An object's identity as one of a volume's numbers (never dereferenced). Exact: user-space
// addresses on the platforms VTK supports take at most 48 bits, a double holds 53.
inline double IdentityOf(const void* object)
{
  return double(reinterpret_cast<std::uintptr_t>(object));
}

} // namespace cloudvis

#endif
