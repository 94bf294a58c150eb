// Bad media input through the binary: render, sweep and batch each refuse it in one
// line naming the file, the JSON path and the problem, with exit code 2 and no output.
#include "hard/hard_cli.h"
#include <gtest/gtest.h>
#include <openvdb/openvdb.h>

namespace penumbra {
namespace {

using namespace hard;

// A floor lit by a point light with `media`, more objects and more render keys.
std::string fogScene(const std::string& media, const std::string& extra = "", const std::string& render = "",
                     const std::string& model = "physical") {
  return R"({"camera": {"position": [0, 3, 3], "look_at": [0, 0, 0], "width": 8, "height": 6},
  "lights": [{"type": "point", "position": [0, 2, 0], "intensity": 5}],
  "materials": {"m": {"diffuse": 0.5}},
  "media": )" + media + R"(,
  "objects": [{"type": "quad", "corner": [-1, 0, 1], "edge1": [2, 0, 0], "edge2": [0, 0, -2], "material": "m"})" +
         extra + R"(],
  "render": {"model": ")" + model + "\"" + render + R"(},
  "photons": {"global": 1000, "caustic": 0, "volume": 1000}})";
}

struct Case {
  const char* name;
  std::string scene;
  std::string says;  // the JSON path and the problem
};

std::vector<Case> badCases() {
  const std::string fog = R"([{"name": "fog", "sigma_s": 0.5}])";
  return {
      {"unknown medium", fogScene(fog, "", R"(, "medium": "fgo")"), "render.medium: unknown medium \"fgo\" (did you mean \"fog\"?)"},
      {"duplicate", fogScene(R"([{"name": "fog"}, {"name": "fog"}])"), "media[1].name: duplicate medium name"},
      {"negative sigma", fogScene(R"([{"name": "fog", "sigma_a": -0.1}])"), "media[0].sigma_a: must be between 0 and 1e+30"},
      {"g of one", fogScene(R"([{"name": "fog", "g": 1}])"), "media[0].g:"},
      {"g below minus one", fogScene(R"([{"name": "fog", "g": -1.5}])"), "media[0].g:"},
      {"open mesh", fogScene(fog, R"(, {"type": "quad", "corner": [0, 0, 0], "edge1": [1, 0, 0], "edge2": [0, 1, 0],
                                       "medium": "fog"})"),
       "objects[1].medium: a medium fills a closed object"},
      {"classic", fogScene(fog, "", "", "classic"), "media[0]: media need the physical model"},
      {"missing vdb", fogScene(R"([{"name": "fog", "density": {"file": "gone.vdb"}}])"),
       "media[0].density.file: gone.vdb: cannot open: does not exist"},
      {"not a vdb", fogScene(R"([{"name": "fog", "density": {"file": "scene.json"}}])"),
       "media[0].density.file: scene.json: not an OpenVDB file"},
      {"no such grid", fogScene(R"([{"name": "fog", "density": {"file": "puff.vdb", "grid": "heat"}}])"),
       "media[0].density.file: puff.vdb: has no grid \"heat\" (it has \"density\")"},
      {"negative density", fogScene(R"([{"name": "fog", "density": {"file": "negative.vdb"}}])"),
       "negative.vdb: grid \"density\" has -2 at voxel (0, 0, 0)"},
  };
}

// puff.vdb: one voxel of 1; negative.vdb: one voxel of -2.
void writeGrids(const ScratchDir& dir) {
  openvdb::initialize();
  for (const auto& [file, value] : {std::pair<const char*, float>{"puff.vdb", 1.0f}, {"negative.vdb", -2.0f}}) {
    auto g = openvdb::FloatGrid::create();
    g->setName("density");
    g->tree().setValueOn(openvdb::Coord(0), value);
    openvdb::io::File((dir / file).string()).write({g});
  }
}

void expectRefused(const CliResult& r, const std::string& file, const std::string& says, const std::string& what) {
  EXPECT_EQ(r.exitCode, 2) << what << "\n" << r.err;
  EXPECT_EQ(occurrences(r.err, "\n"), 1u) << what << ": one line\n" << r.err;
  EXPECT_NE(r.err.find(file), std::string::npos) << what << "\n" << r.err;
  EXPECT_NE(r.err.find(says), std::string::npos) << what << ": expected " << says << "\n" << r.err;
}

TEST(HardMediaInputs, EveryCommandRefusesEachInOneLine) {
  for (const Case& c : badCases()) {
    ScratchDir dir;
    writeGrids(dir);
    dir.write("scene.json", c.scene);
    const std::string path = quote((dir / "scene.json").string());
    expectRefused(runCli("render " + path + " -q -o " + quote((dir / "a.png").string())), "scene.json", c.says,
                  std::string("render: ") + c.name);
    EXPECT_FALSE(fs::exists(dir / "a.png")) << c.name;
    expectRefused(runCli("sweep " + path + " -q --spp 1,2 -o " + quote((dir / "sweep").string())), "scene.json",
                  c.says, std::string("sweep: ") + c.name);
    dir.write("jobs.json", R"({"jobs": [{"name": "a", "scene": "scene.json", "output": "b.png"}]})");
    expectRefused(runCli("batch " + quote((dir / "jobs.json").string()) + " -q"), "scene.json", c.says,
                  std::string("batch: ") + c.name);
    EXPECT_FALSE(fs::exists(dir / "b.png")) << c.name;
  }
}

TEST(HardMediaInputs, ExtremeValuesAreAccepted) {
  // sigma 0 and 1e30, g of +-0.999999: valid media, checked through `check`.
  for (const std::string media : {R"([{"name": "fog", "sigma_s": 0, "sigma_a": 0}])",
                                  R"([{"name": "fog", "sigma_s": 1e30, "g": 0.999999}])",
                                  R"([{"name": "fog", "sigma_a": [1e30, 0, 1], "g": -0.999999}])"}) {
    ScratchDir dir;
    dir.write("scene.json", fogScene(media, "", R"(, "medium": "fog")"));
    const CliResult r = runCli("check " + quote((dir / "scene.json").string()));
    EXPECT_EQ(r.exitCode, 0) << media << "\n" << r.err;
  }
}

}  // namespace
}  // namespace penumbra
