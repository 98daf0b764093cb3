#include "tools/launch/supervisor_client.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <stdexcept>
#include <thread>

namespace slamer::launch {
namespace {

class Fd {
 public:
  explicit Fd(int fd) : fd_(fd) {}
  ~Fd() {
    if (fd_ >= 0) {
      close(fd_);
    }
  }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

}  // namespace

Supervisord::Supervisord(const std::string& config_path) {
  const pid_t parent = getpid();
  pid_ = fork();
  if (pid_ < 0) {
    throw std::runtime_error(std::string("cannot fork supervisord: ") + std::strerror(errno));
  }
  if (pid_ == 0) {
    setsid();
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) {
      _exit(1);
    }
    sigset_t none;
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, nullptr);
    signal(SIGPIPE, SIG_DFL);
    const int null = open("/dev/null", O_RDWR);
    if (null >= 0) {
      dup2(null, STDIN_FILENO);
      dup2(null, STDOUT_FILENO);
    }
    execlp("supervisord", "supervisord", "-n", "-c", config_path.c_str(), static_cast<char*>(nullptr));
    const char message[] = "slamer-launch: error: cannot run supervisord (apt-get install supervisor)\n";
    [[maybe_unused]] const ssize_t ignored = write(STDERR_FILENO, message, sizeof message - 1);
    _exit(127);
  }
}

Supervisord::~Supervisord() {
  if (running()) {
    kill_now();
  }
}

bool Supervisord::running() {
  if (exited_) {
    return false;
  }
  int status = 0;
  const pid_t done = waitpid(pid_, &status, WNOHANG);
  exited_ = done == pid_ || (done < 0 && errno == ECHILD);
  return !exited_;
}

bool Supervisord::wait(double timeout_s) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (running()) {
    if (std::chrono::steady_clock::now() > end) {
      return false;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return true;
}

void Supervisord::kill_now() {
  ::kill(pid_, SIGKILL);
  wait(5.0);
}

XmlRpcValue SupervisorClient::call(const std::string& method, const std::vector<XmlRpcParam>& params,
                                   double timeout_s) const {
  const Fd fd(socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0));
  if (fd.get() < 0) {
    throw std::runtime_error(std::string("socket: ") + std::strerror(errno));
  }
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  if (socket_path_.size() >= sizeof address.sun_path) {
    throw std::runtime_error("supervisor socket path too long: " + socket_path_);
  }
  std::memcpy(address.sun_path, socket_path_.c_str(), socket_path_.size() + 1);
  if (connect(fd.get(), reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    throw std::runtime_error("cannot connect to supervisord at " + socket_path_ + ": " + std::strerror(errno));
  }
  const std::string body = xmlrpc_request(method, params);
  const std::string request =
      "POST /RPC2 HTTP/1.0\r\nContent-Type: text/xml\r\nContent-Length: " + std::to_string(body.size()) + "\r\n\r\n" +
      body;
  std::size_t sent = 0;
  while (sent < request.size()) {
    const ssize_t n = send(fd.get(), request.data() + sent, request.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) {
      throw std::runtime_error(std::string("sending to supervisord: ") + std::strerror(errno));
    }
    sent += static_cast<std::size_t>(n);
  }
  std::string reply;
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  char buffer[8192];
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - std::chrono::steady_clock::now());
    pollfd p{fd.get(), POLLIN, 0};
    if (left.count() <= 0 || poll(&p, 1, static_cast<int>(left.count())) <= 0) {
      throw std::runtime_error("supervisord did not answer " + method + " within " + std::to_string(timeout_s) + " s");
    }
    const ssize_t n = recv(fd.get(), buffer, sizeof buffer, 0);
    if (n < 0) {
      throw std::runtime_error(std::string("reading from supervisord: ") + std::strerror(errno));
    }
    if (n == 0) {
      break;
    }
    reply.append(buffer, static_cast<std::size_t>(n));
    if (reply.size() > (16u << 20)) {
      throw XmlRpcError("supervisord's reply is larger than 16 MB");
    }
  }
  return parse_xmlrpc_response(http_body(reply));
}

bool SupervisorClient::reachable() const {
  try {
    call("supervisor.getState", {}, 1.0);
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

std::vector<ProcessInfo> SupervisorClient::processes() const {
  return parse_process_infos(call("supervisor.getAllProcessInfo"));
}

std::string SupervisorClient::start(const std::string& name) const {
  try {
    call("supervisor.startProcess", {{XmlRpcParam::Kind::kString, name}, {XmlRpcParam::Kind::kBool, "", false}});
  } catch (const XmlRpcError& e) {
    return e.what();
  }
  return "";
}

std::string SupervisorClient::stop(const std::string& name) const {
  try {
    call("supervisor.stopProcess", {{XmlRpcParam::Kind::kString, name}, {XmlRpcParam::Kind::kBool, "", false}});
  } catch (const XmlRpcError& e) {
    return e.what();
  }
  return "";
}

}  // namespace slamer::launch
