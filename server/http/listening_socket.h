#pragma once
// The listening socket and numeric addresses, for the connection layer.
#include <sys/socket.h>

#include <string>

#include "core/expected.h"
#include "http/connection_server.h"

namespace shadelab::http {

// A non-blocking listening socket on host:port (0: a free port). SO_REUSEADDR only, never
// SO_REUSEPORT: a port another server listens on is an error here ("already in use"), not a
// silent share of its connections.
Expected<int> listening_socket(const std::string& host, int port);

PeerAddress address_of(const sockaddr_storage& addr);  // IPv4-mapped IPv6 as plain IPv4
PeerAddress local_address(int fd);

}  // namespace shadelab::http
