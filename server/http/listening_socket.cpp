#include "http/listening_socket.h"

#include <netdb.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

namespace shadelab::http {

PeerAddress address_of(const sockaddr_storage& addr) {
  char host[NI_MAXHOST] = "";
  char port[NI_MAXSERV] = "";
  ::getnameinfo(reinterpret_cast<const sockaddr*>(&addr), sizeof addr, host, sizeof host, port, sizeof port, NI_NUMERICHOST | NI_NUMERICSERV);
  std::string ip = host;
  if (ip.rfind("::ffff:", 0) == 0 && ip.find('.') != std::string::npos) ip = ip.substr(7);
  return {ip, std::atoi(port)};
}

PeerAddress local_address(int fd) {
  sockaddr_storage addr{};
  socklen_t len = sizeof addr;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
  return address_of(addr);
}

Expected<int> listening_socket(const std::string& host, int port) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_PASSIVE | AI_NUMERICSERV;
  addrinfo* found = nullptr;
  const std::string where = host + ":" + std::to_string(port);
  if (const int rc = ::getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &found); rc != 0)
    return make_error(ErrorCode::io_error, "cannot listen on " + where + ": " + ::gai_strerror(rc));
  int error = 0, listener = -1;
  for (addrinfo* a = found; a && listener < 0; a = a->ai_next) {
    const int fd = ::socket(a->ai_family, a->ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC, a->ai_protocol);
    const int one = 1;
    // SO_REUSEADDR only: a restart may bind over connections in TIME_WAIT, but not beside a live listener.
    if (fd >= 0 && ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one) == 0 && ::bind(fd, a->ai_addr, a->ai_addrlen) == 0 &&
        ::listen(fd, 1024) == 0) {
      listener = fd;
      break;
    }
    error = errno;
    if (fd >= 0) ::close(fd);
  }
  ::freeaddrinfo(found);
  if (listener < 0) {
    const std::string why = error == EADDRINUSE ? "the port is already in use (is another server running on it?)" : std::strerror(error);
    return make_error(ErrorCode::io_error, "cannot listen on " + where + ": " + why);
  }
  return listener;
}

}  // namespace shadelab::http
