// OpenVDB density grids: files written here with OpenVDB itself are read back (through the
// reader process) into the dense lattice (values, placement, majorant), and each bad file
// is refused in words.
#include "core/density_codec.h"
#include "core/error.h"
#include "io/scene_loader.h"
#include "io/vdb_reader.h"

#include <gtest/gtest.h>
#include <openvdb/openvdb.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

using namespace penumbra;
namespace fs = std::filesystem;

namespace {

class Vdb : public ::testing::Test {
 protected:
  void SetUp() override {
    openvdb::initialize();
    dir_ = fs::temp_directory_path() / ("penumbra_vdb_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // A float grid "density" with voxel (i, j, k) = value(i, j, k) on [0, n)^3, voxel size
  // `voxel`, its index origin at `origin` in world space.
  template <typename F>
  openvdb::FloatGrid::Ptr grid(int n, double voxel, openvdb::Vec3d origin, F value, const std::string& name = "density") {
    auto g = openvdb::FloatGrid::create(0.0f);
    g->setName(name);
    auto t = openvdb::math::Transform::createLinearTransform(voxel);
    t->postTranslate(origin);
    g->setTransform(t);
    auto acc = g->getAccessor();
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        for (int k = 0; k < n; ++k) acc.setValueOn(openvdb::Coord(i, j, k), value(i, j, k));
    return g;
  }
  std::string write(const std::string& file, const openvdb::GridPtrVec& grids) const {
    const std::string path = (dir_ / file).string();
    openvdb::io::File(path).write(grids);
    return path;
  }
  static std::string problem(const std::string& path, const DensityRequest& request = {}) {
    try {
      loadDensityGrid(path, request);
    } catch (const VdbError& e) {
      return e.what();
    }
    return "";
  }
  fs::path dir_;
};

TEST_F(Vdb, ValuesAndPlacementRoundTrip) {
  auto ramp = [](int i, int j, int k) { return float(i + 10 * j + 100 * k); };
  const std::string path = write("ramp.vdb", {grid(4, 0.5, {1.0, 2.0, 3.0}, ramp)});
  DensityRequest request;
  request.scale = 2.0;
  const DensityGrid g = loadDensityGrid(path, request);
  ASSERT_EQ(g.nx, 4);
  ASSERT_EQ(g.ny, 4);
  ASSERT_EQ(g.nz, 4);
  EXPECT_EQ(g.voxel(3, 2, 1), 2.0f * 123.0f);
  EXPECT_EQ(g.maxDensity, 2.0f * 333.0f);
  // Voxel (i, j, k)'s centre sits at origin + 0.5 (i, j, k).
  EXPECT_NEAR(g.at(Vec3(1.0f + 1.5f, 2.0f + 1.0f, 3.0f + 0.5f)), 2.0f * 123.0f, 1e-3f);
  EXPECT_NEAR(g.at(Vec3(1.0f + 0.75f, 2.0f, 3.0f)), 2.0f * 1.5f, 1e-3f);  // halfway between voxels 1 and 2 in x
  EXPECT_EQ(g.at(Vec3(-5.0f)), 0.0f);
  // The world box reaches one voxel beyond the outer centres, where trilinear falls to 0.
  EXPECT_NEAR(g.worldLo.x, 0.5f, 1e-5f);
  EXPECT_NEAR(g.worldHi.z, 3.0f + 2.0f, 1e-5f);
}

TEST_F(Vdb, TheObjectsTransformMovesTheGrid) {
  const std::string path = write("one.vdb", {grid(2, 1.0, {0, 0, 0}, [](int, int, int) { return 1.0f; })});
  DensityRequest request;
  request.objectToWorld = glm::dmat4(1.0);
  request.objectToWorld[3] = glm::dvec4(10.0, 0.0, 0.0, 1.0);
  const DensityGrid g = loadDensityGrid(path, request);
  EXPECT_EQ(g.at(Vec3(0.5f, 0.5f, 0.5f)), 0.0f);
  EXPECT_NEAR(g.at(Vec3(10.5f, 0.5f, 0.5f)), 1.0f, 1e-6f);
}

TEST_F(Vdb, TheNamedGridOrTheFirstFloatGrid) {
  auto vec = openvdb::Vec3SGrid::create();
  vec->setName("velocity");
  vec->tree().setValueOn(openvdb::Coord(0), openvdb::Vec3s(1.0f));
  auto heat = grid(1, 1.0, {0, 0, 0}, [](int, int, int) { return 3.0f; }, "heat");
  EXPECT_EQ(loadDensityGrid(write("heat.vdb", {vec, heat}), {}).maxDensity, 3.0f);  // the float grid after a vector one
  const std::string path = write("two.vdb", {vec, heat, grid(1, 1.0, {0, 0, 0}, [](int, int, int) { return 5.0f; })});
  DensityRequest named;
  named.grid = "density";
  EXPECT_EQ(loadDensityGrid(path, named).maxDensity, 5.0f);
  named.grid = "velocity";
  EXPECT_NE(problem(path, named).find("not float"), std::string::npos) << problem(path, named);
  named.grid = "densty";
  // OpenVDB lists a file's grids by name.
  EXPECT_EQ(problem(path, named), "has no grid \"densty\" (it has \"density\", \"heat\", \"velocity\")");
  EXPECT_EQ(problem(write("vec.vdb", {vec})), "has no float grid");
}

TEST_F(Vdb, BadFilesAreRefused) {
  EXPECT_NE(problem((dir_ / "missing.vdb").string()).find("cannot open: does not exist"), std::string::npos)
      << problem((dir_ / "missing.vdb").string());
  std::ofstream(dir_ / "text.vdb") << "{\"not\": \"a vdb\"}";
  EXPECT_EQ(problem((dir_ / "text.vdb").string()), "not an OpenVDB file");
  std::ofstream(dir_ / "empty.vdb");
  EXPECT_EQ(problem((dir_ / "empty.vdb").string()), "not an OpenVDB file");
  const std::string negative = write("neg.vdb", {grid(2, 1.0, {0, 0, 0}, [](int i, int, int) { return i ? -1.0f : 1.0f; })});
  EXPECT_NE(problem(negative).find("has -1 at voxel (1, 0, 0)"), std::string::npos) << problem(negative);
  const std::string nan = write("nan.vdb", {grid(1, 1.0, {0, 0, 0}, [](int, int, int) { return NAN; })});
  EXPECT_NE(problem(nan).find("finite"), std::string::npos) << problem(nan);
  auto empty = openvdb::FloatGrid::create();
  empty->setName("density");
  EXPECT_NE(problem(write("none.vdb", {empty})).find("no active voxels"), std::string::npos);
}

TEST_F(Vdb, TheVoxelBudgetIsCheckedBeforeTheLattice) {
  // Two voxels far apart: a box of 1001^3 from two values.
  auto sparse = openvdb::FloatGrid::create();
  sparse->setName("density");
  sparse->tree().setValueOn(openvdb::Coord(0), 1.0f);
  sparse->tree().setValueOn(openvdb::Coord(1000), 1.0f);
  const std::string path = write("sparse.vdb", {sparse});
  DensityRequest request;
  request.maxVoxels = 1000000;
  EXPECT_NE(problem(path, request).find("1003003001 voxels, more than the 1000000"), std::string::npos)
      << problem(path, request);
}

TEST_F(Vdb, NonLinearTransformsAreRefused) {
  auto g = grid(2, 1.0, {0, 0, 0}, [](int, int, int) { return 1.0f; });
  g->setTransform(openvdb::math::Transform::createFrustumTransform(
      openvdb::BBoxd(openvdb::Vec3d(0), openvdb::Vec3d(10)), 0.5, 2.0, 1.0));
  EXPECT_NE(problem(write("frustum.vdb", {g})).find("not linear"), std::string::npos);
}

TEST_F(Vdb, ASceneReadsItsDensityAndListsTheFile) {
  write("puff.vdb", {grid(3, 0.25, {0, 0, 0}, [](int, int, int) { return 2.0f; })});
  const std::string json = R"({"camera": {"position": [0, 0, 5]}, "lights": [{"type": "point", "position": [0, 3, 0]}],
      "media": [{"name": "smoke", "sigma_s": 1, "density": {"file": "puff.vdb", "scale": 0.5,
                 "transform": {"translate": [1, 0, 0]}}}],
      "objects": [{"type": "box", "min": [0, -1, -1], "max": [2, 1, 1], "medium": "smoke"}],
      "render": {"model": "physical"}})";
  const Scene s = parseScene(json, (dir_ / "x.json").string());
  ASSERT_TRUE(s.media[0].density);
  EXPECT_EQ(s.media[0].density->maxDensity, 1.0f);
  EXPECT_NEAR(s.media[0].density->at(Vec3(1.25f, 0.25f, 0.25f)), 1.0f, 1e-6f);
  EXPECT_NE(std::find(s.inputs.begin(), s.inputs.end(), (dir_ / "puff.vdb").string()), s.inputs.end());
  try {
    parseScene(json, (dir_ / "x.json").string(), {"media[0].density.file=gone.vdb"});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("media[0].density.file: gone.vdb: cannot open: does not exist"),
              std::string::npos)
        << e.what();
  }
}

