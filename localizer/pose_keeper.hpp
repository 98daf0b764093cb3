// Keeps a live localizer's last good pose on disk (saved_pose.hpp format) so
// a restart resumes where the robot was: the newest pose with status OK is
// offered after every scan and written atomically (atomic_file.hpp) when
// save() is called (periodically and at a clean stop), only if it changed.
#pragma once

#include <optional>
#include <string>

#include "localizer/saved_pose.hpp"

namespace slamer {

class PoseKeeper {
 public:
  explicit PoseKeeper(std::string path) : path_(std::move(path)) {}

  bool enabled() const { return !path_.empty(); }
  const std::string& path() const { return path_; }
  // The saved pose to resume from; nullopt if there is none or it cannot be
  // read, with *note saying which (one line for the log).
  std::optional<SavedPose> load(std::string* note) const;
  void offer(const SavedPose& pose) { newest_ = pose; }
  // Writes the newest offered pose if it is not on disk yet. Throws
  // std::runtime_error (one line) if it cannot.
  void save();

 private:
  std::string path_;
  std::optional<SavedPose> newest_;
  std::optional<int64_t> written_utime_;
};

}  // namespace slamer
