// SPDX-License-Identifier: GPL-3.0-or-later
#include "robot/robot_session.h"

#include <QDir>
#include <algorithm>
#include <cmath>
#include <limits>

#include "grid_view.h"
#include "remap_controller.h"
#include "sonargrid/io/sglog_recorder.h"
#include "sonargrid/live/wander.h"
#include "timeline.h"

namespace sg::app {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Tens of milliseconds (DESIGN.md, "Threading"): a Pioneer's 10 SIPs a second join in pairs or
// threes, a fast simulator's in larger batches, and the map still moves smoothly.
constexpr int kMergeMs = 40;

QString fromStd(const std::string& s) {
  return QString::fromStdString(s);
}

}  // namespace

RobotSession::RobotSession(ui::RemapController* remap, ui::Timeline* timeline, ui::GridView* view,
                           QObject* parent)
    : QObject(parent), remap_(remap), timeline_(timeline), view_(view) {
  mergeTimer_.setSingleShot(true);
  mergeTimer_.setInterval(kMergeMs);
  connect(&mergeTimer_, &QTimer::timeout, this, &RobotSession::mergeNow);
  syncTimer_.setInterval(1000);
  connect(&syncTimer_, &QTimer::timeout, this, [this] {
    if (!recorder_) return;
    try {
      recorder_->sync();
    } catch (const std::exception& e) {
      emit message(tr("Recording stopped: %1").arg(fromStd(e.what())));
      recorder_.reset();
      syncTimer_.stop();
      emit recordingChanged(false);
    }
  });
  rateTimer_.setInterval(1000);
  connect(&rateTimer_, &QTimer::timeout, this, &RobotSession::measureRate);
  if (timeline_) connect(timeline_, &ui::Timeline::timeChanged, this, &RobotSession::onTimeChanged);
  connect(&host_, &VirtualRobotHost::clientDisconnected, this,
          [this](const QString&, const QString& reason) {
            if (link_ && host_.running() && link_->address().port == host_.port())
              emit message(tr("The virtual robot hung up: %1").arg(reason));
          });
  setState(State::Idle, tr("Not connected"));
}

RobotSession::~RobotSession() {
  stopRecording();
  if (link_) {
    link_->disconnect(this);
    link_->close();
  }
  link_.reset();
  host_.stop();
}

void RobotSession::setMapping(const MapperSettings& settings, double cellSize) {
  settings_ = settings;
  cellSize_ = cellSize;
}

void RobotSession::setState(State state, const QString& text) {
  state_ = state;
  stateText_ = text;
  emit stateChanged(state, text);
}

void RobotSession::connectTo(const live::LinkAddress& address,
                             std::optional<arcos::RobotParameters> robot) {
  if (!clock_.isValid()) clock_.start();
  // A log opened since took the map: the next merge hands the whole source back to the window.
  if (source_ && started_ && !attached()) started_ = false;
  const bool reuse = link_ && link_->address() == address &&
                     linkRobot_.has_value() == robot.has_value() &&
                     (!robot || linkRobot_->preset == robot->preset);
  if (link_ && !reuse) {
    link_->disconnect(this);
    link_->close();
    link_.reset();
  }
  if (!link_) {
    live::RobotLink::Options options;
    options.client.robot = robot;
    linkRobot_ = robot;
    link_ = std::make_unique<live::RobotLink>(address, options);
    // The new link's clock starts at its open(): its scans follow everything received before.
    linkOffset_ = static_cast<double>(clock_.nsecsElapsed()) * 1e-9;
    rateFrames_ = 0;
    connect(link_.get(), &live::RobotLink::connected, this, &RobotSession::onConnected);
    connect(link_.get(), &live::RobotLink::scanReceived, this, &RobotSession::onScan);
    connect(link_.get(), &live::RobotLink::statsChanged, this, [this] { emit statsChanged(); });
    connect(link_.get(), &live::RobotLink::disconnected, this, &RobotSession::onDisconnected);
    connect(link_.get(), &live::RobotLink::error, this, [this](const QString& text) {
      emit message(text);
      if (state_ == State::Connecting || state_ == State::Reconnecting)
        setState(state_, tr("%1; retrying").arg(text));
    });
  }
  setState(State::Connecting, tr("Connecting to %1…").arg(fromStd(address.text())));
  link_->open();
  rateClock_.start();
  rateTimer_.start();
}

