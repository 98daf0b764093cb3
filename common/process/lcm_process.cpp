#include "common/process/lcm_process.hpp"

#include <poll.h>
#include <signal.h>
#include <sys/signalfd.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <iostream>
#include <stdexcept>

#include "common/process/log.hpp"

namespace slamer {

int64_t now_utime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

namespace {

std::chrono::steady_clock::duration to_duration(double seconds) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(seconds));
}

}  // namespace

LcmProcess::LcmProcess(std::string name, const std::string& lcm_url, ProcessOptions options)
    : name_(std::move(name)),
      options_(std::move(options)),
      health_(name_, static_cast<int32_t>(getpid()), now_utime()) {
  // Block the stop signals before LCM starts its threads so they inherit the
  // mask and every SIGINT/SIGTERM is read from the signalfd in run().
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  if (pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr) != 0) {
    throw std::runtime_error("cannot block SIGINT/SIGTERM");
  }
  signal_fd_ = signalfd(-1, &stop_signals, SFD_NONBLOCK | SFD_CLOEXEC);
  if (signal_fd_ < 0) {
    throw std::runtime_error(std::string("cannot create a signalfd: ") + std::strerror(errno));
  }
  lcm_ = std::make_unique<lcm::LCM>(lcm_url);
  if (!lcm_->good()) {
    close(signal_fd_);
    throw std::runtime_error("cannot open LCM" + (lcm_url.empty() ? std::string() : " URL '" + lcm_url + "'") +
                             " (for UDP multicast the host needs a multicast route, e.g. "
                             "'ip route add 224.0.0.0/4 dev lo' on a machine without a network)");
  }
  health_.add_channel(options_.status_channel, channel_stats_t::PUBLISHED);
  every(options_.status_period, [this] { publish_status(); });
  every(options_.error_log_period, [this] { flush_error_summary(); });
}

LcmProcess::~LcmProcess() {
  lcm_.reset();
  if (signal_fd_ >= 0) {
    close(signal_fd_);
  }
}

void LcmProcess::every(double period_s, std::function<void()> callback) {
  const auto period = to_duration(std::max(period_s, 1e-3));
  timers_.push_back(Timer{period, std::chrono::steady_clock::now() + period, std::move(callback)});
}

void LcmProcess::set_state(int8_t state, std::string message) {
  if (state != health_.state()) {
    const std::string text = "state " + std::to_string(state) + (message.empty() ? "" : ": " + message);
    if (state == process_status_t::OK) {
      log_info(text);
    } else {
      log_warning(text);
    }
  }
  health_.set_state(state, std::move(message));
}

void LcmProcess::count_drop(const std::string& channel, int64_t count) {
  health_.count_drop(channel, channel_stats_t::SUBSCRIBED, count);
}

void LcmProcess::log_info(const std::string& text) const {
  log_line(name_, LogLevel::kInfo, text);
}
void LcmProcess::log_warning(const std::string& text) const {
  log_line(name_, LogLevel::kWarning, text);
}

bool LcmProcess::publish_bytes(const std::string& channel, const std::vector<uint8_t>& bytes) {
  if (lcm_->publish(channel, bytes.data(), static_cast<unsigned int>(bytes.size())) != 0) {
    health_.count_drop(channel, channel_stats_t::PUBLISHED);
    if (publish_failures_++ == 0) {
      log_warning("cannot publish on " + channel + " (" + std::to_string(bytes.size()) +
                  " bytes); further failures are only counted");
    }
    return false;
  }
  health_.count_message(channel, channel_stats_t::PUBLISHED, now_utime());
  return true;
}

void LcmProcess::dispatch(const lcm::ReceiveBuffer* buffer, Subscription& subscription) {
  const ReceiveInfo info{subscription.channel, buffer->recv_utime};
  const auto start = std::chrono::steady_clock::now();
  DecodeStatus status = DecodeStatus::kOk;
  try {
    status = subscription.decode_and_handle(buffer->data, buffer->data_size, info);
  } catch (const std::exception& e) {
    health_.count_handler_error(subscription.channel + ": " + e.what());
    return;
  }
  if (status != DecodeStatus::kOk) {
    health_.count_decode_error(subscription.channel, status, info.receive_utime);
    return;
  }
  health_.count_message(subscription.channel, channel_stats_t::SUBSCRIBED, info.receive_utime);
  if (subscription.record_time) {
    health_.record_processing_time(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
}

void LcmProcess::publish_status() {
  publish(options_.status_channel, health_.status(now_utime()));
}

void LcmProcess::flush_error_summary() {
  const std::string summary = health_.take_error_summary();
  if (!summary.empty()) {
    log_warning(summary);
  }
}

int LcmProcess::run() {
  log_info("running (pid " + std::to_string(getpid()) + ")");
  publish_status();
  constexpr auto kMaxWait = std::chrono::milliseconds(100);
  while (!stopping_) {
    auto now = std::chrono::steady_clock::now();
    auto wait = std::chrono::steady_clock::duration(kMaxWait);
    for (const Timer& timer : timers_) {
      wait = std::min(wait, std::max(timer.next - now, std::chrono::steady_clock::duration::zero()));
    }
    pollfd fds[2] = {{lcm_->getFileno(), POLLIN, 0}, {signal_fd_, POLLIN, 0}};
    const int timeout_ms = static_cast<int>(std::ceil(std::chrono::duration<double, std::milli>(wait).count()));
    const int ready = poll(fds, 2, timeout_ms);
    if (ready < 0 && errno != EINTR) {
      log_line(name_, LogLevel::kError, std::string("poll failed: ") + std::strerror(errno));
      return 1;
    }
    if (ready > 0 && (fds[1].revents & POLLIN) != 0) {
      signalfd_siginfo signal_info{};
      if (read(signal_fd_, &signal_info, sizeof(signal_info)) == static_cast<ssize_t>(sizeof(signal_info))) {
        log_info(std::string("received ") + (signal_info.ssi_signo == SIGINT ? "SIGINT" : "SIGTERM") + ", stopping");
      }
      stopping_ = true;
      break;
    }
    if (ready > 0 && (fds[0].revents & POLLIN) != 0) {
      if (lcm_->handleTimeout(0) < 0) {
        log_line(name_, LogLevel::kError, "LCM receive failed");
        return 1;
      }
    }
    now = std::chrono::steady_clock::now();
    for (Timer& timer : timers_) {
      if (now >= timer.next) {
        timer.next += timer.period;
        if (timer.next <= now) {  // fell behind (e.g. a long handler): do not burst
          timer.next = now + timer.period;
        }
        timer.callback();
      }
    }
  }
  flush_error_summary();
  publish_status();
  return 0;
}

int process_main(int argc, const char* const argv[], const std::string& program, const std::string& summary,
                 const std::function<void(CommandLine&)>& declare, const std::function<int(const CommandLine&)>& body) {
  CommandLine command_line(program, summary);
  command_line.add_option("config", "FILE", "YAML configuration file");
  command_line.add_option("lcm-url", "URL", "LCM URL, e.g. udpm://239.255.76.67:7667?ttl=0 (default: LCM's default)");
  try {
    declare(command_line);
    if (!command_line.parse(argc, argv, std::cout)) {
      return 0;
    }
  } catch (const CommandLineError& e) {
    std::cerr << program << ": error: " << e.what() << "\n";
    return 2;
  }
  try {
    return body(command_line);
  } catch (const ConfigError& e) {
    std::cerr << program << ": config error: " << e.what() << "\n";
  } catch (const CommandLineError& e) {
    std::cerr << program << ": error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << program << ": error: " << e.what() << "\n";
  }
  return 1;
}

}  // namespace slamer
