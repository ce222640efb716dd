// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/engine/cell_trace.h"

#include <algorithm>
#include <sstream>

#include "sonargrid/data/scan_poses.h"

namespace sg {

namespace {

// How often the replay looks at the cancel flag, in readings (as Mapper::mapDataset).
constexpr std::size_t kCancelStride = 256;

CellValue valueOf(const UpdateRule& rule, const Grid& grid) {
  CellValue v;
  v.probability = rule.occupancy(grid, 0);
  v.native = rule.native(grid, 0);
  v.level = rule.level(grid, 0);
  v.filled = rule.filled(grid, 0);
  return v;
}

}  // namespace

CellTrace traceCell(const Dataset& dataset, const GridSpec& grid, const MapperSettings& settings,
                    const CellIndex& cell, double until, const std::atomic<bool>* cancel) {
  if (!grid.contains(cell)) {
    std::ostringstream msg;
    msg << "cell (" << cell.x() << ", " << cell.y() << ") is outside the " << grid.width << " × "
        << grid.height << " grid";
    throw CellTraceError(msg.str());
  }
  if (settings.pose == PoseSource::Truth && !anyScanHasPose(dataset, PoseSource::Truth))
    throw MapperError(std::string(kNoTruePose) + "; map with odometry (--pose odom)");
  // The map's own model, rule, parameters and cone tables: the footprints below are the ones
  // mapDataset folds in, cell for cell.
  const Mapper mapper(dataset.ring, grid, settings);
  const UpdateRule& rule = mapper.rule();
  const std::size_t target = grid.linear(cell);

  CellTrace trace;
  trace.grid = grid;
  trace.cell = cell;
  trace.nativeName = rule.info().nativeName;
  // The cell alone, in a grid of one cell made with the rule's layout: a rule updates each cell
  // from that cell's evidence and the footprint's totals only (update_rule.h), which the replay
  // hands it just as the mapper does.
  GridSpec one;
  one.origin = grid.cellCentre(cell) - Position(0.5 * grid.cellSize, 0.5 * grid.cellSize);
  one.cellSize = grid.cellSize;
  one.width = one.height = 1;
  Grid state(one, rule.layout());
  trace.initial = valueOf(rule, state);

  // A model writes no farther than its reach from the sensor (cell centres within it; two cells
  // more hold the cells those centres lie in, as Mapper::append bounds it): readings from farther
  // away cannot touch the cell, and their footprints need not be computed.
  const double reach = mapper.model().reach(dataset.ring.maxRange) + 2.0 * grid.cellSize;
  const Position centre = grid.cellCentre(cell);
  Footprint part;
  for (std::size_t s = 0; s < dataset.scans.size(); ++s) {
    const Scan& scan = dataset.scans[s];
    if (!hasPose(scan, settings.pose)) continue;  // left out of the map (scan_poses.h)
    const Pose2D& robot = dataset.pose(scan, settings.pose);
    for (const Reading& r : scan.readings) {
      if (r.time > until) continue;
      const std::size_t index = trace.readings++;
      trace.firstTime = index == 0 ? r.time : std::min(trace.firstTime, r.time);
      trace.lastTime = index == 0 ? r.time : std::max(trace.lastTime, r.time);
      if (cancel && index % kCancelStride == 0 && cancel->load(std::memory_order_relaxed)) {
        trace.complete = false;
        return trace;
      }
      // A sonar the ring lacks falls through to footprintOf, which names it.
      if (r.sonar < dataset.ring.size()) {
        const Position sensor = robot.compose(dataset.ring.sonars[r.sonar].pose).position;
        if ((sensor - centre).norm() > reach) continue;
      }
      const Footprint fp = mapper.footprintOf(robot, r);
      const CellEvidence* hit = nullptr;
      for (const CellEvidence& c : fp.cells)
        if (c.cell == target) hit = &c;
      if (!hit) continue;
      // The whole footprint's totals, as the mapper gives them to a rule that needs them.
      FootprintTotals totals;
      if (rule.needsTotals()) totals.occupied = occupiedFixedPoint(fp);
      part.clear();
      part.cells.push_back(*hit);
      part.cells.back().cell = 0;
      rule.applyPart(part, totals, state);

      CellTraceStep step;
      step.reading = index;
      step.scan = s;
      step.sonar = r.sonar;
      step.time = r.time;
      step.range = r.range;
      step.empty = hit->empty;
      step.occupied = hit->occupied;
      step.probability = hit->probability;
      step.after = valueOf(rule, state);
      trace.steps.push_back(step);
    }
  }
  return trace;
}

}  // namespace sg
