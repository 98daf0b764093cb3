#include "test/support/driver_processes.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

namespace slamer::test {

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / (name + "_" + std::to_string(getpid()))).string();
}

int free_port() {
  const int s = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  bind(s, reinterpret_cast<sockaddr*>(&addr), sizeof addr);
  socklen_t len = sizeof addr;
  getsockname(s, reinterpret_cast<sockaddr*>(&addr), &len);
  close(s);
  return ntohs(addr.sin_port);
}

std::unique_ptr<ChildProcess> start_urg_sim(std::vector<std::string> args, int* port) {
  const std::string port_file = temp_path("urg_port");
  std::filesystem::remove(port_file);
  args.insert(args.end(), {"--port-file", port_file});
  if (*port > 0) {
    args.insert(args.end(), {"--port", std::to_string(*port)});
  }
  auto sim = std::make_unique<ChildProcess>(binary_path("slamer-urg-sim"), args);
  for (int i = 0; i < 200 && !std::filesystem::exists(port_file); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  *port = std::stoi(read_file(port_file));
  std::filesystem::remove(port_file);
  return sim;
}

std::unique_ptr<ChildProcess> start_urg(const std::string& url, int port, const std::vector<std::string>& extra,
                                        const std::string& config) {
  std::vector<std::string> args = {"--config",  std::string(SLAMER_SOURCE_DIR "/") + config,
                                   "--host",    "127.0.0.1",
                                   "--port",    std::to_string(port),
                                   "--lcm-url", url};
  args.insert(args.end(), extra.begin(), extra.end());
  return std::make_unique<ChildProcess>(binary_path("slamer-urg"), args);
}

std::unique_ptr<ChildProcess> start_tfrog_sim(const std::string& link, const std::vector<std::string>& args) {
  std::vector<std::string> all = {"--link", link, "--robot", SLAMER_SOURCE_DIR "/config/robots/icart-mini.param"};
  all.insert(all.end(), args.begin(), args.end());
  auto sim = std::make_unique<ChildProcess>(binary_path("slamer-tfrog-sim"), all);
  for (int i = 0; i < 200 && access(link.c_str(), F_OK) != 0; ++i) {
    usleep(5000);
  }
  return sim;
}

std::unique_ptr<ChildProcess> start_wheels(const std::string& url, const std::string& link, const std::string& config) {
  return std::make_unique<ChildProcess>(
      binary_path("slamer-wheels"), std::vector<std::string>{"--config", std::string(SLAMER_SOURCE_DIR "/") + config,
                                                             "--device", link, "--lcm-url", url});
}

}  // namespace slamer::test
