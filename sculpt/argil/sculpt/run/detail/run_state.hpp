#pragma once
// Internal to the runner: what a run accumulates tick by tick, for the journal
// and the outputs written at the end.

#include <algorithm>
#include <vector>

#include "argil/sculpt/output/tick_log.hpp"
#include "argil/sculpt/script/script.hpp"

namespace argil::sculpt::detail {

struct RunState {
  TickLog log;                             // every tick, replayed ones included
  std::vector<double> wall_s, cpu_s;       // per live tick [s]
  std::vector<DeviceSample> received;      // every sample, for recorded.csv and the path
  std::vector<DeviceSample> unjournalled;  // since the last journal record
  int strokes = 0;                         // journalled
  long long next_tick = 0;
  /// The script's undo and redo commands applied (and journalled) so far.
  std::vector<ScriptSampler::Command> commands;
};

/// Whether a journal record's samples make a stroke: free moves journalled
/// before an undo or redo do not.
inline bool holds_stroke(const std::vector<DeviceSample>& samples) {
  return std::any_of(samples.begin(), samples.end(),
                     [](const DeviceSample& s) { return s.engaged; });
}

}  // namespace argil::sculpt::detail
