// Byte transports under the URG session (issue 13 "Session and transports"):
// TCP (non-blocking connect, 2 s timeout), serial/USB (/dev/ttyACM*: raw
// termios, baud rates probed in urg_library's order) and an already open file
// descriptor (socketpair, pty) for tests. All non-blocking; the caller polls fd().
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <string_view>

namespace slamer::urg {

class Transport {
 public:
  virtual ~Transport() = default;
  // Opens (again); false with `error` set (one line).
  virtual bool open(std::string* error) = 0;
  virtual void close();
  int fd() const { return fd_; }
  bool is_open() const { return fd_ >= 0; }
  // Bytes read now (may be empty); false on EOF or error (the connection is gone).
  bool read(std::string* bytes, std::string* error);
  // Writes all of `bytes` (short waits on a full buffer); false on error.
  bool write(std::string_view bytes, std::string* error);
  virtual std::string describe() const = 0;
  // Serial only: the next baud rate to probe (false: not serial).
  virtual bool next_baud() { return false; }

 protected:
  int fd_ = -1;
};

class TcpTransport : public Transport {
 public:
  TcpTransport(std::string host, int port, double connect_timeout_s = 2.0)
      : host_(std::move(host)), port_(port), timeout_s_(connect_timeout_s) {}
  ~TcpTransport() override { close(); }
  bool open(std::string* error) override;
  std::string describe() const override { return host_ + ":" + std::to_string(port_); }

 private:
  std::string host_;
  int port_;
  double timeout_s_;
};

class SerialTransport : public Transport {
 public:
  explicit SerialTransport(std::string device) : device_(std::move(device)) {}
  ~SerialTransport() override { close(); }
  bool open(std::string* error) override;
  bool next_baud() override;
  std::string describe() const override;
  int baud() const;

 private:
  std::string device_;
  std::size_t baud_index_ = 2;  // 115200 first (USB models ignore the rate)
};

// Wraps a descriptor opened elsewhere (socketpair, pty master/slave); owns it.
class FdTransport : public Transport {
 public:
  explicit FdTransport(int fd, std::string name = "fd") : initial_fd_(fd), name_(std::move(name)) {}
  ~FdTransport() override { close(); }
  bool open(std::string* error) override;
  std::string describe() const override { return name_; }

 private:
  int initial_fd_;
  std::string name_;
};

}  // namespace slamer::urg
