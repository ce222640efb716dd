// SPDX-License-Identifier: GPL-3.0-or-later
#include "start_pose_picker.h"

#include <QAction>
#include <QMenu>
#include <QStatusBar>

#include "document.h"
#include "grid_view.h"
#include "sonargrid/io/start_pose.h"
#include "start_pose_tool.h"

namespace sg::app {

StartPosePicker::StartPosePicker(Document* document, ui::GridView* view, QMenu* menu,
                                 QStatusBar* bar, QObject* parent)
    : QObject(parent),
      document_(document),
      view_(view),
      bar_(bar),
      tool_(new ui::StartPoseTool(this)),
      place_(new QAction(tr("Place &Start Pose"), this)),
      clear_(new QAction(tr("C&lear Start Pose"), this)) {
  place_->setObjectName(QStringLiteral("placeStartPoseAction"));
  place_->setCheckable(true);
  place_->setShortcut(QKeySequence(tr("Ctrl+Shift+L")));
  place_->setToolTip(
      tr("Press where the robot stood at the log's first scan and drag towards where it faced: "
         "the odometry is moved there, into the reference's frame (undoable)"));
  clear_->setObjectName(QStringLiteral("clearStartPoseAction"));
  clear_->setToolTip(tr("Map the odometry as logged (undoable)"));
  menu->addAction(place_);
  menu->addAction(clear_);
  menu->setToolTipsVisible(true);

  connect(place_, &QAction::toggled, this, &StartPosePicker::setPicking);
  connect(clear_, &QAction::triggered, this, [this] { document_->setStartPose(std::nullopt); });
  connect(tool_, &ui::StartPoseTool::picked, this, [this](const Pose2D& pose) {
    place_->setChecked(false);  // gives the view its tool back
    document_->setStartPose(pose);
  });
  connect(tool_, &ui::StartPoseTool::cancelled, this, [this] { place_->setChecked(false); });
  connect(document_, &Document::logChanged, this, &StartPosePicker::updateActions);
  connect(document_, &Document::startPoseChanged, this, [this] {
    const std::optional<Pose2D>& p = document_->startPose();
    bar_->showMessage(p ? tr("Start pose %1 m, %2 m, %3°: the odometry starts there")
                              .arg(p->x(), 0, 'f', 3)
                              .arg(p->y(), 0, 'f', 3)
                              .arg(radToDeg(p->heading), 0, 'f', 1)
                        : tr("Start pose cleared: the odometry is mapped as logged"),
                      10000);
  });
  updateActions();
}

void StartPosePicker::setPicking(bool on) {
  if (on == (view_->tool() == tool_)) return;
  if (on) {
    previousTool_ = view_->tool();
    // A click keeps the heading the robot has now; a drag sets a new one.
    const auto& data = document_->dataset();
    tool_->setHeading(data && !data->scans.empty() ? data->scans.front().odometry.heading : 0.0);
    view_->setTool(tool_);
    view_->setFocus();
    bar_->showMessage(
        tr("Press where the robot stood at the first scan and drag towards where "
           "it faced; Esc cancels"));
  } else {
    view_->setTool(previousTool_);
    previousTool_ = nullptr;
    bar_->clearMessage();
  }
  const QSignalBlocker block(place_);
  place_->setChecked(on);
}

void StartPosePicker::updateActions() {
  // A live robot's log grows as it streams: it is not placed (Document::setStartPose).
  const auto& source = document_->source();
  const bool loaded = source && source->complete();
  place_->setEnabled(loaded);
  clear_->setEnabled(loaded && document_->startPose().has_value());
  if (!loaded) setPicking(false);
}

}  // namespace sg::app
