#pragma once
// Mapper = SensorModel × UpdateRule × parameters × GridSpec (DESIGN.md, "Data flow"). Batch mapping
// (a whole log, or up to time t) is incremental mapping run over the scans in order, so both give
// bit-identical grids, and the result depends on nothing but the inputs.

#include <atomic>
#include <cstdint>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "sonargrid/beam_tables.h"
#include "sonargrid/dataset.h"
#include "sonargrid/footprint.h"
#include "sonargrid/models/sensor_model.h"
#include "sonargrid/occupancy_map.h"
#include "sonargrid/parameters.h"
#include "sonargrid/rules/update_rule.h"

namespace sg {

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
};

// Every parameter the model and the rule declare, at its default. Throws MapperError on an unknown
// model or rule name.
ParameterSet defaultParameters(const std::string& model, const std::string& rule);

class Mapper {
 public:
  // Throws MapperError for an unknown model or rule, an incompatible pair (with the reason), or an
  // empty grid.
  Mapper(const SonarRing& ring, const GridSpec& grid, const MapperSettings& settings);

  const GridSpec& grid() const { return grid_; }
  const MapperSettings& settings() const { return settings_; }
  const SensorModel& model() const { return *model_; }
  const UpdateRule& rule() const { return *rule_; }

  // Forgets every reading.
  void reset();

  // Incremental mapping: folds in one scan's readings whose time is at most `until`. Throws
  // MapperError when a reading names a sonar the ring does not have.
  void integrate(const Scan& scan, double until = std::numeric_limits<double>::infinity());

  // Batch mapping: resets, then integrates every scan (readings up to `until`). Checks `cancel`
  // every few hundred readings; returns false when it was cancelled (the grid is then unfinished:
  // map again or reset before using it). A large log is mapped on the thread policy's threads
  // (concurrency.h), in stripes of grid rows (or, with an observer, footprints computed ahead and
  // applied in log order); every cell still sees the readings in log order, so the result is
  // bit-identical to integrate() scan by scan for any number of threads. An error on any thread
  // (or a thread that cannot be started) is thrown here once every thread has stopped.
  bool mapDataset(const Dataset& dataset, double until = std::numeric_limits<double>::infinity(),
                  const std::atomic<bool>* cancel = nullptr);

  std::size_t readingsIntegrated() const { return readings_; }

  // Optional; not owned. Reset with the mapper and fed every footprint after the rule applies it.
  void setObserver(FootprintObserver* observer);
  OccupancyMap snapshot() const;

  // The cells one reading writes, as the model gives them (for the beam view and tests).
  Footprint footprintOf(const Pose2D& robot, const Reading& reading) const;

 private:
  Beam beamOf(const Pose2D& robot, const Reading& reading) const;
  void applyFootprint(const Footprint& footprint);
  void markObserved(const Footprint& footprint);
  bool integrateBeams(const std::vector<Beam>& beams, const std::atomic<bool>* cancel);
  bool integrateStripes(const std::vector<Beam>& beams, const std::atomic<bool>* cancel,
                        unsigned threads);

  SonarRing ring_;
  GridSpec grid_;
  MapperSettings settings_;
  std::unique_ptr<SensorModel> model_;
  std::unique_ptr<UpdateRule> rule_;
  std::shared_ptr<const BeamTables> tables_;
  std::vector<std::uint8_t> observed_;
  Footprint scratch_;
  FootprintObserver* observer_ = nullptr;
  std::size_t readings_ = 0;
};

}  // namespace sg
