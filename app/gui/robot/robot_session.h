// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A live robot in the app (issue 13 item 5; docs/live-robot.md, "In the app"): a RobotLink to a
// robot, a simulator or the in-process virtual robot, its scans gathered into one live ScanSource
// and merged into the map on a coalescing timer, never per packet (DESIGN.md, "Threading"), the
// timeline and the robot overlay following them, teleoperation and wander, recording to .sglog and
// the link's status. The session owns no widget: the dock (robot_dock.h) shows and drives it, and
// tests drive it directly.
//
// The scans of every connection of a session go into one source, on one clock: a lost connection
// that the link restores, or a Disconnect followed by a Connect, continues the same map. The
// robot must stay the same (same ring); New Map starts over.

#include <QElapsedTimer>
#include <QObject>
#include <QPointer>
#include <QString>
#include <QTimer>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "robot/virtual_robot_host.h"
#include "sonargrid/arcos/client_session.h"
#include "sonargrid/data/dataset.h"
#include "sonargrid/engine/mapper.h"
#include "sonargrid/engine/scan_source.h"
#include "sonargrid/live/link_address.h"
#include "sonargrid/live/robot_link.h"

namespace sg {
class SglogRecorder;
}
namespace sg::live {
class Wander;
}
namespace sg::ui {
class GridView;
class RemapController;
class Timeline;
}  // namespace sg::ui

namespace sg::app {

class RobotSession : public QObject {
  Q_OBJECT

 public:
  enum class State { Idle, Connecting, Connected, Reconnecting };

  // Scans are mapped by `remap` (startLive, scansAppended); `timeline` and `view` follow them when
  // given. All must outlive the session.
  explicit RobotSession(ui::RemapController* remap, ui::Timeline* timeline = nullptr,
                        ui::GridView* view = nullptr, QObject* parent = nullptr);
  ~RobotSession() override;

  // What a new live map is mapped with (the window's settings and cell size when it starts).
  void setMapping(const MapperSettings& settings, double cellSize);
  // Asked for the settings when a live map starts, instead of those setMapping() gave: the
  // window's, which the user may change between connecting and the first scans.
  void setSettingsProvider(std::function<MapperSettings()> provider) {
    settingsProvider_ = std::move(provider);
  }
  // How often received scans are merged into the map (coalesced; tens of ms).
  void setMergeInterval(int ms) { mergeTimer_.setInterval(ms); }

  // Connects (and keeps reconnecting until disconnectLink()). `robot` reads the robot as that
  // preset instead of the one its subclass names.
  void connectTo(const live::LinkAddress& address,
                 std::optional<arcos::RobotParameters> robot = std::nullopt);
  // Closes the connection; the map and the scans stay (a later connectTo continues them).
  void disconnectLink();
  // Forgets the scans received: the next scan starts a new map. Stops a recording.
  void newMap();

  // Starts the virtual robot in its own thread and connects to it.
  bool startVirtualRobot(const VirtualRobotHost::Options& options, QString* error);
  // Disconnects from it and stops it.
  void stopVirtualRobot();
  const VirtualRobotHost& virtualRobot() const { return host_; }

  // Teleoperation: velocities (m/s, rad/s) sent to the robot now; ends wander.
  void drive(double metresPerSecond, double radiansPerSecond);
  // The sonar obstacle avoidance of `record --wander` drives the robot while on.
  void setWander(bool on);
  bool wandering() const { return wander_ != nullptr; }

  // Appends every scan received from now on to a streamed .sglog at `path`; false with `error`
  // when there is no robot yet or the file cannot be created.
  bool startRecording(const QString& path, QString* error);
  // Closes the log (its 'end' line): complete and loadable.
  void stopRecording();
  bool recording() const { return recorder_ != nullptr; }
  QString recordingPath() const;
  std::size_t recordedScans() const;

  State state() const { return state_; }
  QString stateText() const { return stateText_; }
  const live::RobotLink* link() const { return link_.get(); }
  // Packets per second over the last second.
  double packetsPerSecond() const { return packetsPerSecond_; }
  std::shared_ptr<const ScanSource> source() const { return source_; }
  // Scans and readings received this session (merged or waiting for the next merge).
  std::size_t scansReceived() const { return scansReceived_; }
  std::size_t readingsReceived() const { return readingsReceived_; }
  // Merges the scans waiting for the timer now.
  void mergeNow();
  // Whether the window's map is this session's (opening a log takes the map over).
  bool mapping() const { return attached(); }

 signals:
  void stateChanged(sg::app::RobotSession::State state, const QString& text);
  // The link's counters changed, or packets per second was measured again.
  void statsChanged();
  // A new live map (the first scans of a session arrived): what a metrics view follows.
  void sourceStarted(std::shared_ptr<const sg::ScanSource> source);
  // Scans were merged: the source now holds `scans`.
  void scansMerged(std::size_t scans);
  void recordingChanged(bool recording);
  void wanderChanged(bool on);
  // The window maps with the true pose, but the robot sends none: the live map uses odometry.
  void mappedWithOdometry();
  // Something the user should read (a failed connection, a recording that failed).
  void message(const QString& text);

 private:
  void onConnected(const QString& name, const QString& robotClass, const QString& subclass);
  void onScan(const Scan& scan);
  void onDisconnected(const QString& reason);
  void onTimeChanged(double t, std::size_t scan);
  void setState(State state, const QString& text);
  void measureRate();
  void showRobot(std::size_t scan);
  // The remap controller maps this session's source (a log opened since takes it over).
  bool attached() const;

  ui::RemapController* remap_;
  QPointer<ui::Timeline> timeline_;
  QPointer<ui::GridView> view_;
  MapperSettings settings_;
  std::function<MapperSettings()> settingsProvider_;
  double cellSize_ = 0.05;

  VirtualRobotHost host_;
  std::unique_ptr<live::RobotLink> link_;
  std::optional<arcos::RobotParameters> linkRobot_;  // the override the link was made with
  State state_ = State::Idle;
  QString stateText_;

  // The session's clock: a link's scan times are seconds since its open(); a new link starts
  // at the session's present time, so that the source's times only grow.
  QElapsedTimer clock_;
  double linkOffset_ = 0.0;
  std::shared_ptr<ScanSource> source_;
  std::vector<Scan> pending_;  // received, not merged yet
  QTimer mergeTimer_;
  Dataset shown_;         // the merged scans, for the robot and path overlay
  bool started_ = false;  // the source was handed to the remap controller
  std::size_t scansReceived_ = 0;
  std::size_t readingsReceived_ = 0;

  std::unique_ptr<live::Wander> wander_;
  std::unique_ptr<SglogRecorder> recorder_;
  QTimer syncTimer_;

  QTimer rateTimer_;
  QElapsedTimer rateClock_;
  std::uint64_t rateFrames_ = 0;
  double packetsPerSecond_ = 0.0;
};

}  // namespace sg::app
