// penumbra batch against independent renders: every job's image equals a plain
// runRender of the same scene and overrides, camera variants share one photon
// build, layered EXRs hold every view, reruns skip up-to-date jobs, a failing job
// does not stop the batch, and outputs carry a render's header.
#include "plan/batch/batch_jobs.h"
#include "plan/batch/batch_run.h"
#include "plan/pipeline.h"
#include "core/error.h"
#include "io/image_compare.h"
#include "io/image_io.h"
#include "support/cli_run.h"
#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>
#include <filesystem>
#include <map>

namespace penumbra {
namespace {

namespace fs = std::filesystem;
const std::string kScenes = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/";

fs::path writeJobs(const testing::ScratchDir& dir, const std::string& jobs) {
  return dir.write("jobs.json", "{\"set\": [\"camera.width=40\", \"camera.height=30\", \"photons.indirect=20000\"], "
                                "\"jobs\": [" + jobs + "]}");
}

// Every penumbra:* attribute of an image's header.
std::map<std::string, std::string> penumbraHeader(const std::string& path) {
  std::map<std::string, std::string> keys;
  auto in = OIIO::ImageInput::open(path);
  if (!in) return keys;
  for (const OIIO::ParamValue& p : in->spec().extra_attribs)
    if (p.name().string().rfind("penumbra:", 0) == 0) keys[p.name().string()] = p.get_string();
  return keys;
}

TEST(Batch, CameraVariantsShareOnePhotonBuildAndMatchStandaloneRenders) {
  testing::ScratchDir dir;
  const fs::path jobsFile = writeJobs(dir, "{\"scene\": \"" + kScenes + "fig13_cornell_indirect.json\", "
                                           "\"output\": \"out_{i}.exr\", \"orbit\": {\"count\": 3, \"center\": [0, 1, 0], "
                                           "\"radius\": 2.5, \"height\": 0.2, \"from\": -20, \"to\": 20}}");
  BatchRequest req;
  req.jobs = readJobsFile(jobsFile.string());
  req.session.threads = 2;
  ASSERT_EQ(req.jobs.size(), 3u);
  const BatchOutcome out = runBatch(req);
  EXPECT_EQ(out.rendered, 3u);
  EXPECT_EQ(out.photonBuilds, 1u);
  EXPECT_EQ(out.photonReuses, 2u);
  EXPECT_EQ(out.sceneBuilds, 1u);
  EXPECT_EQ(out.sceneReads, 1u);  // three frames, one scene file read
  EXPECT_EQ(out.jobs[1].reused, "scene+photons");
  for (const BatchJob& job : req.jobs) {
    RenderRequest alone;
    alone.scenePath = job.scene;
    alone.overrides = job.overrides;
    alone.session.threads = 2;
    alone.outputPath = (dir / ("alone_" + job.name + ".exr")).string();
    runRender(alone);
    const ImageError e = compareImages(readImage(job.outputs[0].path), readImage(alone.outputPath));
    EXPECT_EQ(e.maxError, 0.0) << job.name;
    // Its header says what the render's does (every setting), and names the job.
    std::map<std::string, std::string> header = penumbraHeader(job.outputs[0].path);
    EXPECT_EQ(header.erase("penumbra:job"), 1u) << job.name;
    EXPECT_EQ(header.erase("penumbra:inputs"), 1u) << job.name;
    EXPECT_EQ(header, penumbraHeader(alone.outputPath)) << job.name;
    EXPECT_GT(header.count("penumbra:photons.indirect"), 0u) << job.name;
  }
  // Unchanged jobs are skipped; --force renders them again.
  const BatchOutcome again = runBatch(req);
  EXPECT_EQ(again.upToDate, 3u);
  EXPECT_EQ(again.rendered, 0u);
  EXPECT_EQ(again.sceneReads, 0u);  // decided from the outputs alone
  req.force = true;
  EXPECT_EQ(runBatch(req).rendered, 3u);
}

TEST(Batch, SeveralViewsGoIntoOneLayeredExr) {
  testing::ScratchDir dir;
  const fs::path jobsFile = writeJobs(dir, "{\"scene\": \"" + kScenes + "fig03_shadows.json\", \"views\": "
                                           "[\"beauty\", \"depth\", \"normal\"], \"output\": \"all.exr\"}");
  BatchRequest req;
  req.jobs = readJobsFile(jobsFile.string());
  ASSERT_EQ(runBatch(req).rendered, 1u);
  auto in = OIIO::ImageInput::open((dir / "all.exr").string());
  ASSERT_TRUE(in);
  // Depth and normal layers keep their values in float, with their coverage as A.
  const std::vector<std::string> expected = {"beauty.R", "beauty.G", "beauty.B", "depth.R", "depth.G", "depth.B",
                                             "depth.A", "normal.R", "normal.G", "normal.B", "normal.A"};
  EXPECT_EQ(in->spec().channelnames, expected);
  EXPECT_EQ(in->spec().channelformat(0), OIIO::TypeDesc::HALF);
  EXPECT_EQ(in->spec().channelformat(3), OIIO::TypeDesc::FLOAT);
  // The beauty layer is the beauty render (first three channels).
  RenderRequest alone;
  alone.scenePath = kScenes + "fig03_shadows.json";
  alone.overrides = req.jobs[0].overrides;
  alone.outputPath = (dir / "beauty.exr").string();
  runRender(alone);
  EXPECT_EQ(compareImages(readImage((dir / "all.exr").string()), readImage(alone.outputPath)).maxError, 0.0);
  // One header for the three layers: the beauty's settings, the layers named in order.
  const std::map<std::string, std::string> header = penumbraHeader((dir / "all.exr").string());
  ASSERT_GT(header.count("penumbra:aov"), 0u);
  EXPECT_EQ(header.at("penumbra:aov"), "beauty,depth,normal");
  EXPECT_EQ(header.at("penumbra:spp"), penumbraHeader(alone.outputPath).at("penumbra:spp"));
  EXPECT_EQ(header.at("penumbra:error"), penumbraHeader(alone.outputPath).at("penumbra:error"));
}

TEST(Batch, ABadJobIsNamedOrSkippedWithKeepGoing) {
  testing::ScratchDir dir;
  const fs::path jobsFile =
      writeJobs(dir, "{\"scene\": \"" + kScenes + "fig03_shadows.json\", \"output\": \"ok.png\"}, "
                     "{\"name\": \"broken\", \"scene\": \"" + kScenes + "fig03_shadows.json\", \"set\": "
                     "[\"render.max_depth=-1\"], \"output\": \"bad.png\"}");
  BatchRequest req;
  req.jobs = readJobsFile(jobsFile.string());
  try {
    runBatch(req);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("batch job 'broken' (jobs[1])"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir / "ok.png")) << "nothing renders before every job is checked";
  req.keepGoing = true;
  const BatchOutcome out = runBatch(req);
  EXPECT_EQ(out.rendered, 1u);
  EXPECT_EQ(out.failed, 1u);
  EXPECT_EQ(out.jobs[1].status.rfind("failed", 0), 0u);
}

TEST(Batch, JobsFileErrorsNameTheJsonPath) {
  testing::ScratchDir dir;
  auto error = [&](const std::string& jobs) {
    try {
      readJobsFile(writeJobs(dir, jobs).string());
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error("{\"scene\": \"a.json\"}").find("jobs[0].output"), std::string::npos);
  EXPECT_NE(error("{\"scene\": \"a.json\", \"output\": \"x.png\", \"views\": [\"beauty\", \"depth\"]}")
                .find("several views need {view}"), std::string::npos);
  EXPECT_NE(error("{\"scene\": \"a.json\", \"output\": \"x.png\", \"colour\": 1}").find("jobs[0].colour"),
            std::string::npos);
  EXPECT_NE(error("{\"scenes\": \"nothing*.json\", \"output\": \"x.png\"}").find("matches no file"), std::string::npos);
}

// {i:0N} pads an orbit's index to N digits (ffmpeg globs sort turn_002 before turn_010);
// {i} stays as it was, and a malformed width is named before anything renders.
TEST(Batch, OrbitIndexIsZeroPaddedWhenAsked) {
  testing::ScratchDir dir;
  auto names = [&](const std::string& output) {
    std::vector<std::string> out;
    for (const BatchJob& job : readJobsFile(writeJobs(dir, "{\"scene\": \"a.json\", \"output\": \"" + output +
                                                            "\", \"orbit\": {\"count\": 11}}").string()))
      out.push_back(fs::path(job.outputs[0].path).filename().string());
    return out;
  };
  const std::vector<std::string> padded = names("turn_{i:03}.png");
  ASSERT_EQ(padded.size(), 11u);
  EXPECT_EQ(padded[2], "turn_002.png");
  EXPECT_EQ(padded[10], "turn_010.png");
  EXPECT_EQ(names("turn_{i}.png")[10], "turn_10.png");
  EXPECT_EQ(names("a{i:01}_{i}.png")[10], "a10_10.png");
  for (const char* bad : {"turn_{i:3}.png", "turn_{i:00}.png", "turn_{i:0}.png", "turn_{i:04.png"}) {
    try {
      names(bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("jobs[0].output"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace penumbra
