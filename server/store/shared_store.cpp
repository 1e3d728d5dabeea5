#include "store/shared_store.h"

#include <hiredis/hiredis.h>
#include <pthread.h>
#include <signal.h>
#include <sys/time.h>

#include <charconv>

namespace shadelab::store {

namespace {

using Clock = std::chrono::steady_clock;

timeval to_timeval(std::chrono::milliseconds ms) {
  return {static_cast<time_t>(ms.count() / 1000), static_cast<suseconds_t>((ms.count() % 1000) * 1000)};
}

struct ReplyDeleter {
  void operator()(redisReply* r) const { freeReplyObject(r); }
};
using Reply = std::unique_ptr<redisReply, ReplyDeleter>;

// hiredis writes with write(), not send(MSG_NOSIGNAL): a Redis that went away must not end this
// process with SIGPIPE. The signal is blocked for this thread during a command, and one it raised
// is taken off the pending set before the mask is restored (unless it was pending before).
class SigpipeBlocked {
 public:
  SigpipeBlocked() {
    sigemptyset(&pipe_);
    sigaddset(&pipe_, SIGPIPE);
    sigset_t pending;
    sigpending(&pending);
    was_pending_ = sigismember(&pending, SIGPIPE) == 1;
    pthread_sigmask(SIG_BLOCK, &pipe_, &old_);
  }
  ~SigpipeBlocked() {
    sigset_t pending;
    sigpending(&pending);
    if (!was_pending_ && sigismember(&pending, SIGPIPE) == 1) {
      const timespec now{0, 0};
      sigtimedwait(&pipe_, nullptr, &now);
    }
    pthread_sigmask(SIG_SETMASK, &old_, nullptr);
  }
  SigpipeBlocked(const SigpipeBlocked&) = delete;
  SigpipeBlocked& operator=(const SigpipeBlocked&) = delete;

