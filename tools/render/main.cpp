// slamer-render: draws a log on its world's map, as PNG frames (and a video
// where OpenCV was built with a video encoder).
#include <unistd.h>

#include <cstdio>
#include <deque>
#include <filesystem>
#include <map>
#include <opencv2/imgcodecs.hpp>
#ifdef SLAMER_HAVE_VIDEOIO
#include <opencv2/videoio.hpp>
#endif

#include "common/process/convert.hpp"
#include "common/process/decode.hpp"
#include "common/process/event_log.hpp"
#include "common/process/log.hpp"
#include "common/process/process_main.hpp"
#include "common/robot/robot_options.hpp"
#include "slamer/line_objects_t.hpp"
#include "slamer/particles_t.hpp"
#include "slamer/semantic_objects_t.hpp"
#include "tools/render/renderer.hpp"
#include "tools/sim/world.hpp"

namespace slamer {
namespace {

Pose2 to_pose(const pose_estimate_t& m) {
  return {m.x, m.y, m.theta};
}

// Everything received for recent scans, keyed by the scan's utime.
struct Pending {
  std::map<int64_t, Pose2> truth;
  std::map<int64_t, Pose2> estimate;
  std::map<int64_t, std::vector<Pose2>> particles;
  std::map<int64_t, LineObjectSet> semantic;
  std::map<int64_t, LineObjectSet> recognized;
  std::deque<LaserScan> scans;

  template <class T>
  static std::optional<T> take(std::map<int64_t, T>& values, int64_t utime) {
    const auto it = values.find(utime);
    std::optional<T> value;
    if (it != values.end()) {
      value = it->second;
    }
    values.erase(values.begin(), values.upper_bound(utime));  // older ones are done with
    return value;
  }
};

}  // namespace
}  // namespace slamer

