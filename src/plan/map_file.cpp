// The file: a preamble (magic, format version, byte order, header length), a header
// (the key text, lights, classic scale, budgets, each map's record size and count,
// notes, the payload's CRC-32), the header's own CRC-32, then each map's photons in
// emission order. Nothing in it is trusted before both checksums and the key match.
#include "plan/map_file.h"
#include "core/error.h"
#include "core/stats.h"
#include "io/temp_file.h"
#include <fmt/format.h>
#include <zlib.h>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <type_traits>

#ifndef PENUMBRA_VERSION
#define PENUMBRA_VERSION "unknown"
#endif

namespace penumbra {
namespace {

namespace fs = std::filesystem;

constexpr char kMagic[8] = {'P', 'N', 'B', 'R', 'P', 'M', 'A', 'P'};
// 2: five kinds, the fifth the volume map's records (1 held four kinds).
constexpr uint32_t kFormatVersion = 2;
constexpr uint32_t kByteOrder = 0x01020304;  // read back swapped on a machine of the other order
constexpr uint64_t kPreambleBytes = sizeof kMagic + 4 + 4 + 8;
constexpr uint64_t kMaxHeaderBytes = uint64_t(1) << 30;  // a key and notes; more is not a header
constexpr size_t kCheckChunkBytes = size_t(1) << 20;     // checking without keeping reads this much at a time

// zlib's CRC-32 of `size` more bytes. An empty piece leaves it as it is (zlib answers
// a null buffer, an empty array's data(), with the initial value instead).
uint32_t crcOf(uint32_t crc, const void* data, size_t size) {
  return size == 0 ? crc : static_cast<uint32_t>(crc32_z(crc, static_cast<const Bytef*>(data), size));
}

struct Writer {
  std::string bytes;
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>, "plain values only");
    bytes.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void text(const std::string& s) {
    put<uint64_t>(s.size());
    bytes += s;
  }
};

// Reads what Writer wrote; `ok` turns false (and stays) at the first read past the end.
struct Reader {
  const std::string& bytes;
  size_t at = 0;
  bool ok = true;
  template <class T>
  T get() {
    T v{};
    if (!ok || bytes.size() - at < sizeof v) {
      ok = false;
      return v;
    }
    std::memcpy(&v, bytes.data() + at, sizeof v);
    at += sizeof v;
    return v;
  }
  std::string text() {
    const uint64_t n = get<uint64_t>();
    if (!ok || bytes.size() - at < n) {
      ok = false;
      return {};
    }
    std::string s = bytes.substr(at, n);
    at += n;
    return s;
  }
};

// Each map's photons as stored: their record size and count.
struct MapExtent {
  uint32_t recordBytes = 0;
  uint64_t count = 0;
};

std::string hex64(uint64_t v) { return fmt::format("{:016x}", v); }

}  // namespace

std::string mapFileKey(const PhotonStageKey& key, const PhotonNeeds& needs, bool loadDefaults) {
  std::string text = fmt::format("penumbra {} map format {}\nrecords shadow {} indirect {} volume {}\ndefaults {}\n",
                                 PENUMBRA_VERSION, kFormatVersion, sizeof(ShadowPhoton), sizeof(IndirectPhoton),
                                 sizeof(VolumePhoton),
                                 loadDefaults ? "on" : "off");
  for (MapKind k : kAllMaps) {
    text += fmt::format("{} {} {}", mapName(k), key.maps[k] ? "on" : "off", key.budgets[k]);
    for (float r : needs.reach[k]) {
      uint32_t bits;
      std::memcpy(&bits, &r, sizeof bits);
      text += fmt::format(" {:08x}", bits);  // exact: a split that differs in one bit is another key
    }
    text += "\n";
  }
  return text + "geometry\n" + key.geometry + "\nphotons\n" + key.photons + "\n";
}

