// Every scene shipped in scenes/ must load: a broken example is a bug.
#include "io/scene_loader.h"
#include <gtest/gtest.h>
#include <filesystem>

using namespace penumbra;

TEST(ShippedScenes, AllParse) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(PENUMBRA_SOURCE_DIR) + "/scenes")) {
    if (entry.path().extension() != ".json") continue;
    SCOPED_TRACE(entry.path().string());
    Scene scene;
    EXPECT_NO_THROW(scene = loadScene(entry.path().string()));
    EXPECT_FALSE(scene.materials.empty());
    EXPECT_FALSE(scene.spheres.empty() && scene.meshes.empty());
    EXPECT_EQ(scene.name, entry.path().stem().string()) << "scene name should match its file";
    ++count;
  }
  EXPECT_GE(count, 15) << "figures 1-14 and the showcase";
}