 private:
  sigset_t pipe_, old_;
  bool was_pending_ = false;
};

bool parse_int(std::string_view text, int& out) {
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  return ec == std::errc() && end == text.data() + text.size();
}

}  // namespace

Expected<RedisAddress> parse_redis_url(std::string_view url) {
  const auto bad = [&] {
    return make_error(ErrorCode::invalid_argument,
                      "--redis takes redis://HOST[:PORT][/DB], HOST[:PORT] or unix:///PATH; got '" + std::string(url) + "'");
  };
  RedisAddress a;
  if (url.starts_with("unix://")) {
    a.socket_path = url.substr(7);
    if (a.socket_path.empty() || a.socket_path[0] != '/') return bad();
    return a;
  }
  std::string_view rest = url;
  if (rest.starts_with("redis://")) rest.remove_prefix(8);
  if (const auto slash = rest.find('/'); slash != std::string_view::npos) {
    if (!parse_int(rest.substr(slash + 1), a.db) || a.db < 0) return bad();
    rest = rest.substr(0, slash);
  }
  if (const auto colon = rest.rfind(':'); colon != std::string_view::npos) {
    if (!parse_int(rest.substr(colon + 1), a.port) || a.port <= 0 || a.port > 65535) return bad();
    rest = rest.substr(0, colon);
  }
  if (rest.empty()) return bad();
  a.host = rest;
  return a;
}

struct SharedStore::Connection {
  redisContext* context = nullptr;
  ~Connection() {
    if (context) redisFree(context);
  }
  // A reply that is not an error, or null (the connection is then unusable).
  Reply command(std::string& error, const char* format, auto... args) {
    const SigpipeBlocked no_sigpipe;
    Reply reply(static_cast<redisReply*>(redisCommand(context, format, args...)));
    if (!reply) error = context->errstr[0] ? context->errstr : "no reply";
    else if (reply->type == REDIS_REPLY_ERROR) error = std::string(reply->str, reply->len), reply.reset();
    return reply;
  }
};

SharedStore::SharedStore(SharedStoreConfig config, RedisAddress address)
    : config_(std::move(config)), address_(std::move(address)) {
  description_ = address_.socket_path.empty()
                     ? "redis://" + address_.host + ":" + std::to_string(address_.port) + "/" + std::to_string(address_.db)
                     : "unix://" + address_.socket_path;
}

SharedStore::~SharedStore() = default;

Expected<std::unique_ptr<SharedStore>> SharedStore::open(SharedStoreConfig config) {
  auto address = parse_redis_url(config.url);
  if (!address) return address.take_error();
  // Redis need not be up yet: a replica that starts first serves from its own memory meanwhile.
  return std::unique_ptr<SharedStore>(new SharedStore(std::move(config), std::move(*address)));
}

Error SharedStore::failed(const std::string& what) {
  std::lock_guard lock(mutex_);
  ++errors_;
  down_until_ = Clock::now() + config_.retry_after;
  idle_.clear();  // they lead to the same broken server
  return make_error(ErrorCode::store_unavailable, "the shared store " + description_ + " is unavailable: " + what);
}

Expected<std::unique_ptr<SharedStore::Connection>> SharedStore::acquire() {
  {
    std::lock_guard lock(mutex_);
    if (Clock::now() < down_until_) {
      ++skipped_;
      return make_error(ErrorCode::store_unavailable, "the shared store " + description_ + " is unavailable (retrying shortly)");
    }
    if (!idle_.empty()) {
      auto c = std::move(idle_.back());
      idle_.pop_back();
      return c;
    }
  }
  auto c = std::make_unique<Connection>();
  const timeval timeout = to_timeval(config_.timeout);
  c->context = address_.socket_path.empty() ? redisConnectWithTimeout(address_.host.c_str(), address_.port, timeout)
                                            : redisConnectUnixWithTimeout(address_.socket_path.c_str(), timeout);
  if (!c->context || c->context->err) return failed(c->context ? c->context->errstr : "cannot allocate a connection");
  redisSetTimeout(c->context, timeout);
  std::string error;
  if (address_.db != 0 && !c->command(error, "SELECT %d", address_.db)) return failed(error);
  return c;
}

void SharedStore::release(std::unique_ptr<Connection> connection) {
  std::lock_guard lock(mutex_);
  if (idle_.size() < 16) idle_.push_back(std::move(connection));
}

Expected<std::optional<std::string>> SharedStore::get(const std::string& key) {
  auto c = acquire();
  if (!c) return c.take_error();
  std::string error;
  Reply reply = (*c)->command(error, "GET %b", key.data(), key.size());
  if (!reply) return failed(error);
  std::optional<std::string> value;
  if (reply->type == REDIS_REPLY_STRING) value.emplace(reply->str, reply->len);
  release(std::move(*c));
  std::lock_guard lock(mutex_);
  ++(value ? hits_ : misses_);
  return value;
}

Status SharedStore::put(const std::string& key, std::string_view value) {
  if (value.size() > config_.max_value_bytes) return Ok{};
  auto c = acquire();
  if (!c) return c.take_error();
  std::string error;
  const long long ttl = config_.time_to_live.count();
  Reply reply = (*c)->command(error, "SET %b %b EX %lld", key.data(), key.size(), value.data(), value.size(), ttl);
  if (!reply) return failed(error);
  release(std::move(*c));
  std::lock_guard lock(mutex_);
  ++stores_;
  return Ok{};
}

std::string SharedStore::render_metrics() const {
  std::lock_guard lock(mutex_);
  const bool down = Clock::now() < down_until_;
  std::string out;
  out += "# HELP shadelab_shared_store_requests_total Shared store (Redis) lookups and stores, by outcome\n";
  out += "# TYPE shadelab_shared_store_requests_total counter\n";
  for (const auto& [outcome, n] : {std::pair{"hit", hits_}, {"miss", misses_}, {"stored", stores_}, {"error", errors_}, {"skipped", skipped_}})
    out += std::string("shadelab_shared_store_requests_total{outcome=\"") + outcome + "\"} " + std::to_string(n) + "\n";
  out += "# HELP shadelab_shared_store_up 1 while the shared store answers, 0 while it is marked down\n";
  out += "# TYPE shadelab_shared_store_up gauge\n";
  out += "shadelab_shared_store_up " + std::string(down ? "0" : "1") + "\n";
  return out;
}

}  // namespace shadelab::store