std::string mapFilePath(const std::string& dir, const std::string& keyText) {
  uint64_t h = 1469598103934665603ull;  // FNV-1a: collisions are caught by the key in the header
  for (unsigned char c : keyText) h = (h ^ c) * 1099511628211ull;
  return (fs::path(dir) / (hex64(h) + ".pmap")).string();
}

uint64_t writeMapFile(const std::string& path, const std::string& keyText, const Emission& e) {
  std::vector<FilePiece> payload;
  uint32_t payloadCrc = 0;
  uint64_t payloadBytes = 0;
  Writer header;
  header.text(keyText);
  header.put<uint64_t>(e.numLights);
  header.put<float>(e.photons.classicScale);
  for (MapKind k : kAllMaps) header.put<uint64_t>(e.budgets[k]);
  e.photons.batches.forEach([&](auto, const auto& batches) {
    using Photon = std::decay_t<decltype(*batches.begin())>;
    header.put<uint32_t>(sizeof(Photon));
    header.put<uint64_t>(batches.size());
    for (size_t b = 0; b < batches.batchCount(); ++b) {
      const auto& span = batches.batch(b);
      if (span.size == 0) continue;
      payload.push_back({span.data, span.size * sizeof(Photon)});
      payloadCrc = crcOf(payloadCrc, span.data, span.size * sizeof(Photon));
      payloadBytes += span.size * sizeof(Photon);
    }
  });
  header.put<uint64_t>(e.notes.size());
  for (const std::string& n : e.notes) header.text(n);
  header.put<uint32_t>(payloadCrc);

  Writer front;
  front.bytes.append(kMagic, sizeof kMagic);
  front.put<uint32_t>(kFormatVersion);
  front.put<uint32_t>(kByteOrder);
  front.put<uint64_t>(header.bytes.size());
  front.bytes += header.bytes;
  front.put<uint32_t>(crcOf(0, front.bytes.data(), front.bytes.size()));
  payload.insert(payload.begin(), FilePiece{front.bytes.data(), front.bytes.size()});
  writeFileAtomic(path, payload, "photon map file");
  return front.bytes.size() + payloadBytes;
}

