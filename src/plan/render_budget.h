// Renders to a budget (--time-limit, --target-error): progressive passes run until
// the budget is met, and the image equals a render of the same scene with
// photons.passes set to the passes done.
#pragma once
#include "core/error_estimate.h"
#include <array>
#include <functional>
#include <string>

namespace penumbra {

// The most passes a budget runs (photons.passes' own bound).
constexpr int kBudgetMaxPasses = 100000;
// A pass is not started when it would end past the time limit by more than this share
// of it: the render then stops short of the limit by less than one pass.
constexpr double kTimeLimitOverrun = 0.1;

// Which error a target error aims at: the lighting's (pixels that see no emitter, the
// default: a visible emitter's aliased edge is the camera's, not the lighting's) or the
// whole image's.
enum class ErrorFigure { Lighting, Image };
// In enum order (--target-error-of).
inline constexpr std::array<const char*, 2> kErrorFigureNames = {"lighting", "image"};

// Which bias a target error counts: the bias that stands out of its noise (the
// default), or its bound, which adds what noise may hide (ErrorEstimate::
// lightingBiasBound; where the frame has none, the bias that stands out).
enum class BiasFigure { Counted, Bound };
// In enum order (--target-bias).
inline constexpr std::array<const char*, 2> kBiasFigureNames = {"counted", "bound"};

struct RenderBudget {
  double seconds = 0.0;      // --time-limit: wall seconds of the job; 0 = none
  // --target-error: the RMSE of noise and photon-map bias together, sqrt(noise^2 +
  // bias^2), to reach; 0 = none
  double targetError = 0.0;
  bool modelDefault = false;  // kModelBudget, which the user did not give
  ErrorFigure figure = ErrorFigure::Lighting;  // --target-error-of
  BiasFigure bias = BiasFigure::Counted;       // --target-bias
  bool any() const { return seconds > 0.0 || targetError > 0.0; }
};

// What a glTF or OBJ file given as the scene renders to when nothing sets its quality
// (no camera.spp, photons.passes, --spp, --time-limit or --target-error): passes until
// the lighting's noise and bias together are at most kModelTargetError, a figure that
// only depends on the scene and seed, or until kModelTimeLimit seconds have passed,
// whichever comes first.
constexpr double kModelTargetError = 0.005;
constexpr double kModelTimeLimit = 60.0;
constexpr RenderBudget kModelBudget{kModelTimeLimit, kModelTargetError, true, ErrorFigure::Lighting};

struct LoadReport;
// The budget a whole frame renders to: `asked` when it names one, kModelBudget for a
// model scene that sets no quality (LoadReport::modelFile, qualityGiven), else none.
RenderBudget frameBudget(const RenderBudget& asked, const LoadReport& load);
// The note of a frame that renders to kModelBudget: "SCENE: no quality set; passes
// run until ..., whichever comes first (... set your own)".
std::string modelBudgetNote(const std::string& scene);

// Where a budgeted render stands after a pass.
struct BudgetState {
  int passes = 0;             // passes done
  double elapsed = 0.0;       // the job's wall seconds so far
  double lastPass = 0.0;      // the last pass's wall seconds (photons, maps, render)
  ErrorEstimate error;        // the estimate after the last pass
};

// Empty while another pass should run; else why the render stops, naming the figure
// ("target error reached: lighting noise 0.004 and bias 0.002, together 0.0045 <=
// 0.005", "time limit reached", ...). Two passes always run: the estimate needs them;
// a target error also waits for the bias check (4 passes) so that it counts the bias.
std::string budgetStop(const RenderBudget& budget, const BudgetState& s);

// "--time-limit 10 s" / "--target-error 0.03 (lighting)" / both, for notes and --stats;
// the model default says so ("the model default (--time-limit 60 s, --target-error 0.005 (lighting))").
std::string describeBudget(const RenderBudget& budget);

// Throws InputError (exit 2) for a negative or non-finite limit.
void checkBudget(const RenderBudget& budget);

// The figure named `name` (kErrorFigureNames); throws InputError naming them otherwise.
ErrorFigure parseErrorFigure(const std::string& name);
// The bias figure named `name` (kBiasFigureNames); throws InputError naming them otherwise.
BiasFigure parseBiasFigure(const std::string& name);

}  // namespace penumbra
