#pragma once
// The values a fragment stage's main computes, read back at each pixel (issue 79: "align by value,
// not by name"). A probed stage is the stage with, after each write of main's (on the write's own
// line: no line moves), a probe that copies the written variable to the output when the uniform
// `valueprobe_k` names it, and at main's start one for each input as main receives it. The
// grader draws each probe of the student's stage and of the reference's on a small canvas and says
// which of the student's values the reference computes too (grade/value_reading.h); the repair
// search then tries first the edits at the lines where a value departs from the reference's.
//
// A value agrees only with the reference's variable of the same role, never with any value of the
// reference's: `vec3 L = uLightPos - vPosition;` (the normalisation left out) equals the
// reference's `toLight`, and is still a wrong L.
#include <array>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "repair/repair_edit.h"
#include "repair/value_change.h"

namespace shadelab::repair {

class ProgramReading;

// A vec4 uniform: probe k copies its value to the output where the uniform's x is k. A vec4 so
// that one pass draws several probes (shader/uniform_variants.h runs main once per value).
inline constexpr const char* kProbeUniform = "valueprobe_k";

struct ValueProbe {
  bool input = false;  // an input as main receives it; else a variable after a write of main's...
  bool end = false;    // ...or the output as main ends (the last probe)
  std::string name;
  int line = 0;
  int ordinal = 0;     // a write's: the how-manyth write of its variable (0 first)
  bool last = false;   // a write's: the variable's last in main
  std::vector<std::string> reads;  // a write's: the locals and inputs it reads (a `+=` its own variable too)
};

struct ProbedStage {
  std::string glsl;
  std::vector<ValueProbe> probes;  // probe k is drawn where kProbeUniform's x is k
};

// The stage probed; none where it cannot be (not GLSL ES 3.00, no main, not exactly one `out vec4`,
// nothing to probe, a name of its own that begins `valueprobe_`). Writes inside a `for` header or an `if` without braces are not probed.
std::optional<ProbedStage> probed_fragment(std::string_view glsl);

// What the grader's draws of the probes found: for each of the student's probes, the reference's
// probes whose values are the same at every pixel where both were drawn (`agrees_with`), or
// nothing where no pixel was drawn by both; and those whose values differ at a pixel where the
// two programs' outputs differ too (`differs_visibly`): a value that differs only where the output
// does not (a clamp the student put in a local the reference clamps later) is no departure.
// Travels from the worker to the search, never to a client.
struct ValueAgreement {
  bool read = false;  // both stages were probed and drawn
  std::vector<std::vector<int>> agrees_with, differs_visibly;
  std::vector<bool> compared;
  // For each of the student's probes, how it differs from each reference probe it was compared
  // with and is not the same as (repair/value_change.h), where a change turns it into that one.
  std::vector<std::vector<ValueChangeTo>> changes;
};

// The lines of the student's fragment stage where a value first goes wrong, each with the changes
// that turn the student's value written there into its counterpart's (none known: an empty set).
// A write departs where its value differs from its counterpart's while every local and input it
// reads holds its counterpart's value (issue 79: "a write departs where its inputs are aligned and
// its value is not"): the counterpart is the reference's variable of the same role (the same local,
// or the one it aligns with; the k-th write with the k-th, a last with a last). Empty where the
// values were not read or say nothing.
using Departures = std::map<int, std::set<ValueChange>>;
Departures departures(const ProgramReading& read, const ValueAgreement& agreement);
// The departing lines alone.
std::set<int> lines_of(const Departures& d);

// Whether `e` makes a change its line's departing value needs (none where its line departs
// with no change known, or does not depart).
bool makes_departing_change(const RepairEdit& e, const Departures& at);

// The reference's locals whose value the student's write that `edit` changes (the last write of
// the edit's subject on its line) holds at every pixel both drew, other than its own counterpart,
// in the reference's order: `viewDir = normalize(uLightPosition - vPosition)` holds the
// reference's L. Empty where the values were not read or that write was not probed.
std::vector<std::string> values_it_holds(const ProgramReading& read, const RepairEdit& edit, const ValueAgreement& agreement);

// Whether the student's write that `edit` changes holds the reference's local `role` at every
// pixel both drew, or one change of it (repair/value_change.h): `viewDir = normalize(vPosition)`
// is V negated, and so stands for V whatever the names say. False where the values were not read.
bool value_stands_for(const ProgramReading& read, const RepairEdit& edit, const ValueAgreement& agreement, std::string_view role);

}  // namespace shadelab::repair