std::string readMapFile(const std::string& path, const std::string& keyText, Emission* out, uint64_t* bytes) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return kMapFileMissing;
  // The size of the file opened, not of the name: another process may rename a new one onto it.
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in || fs::is_directory(path, ec)) return "cannot open it";
  const uint64_t size = static_cast<uint64_t>(in.tellg());
  in.seekg(0);
  if (bytes) *bytes = size;
  std::string front(kPreambleBytes, '\0');
  if (size < kPreambleBytes || !in.read(front.data(), kPreambleBytes)) return "truncated: no header";
  if (std::memcmp(front.data(), kMagic, sizeof kMagic) != 0) return "not a penumbra photon map file";
  Reader preamble{front, sizeof kMagic};
  const uint32_t version = preamble.get<uint32_t>();
  if (preamble.get<uint32_t>() != kByteOrder) return "written on a machine of the other byte order";
  if (version != kFormatVersion) return fmt::format("format version {}, this penumbra reads {}", version, kFormatVersion);
  const uint64_t headerBytes = preamble.get<uint64_t>();
  if (headerBytes > kMaxHeaderBytes || headerBytes + 4 > size - kPreambleBytes) return "truncated inside its header";
  front.resize(kPreambleBytes + headerBytes + 4);
  if (!in.read(front.data() + kPreambleBytes, static_cast<std::streamsize>(headerBytes + 4))) return "cannot read its header";
  uint32_t headerCrc;
  std::memcpy(&headerCrc, front.data() + kPreambleBytes + headerBytes, sizeof headerCrc);
  if (crcOf(0, front.data(), kPreambleBytes + headerBytes) != headerCrc) return "header damaged (its checksum differs)";

  front.resize(kPreambleBytes + headerBytes);
  Reader header{front, kPreambleBytes};
  if (header.text() != keyText) return "written for another photon key (other scene, settings or budgets)";
  Emission e;
  e.numLights = header.get<uint64_t>();
  e.photons.classicScale = header.get<float>();
  for (MapKind k : kAllMaps) e.budgets[k] = header.get<uint64_t>();
  PerMap<MapExtent> extents;
  uint64_t payloadBytes = 0;
  std::string problem;
  e.photons.batches.forEach([&](auto kind, const auto& batches) {
    using Photon = std::decay_t<decltype(*batches.begin())>;
    MapExtent& x = extents[kind];
    x.recordBytes = header.get<uint32_t>();
    x.count = header.get<uint64_t>();
    if (x.recordBytes == 0 || x.count > UINT64_MAX / kMapKinds / x.recordBytes) {  // so the sum below cannot wrap
      x.count = 0;
      header.ok = false;
    }
    if (header.ok && x.recordBytes != sizeof(Photon) && problem.empty()) {
      problem = fmt::format("{} photons of {} bytes, this penumbra's have {}", mapName(kind), x.recordBytes,
                            sizeof(Photon));
    }
    payloadBytes += x.count * x.recordBytes;
  });
  const uint64_t notes = header.get<uint64_t>();
  for (uint64_t i = 0; header.ok && i < notes; ++i) e.notes.push_back(header.text());
  const uint32_t payloadCrc = header.get<uint32_t>();
  if (!header.ok || header.at != front.size()) return "header damaged (its fields do not add up)";
  if (!problem.empty()) return problem;
  const uint64_t expected = kPreambleBytes + headerBytes + 4 + payloadBytes;
  if (size != expected) {
    return fmt::format("{} ({} bytes, its header says {})", size < expected ? "truncated" : "longer than written",
                       size, expected);
  }

  uint32_t crc = 0;
  bool readOk = true;
  if (out) {
    e.photons.batches.forEach([&](auto kind, auto& batches) {
      using Photon = std::decay_t<decltype(*batches.begin())>;
      PhotonArray<Photon> photons(extents[kind].count);
      const size_t n = photons.size() * sizeof(Photon);
      readOk = readOk && (n == 0 || in.read(reinterpret_cast<char*>(photons.data()), static_cast<std::streamsize>(n)));
      crc = crcOf(crc, photons.data(), readOk ? n : 0);
      batches = PhotonBatches<Photon>(std::move(photons));
    });
  } else {
    std::string chunk(kCheckChunkBytes, '\0');
    for (uint64_t left = payloadBytes; readOk && left > 0;) {
      const size_t n = static_cast<size_t>(std::min<uint64_t>(left, chunk.size()));
      readOk = static_cast<bool>(in.read(chunk.data(), static_cast<std::streamsize>(n)));
      crc = crcOf(crc, chunk.data(), n);
      left -= n;
    }
  }
  if (!readOk) return "cannot read its photons";
  if (crc != payloadCrc) return "photons damaged (their checksum differs)";
  if (out) {
    e.photons.emitted = e.budgets;
    *out = std::move(e);
  }
  return "";
}

Emission loadOrEmit(const std::string& dir, const std::string& keyText, const std::function<Emission()>& emit,
                    MapFileOutcome& outcome, bool keep) {
  const std::string path = mapFilePath(dir, keyText);
  Stopwatch reading;
  Emission e;
  const std::string problem = readMapFile(path, keyText, keep ? &e : nullptr, &outcome.bytes);
  if (problem.empty()) {
    outcome.loaded = true;
    outcome.seconds = reading.seconds();
    return e;
  }
  if (problem != kMapFileMissing) outcome.note = fmt::format("photon maps: {}: {}; emitted again and rewritten", path, problem);
  e = emit();
  Stopwatch writing;
  outcome.bytes = writeMapFile(path, keyText, e);
  outcome.written = true;
  outcome.seconds = writing.seconds();
  return e;
}

}  // namespace penumbra
