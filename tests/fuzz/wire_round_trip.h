#pragma once
// The invariant several targets share: what the HTTP process validated is what the worker gets.
// A job or a scene sent over the worker wire reads back as one that encodes to the same message.
#include <nlohmann/json.hpp>

#include "fuzz_check.h"
#include "worker/job.h"

namespace shadelab::fuzz {

inline bool same_message(const worker::Message& a, const worker::Message& b) { return a.header == b.header && a.payload == b.payload; }

inline void check_job_crosses_the_wire(const worker::Job& job) {
  const worker::Message sent = worker::to_message(job);
  auto received = worker::job_from_message(sent);
  FUZZ_CHECK(received.ok());
  FUZZ_CHECK(same_message(worker::to_message(*received), sent));
}

inline void check_scene_crosses_the_wire(const scene::SceneDescription& scene) {
  const nlohmann::json wire = scene;
  FUZZ_CHECK(nlohmann::json(nlohmann::json::parse(wire.dump()).get<scene::SceneDescription>()) == wire);
}

}  // namespace shadelab::fuzz
