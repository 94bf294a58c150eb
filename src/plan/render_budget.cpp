// The stop rule of a budgeted render, in one place.
#include "plan/render_budget.h"
#include "core/error.h"
#include "core/scene.h"
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <cmath>

namespace penumbra {

namespace {

// "target error reached: lighting noise 0.0041 and bias 0.002, together 0.0046 <= 0.005";
// empty while the figure is above the target or its bias is not measured yet.
std::string targetReached(const RenderBudget& b, const ErrorEstimate& e) {
  // A frame whose every pixel sees an emitter has no lighting figure: the image's stands in.
  const bool lighting = b.figure == ErrorFigure::Lighting && e.lightingKnown();
  const double noise = lighting ? e.lightingNoiseRmse : e.noiseRmse;
  double bias = lighting ? e.lightingBiasRmse : e.biasRmse;
  if (noise < 0.0 || bias < 0.0) return "";
  // The bound is the lighting's; over the whole image it spreads over more pixels.
  const bool bound = b.bias == BiasFigure::Bound && e.lightingBiasBound >= 0.0;
  if (bound) bias = lighting ? e.lightingBiasBound : e.lightingBiasBound * std::sqrt(1.0 - e.emitterShare);
  const double total = bound ? std::sqrt(noise * noise + bias * bias) : lighting ? e.lightingTotalRmse() : e.totalRmse();
  if (!(total <= b.targetError)) return "";
  return fmt::format("target error reached: {} noise {:.3g} and bias {}{:.3g}, together {:.3g} <= {:g}",
                     kErrorFigureNames[static_cast<size_t>(lighting ? ErrorFigure::Lighting : ErrorFigure::Image)],
                     noise, bound ? "bound " : "", bias, total, b.targetError);
}

}  // namespace

std::string budgetStop(const RenderBudget& b, const BudgetState& s) {
  if (s.passes < 2) return "";
  if (b.targetError > 0.0) {
    std::string reached = targetReached(b, s.error);
    if (!reached.empty()) return reached;
  }
  if (s.passes >= kBudgetMaxPasses) return "pass limit reached";
  if (b.seconds > 0.0) {
    if (s.passes == 2 && s.elapsed > b.seconds) {
      return fmt::format("time limit: the 2-pass minimum overran it by {:.3g} s ({:.0f}%)", s.elapsed - b.seconds,
                         100.0 * (s.elapsed - b.seconds) / b.seconds);
    }
    if (s.elapsed >= b.seconds) return "time limit reached";
    // The next pass is expected to take as long as the last one.
    if (s.elapsed + s.lastPass > b.seconds * (1.0 + kTimeLimitOverrun)) return "time limit: the next pass would overrun it";
  }
  return "";
}

ErrorFigure parseErrorFigure(const std::string& name) {
  for (size_t i = 0; i < kErrorFigureNames.size(); ++i)
    if (name == kErrorFigureNames[i]) return static_cast<ErrorFigure>(i);
  throw InputError(fmt::format("--target-error-of: '{}' is not a figure (use {})", name,
                               fmt::join(kErrorFigureNames, " or ")));
}

BiasFigure parseBiasFigure(const std::string& name) {
  for (size_t i = 0; i < kBiasFigureNames.size(); ++i)
    if (name == kBiasFigureNames[i]) return static_cast<BiasFigure>(i);
  throw InputError(fmt::format("--target-bias: '{}' is not a figure (use {})", name, fmt::join(kBiasFigureNames, " or ")));
}

RenderBudget frameBudget(const RenderBudget& asked, const LoadReport& load) {
  if (asked.any() || load.modelFile.empty() || load.qualityGiven) return asked;
  // The model's limits, with the figures the user chose.
  RenderBudget b = kModelBudget;
  b.figure = asked.figure;
  b.bias = asked.bias;
  return b;
}

std::string modelBudgetNote(const std::string& scene) {
  return fmt::format("{}: no quality set; passes run until the lighting's noise and bias together are at most {:g} "
                     "RMSE or {:g} s have passed, "
                     "whichever comes first (camera.spp, photons.passes, --time-limit or --target-error set your own)",
                     scene, kModelTargetError, kModelTimeLimit);
}

std::string describeBudget(const RenderBudget& b) {
  std::string out;
  if (b.seconds > 0.0) out = fmt::format("--time-limit {:g} s", b.seconds);
  if (b.targetError > 0.0) {
    out += fmt::format("{}--target-error {:g} ({}{})", out.empty() ? "" : ", ", b.targetError,
                       kErrorFigureNames[static_cast<size_t>(b.figure)], b.bias == BiasFigure::Bound ? ", bias bound" : "");
  }
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
