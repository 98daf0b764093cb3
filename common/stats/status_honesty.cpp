#include "common/stats/status_honesty.hpp"

namespace slamer {

std::optional<ReportedStatus> reported_status(int8_t status) {
  if (status < static_cast<int8_t>(ReportedStatus::kInitializing) ||
      status > static_cast<int8_t>(ReportedStatus::kLost)) {
    return std::nullopt;
  }
  return static_cast<ReportedStatus>(status);
}

void StatusHonesty::add(double time, double error, ReportedStatus status) {
  far_since_ = error > kFar ? far_since_.value_or(time) : std::optional<double>();
  if (far_since_ && time - *far_since_ >= kGraceSeconds) {
    ++far_after_grace_;
    far_after_grace_flagged_ += status == ReportedStatus::kUncertain || status == ReportedStatus::kLost;
    far_after_grace_ok_ += status == ReportedStatus::kOk;
  }
  if (error < kClose) {
    ++close_;
    close_lost_ += status == ReportedStatus::kLost;
    close_not_ok_ += status != ReportedStatus::kOk;
  }
}

void StatusHonesty::merge(const StatusHonesty& other) {
  far_after_grace_ += other.far_after_grace_;
  far_after_grace_flagged_ += other.far_after_grace_flagged_;
  far_after_grace_ok_ += other.far_after_grace_ok_;
  close_ += other.close_;
  close_lost_ += other.close_lost_;
  close_not_ok_ += other.close_not_ok_;
}

double StatusHonesty::far_flagged_fraction() const {
  return far_after_grace_ == 0 ? 1.0
                               : static_cast<double>(far_after_grace_flagged_) / static_cast<double>(far_after_grace_);
}

double StatusHonesty::close_lost_fraction() const {
  return close_ == 0 ? 0.0 : static_cast<double>(close_lost_) / static_cast<double>(close_);
}

double StatusHonesty::close_not_ok_fraction() const {
  return close_ == 0 ? 0.0 : static_cast<double>(close_not_ok_) / static_cast<double>(close_);
}

}  // namespace slamer
