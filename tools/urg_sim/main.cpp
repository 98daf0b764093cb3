// slamer-urg-sim: a SCIP 2.0 sensor emulator on loopback TCP or a pty (see
// sim_sensor.hpp), scanning a fixed scene, live scans from an LCM channel or
// the scans of an LCM log (scan_feed.hpp).
#include <cstdio>
#include <iostream>
#include <memory>
#include <stdexcept>

#include "common/process/command_line.hpp"
#include "tools/urg_sim/scan_feed.hpp"
#include "tools/urg_sim/sim_server.hpp"

int main(int argc, char** argv) {
  using namespace slamer;
  using namespace slamer::urg;
  CommandLine cl("slamer-urg-sim", "A Hokuyo SCIP 2.0 sensor emulator on 127.0.0.1 (TCP) or a pty");
  cl.add_option("model", "NAME", "URM-40LC, UST-10LX, UTM-30LX or URG-04LX (SCIP 1.1 at power-up)", "URM-40LC");
  cl.add_option("port", "N", "TCP port on 127.0.0.1 (0: a free one)", "0");
  cl.add_option("port-file", "PATH", "write the port here once listening");
  cl.add_flag("pty", "serve on a pty instead of TCP (its name is printed)");
  cl.add_option("pty-link", "PATH", "symlink to the pty");
  cl.add_option("delay-ms", "MS", "transport delay of every reply", "0");
  cl.add_option("jitter-ms", "MS", "plus a uniform random delay in [0, MS]", "0");
  cl.add_option("drift-ppm", "PPM", "device clock drift", "0");
  cl.add_option("offset-ms", "MS", "device clock at power-up", "12345");
  cl.add_flag("tm-5ms-ticks", "answer TM1 only on 5 ms device ticks");
  cl.add_option("segment-max", "BYTES", "split replies into random pieces of 1..BYTES", "0");
  cl.add_option("bad-checksum-rate", "P", "fraction of scans with a corrupted data line", "0");
  cl.add_option("truncate-rate", "P", "fraction of scans with a data line missing", "0");
  cl.add_option("garbage-rate", "P", "fraction of scans preceded by garbage bytes", "0");
  cl.add_option("error-status", "CODE", "status scans fail with (e.g. 50)", "50");
  cl.add_option("error-after", "N", "scans after which the laser fails (-1: never)", "-1");
  cl.add_flag("error-survives-reset", "RS does not clear the failure (RB does)");
  cl.add_option("model-after-reboot", "NAME", "come back from RB as this model (new geometry)");
  cl.add_option("drop-after", "S", "close the first connection after S seconds", "-1");
  cl.add_option("down", "S", "refuse connections for S seconds after the drop", "0");
  cl.add_option("silent-after", "S", "the first connection goes silent after S seconds", "-1");
  cl.add_option("truth", "PATH", "CSV of device stamp and true first-beam host time of each scan");
  cl.add_option("duration", "S", "exit after S seconds (0: run until a signal)", "0");
  cl.add_option("seed", "N", "random seed", "1");
  cl.add_option("source-channel", "CHANNEL",
                "send the laser_scan_t scans received live on CHANNEL (with --source-log: the log's channel, "
                "default LIDAR); their geometry must be the model's");
  cl.add_option("source-log", "FILE", "send the scans of this LCM log at their own pace, then exit");
  cl.add_option("lcm-url", "URL", "LCM URL for --source-channel", "");
  try {
    if (!cl.parse(argc, argv, std::cout)) {
      return 0;
    }
    SimModel model;
    if (!sim_model(cl.get("model"), &model)) {
      std::fprintf(stderr, "slamer-urg-sim: --model: unknown model '%s'\n", cl.get("model").c_str());
      return 2;
    }
    SimKnobs knobs;
    knobs.delay_ms = cl.get_double("delay-ms");
    knobs.jitter_ms = cl.get_double("jitter-ms");
    knobs.drift_ppm = cl.get_double("drift-ppm");
    knobs.offset_ms = cl.get_double("offset-ms");
    knobs.tm_on_5ms_ticks = cl.has("tm-5ms-ticks");
    knobs.bad_checksum_rate = cl.get_double("bad-checksum-rate");
    knobs.truncate_rate = cl.get_double("truncate-rate");
    knobs.garbage_rate = cl.get_double("garbage-rate");
    knobs.error_status = cl.get("error-status");
    knobs.error_after = static_cast<int>(cl.get_int("error-after"));
    knobs.error_survives_reset = cl.has("error-survives-reset");
    knobs.model_after_reboot = cl.get("model-after-reboot");
    knobs.seed = static_cast<unsigned>(cl.get_int("seed"));
    SimModel check;
    if (!knobs.model_after_reboot.empty() && !sim_model(knobs.model_after_reboot, &check)) {
      std::fprintf(stderr, "slamer-urg-sim: --model-after-reboot: unknown model '%s'\n",
                   knobs.model_after_reboot.c_str());
      return 2;
    }
    SimServerOptions options;
    options.port = static_cast<int>(cl.get_int("port"));
    options.port_file = cl.get("port-file");
    options.pty = cl.has("pty");
    options.pty_link = cl.get("pty-link");
    options.segment_max = static_cast<int>(cl.get_int("segment-max"));
    options.drop_after_s = cl.get_double("drop-after");
    options.down_s = cl.get_double("down");
    options.silent_after_s = cl.get_double("silent-after");
    options.truth_file = cl.get("truth");
    options.duration_s = cl.get_double("duration");
    options.seed = knobs.seed;
    // Before the feed's LCM: SIGINT/SIGTERM end the server's loop, which then removes the pty link.
    StopSignals stop;
    std::unique_ptr<ScanFeed> feed;
    if (cl.has("source-log")) {
      feed = std::make_unique<LogScanFeed>(cl.get("source-log"),
                                           cl.has("source-channel") ? cl.get("source-channel") : "LIDAR");
    } else if (cl.has("source-channel")) {
      feed = std::make_unique<LcmScanFeed>(cl.get("lcm-url"), cl.get("source-channel"));
    }
    knobs.external_scans = feed != nullptr;
    SimSensor sensor(model, knobs);
    return run_sim_server(sensor, options, stop, feed.get());
  } catch (const CommandLineError& e) {
    std::fprintf(stderr, "slamer-urg-sim: %s\n", e.what());
    return 2;
  } catch (const std::runtime_error& e) {
    std::fprintf(stderr, "slamer-urg-sim: %s\n", e.what());
    return 1;
  }
}
