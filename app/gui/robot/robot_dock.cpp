// SPDX-License-Identifier: GPL-3.0-or-later
#include "robot/robot_dock.h"

#include <QAction>
#include <QCheckBox>
#include <QComboBox>
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QMenu>
#include <QMenuBar>
#include <QPushButton>
#include <QScrollArea>
#include <QScrollBar>
#include <QSerialPortInfo>
#include <QSettings>
#include <QSpinBox>
#include <QStackedWidget>
#include <QStatusBar>
#include <QTimer>
#include <QToolButton>
#include <QVBoxLayout>

#include "datasets_location.h"
#include "document.h"
#include "main_window.h"
#include "remap_controller.h"
#include "robot/robot_session.h"
#include "robot/teleop_keys.h"
#include "sonargrid/arcos/robot_params.h"

namespace sg::app {
namespace {

constexpr int kBauds[] = {9600, 19200, 38400, 57600, 115200};

QString count(std::uint64_t n) {
  return QString::number(n);
}

}  // namespace

RobotDock::RobotDock(MainWindow* window)
    : QDockWidget(tr("Robot"), window),
      window_(window),
      session_(new RobotSession(window->remapController(), window->timeline(), window->gridView(),
                                this)),
      teleop_(new TeleopKeys(window, session_, this)) {
  setObjectName(QStringLiteral("robotDock"));
  session_->setSettingsProvider([window] { return window->mapperSettings(); });
  buildActions();
  buildWidgets();
  connect(session_, &RobotSession::stateChanged, this, [this] {
    showStatus();
    updateActions();
  });
  connect(session_, &RobotSession::statsChanged, this, &RobotDock::showStatus);
  connect(session_, &RobotSession::scansMerged, this, &RobotDock::showStatus);
  connect(session_, &RobotSession::recordingChanged, this, [this] {
    showStatus();
    updateActions();
  });
  connect(session_, &RobotSession::wanderChanged, wanderAction_, &QAction::setChecked);
  connect(session_, &RobotSession::message, this, &RobotDock::say);
  connect(session_, &RobotSession::mappedWithOdometry, this, [this] {
    MapperSettings s = window_->mapperSettings();
    s.pose = PoseSource::Odometry;
    window_->setMapperSettings(s);
    say(tr("The robot sends no true pose: mapping with odometry"));
  });
  showStatus();
  updateActions();
}

RobotDock::~RobotDock() {
  // Before the window's children go (the remap controller among the first): the keys stop the
  // robot, then the session closes its link and its log without calling back into this dock.
  delete teleop_;
  teleop_ = nullptr;
  session_->disconnect(this);
  delete session_;
  session_ = nullptr;
}

void RobotDock::buildActions() {
  connectAction_ = new QAction(tr("&Connect"), this);
  connectAction_->setToolTip(tr("Connect to the robot the Robot dock names"));
  connect(connectAction_, &QAction::triggered, this, &RobotDock::connectFromFields);
  disconnectAction_ = new QAction(tr("&Disconnect"), this);
  connect(disconnectAction_, &QAction::triggered, session_, &RobotSession::disconnectLink);
  virtualAction_ = new QAction(tr("Start &Virtual Robot"), this);
  connect(virtualAction_, &QAction::triggered, this,
          [this] { startVirtualRobot(virtualRobotOptions()); });
  stopVirtualAction_ = new QAction(tr("S&top Virtual Robot"), this);
  connect(stopVirtualAction_, &QAction::triggered, this, [this] {
    session_->stopVirtualRobot();
    updateActions();
  });
  teleopAction_ = new QAction(tr("&Teleoperate (Arrow Keys)"), this);
  teleopAction_->setCheckable(true);
  teleopAction_->setShortcut(QKeySequence(tr("Ctrl+T")));
  connect(teleopAction_, &QAction::toggled, this, [this](bool on) {
    if (on) wanderAction_->setChecked(false);
    teleop_->setEnabled(on);
    // The keys go to the window, wherever the focus was (the grid view no longer pans with them).
    if (on) window_->gridView()->setFocus();
    showStatus();
  });
  wanderAction_ = new QAction(tr("&Wander"), this);
  wanderAction_->setCheckable(true);
  wanderAction_->setToolTip(tr("Drive with a simple sonar obstacle avoidance"));
  connect(wanderAction_, &QAction::toggled, this, [this](bool on) {
    if (on) teleopAction_->setChecked(false);
    session_->setWander(on);
  });
  recordAction_ = new QAction(tr("&Record to .sglog…"), this);
  connect(recordAction_, &QAction::triggered, this, &RobotDock::chooseRecording);
  stopRecordAction_ = new QAction(tr("Stop Re&cording"), this);
  connect(stopRecordAction_, &QAction::triggered, session_, &RobotSession::stopRecording);
  newMapAction_ = new QAction(tr("&New Map"), this);
  newMapAction_->setToolTip(tr("Forget the scans received; the next ones start a new map"));
  connect(newMapAction_, &QAction::triggered, this, [this] {
    prepareWindow();
    session_->newMap();
  });

  menu_ = new QMenu(tr("&Robot"), window_);
  menu_->addAction(connectAction_);
  menu_->addAction(virtualAction_);
  menu_->addAction(disconnectAction_);
  menu_->addAction(stopVirtualAction_);
  menu_->addSeparator();
  menu_->addAction(teleopAction_);
  menu_->addAction(wanderAction_);
  menu_->addSeparator();
  menu_->addAction(recordAction_);
  menu_->addAction(stopRecordAction_);
  menu_->addAction(newMapAction_);
  menu_->addSeparator();
  QAction* dockAction = toggleViewAction();
  dockAction->setText(tr("Robot &Dock"));
  menu_->addAction(dockAction);
  // Their shortcuts work while the menu is closed.
  window_->addActions({teleopAction_});
}

void RobotDock::buildWidgets() {
  auto* host = new QWidget(this);
  auto* layout = new QVBoxLayout(host);

  // Connection.
  auto* connectBox = new QGroupBox(tr("Connect"), host);
  auto* connectForm = new QFormLayout(connectBox);
  kind_ = new QComboBox(connectBox);
  kind_->addItems({tr("TCP"), tr("Serial port")});
  kind_->setToolTip(
      tr("TCP: a simulator, the virtual robot or a network bridge; serial: the robot's own port"));
  kindPages_ = new QStackedWidget(connectBox);
  auto* tcp = new QWidget(kindPages_);
  auto* tcpRow = new QHBoxLayout(tcp);
  tcpRow->setContentsMargins(0, 0, 0, 0);
  host_ = new QLineEdit(QSettings().value("robot/host", "127.0.0.1").toString(), tcp);
  host_->setObjectName(QStringLiteral("robotHost"));
  port_ = new QSpinBox(tcp);
  port_->setRange(1, 65535);
  port_->setValue(QSettings().value("robot/port", live::kDefaultArcosPort).toInt());
  tcpRow->addWidget(host_, 1);
  tcpRow->addWidget(new QLabel(tr("port"), tcp));
  tcpRow->addWidget(port_);
  auto* serial = new QWidget(kindPages_);
  auto* serialRow = new QHBoxLayout(serial);
  serialRow->setContentsMargins(0, 0, 0, 0);
  serialPort_ = new QComboBox(serial);
  serialPort_->setEditable(true);  // a device the system does not list (a pseudo-terminal)
  auto* refresh = new QToolButton(serial);
  refresh->setText(tr("↻"));
  refresh->setToolTip(tr("List the serial ports again"));
  connect(refresh, &QToolButton::clicked, this, &RobotDock::refreshSerialPorts);
  baud_ = new QComboBox(serial);
  for (const int b : kBauds) baud_->addItem(QString::number(b), b);
  baud_->setToolTip(tr("9600 for ARCOS as shipped; newer controllers often 115200"));
  serialRow->addWidget(serialPort_, 1);
  serialRow->addWidget(refresh);
  serialRow->addWidget(baud_);
  kindPages_->addWidget(tcp);
  kindPages_->addWidget(serial);
  connect(kind_, &QComboBox::currentIndexChanged, kindPages_, &QStackedWidget::setCurrentIndex);
  readAs_ = new QComboBox(connectBox);
  readAs_->addItem(tr("as its subclass says"), QString());
  for (const char* preset : {"p3dx", "amigobot"}) readAs_->addItem(preset, QString(preset));
  readAs_->setToolTip(tr("The sonar ring and conversion factors to read the robot with"));
  auto* connectButtons = new QHBoxLayout;
  auto* connectButton = new QPushButton(tr("Connect"), connectBox);
  connectButton->setObjectName(QStringLiteral("robotConnect"));
  connect(connectButton, &QPushButton::clicked, connectAction_, &QAction::trigger);
  auto* disconnectButton = new QPushButton(tr("Disconnect"), connectBox);
  connect(disconnectButton, &QPushButton::clicked, disconnectAction_, &QAction::trigger);
  connect(disconnectAction_, &QAction::changed, disconnectButton, [this, disconnectButton] {
    disconnectButton->setEnabled(disconnectAction_->isEnabled());
  });
  connectButtons->addWidget(connectButton);
  connectButtons->addWidget(disconnectButton);
  connectForm->addRow(tr("Link:"), kind_);
  connectForm->addRow(kindPages_);
  connectForm->addRow(tr("Read it:"), readAs_);
  connectForm->addRow(connectButtons);
  layout->addWidget(connectBox);

  // The virtual robot.
  auto* virtualBox = new QGroupBox(tr("Virtual robot"), host);
  auto* virtualForm = new QFormLayout(virtualBox);
  world_ = new QComboBox(virtualBox);
  for (const QString& w : worlds()) world_->addItem(QFileInfo(w).dir().dirName(), w);
  virtualRobot_ = new QComboBox(virtualBox);
  virtualRobot_->addItem(tr("Pioneer 3-DX"), QStringLiteral("p3dx"));
  virtualRobot_->addItem(tr("AmigoBot"), QStringLiteral("amigobot"));
  route_ = new QComboBox(virtualBox);
  route_->addItem(tr("loops (in motion)"), QStringLiteral("in-motion"));
  route_->addItem(tr("stops and scans"), QStringLiteral("stop-and-scan"));
  route_->addItem(tr("lanes (U-turns)"), QStringLiteral("u-turn"));
  route_->addItem(tr("none: teleoperate"), QString());
  auto* virtualButtons = new QHBoxLayout;
  auto* startButton = new QPushButton(tr("Start"), virtualBox);
  startButton->setObjectName(QStringLiteral("robotStartVirtual"));
  connect(startButton, &QPushButton::clicked, virtualAction_, &QAction::trigger);
  auto* stopButton = new QPushButton(tr("Stop"), virtualBox);
  connect(stopButton, &QPushButton::clicked, stopVirtualAction_, &QAction::trigger);
  connect(stopVirtualAction_, &QAction::changed, stopButton,
          [this, stopButton] { stopButton->setEnabled(stopVirtualAction_->isEnabled()); });
  virtualButtons->addWidget(startButton);
  virtualButtons->addWidget(stopButton);
  virtualForm->addRow(tr("World:"), world_);
  virtualForm->addRow(tr("Robot:"), virtualRobot_);
  virtualForm->addRow(tr("Route:"), route_);
  virtualForm->addRow(virtualButtons);
  layout->addWidget(virtualBox);

  // Driving and recording.
  auto* driveBox = new QGroupBox(tr("Drive and record"), host);
  auto* driveLayout = new QVBoxLayout(driveBox);
  auto* teleopBox = new QCheckBox(teleopAction_->text().remove('&'), driveBox);
  connect(teleopBox, &QCheckBox::toggled, teleopAction_, &QAction::setChecked);
  connect(teleopAction_, &QAction::toggled, teleopBox, &QCheckBox::setChecked);
  auto* wanderBox = new QCheckBox(tr("Wander (sonar obstacle avoidance)"), driveBox);
  connect(wanderBox, &QCheckBox::toggled, wanderAction_, &QAction::setChecked);
  connect(wanderAction_, &QAction::toggled, wanderBox, &QCheckBox::setChecked);
  auto* recordRow = new QHBoxLayout;
  auto* recordButton = new QPushButton(tr("Record…"), driveBox);
  connect(recordButton, &QPushButton::clicked, recordAction_, &QAction::trigger);
  auto* stopRecordButton = new QPushButton(tr("Stop"), driveBox);
  connect(stopRecordButton, &QPushButton::clicked, stopRecordAction_, &QAction::trigger);
  connect(recordAction_, &QAction::changed, recordButton,
          [this, recordButton] { recordButton->setEnabled(recordAction_->isEnabled()); });
  connect(stopRecordAction_, &QAction::changed, stopRecordButton, [this, stopRecordButton] {
    stopRecordButton->setEnabled(stopRecordAction_->isEnabled());
  });
  auto* newMapButton = new QPushButton(tr("New Map"), driveBox);
  newMapButton->setToolTip(newMapAction_->toolTip());
  connect(newMapButton, &QPushButton::clicked, newMapAction_, &QAction::trigger);
  recordRow->addWidget(recordButton);
  recordRow->addWidget(stopRecordButton);
  recordRow->addWidget(newMapButton);
  recording_ = new QLabel(driveBox);
  recording_->setWordWrap(true);
  driveLayout->addWidget(teleopBox);
  driveLayout->addWidget(wanderBox);
  driveLayout->addLayout(recordRow);
  driveLayout->addWidget(recording_);
  layout->addWidget(driveBox);

  // Status.
  auto* statusBox = new QGroupBox(tr("Link"), host);
  auto* statusLayout = new QVBoxLayout(statusBox);
  state_ = new QLabel(statusBox);
  state_->setObjectName(QStringLiteral("robotState"));
  state_->setWordWrap(true);
  stats_ = new QLabel(statusBox);
  stats_->setObjectName(QStringLiteral("robotStats"));
  stats_->setTextFormat(Qt::RichText);
  stats_->setWordWrap(true);  // the table narrows with the dock
  stats_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  lastMessage_ = new QLabel(statusBox);
  lastMessage_->setWordWrap(true);
  lastMessage_->setStyleSheet(QStringLiteral("color: palette(mid);"));
  statusLayout->addWidget(state_);
  statusLayout->addWidget(stats_);
  statusLayout->addWidget(lastMessage_);
  layout->addWidget(statusBox);
  layout->addStretch(1);
  // A short window scrolls the dock rather than squeezing its status.
  auto* scroll = new QScrollArea(this);
  scroll->setWidgetResizable(true);
  scroll->setFrameShape(QFrame::NoFrame);
  scroll->setWidget(host);
  scroll->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  // As wide as its fields need; only its height scrolls.
  for (QComboBox* box : host->findChildren<QComboBox*>()) {
    box->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
    box->setMinimumContentsLength(10);
  }
  scroll_ = scroll;
  setWidget(scroll);
  refreshSerialPorts();
}

void RobotDock::showEvent(QShowEvent* event) {
  QDockWidget::showEvent(event);
  // As wide as its fields need once they are polished and filled; only its height scrolls.
  QTimer::singleShot(0, this, [this] {
    scroll_->setMinimumWidth(scroll_->widget()->minimumSizeHint().width() +
                             scroll_->verticalScrollBar()->sizeHint().width() +
                             2 * scroll_->frameWidth());
  });
}

QStringList RobotDock::worlds() const {
  QStringList out;
  const QString root = bundledDatasetsDirectory();
  if (root.isEmpty()) return out;
  for (const QString& d : QDir(root).entryList(QDir::Dirs | QDir::NoDotAndDotDot, QDir::Name)) {
    const QString w = root + QStringLiteral("/") + d + QStringLiteral("/world.json");
    if (QFileInfo::exists(w)) out << w;
  }
  return out;
}

void RobotDock::setWorld(const QString& path) {
  int i = world_->findData(path);
  if (i < 0) {
    world_->addItem(QFileInfo(path).fileName(), path);
    i = world_->count() - 1;
  }
  world_->setCurrentIndex(i);
}

void RobotDock::refreshSerialPorts() {
  const QString current = serialPort_->currentText();
  serialPort_->clear();
  for (const QSerialPortInfo& info : QSerialPortInfo::availablePorts()) {
    const QString label = info.description().isEmpty()
                              ? info.systemLocation()
                              : info.systemLocation() + QStringLiteral(" — ") + info.description();
    serialPort_->addItem(label, info.systemLocation());
  }
  if (!current.isEmpty()) serialPort_->setCurrentText(current);
}

void RobotDock::prepareWindow() {
  show();
  raise();
  // The live map replaces the open log (the reference map, if any, stays), and is mapped with
  // what the window shows now.
  window_->closeLog();
  session_->setMapping(window_->mapperSettings(), window_->document()->cellSize());
}

void RobotDock::connectFromFields() {
  live::LinkAddress address;
  if (kind_->currentIndex() == 0) {
    address.kind = live::LinkAddress::Kind::Tcp;
    address.host = host_->text().trimmed().toStdString();
    address.port = static_cast<std::uint16_t>(port_->value());
    if (address.host.empty()) {
      say(tr("Give the robot's host name or address"));
      return;
    }
    QSettings().setValue("robot/host", host_->text().trimmed());
    QSettings().setValue("robot/port", port_->value());
  } else {
    address.kind = live::LinkAddress::Kind::Serial;
    // A listed port by its device; a typed one (a pseudo-terminal) as typed.
    const int i = serialPort_->currentIndex();
    const bool listed = i >= 0 && serialPort_->currentText() == serialPort_->itemText(i);
    const QString device =
        listed ? serialPort_->itemData(i).toString() : serialPort_->currentText().trimmed();
    if (device.isEmpty()) {
      say(tr("Choose a serial port (none is listed: is the adapter plugged in?)"));
      return;
    }
    address.device = device.toStdString();
    address.baud = baud_->currentData().toInt();
  }
  std::optional<arcos::RobotParameters> robot;
  if (const QString preset = readAs_->currentData().toString(); !preset.isEmpty())
    robot = arcos::robotPreset(preset.toStdString());
  prepareWindow();
  session_->connectTo(address, robot);
}

VirtualRobotHost::Options RobotDock::virtualRobotOptions() const {
  VirtualRobotHost::Options o;
  o.world = world_->currentData().toString();
  o.robot = virtualRobot_->currentData().toString().toStdString();
  const QString route = route_->currentData().toString();
  o.route = route.isEmpty() ? std::nullopt : routeKindFromName(route.toStdString());
  return o;
}

bool RobotDock::startVirtualRobot(const VirtualRobotHost::Options& o) {
  if (o.world.isEmpty()) {
    say(tr("No world file: the bundled datasets were not found"));
    return false;
  }
  prepareWindow();
  QString error;
  if (!session_->startVirtualRobot(o, &error)) {
    say(error);
    return false;
  }
  // Its world is the truth to score against: the live map is scored against it, not against a
  // reference of another place that the window had open (issue 49). Opening it is one undo step.
  const QString shown = window_->document()->referencePath();
  if (!window_->hasReference() || window_->document()->referenceModified() ||
      QFileInfo(shown).canonicalFilePath() != QFileInfo(o.world).canonicalFilePath())
    window_->openReference(o.world, true);
  if (!o.route) teleopAction_->setChecked(true);
  updateActions();
  return true;
}

void RobotDock::chooseRecording() {
  QSettings s;
  const QString dir = s.value("files/recordDirectory", QDir::homePath()).toString();
  QString path = QFileDialog::getSaveFileName(this, tr("Record to .sglog"),
                                              dir + QStringLiteral("/live.sglog"),
                                              tr("SonarGrid logs (*.sglog)"));
  if (path.isEmpty()) return;
  if (!path.endsWith(QStringLiteral(".sglog"), Qt::CaseInsensitive))
    path += QStringLiteral(".sglog");
  s.setValue("files/recordDirectory", QFileInfo(path).absolutePath());
  recordTo(path);
}

bool RobotDock::recordTo(const QString& path) {
  QString error;
  if (session_->startRecording(path, &error)) return true;
  say(error);
  return false;
}

void RobotDock::say(const QString& text) {
  lastMessage_->setText(text);
  window_->statusBar()->showMessage(text, 8000);
}

void RobotDock::updateActions() {
  const bool linked = session_->state() != RobotSession::State::Idle;
  disconnectAction_->setEnabled(linked);
  stopVirtualAction_->setEnabled(session_->virtualRobot().running());
  recordAction_->setEnabled(session_->source() != nullptr && !session_->recording());
  stopRecordAction_->setEnabled(session_->recording());
  newMapAction_->setEnabled(session_->source() != nullptr);
}

void RobotDock::showStatus() {
  state_->setText(session_->stateText());
  const live::RobotLink* link = session_->link();
  QString html;
  if (link) {
    const arcos::LinkCounters& c = link->counters();
    html =
        tr("<table>"
           "<tr><td>packets/s</td><td align=right>%1</td></tr>"
           "<tr><td>packets</td><td align=right>%2</td></tr>"
           "<tr><td>SIPs / SIMSTATs</td><td align=right>%3 / %4</td></tr>"
           "<tr><td>readings</td><td align=right>%5</td></tr>"
           "<tr><td>bad checksums</td><td align=right>%6</td></tr>"
           "<tr><td>bad lengths</td><td align=right>%7</td></tr>"
           "<tr><td>short SIP / SIMSTAT / reply</td><td align=right>%8 / %9 / %10</td></tr>"
           "<tr><td>bytes skipped</td><td align=right>%11</td></tr>"
           "<tr><td>connections</td><td align=right>%12</td></tr>"
           "<tr><td>reconnects</td><td align=right>%13</td></tr>"
           "<tr><td>lost / timed out</td><td align=right>%14 / %15</td></tr>"
           "<tr><td>segments / stitched</td><td align=right>%16 / %17</td></tr>")
            .arg(session_->packetsPerSecond(), 0, 'f', 1)
            .arg(count(c.framing.frames), count(c.sips), count(c.simStats), count(c.readings),
                 count(c.framing.badChecksums), count(c.framing.badCounts), count(c.malformedSips),
                 count(c.malformedSimStats))
            .arg(count(c.malformedServerInfo), count(c.framing.skippedBytes), count(c.handshakes),
                 count(c.reconnects), count(c.lostConnections), count(c.timeouts))
            .arg(count(c.segments), count(c.stitched));
  } else {
    html = tr("<table>");
  }
  const auto source = session_->source();
  html += tr("<tr><td>map</td><td align=right>%1 scans, %2 readings</td></tr></table>")
              .arg(source ? source->size() : 0)
              .arg(session_->readingsReceived());
  if (teleopAction_->isChecked())
    html += tr("<p>Arrow keys drive: ↑↓ %1 m/s, ←→ %2°/s</p>")
                .arg(teleop_->speed(), 0, 'f', 1)
                .arg(teleop_->turnRate() * 180.0 / 3.14159265358979, 0, 'f', 0);
  if (!session_->mapping() && source && source->size() > 0)
    html += tr("<p>The window shows another log: New Map maps the robot again.</p>");
  stats_->setText(html);
  recording_->setVisible(session_->recording());
  recording_->setText(session_->recording()
                          ? tr("Recording to %1: %2 scans")
                                .arg(QDir::toNativeSeparators(session_->recordingPath()))
                                .arg(session_->recordedScans())
                          : QString());
}

RobotDock* installRobotMenu(MainWindow* window) {
  auto* dock = new RobotDock(window);
  // Before Settings and Help, as the last menu of the document's kind.
  QAction* before = nullptr;
  for (QAction* a : window->menuBar()->actions())
    if (a->menu() && (a->text() == QObject::tr("&Settings") || a->text() == QObject::tr("&Help"))) {
      before = a;
      break;
    }
  window->menuBar()->insertMenu(before, dock->menu());
  // Tabbed behind the map summary on the right, where the docks about the map live.
  window->addDockWidget(Qt::RightDockWidgetArea, dock);
  if (auto* summary = window->findChild<QDockWidget*>(QStringLiteral("mapDock")))
    window->tabifyDockWidget(summary, dock);
  // The beam view stays in front until a robot is connected (the dock raises itself then).
  if (auto* beams = window->findChild<QDockWidget*>(QStringLiteral("beamModelDock")))
    beams->raise();
  return dock;
}

}  // namespace sg::app
