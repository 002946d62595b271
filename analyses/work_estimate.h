// How long a long run will take, said before it is too late to stop it: a
// command's work is counted in units (a workspace map's samples, a design's
// iterations), the time per unit measured on the first units, and from that
// the whole run estimated. When it will take more than a few seconds the
// estimate is said on stderr, then a progress line every 10 s; when it would
// take more than the bound the run is refused (WorkBoundError, naming how to
// raise the bound) a couple of seconds in, not hours later.
//
//   WorkEstimateOptions o;  // who "ccma workspace", noun "samples", raise_with "--max_minutes", say
//   WorkEstimate estimate(o, 1000000);
//   ... estimate.Update(done);  // after every unit (any thread); may throw WorkBoundError
//
// Used by `ccma workspace`, `ccma design` and their Python twins
// (docs/security.md, "Work bounded by its cost").
#ifndef CCMA_ANALYSES_WORK_ESTIMATE_H_
#define CCMA_ANALYSES_WORK_ESTIMATE_H_

#include <functional>
#include <mutex>
#include <stdexcept>
#include <string>

namespace ccma {

// The bound on a run's estimated time [minutes]: its default and its largest
// value (a week).
constexpr double kDefaultMaxMinutes = 10;
constexpr double kLargestMaxMinutes = 10080;

// A run whose estimate exceeds its bound. what(): the estimate, the bound and
// the value of the bound that would allow it.
class WorkBoundError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct WorkEstimateOptions {
  std::string who;   // starts every line: "ccma workspace", "ccma.design"
  std::string noun;  // what the units are: "samples", "design iterations"
  bool up_to = false;  // the total is a bound ("up to 2,000 design iterations"), not a count
  double max_minutes = kDefaultMaxMinutes;  // refuse a run estimated longer, in (0, kLargestMaxMinutes]
  std::string raise_with;  // how a user raises the bound: "--max_minutes" or "max_minutes"
  std::function<void(const std::string&)> say;  // one line (no newline); null: nothing said
  bool progress_lines = true;  // false: the estimate only (a terminal shows a bar of its own)
  std::function<double()> clock;  // seconds, monotonic; null: std::chrono::steady_clock
};

class WorkEstimate {
 public:
  // Time measured before an estimate is judged [s]: the first update after
  // it (at least one unit) decides.
  static constexpr double kCalibrationSeconds = 2;
  // A run estimated longer than this is announced [s].
  static constexpr double kAnnounceSeconds = 5;
  // Seconds between two progress lines of an announced run; as often the
  // estimate is judged again.
  static constexpr double kProgressSeconds = 10;
  // A run whose estimate, judged again, exceeds this many times the bound is
  // stopped then (units that grow dearer than the first ones).
  static constexpr double kRejudgeFactor = 2;

  // `total` units of work (>= 0). Throws std::invalid_argument when
  // max_minutes is not in (0, kLargestMaxMinutes].
  WorkEstimate(WorkEstimateOptions options, long long total);

  // Seconds of work known to follow the units (e.g. a workspace CSV's
  // columns, timed once before the run), in every estimate; `what` names
  // them in the announcement ("the CSV's computed columns"). Throws
  // WorkBoundError at once when they alone exceed the bound.
  void AddLaterSeconds(double seconds, const std::string& what);

  // `done` units of the current stage finished (thread-safe; `done` never
  // decreases within a stage). Once kCalibrationSeconds have passed in a
  // stage, its time per unit gives the estimate: elapsed + remaining units x
  // time per unit + later seconds. Throws WorkBoundError when that estimate
  // exceeds the bound (and at every later call: other threads stop too);
  // says it once when above kAnnounceSeconds, then a progress line every
  // kProgressSeconds.
  void Update(long long done);

  // A new stage whose units cost differently (design: the objective's
  // iterations; workspace: the CSV's rows): `total` units from 0, the time
  // per unit measured again, the later seconds replaced by `later_seconds`.
  // With `may_refuse` false the stage is never refused (its cost was in the
  // first estimate), only announced.
  void BeginStage(const std::string& noun, long long total, double later_seconds, bool may_refuse);

  // The last estimate of the whole run [s]; 0 before the first.
  double estimated_seconds() const;

 private:
  double Now() const;
  std::string Refusal(double estimate, double per_unit) const;
  void Judge(double estimate, double per_unit);
  void Announce(double now, double per_unit);

  WorkEstimateOptions options_;
  mutable std::mutex mutex_;
  double start_ = 0, stage_start_ = 0, last_line_ = 0;
  double later_seconds_ = 0, estimate_ = 0;
  long long total_ = 0;
  bool judged_ = false, announced_ = false, may_refuse_ = true, first_stage_ = true;
  std::string later_what_;
  std::string refused_;  // the refusal's message, once refused
};

// "4 min 38 s", "12 s", "0.27 ms", "2 h 5 min": a duration [s] for a message.
std::string FormatDuration(double seconds);
// "1,000,000": a count for a message.
std::string FormatCount(long long n);
// The wall time of a call of `f` [s]: the least of up to 10 calls, stopped
// once they have taken 50 ms (the first call is often cold).
double LeastSecondsOf(const std::function<void()>& f);

}  // namespace ccma

#endif  // CCMA_ANALYSES_WORK_ESTIMATE_H_
