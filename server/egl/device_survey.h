#pragma once
// Whether this machine offers a GPU, asked of a short-lived child process: the process that serves
// HTTP forks the render workers and must never load a GL driver itself (a driver's threads and
// open handles would be copied into every worker, and the fork server must start single-threaded).
#include <chrono>

namespace shadelab::egl {

enum class DeviceSurvey {
  hardware,     // an EGL device that is not Mesa's software rasteriser
  software,     // only the software device (llvmpipe), or no EGL device at all
  unanswered,   // the child crashed, hung past the deadline or could not be started
};

// No child where /dev has no GPU node; elsewhere the child loads libEGL and lists the devices, with
// no context (~12 ms on llvmpipe).
DeviceSurvey survey_devices(std::chrono::milliseconds deadline = std::chrono::seconds(5));
// The child's answer alone, whatever /dev holds.
DeviceSurvey survey_devices_in_child(std::chrono::milliseconds deadline);

}  // namespace shadelab::egl
