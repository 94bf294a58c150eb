// The bytes between penumbra and its OpenVDB reader process (core/density_codec.h): a
// request (the file and its limits) on the reader's stdin, a density grid or the problem
// in words on its stdout. Host byte order: both ends are the same build.
#pragma once
#include "core/density_codec.h"
#include <string>

namespace penumbra {

struct DensityJob {
  std::string path;
  DensityRequest request;
  uint64_t memoryCap = 0;  // the reader process's allocations, in bytes (0: no cap)
  double seconds = 0.0;    // the reader's own deadline, a second past the caller's (0: none)
};

std::string encodeJob(const DensityJob& job);
// False when `bytes` is not a whole job.
bool decodeJob(const std::string& bytes, DensityJob& job);

// A grid (problem empty) or a problem.
std::string encodeAnswer(const std::string& problem, const DensityGrid& grid);
// The problem, "" with `grid` filled, or why the bytes are not an answer within the
// request's limits (a lattice over maxVoxels, sizes that disagree, a short answer).
std::string decodeAnswer(const std::string& bytes, const DensityRequest& request, DensityGrid& grid);

}  // namespace penumbra
