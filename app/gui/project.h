// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What a project holds (docs/formats.md, "Project file"): every part of the Document that a
// `.sgproj` file saves, as plain values with no widgets, so that the file's reader and writer
// (project_file.h) and the Document share one description and a test can compare them field by
// field.

#include <QString>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "grid_image.h"
#include "sonargrid/mapper.h"
#include "sonargrid/reference/reference_map.h"

namespace sg::app {

inline constexpr double kMinCellSize = 0.005;  // metres; the same bounds as `sonargrid --cell`
inline constexpr double kMaxCellSize = 1.0;
inline constexpr double kDefaultCellSize = 0.05;

// A configuration the user pinned for the comparison table: the map it names is rebuilt from
// these, so they are all a row needs.
struct PinnedRow {
  QString label;
  MapperSettings settings;
  double cellSize = kDefaultCellSize;
};

// What a parameter sweep run from the app maps (core/sonargrid/sweep/parameter_sweep.h): one model
// × rule over a named parameter grid, each set starting from `base`, judged with the second log as
// the second run when `useSecondRun` is set.
struct SweepPlan {
  std::string model = "parameterized";
  std::string rule = "bayes-recursive";
  PoseSource pose = PoseSource::Odometry;
  std::string parameterGrid = "paper002-table1";  // the only grid today: paper 002 Table 1
  std::map<std::string, double> base;             // values other than the grid's own
  bool useSecondRun = true;
};

struct ProjectState {
  QString logPath;        // absolute; empty when no log is open
  QString secondLogPath;  // the second run of the same route (two-run comparison), if any
  std::optional<ReferenceMap> reference;
  QString referencePath;           // the file it came from or was saved to; may be empty
  bool referenceModified = false;  // edits since it was read or saved: the project holds it inline
  MapperSettings settings;
  double cellSize = kDefaultCellSize;
  ui::Overlays overlays = ui::kAllOverlays;
  std::optional<ui::ViewTransform> view;  // none: fit the map
  std::vector<PinnedRow> pinnedRows;
  SweepPlan sweep;
};

inline bool operator==(const PinnedRow& a, const PinnedRow& b) {
  return a.label == b.label && a.settings.model == b.settings.model &&
         a.settings.rule == b.settings.rule && a.settings.pose == b.settings.pose &&
         a.settings.parameters == b.settings.parameters && a.cellSize == b.cellSize;
}

inline bool operator==(const SweepPlan& a, const SweepPlan& b) {
  return a.model == b.model && a.rule == b.rule && a.pose == b.pose &&
         a.parameterGrid == b.parameterGrid && a.base == b.base && a.useSecondRun == b.useSecondRun;
}

inline bool sameSettings(const MapperSettings& a, const MapperSettings& b) {
  return a.model == b.model && a.rule == b.rule && a.pose == b.pose && a.parameters == b.parameters;
}

}  // namespace sg::app
