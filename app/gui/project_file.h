// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The project file `.sgproj` (docs/formats.md, "Project file"): JSON holding a ProjectState. No
// widgets here, so a test round-trips every field without a window.

#include <QByteArray>
#include <QString>
#include <QStringList>
#include <stdexcept>

#include "project.h"

namespace sg::app {

inline constexpr const char* kProjectFormat = "sonargrid-project";
inline constexpr int kProjectVersion = 1;
inline constexpr const char* kProjectSuffix = "sgproj";

// A project that cannot be read. what() names the file, the line for a JSON syntax error, and the
// field, e.g. "a.sgproj: mapping.parameters.epsilon: 7 is outside [0.005, 1]".
class ProjectError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class ProjectPaths {
  RelativeToFile,  // a saved project: it still opens when its folder moves along with the logs
  Absolute,        // an autosave, kept far from the logs it names
};

// The file text for `state` saved as `projectPath` (relative paths are taken from its folder).
// A reference with unsaved edits, or without a file, is written inline as reference JSON; one
// that JSON cannot hold (an obstacle raster from a ROS map) is named by its path only.
QByteArray projectJson(const ProjectState& state, const QString& projectPath,
                       ProjectPaths paths = ProjectPaths::RelativeToFile);

// Reads the text of `projectPath` (relative paths resolved against its folder). A reference named
// by path is read from that file. Throws ProjectError for a file it cannot read. Sweep settings
// that no longer apply to the sweep's model and rule (an axis, tie or base value of a parameter
// they do not declare or a value out of its range, an unknown metric) are left out, not refused:
// `dropped`, when given, receives one line for each, naming its field, its text and the reason.
ProjectState parseProject(const QByteArray& text, const QString& projectPath,
                          QStringList* dropped = nullptr);
ProjectState readProject(const QString& projectPath, QStringList* dropped = nullptr);

// Leaves out of `plan` what does not apply to its model and rule (as parseProject() does) and
// returns one line for each part left out. A project stores only what applies, so that it always
// reopens.
QStringList keepApplicable(SweepPlan& plan);

// Atomic (core/sonargrid/base/atomic_file.h). Throws ProjectError naming the path and the reason.
void writeProject(const ProjectState& state, const QString& projectPath,
                  ProjectPaths paths = ProjectPaths::RelativeToFile);

}  // namespace sg::app
