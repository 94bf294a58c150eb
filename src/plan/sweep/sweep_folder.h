// Which sweep a folder belongs to: sweep.json beside results.csv names everything
// that changes a row besides its knob values, and a rerun resumes only its own.
#pragma once
#include <string>
#include <vector>

namespace penumbra {

struct SweepRequest;  // plan/sweep/sweep_run.h
struct SweepSpec;     // plan/sweep/sweep_spec.h

struct SweepIdentity {
  std::string scene;                   // the scene path as given
  std::string sceneFiles;              // inputsStamp of every file the scene read
  std::vector<std::string> overrides;  // --set values every run shares (not the knobs')
  std::string view;                    // --aov, empty: the scene's
  std::vector<std::string> plan;       // --enable / --disable, as "+gate" / "-packets"
  std::string reference;               // --reference path and stamp; empty: the sweep's own
};

// The identity of `req`'s sweep, whose first run read the files `inputs`: everything
// but the knobs' own --set values.
SweepIdentity sweepIdentity(const SweepRequest& req, const std::vector<std::string>& inputs);

// Throws InputError naming the folder and what differs (the scene, its files, the
// --set values, the view, the plan overrides or the reference) when the folder holds
// another sweep's results, or results.csv without a sweep.json. Nothing there: fine.
void checkSweepFolder(const std::string& dir, const SweepIdentity& identity);

// Throws InputError naming the first file of the folder the sweep could not write
// (outputPathProblem: a run's name grows with its knobs), before any render.
void checkSweepFiles(const std::string& dir, const SweepSpec& spec);

// Writes sweep.json (atomically), before the first row.
void writeSweepFolder(const std::string& dir, const SweepIdentity& identity);

}  // namespace penumbra
