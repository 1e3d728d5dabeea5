#pragma once
// httplib's Stream over one complete request in memory, collecting the response in memory. The
// connection layer (http/connection_server.h) did the socket I/O already, so httplib's request
// processing never waits on a client.
#include <httplib.h>

#include <string>
#include <string_view>

#include "http/connection_server.h"

namespace shadelab::http {

class MemoryStream final : public httplib::Stream {
 public:
  MemoryStream(const IncomingRequest& request, std::string& response) : request_(request), response_(response) {}

  bool is_readable() const override { return true; }
  bool is_writable() const override { return true; }
  ssize_t read(char* ptr, size_t size) override {
    const size_t n = std::min(size, request_.bytes.size() - read_);
    request_.bytes.copy(ptr, n, read_);
    read_ += n;
    return static_cast<ssize_t>(n);
  }
  ssize_t write(const char* ptr, size_t size) override {
    response_.append(ptr, size);
    return static_cast<ssize_t>(size);
  }
  void get_remote_ip_and_port(std::string& ip, int& port) const override {
    ip = request_.peer.ip;
    port = request_.peer.port;
  }
  void get_local_ip_and_port(std::string& ip, int& port) const override {
    ip = request_.local.ip;
    port = request_.local.port;
  }
  // No socket: httplib only compares it with FD_SETSIZE, which a real descriptor could pass.
  socket_t socket() const override { return INVALID_SOCKET; }

 private:
  const IncomingRequest& request_;
  std::string& response_;
  size_t read_ = 0;
};

}  // namespace shadelab::http
