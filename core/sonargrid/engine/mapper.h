// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Mapper = SensorModel × UpdateRule × parameters × Grid (DESIGN.md, "Data flow"). Batch mapping
// (a whole log, or up to time t) is incremental mapping run over the scans in order, so both give
// bit-identical grids, and the result depends on nothing but the inputs. Streaming (append())
// grows the grid before each batch of scans so that no footprint is cut by its edge; the map is
// then bit-identical to a batch map of the same scans on the grown grid (docs/models.md, "Batch,
// incremental and live mapping").

#include <atomic>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "sonargrid/data/dataset.h"
#include "sonargrid/engine/beam_tables.h"
#include "sonargrid/engine/footprint.h"
#include "sonargrid/engine/grid.h"
#include "sonargrid/engine/occupancy_map.h"
#include "sonargrid/engine/sensor_model.h"
#include "sonargrid/engine/update_rule.h"
#include "sonargrid/params/parameters.h"

namespace sg {

// The farthest a sonar may reach, in cells (the cone tables' radius): 10 m at 5 mm cells, whose
// 16 tables of (2r + 1)² entries take some 2 GiB.
inline constexpr double kMaxReachCells = 2048;

// The readings a batch of a rule with totals (normalising addition) takes at a time on several
// threads (Mapper::integrateBeams): what they keep for their totals is some 500 bytes a reading on
// the 100k workload, 8 MB for a chunk, where the whole of a million-reading log would keep 0.5 GB;
// and a chunk's two passes start its threads twice, some 0.1 ms.
inline constexpr std::size_t kTotalsChunk = 16384;

class MapperError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Sees every reading's footprint, in reading order, as the rule applies it: how per-cell statistics
// of the model's outputs (VSDNS, paper 002 §5) are streamed without storing them.
class FootprintObserver {
 public:
  virtual ~FootprintObserver() = default;
  virtual void reset(std::size_t cells) = 0;
  virtual void observe(const Footprint& footprint) = 0;
};

// Model, rule and their parameters: what a user picks.
struct MapperSettings {
  std::string model = "hpf";
  std::string rule = "addition";
  ParameterSet parameters;  // the model's and the rule's, by name; see defaultParameters()
  PoseSource pose = PoseSource::Odometry;
  // The engine's arithmetic (update_rule.h): the exact engine, the oracle every rule was written
  // in, by default.
  Precision precision = Precision::Exact;

  // The same model, rule, parameter values, pose source and precision: the same map of the same
  // log.
  bool operator==(const MapperSettings&) const = default;
};

// Every parameter the model and the rule declare, at its default. Throws MapperError on an unknown
// model or rule name.
ParameterSet defaultParameters(const std::string& model, const std::string& rule);

// The map of `grid` as `rule` (the rule the grid was made for, configured for good) reads it, named
// by the model and rule: what Mapper::snapshot() gives. Its levels and observed flags are computed
// (on the thread policy's threads for a large grid); its other layers are read from the grid's cell
// values, which the map shares (Grid::sharedCells()) and keeps alive with the rule.
OccupancyMap occupancyMapOf(const Grid& grid, std::shared_ptr<const UpdateRule> rule,
                            const std::string& model, const std::string& ruleName);

class Mapper {
 public:
  // Throws MapperError for an unknown model or rule, an incompatible pair (with the reason), or an
  // empty grid.
  Mapper(const SonarRing& ring, const GridSpec& grid, const MapperSettings& settings);

  // The grid's limits now (append() and reserve() may have grown them) and its storage.
  const GridSpec& grid() const { return grid_.spec(); }
  const Grid& storage() const { return grid_; }
  const MapperSettings& settings() const { return settings_; }
  const SensorModel& model() const { return *model_; }
  const UpdateRule& rule() const { return *rule_; }

  // Forgets every reading (the grid keeps its present limits).
  void reset();

  // Incremental mapping: folds in one scan's readings whose time is at most `until`. Throws
  // MapperError when a reading names a sonar the ring does not have.
  void integrate(const Scan& scan, double until = std::numeric_limits<double>::infinity());

