// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Mapping ▸ Start Pose: where the robot stood at the log's first scan, in the reference's frame.
// "Place Start Pose" puts the start-pose tool on the grid view (press where the robot stood, drag
// towards where it faced); "Clear Start Pose" maps the odometry as logged again. Each change is
// one undo step of the Document, which places the odometry (Document::setStartPose).

#include <QObject>

class QAction;
class QMenu;
class QStatusBar;

namespace sg::ui {
class GridView;
class GridTool;
class StartPoseTool;
}  // namespace sg::ui

namespace sg::app {

class Document;

class StartPosePicker : public QObject {
  Q_OBJECT

 public:
  // Adds its actions to `menu`; says what to do, and what was placed, in `bar`.
  StartPosePicker(Document* document, ui::GridView* view, QMenu* menu, QStatusBar* bar,
                  QObject* parent = nullptr);

  QAction* placeAction() const { return place_; }
  QAction* clearAction() const { return clear_; }
  ui::StartPoseTool* tool() const { return tool_; }
  // Puts the tool on the view (on) or gives the view back its previous tool (off).
  void setPicking(bool on);

 private:
  void updateActions();

  Document* document_;
  ui::GridView* view_;
  QStatusBar* bar_;
  ui::StartPoseTool* tool_;
  ui::GridTool* previousTool_ = nullptr;
  QAction* place_;
  QAction* clear_;
};

}  // namespace sg::app
