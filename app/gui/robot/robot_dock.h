// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The Robot menu and dock (docs/live-robot.md, "In the app"): connect to a robot over TCP or a
// serial port, or start the virtual robot in one click; teleoperate with the arrow keys or let it
// wander; record to .sglog; and the link's status. The work is the RobotSession's; this is its
// face, wired to the window's public API (remap controller, timeline, grid view, settings).

#include <QDockWidget>

#include "robot/virtual_robot_host.h"

class QAction;
class QCheckBox;
class QComboBox;
class QLabel;
class QLineEdit;
class QMenu;
class QPushButton;
class QScrollArea;
class QSpinBox;
class QStackedWidget;

namespace sg::app {

class MainWindow;
class RobotSession;
class TeleopKeys;

class RobotDock : public QDockWidget {
  Q_OBJECT

 public:
  explicit RobotDock(MainWindow* window);
  ~RobotDock() override;

  RobotSession* session() const { return session_; }
  TeleopKeys* teleop() const { return teleop_; }
  QMenu* menu() const { return menu_; }
  QAction* connectAction() const { return connectAction_; }
  QAction* virtualRobotAction() const { return virtualAction_; }
  QAction* disconnectAction() const { return disconnectAction_; }
  QAction* teleopAction() const { return teleopAction_; }
  QAction* wanderAction() const { return wanderAction_; }
  QAction* recordAction() const { return recordAction_; }

  // Connects to what the dock's fields say (TCP host and port, or serial port and baud).
  void connectFromFields();
  // The virtual robot the dock's fields choose (world, robot, route), in real time.
  VirtualRobotHost::Options virtualRobotOptions() const;
  // Starts it and connects to it; its world becomes the window's reference map unless the window
  // has one. False after saying why.
  bool startVirtualRobot(const VirtualRobotHost::Options& options);
  // Starts recording to `path` (no dialog); false after saying why.
  bool recordTo(const QString& path);
  // The world files offered for the virtual robot (the bundled datasets' world.json).
  QStringList worlds() const;
  void setWorld(const QString& path);

 protected:
  void showEvent(QShowEvent* event) override;

 private:
  void buildActions();
  void buildWidgets();
  // Before a session maps: the window's log gives way to the live map, and the window's
  // settings and cell size are the map's.
  void prepareWindow();
  void refreshSerialPorts();
  void showStatus();
  void updateActions();
  void chooseRecording();
  void say(const QString& text);

  MainWindow* window_;
  RobotSession* session_;
  TeleopKeys* teleop_;
  QMenu* menu_ = nullptr;
  QAction* connectAction_ = nullptr;
  QAction* disconnectAction_ = nullptr;
  QAction* virtualAction_ = nullptr;
  QAction* stopVirtualAction_ = nullptr;
  QAction* teleopAction_ = nullptr;
  QAction* wanderAction_ = nullptr;
  QAction* recordAction_ = nullptr;
  QAction* stopRecordAction_ = nullptr;
  QAction* newMapAction_ = nullptr;

  QComboBox* kind_ = nullptr;  // TCP or serial
  QStackedWidget* kindPages_ = nullptr;
  QLineEdit* host_ = nullptr;
  QSpinBox* port_ = nullptr;
  QComboBox* serialPort_ = nullptr;
  QComboBox* baud_ = nullptr;
  QComboBox* readAs_ = nullptr;  // from the robot's subclass, or a preset
  QComboBox* world_ = nullptr;
  QComboBox* virtualRobot_ = nullptr;
  QComboBox* route_ = nullptr;
  QLabel* state_ = nullptr;
  QLabel* stats_ = nullptr;
  QLabel* recording_ = nullptr;
  QLabel* lastMessage_ = nullptr;
  QScrollArea* scroll_ = nullptr;
};

// Creates the Robot menu (before Settings and Help) and the Robot dock of `window`.
RobotDock* installRobotMenu(MainWindow* window);

}  // namespace sg::app
