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
#include "sonargrid/engine/mapper.h"
#include "sonargrid/io/log_options.h"
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

// What a parameter sweep run from the app maps (the sweep view, docs/user-guide.md "Sweeping
// parameters"; the grammar of `sonargrid-cli sweep`, docs/sweeps.md): one model × rule over the
// `axes` (--grid texts, first outermost), `ties` (--tie texts) and `metrics` (--metric names), each
// set starting from `base`, judged with the second log as the second run when `useSecondRun` is
// set. The defaults are paper 002 Table 1's grid (`parameterGrid` names it) measured by VSDNS.
struct SweepPlan {
  std::string model = "parameterized";
  std::string rule = "bayes-recursive";
  PoseSource pose = PoseSource::Odometry;
  std::string parameterGrid = "paper002-table1";  // the preset the axes started from
  std::map<std::string, double> base;             // values other than the grid's own
  bool useSecondRun = true;
  // Paper 002 Table 1: P2, 2·P3 (P3 in metres), P4, P5 (footnote **) and P1 = 1 − P4 (footnote *).
  std::vector<std::string> axes{"p2=0.05:0.05:0.2", "p3=0.25:0.25:1.5", "p4=0.95:0.01:0.98",
                                "p5=6,7,8,10,13,14,15,16,17,18,20,25,27,35,40"};
  std::vector<std::string> ties{"p1=1-p4"};
  std::vector<std::string> metrics{"vsdns"};
};

// How the log was read, beyond what its file says: a CSV log's columns and poses file, the ring of
// a log without geometry, a ROS bag's topics (LogOptions without its progress and cancel hooks). A
// project reopens its log with these, so that a CSV log or a bag read with chosen topics opens as
// it was mapped.
struct LogReading {
  LogFormat format = LogFormat::Auto;
  bool lenient = false;
  std::optional<SonarRing> ring;
  std::optional<CsvLayout> csv;
  QString posesPath;  // absolute
  BagTopics topics;
  // The robot's pose at the first scan in the reference's frame (LogOptions::startPose).
  std::optional<Pose2D> startPose;
  bool operator==(const LogReading&) const = default;
};

inline LogReading readingOf(const LogOptions& o) {
  return {o.format, o.lenient,  o.ring, o.csv, QString::fromStdString(o.posesPath),
          o.topics, o.startPose};
}

inline LogOptions optionsOf(const LogReading& r) {
  LogOptions o;
  o.format = r.format;
  o.lenient = r.lenient;
  o.ring = r.ring;
  o.csv = r.csv;
  o.posesPath = r.posesPath.toStdString();
  o.topics = r.topics;
  o.startPose = r.startPose;
  return o;
}

struct ProjectState {
  QString logPath;        // absolute; empty when no log is open
  LogReading logReading;  // how it was read
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
  return a.label == b.label && a.settings == b.settings && a.cellSize == b.cellSize;
}

inline bool operator==(const SweepPlan& a, const SweepPlan& b) {
  return a.model == b.model && a.rule == b.rule && a.pose == b.pose &&
         a.parameterGrid == b.parameterGrid && a.base == b.base &&
         a.useSecondRun == b.useSecondRun && a.axes == b.axes && a.ties == b.ties &&
         a.metrics == b.metrics;
}

// MapperSettings::operator==, under the name the project tests use.
inline bool sameSettings(const MapperSettings& a, const MapperSettings& b) {
  return a == b;
}

}  // namespace sg::app
