// slamer-launch's I/O with supervisor: supervisord started as a child (its own
// session, so a terminal's Ctrl-C reaches only slamer-launch, which stops the
// processes in order; SIGTERM to it if slamer-launch dies), and XML-RPC calls
// over its unix control socket (HTTP/1.0, one connection per call).
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

#include "tools/launch/xmlrpc.hpp"

namespace slamer::launch {

class Supervisord {
 public:
  // Starts `supervisord -n -c CONF` with stdout to /dev/null (it logs to its logfile).
  explicit Supervisord(const std::string& config_path);
  ~Supervisord();  // SIGKILL if still running
  Supervisord(const Supervisord&) = delete;
  Supervisord& operator=(const Supervisord&) = delete;

  pid_t pid() const { return pid_; }
  bool running();               // false once it has exited (reaped)
  bool wait(double timeout_s);  // true if it exited within the timeout
  void kill_now();

 private:
  pid_t pid_ = -1;
  bool exited_ = false;
};

class SupervisorClient {
 public:
  explicit SupervisorClient(std::string socket_path) : socket_path_(std::move(socket_path)) {}

  // Throws XmlRpcError (a fault, a malformed reply) or std::runtime_error (the socket).
  XmlRpcValue call(const std::string& method, const std::vector<XmlRpcParam>& params = {},
                   double timeout_s = 5.0) const;
  bool reachable() const;
  std::vector<ProcessInfo> processes() const;
  // Without waiting (supervisor's wait=false); a fault is returned as text ("" = done).
  std::string start(const std::string& name) const;
  std::string stop(const std::string& name) const;

 private:
  std::string socket_path_;
};

}  // namespace slamer::launch
