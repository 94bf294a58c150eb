// The passes file: a magic line, the format version and the sizes of the records it
// copies whole (so another build's layout is refused, not misread), the identity, the
// pass loop's state, and an FNV-1a checksum of every byte before it.
#include "plan/saved_passes.h"
#include "io/temp_file.h"
#include <fmt/format.h>
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <type_traits>

namespace penumbra {
namespace {

namespace fs = std::filesystem;

constexpr char kMagic[16] = {'p', 'e', 'n', 'u', 'm', 'b', 'r', 'a', ' ', 'p', 'a', 's', 's', 'e', 's', '\n'};
constexpr uint32_t kVersion = 5;  // 5: the gathers' smoothing probes
// Native byte order and the sizes of the records copied whole: a file of another
// machine or build reads as "another format", never as garbage.
constexpr uint32_t kLayout = 0x01020304u;

static_assert(std::is_trivially_copyable_v<RayCounts> && std::is_trivially_copyable_v<Color>,
              "records copied whole must be plain bytes");

uint64_t fnv1a(const unsigned char* data, size_t size) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (size_t i = 0; i < size; ++i) h = (h ^ data[i]) * 0x100000001b3ull;
  return h;
}

struct Writer {
  std::string bytes;
  void raw(const void* p, size_t n) { bytes.append(static_cast<const char*>(p), n); }
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    raw(&v, sizeof v);
  }
  void text(const std::string& s) {
    put<uint64_t>(s.size());
    raw(s.data(), s.size());
  }
  void image(const Image& im) {
    put<int32_t>(im.width);
    put<int32_t>(im.height);
    raw(im.pixels.data(), im.pixels.size() * sizeof(Color));
    put<uint8_t>(im.coverage.empty() ? 0 : 1);
    raw(im.coverage.data(), im.coverage.size() * sizeof(float));
  }
};

struct Truncated {};

struct Reader {
  const std::string& bytes;
  size_t at = 0;
  void raw(void* p, size_t n) {
    if (n > bytes.size() - at) throw Truncated{};
    std::memcpy(p, bytes.data() + at, n);
    at += n;
  }
  template <class T>
  T get() {
    T v;
    raw(&v, sizeof v);
    return v;
  }
  std::string text() {
    const uint64_t n = get<uint64_t>();
    if (n > bytes.size() - at) throw Truncated{};
    std::string s = bytes.substr(at, n);
    at += n;
    return s;
  }
  // An image of width x height, or an empty one (a half the passes have not reached yet),
  // with its coverage when it has one.
  bool image(Image& im, int width, int height) {
    const int w = get<int32_t>(), h = get<int32_t>();
    if (w == 0 && h == 0) return get<uint8_t>() == 0;
    if (w != width || h != height) return false;
    im = Image(w, h);
    raw(im.pixels.data(), im.pixels.size() * sizeof(Color));
    if (get<uint8_t>() != 0) {
      im.coverage.resize(im.pixels.size());
      raw(im.coverage.data(), im.coverage.size() * sizeof(float));
    }
    return true;
  }
};

uint32_t layoutSizes() { return static_cast<uint32_t>(sizeof(RayCounts) << 8 | sizeof(Color)); }

}  // namespace

std::string savedPassesPath(const std::string& output, const std::string& view) {
  return view.empty() ? output + ".passes" : output + "." + view + ".passes";
}

uint64_t savePasses(const std::string& path, const SavedPasses& s) {
  Writer w;
  w.raw(kMagic, sizeof kMagic);
  w.put(kVersion);
  w.put(kLayout);
  w.put(layoutSizes());
  w.text(s.identity);
  for (int v : {s.done, s.passes, s.sum.width, s.sum.height}) w.put<int32_t>(v);
  w.put(s.seconds);
  const PassCheckpoint& c = s.spread.checkpoint;
  const bool checkpoint = s.spread.keep && c.half > 0;  // a tile's bias check, for its merge
  const int smoothing = s.spread.smoothing.filled();
  for (int v : {s.spread.snapshotPasses, s.spread.passes, s.spread.biasHalf, int(s.spread.keep), int(checkpoint),
                c.passes, c.half, smoothing})
    w.put<int32_t>(v);
  w.put(s.emitted.values);
  w.put(s.stored.values);
  w.put(s.rays);
  w.put(s.gatherRadius.values);
  const PassSpread::Moments& m = s.spread;
  for (const Image* im : {&s.sum, &m.even, &m.odd, &m.snapshotEven, &m.snapshotOdd, &m.drift}) w.image(*im);
  if (checkpoint) for (const Image* im : {&c.firstEven, &c.firstOdd, &c.even, &c.odd}) w.image(*im);
  for (int g = 0; g < smoothing; ++g) w.image(m.smoothing.groups[g]);
  w.put(fnv1a(reinterpret_cast<const unsigned char*>(w.bytes.data()), w.bytes.size()));
  writeFileAtomic(path, w.bytes.data(), w.bytes.size(), "saved passes");
  return w.bytes.size();
}

