#include "common/process/lcm_bus.hpp"

#include <poll.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string_view>

#include "common/process/log.hpp"

namespace slamer {

namespace {
// Per subscribed channel: 10 s of 100 Hz odometry, 25 s of 40 Hz scans (about 9 MB).
constexpr int kQueuedMessagesPerChannel = 1000;
}  // namespace

int64_t now_utime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

std::string literal_pattern(const std::string& channel) {
  std::string pattern;
  for (const char c : channel) {
    if (std::string_view("\\^$.|?*+()[]{}").find(c) != std::string_view::npos) {
      pattern += '\\';
    }
    pattern += c;
  }
  return pattern;
}

struct LcmBus::Context {
  LcmBus* bus;
  const std::string* channel;
};

LcmBus::LcmBus(std::string name, const std::string& lcm_url, ProcessOptions options)
    : Bus(std::move(name), std::move(options), static_cast<int32_t>(getpid()), now_utime()) {
  lcm_ = std::make_unique<lcm::LCM>(lcm_url);
  if (!lcm_->good()) {
    throw std::runtime_error("cannot open LCM" + (lcm_url.empty() ? std::string() : " URL '" + lcm_url + "'") +
                             " (for UDP multicast the host needs a multicast route, e.g. "
                             "'ip route add 224.0.0.0/4 dev lo' on a machine without a network)");
  }
}

LcmBus::~LcmBus() {
  lcm_.reset();  // first: its subscriptions point to channels_
}

void LcmBus::start_receiving(const std::string& channel) {
  channels_.push_back(std::make_unique<std::string>(channel));
  // LCM keeps the context pointer; the bus outlives its subscriptions.
  auto* context = new Context{this, channels_.back().get()};
  lcm::Subscription* subscription = lcm_->subscribeFunction(
      literal_pattern(channel),
      +[](const lcm::ReceiveBuffer* buffer, const std::string&, Context* self) {
        self->bus->deliver(*self->channel, static_cast<const uint8_t*>(buffer->data), buffer->data_size,
                           buffer->recv_utime);
      },
      context);
  // LCM's default holds 30 messages a channel and silently discards the rest:
  // 0.3 s of 100 Hz odometry, so one slow scan update (a global proposal, a
  // moment without CPU) lost input without a trace. Held here they are counted
  // and used; a process that falls behind catches up.
  subscription->setQueueCapacity(kQueuedMessagesPerChannel);
  contexts_.emplace_back(context);
}

bool LcmBus::send(const std::string& channel, const std::vector<uint8_t>& bytes, int64_t) {
  return lcm_->publish(channel, bytes.data(), static_cast<unsigned int>(bytes.size())) == 0;
}

void LcmBus::watch(int fd, std::function<void()> on_readable) {
  watched_[fd] = std::move(on_readable);
}

void LcmBus::unwatch(int fd) {
  watched_.erase(fd);
}

int LcmBus::run() {
  begin_run();
  constexpr int64_t kMaxWaitUs = 100'000;
  std::vector<pollfd> fds;
  std::vector<int> watched_fds;
  while (!stopping()) {
    const int64_t wait = std::clamp<int64_t>(next_timer_due() - now(), 0, kMaxWaitUs);
    // A program that subscribes to nothing never opens LCM's receive side: no
    // copies of every datagram on the group (its own included) to read and drop.
    fds.assign({{channels_.empty() ? -1 : lcm_->getFileno(), POLLIN, 0}, {stop_signals_.fd(), POLLIN, 0}});
    watched_fds.clear();
    for (const auto& [fd, callback] : watched_) {
      fds.push_back({fd, POLLIN, 0});
      watched_fds.push_back(fd);
    }
    const int ready = poll(fds.data(), fds.size(), static_cast<int>((wait + 999) / 1000));
    if (ready < 0 && errno != EINTR) {
      log_line(name(), LogLevel::kError, std::string("poll failed: ") + std::strerror(errno));
      return 1;
    }
    if (ready > 0 && (fds[1].revents & POLLIN) != 0) {
      if (stop_signals_.requested()) {
        log_info(std::string("received ") + (stop_signals_.last_signal() == SIGINT ? "SIGINT" : "SIGTERM") +
                 ", stopping");
      }
      stop();
      break;
    }
    if (ready > 0 && (fds[0].revents & POLLIN) != 0 && lcm_->handleTimeout(0) < 0) {
      log_line(name(), LogLevel::kError, "LCM receive failed");
      return 1;
    }
    for (std::size_t i = 0; ready > 0 && i < watched_fds.size(); ++i) {
      // Readable, hung up or in error: the callback reads and finds out which.
      const auto it = watched_.find(watched_fds[i]);
      if ((fds[i + 2].revents & (POLLIN | POLLHUP | POLLERR | POLLNVAL)) != 0 && it != watched_.end()) {
        const std::function<void()> callback = it->second;  // it may unwatch itself
        try {
          callback();
        } catch (const std::exception& e) {
          count_error(std::string("device: ") + e.what());
        }
      }
    }
    fire_due_timers(now());
  }
  end_run();
  return 0;
}

}  // namespace slamer
