#pragma once
// Which assignments of a stage can change what the program draws, read from tokens: an edit
// anywhere else cannot repair it, so the repair search (repair/repair_edits.h) spends no candidate
// there. Conservative: only an assignment to a name nothing live reads, and a condition or loop
// whose blocks hold nothing live, are dead; every other statement that is not an assignment (a
// call, a return) is live, and so is every name it reads.
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "repair/stage_tokens.h"

namespace shadelab::repair {

struct StageLiveness {
  std::set<std::string, std::less<>> live_names;
  std::vector<std::pair<size_t, size_t>> dead_spans;  // bytes of the GLSL: [begin, end)
  bool dead(size_t byte) const;
};

// The fragment stage's liveness: what reaches its outputs (its `out` variables, gl_FragColor).
StageLiveness fragment_liveness(const StageTokens& fragment);

// The vertex stage's: what reaches gl_Position and the outputs the fragment stage reads
// (`fragment_reads`: the fragment stage's live names).
StageLiveness vertex_liveness(const StageTokens& vertex, const std::set<std::string, std::less<>>& fragment_reads);

}  // namespace shadelab::repair
