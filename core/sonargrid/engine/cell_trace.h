// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// One cell's history over a log: every reading that wrote the cell, what the sensor model gave it
// (pE, pO, P(s|occ)), and the cell's value after the update rule folded that in. It replays the
// log with the map's own model and rule (a Mapper made with the same settings and grid), so the
// trace's last value is, bit for bit, the value a map of the same log has at that cell (the cell
// inspector of the desktop app; docs/user-guide.md, "Inspecting a cell").

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "sonargrid/data/dataset.h"
#include "sonargrid/engine/grid_spec.h"
#include "sonargrid/engine/mapper.h"

namespace sg {

// A cell that is not in the grid.
class CellTraceError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// The cell's value as the rule reads it: the four layers of an OccupancyMap at that cell.
struct CellValue {
  double probability = 0.5;  // p(occupied)
  double native = 0.0;       // the rule's own value (HIMM CV, log-odds, Occ − Emp …)
  std::uint8_t level = 8;    // 0..15
  bool filled = false;
};

// One reading that wrote the cell.
struct CellTraceStep {
  std::size_t reading = 0;  // its index among the log's readings taken (up to `until`), log order
  std::size_t scan = 0;     // the scan it belongs to
  std::uint16_t sonar = 0;
  double time = 0.0;   // seconds
  double range = 0.0;  // metres, or Reading::kNoEcho
  // The model's output at the cell, as the rule is given it (footprint.h).
  float empty = 0.0f;        // pE
  float occupied = 0.0f;     // pO
  float probability = 0.5f;  // P(occupied | this reading)
  CellValue after;           // the cell once the rule has folded the reading in
};

struct CellTrace {
  GridSpec grid;
  CellIndex cell{0, 0};
  std::string nativeName;  // what CellValue::native holds (RuleInfo::nativeName)
  CellValue initial;       // a cell nobody has seen, as the rule declares it
  std::vector<CellTraceStep> steps;
  std::size_t readings = 0;  // readings of the log taken (time <= until), whether or not they wrote
  double firstTime = 0.0, lastTime = 0.0;  // of those readings (both 0 when there are none)
  bool complete = true;                    // false when `cancel` stopped the replay part-way

  // The value after the last reading (the map's value at the cell), or `initial`.
  const CellValue& final() const { return steps.empty() ? initial : steps.back().after; }
};

// Replays `dataset` (readings up to `until`) for cell `cell` of `grid` with the model, rule,
// parameters and pose source of `settings`, as Mapper::mapDataset on `grid` maps it. Checks
// `cancel` every few hundred readings (then returns what it has, complete = false). Throws
// MapperError as the Mapper does (unknown model or rule, a pair not allowed, a missing true pose,
// a reading naming a sonar the ring lacks) and CellTraceError when the cell is outside `grid`.
CellTrace traceCell(const Dataset& dataset, const GridSpec& grid, const MapperSettings& settings,
                    const CellIndex& cell, double until = std::numeric_limits<double>::infinity(),
                    const std::atomic<bool>* cancel = nullptr);

}  // namespace sg