void RobotSession::disconnectLink() {
  setWander(false);
  if (link_) link_->close();
  rateTimer_.stop();
  packetsPerSecond_ = 0.0;
  mergeNow();
  setState(State::Idle, tr("Disconnected"));
  emit statsChanged();
}

void RobotSession::onConnected(const QString& name, const QString& robotClass,
                               const QString& subclass) {
  const arcos::RobotParameters& robot = *link_->robot();
  if (source_ && !(source_->ring() == robot.ring)) {
    emit message(tr("The robot at %1 is a %2, not the %3 of this map: choose New Map to map it")
                     .arg(fromStd(link_->address().text()), fromStd(robot.preset),
                          fromStd(source_->ring().robot)));
    // Not from inside the link's own signal: closing deletes the transport that is emitting.
    QTimer::singleShot(0, this, &RobotSession::disconnectLink);
    return;
  }
  if (!source_) {
    source_ = std::make_shared<ScanSource>(
        "live: " + name.toStdString() + " at " + link_->address().text(), robot.ring);
    shown_ = Dataset{};
    shown_.name = source_->name();
    shown_.ring = robot.ring;
    started_ = false;
    emit sourceStarted(source_);
  }
  setState(State::Connected, tr("Connected to %1 (%2 %3) at %4, read as %5")
                                 .arg(name, robotClass, subclass, fromStd(link_->address().text()),
                                      fromStd(robot.preset)));
}

void RobotSession::onDisconnected(const QString& reason) {
  if (link_ && link_->isActive())
    setState(State::Reconnecting, tr("Connection lost (%1); reconnecting…").arg(reason));
  else
    setState(State::Idle, tr("Disconnected (%1)").arg(reason));
}

void RobotSession::onScan(const Scan& scan) {
  if (!source_) return;
  if (wander_) {
    const auto [v, w] = wander_->command(link_->latestRanges(), scan.odometry, scan.time);
    link_->setVelocity(v, w);
  }
  Scan s = scan;
  s.time += linkOffset_;
  for (Reading& r : s.readings) r.time += linkOffset_;
  ++scansReceived_;
  readingsReceived_ += s.readings.size();
  if (recorder_) {
    try {
      recorder_->append(s);
    } catch (const std::exception& e) {
      emit message(tr("Recording stopped: %1").arg(fromStd(e.what())));
      recorder_.reset();
      syncTimer_.stop();
      emit recordingChanged(false);
    }
  }
  pending_.push_back(std::move(s));
  if (!mergeTimer_.isActive()) mergeTimer_.start();
}

void RobotSession::mergeNow() {
  mergeTimer_.stop();
  if (pending_.empty() || !source_) return;
  std::vector<double> times;
  times.reserve(pending_.size());
  double end = timeline_ ? timeline_->endTime() : 0.0;
  for (const Scan& s : pending_) {
    times.push_back(s.time);
    end = std::max(end, s.time);
    for (const Reading& r : s.readings) end = std::max(end, r.time);
  }
  shown_.scans.insert(shown_.scans.end(), pending_.begin(), pending_.end());
  try {
    source_->append(std::move(pending_));
  } catch (const ScanSourceError& e) {
    emit message(fromStd(e.what()));
  }
  pending_.clear();
  if (!started_) {
    // The whole source: the first scans, or every scan so far when the map comes back to the
    // window (a log had taken it over).
    started_ = true;
    times.clear();
    end = 0.0;
    for (const Scan& scan : shown_.scans) {
      times.push_back(scan.time);
      end = std::max(end, scan.time);
      for (const Reading& r : scan.readings) end = std::max(end, r.time);
    }
    MapperSettings settings = settingsProvider_ ? settingsProvider_() : settings_;
    if (settings.pose == PoseSource::Truth && !shown_.scans.front().truth) {
      settings.pose = PoseSource::Odometry;
      emit mappedWithOdometry();
    }
    remap_->startLive(source_, cellSize_, settings, kInfinity);
    if (timeline_) {
      const QSignalBlocker block(timeline_);
      timeline_->setScanTimes(std::move(times), end);
    }
    showRobot(shown_.scans.size() - 1);
  } else if (remap_->source() == source_) {
    remap_->scansAppended();
    // At the end the timeline follows the live edge and says so (onTimeChanged shows the robot).
    if (timeline_) timeline_->appendScanTimes(times, end);
    if (!timeline_) showRobot(shown_.scans.size() - 1);
  }
  emit scansMerged(source_->size());
}

bool RobotSession::attached() const {
  return source_ && started_ && remap_->source() == source_;
}

