// The reader process's plumbing: a child's stdin and stdout, its exit code or signal, the
// output cap and the deadline (core/subprocess.h), and the bytes of a density job and its
// answer (core/density_wire.h), whose decoder trusts no length it reads.
#include "core/density_wire.h"
#include "core/subprocess.h"

#include <gtest/gtest.h>
#include <limits>

namespace penumbra {
namespace {

TEST(Subprocess, ItsOutputIsWhatItWasGivenEvenWhenLargerThanAPipe) {
  std::string input(3 << 20, '\0');
  for (size_t i = 0; i < input.size(); ++i) input[i] = char(i * 7 + i / 4096);
  const ProcessResult r = runProcess("/bin/cat", {}, input, {});
  ASSERT_TRUE(r.started) << r.error;
  EXPECT_EQ(r.exitCode, 0);
  EXPECT_FALSE(r.timedOut);
  EXPECT_EQ(r.output, input);
}

TEST(Subprocess, ExitCodesAndSignalsAreTold) {
  const ProcessResult code = runProcess("/bin/sh", {"-c", "exit 7"}, "", {});
  EXPECT_EQ(code.exitCode, 7);
  EXPECT_EQ(code.signal, 0);
  const ProcessResult killed = runProcess("/bin/sh", {"-c", "kill -SEGV $$"}, "", {});
  EXPECT_EQ(killed.signal, 11);
  EXPECT_EQ(killed.exitCode, -1);
  const ProcessResult missing = runProcess("/nonexistent/reader", {}, "", {});
  EXPECT_FALSE(missing.started);
  EXPECT_FALSE(missing.error.empty());
}

// Neither outcome depends on timing: `yes` never stops writing, `sleep 600` never ends
// within its deadline, and a child that ignores its input still ends.
TEST(Subprocess, AnEndlessWriterIsCappedAndASleeperIsKilledAtItsDeadline) {
  ProcessLimits capped;
  capped.maxOutputBytes = 1 << 20;
  const ProcessResult yes = runProcess("/usr/bin/yes", {}, "", capped);
  EXPECT_TRUE(yes.outputCapped);
  EXPECT_LE(yes.output.size(), size_t(1) << 20);
  EXPECT_EQ(yes.signal, 9);
  ProcessLimits brief;
  brief.seconds = 0.2;
  const ProcessResult sleeper = runProcess("/bin/sleep", {"600"}, std::string(1 << 20, 'x'), brief);
  EXPECT_TRUE(sleeper.timedOut);
  EXPECT_EQ(sleeper.signal, 9);
}

TEST(DensityWire, AJobAndAGridRoundTrip) {
  DensityJob job;
  job.path = "/tmp/smoke.vdb";
  job.request.grid = "density";
  job.request.scale = 2.5;
  job.request.objectToWorld[3] = glm::dvec4(1.0, 2.0, 3.0, 1.0);
  job.request.maxVoxels = 64;
  job.memoryCap = 12345;
  DensityJob back;
  ASSERT_TRUE(decodeJob(encodeJob(job), back));
  EXPECT_EQ(back.path, job.path);
  EXPECT_EQ(back.request.grid, "density");
  EXPECT_EQ(back.request.scale, 2.5);
  EXPECT_EQ(back.request.objectToWorld, job.request.objectToWorld);
  EXPECT_EQ(back.memoryCap, 12345u);
  EXPECT_FALSE(decodeJob(encodeJob(job) + "x", back));
  EXPECT_FALSE(decodeJob(encodeJob(job).substr(0, 20), back));

  DensityGrid g;
  g.nx = 2, g.ny = 3, g.nz = 4;
  g.values.resize(24);
  for (size_t i = 0; i < 24; ++i) g.values[i] = float(i);
  g.worldLo = Vec3(-1.0f), g.worldHi = Vec3(1.0f);
  DensityGrid out;
  ASSERT_EQ(decodeAnswer(encodeAnswer("", g), job.request, out), "");
  EXPECT_EQ(out.nx, 2);
  EXPECT_EQ(out.nz, 4);
  EXPECT_EQ(out.values, g.values);
  EXPECT_EQ(out.worldHi, g.worldHi);
  EXPECT_EQ(decodeAnswer(encodeAnswer("no such grid", g), job.request, out), "no such grid");
}

TEST(DensityWire, AnAnswerThatDisagreesWithItselfOrTheLimitsIsRefused) {
  DensityRequest request;
  request.maxVoxels = 16;
  DensityGrid g;
  g.nx = g.ny = g.nz = 2;
  g.values.assign(8, 1.0f);
  DensityGrid out;
  const std::string good = encodeAnswer("", g);
  EXPECT_EQ(decodeAnswer(good, request, out), "");
  EXPECT_NE(decodeAnswer(good.substr(0, good.size() - 1), request, out), "");
  EXPECT_NE(decodeAnswer(good + "xxxx", request, out), "");
  EXPECT_NE(decodeAnswer("", request, out), "");
  g.nx = g.ny = g.nz = 3;
  g.values.assign(27, 1.0f);
  EXPECT_NE(decodeAnswer(encodeAnswer("", g), request, out), "");  // over maxVoxels
  g.nx = 4;  // 36 values named, 27 sent
  EXPECT_NE(decodeAnswer(encodeAnswer("", g), DensityRequest{}, out), "");
  g.nx = g.ny = 1 << 30, g.nz = 16;  // 2^64 voxels: wraps to 0, and no values are sent
  g.values.clear();
  EXPECT_NE(decodeAnswer(encodeAnswer("", g), DensityRequest{}, out), "");
  g.nx = g.ny = g.nz = 2;
  g.values.assign(8, 1.0f);
  g.worldHi = Vec3(std::numeric_limits<float>::infinity());
  EXPECT_NE(decodeAnswer(encodeAnswer("", g), request, out), "");
}

}  // namespace
}  // namespace penumbra
