// The standalone measuring programs' list arguments: "1,2" -> {"1", "2"}.
#pragma once
#include <sstream>
#include <string>
#include <vector>

namespace penumbra::bench {

inline std::vector<std::string> commaList(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, ',');) out.push_back(part);
  return out;
}

}  // namespace penumbra::bench
