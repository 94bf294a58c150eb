// A private scratch folder for fuzz targets whose loaders take a path, not bytes:
// RAM-backed when possible, one per process, files unlinked and recreated.
#pragma once
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace penumbra_fuzz {

namespace fs = std::filesystem;

// RAM-backed when possible: on ext4, rewriting a truncated file flushes it on
// close (auto_da_alloc), which cut the run to ~200 inputs/s.
fs::path scratchRoot() {
  std::error_code ec;
  if (std::getenv("TMPDIR") == nullptr && fs::is_directory("/dev/shm", ec)) return "/dev/shm";
  return fs::temp_directory_path();
}

// One private folder per process (libFuzzer -jobs/-fork run several at once),
// removed at exit. Files are unlinked and recreated, never truncated in place.
class Scratch {
 public:
  Scratch() {
    std::string pattern = (scratchRoot() / "penumbra_fuzz.XXXXXX").string();
    if (!mkdtemp(pattern.data())) {
      std::perror("fuzz: mkdtemp");
      std::abort();
    }
    dir_ = pattern;
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string write(const char* name, const std::string& text) const {
    std::string path = (dir_ / name).string();
    ::unlink(path.c_str());
    std::ofstream out(path, std::ios::binary);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    if (!out) {
      std::fprintf(stderr, "fuzz: cannot write %s\n", path.c_str());
      std::abort();
    }
    return path;
  }

 private:
  fs::path dir_;
};

}  // namespace penumbra_fuzz
