#include "localizer/pose_keeper.hpp"

#include <cstdio>
#include <filesystem>

#include "common/process/atomic_file.hpp"

namespace slamer {

std::optional<SavedPose> PoseKeeper::load(std::string* note) const {
  if (!enabled()) {
    *note = "";
    return std::nullopt;
  }
  if (!std::filesystem::exists(path_)) {
    *note = "no saved pose in " + path_ + " yet: starting from the configured initial pose";
    return std::nullopt;
  }
  try {
    const auto saved = load_options<SavedPose>(path_);
    char pose[96];
    std::snprintf(pose, sizeof pose, "(%.3f, %.3f, %.3f)", saved.pose.x, saved.pose.y, saved.pose.theta);
    *note = "resuming from the pose saved in " + path_ + ": " + pose;
    return saved;
  } catch (const ConfigError& e) {
    *note = std::string("cannot resume: ") + e.what() + "; starting from the configured initial pose";
    return std::nullopt;
  }
}

void PoseKeeper::save() {
  if (!enabled() || !newest_ || written_utime_ == newest_->utime) {
    return;
  }
  write_file_atomically(path_, format_saved_pose(*newest_));
  written_utime_ = newest_->utime;
}

}  // namespace slamer
