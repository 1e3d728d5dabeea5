// The small parsers of what a client or an operator writes, each the function the service calls:
// X-Forwarded-For through client_address (the address a tenant's rate is counted by),
// --trusted-proxy ranges, --redis URLs, and the number lists of /api/dolly's query and --uniform.
// The selector byte picks the parser. Invariants: the client address is the peer or an entry the
// header holds; a range accepted is a range address_in can use; a Redis URL accepted has a
// socket path or a host, a port in range and a database number >= 0; a number list accepted
// holds finite numbers, as many as asked.
#include <cmath>
#include <string>

#include "core/number_list.h"
#include "fuzz_check.h"
#include "http/tenants.h"
#include "store/shared_store.h"

namespace {

using namespace shadelab;

void forwarded_for(fuzz::InputReader& input) {
  const std::string peer(input.part()), header(input.part()), range(input.rest());
  const std::vector<std::string> trusted{range, "127.0.0.1", "10.0.0.0/8"};
  const std::string client = http::client_address(peer, header, trusted);
  FUZZ_CHECK(client == peer || (!client.empty() && header.find(client) != std::string::npos));
}

void proxy_range(fuzz::InputReader& input) {
  const std::string range(input.part()), address(input.rest());
  if (!http::check_address_ranges({range})) return;
  (void)http::address_in(address, {range});
  // Every range holds its own network address (the text before the slash).
  FUZZ_CHECK(http::address_in(range.substr(0, range.find('/')), {range}));
}

void redis_url(fuzz::InputReader& input) {
  auto address = store::parse_redis_url(input.rest());
  if (!address) return;
  FUZZ_CHECK(!address->socket_path.empty() || !address->host.empty());
  FUZZ_CHECK(address->port >= 1 && address->port <= 65535);
  FUZZ_CHECK(address->db >= 0);
}

void number_list(fuzz::InputReader& input) {
  const std::uint8_t flags = input.byte();
  const NumberListOptions options{.booleans = (flags & 1) != 0, .count = static_cast<size_t>(flags >> 1) % 5};
  auto numbers = parse_number_list(input.rest(), "uLight", options);
  if (!numbers) {
    FUZZ_CHECK(!numbers.error().message.empty());
    return;
  }
  for (double v : *numbers) FUZZ_CHECK(std::isfinite(v));
  FUZZ_CHECK(options.count == 0 || numbers->size() == options.count);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
  fuzz::InputReader input(data, size);
  switch (input.byte() % 4) {
    case 0: forwarded_for(input); break;
    case 1: proxy_range(input); break;
    case 2: redis_url(input); break;
    default: number_list(input); break;
  }
  return 0;
}
