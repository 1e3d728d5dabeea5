// The shared store against a real redis-server (on a Unix socket in a folder of the test's own):
// values round-trip, a dead or hung Redis is an error within the timeout and is then left alone,
// and the store comes back by itself. The reference store's cluster tier on it: one node's
// references read by another, whole or not at all.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <thread>

#include "grade/reference_store.h"
#include "store/shared_store.h"

namespace shadelab::store {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

class RedisServer {
 public:
  explicit RedisServer(const fs::path& dir) : socket_((dir / "redis.sock").string()), log_((dir / "redis.log").string()) {
    fs::create_directories(dir);
    start();
  }
  ~RedisServer() { stop(); }
  void start() {
    pid_ = ::fork();
    if (pid_ == 0) {
      ::prctl(PR_SET_PDEATHSIG, SIGKILL);
      ::execlp("redis-server", "redis-server", "--port", "0", "--unixsocket", socket_.c_str(), "--save", "", "--appendonly", "no",
               "--logfile", log_.c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
    // Ready when it accepts a connection: redis creates the socket file at bind(), before
    // listen(), and a connect in between is refused (seen on a loaded machine).
    const auto deadline = Clock::now() + 10s;
    while (!accepts_connections() && Clock::now() < deadline) std::this_thread::sleep_for(10ms);
  }
  bool accepts_connections() const {
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    if (socket_.size() >= sizeof address.sun_path) return false;
    std::memcpy(address.sun_path, socket_.c_str(), socket_.size() + 1);
    const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0) return false;
    const bool connected = ::connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) == 0;
    ::close(fd);
    return connected;
  }
  void stop() {
    if (pid_ <= 0) return;
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
    fs::remove(socket_);
    pid_ = 0;
  }
  void pause() const { ::kill(pid_, SIGSTOP); }
  void resume() const { ::kill(pid_, SIGCONT); }
  std::string url() const { return "unix://" + socket_; }

