// Lists in words, as messages and help write them: "a, b, c".
#ifndef cloudvis_Words_h
#define cloudvis_Words_h

#include <string>
#include <vector>

namespace cloudvis
{

// The names with `separator` between them ("" when there are none).
std::string Join(const std::vector<std::string>& names, const std::string& separator = ", ");

} // namespace cloudvis

#endif
