#include "repair/search_order.h"

#include <algorithm>
#include <limits>
#include <map>
#include <set>

namespace shadelab::repair {

namespace {

// Whether the search goes on after a phase: nothing confirmed, and the caller could draw it.
bool open(Pass p) { return p == Pass::none_passed || p == Pass::budget_spent; }

bool at(const RepairEdit& e, const std::set<int>& departing) { return e.stage == shader::Stage::fragment && departing.count(e.line) > 0; }

// The singles in two groups, each in the singles' order: first those that align the student's line
// with the reference (aligns) or edit a line where a value first departs, then the others. A
// departure alone does not put an edit first: where the student clamps at the write and the
// reference at the use (`float diff = dot(N, L)` against `max(0.0, NdotL)`), the value departs at
// the use, a line after the mistake.
struct Singles {
  std::vector<RepairCandidate> first, rest;
  std::vector<RepairCandidate> all() const {
    std::vector<RepairCandidate> out = first;
    out.insert(out.end(), rest.begin(), rest.end());
    return out;
  }
};

// How many of `c`'s edits make the change their line's departing value needs (repair/value_change.h).
int making(const RepairCandidate& c, const Departures& changes) {
  return static_cast<int>(std::count_if(c.edits.begin(), c.edits.end(), [&](const auto& e) { return makes_departing_change(e, changes); }));
}

// Whether `c` restores the reference's value at a line whose value departs in no one change the
// values could name (`normalize(L + V)` for `reflect(-L, N)`): no edit makes that change but the
// value put back whole.
bool restores_unknown_change(const RepairCandidate& c, const Departures& changes) {
  return c.edits.size() == 1 && c.edits.front().kind == RepairKind::value_restored && c.edits.front().stage == shader::Stage::fragment &&
         changes.contains(c.edits.front().line) && changes.at(c.edits.front().line).empty();
}

// `candidates` with those whose edits make more of the changes the values need first, each
// group in its own order: the values chose their edit before any was drawn.
std::vector<RepairCandidate> changes_first(std::vector<RepairCandidate> candidates, const Departures& changes) {
  std::stable_sort(candidates.begin(), candidates.end(),
                   [&](const RepairCandidate& a, const RepairCandidate& b) { return making(a, changes) > making(b, changes); });
  return candidates;
}

Singles split_at(std::vector<RepairCandidate> singles, const Departures& changes) {
  Singles out;
  const std::set<int> departing = lines_of(changes);
  for (auto& c : singles) {
    const bool first = std::any_of(c.edits.begin(), c.edits.end(), [&](const auto& e) { return aligns(e) || at(e, departing); });
    (first ? out.first : out.rest).push_back(std::move(c));
  }
  out.first = changes_first(std::move(out.first), changes);
  return out;
}

// The pairs of two of `first` (screened: `distances`) at two lines where a value departs, in
// pair_candidates' order: two mistakes whose values do not depend on each other, each found at
// its own line.
std::vector<RepairCandidate> departure_pairs(const RepairProgram& p, const std::vector<RepairCandidate>& first,
                                             const std::vector<double>& distances, double own, const std::set<int>& departing,
                                             const Departures& changes, const CandidateCounts& counts) {
  auto pairs = pair_candidates(p, first, distances, own, counts);
  std::erase_if(pairs, [&](const RepairCandidate& c) {
    return c.edits.size() != 2 || !at(c.edits[0], departing) || !at(c.edits[1], departing) || c.edits[0].line == c.edits[1].line;
  });
  return changes_first(std::move(pairs), changes);
}

// The screened single that drew nearest the reference, nearer than the student's `own` program
// (the first of equals); none where none did.
std::optional<size_t> nearest(const std::vector<double>& distances, double own) {
  std::optional<size_t> out;
  for (size_t i = 0; i < distances.size(); ++i)
    if (distances[i] < own && (!out || distances[i] < distances[*out])) out = i;
  return out;
}

// Whether `c`'s program is one of `tried`'s.
bool tried(const RepairCandidate& c, const std::vector<RepairCandidate>& tried) {
  return std::any_of(tried.begin(), tried.end(), [&](const auto& t) { return t.vertex.text == c.vertex.text && t.fragment.text == c.fragment.text; });
}

// A pairs' phase between two of the singles': where it confirms nothing, the singles go on as the
// last singles' phase left them.
Pass between(Pass singles, Pass pairs) { return open(pairs) ? singles : pairs; }

// One search's state: what it was given, what it tried and what is left of its budget.
struct Search {
  const RepairProgram& p;
  const CandidateCounts& counts;
  Screens& screens;
  Confirmations left;
  const Departures changes;
  const std::set<int> departing;
  const Singles singles;
  std::vector<double> distances;       // each screened single's, `singles.first`'s first
  std::vector<RepairCandidate> early;  // the pairs phases 1 to 3 tried
  std::optional<double> own;
  std::vector<RepairEdit> found;       // the confirmed candidate's edits
  // Where each single (of `singles.first`) whose values were read still departs: read once.
  std::map<size_t, Departures> departing_after_read;

  bool pairing() const { return counts.pairs > 0 && left.pairs > 0; }
  int pairs_left() const { return std::max(0, counts.pairs - static_cast<int>(early.size())); }

  // The student's own distance, drawn once; false where it could not be.
  bool know_own() { return own || (own = screens.own_distance()); }

  Pass run(const std::vector<RepairCandidate>& candidates, int& budget, std::vector<double>* screened) {
    const RepairCandidate* winner = nullptr;
    const Pass pass = screens.try_within(candidates, budget, screened, &winner);
    if (pass == Pass::confirmed && winner) found = winner->edits;
    return pass;
  }

