// Texture orientation end to end: an OBJ quad facing the camera, its corners' vt in
// the usual convention (v = 0 at the bottom), textured by an MTL map_Kd whose top
// half is red and bottom half blue, renders red above and blue below.
#include "plan/pipeline.h"
#include "io/image_io.h"
#include "support/cli_run.h"
#include <gtest/gtest.h>
#include <fstream>

namespace penumbra {
namespace {

using testing::ScratchDir;

void write(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

TEST(ObjTexture, MtlMapKdIsUprightAsInEveryOtherTool) {
  ScratchDir dir;
  Image tex(8, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) tex.at(x, y) = y < 4 ? Color(1, 0, 0) : Color(0, 0, 1);  // row 0 is the top
  writeImage((dir / "tex.png").string(), tex);
  write((dir / "quad.mtl").string(), "newmtl t\nKd 1 1 1\nKs 0 0 0\nmap_Kd tex.png\n");
  // Counter-clockwise from the bottom left, seen from +z; vt (0,0) at the bottom left.
  write((dir / "quad.obj").string(),
        "mtllib quad.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
        "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl t\nf 1/1 2/2 3/3 4/4\n");
  write((dir / "scene.json").string(), R"({
    "camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "fov": 40, "width": 21, "height": 21},
    "lights": [{"type": "directional", "direction": [0, 0, -1], "intensity": 1}],
    "objects": [{"type": "mesh", "file": "quad.obj"}],
    "render": {"ambient": 0}
  })");
  RenderRequest req;
  req.scenePath = (dir / "scene.json").string();
  req.session.threads = 1;
  const Image img = runRender(req).image;
  const Color top = img.at(10, 6), bottom = img.at(10, 14);
  EXPECT_GT(top.r, 5.0f * top.b) << "top " << top.r << " " << top.b;
  EXPECT_GT(bottom.b, 5.0f * bottom.r) << "bottom " << bottom.r << " " << bottom.b;
}

}  // namespace
}  // namespace penumbra