int main(int argc, char** argv) {
  return slamer::process_main(
      argc, argv, "slamer-render",
      "Draws a log on its world's map into PNG frames: map, scan, particles, true (green) and estimated\n"
      "(blue) pose, and recognized objects in the paper's colours (no-entry line red, glass door purple,\n"
      "open door green).",
      [](slamer::CommandLine& cli) {
        cli.add_option("world", "FILE", "the world file (for the map and the LiDAR mount)");
        cli.add_option("out", "DIR", "folder for frame_NNNNNN.png", "frames");
        cli.add_option("every", "N", "draw every N-th scan", "40");
        cli.add_option("max-frames", "N", "stop after N frames (0: no limit)", "0");
        cli.add_option("scale", "PX", "pixels per map cell", "2");
        cli.add_option("video", "FILE", "also write a video (needs OpenCV videoio)");
        cli.set_positional("LOG", "the LCM log to draw", 1, 1);
      },
      [](const slamer::CommandLine& cli) {
        if (!cli.has("world")) {
          throw slamer::CommandLineError("--world FILE is required");
        }
        const int64_t every = cli.get_int("every");
        const int64_t max_frames = cli.get_int("max-frames");
        const double scale = cli.get_double("scale");
        if (every < 1 || max_frames < 0 || !(scale > 0.0 && scale <= 20.0)) {
          throw slamer::CommandLineError("--every >= 1, --max-frames >= 0 and --scale in (0, 20] expected");
        }
        const auto world = slamer::load_options<slamer::WorldOptions>(cli.get("world"));
        const auto robot = slamer::load_options<slamer::RobotOptions>(world.robot_path);
        const slamer::SemanticMap map = slamer::load_semantic_map(world.map_path);
        slamer::RenderOptions options;
        options.pixels_per_cell = scale;
        options.lidar_mount = robot.lidar.mount;
        const slamer::FrameRenderer renderer(map, options);
        const std::string out = cli.get("out");
        std::filesystem::create_directories(out);
#ifdef SLAMER_HAVE_VIDEOIO
        cv::VideoWriter video;
#endif
        if (cli.has("video")) {
#ifndef SLAMER_HAVE_VIDEOIO
          slamer::log_line("slamer-render", slamer::LogLevel::kWarning,
                           "built without OpenCV videoio (apt-get install libopencv-videoio-dev and rebuild): "
                           "writing PNG frames only");
#endif
        }
        slamer::EventLogReader log(cli.positional()[0]);
        slamer::Pending pending;
        int64_t scan_count = 0;
        int64_t frames = 0;
        int64_t first_utime = -1;
        const bool terminal = isatty(STDERR_FILENO) != 0;
        const auto render = [&](const slamer::LaserScan& scan) {
          slamer::Frame frame;
          frame.utime = scan.utime;
          frame.elapsed = static_cast<double>(scan.utime - first_utime) * 1e-6;
          frame.scan = scan;
          frame.truth = slamer::Pending::take(pending.truth, scan.utime);
          frame.estimate = slamer::Pending::take(pending.estimate, scan.utime);
          frame.particles = slamer::Pending::take(pending.particles, scan.utime).value_or(std::vector<slamer::Pose2>{});
          frame.semantic = slamer::Pending::take(pending.semantic, scan.utime);
          frame.recognized = slamer::Pending::take(pending.recognized, scan.utime);
          const cv::Mat image = renderer.draw(frame);
          char name[64];
          std::snprintf(name, sizeof(name), "/frame_%06lld.png", static_cast<long long>(frames));
          if (!cv::imwrite(out + name, image)) {
            throw std::runtime_error("cannot write " + out + name);
          }
#ifdef SLAMER_HAVE_VIDEOIO
          if (cli.has("video")) {
            if (!video.isOpened() &&
                !video.open(cli.get("video"), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10.0, image.size())) {
              throw std::runtime_error("OpenCV cannot encode " + cli.get("video"));
            }
            video.write(image);
          }
#endif
          ++frames;
          if (terminal) {
            std::fprintf(stderr, "\rslamer-render: %lld frames", static_cast<long long>(frames));
          }
        };
        const auto done = [&] { return max_frames > 0 && frames >= max_frames; };
        for (std::optional<slamer::LogEvent> e = log.next(); e && !done(); e = log.next()) {
          const auto size = e->data.size();
          if (e->channel == "LIDAR") {
            slamer::laser_scan_t m{};
            if (slamer::decode_message(e->data.data(), size, &m) != slamer::DecodeStatus::kOk) {
              continue;
            }
            first_utime = first_utime < 0 ? m.utime : first_utime;
            // A scan is drawn when the next one arrives: by then its pose and objects are in.
            while (!pending.scans.empty() && !done()) {
              render(pending.scans.front());
              pending.scans.pop_front();
            }
            if (scan_count++ % every == 0) {
              pending.scans.push_back(slamer::from_message(m));
            }
          } else if (e->channel == "GROUND_TRUTH" || e->channel == "POSE") {
            slamer::pose_estimate_t m{};
            if (slamer::decode_message(e->data.data(), size, &m) == slamer::DecodeStatus::kOk) {
              (e->channel == "POSE" ? pending.estimate : pending.truth)[m.utime] = slamer::to_pose(m);
            }
          } else if (e->channel == "PARTICLES") {
            slamer::particles_t m{};
            if (slamer::decode_message(e->data.data(), size, &m) == slamer::DecodeStatus::kOk) {
              auto& list = pending.particles[m.utime];
              for (int32_t i = 0; i < m.n; ++i) {
                list.push_back({m.x[static_cast<std::size_t>(i)], m.y[static_cast<std::size_t>(i)],
                                m.theta[static_cast<std::size_t>(i)]});
              }
            }
          } else if (e->channel == "SEMANTIC_OBJECTS") {
            slamer::semantic_objects_t m{};
            if (slamer::decode_message(e->data.data(), size, &m) == slamer::DecodeStatus::kOk) {
              pending.semantic[m.utime] = slamer::from_message(m);
            }
          } else if (e->channel == "LINE_OBJECTS") {
            slamer::line_objects_t m{};
            if (slamer::decode_message(e->data.data(), size, &m) == slamer::DecodeStatus::kOk) {
              pending.recognized[m.utime] = slamer::from_message(m);
            }
          }
        }
        while (!pending.scans.empty() && !done()) {
          render(pending.scans.front());
          pending.scans.pop_front();
        }
        if (terminal) {
          std::fprintf(stderr, "\n");
        }
        if (!log.problems().empty()) {
          slamer::log_line("slamer-render", slamer::LogLevel::kWarning, log.problems());
        }
        slamer::log_line("slamer-render", slamer::LogLevel::kInfo,
                         "wrote " + std::to_string(frames) + " frames to " + out);
        return 0;
      });
}