  // `pairs` not tried yet, at most what is left of `pairs` in all, tried within the pairs'
  // confirmations and remembered as tried.
  Pass try_pairs(std::vector<RepairCandidate> pairs) {
    std::erase_if(pairs, [&](const RepairCandidate& c) { return tried(c, early); });
    pairs.resize(std::min(pairs.size(), static_cast<size_t>(pairs_left())));
    const Pass pass = run(pairs, left.pairs, nullptr);
    early.insert(early.end(), std::make_move_iterator(pairs.begin()), std::make_move_iterator(pairs.end()));
    return pass;
  }

  // Pairs of two of `picked` (singles whose edit makes the change its line's value needs) at two
  // lines, in `picked`'s order.
  std::vector<RepairCandidate> pairs_among(const std::vector<RepairCandidate>& picked) const {
    std::vector<RepairCandidate> out;
    CandidateCounts within = counts;
    within.pairs = pairs_left();
    for (const auto& a : picked) {
      std::set<int> later;
      for (const auto& b : picked)
        if (b.edits.front().line > a.edits.front().line) later.insert(b.edits.front().line);
      auto with = pairs_with(p, a.edits.front(), picked, later, within);
      out.insert(out.end(), std::make_move_iterator(with.begin()), std::make_move_iterator(with.end()));
    }
    return out;
  }

  // Phase 1: first the singles the values chose (a prefix of `singles.first`: each edit makes
  // the change its line's departing value needs), then, where they are at two lines, their pairs,
  // then the nearest of them with the lines where its own values still depart (phase 3 for the
  // chosen alone), then the rest of `singles.first`; each screen's distance kept in
  // `singles.first`'s order.
  Pass chosen_first() {
    const auto& first = singles.first;
    const auto chosen = std::find_if(first.begin(), first.end(), [&](const RepairCandidate& c) { return making(c, changes) == 0; });
    const std::vector<RepairCandidate> picked(first.begin(), chosen), others(chosen, first.end());
    Pass pass = run(picked, left.singles, &distances);
    if (pass == Pass::none_passed && pairing()) pass = between(pass, try_pairs(pairs_among(picked)));
    if (pass == Pass::none_passed && pairing() && !picked.empty()) pass = between(pass, hidden_departures(Seconds::chosen));
    return open(pass) ? run(others, left.singles, &distances) : pass;
  }

  // Phase 2: two lines where a value departs, a mistake at each.
  Pass departures() {
    if (!know_own()) return Pass::trouble;
    return try_pairs(departure_pairs(p, singles.first, distances, *own, departing, changes, counts));
  }

  // Which singles phase 3 pairs with the nearest: every one at a line where its program still
  // departs, or (where the values chose the nearest) only those that make the change that line's
  // value needs: a nearest chosen wrongly must not spend the pairs on every edit of its lines.
  enum class Seconds { all, chosen };

  // Phase 3: the lines where the nearest single screened so far still departs in its own
  // program's values (each single's values read once, its pairs not tried twice).
  Pass hidden_departures(Seconds seconds = Seconds::all) {
    if (!know_own()) return Pass::trouble;
    // The values chose each of `chosen`'s singles: its value is its counterpart's after the edit,
    // however far it draws (V's sign mended beside the half vector draws further from the
    // reference than the student's own program does).
    const auto n = nearest(distances, seconds == Seconds::chosen ? std::numeric_limits<double>::infinity() : *own);
    if (!n) return Pass::none_passed;
    const RepairCandidate& single = singles.first[*n];
    if (!departing_after_read.count(*n)) {
      const auto read = screens.values_of(single);
      departing_after_read[*n] = read ? departing_after(p, single, *read) : Departures{};
    }
    const Departures& after = departing_after_read[*n];
    if (after.empty()) return Pass::none_passed;
    CandidateCounts within = counts;
    within.pairs = pairs_left();
    std::vector<RepairCandidate> with = changes_first(singles.all(), after);
    if (seconds == Seconds::chosen)
      std::erase_if(with, [&](const RepairCandidate& c) { return making(c, after) == 0 && !restores_unknown_change(c, after); });
    return try_pairs(pairs_with(p, single.edits.front(), with, lines_of(after), within));
  }

  // Phase 5: no one edit repairs it: two edits (pair_candidates says which, in what order).
  Pass all_pairs() {
    if (!know_own()) return Pass::trouble;
    return try_pairs(pair_candidates(p, singles.all(), distances, *own, counts));
  }
};

}  // namespace

SearchOutcome search_in_order(const RepairProgram& p, const CandidateCounts& counts, Confirmations confirmations,
                              const ValueAgreement& values, Screens& screens) {
  const Departures changes = departures(p.read, values);
  Search s{p, counts, screens, confirmations, changes, lines_of(changes), split_at(single_candidates(p, counts), changes), {}, {}, {}, {}, {}};
  const Pass first = s.chosen_first();
  Pass pass = first;
  if (open(pass) && s.pairing() && s.departing.size() >= 2) pass = between(first, s.departures());
  if (open(pass) && s.pairing() && values.read) pass = between(first, s.hidden_departures());
  if (pass == Pass::none_passed) pass = s.run(s.singles.rest, s.left.singles, &s.distances);
  // A single whose screen passed and whose full render did not is a mistake half mended: the
  // pairs still get confirmations of their own.
  if (open(pass) && s.pairing()) pass = s.all_pairs();
  return {pass, std::move(s.found)};
}

}  // namespace shadelab::repair