std::optional<SavedPasses> loadPasses(const std::string& path, const std::string& identity, int passes, int width,
                                      int height, std::string& why) {
  why.clear();
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) {
    why = "cannot be read";
    return std::nullopt;
  }
  const size_t head = sizeof kMagic + 3 * sizeof(uint32_t);
  if (std::memcmp(bytes.data(), kMagic, std::min(bytes.size(), sizeof kMagic)) != 0) {
    why = "not a passes file";
    return std::nullopt;
  }
  if (bytes.size() < head + sizeof(uint64_t)) {
    why = "truncated";
    return std::nullopt;
  }
  const size_t body = bytes.size() - sizeof(uint64_t);
  uint64_t sum = 0;
  std::memcpy(&sum, bytes.data() + body, sizeof sum);
  if (sum != fnv1a(reinterpret_cast<const unsigned char*>(bytes.data()), body)) {
    why = "truncated or corrupt (its checksum does not match)";
    return std::nullopt;
  }
  const std::string content = bytes.substr(0, body);
  Reader r{content, sizeof kMagic};
  SavedPasses s;
  try {
    const uint32_t version = r.get<uint32_t>(), layout = r.get<uint32_t>(), sizes = r.get<uint32_t>();
    if (version != kVersion || layout != kLayout || sizes != layoutSizes()) {
      why = fmt::format("format {} of another version or machine (this penumbra reads format {})", version, kVersion);
      return std::nullopt;
    }
    s.identity = r.text();
    if (s.identity != identity) {
      why = "saved by another job or setting";
      return std::nullopt;
    }
    s.done = r.get<int32_t>();
    s.passes = r.get<int32_t>();
    const int w = r.get<int32_t>(), h = r.get<int32_t>();
    s.seconds = r.get<double>();
    s.spread.snapshotPasses = r.get<int32_t>();
    s.spread.passes = r.get<int32_t>();
    s.spread.biasHalf = r.get<int32_t>();
    s.spread.keep = r.get<int32_t>() != 0;
    const bool checkpoint = r.get<int32_t>() != 0;
    s.spread.checkpoint.passes = r.get<int32_t>();
    s.spread.checkpoint.half = r.get<int32_t>();
    const int smoothing = r.get<int32_t>();
    s.emitted.values = r.get<decltype(s.emitted.values)>();
    s.stored.values = r.get<decltype(s.stored.values)>();
    s.rays = r.get<RayCounts>();
    s.gatherRadius.values = r.get<decltype(s.gatherRadius.values)>();
    if (s.passes != passes || w != width || h != height || s.done < 1 || s.done >= passes ||
        s.spread.passes != s.done) {
      why = fmt::format("saved for {} passes of {}x{} after {}, not this frame's {} of {}x{}", s.passes, w, h, s.done,
                        passes, width, height);
      return std::nullopt;
    }
    bool sized = r.image(s.sum, width, height) && !s.sum.pixels.empty();
    PassSpread::Moments& m = s.spread;
    for (Image* im : {&m.even, &m.odd, &m.snapshotEven, &m.snapshotOdd, &m.drift})
      sized = sized && r.image(*im, width, height);
    PassCheckpoint& c = s.spread.checkpoint;
    if (checkpoint) {
      for (Image* im : {&c.firstEven, &c.firstOdd, &c.even, &c.odd}) sized = sized && r.image(*im, width, height);
    }
    // None, or one group per pass up to four.
    sized = sized && (smoothing == 0 || smoothing == std::min(s.done, SmoothingSums::kGroups));
    for (int g = 0; sized && g < smoothing; ++g) sized = r.image(m.smoothing.groups[g], width, height);
    if (!sized || r.at != content.size()) {
      why = "its images do not match its header";
      return std::nullopt;
    }
  } catch (const Truncated&) {
    why = "truncated";
    return std::nullopt;
  }
  return s;
}

void removeSavedPasses(const std::string& path) {
  if (path.empty()) return;
  std::error_code ec;
  fs::remove(path, ec);
}

}  // namespace penumbra
