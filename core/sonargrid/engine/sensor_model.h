// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// An inverse sensor model turns one sonar reading into per-cell evidence (a Footprint). It knows
// nothing of how the grid stores or combines values: that is the UpdateRule's job.

#include <memory>
#include <string>
#include <vector>

#include "sonargrid/engine/beam_tables.h"
#include "sonargrid/engine/footprint.h"
#include "sonargrid/engine/grid_spec.h"
#include "sonargrid/params/parameters.h"

namespace sg {

class Grid;
class UpdateRule;

struct ModelInfo {
  std::string name;    // registry and CLI name, e.g. "hpf"
  std::string title;   // e.g. "Moravec–Elfes heuristic probability functions (HPF)"
  std::string source;  // paper and section
  std::vector<ParameterSpec> parameters;
  // The update rule the model's paper pairs it with; the app switches to it with the model (the
  // user may then choose another).
  std::string preferredRule;
  // The model's own names for its regions (paper 002 §3.1 Figure 1 names Murphy's I, II, III),
  // which the beam view labels: `occupied` where the reading raises P(occ), `empty` where it
  // lowers it, and `beyond` past the reading where the model writes nothing ("" when the model
  // does not name that part; the view then says "no update").
  struct Regions {
    std::string occupied;
    std::string empty;
    std::string beyond;
  } regions;
};

// Where a point falls for a reading (paper 002 §3.1, Figure 1).
enum class BeamRegion { Outside, Occupied /* Region I */, Empty /* Region II */ };

// The model's value at one point, as a Footprint cell carries it.
struct ModelValue {
  BeamRegion region = BeamRegion::Outside;
  double empty = 0.0;
  double occupied = 0.0;
  double probability = 0.5;
};

class SensorModel {
 public:
  virtual ~SensorModel() = default;

  virtual const ModelInfo& info() const = 0;
  // Reads this model's parameters from `params` (which may hold others too).
  virtual void configure(const ParameterSet& params) = 0;

  // The value at distance `delta` (m) from the sensor and `theta` (rad) off its acoustic axis, for
  // a reading of `range` metres (Reading::kNoEcho for none) from a transducer of `maxRange`.
  virtual ModelValue evaluate(double delta, double theta, double range, double maxRange) const = 0;

  // How far from the sensor this model may write for a transducer of `maxRange` (sizes tables).
  virtual double reach(double maxRange) const = 0;

  // Appends every cell the reading updates to `out`, in a fixed order, each cell at most once.
  virtual void footprint(const Beam& beam, const GridSpec& grid, const BeamTables& tables,
                         Footprint& out) const = 0;
  // The cells of footprint() that lie in the grid rows of `window`, in the same order. This default
  // computes the whole footprint and keeps those rows; the cone models rasterise only the window.
  virtual void footprintRows(const Beam& beam, const GridSpec& grid, const BeamTables& tables,
                             RowWindow window, Footprint& out) const;
  // Whether footprintRows() rasterises only the window's rows, so that it costs about the window's
  // share of footprint() (the cone models; the default above computes the whole footprint and
  // filters it). The mapper splits a batch between threads by bands of rows for such a model.
  virtual bool rasterisesRows() const { return false; }
  // For a model whose every reading gives its cells one of two values (HIMM's axis), the batch
  // path without footprints: listDirect() appends the cells of beams[0, count) to `out`
  // (DirectCells, footprint.h), on any thread; applyDirect() folds such a list into `grid` as
  // footprint() and `rule`.apply() would, one beam after another, to the same bits, and the caller
  // marks the list's cells written (Grid::markWritten, or Grid::markWrittenShared where several
  // threads mark; in any order: a mark is one value, so the lister may mark them ahead of the
  // fold). applyDirect() returns false, having done nothing, when the model has no such path for
  // the rule, and listDirect() when the model has none at all (these defaults): the mapper then
  // goes through footprints. With several threads the mapper lists the next readings' cells on one
  // while another folds the earlier ones in, in order (Mapper::integrateDirect).
  virtual bool listDirect(const Beam* /*beams*/, std::size_t /*count*/, const GridSpec& /*grid*/,
                          DirectCells& /*out*/) const {
    return false;
  }
  virtual bool applyDirect(const DirectCells& /*cells*/, const UpdateRule& /*rule*/,
                           Grid& /*grid*/) const {
    return false;
  }
  // The two fused, each cell folded in and marked written as it is traced (the mapper's path on
  // one thread, where a list only costs; unlike applyDirect(), this one marks): false, having done
  // nothing, where the model has no such path for the rule (this default; HIMM's axis has one for
  // a one-byte rule), and then the mapper lists and folds.
  virtual bool integrateDirect(const Beam* /*beams*/, std::size_t /*count*/,
                               const UpdateRule& /*rule*/, Grid& /*grid*/) const {
    return false;
  }
  // The cells of footprintRows(), with the same values, appended to `out` as runs of consecutive
  // cells (footprint.h), without a Footprint in between. Returns false, leaving `out` as it was,
  // for a model that cannot (the default; HIMM): the caller then uses footprintRows().
  virtual bool evidenceRuns(const Beam& /*beam*/, const GridSpec& /*grid*/,
                            const BeamTables& /*tables*/, RowWindow /*window*/,
                            EvidenceRuns& /*out*/) const {
    return false;
  }
};

// The registry: one place that knows every model.
std::vector<std::string> sensorModelNames();
std::unique_ptr<SensorModel> makeSensorModel(const std::string& name);  // nullptr when unknown
const ModelInfo& sensorModelInfo(const std::string& name);              // throws when unknown

// What a user should expect of the model's maps where they look poor by design, in one line (the
// parameter panel shows it under the choosers; docs/models.md says the same), or "" for a model
// without such a caveat. Measured on the bundled logs (issue 49): Murphy's model as printed fills
// the room with occupied wedges, and the cone models draw echoes of multipath as arcs beyond the
// walls.
std::string sensorModelCaveat(const std::string& name);

}  // namespace sg
