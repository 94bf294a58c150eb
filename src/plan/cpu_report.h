// CPU time in every report that shows wall time: the --stats fields (cpu_s,
// cpu_share, load_avg_1m), the summary's cpu line, and the note that says times
// are contended (share below kContendedShare, core/cpu_time.h).
#pragma once
#include "core/cpu_time.h"
#include "plan/pipeline.h"
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

namespace penumbra {

// Writes cpu_s, cpu_share and load_avg_1m (null when unknown) into `j`.
void addCpuFields(nlohmann::json& j, const CpuTiming& t);

// "cpu 2.31 s (user + sys), share 0.97 of 2 threads, load 0.52 at start"
std::string cpuLine(const CpuTiming& t);

// One line when any of `spans` (each one `what`: "render", "run", "job") had a CPU
// share below kContendedShare; empty when all had their cores.
std::string contendedNote(const std::vector<CpuTiming>& spans, const std::string& what);

// The --stats JSON of a render: its statistics, the CPU fields, the up-front
// estimate and the notes, in one object.
std::string statsReport(const RenderResult& result);

}  // namespace penumbra