// The fuzzer's findings in OpenVDB, which trusts the lengths a file states: a chunk
// size of exabytes, and a metadata string of 1.7 GB that it fills before reading. Each is
// a one-line refusal from the reader process (its allocation cap, or its end: under ASan
// the allocation aborts it), and this process never holds the memory.
TEST_F(Vdb, AChunkSizeOfExabytesIsRefused) {
  const std::string path =
      std::string(PENUMBRA_SOURCE_DIR) + "/fuzz/crashers/fuzz_vdb_reader/blosc_chunk_size_exabytes.vdb";
  EXPECT_EQ(problem(path).rfind("cannot be read (", 0), 0u) << problem(path);
}

TEST_F(Vdb, AMetadataStringOfGigabytesIsRefusedUnderTheReadersCap) {
  const std::string path =
      std::string(PENUMBRA_SOURCE_DIR) + "/fuzz/crashers/fuzz_vdb_reader/metadata_string_1_7gb.vdb";
  DensityRequest request;
  request.maxVoxels = 1 << 20;  // a 4 MB lattice: the reader may hold 140 MB
  EXPECT_LT(densityMemoryCap(request), uint64_t(1700) << 20);
  EXPECT_EQ(problem(path, request).rfind("cannot be read (", 0), 0u) << problem(path, request);
}

TEST_F(Vdb, TheShippedSmokeLoads) {
  const Scene s = loadScene(std::string(PENUMBRA_SOURCE_DIR) + "/scenes/smoke.json");
  ASSERT_TRUE(s.media.at(0).density);
  EXPECT_EQ(s.media[0].density->nx, 24);
  EXPECT_GT(s.media[0].density->maxDensity, 0.5f);
  EXPECT_LE(s.media[0].density->maxDensity, 1.0f);
}

}  // namespace
