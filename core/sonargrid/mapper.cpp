#include "sonargrid/mapper.h"

namespace sg {

ParameterSet defaultParameters(const std::string& model, const std::string& rule) {
  try {
    ParameterSet p(sensorModelInfo(model).parameters);
    p.append(ParameterSet(updateRuleInfo(rule).parameters));
    return p;
  } catch (const std::invalid_argument& e) {
    throw MapperError(e.what());
  }
}

Mapper::Mapper(const SonarRing& ring, const GridSpec& grid, const MapperSettings& settings)
    : ring_(ring), grid_(grid), settings_(settings) {
  model_ = makeSensorModel(settings.model);
  if (!model_) throw MapperError("unknown sensor model '" + settings.model + "'");
  rule_ = makeUpdateRule(settings.rule);
  if (!rule_) throw MapperError("unknown update rule '" + settings.rule + "'");
  const Compatibility c = compatibility(settings.model, settings.rule);
  if (!c.allowed) {
    throw MapperError("model '" + settings.model + "' cannot be used with rule '" + settings.rule + "': " + c.reason);
  }
  if (grid_.width <= 0 || grid_.height <= 0 || !(grid_.cellSize > 0.0)) throw MapperError("the grid is empty");
  // Parameters the caller did not give stay at their defaults.
  ParameterSet params = defaultParameters(settings.model, settings.rule);
  for (const auto& [name, value] : settings.parameters.values()) {
    if (params.has(name)) params.set(name, value);
  }
  settings_.parameters = params;
  model_->configure(params);
  rule_->configure(params);
  tables_ = BeamTables::shared(grid_.cellSize, model_->reach(ring_.maxRange));
  reset();
}

void Mapper::reset() {
  rule_->reset(grid_.cellCount());
  observed_.assign(grid_.cellCount(), 0);
  readings_ = 0;
  if (observer_) observer_->reset(grid_.cellCount());
}

void Mapper::setObserver(FootprintObserver* observer) {
  observer_ = observer;
  if (observer_) observer_->reset(grid_.cellCount());
}

Beam Mapper::beamOf(const Pose2D& robot, const Reading& reading) const {
  if (reading.sonar >= ring_.size()) {
    throw MapperError("reading names sonar " + std::to_string(reading.sonar) + " but the ring has " +
                      std::to_string(ring_.size()));
  }
  Beam beam;
  beam.sensor = robot.compose(ring_.sonars[reading.sonar].pose);
  // A range at or beyond the transducer's maximum is no echo (notes, Conventions).
  beam.range = reading.range < ring_.maxRange ? reading.range : Reading::kNoEcho;
  beam.maxRange = ring_.maxRange;
  return beam;
}

Footprint Mapper::footprintOf(const Pose2D& robot, const Reading& reading) const {
  Footprint fp;
  model_->footprint(beamOf(robot, reading), grid_, *tables_, fp);
  return fp;
}

void Mapper::integrate(const Scan& scan, double until) {
  const Pose2D& robot = settings_.pose == PoseSource::Truth && scan.truth ? *scan.truth : scan.odometry;
  for (const Reading& r : scan.readings) {
    if (r.time > until) continue;
    scratch_.clear();
    model_->footprint(beamOf(robot, r), grid_, *tables_, scratch_);
    rule_->apply(scratch_);
    if (observer_) observer_->observe(scratch_);
    for (const CellEvidence& c : scratch_.cells) observed_[c.cell] = 1;
    ++readings_;
  }
}

bool Mapper::mapDataset(const Dataset& dataset, double until, const std::atomic<bool>* cancel) {
  if (settings_.pose == PoseSource::Truth && !dataset.hasTruth()) {
    throw MapperError("the log has no true pose for every scan; map with odometry (--pose odom)");
  }
  reset();
  for (const Scan& scan : dataset.scans) {
    if (cancel && cancel->load(std::memory_order_relaxed)) return false;
    integrate(scan, until);
  }
  return true;
}

OccupancyMap Mapper::snapshot() const {
  OccupancyMap m;
  m.spec = grid_;
  m.model = settings_.model;
  m.rule = settings_.rule;
  const std::size_t n = grid_.cellCount();
  m.probability.resize(n);
  m.native.resize(n);
  m.level.resize(n);
  m.filled.resize(n);
  m.observed = observed_;
  for (std::size_t i = 0; i < n; ++i) {
    m.probability[i] = rule_->occupancy(i);
    m.native[i] = rule_->native(i);
    m.level[i] = rule_->level(i);
    m.filled[i] = rule_->filled(i) ? 1 : 0;
  }
  return m;
}

}  // namespace sg
