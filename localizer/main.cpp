// slamer-localizer: LIDAR + ODOMETRY + LINE_OBJECTS in; POSE, SEMANTIC_OBJECTS
// and PARTICLES out. Live on LCM, or offline from a log (--replay IN --out OUT).
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "common/map/semantic_map.hpp"
#include "common/process/atomic_file.hpp"
#include "common/process/convert.hpp"
#include "common/process/lcm_process.hpp"
#include "common/process/log.hpp"
#include "common/process/log_replay.hpp"
#include "common/robot/robot_options.hpp"
#include "localizer/localizer_config.hpp"
#include "localizer/localizer_node.hpp"
#include "localizer/saved_pose.hpp"
#include "slamer/initial_pose_t.hpp"
#include "slamer/odometry_t.hpp"
#include "slamer/particles_t.hpp"

namespace slamer {
namespace {

int8_t to_status(LocalizerStatus status) {
  switch (status) {
    case LocalizerStatus::kInitializing:
      return pose_estimate_t::INITIALIZING;
    case LocalizerStatus::kOk:
      return pose_estimate_t::OK;
    case LocalizerStatus::kUncertain:
      return pose_estimate_t::UNCERTAIN;
    case LocalizerStatus::kLost:
      return pose_estimate_t::LOST;
  }
  return pose_estimate_t::LOST;
}

pose_estimate_t to_pose_message(const UpdateResult& result, int64_t utime, int particles) {
  pose_estimate_t message;
  message.utime = utime;
  message.x = result.estimate.pose.x;
  message.y = result.estimate.pose.y;
  message.theta = result.estimate.pose.theta;
  std::copy(std::begin(result.estimate.covariance), std::end(result.estimate.covariance), std::begin(message.cov));
  message.nparticles = particles;
  message.ess = result.estimate.ess;
  message.status = to_status(result.estimate.status);
  return message;
}

particles_t to_particles_message(const std::vector<Particle>& particles, int64_t utime, int count) {
  particles_t message;
  message.utime = utime;
  const std::size_t n = std::min(particles.size(), static_cast<std::size_t>(count));
  for (std::size_t i = 0; i < n; ++i) {
    const Particle& p = particles[i * particles.size() / n];  // evenly picked
    message.x.push_back(p.pose.x);
    message.y.push_back(p.pose.y);
    message.theta.push_back(p.pose.theta);
    message.weight.push_back(std::exp(p.log_weight));
  }
  message.n = static_cast<int32_t>(n);
  return message;
}

// The outputs of one processed scan, as encoded events.
std::vector<OutputEvent> outputs_of(const UpdateResult& result, const std::vector<Particle>& particles,
                                    const LocalizerProcessConfig& config, int64_t* last_particles_utime) {
  const int64_t utime = result.semantic.utime;
  std::vector<OutputEvent> events;
  events.push_back(encode_event(config.channels.pose, to_pose_message(result, utime, config.localizer.particles)));
  events.push_back(encode_event(config.channels.semantic_objects, to_semantic_objects_message(result.semantic)));
  if (config.particles_out > 0 &&
      utime - *last_particles_utime >= static_cast<int64_t>(config.particles_period * 1e6)) {
    events.push_back(
        encode_event(config.channels.particles, to_particles_message(particles, utime, config.particles_out)));
    *last_particles_utime = utime;
  }
  return events;
}

// An INITIAL_POSE in a log line: the pose and the position sigmas it asks for.
std::string describe(const initial_pose_t& m) {
  char text[160];
  std::snprintf(text, sizeof text, "(%.3f, %.3f, %.3f), sigma (%.3g, %.3g, %.3g)", m.x, m.y, m.theta,
                std::sqrt(m.cov[0]), std::sqrt(m.cov[4]), std::sqrt(m.cov[8]));
  return text;
}

// The node with the map's fields built; the map itself is freed on return.
LocalizerNode make_node(const LocalizerProcessConfig& config) {
  if (config.map.empty()) {
    throw ConfigError("no map: set 'map' in the config or pass --map");
  }
  const SemanticMap map = load_semantic_map(config.map);
  for (const std::string& warning : map.warnings) {
    log_line("slamer-localizer", LogLevel::kWarning, warning);
  }
  const RobotOptions robot = config.robot.empty() ? RobotOptions{} : load_options<RobotOptions>(config.robot);
  LocalizerNode node(map, config.localizer, robot.lidar.mount);
  char line[200];
  std::snprintf(line, sizeof line, "map %d x %d cells at %.3f m: distance fields %.1f MB", map.geometry.width,
                map.geometry.height, map.geometry.resolution, static_cast<double>(node.map_memory_bytes()) / 1e6);
  log_line("slamer-localizer", LogLevel::kInfo, line);
  return node;
}

// Peak resident size of this process [MB], for the log.
double peak_resident_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

int run_replay(const LocalizerProcessConfig& config, const std::string& in, const std::string& out) {
  LocalizerNode node = make_node(config);
  int64_t last_particles = std::numeric_limits<int64_t>::min() / 2;
  int64_t scans = 0;
  const LocalizerChannels& ch = config.channels;
  // The log's timestamps (receive times) are the clock: a scan waits for its
  // objects as it did live, so a recorded run replays the way it ran.
  const auto publish_ready = [&](std::vector<OutputEvent>* outputs, int64_t now) {
    while (const std::optional<UpdateResult> result = node.poll(now)) {
      const auto events = outputs_of(*result, node.particles(), config, &last_particles);
      outputs->insert(outputs->end(), events.begin(), events.end());
      ++scans;
    }
  };
  const ReplayStats stats = replay_log(
      "slamer-localizer", in, out, {ch.lidar, ch.odometry, ch.line_objects, ch.initial_pose},
      {ch.pose, ch.semantic_objects, ch.particles},
      [&](const std::string& channel, const std::vector<uint8_t>& bytes, int64_t timestamp,
          std::vector<OutputEvent>* outputs) {
        if (channel == ch.odometry) {
          odometry_t m{};
          if (decode_message(bytes.data(), bytes.size(), &m) == DecodeStatus::kOk) {
            node.on_odometry(m.utime, {m.x, m.y, m.theta});
          }
        } else if (channel == ch.lidar) {
          laser_scan_t m{};
          if (decode_message(bytes.data(), bytes.size(), &m) == DecodeStatus::kOk) {
            node.on_scan(from_message(m));
          }
        } else if (channel == ch.line_objects) {
          line_objects_t m{};
          if (decode_message(bytes.data(), bytes.size(), &m) == DecodeStatus::kOk) {
            node.on_objects(from_message(m));
          }
        } else if (channel == ch.initial_pose) {
          initial_pose_t m{};
          if (decode_message(bytes.data(), bytes.size(), &m) == DecodeStatus::kOk &&
              !node.on_initial_pose({m.x, m.y, m.theta}, sigma_of_covariance(m.cov))) {
            log_line("slamer-localizer", LogLevel::kWarning, "INITIAL_POSE ignored: " + describe(m));
          }
        }
        publish_ready(outputs, timestamp);
      },
      [&](std::vector<OutputEvent>* outputs) { publish_ready(outputs, std::numeric_limits<int64_t>::max()); });
  const NodeCounters& c = node.counters();
  log_line("slamer-localizer", LogLevel::kInfo,
           "replayed " + std::to_string(scans) + " scans of " + in + " into " + out + " (" +
               std::to_string(c.scans_without_objects) + " without objects, " +
               std::to_string(c.scans_without_odometry) + " without odometry, " + std::to_string(c.stale_scans) +
               " stale, " + std::to_string(c.resets) + " resets, " + std::to_string(stats.handler_errors) +
               " errors); peak resident " + std::to_string(static_cast<int>(peak_resident_mb())) + " MB");
  return 0;
}

// What PROCESS_STATUS says: the filter's state and the inputs it goes without.
std::pair<int8_t, std::string> process_state(LocalizerStatus status, const InputHealth& health,
                                             const LocalizerChannels& channels) {
  std::string message;
  const auto add = [&](const std::string& part) { message += (message.empty() ? "" : "; ") + part; };
  const auto missing = [&](const std::string& channel, double age, const std::string& consequence) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f s", age);
    add("no " + channel + (std::isfinite(age) ? " for " + std::string(text) : " yet") + ": " + consequence);
  };
  if (status == LocalizerStatus::kLost) {
    add("lost: the scans do not fit the map");
  } else if (status == LocalizerStatus::kUncertain) {
    add("uncertain");
  }
  if (health.odometry_missing) {
    missing(channels.odometry, health.odometry_age, "following the scans alone");
  }
  if (health.objects_missing) {
    missing(channels.line_objects, health.objects_age, "geometry only");
  }
  if (status == LocalizerStatus::kLost) {
    return {process_status_t::ERROR, message};
  }
  return {message.empty() ? process_status_t::OK : process_status_t::DEGRADED, message};
}

// Where the live localizer starts: the saved pose if there is a good one, else the config's.
void resume_from_saved_pose(const LocalizerProcessConfig& config, LocalizerNode* node) {
  if (config.pose_file.empty()) {
    return;
  }
  if (!std::filesystem::exists(config.pose_file)) {
    log_line("slamer-localizer", LogLevel::kInfo,
             "no saved pose in " + config.pose_file + " yet: starting from the configured initial pose");
    return;
  }
  try {
    const auto saved = load_options<SavedPose>(config.pose_file);
    node->on_initial_pose(saved.pose, saved.sigma);
    char pose[96];
    std::snprintf(pose, sizeof pose, "(%.3f, %.3f, %.3f)", saved.pose.x, saved.pose.y, saved.pose.theta);
    log_line("slamer-localizer", LogLevel::kInfo, "resuming from the pose saved in " + config.pose_file + ": " + pose);
  } catch (const ConfigError& e) {
    log_line("slamer-localizer", LogLevel::kWarning,
             std::string("cannot resume: ") + e.what() + "; starting from the configured initial pose");
  }
}

int run_live(const LocalizerProcessConfig& config, const std::string& lcm_url) {
  LocalizerNode node = make_node(config);
  resume_from_saved_pose(config, &node);
  LcmProcess process("slamer-localizer", lcm_url, config.process);
  int64_t last_particles = std::numeric_limits<int64_t>::min() / 2;
  const LocalizerChannels& ch = config.channels;
  NodeCounters reported;
  std::optional<SavedPose> good_pose;  // the newest pose with status OK
  std::optional<int64_t> written_utime;
  int64_t last_scan_wall = now_utime();
  const auto save_pose = [&] {
    if (config.pose_file.empty() || !good_pose || written_utime == good_pose->utime) {
      return;
    }
    try {
      write_file_atomically(config.pose_file, format_saved_pose(*good_pose));
      written_utime = good_pose->utime;
    } catch (const std::runtime_error& e) {
      process.health().count_handler_error(e.what());  // summarized in the log, rate-limited
    }
  };
  const auto publish_ready = [&](int64_t now) {
    // Only scans actually processed count toward the processing time p50/p99.
    for (auto start = std::chrono::steady_clock::now();; start = std::chrono::steady_clock::now()) {
      const std::optional<UpdateResult> result = node.poll(now);
      if (!result) {
        break;
      }
      process.record_processing_time(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      for (const OutputEvent& event : outputs_of(*result, node.particles(), config, &last_particles)) {
        process.publish_raw(event.channel, event.bytes);
      }
      const auto [state, message] = process_state(result->estimate.status, node.health(), ch);
      process.set_state(state, message);
      if (result->estimate.status == LocalizerStatus::kOk) {
        good_pose =
            SavedPose{result->semantic.utime, result->estimate.pose, sigma_of_covariance(result->estimate.covariance)};
      }
    }
    const NodeCounters& c = node.counters();
    process.count_drop(ch.lidar, c.stale_scans - reported.stale_scans);
    process.count_drop(ch.odometry,
                       c.stale_odometry - reported.stale_odometry + c.invalid_odometry - reported.invalid_odometry);
    process.count_drop(ch.line_objects, c.stale_objects - reported.stale_objects);
    reported = c;
  };
  process.subscribe<odometry_t>(ch.odometry, [&](const odometry_t& m, const ReceiveInfo&) {
    node.on_odometry(m.utime, {m.x, m.y, m.theta});
  });
  process.subscribe<laser_scan_t>(ch.lidar, [&](const laser_scan_t& m, const ReceiveInfo& info) {
    last_scan_wall = info.receive_utime;
    node.on_scan(from_message(m));
    publish_ready(info.receive_utime);
  });
  process.subscribe<line_objects_t>(ch.line_objects, [&](const line_objects_t& m, const ReceiveInfo& info) {
    node.on_objects(from_message(m));
    publish_ready(info.receive_utime);
  });
  process.subscribe<initial_pose_t>(ch.initial_pose, [&](const initial_pose_t& m, const ReceiveInfo&) {
    if (!node.on_initial_pose({m.x, m.y, m.theta}, sigma_of_covariance(m.cov))) {
      process.count_drop(ch.initial_pose);
      process.log_warning("INITIAL_POSE ignored: " + describe(m));
      return;
    }
    process.log_info("initial pose set: " + describe(m));
  });
  // A scan whose objects do not come is processed without them after objects_wait.
  process.every(0.01, [&] { publish_ready(now_utime()); });
  process.every(config.pose_save_period, save_pose);
  process.every(1.0, [&] {
    if (now_utime() - last_scan_wall > 2'000'000) {
      process.set_state(process_status_t::DEGRADED, "no scans on " + ch.lidar + " for 2 s: no pose");
    }
  });
  const int code = process.run();
  save_pose();  // a clean stop keeps the very last good pose
  return code;
}

}  // namespace
}  // namespace slamer

