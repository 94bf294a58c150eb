// The commands' calls into io and core, so the command line includes only the plan layer.
#include "plan/command_support.h"
#include "plan/cpu_report.h"
#include "plan/media_report.h"
#include "core/cpu_time.h"
#include "io/image_io.h"
#include "io/report_json.h"
#include "io/scene_warnings.h"
#include "io/suggest.h"
#include "io/temp_file.h"
#include "io/texture_gen.h"

namespace penumbra {

std::string rayTreeReport(const RenderResult& result, int x, int y) { return rayTreeToJson(result.rayTree, x, y); }

std::string renderSummary(const RenderResult& result, bool detail) {
  return statsSummary(result.stats, detail) + (result.media ? mediaCountsLine(result.stats) : "") + "  " +
         cpuLine(result.stats.cpu);
}

void writeTextOutput(const std::string& path, const std::string& text) { writeTextFileAtomic(path, text); }

void installOutputCleanup() { installTempFileCleanup(); }

void writeProceduralTexture(const std::string& name, int width, uint64_t seed, const std::string& path) {
  writeImage(path, makeTexture(name, width, width / 2, seed), {{"penumbra:texture", name}});
}

std::string optionHint(const std::string& option, const std::vector<std::string>& names) {
  return didYouMean(option, names);
}

double processSeconds() { return processAgeSeconds(); }

std::string noteLine(const std::string& note) {
  return note.compare(0, kWarningNote.size(), kWarningNote) == 0 ? note : "note: " + note;
}

}  // namespace penumbra
