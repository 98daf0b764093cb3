// slamer-render: draws a log on its world's map, as PNG frames (and a video
// where OpenCV was built with a video encoder).
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#ifdef SLAMER_HAVE_VIDEOIO
#include <opencv2/videoio.hpp>
#endif

#include "common/process/event_log.hpp"
#include "common/process/log.hpp"
#include "common/process/process_main.hpp"
#include "common/robot/robot_options.hpp"
#include "tools/render/frame_collector.hpp"
#include "tools/render/renderer.hpp"
#include "tools/sim/world.hpp"

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
        slamer::FrameCollector collector(every);
        int64_t frames = 0;
        const bool terminal = isatty(STDERR_FILENO) != 0;
        const auto done = [&] { return max_frames > 0 && frames >= max_frames; };
        const auto render = [&](const std::vector<slamer::Frame>& ready) {
          for (auto frame = ready.begin(); frame != ready.end() && !done(); ++frame) {
            const cv::Mat image = renderer.draw(*frame);
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
          }
        };
        for (std::optional<slamer::LogEvent> e = log.next(); e && !done(); e = log.next()) {
          render(collector.add(e->channel, e->data));
        }
        render(collector.finish());
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
