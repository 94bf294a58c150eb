// The merge subcommand: its options and its one summary line; the checks and the
// paste are plan/frame_merge's.
#include "cli/merge_command.h"
#include "plan/frame_merge.h"
#include <iostream>

namespace penumbra {

MergeCommand::MergeCommand(CLI::App& app) {
  command_ = app.add_subcommand("merge", "Merge the part files of a tiled render (render --tile, a jobs file's "
                                         "\"tiles\") into one frame, byte-identical to the whole render");
  command_->add_option("parts", parts_, "Part files (.exr), in any order")->required();
  command_->add_option("-o,--output", output_, "The frame: .png or .exr")->required();
  addSessionOptions(*command_, args_, kQuietOption | kDisplayOption, "");
}

int MergeCommand::run() {
  const MergeOutcome m = mergeFrame(parts_, output_, args_.display());
  if (!args_.quiet) {
    std::cerr << "merged " << m.parts << " parts into " << output_ << " (" << m.width << "x" << m.height
              << "); error: " << m.error << "\n";
  }
  return 0;
}

}  // namespace penumbra
