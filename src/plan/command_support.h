// What the commands need from the stages besides the render session: a render's
// reports (stats, ray tree, summary), the checked write of a text output and the
// interrupt cleanup behind it, the procedural textures, an unknown option's hint,
// and the process's age. The progress interface a display implements comes with it.
#pragma once
#include "core/progress.h"
#include "plan/pipeline.h"
#include <cstdint>
#include <string>
#include <vector>

namespace penumbra {

// The --trace-pixel JSON of a render that recorded pixel (x, y).
std::string rayTreeReport(const RenderResult& result, int x, int y);
// The lines printed to stderr after a render: the statistics (`detail`: -v or --stats
// adds the reasons of automatic decisions) and the CPU line.
std::string renderSummary(const RenderResult& result, bool detail);

// Writes `text` to `path` whole or not at all (a temp file, checked, then renamed).
void writeTextOutput(const std::string& path, const std::string& text);
// From here on SIGINT and SIGTERM remove the temp files of unfinished writes, never an old output.
void installOutputCleanup();

// `penumbra texture`: the built-in texture `name`, width x width/2, into `path`.
void writeProceduralTexture(const std::string& name, int width, uint64_t seed, const std::string& path);

// " (did you mean \"--threads\"?)" for the closest of `names`; "" when none is close.
std::string optionHint(const std::string& option, const std::vector<std::string>& names);

// A note as a command prints it on stderr: a warning (io/scene_warnings.h) as it is,
// any other after "note: ".
std::string noteLine(const std::string& note);

// Seconds since the process started (what a render's time limit counts); < 0 unknown.
double processSeconds();

}  // namespace penumbra