int main(int argc, char** argv) {
  return slamer::process_main(
      argc, argv, "slamer-localizer",
      "SLAMER: localization and map-assisted environment recognition with a particle filter. Publishes\n"
      "POSE, SEMANTIC_OBJECTS and PARTICLES. --mode lfm|slfm|slamer picks the measurement model;\n"
      "--replay IN --out OUT runs offline on a log, as fast as it can, the same for the same seed.",
      [](slamer::CommandLine& cli) {
        cli.add_option("mode", "MODE", "lfm, slfm or slamer (overrides the config)");
        cli.add_option("seed", "N", "random seed (overrides the config)");
        cli.add_option("map", "FILE", "semantic map YAML (overrides the config)");
        cli.add_option("robot", "FILE", "robot YAML, for the LiDAR mount (overrides the config)");
        cli.add_multi_option("initial-pose", 3, "X Y THETA", "start here [m, m, rad] (overrides the config)");
        cli.add_option("replay", "IN.lcm", "offline: read this log");
        cli.add_option("out", "OUT.lcm", "offline: write the log with the results added here");
      },
      [](const slamer::CommandLine& cli) {
        auto config = slamer::load_config<slamer::LocalizerProcessConfig>(cli);
        if (cli.has("mode")) {
          try {
            config.localizer.mode = slamer::parse_mode(cli.get("mode"));
          } catch (const std::invalid_argument& e) {
            throw slamer::CommandLineError(std::string("option '--mode': ") + e.what());
          }
        }
        if (cli.has("seed")) {
          const int64_t seed = cli.get_int("seed");
          if (seed < 0) {
            throw slamer::CommandLineError("option '--seed': expected a number >= 0");
          }
          config.localizer.seed = static_cast<uint64_t>(seed);
        }
        if (cli.has("map")) {
          config.map = cli.get("map");
        }
        if (cli.has("robot")) {
          config.robot = cli.get("robot");
        }
        if (cli.has("initial-pose")) {
          const std::vector<double> pose = cli.get_doubles("initial-pose");
          config.localizer.initial_pose = {pose[0], pose[1], pose[2]};
        }
        if (cli.has("replay") != cli.has("out")) {
          throw slamer::CommandLineError("--replay and --out go together");
        }
        return cli.has("replay") ? slamer::run_replay(config, cli.get("replay"), cli.get("out"))
                                 : slamer::run_live(config, cli.get("lcm-url"));
      });
}
