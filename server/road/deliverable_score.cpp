#include "road/deliverable_score.h"

#include <cmath>
#include <cstdio>

namespace shadelab::road {

namespace {

using course::DeliverableTest;

// A whole report as a test worth `max`: its pass, not its own scale, decides the score.
grade::Report worth(const grade::Report& r, double max) {
  grade::Report out = r;
  out.max_score = max;
  out.score = r.pass ? max : 0;
  return out;
}

}  // namespace

std::string DeliverableScore::verdict() const {
  const auto number = [](double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", std::round(v * 1e6) / 1e6);
    return std::string(buf);
  };
  // What leads: the first graded test that fails; else the code's (it says the most), else the first graded.
  const TestScore* lead = nullptr;
  for (const auto& t : tests)
    if (t.report && !t.report->pass && t.max_score > 0) {
      lead = &t;
      break;
    }
  for (const auto& t : tests)
    if (!lead && t.report && t.test == course::DeliverableTest::code) lead = &t;
  for (const auto& t : tests)
    if (!lead && t.report) lead = &t;
  std::string out = number(score) + " / " + number(max_score) + ": ";
  if (!lead) out += "nothing to grade";
  else out += lead->report->messages.empty() ? (lead->report->pass ? "passes" : "does not pass") : lead->report->messages.front();
  std::string missing;
  for (const auto& t : tests)
    if (!t.report && t.max_score > 0) missing += (missing.empty() ? "" : ", ") + std::string(to_string(t.test)) + " (" + number(t.max_score) + ")";
  if (!missing.empty() && lead) out += "; not graded, nothing handed in for it: " + missing;
  return out;
}

DeliverableScore score_deliverable(const course::Checkpoint& k, double points, const DeliverableReports& g) {
  DeliverableScore out;
  const auto add = [&](DeliverableTest test, std::optional<grade::Report> report) {
    const double max = k.max_score(test, points);
    if (!k.applies(test) && !report) return;
    TestScore t{test, 0, max, std::move(report)};
    if (t.report) t.score = t.report->score;
    out.score += t.score;
    out.max_score += max;
    out.tests.push_back(std::move(t));
  };
  add(DeliverableTest::frames, g.frames ? std::optional(worth(*g.frames, k.max_score(DeliverableTest::frames, points))) : std::nullopt);
  add(DeliverableTest::code, g.code ? std::optional(part_of(*g.code, false, k.max_score(DeliverableTest::code, points))) : std::nullopt);
  if (k.applies(DeliverableTest::probe))
    add(DeliverableTest::probe, g.code ? std::optional(part_of(*g.code, true, k.max_score(DeliverableTest::probe, points))) : std::nullopt);
  add(DeliverableTest::match, g.match ? std::optional(worth(*g.match, k.max_score(DeliverableTest::match, points))) : std::nullopt);
  return out;
}

}  // namespace shadelab::road
