// slamer-urg-timing: listens to LIDAR for a while, then compares each scan's
// utime with the emulator's truth file (matched by device stamp): p50/p99 of
// |utime - true first-beam time| and the scans the emulator sent that never
// came (lost). For the timing benchmark (tools/urg_sim/timing_benchmark.sh).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <sstream>

#include "common/process/command_line.hpp"
#include "common/process/decode.hpp"
#include "slamer/laser_scan_t.hpp"

namespace {
struct Listener {
  std::vector<std::pair<int64_t, int64_t>> scans;  // sensor_utime, utime
  void on_scan(const lcm::ReceiveBuffer* b, const std::string&) {
    slamer::laser_scan_t scan;
    if (slamer::decode_message(b->data, b->data_size, &scan) == slamer::DecodeStatus::kOk) {
      scans.emplace_back(scan.sensor_utime, scan.utime);
    }
  }
};
}  // namespace

int main(int argc, char** argv) {
  slamer::CommandLine cl("slamer-urg-timing", "LIDAR utime against the slamer-urg-sim truth file");
  cl.add_option("lcm-url", "URL", "LCM URL", "");
  cl.add_option("channel", "NAME", "scan channel", "LIDAR");
  cl.add_option("truth", "PATH", "the emulator's truth CSV");
  cl.add_option("duration", "S", "listen this long", "60");
  cl.add_option("skip", "S", "leave out the first S seconds of scans (start-up)", "0");
  cl.add_option("blocks", "S", "also print the signed error per block of S seconds");
  try {
    if (!cl.parse(argc, argv, std::cout)) {
      return 0;
    }
  } catch (const slamer::CommandLineError& e) {
    std::fprintf(stderr, "slamer-urg-timing: %s\n", e.what());
    return 2;
  }
  lcm::LCM lcm(cl.get("lcm-url"));
  if (!lcm.good()) {
    std::fprintf(stderr, "slamer-urg-timing: cannot open LCM\n");
    return 1;
  }
  Listener listener;
  lcm.subscribe(cl.get("channel"), &Listener::on_scan, &listener);
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(cl.get_double("duration"));
  while (std::chrono::steady_clock::now() < end) {
    lcm.handleTimeout(50);
  }
  std::ifstream truth(cl.get("truth"));
  std::string line;
  std::getline(truth, line);
  std::vector<std::pair<int64_t, int64_t>> rows;  // stamp (24 bit), first beam
  while (std::getline(truth, line)) {
    std::istringstream in(line);
    int64_t stamp = 0, beam = 0;
    char comma;
    if (in >> stamp >> comma >> beam) {
      rows.emplace_back(stamp, beam);
    }
  }
  if (rows.empty() || listener.scans.empty()) {
    std::fprintf(stderr, "slamer-urg-timing: %zu truth rows, %zu scans: nothing to compare\n", rows.size(),
                 listener.scans.size());
    return 1;
  }
  const int64_t skip_until = listener.scans.front().second + static_cast<int64_t>(cl.get_double("skip") * 1e6);
  std::map<int64_t, int64_t> published;  // stamp -> utime (stamps are unique within 4.6 h)
  for (const auto& [sensor_utime, utime] : listener.scans) {
    published[(sensor_utime / 1000) & 0xFFFFFF] = utime;
  }
  std::vector<double> errors;
  std::vector<std::pair<int64_t, double>> timeline;  // first beam, signed error
  int64_t lost = 0, considered = 0;
  const int64_t first_published = listener.scans.front().second - 1'000'000;
  const int64_t last_published = listener.scans.back().second;
  for (const auto& [stamp, beam] : rows) {
    if (beam < first_published || beam > last_published || beam < skip_until) {
      continue;  // before the driver connected / after it stopped listening
    }
    ++considered;
    const auto it = published.find(stamp);
    if (it == published.end()) {
      ++lost;
      continue;
    }
    errors.push_back(std::abs(static_cast<double>(it->second - beam)));
    timeline.emplace_back(beam, static_cast<double>(it->second - beam));
  }
  if (cl.has("blocks")) {
    // Signed error per block of `blocks` seconds: how it evolves.
    const int64_t block = static_cast<int64_t>(cl.get_double("blocks") * 1e6);
    for (std::size_t i = 0; i < timeline.size();) {
      std::vector<double> e;
      const int64_t start = timeline[i].first;
      for (; i < timeline.size() && timeline[i].first - start < block; ++i) {
        e.push_back(timeline[i].second);
      }
      std::sort(e.begin(), e.end());
      std::printf("  block of %zu: signed error min %.0f median %.0f max %.0f us\n", e.size(), e.front(),
                  e[e.size() / 2], e.back());
    }
  }
  std::sort(errors.begin(), errors.end());
  if (errors.empty()) {
    std::fprintf(stderr, "slamer-urg-timing: no scan matched the truth\n");
    return 1;
  }
  std::printf(
      "scans %zu matched of %lld sent while listening, lost %lld; |utime - truth| p50 %.0f us, p99 %.0f us, "
      "max %.0f us\n",
      errors.size(), static_cast<long long>(considered), static_cast<long long>(lost), errors[errors.size() / 2],
      errors[errors.size() * 99 / 100], errors.back());
  return 0;
}
