// Loading stays inside the memory budget and seconds: instances of a big mesh are
// refused at the object that passes the budget, a texture whose header claims
// billions of pixels is refused before one is decoded.
#include "hard/hard_cli.h"
#include <gtest/gtest.h>
#include <array>
#include <chrono>

namespace penumbra {
namespace {

using namespace hard;

TEST(HardLoadBudget, InstancesAreRefusedAtTheObjectThatPassesTheBudget) {
  ScratchDir dir;
  // A 100 x 100 grid OBJ (20k triangles, ~0.5 MB in memory) placed 1000 times
  // against a 64 MB budget: refused at an object near the 120th.
  std::string obj;
  for (int y = 0; y <= 100; ++y)
    for (int x = 0; x <= 100; ++x) obj += "v " + std::to_string(x) + " 0 " + std::to_string(y) + "\n";
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 100; ++x) {
      const int a = y * 101 + x + 1;
      obj += "f " + std::to_string(a) + " " + std::to_string(a + 1) + " " + std::to_string(a + 102) + " " +
             std::to_string(a + 101) + "\n";
    }
  dir.write("grid.obj", obj);
  std::string objects;
  for (int i = 0; i < 1000; ++i) {
    objects += std::string(i ? "," : "") + R"({"type": "mesh", "file": "grid.obj", "translate": [0, )" +
               std::to_string(i) + ", 0]}";
  }
  const std::string scene = quote(dir.write("s.json", R"({"camera": {"position": [50, 300, -200],
    "look_at": [50, 0, 50], "width": 16, "height": 12},
    "lights": [{"type": "point", "position": [50, 2000, 50], "intensity": 5}], "objects": [)" + objects + "]}")
                                         .string());
  const CliResult r = runCli("render " + scene + " -q -o " + quote((dir / "a.png").string()) + " --max-memory 64M");
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("the scene's meshes would reach"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--max-memory"), std::string::npos) << r.err;
}

TEST(HardLoadBudget, TeapotsAreJudgedByTheirGridBeforeTessellation) {
  ScratchDir dir;
  // 64 teapots of ~1M triangles (subdivisions 128), ~2 GB of mesh against 256 MB.
  std::string objects;
  for (int i = 0; i < 64; ++i) {
    objects += std::string(i ? "," : "") + R"({"type": "teapot", "subdivisions": 128, "translate": [)" +
               std::to_string(i * 4) + ", 0, 0]}";
  }
  const std::string scene = quote(dir.write("s.json", R"({"camera": {"position": [0, 3, 8], "look_at": [0, 0, 0],
    "width": 16, "height": 12}, "lights": [{"type": "point", "position": [0, 5, 0], "intensity": 5}],
    "objects": [)" + objects + "]}").string());
  const CliResult small = runCli("render " + scene + " -q -o " + quote((dir / "a.png").string()) +
                                 " --max-memory 256M");
  EXPECT_EQ(small.exitCode, 2) << small.err;
  EXPECT_NE(small.err.find("]: the scene's meshes would reach"), std::string::npos) << small.err;
}

// CRC-32 (PNG's chunk checksum), bit by bit: a test writes a handful of bytes.
uint32_t crc32(const std::string& bytes) {
  uint32_t c = 0xFFFFFFFFu;
  for (unsigned char b : bytes) {
    c ^= b;
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
  }
  return c ^ 0xFFFFFFFFu;
}

std::string be32(uint32_t v) {
  return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
}

// A PNG whose header says `width` x `height` RGB pixels, with no pixel data at all.
std::string pngClaiming(uint32_t width, uint32_t height) {
  const std::string ihdr = "IHDR" + be32(width) + be32(height) + std::string("\x08\x02\x00\x00\x00", 5);
  const std::string idat = "IDAT" + std::string("\x78\x9c\x03\x00\x00\x00\x00\x01", 8);  // an empty zlib stream
  return std::string("\x89PNG\r\n\x1a\n", 8) + be32(13) + ihdr + be32(crc32(ihdr)) + be32(8) + idat +
         be32(crc32(idat)) + be32(0) + "IEND" + be32(crc32("IEND"));
}

TEST(HardLoadBudget, ATextureHeaderClaimingBillionsOfPixelsIsRefusedUnread) {
  ScratchDir dir;
  dir.write("bomb.png", pngClaiming(100000, 100000));
  const std::string scene = quote(dir.write("s.json", R"({"camera": {"position": [0, 3, 3], "look_at": [0, 0, 0],
    "width": 16, "height": 12}, "lights": [{"type": "point", "position": [0, 2, 0], "intensity": 5}],
    "materials": {"m": {"diffuse": 0.5, "texture": {"file": "bomb.png"}}},
    "objects": [{"type": "quad", "material": "m", "corner": [-1, 0, 1], "edge1": [2, 0, 0], "edge2": [0, 0, -2]}]})")
                                         .string());
  const CliResult r = runCli("check " + scene);
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("100000x100000 pixels"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace penumbra