void RobotSession::onTimeChanged(double t, std::size_t scan) {
  if (!attached()) return;
  showRobot(scan);
  // At the live edge the map takes every scan as it comes; behind it, the readings up to t.
  const double until = timeline_->atEnd() ? kInfinity : t;
  if (until != remap_->until()) remap_->setUntil(until);
}

void RobotSession::showRobot(std::size_t scan) {
  if (!view_ || scan >= shown_.scans.size()) return;
  // At the live edge the view keeps the robot in sight, until the user pans away.
  view_->setFollowRobot(!timeline_ || timeline_->atEnd());
  view_->setRobotAt(&shown_, remap_->settings().pose, scan);
}

void RobotSession::newMap() {
  stopRecording();
  mergeTimer_.stop();
  pending_.clear();
  source_.reset();
  shown_ = Dataset{};
  started_ = false;
  scansReceived_ = 0;
  readingsReceived_ = 0;
  // Connected: the next scans start the new map.
  if (link_ && link_->isOpen() && link_->robot()) {
    source_ = std::make_shared<ScanSource>(
        "live: " + (link_->server() ? link_->server()->name : std::string("robot")) + " at " +
            link_->address().text(),
        link_->robot()->ring);
    shown_.name = source_->name();
    shown_.ring = source_->ring();
    emit sourceStarted(source_);
  }
  emit scansMerged(0);
}

bool RobotSession::startVirtualRobot(const VirtualRobotHost::Options& options, QString* error) {
  if (link_) disconnectLink();
  if (!host_.start(options, error)) return false;
  live::LinkAddress address;
  address.kind = live::LinkAddress::Kind::Tcp;
  address.host = "127.0.0.1";
  address.port = host_.port();
  connectTo(address);
  return true;
}

void RobotSession::stopVirtualRobot() {
  if (!host_.running()) return;
  if (link_ && link_->address().port == host_.port() && link_->address().host == "127.0.0.1")
    disconnectLink();
  host_.stop();
}

void RobotSession::drive(double metresPerSecond, double radiansPerSecond) {
  setWander(false);
  if (link_ && link_->isOpen()) link_->setVelocity(metresPerSecond, radiansPerSecond);
}

void RobotSession::setWander(bool on) {
  if (on == wandering()) return;
  if (on) {
    if (!link_ || !link_->robot()) {
      emit message(tr("Wander needs a robot: connect first"));
      emit wanderChanged(false);
      return;
    }
    wander_ = std::make_unique<live::Wander>(link_->robot()->ring);
  } else {
    wander_.reset();
    if (link_ && link_->isOpen()) link_->setVelocity(0.0, 0.0);
  }
  emit wanderChanged(on);
}

bool RobotSession::startRecording(const QString& path, QString* error) {
  stopRecording();
  if (!source_) {
    if (error) *error = tr("Connect to a robot first: a log's header names its sonar ring");
    return false;
  }
  Dataset header;
  header.name = "recorded in SonarGrid from " +
                (link_ ? link_->address().text() : std::string("a robot")) +
                (link_ && link_->server() ? ": " + link_->server()->name : std::string());
  header.ring = source_->ring();
  try {
    recorder_ =
        std::make_unique<SglogRecorder>(QDir::toNativeSeparators(path).toStdString(), header);
  } catch (const std::exception& e) {
    if (error) *error = fromStd(e.what());
    return false;
  }
  syncTimer_.start();
  emit recordingChanged(true);
  return true;
}

void RobotSession::stopRecording() {
  if (!recorder_) return;
  syncTimer_.stop();
  try {
    recorder_->finish();
  } catch (const std::exception& e) {
    emit message(tr("Recording failed: %1").arg(fromStd(e.what())));
  }
  recorder_.reset();
  emit recordingChanged(false);
}

QString RobotSession::recordingPath() const {
  return recorder_ ? fromStd(recorder_->path()) : QString();
}

std::size_t RobotSession::recordedScans() const {
  return recorder_ ? recorder_->scans() : 0;
}

void RobotSession::measureRate() {
  if (!link_) return;
  const std::uint64_t frames = link_->counters().framing.frames;
  const double seconds = static_cast<double>(rateClock_.restart()) / 1000.0;
  if (seconds > 0.0)
    packetsPerSecond_ = static_cast<double>(frames - std::min(frames, rateFrames_)) / seconds;
  rateFrames_ = frames;
  emit statsChanged();
}

}  // namespace sg::app
