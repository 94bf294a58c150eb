// The stop rule of a budgeted render, in one place.
#include "plan/render_budget.h"
#include "core/error.h"
#include "core/scene.h"
#include <fmt/format.h>
#include <cmath>

namespace penumbra {

const char* budgetStop(const RenderBudget& b, const BudgetState& s) {
  if (s.passes < 2) return nullptr;
  if (b.targetError > 0.0 && s.noiseRmse >= 0.0 && s.noiseRmse <= b.targetError) return "target error reached";
  if (s.passes >= kBudgetMaxPasses) return "pass limit reached";
  if (b.seconds > 0.0) {
    if (s.elapsed >= b.seconds) return "time limit reached";
    // The next pass is expected to take as long as the last one.
    if (s.elapsed + s.lastPass > b.seconds * (1.0 + kTimeLimitOverrun)) return "time limit: the next pass would overrun it";
  }
  return nullptr;
}

RenderBudget frameBudget(const RenderBudget& asked, const LoadReport& load) {
  if (asked.any() || load.modelFile.empty() || load.qualityGiven) return asked;
  return kModelBudget;
}

std::string modelBudgetNote(const std::string& scene) {
  return fmt::format("{}: no quality set; passes run until the noise RMSE is at most {:g} or {:g} s have passed, "
                     "whichever comes first (camera.spp, photons.passes, --time-limit or --target-error set your own)",
                     scene, kModelTargetError, kModelTimeLimit);
}

std::string describeBudget(const RenderBudget& b) {
  std::string out;
  if (b.seconds > 0.0) out = fmt::format("--time-limit {:g} s", b.seconds);
  if (b.targetError > 0.0) out += fmt::format("{}--target-error {:g}", out.empty() ? "" : ", ", b.targetError);
  return b.modelDefault ? "the model default (" + out + ")" : out;
}

void checkBudget(const RenderBudget& b) {
  if (!std::isfinite(b.seconds) || b.seconds < 0.0) {
    throw InputError(fmt::format("--time-limit: {} is not a number of seconds >= 0", b.seconds));
  }
  if (!std::isfinite(b.targetError) || b.targetError < 0.0) {
    throw InputError(fmt::format("--target-error: {} is not an RMSE >= 0", b.targetError));
  }
}

}  // namespace penumbra