  // Batch mapping: resets, then integrates every scan (readings up to `until`); with
  // PoseSource::Truth, every scan that has a true pose (the others are left out, and a log without
  // any is a MapperError: data/scan_poses.h). Checks `cancel`
  // every few hundred readings; returns false when it was cancelled (the grid is then unfinished:
  // map again or reset before using it). A large log is mapped on the thread policy's threads
  // (concurrency.h), each thread with its own grid rows (row_bands.h; HIMM's axis: chunks of
  // readings whose cells any thread lists and one folds in, in log order; with an observer,
  // footprints computed ahead and applied in log order); every cell still sees the readings in
  // log order, so the result is bit-identical to integrate() scan by scan for any number of
  // threads. An error on any thread (or a thread that cannot be started) is thrown here once
  // every thread has stopped.
  bool mapDataset(const Dataset& dataset, double until = std::numeric_limits<double>::infinity(),
                  const std::atomic<bool>* cancel = nullptr);

  // Streaming: first grows the grid until it holds the whole footprint of every reading of `scans`
  // up to `until` (the model's reach around each sensor), then integrates them in order, on several
  // threads for a large batch as mapDataset() does. Appending a log's scans in any number of
  // batches gives, bit for bit, what mapDataset() of all of them gives on the grid's final limits.
  // With PoseSource::Truth a scan without a true pose is left out, as mapDataset() leaves it out
  // (data/scan_poses.h). Returns false when `cancel` stopped it part-way (then map again or reset).
  // Throws MapperError for a reading naming a sonar the ring does not have, a grid that would pass
  // kMaxGridCells, or an observer when the grid must grow (it counts cells of the old limits).
  bool append(std::span<const Scan> scans, double until = std::numeric_limits<double>::infinity(),
              const std::atomic<bool>* cancel = nullptr);
  // Grows the grid, if it must, to cover the world box [lo, hi] (as append() grows it). Returns
  // whether the limits changed. Throws MapperError as append() does.
  bool reserve(const Position& lo, const Position& hi);

  std::size_t readingsIntegrated() const { return readings_; }

  // Optional; not owned. Reset with the mapper and fed every footprint after the rule applies it.
  void setObserver(FootprintObserver* observer);
  // The map as it is now. It shares the grid's cell values; mapping more copies any the snapshot
  // still holds before writing them, so the snapshot never changes (Grid::sharedCells()).
  OccupancyMap snapshot() const;
  // A snapshot the mapper keeps and brings up to date: only the rows written since the previous
  // call are computed again (every row after reset() or growth, and on the first call), so a live
  // map's refresh costs the rows that changed. Bit-identical to snapshot(). `rewritten`, when
  // given, receives the rows it rewrote as one band (every row between the first and the last).
  // The reference is valid until the next call or the mapper's end, and its derived layers
  // (OccupancyMap::derive) until the mapper next maps or resets: keep a copy, as a view does.
  const OccupancyMap& liveMap(RowBand* rewritten = nullptr);

  // The cells one reading writes, as the model gives them (for the beam view and tests).
  Footprint footprintOf(const Pose2D& robot, const Reading& reading) const;

 private:
  // `rotation` is robot.rotation(), computed once a scan for its readings.
  Beam beamOf(const Pose2D& robot, const Eigen::Matrix2d& rotation, const Reading& reading) const;
  void applyFootprint(const Footprint& footprint);
  // The rule's applyRuns() (its deferred runs to `deferred`), and the runs' cells marked observed.
  // Several threads may apply runs in disjoint rows at once.
  void applyRuns(const EvidenceRuns& runs, EvidenceRuns* deferred);
  void markObserved(const Footprint& footprint) { grid_.markWritten(footprint); }
  bool grow(const Position& lo, const Position& hi);
  bool integrateBeams(const std::vector<Beam>& beams, const std::atomic<bool>* cancel);
  bool integrateBands(const std::vector<Beam>& beams, const std::atomic<bool>* cancel,
                      unsigned threads);
  bool integrateDirect(const std::vector<Beam>& beams, const std::atomic<bool>* cancel,
                       unsigned threads);
  // Before the cells are written: liveMap()'s own map lets go of the grid's cells, and the grid
  // copies the planes that snapshots still share.
  void beginWriting();

  SonarRing ring_;
  MapperSettings settings_;
  std::unique_ptr<SensorModel> model_;
  std::shared_ptr<UpdateRule> rule_;  // shared with the snapshots, which read their layers by it
  Grid grid_;
  std::shared_ptr<const BeamTables> tables_;
  OccupancyMap live_;  // liveMap()'s, empty until it is first asked for
  Footprint scratch_;
  FootprintObserver* observer_ = nullptr;
  std::size_t readings_ = 0;
};

}  // namespace sg
