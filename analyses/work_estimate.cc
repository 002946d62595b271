#include "analyses/work_estimate.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

namespace ccma {
namespace {

std::string Printf(const char* format, double a, double b = 0) {
  char text[64];
  std::snprintf(text, sizeof(text), format, a, b);
  return text;
}

}  // namespace

std::string FormatDuration(double seconds) {
  if (!(seconds >= 0)) seconds = 0;
  if (seconds < 1) return Printf("%.3g ms", seconds * 1e3);
  if (seconds < 10) return Printf("%.1f s", seconds);
  if (seconds < 60) return Printf("%.0f s", seconds);
  const double whole = std::round(seconds);
  if (whole < 3600) return Printf("%.0f min %.0f s", std::floor(whole / 60), std::fmod(whole, 60));
  const double minutes = std::round(seconds / 60);
  return Printf("%.0f h %.0f min", std::floor(minutes / 60), std::fmod(minutes, 60));
}

std::string FormatCount(long long n) {
  std::string digits = std::to_string(n < 0 ? -n : n), out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return (n < 0 ? "-" : "") + out;
}

double LeastSecondsOf(const std::function<void()>& f) {
  double least = std::numeric_limits<double>::infinity(), spent = 0;
  for (int run = 0; run < 10 && spent < 0.05; ++run) {
    const auto start = std::chrono::steady_clock::now();
    f();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    least = std::min(least, seconds);
    spent += seconds;
  }
  return least;
}

WorkEstimate::WorkEstimate(WorkEstimateOptions options, long long total) : options_(std::move(options)) {
  if (!(options_.max_minutes > 0 && options_.max_minutes <= kLargestMaxMinutes)) {
    throw std::invalid_argument(options_.raise_with + ": the bound on the estimated time must lie in (0, " +
                                Printf("%g", kLargestMaxMinutes) + "] minutes, got " +
                                Printf("%g", options_.max_minutes));
  }
  total_ = std::max(0LL, total);
  start_ = stage_start_ = last_line_ = Now();
}

double WorkEstimate::Now() const {
  if (options_.clock) return options_.clock();
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double WorkEstimate::estimated_seconds() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return estimate_;
}

std::string WorkEstimate::Refusal(double estimate, double per_unit) const {
  const double minutes = estimate / 60;
  std::string text = options_.who + ": about " + FormatDuration(estimate) + " for " +
                     (options_.up_to ? "up to " : "") + FormatCount(total_) + " " + options_.noun + " (" +
                     FormatDuration(per_unit) + " each), more than the " + Printf("%g", options_.max_minutes) +
                     " min that " + options_.raise_with + "=" + Printf("%g", options_.max_minutes) + " allows: ";
  const double suggestion = std::ceil(minutes * 1.2);
  if (suggestion > kLargestMaxMinutes) return text + "ask for less work (the bound is at most a week)";
  return text + "give " + options_.raise_with + "=" + Printf("%g", suggestion) +
         " or more to run it, or ask for less work";
}

void WorkEstimate::AddLaterSeconds(double seconds, const std::string& what) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!(seconds > 0)) return;
  later_seconds_ += seconds;
  later_what_ = what;
  estimate_ = Now() - start_ + later_seconds_;
  if (may_refuse_ && estimate_ > 60 * options_.max_minutes) {
    refused_ = Refusal(estimate_, later_seconds_ / static_cast<double>(std::max(1LL, total_)));
    throw WorkBoundError(refused_);
  }
}

void WorkEstimate::Judge(double estimate, double per_unit) {
  if (may_refuse_ && estimate > 60 * options_.max_minutes) {
    refused_ = Refusal(estimate, per_unit);
    throw WorkBoundError(refused_);
  }
}

void WorkEstimate::Announce(double now, double per_unit) {
  // The first stage says the whole run; a later one what is left.
  const double left = estimate_ - (now - start_);
  const double shown = first_stage_ ? estimate_ : left;
  if (!options_.say || !(shown > kAnnounceSeconds) || !(left > 1)) return;
  std::string line = options_.who + ": about " + FormatDuration(shown) + (first_stage_ ? "" : " more") + " for " +
                     (options_.up_to ? "up to " : "") + FormatCount(total_) + " " + options_.noun + " (" +
                     FormatDuration(per_unit) + " each";
  if (later_seconds_ > 0) line += ", then " + FormatDuration(later_seconds_) + " for " + later_what_;
  line += ")";
  if (options_.progress_lines) line += "; progress every " + Printf("%g", kProgressSeconds) + " s";
  options_.say(line);
  announced_ = true;
  last_line_ = now;
}

void WorkEstimate::Update(long long done) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!refused_.empty()) throw WorkBoundError(refused_);
  if (done <= 0) return;
  const double now = Now();
  const double stage_elapsed = now - stage_start_;
  if (!judged_ && stage_elapsed < kCalibrationSeconds && done < total_) return;
  const double per_unit = stage_elapsed / static_cast<double>(done);
  estimate_ = now - start_ + per_unit * static_cast<double>(std::max(0LL, total_ - done)) + later_seconds_;
  if (!judged_) {
    judged_ = true;
    Judge(estimate_, per_unit);
  }
  // Said as soon as the run looks long, also when its units grow dearer.
  if (!announced_) return Announce(now, per_unit);
  if (done >= total_ || now - last_line_ < kProgressSeconds) return;
  last_line_ = now;
  // Past kRejudgeFactor times the bound the run stops after all.
  if (may_refuse_ && estimate_ > kRejudgeFactor * 60 * options_.max_minutes) {
    refused_ = Refusal(estimate_, per_unit) + " (stopped after " + FormatDuration(now - start_) + ")";
    throw WorkBoundError(refused_);
  }
  if (!options_.progress_lines || !options_.say) return;
  const double percent = 100.0 * static_cast<double>(done) / static_cast<double>(std::max(1LL, total_));
  options_.say(options_.who + ": " + FormatCount(done) + " of " + (options_.up_to ? "up to " : "") +
               FormatCount(total_) + " " + options_.noun + Printf(" (%.0f %%) in ", percent) +
               FormatDuration(now - start_) + "; about " + FormatDuration(estimate_ - (now - start_)) + " left");
}

void WorkEstimate::BeginStage(const std::string& noun, long long total, double later_seconds, bool may_refuse) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!refused_.empty()) throw WorkBoundError(refused_);
  options_.noun = noun;
  total_ = std::max(0LL, total);
  stage_start_ = Now();
  later_seconds_ = std::max(0.0, later_seconds);
  later_what_ = "what follows";
  may_refuse_ = may_refuse;
  judged_ = announced_ = false;
  first_stage_ = false;
}

}  // namespace ccma