 private:
  std::string socket_, log_;
  pid_t pid_ = 0;
};

// A redis-server of the test's own, in a folder removed afterwards (also when an assertion failed).
class SharedStoreTest : public ::testing::Test {
 protected:
  fs::path dir_ = fs::temp_directory_path() / ("shadelab_store_" + std::to_string(::getpid()) + "_" +
                                               ::testing::UnitTest::GetInstance()->current_test_info()->name());
  RedisServer redis{dir_};
  void TearDown() override {
    redis.stop();
    fs::remove_all(dir_);
  }
};

std::unique_ptr<SharedStore> open_store(const std::string& url) {
  SharedStoreConfig config;
  config.url = url;
  config.timeout = 200ms;
  config.retry_after = 500ms;
  auto store = SharedStore::open(config);
  EXPECT_TRUE(store);
  return store ? std::move(*store) : nullptr;
}

TEST_F(SharedStoreTest, ValuesRoundTripBinarySafe) {
  auto store = open_store(redis.url());
  const std::string value("\0png\r\n\xff", 8);
  ASSERT_TRUE(store->put("k", value));
  auto got = store->get("k");
  ASSERT_TRUE(got);
  ASSERT_TRUE(*got);
  EXPECT_EQ(**got, value);
  auto missing = store->get("nothing here");
  ASSERT_TRUE(missing);
  EXPECT_FALSE(*missing);
  EXPECT_NE(store->render_metrics().find("shadelab_shared_store_requests_total{outcome=\"hit\"} 1"), std::string::npos);
}

TEST_F(SharedStoreTest, AHungRedisCostsOneTimeoutThenIsLeftAloneUntilItIsBack) {
  auto store = open_store(redis.url());
  ASSERT_TRUE(store->put("k", "v"));
  redis.pause();
  auto start = Clock::now();
  auto hung = store->get("k");
  ASSERT_FALSE(hung);
  EXPECT_EQ(hung.error().code, ErrorCode::store_unavailable);
  EXPECT_LT(Clock::now() - start, 2s) << "the command timeout did not hold";
  start = Clock::now();
  EXPECT_FALSE(store->get("k"));  // marked down: no second timeout
  EXPECT_LT(Clock::now() - start, 50ms);
  EXPECT_NE(store->render_metrics().find("shadelab_shared_store_up 0"), std::string::npos);
  redis.resume();
  std::this_thread::sleep_for(600ms);  // past retry_after
  auto back = store->get("k");
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(back->value_or(""), "v");
}

TEST_F(SharedStoreTest, ADeadRedisIsAnErrorAndARestartedOneIsUsedAgain) {
  auto store = open_store(redis.url());
  ASSERT_TRUE(store->put("k", "v"));
  redis.stop();
  EXPECT_FALSE(store->get("k"));
  redis.start();  // empty, as the supervisor restarts it
  std::this_thread::sleep_for(600ms);
  auto after = store->get("k");
  ASSERT_TRUE(after);
  EXPECT_FALSE(*after) << "a restarted Redis holds nothing: a miss, recomputed";
}

grade::SharedFrames two_frames() {
  grade::SharedFrames frames;
  for (int k = 0; k < 2; ++k) {
    auto f = std::make_shared<image::Image>(image::Image::blank(5, 3, image::PixelType::u8));
    for (size_t i = 0; i < f->bytes.size(); ++i) f->bytes[i] = static_cast<std::uint8_t>(i * 7 + k);
    frames.push_back(std::move(f));
  }
  return frames;
}

// What two_frames() renders: the shape a load expects.
render::RenderRequest two_frames_request() {
  render::RenderRequest r;
  r.width = 5;
  r.height = 3;
  r.frames = 2;
  r.pixel_type = image::PixelType::u8;
  return r;
}

size_t files_in(const fs::path& folder) {
  size_t n = 0;
  for (std::error_code ec; const auto& e : fs::directory_iterator(folder, ec)) n += e.is_regular_file() ? 1 : 0;
  return n;
}

TEST_F(SharedStoreTest, ReferencesSavedOnOneNodeAreReadOnAnotherAndKeptOnItsDisk) {
  auto shared = open_store(redis.url());
  const grade::ReferenceStore first(dir_ / "node-a", shared.get(), "llvmpipe"), second(dir_ / "node-b", shared.get(), "llvmpipe");
  const std::string key = first.key({}, "mesh");
  const auto request = two_frames_request();
  EXPECT_FALSE(second.load(key, request)) << "nothing saved yet";
  first.save(key, two_frames());
  const auto read = second.load(key, request);
  ASSERT_TRUE(read);
  ASSERT_EQ(read->size(), 2u);
  EXPECT_EQ((*read)[1]->bytes, two_frames()[1]->bytes);
  EXPECT_EQ(files_in(dir_ / "node-b"), 1u) << "kept on the second node's disk";

  redis.pause();  // a hung Redis: the disk still answers, and a miss costs one timeout
  const auto from_disk = second.load(key, request);
  ASSERT_TRUE(from_disk);
  EXPECT_EQ((*from_disk)[0]->bytes, two_frames()[0]->bytes);
  const grade::ReferenceStore third(dir_ / "node-c", shared.get(), "llvmpipe");
  const auto start = Clock::now();
  EXPECT_FALSE(third.load(key, request)) << "Redis is down: a miss, rendered";
  EXPECT_LT(Clock::now() - start, 2s);
  redis.resume();
}

TEST_F(SharedStoreTest, APartReferenceInRedisIsAMiss) {
  auto shared = open_store(redis.url());
  const grade::ReferenceStore first(dir_ / "node-a", shared.get(), "llvmpipe"), second(dir_ / "node-b", shared.get(), "llvmpipe");
  const std::string key = first.key({}, "mesh"), redis_key = "shadelab:1:reference:" + key;
  const auto request = two_frames_request();
  first.save(key, two_frames());
  const auto whole = shared->get(redis_key);
  ASSERT_TRUE(whole && *whole) << "the entry is in Redis under the reference prefix";
  const std::string entry = **whole;
  ASSERT_TRUE(second.load(key, request)) << "whole, it reads";
  fs::remove_all(dir_ / "node-b");
  const auto misses = [&](const std::string& stored, const std::string& why) {
    ASSERT_TRUE(shared->put(redis_key, stored));
    EXPECT_FALSE(second.load(key, request)) << why;
    EXPECT_EQ(files_in(dir_ / "node-b"), 0u) << why << ": not copied to disk";
  };
  misses(entry.substr(0, entry.size() / 2), "half an entry is no frames");
  misses(entry.substr(0, entry.size() - 1), "the checksum cut short");
  misses(entry + "x", "a byte after the frames");
  for (size_t at : {entry.size() / 2, entry.size() - 2}) {  // inside the pixels, inside the checksum
    std::string flipped = entry;
    flipped[at] = static_cast<char>(flipped[at] ^ 0x10);
    misses(flipped, "a bit flipped at byte " + std::to_string(at));
  }
  // A header claiming 16384 x 16384 x 3600 float frames over a few bytes: a miss, not an allocation.
  std::string claim = entry.substr(0, 7);
  for (std::uint32_t v : {16384u, 16384u, 3600u, 1u})
    for (int i = 0; i < 4; ++i) claim += static_cast<char>((v >> (8 * i)) & 0xff);
  misses(claim + "xx", "a header of another shape");
  // The request decides the shape: the same entry read for three frames is not its frames.
  ASSERT_TRUE(shared->put(redis_key, entry));
  auto three = request;
  three.frames = 3;
  EXPECT_FALSE(second.load(key, three));
}

TEST(RedisAddressTest, AddressesAreParsedOrRefused) {
  auto tcp = parse_redis_url("redis://cache.internal:6380/2");
  ASSERT_TRUE(tcp);
  EXPECT_EQ(tcp->host, "cache.internal");
  EXPECT_EQ(tcp->port, 6380);
  EXPECT_EQ(tcp->db, 2);
  auto bare = parse_redis_url("localhost");
  ASSERT_TRUE(bare);
  EXPECT_EQ(bare->port, 6379);
  auto unix_socket = parse_redis_url("unix:///run/redis.sock");
  ASSERT_TRUE(unix_socket);
  EXPECT_EQ(unix_socket->socket_path, "/run/redis.sock");
  for (const char* bad : {"", "redis://", "redis://h:0", "redis://h:99999", "h:port", "redis://h/x", "unix://relative"})
    EXPECT_FALSE(parse_redis_url(bad)) << bad;
}

}  // namespace
}  // namespace shadelab::store
