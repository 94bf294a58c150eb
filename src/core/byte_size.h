// Byte counts for people: the one spelling every estimate, budget and refusal uses.
#pragma once
#include <fmt/format.h>
#include <string>

namespace penumbra {

// "512.0 KiB", "3.2 MiB", "22.4 GiB".
inline std::string formatBytes(double bytes) {
  if (bytes >= 1024.0 * 1024 * 1024) return fmt::format("{:.1f} GiB", bytes / (1024.0 * 1024 * 1024));
  if (bytes >= 1024.0 * 1024) return fmt::format("{:.1f} MiB", bytes / (1024.0 * 1024));
  return fmt::format("{:.1f} KiB", bytes / 1024.0);
}

}  // namespace penumbra
