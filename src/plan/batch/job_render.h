// One batch job's frames: every view rendered from the same photon maps, and its
// files written with the job's stamp and the record of what it read.
#pragma once
#include "plan/batch/batch_run.h"
#include "plan/batch/job_state.h"
#include "plan/render_session.h"
#include <string>
#include <vector>

namespace penumbra {

struct JobRender {
  bool sceneReused = false, photonsReused = false;
  std::vector<std::string> notes;  // a view resumed from saved passes, or why they were not used
};

// Renders `views` (planned and prepared, one per output of `job`) and writes each
// output file once (several views of one .exr as its layers; a tile's views as part
// files, plan/frame_part.h); then the views' saved passes are removed: nothing is
// left to resume.
// What each output's header says of the job: its stamp, a tile's frame stamp (the
// untiled job's, which the merged frame carries) and the files it read.
struct JobStamps {
  std::string job, frame;
  std::vector<InputRecord> inputs;
};
JobRender renderJob(RenderSession& session, const BatchJob& job, const std::vector<PlannedJob>& views,
                    const JobStamps& stamps);

}  // namespace penumbra
