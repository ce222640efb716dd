// SPDX-License-Identifier: GPL-3.0-or-later
// Opening logs and reference maps: the load on a worker (LogLoader) with its progress in the status
// bar, and adopting a loaded log (or a project waiting for its log) as the document's.
#include <QAction>
#include <QApplication>
#include <QComboBox>
#include <QCoreApplication>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QSettings>
#include <QStatusBar>

#include "bag_import_dialog.h"
#include "beam_dock.h"
#include "beam_model_view.h"
#include "csv_import_dialog.h"
#include "dataset_manifest.h"
#include "document.h"
#include "log_loader.h"
#include "main_window.h"
#include "remap_controller.h"
#include "sonargrid/data/scan_poses.h"
#include "sonargrid/io/bag/bag_log.h"
#include "sonargrid/io/log_reader.h"
#include "sonargrid/reference/read_reference.h"
#include "status_report.h"
#include "timeline.h"

namespace sg::app {
namespace {

// A .csv / .txt / .tsv file whose content is not another format: it needs a column mapping.
bool needsColumns(const QString& path) {
  const QString suffix = QFileInfo(path).suffix().toLower();
  if (suffix != QLatin1String("csv") && suffix != QLatin1String("txt") &&
      suffix != QLatin1String("tsv"))
    return false;
  QFile f(path);
  if (!f.open(QIODevice::ReadOnly)) return false;  // readLog names the file and the problem
  const QByteArray head = f.read(static_cast<qint64>(kDetectBytes));
  const LogFormat detected = detectLogFormat(std::string_view(head.constData(), head.size()));
  return detected == LogFormat::Csv || detected == LogFormat::Auto;
}

}  // namespace

bool MainWindow::openLog(const QString& path, bool quiet) {
  if (!quiet && needsColumns(path)) return importCsv(path);
  if (!quiet && bag::isBag(QDir::toNativeSeparators(path).toStdString())) return importBag(path);
  loadLog(path, LogOptions{}, quiet);
  return !quiet || waitForLoad();
}

bool MainWindow::importCsv(const QString& path) {
  ui::CsvImportDialog dialog(path, this);
  if (dialog.exec() != QDialog::Accepted || !dialog.options()) return false;
  loadLog(path, *dialog.options());
  return true;
}

bool MainWindow::importBag(const QString& path) {
  bag::Overview overview;
  try {
    QApplication::setOverrideCursor(Qt::WaitCursor);  // an index-less bag is walked once here
    overview = bag::inspectBag(QDir::toNativeSeparators(path).toStdString());
    QApplication::restoreOverrideCursor();
  } catch (const std::exception& e) {
    QApplication::restoreOverrideCursor();
    return reportError(tr("Cannot open log"), QString::fromUtf8(e.what()), false);
  }
  ui::BagImportDialog dialog(path, std::move(overview), LogOptions{}, this);
  if (dialog.exec() != QDialog::Accepted || !dialog.options()) return false;
  loadLog(path, *dialog.options());
  return true;
}

void MainWindow::loadLog(const QString& path, const LogOptions& options, bool quiet) {
  cancelLoad();
  const MapperSettings& settings = pendingProject_ && pendingProject_->logPath == path
                                       ? pendingProject_->state->settings
                                       : document_->mapperSettings();
  const double cell = pendingProject_ && pendingProject_->logPath == path
                          ? pendingProject_->state->cellSize
                          : document_->cellSize();
  loader_->start(path, options, settings.pose, cell, quiet);
  status_->loadStarted(QFileInfo(path).fileName());
  actions_.cancelLoad->setEnabled(true);
}

void MainWindow::cancelLoad() {
  const QString path = loader_->cancel();
  if (path.isEmpty()) return;
  if (pendingProject_ && pendingProject_->logPath == path) {
    // Loading a project's log is how the project opens: a new load replaces that wish too.
    pendingProject_.reset();
  }
  hideLoadProgress();
  statusBar()->showMessage(tr("Loading %1 cancelled").arg(QFileInfo(path).fileName()), 5000);
  emit loadCancelled(path);
}

bool MainWindow::waitForLoad(int timeoutMs) {
  QElapsedTimer clock;
  clock.start();
  while (loader_->busy() && (timeoutMs < 0 || clock.elapsed() < timeoutMs))
    QCoreApplication::processEvents(QEventLoop::AllEvents | QEventLoop::WaitForMoreEvents, 50);
  return !loader_->busy() && lastLoadSucceeded_;
}

void MainWindow::hideLoadProgress() {
  status_->loadEnded();
  actions_.cancelLoad->setEnabled(false);
}

void MainWindow::onLoadFailed(const QString& path, const QString& message, bool quiet) {
  hideLoadProgress();
  lastLoadSucceeded_ = false;
  QString shown = message;
  if (pendingProject_ && pendingProject_->logPath == path) {
    shown = tr("%1: its log cannot be opened, the project is not opened: %2")
                .arg(QDir::toNativeSeparators(pendingProject_->path), message);
    pendingProject_.reset();
  }
  reportError(tr("Cannot open log"), shown, quiet);
  emit loadFailed(path, message);
}

void MainWindow::adoptLog(const QString& path, std::shared_ptr<const ScanSource> source,
                          const LogReading& reading) {
  // The document takes the new log first: until remap_->start() below, the controller still holds
  // the previous one, and the settings and cell size that change meanwhile map nothing
  // (onSettingsChanged, onCellSizeChanged).
  document_->setLog(path, std::move(source), reading);
  if (pendingProject_ && pendingProject_->logPath == path) {
    const PendingProject project = *std::exchange(pendingProject_, std::nullopt);
    document_->restore(*project.state, project.modified);  // the project names this log
    document_->setProjectPath(project.path);
    pendingView_ = project.state->view;
  } else {
    pendingProject_.reset();
    // The log's own reference map: the one its dataset's manifest declares (datasets/*/
    // dataset.json, docs/formats.md), else one beside it with its name (room.sglog + room.json).
    QString manifestError;
    const std::optional<DatasetManifest> manifest = manifestForLog(path, &manifestError);
    if (!manifestError.isEmpty())
      reportError(tr("Cannot read the dataset's manifest"), manifestError, true);
    const QString sibling = QFileInfo(path).path() + QDir::separator() +
                            QFileInfo(path).completeBaseName() + QStringLiteral(".json");
    const QString own = manifest && !manifest->reference.isEmpty() ? manifest->reference
                        : QFileInfo::exists(sibling)               ? sibling
                                                                   : QString();
    // A reference drawn for another log does not describe this one: it goes with the document it
    // belonged to (unless it is this log's own, unedited: another run of the same dataset). The
    // new log starts a new undo history below, so no undo brings it back over this log.
    const bool ownAlready = document_->reference() && !document_->referenceModified() &&
                            !own.isEmpty() &&
                            QFileInfo(document_->referencePath()).canonicalFilePath() ==
                                QFileInfo(own).canonicalFilePath();
    if (document_->reference() && !document_->referenceLog().isEmpty() &&
        document_->referenceLog() != path && !ownAlready) {
      document_->applyReference(std::nullopt, {}, false);
      statusBar()->showMessage(tr("Reference map closed: it was drawn for another log"), 15000);
    }
    if (document_->reference()) document_->setReferenceLog(path);
    // Unless one is loaded, the log's own comes with it: part of opening the log, not an edit.
    if (!document_->reference() && !own.isEmpty()) {
      try {
        document_->applyReference(readReference(QDir::toNativeSeparators(own).toStdString()), own,
                                  false);
        document_->setReferenceLog(path);
      } catch (const std::exception& e) {
        reportError(tr("Cannot open reference map"), QString::fromStdString(e.what()), true);
      }
    }
    document_->startNewHistory();
  }
  const Dataset& run = *document_->dataset();
  rememberRecent(document_->projectPath().isEmpty() ? path : document_->projectPath());
  QSettings().setValue("files/lastDirectory", QFileInfo(path).absolutePath());

  if (document_->mapperSettings().pose == PoseSource::Truth &&
      !anyScanHasPose(run, PoseSource::Truth)) {
    MapperSettings s = document_->mapperSettings();
    s.pose = PoseSource::Odometry;
    document_->adjustMapperSettings(s);
  } else if (const std::size_t without = scansWithoutPose(run, document_->mapperSettings().pose);
             without != 0) {
    // A simulator's first SIP before its first SIMSTAT (data/scan_poses.h): left out, and said.
    statusBar()->showMessage(tr("%1 of %2 scans have no true pose and are left out of the map "
                                "(Mapping ▸ Pose ▸ Odometry maps them all)")
                                 .arg(without)
                                 .arg(run.scans.size()),
                             15000);
  }
  std::vector<double> times;
  double end = 0.0;
  times.reserve(run.scans.size());
  for (const Scan& scan : run.scans) {
    times.push_back(scan.time);
    end = std::max(end, scan.time);
    for (const Reading& r : scan.readings) end = std::max(end, r.time);
  }
  {
    const QSignalBlocker block(timeline_);
    timeline_->setScanTimes(std::move(times), end);
  }
  status_->setHint(tr("Hover over the grid to read a cell; drag to pan, wheel to zoom."));
  beamDock_->startLog(run.ring.maxRange);
  scanShownPose_.reset();  // a new log: its scan must be drawn
  onReferenceChanged();    // the first view fits the robot's path and the reference
  showSettings();
  remap_->start(document_->source(), document_->cellSize(), document_->mapperSettings(),
                timeline_->time());
}

bool MainWindow::openReference(const QString& path, bool quiet) {
  try {
    document_->setReferenceFromFile(readReference(QDir::toNativeSeparators(path).toStdString()),
                                    path);
  } catch (const std::exception& e) {
    return reportError(tr("Cannot open reference map"), QString::fromStdString(e.what()), quiet);
  }
  return true;
}

void MainWindow::closeLog() {
  cancelLoad();
  document_->setLog({}, std::shared_ptr<const ScanSource>());
  beamDock_->clearReadings();
  view_->setHighlightedSonar(std::nullopt);
  view_->setRobotAt(nullptr, document_->mapperSettings().pose, 0);
  updateSummary();
  updateTitle();
}

bool MainWindow::hasReference() const {
  return document_->reference().has_value();
}

}  // namespace sg::app
