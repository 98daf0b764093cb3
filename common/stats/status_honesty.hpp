// Whether a localizer's status tells the truth about its error (issue 9's
// bars), counted scan by scan against a reference: of the scans more than
// kFar off, those kGraceSeconds or more after the error passed kFar (the start
// of that stretch above it) must say UNCERTAIN or LOST; of the scans under
// kClose off, few may say LOST. One count for slamer-bench, the tests and the
// status report, so the three measure the same thing.
#pragma once

#include <cstdint>
#include <optional>

namespace slamer {

// pose_estimate_t status values.
enum class ReportedStatus : int8_t { kInitializing = 0, kOk = 1, kUncertain = 2, kLost = 3 };
// A message's status field as one of those; nullopt for a value outside them (a damaged or foreign log).
std::optional<ReportedStatus> reported_status(int8_t status);

class StatusHonesty {
 public:
  static constexpr double kFar = 0.5;    // [m]
  static constexpr double kClose = 0.2;  // [m]
  static constexpr double kGraceSeconds = 2.0;

  // One scan at `time` [s], in order, `error` [m] off the reference.
  void add(double time, double error, ReportedStatus status);
  // Adds another run's counts (for totals over runs).
  void merge(const StatusHonesty& other);

  int64_t far_after_grace() const { return far_after_grace_; }
  int64_t far_after_grace_flagged() const { return far_after_grace_flagged_; }  // UNCERTAIN or LOST
  int64_t far_after_grace_ok() const { return far_after_grace_ok_; }
  int64_t close() const { return close_; }
  int64_t close_lost() const { return close_lost_; }
  int64_t close_not_ok() const { return close_not_ok_; }  // UNCERTAIN, LOST or INITIALIZING: what honesty costs
  // 1 when there is nothing to flag; 0 when none are close.
  double far_flagged_fraction() const;
  double close_lost_fraction() const;
  double close_not_ok_fraction() const;

 private:
  std::optional<double> far_since_;
  int64_t far_after_grace_ = 0;
  int64_t far_after_grace_flagged_ = 0;
  int64_t far_after_grace_ok_ = 0;
  int64_t close_ = 0;
  int64_t close_lost_ = 0;
  int64_t close_not_ok_ = 0;
};

}  // namespace slamer
