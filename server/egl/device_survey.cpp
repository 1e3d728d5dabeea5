#include "egl/device_survey.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <filesystem>

#include "egl/headless_context.h"

namespace shadelab::egl {

namespace {

// In the child: one byte, 'h' or 's'.
[[noreturn]] void answer(int fd) {
  const auto devices = enumerate_devices();
  const bool hardware = std::any_of(devices.begin(), devices.end(), [](const DeviceDescription& d) { return !d.software; });
  const char verdict = hardware ? 'h' : 's';
  (void)!::write(fd, &verdict, 1);
  ::_exit(0);
}

// A GPU's EGL device is backed by a node in /dev: a DRM render node (Mesa's drivers) or NVIDIA's
// own. Without one only the software device can be listed, and the child (~12 ms) is not needed.
bool has_gpu_node() {
  std::error_code ignored;
  for (const auto& entry : std::filesystem::directory_iterator("/dev/dri", ignored))
    if (entry.path().filename().string().starts_with("renderD")) return true;
  return std::filesystem::exists("/dev/nvidia0", ignored) || std::filesystem::exists("/dev/nvidiactl", ignored);
}

}  // namespace

DeviceSurvey survey_devices(std::chrono::milliseconds deadline) {
  return has_gpu_node() ? survey_devices_in_child(deadline) : DeviceSurvey::software;
}

DeviceSurvey survey_devices_in_child(std::chrono::milliseconds deadline) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) return DeviceSurvey::unanswered;
  const pid_t child = ::fork();
  if (child < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    return DeviceSurvey::unanswered;
  }
  if (child == 0) {
    ::close(fds[0]);
    answer(fds[1]);
  }
  ::close(fds[1]);
  char verdict = 0;
  pollfd p{fds[0], POLLIN, 0};
  int polled;
  while ((polled = ::poll(&p, 1, static_cast<int>(deadline.count()))) < 0 && errno == EINTR) {
  }
  const bool read_one = polled > 0 && ::read(fds[0], &verdict, 1) == 1;
  ::close(fds[0]);
  if (!read_one) ::kill(child, SIGKILL);  // a driver that hangs listing its devices
  while (::waitpid(child, nullptr, 0) < 0 && errno == EINTR) {
  }
  if (!read_one) return DeviceSurvey::unanswered;
  return verdict == 'h' ? DeviceSurvey::hardware : DeviceSurvey::software;
}

}  // namespace shadelab::egl
